/* SPDX-License-Identifier: Apache-2.0 */
/* rt_ray_packet.cl - the packet kernels for OpenCL CPU devices (issue 7).
 *
 * rt_single_ray.cl runs the shared scalar maths one ray per work-item; a CPU
 * device's compiler (PoCL's LLVM) cannot vectorise the divergent traversal
 * across work-items. Here one work-item traces a block of RT_PK_LANES pixels
 * (4x4 by default) as OpenCL vectors (float16: one AVX-512 register on
 * PoCL's skylake-avx512 target), through the same two-level BVH: a node is
 * visited when any active lane's box test passes, and each lane carries its
 * own mask, so a lane goes into a node's children only where its own test of
 * the node passed. Then the block's primary hits are shaded in vectors as
 * well (the surface, Phong and the shadow rays, traced as a packet: any hit,
 * a lane retires when occluded); in Whitted frames each lane then shades its
 * reflection and refraction subtrees with the shared functions. rt_k_packet
 * does a whole direct frame's block (camera, trace, shading, shadows) in one
 * launch; rt_k_packet_trace answers closest-hit ray queries in packets of
 * consecutive rays.
 *
 * Exactness (the oracle's bits). Every pk_* function below mirrors one
 * function of the shared maths (rt_box.h .. rt_shade.h, named at each): per lane it performs
 * the same IEEE operations in the same order (no contraction: the pragma; no
 * -cl-mad-enable option; correctly rounded division and sqrt), choosing between
 * values with select() where the scalar code branches or indexes (the
 * watertight test's per-ray axes kx, ky, kz), so each lane computes its own
 * scalar values; the watertight test's exact re-check of zero edge
 * functions is done for the lanes that have one. Per lane the traversal is
 * then the scalar traversal in another order, each node tested against the
 * lane's own current range [tmin, best t]. Closest hit has a total order
 * (rt_hit_before) and box tests are conservative: the best t only shrinks
 * and never below the closest hit's t, so every node holding the closest
 * hit passes, its triangle is tested with the scalar arithmetic and accepted
 * by the same order, and nothing replaces it; the hit is the oracle's,
 * whatever the order (the property that already makes the oracle's hit
 * independent of layout and threads). An any-hit lane's range stays
 * [tmin, tmax] until it finds a hit, so the leaves it can reach are the
 * scalar traversal's and it is occluded exactly when that is. Camera rays,
 * the AOVs' surfaces, rt_shade_end's secondary rays and the subtrees are the
 * shared functions, called per lane; the vector shading of the primary hits
 * mirrors rt_surface_at, rt_shade_begin, rt_phong_light, rt_phong_add and
 * rt_shade_end's term like the traversal. Only the test counters differ from the scalar kernels:
 * each lane counts the box and triangle tests performed while it was active (docs/OPENCL.md).
 *
 * Built together with rt_single_ray.cl (one program) on CPU devices only.
 */
#pragma OPENCL FP_CONTRACT OFF
/* Vectors wider than the target's registers (float16 without AVX-512, float8
 * without AVX) pass between functions differently by target, and clang warns
 * about that ABI change (-Wpsabi) at every such call, the built-ins' included:
 * a couple of hundred "warnings generated" on a cold cache. The warning is
 * about linking objects built for different targets; a program is compiled
 * and linked for its one device here, so it does not apply. Only that warning
 * is off; tests/check_kernels_clang.sh builds the kernels for several x86
 * targets with every other warning an error. */
#ifdef __clang__
#pragma clang diagnostic ignored "-Wpsabi"
#endif

#include "rt_kernel_args.h"

#ifndef RT_PK_LANES
#define RT_PK_LANES 16
#endif

#if RT_PK_LANES == 16
typedef float16 pk_f;
typedef int16 pk_i;
typedef uint16 pk_u;
#define PK_W      4 /* block width in pixels (lanes l: x = l % PK_W, y = l / PK_W) */
#define pk_vload  vload16
#define pk_vstore vstore16
#define pk_as_i   as_int16
#define pk_as_f   as_float16
#define pk_to_i   convert_int16 /* towards zero, as C's (int) */
#elif RT_PK_LANES == 8
typedef float8 pk_f;
typedef int8 pk_i;
typedef uint8 pk_u;
#define PK_W      4
#define pk_vload  vload8
#define pk_vstore vstore8
#define pk_as_i   as_int8
#define pk_as_f   as_float8
#define pk_to_i   convert_int8 /* towards zero, as C's (int) */
#elif RT_PK_LANES == 4
typedef float4 pk_f;
typedef int4 pk_i;
typedef uint4 pk_u;
#define PK_W      2
#define pk_vload  vload4
#define pk_vstore vstore4
#define pk_as_i   as_int4
#define pk_as_f   as_float4
#define pk_to_i   convert_int4 /* towards zero, as C's (int) */
#else
#error "RT_PK_LANES must be 4, 8 or 16"
#endif
#define PK_H (RT_PK_LANES / PK_W)

/* Division and sqrt per lane. In the portable profile they are the shared
 * integer-only functions (RT_DIV, RT_SQRT), which branch, so each lane calls
 * them in turn; otherwise the device's vector operations, correctly rounded
 * under -cl-fp32-correctly-rounded-divide-sqrt. */
#ifdef RT_PORTABLE_MATH
static pk_f pk_div_lanes(pk_f a, pk_f b) {
    float x[RT_PK_LANES], y[RT_PK_LANES];
    pk_vstore(a, 0, x);
    pk_vstore(b, 0, y);
    for (int l = 0; l < RT_PK_LANES; l++) x[l] = RT_DIV(x[l], y[l]);
    return pk_vload(0, x);
}
static pk_f pk_sqrt_lanes(pk_f a) {
    float x[RT_PK_LANES];
    pk_vstore(a, 0, x);
    for (int l = 0; l < RT_PK_LANES; l++) x[l] = RT_SQRT(x[l]);
    return pk_vload(0, x);
}
#define PK_DIV(a, b) pk_div_lanes((pk_f)(a), (pk_f)(b))
#define PK_SQRT(x)   pk_sqrt_lanes((pk_f)(x))
#else
#define PK_DIV(a, b) RT_DIV((a), (b))
#define PK_SQRT(x)   RT_SQRT(x)
#endif

/* A packet of rays: rt_ray and rt_ray_pre per lane, as vectors. Masks are
 * integer vectors, -1 in a lane where true (OpenCL's vector comparisons). */
typedef struct pk_ray {
    pk_f org[3], dir[3];
    pk_f tmin, tmax;
    pk_f inv[3];
    pk_i neg[3]; /* rt_ray_pre.sign: inv < 0 */
    pk_i kx, ky, kz;
    pk_f sx, sy, sz;
    pk_f box_lo; /* rt_box_lo(tmin) */
    /* rt_ray_pre.inst_lo per lane, and the lanes whose ray meets the
     * instance box (rt_inst_enter; all lanes outside an object BVH). */
    pk_f inst_lo;
    pk_i inst_ok;
} pk_ray;

/* rt_hit_d per lane, and the lanes' test counters (rt_counters). */
typedef struct pk_state {
    pk_f t, u, v;
    pk_u prim, inst, entry;
    pk_i boxes, tris, rays;
    pk_i done; /* any hit: lanes that found an occluder */
    int any_hit;
    pk_u ray_mask; /* the lanes' ray masks (rt_trace_masked) */
} pk_state;

/* Whether some lane of a -1/0 mask is set: OpenCL's any(), which on PoCL
 * tests each lane's sign bit in turn (a chain of branches); an OR of halves
 * compiles to a few vector instructions (vpor, vptest). */
static int pk_any(pk_i m) {
#if RT_PK_LANES == 16
    int8 a = m.lo | m.hi;
    int4 b = a.lo | a.hi;
#elif RT_PK_LANES == 8
    int4 b = m.lo | m.hi;
#else
    int4 b = m;
#endif
    int2 c = b.lo | b.hi;
    return (c.x | c.y) != 0;
}

/* c ? b : a per lane (a select on a -1/0 mask). */
#define PK_PICK(a0, a1, a2, k) select(select((a0), (a1), (k) == 1), (a2), (k) == 2)

/* ---- rays ----------------------------------------------------------------- */

