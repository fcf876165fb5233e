/* rt_shared.h - the one source of the ray tracing maths: ray/box and
 * ray/triangle tests, single- and two-level BVH traversal (closest hit and
 * any hit), the camera, surface offsets and Whitted shading.
 *
 * Valid C99 and valid OpenCL C. The CPU oracle (cpu_ref/), the packet path and
 * the OpenCL kernels include it, so they evaluate the same operations in the
 * same order and get the same bits. Rules that keep it so:
 * - only + - * /, sqrt, comparisons, fabs (division as RT_DIV and square
 *   root as RT_SQRT: correctly rounded in every profile but the OpenCL
 *   study build with -DRT_NATIVE_MATH); minimum and maximum written as
 *   comparisons (so NaN handling is spelled out); integer powers by repeated
 *   multiplication; no vector operators; no recursion, no function pointers,
 *   no allocation; no double anywhere;
 * - C builds with -ffp-contract=off and without fast-math; OpenCL builds with
 *   '#pragma OPENCL FP_CONTRACT OFF', without the options -cl-mad-enable or
 *   fast-relaxed maths.
 *
 * Two maths profiles give the same bits (docs/PORTABLE_MATH.md):
 * - native: the device's division and sqrt, built with
 *   -cl-fp32-correctly-rounded-divide-sqrt; only where the device promises
 *   them correctly rounded (the C oracle: IEEE hardware);
 * - portable (-DRT_PORTABLE_MATH): division and sqrt in software from 32-bit
 *   integer operations (rt_soft_math.h), for devices whose division and
 *   sqrt may be off by ulps (OpenCL allows 2.5 and 3, Vulkan 2.5).
 * Denormals: -DRT_FLUSH_DENORMALS (OpenCL, with -cl-denorms-are-zero) picks
 * the flush-to-zero variants of the software functions; the C oracle follows
 * its thread's mode (rt_fp_mode.h), which the CPU backends set.
 * - the evaluation order of every sum is written out (a + b + c is (a + b) + c).
 *
 * Closest hit has a total order: smaller t wins; equal t goes to the lower
 * instance, then the lower triangle index. The hit then does not depend on
 * traversal order, node layout or thread count. [tmin, tmax] is inclusive; the
 * direction is not normalised and t is in units of its length.
 */
#ifndef RT_SHARED_H
#define RT_SHARED_H

#include "rt_layout.h"

#include "rt_soft_math.h"

#ifdef RT_OPENCL
#define RT_GLOBAL __global
#define RT_FN
#if defined(RT_PORTABLE_MATH) && defined(RT_NATIVE_MATH)
#error "RT_PORTABLE_MATH and RT_NATIVE_MATH exclude each other"
#endif
#if defined(RT_PORTABLE_MATH) && defined(RT_FLUSH_DENORMALS)
#define RT_DIV(a, b) rt_soft_div_ftz((a), (b))
#define RT_SQRT(x)   rt_soft_sqrt_ftz(x)
#elif defined(RT_PORTABLE_MATH)
#define RT_DIV(a, b) rt_soft_div((a), (b))
#define RT_SQRT(x)   rt_soft_sqrt(x)
#elif defined(RT_NATIVE_MATH)
/* Only for the speed-versus-error study (bench/study_opencl_options.sh): the
 * device's own, faster division and square root, whose error the
 * implementation defines. Never in a build that claims the oracle's bits. */
#define RT_DIV(a, b) native_divide((a), (b))
#define RT_SQRT(x)   native_sqrt(x)
#else
#define RT_DIV(a, b) ((a) / (b))
#define RT_SQRT(x)   sqrt(x)
#endif
#ifdef RT_FLUSH_DENORMALS
#define RT_DOP(a, b, c, d) rt_soft_diff_of_products_ftz((a), (b), (c), (d))
#else
#define RT_DOP(a, b, c, d) rt_soft_diff_of_products((a), (b), (c), (d))
#endif
#define RT_FABS(x)     fabs(x)
#define RT_AS_INT(x)   as_int(x)
#define RT_AS_FLOAT(x) as_float(x)
#define RT_INF         INFINITY
#else
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "rt_fp_mode.h"
#define RT_GLOBAL
#define RT_FN          static inline
#define RT_DIV(a, b)   ((a) / (b))
#define RT_SQRT(x)     sqrtf(x)
#define RT_FABS(x)     fabsf(x)
#define RT_AS_INT(x)   rt_as_int_(x)
#define RT_AS_FLOAT(x) rt_as_float_(x)
#define RT_INF         INFINITY
/* The hardware's division and sqrt flush when the thread's mode does; the
 * integer-only difference of products follows that mode explicitly. */