/* Mirrors rt_ray_prepare, and rt_box_lo(tmin). */
static void pk_prepare(pk_ray *p) {
    for (int i = 0; i < 3; i++) {
        p->inv[i] = PK_DIV(1.0f, p->dir[i]);
        p->neg[i] = p->inv[i] < 0.0f;
    }
    pk_f ax = RT_FABS(p->dir[0]), ay = RT_FABS(p->dir[1]), az = RT_FABS(p->dir[2]);
    pk_i kz = select((pk_i)0, (pk_i)1, ay > ax);
    kz = select(kz, (pk_i)2, az > select(ax, ay, kz == 1));
    pk_i kx = select(kz + 1, (pk_i)0, kz + 1 == 3);
    pk_i ky = select(kx + 1, (pk_i)0, kx + 1 == 3);
    pk_f dkz = PK_PICK(p->dir[0], p->dir[1], p->dir[2], kz);
    pk_i swap = dkz < 0.0f; /* keep the winding */
    pk_i tmp = kx;
    kx = select(kx, ky, swap);
    ky = select(ky, tmp, swap);
    p->kx = kx;
    p->ky = ky;
    p->kz = kz;
    p->sx = PK_DIV(PK_PICK(p->dir[0], p->dir[1], p->dir[2], kx), dkz);
    p->sy = PK_DIV(PK_PICK(p->dir[0], p->dir[1], p->dir[2], ky), dkz);
    p->sz = PK_PICK(p->inv[0], p->inv[1], p->inv[2], kz); /* 1 / dkz, as the oracle */
    p->box_lo = p->tmin - RT_FABS(p->tmin) * RT_BOX_T_MARGIN;
    p->inst_lo = (pk_f)(-RT_INF);
    p->inst_ok = (pk_i)(-1);
}

/* The packet of the lanes' rays r[0 .. RT_PK_LANES - 1] (each lane's own
 * rt_ray, e.g. from rt_camera_ray or rt_phong_light). */
static void pk_load(const rt_ray *r, pk_ray *p) {
    float a[8][RT_PK_LANES];
    for (int l = 0; l < RT_PK_LANES; l++) {
        for (int k = 0; k < 3; k++) {
            a[k][l] = r[l].org[k];
            a[3 + k][l] = r[l].dir[k];
        }
        a[6][l] = r[l].tmin;
        a[7][l] = r[l].tmax;
    }
    for (int k = 0; k < 3; k++) {
        p->org[k] = pk_vload(0, a[k]);
        p->dir[k] = pk_vload(0, a[3 + k]);
    }
    p->tmin = pk_vload(0, a[6]);
    p->tmax = pk_vload(0, a[7]);
    pk_prepare(p);
}

/* Mirrors rt_ray_to_object (and rt_ray_prepare on the result). */
static void pk_to_object(RT_GLOBAL const rt_instance *in, const pk_ray *r, pk_ray *o) {
    RT_GLOBAL const float *m = in->world_to_object;
    for (int i = 0; i < 3; i++) {
        o->org[i] = ((m[4 * i] * r->org[0] + m[4 * i + 1] * r->org[1]) + m[4 * i + 2] * r->org[2]) +
                    m[4 * i + 3];
        o->dir[i] = (m[4 * i] * r->dir[0] + m[4 * i + 1] * r->dir[1]) + m[4 * i + 2] * r->dir[2];
    }
    o->tmin = r->tmin;
    o->tmax = r->tmax;
    pk_prepare(o);
}

/* ---- ray/box -------------------------------------------------------------- */

/* Mirrors rt_slab per lane: axis i of a box [mn, mx] narrows [*lo, *hi]. */
static void pk_slab(pk_f mn, pk_f mx, const pk_ray *p, int i, pk_f *lo, pk_f *hi) {
    pk_f a = select(mn, mx, p->neg[i]);
    pk_f b = select(mx, mn, p->neg[i]);
    pk_f t0 = (a - p->org[i]) * p->inv[i];
    pk_f t1 = (b - p->org[i]) * p->inv[i];
    *lo = select(*lo, t0, t0 > *lo);
    *hi = select(*hi, t1, t1 < *hi);
}

/* Mirrors rt_slab_end per lane (without tnear). */
static pk_i pk_slab_end(pk_f lo, pk_f hi, pk_f tmax) {
    hi = hi * select((pk_f)RT_BOX_FAR_SCALE, (pk_f)RT_BOX_FAR_SCALE_NEG, hi < 0.0f);
    hi = select(hi, tmax, tmax < hi);
    return lo <= hi;
}

/* Mirrors rt_box_test: lo is rt_box_lo(tmin), tmax is rt_box_hi(best t). */
static pk_i pk_box(RT_GLOBAL const rt_node *n, const pk_ray *p, pk_f lo, pk_f tmax, pk_f *tnear) {
    pk_f hi = (pk_f)RT_INF;
    for (int i = 0; i < 3; i++) pk_slab((pk_f)n->bmin[i], (pk_f)n->bmax[i], p, i, &lo, &hi);
    *tnear = lo;
    return pk_slab_end(lo, hi, tmax);
}

/* Mirrors rt_hit_accepted per lane: the hits at t on tri that lie in the
 * slabs of its box and of the instance's. */
static pk_i pk_hit_accepted(RT_GLOBAL const rt_tri *tri, const pk_ray *p, pk_f t) {
    pk_f hi_t = t + RT_FABS(t) * RT_BOX_T_MARGIN; /* rt_box_hi(t) */
    pk_f lo = p->box_lo, hi = (pk_f)RT_INF;
    for (int i = 0; i < 3; i++)
        pk_slab((pk_f)rt_min3(tri->v0[i], tri->v1[i], tri->v2[i]),
                (pk_f)rt_max3(tri->v0[i], tri->v1[i], tri->v2[i]), p, i, &lo, &hi);
    return pk_slab_end(lo, hi, hi_t) & ~(hi_t < p->inst_lo) & p->inst_ok;
}

/* Mirrors rt_inst_enter per lane (w the world rays), into p->inst_lo and
 * p->inst_ok. */
static void pk_inst_enter(RT_GLOBAL const rt_instance *in, const pk_ray *w, pk_ray *p) {
    pk_f lo = w->box_lo, hi = (pk_f)RT_INF;
    for (int i = 0; i < 3; i++) pk_slab((pk_f)in->bmin[i], (pk_f)in->bmax[i], w, i, &lo, &hi);
    p->inst_lo = lo;
    p->inst_ok = pk_slab_end(lo, hi, (pk_f)RT_INF);
}

/* ---- ray/triangle: each returns the lanes of act that hit, with t, u, v ---- */

/* Mirrors rt_dot3 and rt_cross3 on vectors. */
static pk_f pk_dot3(const pk_f *a, const pk_f *b) {
    return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}
static void pk_cross3(const pk_f *a, const pk_f *b, pk_f *out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* rt_edge_recheck for the lanes of m (rare): per lane, the shared scalar
 * function, since the exact difference of products is integer code. */
static void pk_edge_recheck(pk_i m, pk_f Ax, pk_f Ay, pk_f Bx, pk_f By, pk_f Cx, pk_f Cy, pk_f *U,
                            pk_f *V, pk_f *W) {
    float ax[RT_PK_LANES], ay[RT_PK_LANES], bx[RT_PK_LANES], by[RT_PK_LANES], cx[RT_PK_LANES],
        cy[RT_PK_LANES], u[RT_PK_LANES], v[RT_PK_LANES], w[RT_PK_LANES];
    int mm[RT_PK_LANES];
    pk_vstore(Ax, 0, ax);
    pk_vstore(Ay, 0, ay);
    pk_vstore(Bx, 0, bx);
    pk_vstore(By, 0, by);
    pk_vstore(Cx, 0, cx);
    pk_vstore(Cy, 0, cy);
    pk_vstore(*U, 0, u);
    pk_vstore(*V, 0, v);
    pk_vstore(*W, 0, w);
    pk_vstore(m, 0, mm);
    for (int l = 0; l < RT_PK_LANES; l++)
        if (mm[l]) rt_edge_recheck(ax[l], ay[l], bx[l], by[l], cx[l], cy[l], &u[l], &v[l], &w[l]);
    *U = pk_vload(0, u);
    *V = pk_vload(0, v);
    *W = pk_vload(0, w);
}

/* rt_tri_t_max per lane (a > b ? a : b; fmax differs on NaN). */
static pk_f pk_tmax(pk_f a, pk_f b) {
    return select(b, a, a > b);
}

/* rt_tri_t_check per lane: RT_T_FAST, RT_T_PLANE or RT_T_BEFORE in each
 * lane (a verdict, not a pointer out: Oclgrind computed the packet kernel
 * wrongly with a vector written through a pointer argument here). */
static pk_i pk_tri_t_check(pk_f Akz, pk_f Bkz, pk_f Ckz, pk_f sx, pk_f sy, pk_f Ax, pk_f Ay,
                           pk_f Bx, pk_f By, pk_f Cx, pk_f Cy, pk_f Az, pk_f Bz, pk_f Cz, pk_f det,
                           pk_f t, pk_f tmin) {
    pk_f S = pk_tmax(fabs(sx), fabs(sy));
    pk_f K = pk_tmax(fabs(Akz), pk_tmax(fabs(Bkz), fabs(Ckz)));
    pk_f P = pk_tmax(pk_tmax(fabs(Ax), fabs(Ay)),
                     pk_tmax(pk_tmax(fabs(Bx), fabs(By)), pk_tmax(fabs(Cx), fabs(Cy))));
    pk_f zmax = pk_tmax(Az, pk_tmax(Bz, Cz));
    pk_f zmin = -pk_tmax(-Az, pk_tmax(-Bz, -Cz));
    pk_f Z = pk_tmax(zmax, -zmin);
    pk_f adet = fabs(det);
    pk_f lhs = (((S * K + 0.75f * P) * P) * (zmax - zmin)) * 0.5f + (adet * Z) * 0.0625f;
    pk_i unsure = lhs > fabs(t) * adet;
    pk_i before = unsure & (((tmin - t) * adet) * 32768.0f > lhs) & (lhs > RT_T_BEFORE_FLOOR);
    return select(select((pk_i)RT_T_FAST, (pk_i)RT_T_PLANE, unsure), (pk_i)RT_T_BEFORE, before);
}

/* rt_tri_t_plane for the lanes of m (rare): per lane, the shared scalar
 * function. */
static pk_f pk_tri_t_plane(RT_GLOBAL const rt_tri *tri, const pk_ray *p, pk_i m, pk_f t) {
    float o[3][RT_PK_LANES], d[3][RT_PK_LANES], tt[RT_PK_LANES];
    int mm[RT_PK_LANES];
    for (int i = 0; i < 3; i++) {
        pk_vstore(p->org[i], 0, o[i]);
        pk_vstore(p->dir[i], 0, d[i]);
    }
    pk_vstore(t, 0, tt);
    pk_vstore(m, 0, mm);
    for (int l = 0; l < RT_PK_LANES; l++) {
        if (!mm[l]) continue;
        rt_ray r;
        for (int i = 0; i < 3; i++) {
            r.org[i] = o[i][l];
            r.dir[i] = d[i][l];
        }
        r.tmin = 0.0f;
        r.tmax = 0.0f;
        tt[l] = rt_tri_t_plane(tri, &r, tt[l]);
    }
    return pk_vload(0, tt);
}

/* Mirrors rt_tri_watertight; the exact re-check of zero edge functions is
 * done for the lanes that have one, and the plane's t for the lanes whose
 * fast t may be off (rt_tri_t.h). */
static pk_i pk_tri_watertight(RT_GLOBAL const rt_tri *tri, const pk_ray *p, pk_f tmin, pk_f tmax,
                              pk_i act, pk_f *t, pk_f *u, pk_f *v) {
    pk_f A[3], B[3], C[3];
    for (int i = 0; i < 3; i++) {
        A[i] = tri->v0[i] - p->org[i];
        B[i] = tri->v1[i] - p->org[i];
        C[i] = tri->v2[i] - p->org[i];
    }
    pk_f Akz = PK_PICK(A[0], A[1], A[2], p->kz), Bkz = PK_PICK(B[0], B[1], B[2], p->kz),
         Ckz = PK_PICK(C[0], C[1], C[2], p->kz);
    pk_f Ax = PK_PICK(A[0], A[1], A[2], p->kx) - p->sx * Akz;
    pk_f Ay = PK_PICK(A[0], A[1], A[2], p->ky) - p->sy * Akz;
    pk_f Bx = PK_PICK(B[0], B[1], B[2], p->kx) - p->sx * Bkz;
    pk_f By = PK_PICK(B[0], B[1], B[2], p->ky) - p->sy * Bkz;
    pk_f Cx = PK_PICK(C[0], C[1], C[2], p->kx) - p->sx * Ckz;
    pk_f Cy = PK_PICK(C[0], C[1], C[2], p->ky) - p->sy * Ckz;
    pk_f U = Cx * By - Cy * Bx;
    pk_f V = Ax * Cy - Ay * Cx;
    pk_f W = Bx * Ay - By * Ax;
    pk_i zero = (U == 0.0f) | (V == 0.0f) | (W == 0.0f);
    if (pk_any(zero & act)) pk_edge_recheck(zero & act, Ax, Ay, Bx, By, Cx, Cy, &U, &V, &W);
    pk_i ok =
        act & ~(((U < 0.0f) | (V < 0.0f) | (W < 0.0f)) & ((U > 0.0f) | (V > 0.0f) | (W > 0.0f)));
    if (!pk_any(ok)) return ok;
    pk_f det = (U + V) + W;
    ok &= det != 0.0f;
    if (!pk_any(ok)) return ok;
    pk_f Az = p->sz * Akz, Bz = p->sz * Bkz, Cz = p->sz * Ckz;
    pk_f T = (U * Az + V * Bz) + W * Cz;
    pk_f tt = PK_DIV(T, det);
    pk_i check = pk_tri_t_check(Akz, Bkz, Ckz, p->sx, p->sy, Ax, Ay, Bx, By, Cx, Cy, Az, Bz, Cz,
                                det, tt, tmin);
    pk_i unsure = ok & (check == RT_T_PLANE);
    ok &= check != RT_T_BEFORE;
    if (pk_any(unsure)) tt = pk_tri_t_plane(tri, p, unsure, tt);
    ok &= (tt >= tmin) & (tt <= tmax);
    if (!pk_any(ok)) return ok;
    *t = tt;
    *u = PK_DIV(V, det);
    *v = PK_DIV(W, det);
    return ok;
}

/* Mirrors rt_tri_moller. */
static pk_i pk_tri_moller(RT_GLOBAL const rt_tri *tri, const pk_ray *p, pk_f tmin, pk_f tmax,
                          pk_i act, pk_f *t, pk_f *u, pk_f *v) {
    pk_f e1[3], e2[3], s[3], pv[3], q[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = (pk_f)(tri->v1[i] - tri->v0[i]);
        e2[i] = (pk_f)(tri->v2[i] - tri->v0[i]);
        s[i] = p->org[i] - tri->v0[i];
    }
    pk_cross3(p->dir, e2, pv);
    pk_f det = pk_dot3(e1, pv);
    pk_i ok = act & (det != 0.0f);
    if (!pk_any(ok)) return ok;
    pk_f inv = PK_DIV(1.0f, det);
    pk_f uu = pk_dot3(s, pv) * inv;
    ok &= (uu >= 0.0f) & (uu <= 1.0f);
    if (!pk_any(ok)) return ok;
    pk_cross3(s, e1, q);
    pk_f vv = pk_dot3(p->dir, q) * inv;
    ok &= (vv >= 0.0f) & (uu + vv <= 1.0f);
    if (!pk_any(ok)) return ok;
    pk_f tt = pk_dot3(e2, q) * inv;
    ok &= (tt >= tmin) & (tt <= tmax);
    *t = tt;
    *u = uu;
    *v = vv;
    return ok;
}

/* Mirrors rt_tri_pluecker. */
static pk_i pk_tri_pluecker(RT_GLOBAL const rt_tri *tri, const pk_ray *p, pk_f tmin, pk_f tmax,
                            pk_i act, pk_f *t, pk_f *u, pk_f *v) {
    pk_f a[3], b[3], c[3], bc[3], ca[3], ab[3];
    for (int i = 0; i < 3; i++) {
        a[i] = tri->v0[i] - p->org[i];
        b[i] = tri->v1[i] - p->org[i];
        c[i] = tri->v2[i] - p->org[i];
    }
    pk_cross3(b, c, bc);
    pk_cross3(c, a, ca);
    pk_cross3(a, b, ab);
    pk_f U = pk_dot3(p->dir, bc), V = pk_dot3(p->dir, ca), W = pk_dot3(p->dir, ab);
    pk_i ok =
        act & ~(((U < 0.0f) | (V < 0.0f) | (W < 0.0f)) & ((U > 0.0f) | (V > 0.0f) | (W > 0.0f)));
    if (!pk_any(ok)) return ok;
    pk_f det = (U + V) + W;
    ok &= det != 0.0f;
    if (!pk_any(ok)) return ok;
    pk_f tt = PK_DIV(pk_dot3(a, bc), det);
    ok &= (tt >= tmin) & (tt <= tmax);
    if (!pk_any(ok)) return ok;
    *t = tt;
    *u = PK_DIV(V, det);
    *v = PK_DIV(W, det);
    return ok;
}

/* Mirrors rt_tri_badouel: the plane and its projection axis are the
 * triangle's (the same for every lane), the hit point each lane's. */
static pk_i pk_tri_badouel(RT_GLOBAL const rt_tri *tri, const pk_ray *p, pk_f tmin, pk_f tmax,
                           pk_i act, pk_f *t, pk_f *u, pk_f *v) {
    float e1[3], e2[3], n[3];
    pk_f a[3], nv[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = tri->v1[i] - tri->v0[i];
        e2[i] = tri->v2[i] - tri->v0[i];
        a[i] = tri->v0[i] - p->org[i];
    }
    rt_cross3(e1, e2, n);
    for (int i = 0; i < 3; i++) nv[i] = (pk_f)n[i];
    pk_f nd = pk_dot3(nv, p->dir);
    pk_i ok = act & (nd != 0.0f);
    if (!pk_any(ok)) return ok;
    pk_f tt = PK_DIV(pk_dot3(nv, a), nd);
    ok &= (tt >= tmin) & (tt <= tmax);
    if (!pk_any(ok)) return ok;
    float nx = RT_FABS(n[0]), ny = RT_FABS(n[1]), nz = RT_FABS(n[2]);
    rt_i32 k = 0;
    if (ny > nx) k = 1;
    if (nz > (k == 1 ? ny : nx)) k = 2;
    rt_i32 i1 = k == 0 ? 1 : 0, i2 = k == 2 ? 1 : 2;
    pk_f p1 = (p->org[i1] + tt * p->dir[i1]) - tri->v0[i1];
    pk_f p2 = (p->org[i2] + tt * p->dir[i2]) - tri->v0[i2];
    float det = e1[i1] * e2[i2] - e1[i2] * e2[i1];
    pk_f uu = PK_DIV(p1 * e2[i2] - p2 * e2[i1], (pk_f)det);
    pk_f vv = PK_DIV(e1[i1] * p2 - e1[i2] * p1, (pk_f)det);
    ok &= (uu >= 0.0f) & (vv >= 0.0f) & (uu + vv <= 1.0f);
    *t = tt;
    *u = uu;
    *v = vv;
    return ok;
}

/* Mirrors rt_tri_test (a compile-time method in a specialised build). */
static pk_i pk_tri(rt_u32 method, RT_GLOBAL const rt_tri *tri, const pk_ray *p, pk_f tmin,
                   pk_f tmax, pk_i act, pk_f *t, pk_f *u, pk_f *v) {
    if (method == RT_TRI_MOLLER) return pk_tri_moller(tri, p, tmin, tmax, act, t, u, v);
    if (method == RT_TRI_PLUECKER) return pk_tri_pluecker(tri, p, tmin, tmax, act, t, u, v);
    if (method == RT_TRI_BADOUEL) return pk_tri_badouel(tri, p, tmin, tmax, act, t, u, v);
    return pk_tri_watertight(tri, p, tmin, tmax, act, t, u, v);
}

/* ---- traversal ------------------------------------------------------------ */

/* Mirrors rt_hit_before per lane: is (t, inst, prim) before the lane's best? */
static pk_i pk_before(pk_f t, rt_u32 inst, rt_u32 prim, const pk_state *st) {
    return select(select(prim < st->prim, inst < st->inst, inst != st->inst), t < st->t,
                  t != st->t);
}

/* Mirrors rt_leaf_test for the lanes in mask: each lane tests every
 * triangle of the leaf against its own range [tmin, best t]. */
static void pk_leaf(const rt_scene_view *s, rt_u32 first, rt_u32 count, rt_u32 inst,
                    const pk_ray *p, pk_i mask, pk_state *st) {
    rt_u32 method = RT_TRI_METHOD(s);
    for (rt_u32 e = first; e < first + count; e++) {
        pk_i act = mask & ~st->done;
        if (!pk_any(act)) return;
        pk_f t, u, v;
        st->tris -= act; /* c->tri_tests++ in the active lanes */
        pk_i hit = pk_tri(method, &s->tris[e], p, p->tmin, st->t, act, &t, &u, &v);
        if (!pk_any(hit)) continue;
        hit &= pk_hit_accepted(&s->tris[e], p, t);
        if (!pk_any(hit)) continue;
        rt_u32 prim = s->tri_ids[e];
        pk_i take = st->any_hit ? hit : hit & pk_before(t, inst, prim, st);
        st->t = select(st->t, t, take);
        st->u = select(st->u, u, take);
        st->v = select(st->v, v, take);
        st->prim = select(st->prim, (pk_u)prim, take);
        st->inst = select(st->inst, (pk_u)inst, take);
        st->entry = select(st->entry, (pk_u)e, take);
        if (st->any_hit) st->done |= take;
    }
}

/* Pushes or continues with the nearer child: the order is a heuristic only
 * (the hit does not depend on it), judged by the lanes that hit both. */
static int pk_right_first(pk_i both, pk_f t0, pk_f t1) {
    return pk_any(both & (t1 < t0));
}

/* A traversal's stack: node index and lane mask per entry. */
typedef struct pk_stack {
    rt_u32 node[RT_STACK_SIZE];
    pk_i mask[RT_STACK_SIZE];
    int sp;
} pk_stack;

/* Starts a traversal of the BVH at root for the lanes in active: mirrors the
 * root box test of rt_trace_mesh and rt_trace (counted per lane). */
static pk_i pk_start(const rt_scene_view *s, rt_u32 root, const pk_ray *p, pk_i active,
                     pk_state *st, pk_stack *k) {
    pk_f tn;
    k->sp = 0;
    active &= ~st->done;
    if (!pk_any(active)) return active;
    st->boxes -= active;
    pk_f hi = st->t + RT_FABS(st->t) * RT_BOX_T_MARGIN; /* rt_box_hi(best t) */
    return pk_box(&s->nodes[root], p, p->box_lo, hi, &tn) & active;
}

/* Goes from (node, mask) to the next leaf that some lane reaches: mirrors
 * rt_descend per lane (a lane tests a node's children when its test of the
 * node passed, against its own range [tmin, best t]) and the pops of
 * rt_trace_mesh and rt_trace. Returns 0 when the stack is empty. */
static int pk_next_leaf(const rt_scene_view *s, const pk_ray *p, pk_state *st, pk_stack *k,
                        rt_u32 *node, pk_i *mask) {
    for (;;) {
        while (!pk_any(*mask)) {
            if (k->sp == 0) return 0;
            --k->sp;
            *node = k->node[k->sp];
            *mask = k->mask[k->sp] & ~st->done;
        }
        RT_GLOBAL const rt_node *n = &s->nodes[*node];
        if (n->b & RT_NODE_LEAF_FLAG) return 1;
        pk_f tn0, tn1, hi = st->t + RT_FABS(st->t) * RT_BOX_T_MARGIN;
        st->boxes -= *mask;
        st->boxes -= *mask;
        pk_i m0 = pk_box(&s->nodes[n->a], p, p->box_lo, hi, &tn0) & *mask;
        pk_i m1 = pk_box(&s->nodes[n->b], p, p->box_lo, hi, &tn1) & *mask;
        int h0 = pk_any(m0), h1 = pk_any(m1);
        if (h0 && h1) {
            int right_first = pk_right_first(m0 & m1, tn0, tn1);
            k->node[k->sp] = right_first ? n->a : n->b;
            k->mask[k->sp++] = right_first ? m0 : m1;
            *node = right_first ? n->b : n->a;
            *mask = right_first ? m1 : m0;
        } else {
            *node = h0 ? n->a : n->b;
            *mask = h0 ? m0 : m1;
        }
    }
}

/* Mirrors rt_trace_mesh: the mesh BVH at root, the rays in its space. */
static void pk_mesh(const rt_scene_view *s, rt_u32 root, rt_u32 inst, const pk_ray *p, pk_i active,
                    pk_state *st) {
    pk_stack k;
    rt_u32 node = root;
    pk_i mask = pk_start(s, root, p, active, st, &k);
    while (pk_next_leaf(s, p, st, &k, &node, &mask)) {
        RT_GLOBAL const rt_node *n = &s->nodes[node];
        pk_leaf(s, n->a, n->b & RT_NODE_COUNT_MASK, inst, p, mask, st);
        mask = (pk_i)0;
    }
}

/* ---- kd-tree meshes (RT_INST_KD) -----------------------------------------
 *
 * Mirrors rt_kd_trace_mesh (rt_kd.h) per lane, as cpu_ref/packet_kd.h does
 * for the CPU packet backend: a lane takes part in a cell exactly when its
 * own traversal visits that cell, in its own front-to-back order. Forward
 * lanes (1/dir >= 0 on the split axis, or parallel to the plane) take the
 * left child first, backward lanes the right; a node schedules, bottom to
 * top of the stack, the left child for backward lanes that go there second,
 * the right child for every lane that goes there, and (at once) the left
 * child for forward lanes that go there first. On a pop a lane stays when
 * its entry is at most rt_box_hi(best t), unless it is one the oracle takes
 * straight into that cell (its first or only child: 'keep'). So each lane's
 * leaves, tests and hits are the oracle's for the same starting best hit. */

/* Two cells per node on the path at most; flatten admits no tree deeper than
 * RT_KD_STACK - 2. */
#define PK_KD_STACK (2 * RT_KD_STACK)

static void pk_kd_mesh(const rt_scene_view *s, rt_u32 root, rt_u32 inst, const pk_ray *p,
                       pk_i active, pk_state *st) {
    pk_i m = active & ~st->done;
    if (!pk_any(m)) return;
    RT_GLOBAL const rt_node *rn = &s->nodes[root];
    /* rt_kd_root_interval over [rt_box_lo(tmin), rt_box_hi(best t)]. */
    st->boxes -= m;
    pk_f tn = p->box_lo, tf = (pk_f)RT_INF;
    for (int i = 0; i < 3; i++) pk_slab((pk_f)rn->bmin[i], (pk_f)rn->bmax[i], p, i, &tn, &tf);
    pk_f hi = st->t + RT_FABS(st->t) * RT_BOX_T_MARGIN;
    tf = tf * select((pk_f)RT_BOX_FAR_SCALE, (pk_f)RT_BOX_FAR_SCALE_NEG, tf < 0.0f);
    tf = select(tf, hi, hi < tf);
    m &= tn <= tf;
    if (!pk_any(m)) return;
    pk_f c_tn[PK_KD_STACK], c_tf[PK_KD_STACK];
    pk_i c_mask[PK_KD_STACK], c_keep[PK_KD_STACK];
    rt_u32 c_node[PK_KD_STACK];
    int sp = 0;
    rt_u32 node = rn->a;
    for (;;) {
        RT_GLOBAL const rt_kd_node *n = &s->kd_nodes[node];
        rt_u32 k = n->b & 3u;
        if (k == RT_KD_LEAF) {
            pk_leaf(s, n->a, n->b >> 2, inst, p, m, st);
        } else {
            st->boxes -= m;
            pk_f split = (pk_f)RT_AS_FLOAT((rt_i32)n->a);
            rt_u32 left = node + 1u, right = n->b >> 2;
            pk_f o = p->org[k], inv = p->inv[k];
            /* Parallel lanes: the origin's side, both in the plane; their
             * plane distance (maybe 0 * inf) is never used. */
            pk_i par = ~(RT_FABS(inv) < (pk_f)RT_INF);
            pk_f ts = (split - o) * inv;
            pk_f mg = select((pk_f)0.0f, RT_FABS(ts) * RT_BOX_T_MARGIN, RT_FABS(ts) < (pk_f)RT_INF);
            pk_f ts_lo = ts - mg, ts_hi = ts + mg;
            pk_f first_tf = select(select(tf, ts_hi, ts_hi < tf), tf, par);
            pk_f second_tn = select(select(tn, ts_lo, ts_lo > tn), tn, par);
            hi = st->t + RT_FABS(st->t) * RT_BOX_T_MARGIN;
            pk_i go_first = select(tn <= ts_hi, o <= split, par);
            pk_i go_second = select((ts_lo <= tf) & (second_tn <= hi), o >= split, par);
            pk_i fwd = par | (inv >= 0.0f);
            pk_i bf = go_first & m, bs = go_second & m;
            pk_i left_fwd = bf & fwd, left_bwd = bs & ~fwd;
            pk_i to_right = (bf & ~fwd) | (bs & fwd);
            pk_i only = ~(bf & bs); /* straight into the cell, as the oracle goes */
            if (pk_any(left_bwd)) {
                c_tn[sp] = second_tn;
                c_tf[sp] = tf;
                c_mask[sp] = left_bwd;
                c_keep[sp] = left_bwd & only;
                c_node[sp++] = left;
            }
            if (pk_any(to_right)) {
                c_tn[sp] = select(tn, second_tn, fwd);
                c_tf[sp] = select(first_tf, tf, fwd);
                c_mask[sp] = to_right;
                c_keep[sp] = (bf & ~fwd) | (to_right & only);
                c_node[sp++] = right;
            }
            if (pk_any(left_fwd)) {
                node = left;
                tf = first_tf;
                m = left_fwd;
                continue;
            }
        }
        /* The next cell with a lane whose best hit may still lie in it. */
        for (;;) {
            if (sp == 0) return;
            --sp;
            hi = st->t + RT_FABS(st->t) * RT_BOX_T_MARGIN;
            m = c_mask[sp] & ~st->done & (c_keep[sp] | (c_tn[sp] <= hi));
            if (pk_any(m)) break;
        }
        node = c_node[sp];
        tn = c_tn[sp];
        tf = c_tf[sp];
    }
}

/* Mirrors rt_trace_instance. */
static void pk_instance(const rt_scene_view *s, rt_u32 inst, const pk_ray *p, pk_i active,
                        pk_state *st) {
    RT_GLOBAL const rt_instance *in = &s->instances[inst];
    /* rt_trace_masked's mask test: the lanes whose mask shares a bit with
     * the instance's. */
    active &= (st->ray_mask & (pk_u)in->mask) != (pk_u)0u;
    if (!pk_any(active)) return;
    pk_ray o;
    if (RT_INST_FLAGS(in) & RT_INST_IDENTITY)
        o = *p;
    else
        pk_to_object(in, p, &o);
    if (!(RT_SCENE_FLAGS(s) & RT_SCENE_SINGLE)) {
        pk_inst_enter(in, p, &o);
        active &= o.inst_ok;
        if (!pk_any(active)) return;
    }
    if (RT_INST_FLAGS(in) & RT_INST_KD)
        pk_kd_mesh(s, in->root, inst, &o, active, st);
    else
        pk_mesh(s, in->root, inst, &o, active, st);
}

/* Mirrors the object-BVH loop of rt_trace: each reached leaf's instances
 * for the lanes that reached it. */
static void pk_top(const rt_scene_view *s, const pk_ray *p, pk_i active, pk_state *st) {
    pk_stack k;
    rt_u32 node = s->hdr->top_root;
    pk_i mask = pk_start(s, node, p, active, st, &k);
    while (pk_next_leaf(s, p, st, &k, &node, &mask)) {
        RT_GLOBAL const rt_node *n = &s->nodes[node];
        for (rt_u32 e = n->a; e < n->a + (n->b & RT_NODE_COUNT_MASK); e++)
            pk_instance(s, s->inst_ids[e], p, mask, st);
        mask = (pk_i)0;
    }
}

/* Mirrors rt_trace_masked (with rt_hit_init) for the lanes in active, lane
 * l's mask lane l of ray_mask; the hits are in st (prim RT_NO_HIT on a
 * miss), the tests added to st's counters. */
static void pk_trace(const rt_scene_view *s, const pk_ray *p, pk_i active, int any_hit,
                     pk_u ray_mask, pk_state *st) {
    st->ray_mask = ray_mask;
    st->t = p->tmax;
    st->u = st->v = (pk_f)0.0f;
    st->prim = st->inst = st->entry = (pk_u)RT_NO_HIT;
    st->done = (pk_i)0;
    st->any_hit = any_hit;
    st->rays -= active;
    if (s->hdr->instance_count == 0) return;
    if (RT_SCENE_FLAGS(s) & RT_SCENE_SINGLE) {
        pk_instance(s, 0, p, active, st);
        return;
    }
    pk_top(s, p, active, st);
}

/* ---- shading of the primary hits ------------------------------------------
 *
 * The root node of each pixel's shading tree (the whole tree without
 * secondary rays) is shaded in vectors: each function mirrors the shared one
 * named at it, per lane, with the lane's own triangle, instance and material
 * gathered into vectors. The subtrees of reflection and refraction rays are
 * the shared functions per lane (rt_k_packet). */

/* Mirrors rt_normalize3. */
static void pk_normalize3(pk_f *v) {
    pk_f len = PK_SQRT(pk_dot3(v, v));
    pk_i pos = len > 0.0f;
    for (int k = 0; k < 3; k++) v[k] = select(v[k], PK_DIV(v[k], len), pos);
}

/* Mirrors rt_offset_point. */
static void pk_offset_point(const pk_f *p, const pk_f *n, pk_f sign, pk_f *out) {
    for (int i = 0; i < 3; i++) {
        pk_f ni = sign * n[i];
        pk_i of = pk_to_i(256.0f * ni);
        pk_f pi = pk_as_f(pk_as_i(p[i]) + select(of, -of, p[i] < 0.0f));
        out[i] = select(pi, p[i] + 0.0000152587890625f * ni, RT_FABS(p[i]) < 0.03125f);
    }
}

/* rt_surface per lane, and the lanes' materials (rt_material_d). */
typedef struct pk_surf {
    pk_f p[3], ng[3], ns[3];
    pk_i front;
    pk_u material;
} pk_surf;

typedef struct pk_mat {
    pk_f color[3], ambient, diffuse, specular, reflectivity, transparency, emission[3];
    pk_i shininess;
} pk_mat;

/* Mirrors rt_normal_to_world: m[j][i] is the lanes' world_to_object[4 j + i]. */
static void pk_normal_to_world(pk_f m[3][3], const pk_f *n, pk_f *out) {
    for (int i = 0; i < 3; i++) out[i] = (m[0][i] * n[0] + m[1][i] * n[1]) + m[2][i] * n[2];
}

/* Mirrors rt_surface_at for the lanes in hit (closest hits in h of the rays
 * r), and gathers each hit lane's material into mat. Lanes outside hit read
 * lane some's triangle (some hits) and compute values nobody uses. */
static void pk_surface_at(const rt_scene_view *s, const pk_ray *r, const pk_state *h, pk_i hit,
                          int some, pk_surf *sf, pk_mat *mat) {
    uint ent[RT_PK_LANES], ins[RT_PK_LANES], mi[RT_PK_LANES];
    int hm[RT_PK_LANES], fl[RT_PK_LANES], shin[RT_PK_LANES];
    float v[9][RT_PK_LANES], m[9][RT_PK_LANES], vn[9][RT_PK_LANES], mf[11][RT_PK_LANES];
    float om[12][RT_PK_LANES];
    pk_vstore(h->entry, 0, ent);
    pk_vstore(h->inst, 0, ins);
    pk_vstore(hit, 0, hm);
    for (int l = 0; l < RT_PK_LANES; l++) {
        uint e = hm[l] ? ent[l] : ent[some], ii = hm[l] ? ins[l] : ins[some];
        RT_GLOBAL const rt_tri *tri = &s->tris[e];
        RT_GLOBAL const rt_instance *in = &s->instances[ii];
        for (int k = 0; k < 3; k++) {
            v[k][l] = tri->v0[k];
            v[3 + k][l] = tri->v1[k];
            v[6 + k][l] = tri->v2[k];
            for (int j = 0; j < 3; j++) m[3 * j + k][l] = in->world_to_object[4 * j + k];
        }
        for (int k = 0; k < 12; k++) om[k][l] = in->object_to_world[k];
        fl[l] = (int)RT_INST_FLAGS(in);
        for (int k = 0; k < 9; k++)
            vn[k][l] = (RT_INST_FLAGS(in) & RT_INST_NORMALS) ? s->tri_normals[9 * e + k] : 0.0f;
        mi[l] = in->material;
        if ((RT_SCENE_FLAGS(s) & RT_SCENE_TRI_MATS) && s->tri_mats[e] != RT_NO_MATERIAL)
            mi[l] = s->tri_mats[e];
        RT_GLOBAL const rt_material_d *md = &s->materials[mi[l]];
        for (int k = 0; k < 3; k++) mf[k][l] = md->color[k];
        mf[3][l] = md->ambient;
        mf[4][l] = md->diffuse;
        mf[5][l] = md->specular;
        mf[6][l] = md->reflectivity;
        mf[7][l] = md->transparency;
        for (int k = 0; k < 3; k++) mf[8 + k][l] = md->emission[k];
        shin[l] = md->shininess;
    }
    sf->material = pk_vload(0, mi);
    for (int k = 0; k < 3; k++) mat->color[k] = pk_vload(0, mf[k]);
    mat->ambient = pk_vload(0, mf[3]);
    mat->diffuse = pk_vload(0, mf[4]);
    mat->specular = pk_vload(0, mf[5]);
    mat->reflectivity = pk_vload(0, mf[6]);
    mat->transparency = pk_vload(0, mf[7]);
    for (int k = 0; k < 3; k++) mat->emission[k] = pk_vload(0, mf[8 + k]);
    mat->shininess = pk_vload(0, shin);

    pk_i flags = pk_vload(0, fl);
    pk_i identity = (flags & (int)RT_INST_IDENTITY) != 0;
    int transform = pk_any(hit & ~identity);
    pk_f wm[3][3];
    if (transform)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) wm[j][k] = pk_vload(0, m[3 * j + k]);
    pk_f e1[3], e2[3], n[3], w[3], po[3];
    pk_f b0 = (1.0f - h->u) - h->v;
    for (int k = 0; k < 3; k++) {
        pk_f v0 = pk_vload(0, v[k]), v1 = pk_vload(0, v[3 + k]), v2 = pk_vload(0, v[6 + k]);
        e1[k] = v1 - v0;
        e2[k] = v2 - v0;
        po[k] = (b0 * v0 + h->u * v1) + h->v * v2;
    }
    /* rt_point_to_world where a lane has a transform. */
    for (int i = 0; i < 3; i++) {
        sf->p[i] = po[i];
        if (transform) {
            pk_f pw = ((pk_vload(0, om[4 * i]) * po[0] + pk_vload(0, om[4 * i + 1]) * po[1]) +
                       pk_vload(0, om[4 * i + 2]) * po[2]) +
                      pk_vload(0, om[4 * i + 3]);
            sf->p[i] = select(pw, po[i], identity);
        }
    }
    pk_cross3(e1, e2, n);
    if (transform) {
        pk_normal_to_world(wm, n, w);
        for (int k = 0; k < 3; k++) sf->ng[k] = select(w[k], n[k], identity);
    } else {
        for (int k = 0; k < 3; k++) sf->ng[k] = n[k];
    }
    pk_normalize3(sf->ng);
    for (int k = 0; k < 3; k++) sf->ns[k] = sf->ng[k];
    pk_i normals = hit & ((flags & (int)RT_INST_NORMALS) != 0);
    if (pk_any(normals)) {
        pk_f wt = (1.0f - h->u) - h->v, ns[3];
        for (int k = 0; k < 3; k++)
            n[k] = (wt * pk_vload(0, vn[k]) + h->u * pk_vload(0, vn[3 + k])) +
                   h->v * pk_vload(0, vn[6 + k]);
        if (transform) {
            pk_normal_to_world(wm, n, w);
            for (int k = 0; k < 3; k++) ns[k] = select(w[k], n[k], identity);
        } else {
            for (int k = 0; k < 3; k++) ns[k] = n[k];
        }
        pk_normalize3(ns);
        pk_i take = normals & (pk_dot3(ns, ns) > 0.0f);
        for (int k = 0; k < 3; k++) sf->ns[k] = select(sf->ns[k], ns[k], take);
    }
    sf->front = pk_dot3(sf->ns, r->dir) < 0.0f;
    pk_i flip = pk_dot3(sf->ng, r->dir) > 0.0f;
    for (int k = 0; k < 3; k++) {
        sf->ng[k] = select(sf->ng[k], -sf->ng[k], flip);
        sf->ns[k] = select(-sf->ns[k], sf->ns[k], sf->front);
    }
}