#define RT_DOP(a, b, c, d)                                                                         \
    (rt_fp_flushing() ? rt_soft_diff_of_products_ftz((a), (b), (c), (d))                           \
                      : rt_soft_diff_of_products((a), (b), (c), (d)))
static inline rt_i32 rt_as_int_(float f) {
    rt_i32 i;
    memcpy(&i, &f, sizeof i);
    return i;
}
static inline float rt_as_float_(rt_i32 i) {
    float f;
    memcpy(&f, &i, sizeof f);
    return f;
}
#endif

#define RT_NO_HIT 0xffffffffu

/* Feature switches. By default the header and instance flags are read at run
 * time. An OpenCL kernel specialised to a scene is compiled with
 * -DRT_STATIC_FLAGS=<header flags> (and RT_STATIC_INST_SET / _MASK, and
 * RT_STATIC_TRI_METHOD), so unused paths (secondary rays, instance transforms,
 * normal interpolation) fold away. The values are those of the scene being
 * rendered, so the result is the same either way. */
#ifdef RT_STATIC_FLAGS
#define RT_SCENE_FLAGS(s) (RT_STATIC_FLAGS)
#define RT_INST_FLAGS(in) ((((in)->flags) | (RT_STATIC_INST_SET)) & (RT_STATIC_INST_MASK))
#else
#define RT_SCENE_FLAGS(s) ((s)->hdr->flags)
#define RT_INST_FLAGS(in) ((in)->flags)
#endif
#ifdef RT_STATIC_TRI_METHOD
#define RT_TRI_METHOD(s) (RT_STATIC_TRI_METHOD)
#else
#define RT_TRI_METHOD(s) ((s)->hdr->tri_method)
#endif

/* Traversal stack entries; host/flatten.c rejects deeper trees. */
#define RT_STACK_SIZE 64

/* Ize 2013: the far slab distance times 1 + 2 gamma(3), gamma(n) =
 * n eps / (1 - n eps), eps = 2^-24, makes the float slab test conservative.
 * 1 + 2 gamma(3) = 1 + 3.58e-7 is rounded up to 1 + 4 * 2^-23. */
#define RT_BOX_FAR_SCALE 1.000000476837158203125f
/* The same margin for a far distance below zero (a ray range with negative
 * t): there the far end must grow towards zero, 1 - 4 * 2^-23. Without it a
 * flat box behind the origin was culled (tests/robust, grazing rays). */
#define RT_BOX_FAR_SCALE_NEG 0.999999523162841796875f

/* The t range a box is tested against is widened by this relative margin:
 * a triangle test's t has rounding errors of its own, and a hit is accepted
 * only where its t passes its triangle's box test (rt_hit_accepted), so the
 * margin is also how far a t may fall before its box and still count. The
 * watertight test's t is off by up to ~1e-2 relative on large triangles
 * crossed near the origin (t error ~ eps |v - o| / |dir|): 2^-16 refused 5
 * of 30k random rays and 2 of 195k diffuse bounces on Sponza (light through
 * a wall), 2^-10 the bounces; 2^-6 none of 770k on Sponza and Sibenik. It
 * costs only boxes entered up to 1.6% beyond the best hit. */
#define RT_BOX_T_MARGIN 0.015625f /* 2^-6 */

/* Shadow rays run from the offset surface point (t = 0) to the light (t = 1),
 * excluding the light itself. */
#define RT_SHADOW_TMAX 0.999999940395355224609375f /* 1 - 2^-24 */

/* Shading stack: depth-first, each bounce pushes at most two rays, so
 * max_depth + 2 entries suffice; flatten caps max_depth at 8. */
#define RT_SHADE_STACK 12
#define RT_MAX_DEPTH   8

/* A ray o + t d, t in [tmin, tmax]: the public rt_ray of host/rt.h, defined
 * in both headers under one guard so that C code including both sees one
 * type (and the library passes the caller's rays to the backends as they
 * are); the layouts must stay equal. */
#ifndef RT_RAY_DEFINED
#define RT_RAY_DEFINED
typedef struct rt_ray {
    float org[3];
    float dir[3];
    float tmin;
    float tmax;
} rt_ray;
#endif

/* Per-ray values both tests reuse. */
typedef struct rt_ray_pre {
    float inv[3];   /* 1 / dir (inf for a zero component) */
    rt_i32 sign[3]; /* inv < 0 */
    rt_i32 kx, ky, kz;
    float sx, sy, sz; /* watertight shear */
    /* The entry distance of the ray's instance box (rt_inst_enter), -inf
     * outside an object BVH: a hit at t is accepted only where
     * inst_lo <= rt_box_hi(t) (rt_hit_accepted). */
    float inst_lo;
} rt_ray_pre;