/* The root node of each lane's shading tree (primary rays p, closest hits
 * h), as rt_shade_step: rt_shade_begin, then per light rt_phong_light and,
 * where the shadow ray (the lanes' traced together) finds no occluder,
 * rt_phong_add; then rt_shade_end's term. rgb gets 0 + that term (a miss:
 * 0 + the background; nothing without local weight): the pixel where there
 * are no secondary rays. The shadow rays' tests are added to boxes, tris,
 * rays. For rt_shade_end's secondary rays the node's halves stay in hitp
 * (lanes with a hit), sfp, dn, lit and lwp (rt_shade_node's fields). */
static void pk_shade_root(const rt_scene_view *s, const pk_ray *p, const pk_state *h, pk_i active,
                          pk_f *rgb, pk_i *boxes, pk_i *tris, pk_i *rays, pk_i *hitp, pk_surf *sfp,
                          pk_f *dn, pk_f *lit, pk_f *lwp) {
    RT_GLOBAL const rt_scene_header *hdr = s->hdr;
    const float one = 1.0f; /* the primary ray's weight, each channel */
    pk_i hit = active & (h->prim != RT_NO_HIT);
    *hitp = hit;
    for (int k = 0; k < 3; k++) lit[k] = (pk_f)0.0f; /* defined where not lit */
    for (int k = 0; k < 3; k++) /* rt_shade_end of a miss: 0 + w * background */
        rgb[k] = select((pk_f)0.0f, (pk_f)(0.0f + one * hdr->background[k]), active & ~hit);
    int some = -1;
    {
        int hm[RT_PK_LANES];
        pk_vstore(hit, 0, hm);
        for (int l = RT_PK_LANES - 1; l >= 0; l--)
            if (hm[l]) some = l;
    }
    if (some < 0) return;
    /* rt_shade_begin */
    pk_mat m;
    pk_surface_at(s, p, h, hit, some, sfp, &m);
    const pk_surf *sf = sfp;
    for (int k = 0; k < 3; k++) dn[k] = p->dir[k];
    pk_normalize3(dn);
    pk_f lw = (1.0f - m.reflectivity) - m.transparency;
    *lwp = lw;
    pk_i lighting = hit & (lw > 0.0f);
    if (!pk_any(lighting)) return;
    for (int k = 0; k < 3; k++) lit[k] = m.emission[k] + (m.ambient * m.color[k]) * hdr->ambient[k];
    for (rt_u32 li = 0; li < hdr->light_count; li++) {
        /* rt_phong_light */
        RT_GLOBAL const rt_light_d *light = &s->lights[li];
        pk_f L[3], Ln[3];
        for (int k = 0; k < 3; k++) L[k] = light->position[k] - sf->p[k];
        pk_f dist = PK_SQRT(pk_dot3(L, L));
        pk_i ok = lighting & (dist > 0.0f);
        for (int k = 0; k < 3; k++) Ln[k] = PK_DIV(L[k], dist);
        pk_f ndl = pk_dot3(sf->ns, Ln);
        ok &= ndl > 0.0f;
        if (!pk_any(ok)) continue;
        pk_ray sr;
        pk_offset_point(sf->p, sf->ng, select((pk_f)-1.0f, (pk_f)1.0f, pk_dot3(sf->ng, L) >= 0.0f),
                        sr.org);
        for (int k = 0; k < 3; k++) {
            sr.dir[k] = light->position[k] - sr.org[k];
            /* Lanes without a shadow ray trace their primary ray, inactive. */
            sr.org[k] = select(p->org[k], sr.org[k], ok);
            sr.dir[k] = select(p->dir[k], sr.dir[k], ok);
        }
        sr.tmin = (pk_f)0.0f;
        sr.tmax = (pk_f)RT_SHADOW_TMAX;
        pk_prepare(&sr);
        pk_state ss;
        ss.boxes = ss.tris = ss.rays = (pk_i)0;
        pk_trace(s, &sr, ok, 1, (pk_u)0xffffffffu, &ss);
        *boxes += ss.boxes;
        *tris += ss.tris;
        *rays += ss.rays;
        /* rt_phong_add where the shadow ray found no occluder */
        pk_i add = ok & (ss.prim == RT_NO_HIT);
        if (!pk_any(add)) continue;
        for (int k = 0; k < 3; k++)
            lit[k] =
                select(lit[k], lit[k] + ((m.diffuse * m.color[k]) * light->color[k]) * ndl, add);
        pk_i spec = add & (m.specular > 0.0f);
        if (!pk_any(spec)) continue;
        pk_f R[3];
        for (int k = 0; k < 3; k++) R[k] = (2.0f * ndl) * sf->ns[k] - Ln[k];
        pk_f rv = -pk_dot3(R, dn); /* R . V with V = -dn */
        spec &= rv > 0.0f;
        if (!pk_any(spec)) continue;
        int sh[RT_PK_LANES], most = 0;
        pk_vstore(select((pk_i)0, m.shininess, spec), 0, sh);
        for (int l = 0; l < RT_PK_LANES; l++) most = sh[l] > most ? sh[l] : most;
        pk_f pw = (pk_f)1.0f;
        for (int i = 0; i < most; i++) pw = select(pw, pw * rv, (pk_i)i < m.shininess);
        for (int k = 0; k < 3; k++)
            lit[k] = select(lit[k], lit[k] + (m.specular * light->color[k]) * pw, spec);
    }
    /* rt_shade_end: the term (w * lw) * lit, added to 0 */
    for (int k = 0; k < 3; k++) rgb[k] = select(rgb[k], 0.0f + (one * lw) * lit[k], lighting);
}

/* The lanes' hits and counters as scalars (rt_hit_d, rt_counters). */
static void pk_unpack(const pk_state *st, rt_hit_d *hit, rt_counters *c) {
    float ht[RT_PK_LANES], hu[RT_PK_LANES], hv[RT_PK_LANES];
    uint hprim[RT_PK_LANES], hinst[RT_PK_LANES], hentry[RT_PK_LANES];
    int cbox[RT_PK_LANES], ctri[RT_PK_LANES], crays[RT_PK_LANES];
    pk_vstore(st->t, 0, ht);
    pk_vstore(st->u, 0, hu);
    pk_vstore(st->v, 0, hv);
    pk_vstore(st->prim, 0, hprim);
    pk_vstore(st->inst, 0, hinst);
    pk_vstore(st->entry, 0, hentry);
    pk_vstore(st->boxes, 0, cbox);
    pk_vstore(st->tris, 0, ctri);
    pk_vstore(st->rays, 0, crays);
    for (int l = 0; l < RT_PK_LANES; l++) {
        hit[l].t = ht[l];
        hit[l].u = hu[l];
        hit[l].v = hv[l];
        hit[l].prim = hprim[l];
        hit[l].inst = hinst[l];
        hit[l].entry = hentry[l];
        c[l].box_tests = (rt_u32)cbox[l];
        c[l].tri_tests = (rt_u32)ctri[l];
        c[l].rays = (rt_u32)crays[l];
    }
}