typedef struct rt_hit_d {
    float t, u, v; /* p = (1 - u - v) v0 + u v1 + v v2 */
    rt_u32 prim;   /* triangle index in its mesh, RT_NO_HIT on a miss */
    rt_u32 inst;   /* instance index, RT_NO_HIT on a miss */
    rt_u32 entry;  /* index into the layout's tris (for shading) */
} rt_hit_d;

typedef struct rt_counters {
    rt_u32 box_tests;
    rt_u32 tri_tests;
    rt_u32 rays;
} rt_counters;

/* Everything a backend reads. In OpenCL each pointer is a kernel argument. */
typedef struct rt_scene_view {
    RT_GLOBAL const rt_scene_header *hdr;
    RT_GLOBAL const rt_node *nodes;
    RT_GLOBAL const rt_tri *tris;
    RT_GLOBAL const rt_u32 *tri_ids;
    RT_GLOBAL const float *tri_normals;
    RT_GLOBAL const rt_u32 *tri_mats;
    RT_GLOBAL const rt_instance *instances;
    RT_GLOBAL const rt_u32 *inst_ids;
    RT_GLOBAL const rt_material_d *materials;
    RT_GLOBAL const rt_light_d *lights;
    RT_GLOBAL const rt_kd_node *kd_nodes; /* kd-tree meshes (rt_kd.h) */
} rt_scene_view;

/* ---- small vector helpers (explicit order of operations) ---------------- */