/* ---- the kernels ----------------------------------------------------------- */

/* Blocks first .. first + count - 1 of the image (PK_W x PK_H pixels each,
 * row-major over the image, partial at the right and bottom edges): primary
 * rays, closest hits, then the image (the primary hits shaded in vectors,
 * their shadow rays as packets; with secondary rays, each lane's reflection
 * and refraction subtrees one ray at a time) or an AOV into fb (channels
 * floats per pixel,
 * the whole frame), as rt_k_camera + rt_k_trace + rt_k_shade would.
 * counters[i] gets the block's rays and tests (the host only adds them up:
 * a block's sum is 1/16 of the bytes to read back). */
__kernel void rt_k_packet(RT_VIEW_ARGS, uint first, uint count, int aov, int channels,
                          __global rt_counters *counters, __global float *fb, __global uint *done) {
    uint i = (uint)get_global_id(0);
    if (i >= count || RT_K_SKIPPED(i)) return;
    rt_scene_view s = RT_VIEW_INIT;
    const int w = hdr->width, h = hdr->height;
    const uint bw = ((uint)w + PK_W - 1u) / PK_W, block = first + i;
    const int x0 = (int)(block % bw) * PK_W, y0 = (int)(block / bw) * PK_H;

    /* rt_camera_ray per lane, its screen coordinates once per column and
     * row of the block. Lanes outside the image trace a copy of an inside
     * pixel's ray, inactive. */
    float sx[PK_W], sy[PK_H];
    for (int i = 0; i < PK_W; i++) sx[i] = rt_camera_sx(hdr, x0 + i < w ? x0 + i : w - 1);
    for (int j = 0; j < PK_H; j++) sy[j] = rt_camera_sy(hdr, y0 + j < h ? y0 + j : h - 1);
    rt_ray ray[RT_PK_LANES];
    int in_image[RT_PK_LANES];
    for (int l = 0; l < RT_PK_LANES; l++) {
        in_image[l] = x0 + l % PK_W < w && y0 + l / PK_W < h;
        rt_camera_ray_at(hdr, sx[l % PK_W], sy[l / PK_W], &ray[l]);
    }
    pk_i active = pk_vload(0, in_image) != 0;
    pk_ray p;
    pk_load(ray, &p);
    pk_state st;
    st.boxes = st.tris = st.rays = (pk_i)0;
    pk_trace(&s, &p, active, 0, (pk_u)0xffffffffu, &st);

    rt_hit_d hit[RT_PK_LANES];
    rt_counters c[RT_PK_LANES];
    pk_unpack(&st, hit, c);

    if (aov == AOV_DEPTH || aov == AOV_PRIMID || aov == AOV_INSTID || aov == AOV_NORMAL) {
        /* As rt_k_shade (rt_cpu_finish_pixel). */
        for (int l = 0; l < RT_PK_LANES; l++) {
            if (!in_image[l]) continue;
            __global float *out =
                fb + ((size_t)(y0 + l / PK_W) * (size_t)w + (size_t)(x0 + l % PK_W)) * channels;
            int hit_any = hit[l].prim != RT_NO_HIT;
            if (aov == AOV_DEPTH) {
                out[0] = hit_any ? hit[l].t : INFINITY;
            } else if (aov == AOV_PRIMID) {
                out[0] = hit_any ? (float)hit[l].prim : -1.0f;
            } else if (aov == AOV_INSTID) {
                out[0] = hit_any ? (float)hit[l].inst : -1.0f;
            } else {
                out[0] = out[1] = out[2] = 0.0f;
                if (hit_any) {
                    rt_surface sf;
                    rt_surface_at(&s, &ray[l], &hit[l], &sf);
                    for (int k = 0; k < 3; k++) out[k] = sf.ns[k];
                }
            }
        }
    } else {
        float rgb[RT_PK_LANES][3];
        /* The root nodes in vectors (pk_shade_root); the pixel where the
         * scene has no secondary rays. */
        pk_f col[3], dn[3], lit[3], lw;
        pk_i hitm, sb = (pk_i)0, stt = (pk_i)0, srays = (pk_i)0;
        pk_surf sf;
        pk_shade_root(&s, &p, &st, active, col, &sb, &stt, &srays, &hitm, &sf, dn, lit, &lw);
        float cc[3][RT_PK_LANES];
        int b0[RT_PK_LANES], t0[RT_PK_LANES], r0[RT_PK_LANES];
        for (int k = 0; k < 3; k++) pk_vstore(col[k], 0, cc[k]);
        pk_vstore(sb, 0, b0);
        pk_vstore(stt, 0, t0);
        pk_vstore(srays, 0, r0);
        for (int l = 0; l < RT_PK_LANES; l++) {
            for (int k = 0; k < 3; k++) rgb[l][k] = cc[k][l];
            c[l].box_tests += (rt_u32)b0[l];
            c[l].tri_tests += (rt_u32)t0[l];
            c[l].rays += (rt_u32)r0[l];
        }
        if ((RT_SCENE_FLAGS(&s) & RT_SCENE_SECONDARY) && pk_any(hitm)) {
            /* rt_shade_end per lane on the root's halves (rt_shade_node from
             * the vectors' lanes) for its secondary rays, then the lane's
             * subtrees one ray at a time (rt_shade_children), added after
             * the root's term as in rt_shade_hit. */
            rt_shade_node nd;
            int hm[RT_PK_LANES], fr[RT_PK_LANES];
            float v[16][RT_PK_LANES];
            uint mt[RT_PK_LANES];
            pk_vstore(hitm, 0, hm);
            pk_vstore(sf.front, 0, fr);
            pk_vstore(sf.material, 0, mt);
            for (int k = 0; k < 3; k++) {
                pk_vstore(sf.p[k], 0, v[k]);
                pk_vstore(sf.ng[k], 0, v[3 + k]);
                pk_vstore(sf.ns[k], 0, v[6 + k]);
                pk_vstore(dn[k], 0, v[9 + k]);
                pk_vstore(lit[k], 0, v[12 + k]);
            }
            pk_vstore(lw, 0, v[15]);
            for (int l = 0; l < RT_PK_LANES; l++) {
                if (!hm[l]) continue;
                for (int k = 0; k < 3; k++) {
                    nd.sf.p[k] = v[k][l];
                    nd.sf.ng[k] = v[3 + k][l];
                    nd.sf.ns[k] = v[6 + k][l];
                    nd.dn[k] = v[9 + k][l];
                    nd.lit[k] = v[12 + k][l];
                }
                nd.sf.front = fr[l] != 0;
                nd.sf.material = mt[l];
                nd.lw = v[15][l];
                rt_shade_entry root, child[2];
                root.ray = ray[l];
                root.w[0] = root.w[1] = root.w[2] = 1.0f;
                root.depth = 0;
                float term[3];
                int has_term, children;
                rt_shade_end(&s, &root, &hit[l], &nd, term, &has_term, child, &children);
                rt_shade_children(&s, child, children, &c[l], rgb[l]);
            }
        }
        for (int l = 0; l < RT_PK_LANES; l++) {
            if (!in_image[l]) continue;
            __global float *out =
                fb + ((size_t)(y0 + l / PK_W) * (size_t)w + (size_t)(x0 + l % PK_W)) * channels;
            if (aov == AOV_NONE)
                for (int k = 0; k < 3; k++) out[k] = rgb[l][k];
            else
                out[0] = (float)(aov == AOV_BOX_TESTS ? c[l].box_tests : c[l].tri_tests);
        }
    }
    rt_counters sum = {0, 0, 0};
    for (int l = 0; l < RT_PK_LANES; l++) {
        if (!in_image[l]) continue;
        sum.box_tests += c[l].box_tests;
        sum.tri_tests += c[l].tri_tests;
        sum.rays += c[l].rays;
    }
    counters[i] = sum;
    RT_K_DONE(done, PACKET, i);
}

/* Ray queries, closest hit: rays RT_PK_LANES * i .. + RT_PK_LANES - 1 of
 * count as one packet (the last one partial), as rt_k_trace would answer
 * each; counters[j] gets ray j's tests (counted per lane). */
__kernel void rt_k_packet_trace(RT_VIEW_ARGS, uint count, __global const rt_ray *rays,
                                __global rt_hit_d *hits, __global rt_counters *counters,
                                uint masked, __global const uint *masks, __global uint *done) {
    uint i = (uint)get_global_id(0);
    uint first = i * RT_PK_LANES;
    if (first >= count || RT_K_SKIPPED(i)) return;
    rt_scene_view s = RT_VIEW_INIT;
    rt_ray r[RT_PK_LANES];
    int inside[RT_PK_LANES];
    uint m[RT_PK_LANES];
    for (int l = 0; l < RT_PK_LANES; l++) {
        inside[l] = first + (uint)l < count;
        r[l] = rays[inside[l] ? first + (uint)l : first]; /* outside: a copy, inactive */
        m[l] = masked && inside[l] ? masks[first + (uint)l] : 0xffffffffu;
    }
    pk_ray p;
    pk_load(r, &p);
    pk_state st;
    st.boxes = st.tris = st.rays = (pk_i)0;
    pk_trace(&s, &p, pk_vload(0, inside) != 0, 0, pk_vload(0, m), &st);
    rt_hit_d hit[RT_PK_LANES];
    rt_counters c[RT_PK_LANES];
    pk_unpack(&st, hit, c);
    for (int l = 0; l < RT_PK_LANES; l++) {
        if (!inside[l]) continue;
        hits[first + l] = hit[l];
        counters[first + l] = c[l];
    }
    RT_K_DONE(done, PTRACE, i);
}