RT_FN float rt_dot3(const float *a, const float *b) {
    return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

RT_FN void rt_cross3(const float *a, const float *b, float *out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

RT_FN void rt_normalize3(float *v) {
    float len = RT_SQRT(rt_dot3(v, v));
    if (len > 0.0f) {
        v[0] = RT_DIV(v[0], len);
        v[1] = RT_DIV(v[1], len);
        v[2] = RT_DIV(v[2], len);
    }
}

/* ---- rays ----------------------------------------------------------------- */

RT_FN void rt_ray_prepare(const rt_ray *r, rt_ray_pre *p) {
    for (int i = 0; i < 3; i++) {
        p->inv[i] = RT_DIV(1.0f, r->dir[i]);
        p->sign[i] = p->inv[i] < 0.0f;
    }
    /* Watertight test: kz is the axis where |dir| is largest. */
    float ax = RT_FABS(r->dir[0]), ay = RT_FABS(r->dir[1]), az = RT_FABS(r->dir[2]);
    rt_i32 kz = 0;
    if (ay > ax) kz = 1;
    if (az > (kz == 1 ? ay : ax)) kz = 2;
    rt_i32 kx = kz + 1 == 3 ? 0 : kz + 1;
    rt_i32 ky = kx + 1 == 3 ? 0 : kx + 1;
    if (r->dir[kz] < 0.0f) { /* keep the winding */
        rt_i32 tmp = kx;
        kx = ky;
        ky = tmp;
    }
    p->kx = kx;
    p->ky = ky;
    p->kz = kz;
    p->sx = RT_DIV(r->dir[kx], r->dir[kz]);
    p->sy = RT_DIV(r->dir[ky], r->dir[kz]);
    p->sz = p->inv[kz]; /* 1 / dir[kz], the same operation: one division less */
    p->inst_lo = -RT_INF;
}

/* The primary ray through the centre of pixel (px, py); see rt_layout.h. Its
 * screen coordinates depend on the column and the row alone, so a caller
 * with many pixels of one row or column may compute them once. */
RT_FN float rt_camera_sx(RT_GLOBAL const rt_scene_header *h, rt_i32 px) {
    return RT_DIV(2.0f * ((float)px + 0.5f), (float)h->width) - 1.0f;
}
RT_FN float rt_camera_sy(RT_GLOBAL const rt_scene_header *h, rt_i32 py) {
    return 1.0f - RT_DIV(2.0f * ((float)py + 0.5f), (float)h->height);
}
RT_FN void rt_camera_ray_at(RT_GLOBAL const rt_scene_header *h, float sx, float sy, rt_ray *r) {
    for (int i = 0; i < 3; i++) {
        r->org[i] = h->cam_pos[i];
        r->dir[i] = (h->cam_forward[i] + sx * h->cam_right[i]) + sy * h->cam_up[i];
    }
    r->tmin = 0.0f;
    r->tmax = RT_INF;
}
RT_FN void rt_camera_ray(RT_GLOBAL const rt_scene_header *h, rt_i32 px, rt_i32 py, rt_ray *r) {
    rt_camera_ray_at(h, rt_camera_sx(h, px), rt_camera_sy(h, py), r);
}

/* Waechter and Binder 2019 (Ray Tracing Gems, ch. 6): moves p off the surface
 * along n by a fixed number of ulps (256 |n|), which scales with p's magnitude;
 * near the origin, where ulps are tiny, by a fixed 2^-16 |n| instead.
 * n is a unit normal (the shading's are). For any other n (a ray file's
 * normal can be anything) a component beyond +-1 moves at most 256 ulps, a
 * NaN in n or p gives NaN, and the bit arithmetic is unsigned, so nothing is
 * undefined for any input (the float-to-int conversion was, for |n| >= 2^23
 * and infinities, and the add for -0 and large NaN payloads: found by
 * tests/fuzz/fuzz_rays). For unit normals and finite p the bits are those of
 * the plain signed formula. rt_packet.cl's pk_offset_point sees unit normals
 * and finite points only. */
RT_FN void rt_offset_point(const float *p, const float *n, float sign, float *out) {
    for (int i = 0; i < 3; i++) {
        float ni = sign * n[i];
        float s = 256.0f * ni;
        rt_i32 of = s >= 256.0f ? 256 : (s <= -256.0f ? -256 : (s == s ? (rt_i32)s : 0));
        float pi =
            RT_AS_FLOAT((rt_i32)((rt_u32)RT_AS_INT(p[i]) + (rt_u32)(p[i] < 0.0f ? -of : of)));
        out[i] = RT_FABS(p[i]) < 0.03125f ? p[i] + 0.0000152587890625f * ni
                                          : (s == s && p[i] == p[i] ? pi : p[i] + s);
    }
}

/* ---- ray/box: robust slab test (Ize 2013) --------------------------------- */

/* One slab of the test: the ray's distances to the planes a (entered) and b
 * (left) on axis i narrow [*lo, *hi]. Every box test is built from these two
 * steps, so that a box containing another never passes less (the rounding
 * is monotonic in a and b). */
RT_FN void rt_slab(float a, float b, float org, float inv, float *lo, float *hi) {
    float t0 = (a - org) * inv;
    float t1 = (b - org) * inv;
    *lo = t0 > *lo ? t0 : *lo;
    *hi = t1 < *hi ? t1 : *hi;
}

/* The end of the test: the far distance made conservative (Ize), cut at
 * tmax; *tnear is the entry distance. */
RT_FN int rt_slab_end(float lo, float hi, float tmax, float *tnear) {
    hi = hi * (hi < 0.0f ? RT_BOX_FAR_SCALE_NEG : RT_BOX_FAR_SCALE);
    hi = tmax < hi ? tmax : hi;
    *tnear = lo;
    return lo <= hi;
}

/* Tests the box [bmin, bmax] against [tmin, tmax]; *tnear is the entry
 * distance. A 0 * inf (origin on a slab plane, direction parallel to it)
 * gives NaN, which the comparisons skip, keeping the test conservative. */
RT_FN int rt_box_test_bounds(RT_GLOBAL const float *bmin, RT_GLOBAL const float *bmax,
                             const rt_ray *r, const rt_ray_pre *p, float tmin, float tmax,
                             float *tnear) {
    float lo = tmin, hi = RT_INF;
    for (int i = 0; i < 3; i++)
        rt_slab(p->sign[i] ? bmax[i] : bmin[i], p->sign[i] ? bmin[i] : bmax[i], r->org[i],
                p->inv[i], &lo, &hi);
    return rt_slab_end(lo, hi, tmax, tnear);
}

/* rt_box_test_bounds on a node's box. */
RT_FN int rt_box_test(RT_GLOBAL const rt_node *n, const rt_ray *r, const rt_ray_pre *p, float tmin,
                      float tmax, float *tnear) {
    return rt_box_test_bounds(n->bmin, n->bmax, r, p, tmin, tmax, tnear);
}

/* ---- ray/triangle tests --------------------------------------------------- */

/* Each returns 1 and sets t, u, v when the ray hits the triangle with t in
 * [tmin, tmax]. Both faces count. A ray in the triangle's plane and a
 * zero-area triangle give a zero determinant: a miss. */

/* Woop, Benthin and Wald 2013: shear and scale so the ray is the +z axis, then
 * 2D edge functions. Watertight: a ray through a shared edge or vertex hits at
 * least one of the triangles. Edge functions that come out exactly zero are
 * recomputed exactly (rt_edge_recheck). */
/* An edge function of exactly zero may be rounding (two equal products):
 * all three are recomputed as a*b - c*d with exact products, rounded once
 * (rt_soft_math.h: integer operations, no fp64, the same bits on every
 * device), as the paper does in double. Without this, sliver triangles of
 * scanned meshes report hits for rays that pass far from them. */
RT_FN void rt_edge_recheck(float Ax, float Ay, float Bx, float By, float Cx, float Cy, float *U,
                           float *V, float *W) {
    *U = RT_DOP(Cx, By, Cy, Bx);
    *V = RT_DOP(Ax, Cy, Ay, Cx);
    *W = RT_DOP(Bx, Ay, By, Ax);
}

RT_FN int rt_tri_watertight(RT_GLOBAL const rt_tri *tri, const rt_ray *r, const rt_ray_pre *p,
                            float tmin, float tmax, float *t, float *u, float *v) {
    float A[3], B[3], C[3];
    for (int i = 0; i < 3; i++) {
        A[i] = tri->v0[i] - r->org[i];
        B[i] = tri->v1[i] - r->org[i];
        C[i] = tri->v2[i] - r->org[i];
    }
    const rt_i32 kx = p->kx, ky = p->ky, kz = p->kz;
    float Ax = A[kx] - p->sx * A[kz], Ay = A[ky] - p->sy * A[kz];
    float Bx = B[kx] - p->sx * B[kz], By = B[ky] - p->sy * B[kz];
    float Cx = C[kx] - p->sx * C[kz], Cy = C[ky] - p->sy * C[kz];
    float U = Cx * By - Cy * Bx;
    float V = Ax * Cy - Ay * Cx;
    float W = Bx * Ay - By * Ax;
    if (U == 0.0f || V == 0.0f || W == 0.0f) rt_edge_recheck(Ax, Ay, Bx, By, Cx, Cy, &U, &V, &W);
    if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return 0;
    float det = (U + V) + W;
    if (det == 0.0f) return 0;
    float Az = p->sz * A[kz], Bz = p->sz * B[kz], Cz = p->sz * C[kz];
    float T = (U * Az + V * Bz) + W * Cz;
    float tt = RT_DIV(T, det);
    if (!(tt >= tmin && tt <= tmax)) return 0;
    *t = tt;
    *u = RT_DIV(V, det);
    *v = RT_DIV(W, det);
    return 1;
}

/* Moller and Trumbore 1997. */
RT_FN int rt_tri_moller(RT_GLOBAL const rt_tri *tri, const rt_ray *r, float tmin, float tmax,
                        float *t, float *u, float *v) {
    float e1[3], e2[3], s[3], pv[3], q[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = tri->v1[i] - tri->v0[i];
        e2[i] = tri->v2[i] - tri->v0[i];
        s[i] = r->org[i] - tri->v0[i];
    }
    rt_cross3(r->dir, e2, pv);
    float det = rt_dot3(e1, pv);
    if (det == 0.0f) return 0;
    float inv = RT_DIV(1.0f, det);
    float uu = rt_dot3(s, pv) * inv;
    if (!(uu >= 0.0f && uu <= 1.0f)) return 0;
    rt_cross3(s, e1, q);
    float vv = rt_dot3(r->dir, q) * inv;
    if (!(vv >= 0.0f && uu + vv <= 1.0f)) return 0;
    float tt = rt_dot3(e2, q) * inv;
    if (!(tt >= tmin && tt <= tmax)) return 0;
    *t = tt;
    *u = uu;
    *v = vv;
    return 1;
}

/* Signed volumes of the ray with each edge (the Pluecker inner products,
 * written as triple products of the vertices relative to the origin). */
RT_FN int rt_tri_pluecker(RT_GLOBAL const rt_tri *tri, const rt_ray *r, float tmin, float tmax,
                          float *t, float *u, float *v) {
    float a[3], b[3], c[3], bc[3], ca[3], ab[3];
    for (int i = 0; i < 3; i++) {
        a[i] = tri->v0[i] - r->org[i];
        b[i] = tri->v1[i] - r->org[i];
        c[i] = tri->v2[i] - r->org[i];
    }
    rt_cross3(b, c, bc);
    rt_cross3(c, a, ca);
    rt_cross3(a, b, ab);
    float U = rt_dot3(r->dir, bc), V = rt_dot3(r->dir, ca), W = rt_dot3(r->dir, ab);
    if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return 0;
    float det = (U + V) + W;
    if (det == 0.0f) return 0;
    float tt = RT_DIV(rt_dot3(a, bc), det);
    if (!(tt >= tmin && tt <= tmax)) return 0;
    *t = tt;
    *u = RT_DIV(V, det);
    *v = RT_DIV(W, det);
    return 1;
}

/* Badouel 1990 (Wald's projection variant): hit the plane, then a 2D
 * barycentric test in the projection that drops the normal's largest axis. */
RT_FN int rt_tri_badouel(RT_GLOBAL const rt_tri *tri, const rt_ray *r, float tmin, float tmax,
                         float *t, float *u, float *v) {
    float e1[3], e2[3], n[3], a[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = tri->v1[i] - tri->v0[i];
        e2[i] = tri->v2[i] - tri->v0[i];
        a[i] = tri->v0[i] - r->org[i];
    }
    rt_cross3(e1, e2, n);
    float nd = rt_dot3(n, r->dir);
    if (nd == 0.0f) return 0;
    float tt = RT_DIV(rt_dot3(n, a), nd);
    if (!(tt >= tmin && tt <= tmax)) return 0;
    float nx = RT_FABS(n[0]), ny = RT_FABS(n[1]), nz = RT_FABS(n[2]);
    rt_i32 k = 0;
    if (ny > nx) k = 1;
    if (nz > (k == 1 ? ny : nx)) k = 2;
    rt_i32 i1 = k == 0 ? 1 : 0, i2 = k == 2 ? 1 : 2;
    float p1 = (r->org[i1] + tt * r->dir[i1]) - tri->v0[i1];
    float p2 = (r->org[i2] + tt * r->dir[i2]) - tri->v0[i2];
    float det = e1[i1] * e2[i2] - e1[i2] * e2[i1];
    float uu = RT_DIV(p1 * e2[i2] - p2 * e2[i1], det);
    float vv = RT_DIV(e1[i1] * p2 - e1[i2] * p1, det);
    if (!(uu >= 0.0f && vv >= 0.0f && uu + vv <= 1.0f)) return 0;
    *t = tt;
    *u = uu;
    *v = vv;
    return 1;
}

/* The triangle test selected by method (RT_TRI_*). OpenCL kernels pass a
 * compile-time constant, so the switch folds away. */
RT_FN int rt_tri_test(rt_u32 method, RT_GLOBAL const rt_tri *tri, const rt_ray *r,
                      const rt_ray_pre *p, float tmin, float tmax, float *t, float *u, float *v) {
    if (method == RT_TRI_MOLLER) return rt_tri_moller(tri, r, tmin, tmax, t, u, v);
    if (method == RT_TRI_PLUECKER) return rt_tri_pluecker(tri, r, tmin, tmax, t, u, v);
    if (method == RT_TRI_BADOUEL) return rt_tri_badouel(tri, r, tmin, tmax, t, u, v);
    return rt_tri_watertight(tri, r, p, tmin, tmax, t, u, v);
}

/* ---- traversal ------------------------------------------------------------ */

/* The total order of hits: is (t, inst, prim) before the best so far? */
RT_FN int rt_hit_before(float t, rt_u32 inst, rt_u32 prim, const rt_hit_d *best) {
    if (t != best->t) return t < best->t;
    if (inst != best->inst) return inst < best->inst;
    return prim < best->prim;
}

RT_FN void rt_hit_init(rt_hit_d *h, const rt_ray *r) {
    h->t = r->tmax;
    h->u = 0.0f;
    h->v = 0.0f;
    h->prim = RT_NO_HIT;
    h->inst = RT_NO_HIT;
    h->entry = RT_NO_HIT;
}

/* The box range for a ray whose accepted t range is [tmin, tmax]. */
RT_FN float rt_box_lo(float tmin) {
    return tmin - RT_FABS(tmin) * RT_BOX_T_MARGIN;
}
RT_FN float rt_box_hi(float tmax) {
    return tmax + RT_FABS(tmax) * RT_BOX_T_MARGIN;
}

/* ---- hit acceptance -----------------------------------------------------
 *
 * A triangle test's t carries rounding errors that grow with the distance of
 * the triangle from the origin over |dir|; in the nasty cases (a tiny
 * direction, flushed denormals, a ray through a vertex) t lands far outside
 * the slabs of the triangle's own box. Which boxes a tree tests then decided
 * whether the hit was seen: a wide tree, a merged leaf or another traversal
 * order gave another answer. So a hit at t is accepted only where the box
 * test of its triangle's own box passes for the range
 * [rt_box_lo(tmin), rt_box_hi(t)], and, under an object BVH, that of its
 * instance's world box too. Every box of any tree above the triangle contains
 * these boxes and is tested with a range that reaches at least as far
 * (rt_box_hi(best t), best t >= t), and the slab test is monotonic in the
 * box: an accepted hit's boxes always pass, so the closest accepted hit is
 * the same whatever the tree, its width, its leaves or the order. */

/* The instance box's entry distance for the ray r in world space, into
 * p_obj->inst_lo; returns 0 when the ray misses the box at every t (the
 * instance then has no acceptable hit). */
RT_FN int rt_inst_enter(RT_GLOBAL const rt_instance *in, const rt_ray *r, const rt_ray_pre *p,
                        float *inst_lo) {
    return rt_box_test_bounds(in->bmin, in->bmax, r, p, rt_box_lo(r->tmin), RT_INF, inst_lo);
}

RT_FN float rt_min3(float a, float b, float c) {
    float m = a < b ? a : b;
    return c < m ? c : m;
}
RT_FN float rt_max3(float a, float b, float c) {
    float m = a > b ? a : b;
    return c > m ? c : m;
}

/* rt_hit_accepted for a triangle whose box is [mn, mx] (each the exact
 * min and max of its vertices' coordinates). */
RT_FN int rt_hit_accepted_box(const float *mn, const float *mx, const rt_ray *r,
                              const rt_ray_pre *p, float t) {
    /* The instance box passed for [lo, inf] (rt_inst_enter); cut at hi_t it
     * passes unless hi_t falls before its entry (a NaN hi_t cuts nothing, as
     * in rt_slab_end). */
    const float hi_t = rt_box_hi(t);
    if (hi_t < p->inst_lo) return 0;
    float lo = rt_box_lo(r->tmin), hi = RT_INF, tn;
    for (int i = 0; i < 3; i++)
        rt_slab(p->sign[i] ? mx[i] : mn[i], p->sign[i] ? mn[i] : mx[i], r->org[i], p->inv[i], &lo,
                &hi);
    return rt_slab_end(lo, hi, hi_t, &tn);
}

/* Whether a hit at t on tri (the ray r in the triangle's space, prepared as
 * p) is accepted: see above. */
RT_FN int rt_hit_accepted(RT_GLOBAL const rt_tri *tri, const rt_ray *r, const rt_ray_pre *p,
                          float t) {
    float mn[3], mx[3];
    for (int i = 0; i < 3; i++) {
        mn[i] = rt_min3(tri->v0[i], tri->v1[i], tri->v2[i]);
        mx[i] = rt_max3(tri->v0[i], tri->v1[i], tri->v2[i]);
    }
    return rt_hit_accepted_box(mn, mx, r, p, t);
}

/* Tests the triangles of one leaf; returns 1 when any_hit found one. */
RT_FN int rt_leaf_test(const rt_scene_view *s, rt_u32 first, rt_u32 count, rt_u32 inst,
                       const rt_ray *r, const rt_ray_pre *p, int any_hit, rt_hit_d *best,
                       rt_counters *c) {
    rt_u32 method = RT_TRI_METHOD(s);
    for (rt_u32 e = first; e < first + count; e++) {
        float t, u, v;
        c->tri_tests++;
        if (!rt_tri_test(method, &s->tris[e], r, p, r->tmin, best->t, &t, &u, &v)) continue;
        if (!rt_hit_accepted(&s->tris[e], r, p, t)) continue;
        rt_u32 prim = s->tri_ids[e];
        if (any_hit || rt_hit_before(t, inst, prim, best)) {
            best->t = t;
            best->u = u;
            best->v = v;
            best->prim = prim;
            best->inst = inst;
            best->entry = e;
            if (any_hit) return 1;
        }
    }
    return 0;
}

/* One inner-node step of a traversal, shared by both levels: tests the two
 * children, goes on with the nearer one that the ray hits and pushes the
 * other, or pops the stack. Returns 0 when the stack is empty. */
RT_FN int rt_descend(const rt_scene_view *s, RT_GLOBAL const rt_node *n, const rt_ray *r,
                     const rt_ray_pre *p, const rt_hit_d *best, rt_counters *c, rt_u32 *stack,
                     int *sp, rt_u32 *node) {
    float t0, t1, lo = rt_box_lo(r->tmin), hi = rt_box_hi(best->t);
    c->box_tests += 2;
    int h0 = rt_box_test(&s->nodes[n->a], r, p, lo, hi, &t0);
    int h1 = rt_box_test(&s->nodes[n->b], r, p, lo, hi, &t1);
    if (h0 && h1) {
        int right_first = t1 < t0;
        stack[(*sp)++] = right_first ? n->a : n->b;
        *node = right_first ? n->b : n->a;
    } else if (h0) {
        *node = n->a;
    } else if (h1) {
        *node = n->b;
    } else {
        if (*sp == 0) return 0;
        *node = stack[--*sp];
    }
    return 1;
}

#include "rt_kd.h" /* kd-tree meshes: rt_kd_trace_mesh */

/* Traverses one mesh BVH from node 'root' with a ray already in the mesh's
 * space. best->t is the current upper end of the range. Returns 1 when any_hit
 * found an occluder. */
RT_FN int rt_trace_mesh(const rt_scene_view *s, rt_u32 root, rt_u32 inst, const rt_ray *r,
                        const rt_ray_pre *p, int any_hit, rt_hit_d *best, rt_counters *c) {
    rt_u32 stack[RT_STACK_SIZE];
    int sp = 0;
    float tn;
    c->box_tests++;
    if (!rt_box_test(&s->nodes[root], r, p, rt_box_lo(r->tmin), rt_box_hi(best->t), &tn)) return 0;
    rt_u32 node = root;
    for (;;) {
        RT_GLOBAL const rt_node *n = &s->nodes[node];
        if (n->b & RT_NODE_LEAF_FLAG) {
            if (rt_leaf_test(s, n->a, n->b & RT_NODE_COUNT_MASK, inst, r, p, any_hit, best, c))
                return 1;
            if (sp == 0) return 0;
            node = stack[--sp];
            continue;
        }
        if (!rt_descend(s, n, r, p, best, c, stack, &sp, &node)) return 0;
    }
}

/* The ray in an instance's object space: o' = M o + m, d' = M d, with M the
 * inverse transform. t keeps its meaning because d' is not normalised. */
RT_FN void rt_ray_to_object(RT_GLOBAL const rt_instance *in, const rt_ray *r, rt_ray *o) {
    RT_GLOBAL const float *m = in->world_to_object;
    for (int i = 0; i < 3; i++) {
        o->org[i] = ((m[4 * i] * r->org[0] + m[4 * i + 1] * r->org[1]) + m[4 * i + 2] * r->org[2]) +
                    m[4 * i + 3];
        o->dir[i] = (m[4 * i] * r->dir[0] + m[4 * i + 1] * r->dir[1]) + m[4 * i + 2] * r->dir[2];
    }
    o->tmin = r->tmin;
    o->tmax = r->tmax;
}

/* Traces one instance: transforms the ray unless the instance is the
 * identity. */
RT_FN int rt_trace_instance(const rt_scene_view *s, rt_u32 inst, const rt_ray *r,
                            const rt_ray_pre *p, int any_hit, rt_hit_d *best, rt_counters *c) {
    RT_GLOBAL const rt_instance *in = &s->instances[inst];
    int kd = (RT_INST_FLAGS(in) & RT_INST_KD) != 0;
    float inst_lo = -RT_INF;
    if (!(RT_SCENE_FLAGS(s) & RT_SCENE_SINGLE) && !rt_inst_enter(in, r, p, &inst_lo)) return 0;
    rt_ray o;
    rt_ray_pre op;
    if (RT_INST_FLAGS(in) & RT_INST_IDENTITY) {
        op = *p;
        op.inst_lo = inst_lo;
        return kd ? rt_kd_trace_mesh(s, in->root, inst, r, &op, any_hit, best, c)
                  : rt_trace_mesh(s, in->root, inst, r, &op, any_hit, best, c);
    }
    rt_ray_to_object(in, r, &o);
    rt_ray_prepare(&o, &op);
    op.inst_lo = inst_lo;
    return kd ? rt_kd_trace_mesh(s, in->root, inst, &o, &op, any_hit, best, c)
              : rt_trace_mesh(s, in->root, inst, &o, &op, any_hit, best, c);
}

/* The two-level traversal (Langr 2016, section 3.2.1): the object BVH, then
 * each reached instance's mesh BVH. With one identity instance the object BVH
 * is skipped. Returns 1 on a hit (for any_hit: some hit in range). */
RT_FN int rt_trace(const rt_scene_view *s, const rt_ray *r, int any_hit, rt_hit_d *best,
                   rt_counters *c) {
    rt_ray_pre p;
    rt_ray_prepare(r, &p);
    rt_hit_init(best, r);
    c->rays++;
    if (s->hdr->instance_count == 0) return 0;
    if (RT_SCENE_FLAGS(s) & RT_SCENE_SINGLE) {
        rt_trace_instance(s, 0, r, &p, any_hit, best, c);
        return best->prim != RT_NO_HIT;
    }
    rt_u32 stack[RT_STACK_SIZE];
    int sp = 0;
    float tn;
    rt_u32 node = s->hdr->top_root;
    c->box_tests++;
    if (!rt_box_test(&s->nodes[node], r, &p, rt_box_lo(r->tmin), rt_box_hi(best->t), &tn)) return 0;
    for (;;) {
        RT_GLOBAL const rt_node *n = &s->nodes[node];
        if (n->b & RT_NODE_LEAF_FLAG) {
            rt_u32 count = n->b & RT_NODE_COUNT_MASK;
            for (rt_u32 e = n->a; e < n->a + count; e++)
                if (rt_trace_instance(s, s->inst_ids[e], r, &p, any_hit, best, c)) return 1;
            if (sp == 0) break;
            node = stack[--sp];
            continue;
        }
        if (!rt_descend(s, n, r, &p, best, c, stack, &sp, &node)) break;
    }
    return best->prim != RT_NO_HIT;
}

#endif /* RT_SHARED_H */
