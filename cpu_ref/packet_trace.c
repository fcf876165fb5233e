/* SPDX-License-Identifier: Apache-2.0 */
/* packet_trace.c - RT_PK_LANES rays through the two-level BVH together
 * (packet_trace.h), in G groups of RT_VN lanes, one native vector each
 * (simd.h: 16 groups of 4 lanes with NEON or SSE2, 8 of 8 with AVX2, 4 of
 * 16 with AVX-512), over the layout's BVHs as four-wide nodes
 * (wide_bvh.h, rt_pk_shape).
 *
 * Until a node is narrower than the packet where the packet enters it, the
 * whole packet decides each node with one interval test over its four
 * children (pk_bvh_ia); below such nodes, and for packets whose signs differ, each group goes on
 * with its lanes' own box tests (pk_bvh_group); at a leaf each group's lanes that pass its box test
 * test the triangles, a group's lanes in one vector test
 * (watertight_lanes.h). Meshes with a
 * kd-tree (RT_INST_KD) are walked by each group in turn (packet_kd.h).
 *
 * Every vector operation below is the scalar oracle's operation on each lane
 * (kernels/rt_shared.h, named at each function), in the same order, so each
 * lane's values are the oracle's bits. Minimum and maximum are the oracle's
 * 'a < b ? a : b', NaN behaviour included (rt_vmin_of, rt_vmax_of).
 *
 * This file is compiled once per instruction set (cpu_isa.h: RT_ISA names
 * the build, and the run-time choice is made there); the builds differ in
 * register width only, never in results. */
#include <assert.h>
#include <string.h>

#include "cpu_isa.h"
#include "packet_trace.h"
#include "simd.h"
#include "watertight_lanes.h"

#define RT_PK_TRACE RT_ISA_SYMBOL(rt_pk_trace)

enum { L = RT_PK_LANES, N = RT_VN, G = RT_PK_LANES / RT_VN };
_Static_assert(RT_PK_LANES % RT_VN == 0, "a packet is whole vectors");

/* The packet's rays in one space: the world, or an instance's object space. */
typedef struct pk_geom {
    rt_vf org[3][G], dir[3][G], inv[3][G];
    rt_vi neg[3][G]; /* inv < 0 */
    rt_vf lo[G];     /* rt_box_lo(tmin) */
    rt_vf tmin[G];
    rt_vf sx[G], sy[G], sz[G]; /* the watertight shear ... */
    rt_vi kx0[G], kx1[G];      /* ... and its axes per lane: kx == 0, kx == 1 */
    rt_vi ky0[G], ky1[G], kz0[G], kz1[G];
    int perm[G][3];  /* kx, ky, kz when the group's lanes agree on them, else
                        perm[g][0] = -1 */
    int uniform;     /* all lanes share the sign of inv on every axis ... */
    int neg_axis[3]; /* ... and these are the signs */
    /* The packet's bounds for the interval test (pk_ia_children): the range
     * of every lane's org and inv per axis and the least rt_box_lo(tmin);
     * only when 'uniform' and all of them are finite (ia). One origin for
     * every lane (primary rays) makes the test cheaper and tighter. */
    int ia, one_origin;
    float org_min[3], org_max[3], inv_min[3], inv_max[3], lo_min;
    float org_span, dir_span; /* the largest range of org and of dir over the axes */
} pk_geom;

typedef struct pk_state {
    const rt_scene_view *s;
    const rt_wide_bvh *w;
    rt_vf t[G];  /* the best hit's t (the ray's tmax at first) */
    rt_vf hi[G]; /* rt_box_hi(t) */
    /* The best hit's edge functions (u = V / det, v = W / det once the
     * traversal is done, as the oracle divides) and its names. */
    rt_vf V[G], W[G], det[G];
    rt_vi prim[G], inst[G], entry[G];
    /* The instance being traced: the lanes whose ray meets its box and their
     * entry distances (rt_inst_enter), for rt_hit_accepted. */
    uint32_t inst_ok[G];
    rt_vf inst_lo[G];
    /* The lanes' ray masks (rt_trace_masked), when the caller gave them. */
    const uint32_t *masks;
    rt_vi box[G], tri[G]; /* tests per lane, when per_lane */
    int per_lane;         /* counts->per_lane */
    float hi_max;         /* the greatest of hi (for the interval test) ... */
    int hi_stale;         /* ... to be recomputed: some hit shortened hi */
    rt_pk_counts *counts;
    uint32_t alive[G];     /* lanes of each group still tracing */
    uint32_t alive_groups; /* groups with a lane alive */
    int any_hit;
    rt_u32 method;
} pk_state;

/* rt_box_hi per lane. */
static inline rt_vf box_hi(rt_vf t) {
    return t + rt_vabs(t) * rt_vsplat(RT_BOX_T_MARGIN);
}

/* Counts one test for each lane of m in group g. */
static inline void count(const pk_state *st, uint64_t *total, rt_vi *per_lane, int g, uint32_t m) {
    *total += rt_lane_count(m);
    if (st->per_lane) per_lane[g] -= rt_vmask(m);
}

/* ---- set-up --------------------------------------------------------------- */

/* rt_ray_prepare on every lane of group g. */
static void pk_prepare(pk_geom *p, int g) {
    const rt_vf *dir = (const rt_vf[3]){p->dir[0][g], p->dir[1][g], p->dir[2][g]};
    const rt_vf zero = rt_vsplat(0.0f), one = rt_vsplat(1.0f);
    for (int k = 0; k < 3; k++) {
        p->inv[k][g] = one / dir[k];
        p->neg[k][g] = p->inv[k][g] < zero;
    }
    /* kz: the axis of the largest |dir| (ties broken as rt_ray_prepare
     * breaks them); kx, ky the next two, swapped where dir[kz] < 0. */
    rt_vf ax = rt_vabs(dir[0]), ay = rt_vabs(dir[1]), az = rt_vabs(dir[2]);
    rt_vi m1 = ay > ax;
    rt_vi z2 = az > rt_vsel(m1, ay, ax);
    rt_vi z1 = m1 & ~z2, z0 = ~m1 & ~z2;
    rt_vf dz = rt_vsel(z2, dir[2], rt_vsel(z1, dir[1], dir[0]));
    /* Unswapped, kx = kz + 1 and ky = kz + 2 (mod 3). */
    rt_vi ux0 = z2, ux1 = z0, uy0 = z1, uy1 = z2;
    rt_vf dx = rt_vsel(ux0, dir[0], rt_vsel(ux1, dir[1], dir[2]));
    rt_vf dy = rt_vsel(uy0, dir[0], rt_vsel(uy1, dir[1], dir[2]));
    rt_vi swap = dz < zero;
    p->kx0[g] = (swap & uy0) | (~swap & ux0);
    p->kx1[g] = (swap & uy1) | (~swap & ux1);
    p->ky0[g] = (swap & ux0) | (~swap & uy0);
    p->ky1[g] = (swap & ux1) | (~swap & uy1);
    p->kz0[g] = z0;
    p->kz1[g] = z1;
    p->sx[g] = rt_vsel(swap, dy, dx) / dz;
    p->sy[g] = rt_vsel(swap, dx, dy) / dz;
    p->sz[g] = one / dz;
    /* One permutation for the whole group? */
    const uint32_t all = (1u << N) - 1u;
    uint32_t b[6] = {rt_vbits(p->kx0[g]), rt_vbits(p->kx1[g]), rt_vbits(p->ky0[g]),
                     rt_vbits(p->ky1[g]), rt_vbits(p->kz0[g]), rt_vbits(p->kz1[g])};
    int same = 1;
    for (int i = 0; i < 6; i++) same &= b[i] == 0 || b[i] == all;
    p->perm[g][0] = !same ? -1 : b[0] ? 0 : b[1] ? 1 : 2;
    p->perm[g][1] = b[2] ? 0 : b[3] ? 1 : 2;
    p->perm[g][2] = b[4] ? 0 : b[5] ? 1 : 2;
}

/* The rest of the set-up once org, dir and tmin are in place: rt_ray_prepare
 * per lane, the box range's lower ends, the signs and the interval bounds. */
static void pk_geom_finish(pk_geom *p) {
    rt_pk_mask neg_bits[3] = {0, 0, 0};
    for (int g = 0; g < G; g++) {
        p->lo[g] = p->tmin[g] - rt_vabs(p->tmin[g]) * rt_vsplat(RT_BOX_T_MARGIN);
        pk_prepare(p, g);
        for (int k = 0; k < 3; k++) neg_bits[k] |= (rt_pk_mask)rt_vbits(p->neg[k][g]) << (N * g);
    }
    p->uniform = 1;
    for (int k = 0; k < 3; k++) {
        p->neg_axis[k] = neg_bits[k] != 0;
        if (neg_bits[k] != 0 && neg_bits[k] != RT_PK_ALL) p->uniform = 0;
    }
    p->ia = p->uniform;
    if (!p->ia) return;
    /* The ranges, lane by lane of the vectors' minima and maxima. */
    rt_vf lo = p->lo[0], fin = rt_vsplat(0.0f);
    rt_vf omin[3], omax[3], imin[3], imax[3];
    for (int k = 0; k < 3; k++) omin[k] = omax[k] = p->org[k][0], imin[k] = imax[k] = p->inv[k][0];
    for (int g = 0; g < G; g++) {
        lo = rt_vmin_of(p->lo[g], lo);
        fin = fin + p->lo[g] * rt_vsplat(0.0f); /* NaN where lo is not finite */
        for (int k = 0; k < 3; k++) {
            omin[k] = rt_vmin_of(p->org[k][g], omin[k]),
            omax[k] = rt_vmax_of(p->org[k][g], omax[k]);
            imin[k] = rt_vmin_of(p->inv[k][g], imin[k]),
            imax[k] = rt_vmax_of(p->inv[k][g], imax[k]);
            fin = fin + (p->org[k][g] + p->inv[k][g]) * rt_vsplat(0.0f);
        }
    }
    /* An infinite or NaN org, inv or lo makes fin NaN: no bounds then. */
    if (rt_vbits(fin == fin) != (1u << N) - 1u) {
        p->ia = 0;
        return;
    }
    p->one_origin = 1;
    p->org_span = p->dir_span = 0.0f;
    for (int k = 0; k < 3; k++) {
        rt_vf dmin = p->dir[k][0], dmax = p->dir[k][0];
        for (int g = 1; g < G; g++)
            dmin = rt_vmin_of(p->dir[k][g], dmin), dmax = rt_vmax_of(p->dir[k][g], dmax);
        float d = rt_vhmax(dmax) - rt_vhmin(dmin);
        p->dir_span = d > p->dir_span ? d : p->dir_span;
    }
    p->lo_min = rt_vhmin(lo);
    for (int k = 0; k < 3; k++) {
        p->org_min[k] = rt_vhmin(omin[k]), p->org_max[k] = rt_vhmax(omax[k]);
        p->inv_min[k] = rt_vhmin(imin[k]), p->inv_max[k] = rt_vhmax(imax[k]);
        p->one_origin &= p->org_min[k] == p->org_max[k];
        float o = p->org_max[k] - p->org_min[k];
        p->org_span = o > p->org_span ? o : p->org_span;
    }
}

/* The packet's rays as vectors; invalid lanes take a valid lane's ray, so
 * that every lane computes on real numbers. */
static void pk_geom_setup(pk_geom *p, const rt_pk_rays *r, rt_pk_mask valid) {
    const int src = valid ? __builtin_ctzll(valid) : 0;
    for (int g = 0; g < G; g++) {
        const rt_vi in = rt_vmask((uint32_t)(valid >> (N * g)) & ((1u << N) - 1u));
        for (int k = 0; k < 3; k++) {
            rt_vf o, d;
            memcpy(&o, &r->org[k][N * g], sizeof o);
            memcpy(&d, &r->dir[k][N * g], sizeof d);
            p->org[k][g] = rt_vsel(in, o, rt_vsplat(r->org[k][src]));
            p->dir[k][g] = rt_vsel(in, d, rt_vsplat(r->dir[k][src]));
        }
        rt_vf t;
        memcpy(&t, &r->tmin[N * g], sizeof t);
        p->tmin[g] = rt_vsel(in, t, rt_vsplat(r->tmin[src]));
    }
    pk_geom_finish(p);
}

/* The world packet w in an instance's object space: rt_ray_to_object per
 * lane, o' = M o + m and d' = M d in its order of operations. */
static void pk_geom_to_object(pk_geom *o, const pk_geom *w, const rt_instance *in) {
    const float *m = in->world_to_object;
    for (int g = 0; g < G; g++) {
        for (int i = 0; i < 3; i++) {
            const rt_vf m0 = rt_vsplat(m[4 * i]), m1 = rt_vsplat(m[4 * i + 1]);
            const rt_vf m2 = rt_vsplat(m[4 * i + 2]), m3 = rt_vsplat(m[4 * i + 3]);
            o->org[i][g] = ((m0 * w->org[0][g] + m1 * w->org[1][g]) + m2 * w->org[2][g]) + m3;
            o->dir[i][g] = (m0 * w->dir[0][g] + m1 * w->dir[1][g]) + m2 * w->dir[2][g];
        }
        o->tmin[g] = w->tmin[g];
    }
    pk_geom_finish(o);
}

/* Lane i of group g as a ray (for the shared scalar tests; tmax unused). */
static void lane_ray(const pk_geom *p, int g, int i, rt_ray *r) {
    for (int k = 0; k < 3; k++) {
        r->org[k] = p->org[k][g][i];
        r->dir[k] = p->dir[k][g][i];
    }
    r->tmin = p->tmin[g][i];
    r->tmax = RT_INF;
}

/* One lane per child of a wide node. */
typedef RT_VF(RT_PK_WIDTH) ck_f;
typedef RT_VI(RT_PK_WIDTH) ck_i;
#define ck_splat RT_VOP(RT_PK_WIDTH, splat)
#define ck_min   RT_VOP(RT_PK_WIDTH, min_of)
#define ck_max   RT_VOP(RT_PK_WIDTH, max_of)
#define ck_bits  RT_VOP(RT_PK_WIDTH, bits)

/* The slots of n that hold a child. An empty slot's inverted box is missed
 * by every ray with numbers in it, but a NaN (a NaN ray, or 0 * inf where a
 * direction is infinite) passes any slab test, as it passes the oracle's:
 * the slot itself must never be entered (its ref is no node). */
static inline uint32_t real_children(const rt_pk_node *n) {
    uint32_t m = 0;
    for (int s = 0; s < RT_PK_WIDTH; s++) m |= (uint32_t)(n->ref[s] != RT_WIDE_EMPTY) << s;
    return m;
}

/* Interval arithmetic over the whole packet (Wald, Boulos and Shirley 2007),
 * for all children of a wide node at once: bit c is set unless no
 * lane's rt_box_test can pass for child c. Every lane computes t0 =
 * fl(fl(a - org) * inv) with its org and inv inside the packet's ranges;
 * rounding is monotonic and the product bilinear, so t0 is at least the
 * least product at the ranges' corners and its t1 at most the greatest. Its
 * entry (the greatest t0, and its rt_box_lo(tmin)) is then at least 'enter'
 * and its exit (the least t1, scaled as rt_box_test scales it, and its
 * rt_box_hi(t)) at most 'leave'. *enter_out gets 'enter' per child. Empty
 * slots (inverted boxes) come out infinitely far. */
static inline uint32_t pk_ia_children(const rt_pk_node *n, const pk_geom *p, float hi_max,
                                      ck_f *enter_out) {
    ck_f enter = ck_splat(p->lo_min), leave = ck_splat(RT_INF);
    for (int k = 0; k < 3; k++) {
        ck_f a, b, t0, t1;
        memcpy(&a, p->neg_axis[k] ? n->bmax[k] : n->bmin[k], sizeof a);
        memcpy(&b, p->neg_axis[k] ? n->bmin[k] : n->bmax[k], sizeof b);
        const ck_f i0 = ck_splat(p->inv_min[k]), i1 = ck_splat(p->inv_max[k]);
        if (p->one_origin) {
            const ck_f o = ck_splat(p->org_min[k]);
            a = a - o, b = b - o;
            t0 = ck_min(a * i0, a * i1);
            t1 = ck_max(b * i0, b * i1);
        } else {
            const ck_f o0 = ck_splat(p->org_max[k]), o1 = ck_splat(p->org_min[k]);
            const ck_f a0 = a - o0, a1 = a - o1, b0 = b - o0, b1 = b - o1;
            t0 = ck_min(ck_min(a0 * i0, a0 * i1), ck_min(a1 * i0, a1 * i1));
            t1 = ck_max(ck_max(b0 * i0, b0 * i1), ck_max(b1 * i0, b1 * i1));
        }
        enter = ck_max(enter, t0);
        leave = ck_min(leave, t1);
    }
    const ck_f zero = ck_splat(0.0f);
    const ck_f neg = ck_splat(RT_BOX_FAR_SCALE_NEG), pos = ck_splat(RT_BOX_FAR_SCALE);
    leave = leave * (ck_f)(((leave < zero) & (ck_i)neg) | (~(leave < zero) & (ck_i)pos));
    leave = ck_min(leave, ck_splat(hi_max));
    *enter_out = enter;
    return ck_bits(enter <= leave) & real_children(n);
}

/* ---- box test: rt_box_test on the lanes of group g ------------------------ */

/* rt_slab on the lanes of group g, axis k: the planes a (entered) and b
 * (left) narrow [*lo, *hi]. */
static inline void pk_slab(rt_vf a, rt_vf b, const pk_geom *p, int k, int g, rt_vf *lo, rt_vf *hi) {
    *lo = rt_vmax_of((a - p->org[k][g]) * p->inv[k][g], *lo);
    *hi = rt_vmin_of((b - p->org[k][g]) * p->inv[k][g], *hi);
}

/* The box [mn, mx] on axis k of group g: rt_slab with the planes ordered by
 * each lane's direction. */
static inline void pk_slab_box(float mn, float mx, const pk_geom *p, int k, int g, rt_vf *lo,
                               rt_vf *hi) {
    const rt_vf vmn = rt_vsplat(mn), vmx = rt_vsplat(mx);
    pk_slab(rt_vsel(p->neg[k][g], vmx, vmn), rt_vsel(p->neg[k][g], vmn, vmx), p, k, g, lo, hi);
}

/* rt_slab_end's far scale (Ize) per lane. */
static inline rt_vf pk_far(rt_vf hi) {
    return hi * rt_vsel(hi < rt_vsplat(0.0f), rt_vsplat(RT_BOX_FAR_SCALE_NEG),
                        rt_vsplat(RT_BOX_FAR_SCALE));
}

static inline uint32_t pk_box(const rt_pk_node *n, int c, const pk_geom *p, const pk_state *st,
                              int g, rt_vf *tnear) {
    rt_vf lo = p->lo[g], hi = rt_vsplat(RT_INF);
    for (int k = 0; k < 3; k++) {
        if (p->uniform) /* every lane enters at the same plane: no select */
            pk_slab(rt_vsplat(p->neg_axis[k] ? n->bmax[k][c] : n->bmin[k][c]),
                    rt_vsplat(p->neg_axis[k] ? n->bmin[k][c] : n->bmax[k][c]), p, k, g, &lo, &hi);
        else
            pk_slab_box(n->bmin[k][c], n->bmax[k][c], p, k, g, &lo, &hi);
    }
    hi = rt_vmin_of(st->hi[g], pk_far(hi));
    *tnear = lo;
    return rt_vbits(lo <= hi) & st->alive[g];
}

/* ---- triangles -------------------------------------------------------------- */

/* The greatest of hi (hi only shrinks, so a stale value is merely loose). */
static inline float hi_max(pk_state *st) {
    if (st->hi_stale) {
        /* A NaN hi (tmax NaN or -inf: rt_box_hi(-inf) = -inf + inf) limits
         * nothing in the oracle's box test ('tmax < hi ? tmax : hi' keeps
         * the box's hi): it counts as +inf here, or one such lane would cull
         * every node for the whole packet. */
        const rt_vf inf = rt_vsplat(RT_INF);
        rt_vf m = rt_vsplat(-RT_INF);
        for (int g = 0; g < G; g++)
            m = rt_vmax_of(rt_vsel(st->hi[g] == st->hi[g], st->hi[g], inf), m);
        float x = m[0];
        for (int i = 1; i < N; i++) x = m[i] > x ? m[i] : x;
        st->hi_max = x;
        st->hi_stale = 0;
    }
    return st->hi_max;
}

/* Retires the any-hit lanes of m in group g (they found an occluder). */
static inline void retire(pk_state *st, int g, uint32_t m, rt_u32 prim) {
    st->prim[g] = rt_vsel_i(rt_vmask(m), rt_vsplat_i((int32_t)prim), st->prim[g]);
    st->alive[g] &= ~m;
    if (!st->alive[g]) st->alive_groups &= ~(1u << g);
}

/* rt_hit_before for lane i of group g: is (t, inst, prim) before its best
 * hit, whose t is t (a tie)? */
static inline int tie_before(const pk_state *st, int g, int i, rt_u32 inst, rt_u32 prim) {
    rt_u32 best_inst = (rt_u32)st->inst[g][i], best_prim = (rt_u32)st->prim[g][i];
    if (inst != best_inst) return inst < best_inst;
    return prim < best_prim;
}

/* Records lane i of group g's hit on entry e at t with edge functions V, W
 * and det (u = V / det, v = W / det), as rt_leaf_test accepts it. */
static void accept_lane(pk_state *st, int g, int i, rt_u32 e, rt_u32 inst, float t, float V,
                        float W, float det) {
    st->t[g][i] = t;
    st->hi[g][i] = rt_box_hi(t);
    st->V[g][i] = V;
    st->W[g][i] = W;
    st->det[g][i] = det;
    st->prim[g][i] = (int32_t)st->s->tri_ids[e];
    st->inst[g][i] = (int32_t)inst;
    st->entry[g][i] = (int32_t)e;
    st->hi_stale = 1;
}

/* rt_hit_accepted on the lanes of group g for their hits at t on tri: the
 * lanes in the instance's box whose t lies in the slabs of tri's box. */
static inline uint32_t pk_hit_accepted(const pk_state *st, const pk_geom *p, int g,
                                       const rt_tri *tri, rt_vf t) {
    const rt_vf hi_t = box_hi(t);
    rt_vf lo = p->lo[g], hi = rt_vsplat(RT_INF);
    for (int k = 0; k < 3; k++)
        pk_slab_box(rt_min3(tri->v0[k], tri->v1[k], tri->v2[k]),
                    rt_max3(tri->v0[k], tri->v1[k], tri->v2[k]), p, k, g, &lo, &hi);
    hi = rt_vmin_of(hi_t, pk_far(hi));
    return rt_vbits((lo <= hi) & ~(hi_t < st->inst_lo[g])) & st->inst_ok[g];
}

/* The lanes of m in group g through the shared scalar test (rt_leaf_test's
 * body): the other triangle tests, and lanes that need the watertight test's
 * exact re-check of a zero edge function. */
static void pk_tri_lanes(pk_state *st, const pk_geom *p, int g, uint32_t m, rt_u32 e, rt_u32 inst) {
    const rt_tri *tri = &st->s->tris[e];
    const rt_u32 prim = st->s->tri_ids[e];
    for (m &= st->inst_ok[g]; m; m &= m - 1) {
        const int i = rt_lane_first(m);
        rt_ray lr;
        lane_ray(p, g, i, &lr);
        const rt_ray *r = &lr;
        rt_ray_pre pre;
        float t, u, v;
        rt_ray_prepare(r, &pre);
        pre.inst_lo = st->inst_lo[g][i];
        if (!rt_tri_test(st->method, tri, r, &pre, r->tmin, st->t[g][i], &t, &u, &v)) continue;
        if (!rt_hit_accepted(tri, r, &pre, t)) continue;
        if (st->any_hit)
            retire(st, g, 1u << i, prim);
        else if (t < st->t[g][i] || tie_before(st, g, i, inst, prim))
            accept_lane(st, g, i, e, inst, t, u, v, 1.0f); /* u / 1 and v / 1 are u and v */
    }
}

/* v[k] per lane, k given by the masks k0 (k == 0) and k1 (k == 1). */
static inline rt_vf pick(rt_vi k0, rt_vi k1, const rt_vf *v) {
    return rt_vsel(k0, v[0], rt_vsel(k1, v[1], v[2]));
}

/* rt_tri_t_plane's first tier (the plane in float, within its bound) for
 * the lanes of un in group g, in vectors: the triangle's part once
 * (rt_tri_t_normal), each lane's by the oracle's operations in its order.
 * Sets those lanes' t and returns the lanes the tier did not settle, which
 * take the whole scalar function. Most lanes past the fast bound end here
 * (large triangles near the origin), and the scalar function's dependent
 * chains cost far more time per lane than its instruction count says. */
static uint32_t pk_plane_tier1(const rt_tri *tri, int ip, const float *n, const float *m,
                               const pk_geom *p, int g, uint32_t un, rt_vf *t) {
    const float *v = RT_TRI_VERTEX(tri, ip); /* the apex, a vertex of its own (rt_tri_t.h) */
    rt_vf a[3], nv[3], mv[3], d[3];
    for (int i = 0; i < 3; i++) {
        a[i] = rt_vsplat(v[i]) - p->org[i][g];
        nv[i] = rt_vsplat(n[i]);
        mv[i] = rt_vsplat(m[i]);
        d[i] = p->dir[i][g];
    }
    return rt_vwt_plane1(a, nv, mv, d, un, t);
}

/* rt_ff_* of rt_tri_t.h per lane, the same operations in the same order. */
static inline rt_vf pk_ff_sum_err(rt_vf a, rt_vf b, rt_vf s) {
    const rt_vf bv = s - a;
    const rt_vf av = s - bv;
    return (a - av) + (b - bv);
}
static inline void pk_ff_split(rt_vf a, rt_vf *hi, rt_vf *lo) {
    const rt_vf c = rt_vsplat(4097.0f) * a;
    const rt_vf h = c - (c - a);
    *hi = h;
    *lo = a - h;
}
static inline void pk_ff_mul(rt_vf a, rt_vf alo, rt_vf as, rt_vf al2, rt_vf b, rt_vf blo, rt_vf bs,
                             rt_vf bl2, rt_vf *ph, rt_vf *pl) {
    const rt_vf x = a * b;
    const rt_vf e = ((((as * bs - x) + as * bl2) + al2 * bs) + al2 * bl2) + (a * blo + alo * b);
    const rt_vf h = x + e;
    *ph = h;
    *pl = e - (h - x);
}
static inline void pk_ff_add(rt_vf ah, rt_vf al, rt_vf bh, rt_vf bl, rt_vf *sh, rt_vf *sl) {
    const rt_vf s0 = ah + bh;
    const rt_vf e0 = pk_ff_sum_err(ah, bh, s0) + (al + bl);
    *sh = s0 + e0;
    *sl = pk_ff_sum_err(s0, e0, *sh);
}

/* rt_tri_t_plane's second tier (float-float) for the lanes of un in group
 * g, in vectors: the triangle's float-float normal once
 * (rt_tri_t_normal_ff), each lane's part by the oracle's operations in its
 * order; the rare lanes whose result is not finite take the scalar function
 * (its fallback to the fast t). Returns those lanes. */
static uint32_t pk_plane_tier2(const rt_tri *tri, int ip, const float *e, const float *f,
                               const pk_geom *p, int g, uint32_t un, rt_vf *t) {
    float nh[3], nl[3];
    rt_tri_t_normal_ff(tri, ip, e, f, nh, nl);
    const float *v = RT_TRI_VERTEX(tri, ip);
    rt_vf a[3], al[3], as[3], at[3], ds[3], dt[3];
    for (int i = 0; i < 3; i++) {
        const rt_vf vp = rt_vsplat(v[i]), mo = -p->org[i][g];
        a[i] = vp - p->org[i][g];
        al[i] = pk_ff_sum_err(vp, mo, a[i]);
        pk_ff_split(a[i], &as[i], &at[i]);
        pk_ff_split(p->dir[i][g], &ds[i], &dt[i]);
    }
    const rt_vf zero = rt_vsplat(0.0f);
    rt_vf Nh = zero, Nl = zero, Dh = zero, Dl = zero;
    for (int i = 0; i < 3; i++) {
        float ns, nt;
        rt_ff_split(nh[i], &ns, &nt);
        const rt_vf h = rt_vsplat(nh[i]), l = rt_vsplat(nl[i]), hs = rt_vsplat(ns),
                    ht = rt_vsplat(nt);
        rt_vf ph, pl;
        pk_ff_mul(h, l, hs, ht, a[i], al[i], as[i], at[i], &ph, &pl);
        pk_ff_add(Nh, Nl, ph, pl, &Nh, &Nl);
        pk_ff_mul(h, l, hs, ht, p->dir[i][g], zero, ds[i], dt[i], &ph, &pl);
        pk_ff_add(Dh, Dl, ph, pl, &Dh, &Dl);
    }
    const rt_vf t2 = Nh / Dh;
    const uint32_t good = rt_vbits(t2 - t2 == zero) & un;
    *t = rt_vsel(rt_vmask(good), t2, *t);
    return un & ~good;
}

/* rt_tri_watertight on the lanes of m in group g against entry e. */
static void pk_tri(pk_state *st, const pk_geom *p, int g, uint32_t m, rt_u32 e, rt_u32 inst) {
    st->counts->group_tri_tests++;
    count(st, &st->counts->tri_tests, st->tri, g, m);
    if (st->method != RT_TRI_WATERTIGHT) {
        pk_tri_lanes(st, p, g, m, e, inst);
        return;
    }
    const rt_tri *tri = &st->s->tris[e];
    /* The oracle's A[i] = v0[i] - org[i] (and B, C), taken at kx, ky, kz. */
    rt_vf A[3], B[3], C[3];
    const int kx = p->perm[g][0], ky = p->perm[g][1], kz = p->perm[g][2];
    if (kx >= 0) {
        const rt_vf ox = p->org[kx][g], oy = p->org[ky][g], oz = p->org[kz][g];
        A[0] = rt_vsplat(tri->v0[kx]) - ox, A[1] = rt_vsplat(tri->v0[ky]) - oy;
        A[2] = rt_vsplat(tri->v0[kz]) - oz;
        B[0] = rt_vsplat(tri->v1[kx]) - ox, B[1] = rt_vsplat(tri->v1[ky]) - oy;
        B[2] = rt_vsplat(tri->v1[kz]) - oz;
        C[0] = rt_vsplat(tri->v2[kx]) - ox, C[1] = rt_vsplat(tri->v2[ky]) - oy;
        C[2] = rt_vsplat(tri->v2[kz]) - oz;
    } else { /* lanes disagree on the axes: each picks its own */
        rt_vf a[3], b[3], c[3];
        for (int k = 0; k < 3; k++) {
            a[k] = rt_vsplat(tri->v0[k]) - p->org[k][g];
            b[k] = rt_vsplat(tri->v1[k]) - p->org[k][g];
            c[k] = rt_vsplat(tri->v2[k]) - p->org[k][g];
        }
        const rt_vi x0 = p->kx0[g], x1 = p->kx1[g], y0 = p->ky0[g], y1 = p->ky1[g];
        const rt_vi z0 = p->kz0[g], z1 = p->kz1[g];
        A[0] = pick(x0, x1, a), A[1] = pick(y0, y1, a), A[2] = pick(z0, z1, a);
        B[0] = pick(x0, x1, b), B[1] = pick(y0, y1, b), B[2] = pick(z0, z1, b);
        C[0] = pick(x0, x1, c), C[1] = pick(y0, y1, c), C[2] = pick(z0, z1, c);
    }
    rt_vwt x;
    /* An edge function of exactly zero takes the oracle's exact re-check. */
    const uint32_t z = rt_vwt_edges(A, B, C, p->sx[g], p->sy[g], &x) & m;
    if (z) {
        pk_tri_lanes(st, p, g, z, e, inst);
        m &= ~z;
    }
    uint32_t inside = rt_vwt_inside(&x, m);
    if (!inside) return;
    rt_vf t = rt_vwt_t(&x, p->sz[g]);
    /* A t that the oracle takes from the plane (rt_tri_t.h): the shared
     * scalar function for those lanes (rare). */
    uint32_t before;
    uint32_t un =
        rt_vwt_unsure(&x, A, B, C, p->sx[g], p->sy[g], p->sz[g], p->tmin[g], inside, &before);
    inside &= ~before;
    if (un) {
        /* The triangle's part of both tiers, once. */
        const int ip = rt_tri_t_apex(tri);
        float te[3], tf[3], tn[3], tm[3];
        rt_tri_t_normal(tri, ip, te, tf, tn, tm);
        un = pk_plane_tier1(tri, ip, tn, tm, p, g, un, &t);
        if (un) un = pk_plane_tier2(tri, ip, te, tf, p, g, un, &t);
    }
    for (; un; un &= un - 1) {
        const int i = rt_lane_first(un);
        rt_ray lr;
        lane_ray(p, g, i, &lr);
        t[i] = rt_tri_t_plane(tri, &lr, t[i]);
    }
    uint32_t hit = rt_vbits((t >= p->tmin[g]) & (t <= st->t[g])) & inside;
    if (!hit) return;
    hit &= pk_hit_accepted(st, p, g, tri, t);
    if (!hit) return;
    const rt_u32 prim = st->s->tri_ids[e];
    if (st->any_hit) {
        retire(st, g, hit, prim);
        return;
    }
    /* rt_hit_before: a smaller t wins at once; an equal t goes by the names. */
    uint32_t closer = rt_vbits(t < st->t[g]) & hit;
    for (uint32_t tie = hit & ~closer; tie; tie &= tie - 1) {
        int i = rt_lane_first(tie);
        if (tie_before(st, g, i, inst, prim)) closer |= 1u << i;
    }
    if (!closer) return;
    const rt_vi take = rt_vmask(closer);
    st->t[g] = rt_vsel(take, t, st->t[g]);
    st->hi[g] = rt_vsel(take, box_hi(t), st->hi[g]);
    st->V[g] = rt_vsel(take, x.V, st->V[g]);
    st->W[g] = rt_vsel(take, x.W, st->W[g]);
    st->det[g] = rt_vsel(take, x.det, st->det[g]);
    st->prim[g] = rt_vsel_i(take, rt_vsplat_i((int32_t)prim), st->prim[g]);
    st->inst[g] = rt_vsel_i(take, rt_vsplat_i((int32_t)inst), st->inst[g]);
    st->entry[g] = rt_vsel_i(take, rt_vsplat_i((int32_t)e), st->entry[g]);
    st->hi_stale = 1;
}

/* The layout's entries [begin, end) for the lanes of m in group g, in
 * order (rt_leaf_test's loop): a BVH leaf or a kd-tree leaf. */
static void pk_leaf_range(pk_state *st, const pk_geom *p, rt_u32 begin, rt_u32 end, rt_u32 inst,
                          int g, uint32_t m) {
    for (rt_u32 e = begin; e < end && m; e++) {
        pk_tri(st, p, g, m, e, inst);
        m &= st->alive[g];
    }
}

/* The triangles of leaf child c of n for the lanes of m in group g. */
static void pk_leaf(pk_state *st, const pk_geom *p, const rt_pk_node *n, int c, rt_u32 inst, int g,
                    uint32_t m) {
    const rt_u32 begin = n->ref[c];
    pk_leaf_range(st, p, begin, begin + (n->count[c] & RT_NODE_COUNT_MASK), inst, g, m);
}

/* ---- traversal -------------------------------------------------------------- */

/* The node of child s of ch, read next (if nearest) or later: both of its
 * cache lines. */
static inline void prefetch_child(const rt_pk_node *nodes, const rt_pk_node *ch, int s) {
    if (ch->count[s] & RT_NODE_LEAF_FLAG) return;
    __builtin_prefetch(&nodes[ch->ref[s]]);
    __builtin_prefetch((const char *)&nodes[ch->ref[s]] + 64);
}

/* The traversal stacks below hold the entered siblings of the nodes on the
 * path from the entry node: at most RT_PK_WIDTH - 1 per wide level. Only
 * real children are ever entered (real_children: a NaN lane passes every
 * slab test, an empty slot's included), so the path follows the wide tree,
 * whose levels are at most the binary tree's (each wide node collapses one
 * binary level or more) plus the entry node, which has one child and pushes
 * nothing; host/layout/flatten.c rejects binary trees deeper than
 * RT_STACK_SIZE. Hence (RT_PK_WIDTH - 1) * RT_STACK_SIZE + 1 entries suffice
 * for any ray, NaN and infinite ones included (asserted in debug builds). */

/* A set of groups: bit g is group g. */
typedef uint32_t pk_groups;

static void pk_instance(pk_state *st, const pk_geom *world, rt_u32 inst, pk_groups gm);

/* Counts the box tests of lanes m of group g, n_boxes of them each. */
static inline void count_boxes(pk_state *st, int g, uint32_t m, int n_boxes) {
    st->counts->group_box_tests += (uint64_t)n_boxes;
    st->counts->box_tests += (uint64_t)n_boxes * rt_lane_count(m);
    if (st->per_lane) st->box[g] -= rt_vmask(m) * n_boxes;
}

/* Group g's lanes through the tree below child 'slot' of node 'entry' (a
 * mesh's, inst its instance, or the object BVH's, inst == RT_NO_HIT):
 * rt_trace_mesh's and rt_trace's loops with each lane's own box tests, the
 * children of a wide node all tested without a branch (an empty slot's
 * inverted box is missed by every lane) by the lanes that entered it,
 * entered children nearest first (by the entry distance of the first lane
 * that enters; the order changes speed, never the hits). A pushed child
 * goes on, when popped, with the lanes whose entry distance is still inside
 * their range (hits found since may have shortened it): the others would
 * fail its box test now, and the oracle's culling relies on that losing
 * nothing. */
static void pk_bvh_group(pk_state *st, const pk_geom *p, rt_u32 entry, int slot, rt_u32 inst,
                         int g) {
    typedef struct {
        rt_vf tnear;
        rt_u32 node;
        int slot;
        uint32_t mask;
    } item;
    const rt_pk_node *nodes = (const rt_pk_node *)st->w->nodes;
    item stack[(RT_PK_WIDTH - 1) * RT_STACK_SIZE + 1];
    int sp = 0;
    item cur = {rt_vsplat(0.0f), entry, slot, st->alive[g]};
    count_boxes(st, g, cur.mask, 1);
    cur.mask &= pk_box(&nodes[entry], slot, p, st, g, &cur.tnear);
    while (cur.mask) {
        const rt_pk_node *n = &nodes[cur.node];
        const int c = cur.slot;
        if (n->count[c] & RT_NODE_LEAF_FLAG) {
            if (inst != RT_NO_HIT) {
                pk_leaf(st, p, n, c, inst, g, cur.mask);
            } else {
                const rt_u32 end = n->ref[c] + (n->count[c] & RT_NODE_COUNT_MASK);
                for (rt_u32 e = n->ref[c]; e < end && st->alive[g]; e++)
                    pk_instance(st, p, st->s->inst_ids[e], 1u << g);
            }
            if (!st->alive[g]) return;
        } else {
            const rt_u32 child = n->ref[c];
            const rt_pk_node *ch = &nodes[child];
            const uint32_t lanes = cur.mask & st->alive[g];
            uint32_t ms[RT_PK_WIDTH], entered = 0;
            rt_vf ts[RT_PK_WIDTH];
            int kids = 0;
            for (int s = 0; s < RT_PK_WIDTH; s++) {
                const int real = ch->ref[s] != RT_WIDE_EMPTY;
                kids += real;
                ms[s] = real ? pk_box(ch, s, p, st, g, &ts[s]) & lanes : 0u;
                entered |= (uint32_t)(ms[s] != 0) << s;
            }
            count_boxes(st, g, lanes, kids);
            item hit[RT_PK_WIDTH];
            float key[RT_PK_WIDTH];
            int hits = 0;
            for (; entered; entered &= entered - 1) {
                const int s = rt_lane_first(entered);
                prefetch_child(nodes, ch, s);
                const float k = ts[s][rt_lane_first(ms[s])];
                int i = hits++;
                while (i > 0 && key[i - 1] > k) {
                    hit[i] = hit[i - 1];
                    key[i] = key[i - 1];
                    i--;
                }
                hit[i] = (item){ts[s], child, s, ms[s]};
                key[i] = k;
            }
            if (hits) {
                assert(sp + hits - 1 <= (int)(sizeof stack / sizeof stack[0]));
                for (int i = hits - 1; i > 0; i--) stack[sp++] = hit[i];
                cur = hit[0];
                continue;
            }
        }
        cur.mask = 0;
        while (!cur.mask && sp > 0) {
            cur = stack[--sp];
            /* The lanes whose box test could still pass (a NaN hi limits
             * nothing, as in rt_box_test). */
            cur.mask &= st->alive[g] & ~rt_vbits(cur.tnear > st->hi[g]);
        }
    }
}

/* Leaf child c of n for the alive lanes of the groups of gm: each group's
 * lanes that pass its box test test its triangles (or, in the object BVH,
 * its instances). */
static void pk_leaf_all(pk_state *st, const pk_geom *p, const rt_pk_node *n, int c, rt_u32 inst,
                        pk_groups gm) {
    if (inst == RT_NO_HIT) {
        const rt_u32 end = n->ref[c] + (n->count[c] & RT_NODE_COUNT_MASK);
        for (rt_u32 e = n->ref[c]; e < end && (st->alive_groups & gm); e++)
            pk_instance(st, p, st->s->inst_ids[e], gm);
        return;
    }
    for (pk_groups todo = gm & st->alive_groups; todo; todo &= todo - 1) {
        const int g = rt_lane_first(todo);
        rt_vf tn;
        count_boxes(st, g, st->alive[g], 1);
        pk_leaf(st, p, n, c, inst, g, pk_box(n, c, p, st, g, &tn));
    }
}

/* The groups of gm through a BVH by the packet's bounds (p->ia): the
 * interval test over all children of a wide node at once stands for every
 * lane (it fails only when every lane's box test would), so the packet
 * decides each inner node with one test (Embree's coherent packets do the
 * like with frusta). Where the rays part ways, at a leaf or a node narrower
 * than the packet (narrower()), each group goes on with its lanes' own tests.
 * Either way a lane visits a superset of the nodes its scalar traversal
 * visits and gets the same hits. Children are taken nearest first by their
 * interval entry, and a pushed child whose entry lies beyond every lane's
 * range by the time it is popped is dropped. */
/* Does child c of n lie inside the packet's width where it enters it? The
 * rays are then bound to part ways inside the child: rather than take its
 * subtree by the packet's bounds, each group takes it with its own lanes
 * (pk_bvh_ia). The packet's width at distance t is at most org_span + t
 * dir_span on every axis; FOOTPRINT scales it (measured best about 2 for
 * every vector width on the shared scenes, docs/OPTIMISATION_LOG.md). Where
 * the packets switch changes speed only: either way is exact. */
enum { FOOTPRINT = 2 };
static inline int narrower(const rt_pk_node *n, int c, const pk_geom *p, float enter) {
    float e = 0.0f;
    for (int k = 0; k < 3; k++) {
        float d = n->bmax[k][c] - n->bmin[k][c];
        e = d > e ? d : e;
    }
    float t = enter > 0.0f ? enter : 0.0f;
    return e < (float)FOOTPRINT * (p->org_span + t * p->dir_span);
}

static void pk_bvh_ia(pk_state *st, const pk_geom *p, rt_u32 entry, rt_u32 inst, pk_groups gm) {
    typedef struct {
        float enter;
        rt_u32 node;
        int slot;
    } item;
    const rt_pk_node *nodes = (const rt_pk_node *)st->w->nodes;
    item stack[(RT_PK_WIDTH - 1) * RT_STACK_SIZE + 1];
    int sp = 0;
    ck_f en;
    st->counts->group_box_tests++;
    if (!(pk_ia_children(&nodes[entry], p, hi_max(st), &en) & 1u)) return;
    item cur = {en[0], entry, 0};
    for (;;) {
        const rt_pk_node *n = &nodes[cur.node];
        const int c = cur.slot;
        if (n->count[c] & RT_NODE_LEAF_FLAG) {
            pk_leaf_all(st, p, n, c, inst, gm);
        } else if (narrower(n, c, p, cur.enter)) {
            for (pk_groups todo = gm & st->alive_groups; todo; todo &= todo - 1)
                pk_bvh_group(st, p, cur.node, c, inst, rt_lane_first(todo));
        } else {
            const rt_u32 child = n->ref[c];
            const rt_pk_node *ch = &nodes[child];
            st->counts->group_box_tests += RT_PK_WIDTH;
            uint32_t entered = pk_ia_children(ch, p, hi_max(st), &en);
            item hit[RT_PK_WIDTH];
            int hits = 0;
            for (; entered; entered &= entered - 1) {
                const int s = rt_lane_first(entered);
                prefetch_child(nodes, ch, s);
                int i = hits++;
                while (i > 0 && hit[i - 1].enter > en[s]) {
                    hit[i] = hit[i - 1];
                    i--;
                }
                hit[i] = (item){en[s], child, s};
            }
            if (hits) {
                assert(sp + hits - 1 <= (int)(sizeof stack / sizeof stack[0]));
                for (int i = hits - 1; i > 0; i--) stack[sp++] = hit[i];
                cur = hit[0];
                continue;
            }
        }
        if (!(st->alive_groups & gm)) return;
        do {
            if (sp == 0) return;
            cur = stack[--sp];
        } while (cur.enter > hi_max(st));
    }
}

/* One BVH from its entry node for the groups of gm: by the packet's bounds
 * where they exist, else group by group. */
static void pk_bvh(pk_state *st, const pk_geom *p, rt_u32 entry, rt_u32 inst, pk_groups gm) {
    if (p->ia) {
        pk_bvh_ia(st, p, entry, inst, gm);
        return;
    }
    for (pk_groups todo = gm & st->alive_groups; todo; todo &= todo - 1)
        pk_bvh_group(st, p, entry, 0, inst, rt_lane_first(todo));
}

#include "packet_kd.h" /* pk_kd: kd-tree meshes, a group of lanes at a time */

/* rt_inst_enter on the lanes of the groups of gm (the world rays), into
 * st->inst_ok and st->inst_lo; returns the groups with a lane in the box. */
static pk_groups pk_inst_enter(pk_state *st, const pk_geom *p, const rt_instance *in,
                               pk_groups gm) {
    pk_groups out = 0;
    for (pk_groups todo = gm; todo; todo &= todo - 1) {
        const int g = rt_lane_first(todo);
        /* rt_trace_masked's mask test: the lanes whose mask shares a bit
         * with the instance's (without masks every lane's is 0xffffffff). */
        uint32_t lanes = in->mask ? (1u << N) - 1u : 0u;
        if (st->masks)
            lanes = rt_vbits((rt_vload_i(st->masks + N * g) & rt_vsplat_i((int32_t)in->mask)) !=
                             rt_vsplat_i(0));
        if (st->s->hdr->flags & RT_SCENE_SINGLE) {
            st->inst_lo[g] = rt_vsplat(-RT_INF);
            st->inst_ok[g] = lanes;
            if (lanes & st->alive[g]) out |= 1u << g;
            continue;
        }
        rt_vf lo = p->lo[g], hi = rt_vsplat(RT_INF);
        for (int k = 0; k < 3; k++) pk_slab_box(in->bmin[k], in->bmax[k], p, k, g, &lo, &hi);
        st->inst_lo[g] = lo;
        st->inst_ok[g] = rt_vbits(lo <= pk_far(hi)) & lanes;
        if (st->inst_ok[g] & st->alive[g]) out |= 1u << g;
    }
    return out;
}

/* One instance for the groups of gm: the same rays when it is the identity,
 * else each lane's ray moved into object space as rt_trace_instance moves
 * it. */
static void pk_instance(pk_state *st, const pk_geom *world, rt_u32 inst, pk_groups gm) {
    const rt_instance *in = &st->s->instances[inst];
    const rt_u32 entry = st->w->inst_root[inst];
    const int kd = (in->flags & RT_INST_KD) != 0;
    gm = pk_inst_enter(st, world, in, gm);
    if (!gm) return;
    if (in->flags & RT_INST_IDENTITY) {
        if (kd)
            pk_kd(st, world, in->root, inst, gm);
        else
            pk_bvh(st, world, entry, inst, gm);
        return;
    }
    pk_geom obj;
    pk_geom_to_object(&obj, world, in);
    if (kd)
        pk_kd(st, &obj, in->root, inst, gm);
    else
        pk_bvh(st, &obj, entry, inst, gm);
}

/* This build's entry point (rt_pk_tracer.trace). */
void RT_PK_TRACE(const rt_scene_view *s, const rt_wide_bvh *w, const rt_pk_rays *rays,
                 const uint32_t *masks, int any_hit, rt_pk_hits *hits, rt_pk_counts *counts);
void RT_PK_TRACE(const rt_scene_view *s, const rt_wide_bvh *w, const rt_pk_rays *rays,
                 const uint32_t *masks, int any_hit, rt_pk_hits *hits, rt_pk_counts *counts) {
    pk_state st;
    st.s = s;
    st.w = w;
    st.masks = masks;
    st.counts = counts;
    st.per_lane = counts->per_lane;
    st.any_hit = any_hit;
    st.method = s->hdr->tri_method;
    st.alive_groups = 0;
    st.hi_stale = 1;
    const rt_vi none = rt_vsplat_i((int32_t)RT_NO_HIT);
    for (int g = 0; g < G; g++) {
        st.box[g] = st.tri[g] = rt_vsplat_i(0);
        st.alive[g] = (uint32_t)(rays->valid >> (N * g)) & ((1u << N) - 1u);
        if (st.alive[g]) st.alive_groups |= 1u << g;
        st.prim[g] = st.inst[g] = st.entry[g] = none;
        st.V[g] = st.W[g] = rt_vsplat(0.0f);
        st.det[g] = rt_vsplat(1.0f);
        rt_vf tmax; /* rt_hit_init's t; no ray: a miss at infinity */
        memcpy(&tmax, &rays->tmax[N * g], sizeof tmax);
        st.t[g] = rt_vsel(rt_vmask(st.alive[g]), tmax, rt_vsplat(RT_INF));
        st.hi[g] = box_hi(st.t[g]);
        counts->rays += rt_lane_count(st.alive[g]);
    }
    const rt_pk_mask valid = rays->valid & RT_PK_ALL;
    if (st.alive_groups && s->hdr->instance_count != 0) {
        pk_geom world;
        pk_geom_setup(&world, rays, valid);
        if (s->hdr->flags & RT_SCENE_SINGLE)
            pk_instance(&st, &world, 0, st.alive_groups);
        else
            pk_bvh(&st, &world, w->top, RT_NO_HIT, st.alive_groups);
    }
    for (int g = 0; g < G; g++) {
        const rt_vi miss = st.prim[g] == none;
        const rt_vf u = rt_vsel(miss, rt_vsplat(0.0f), st.V[g] / st.det[g]);
        const rt_vf v = rt_vsel(miss, rt_vsplat(0.0f), st.W[g] / st.det[g]);
        memcpy(&hits->t[N * g], &st.t[g], sizeof(rt_vf));
        memcpy(&hits->u[N * g], &u, sizeof(rt_vf));
        memcpy(&hits->v[N * g], &v, sizeof(rt_vf));
        memcpy(&hits->prim[N * g], &st.prim[g], sizeof(rt_vi));
        memcpy(&hits->inst[N * g], &st.inst[g], sizeof(rt_vi));
        memcpy(&hits->entry[N * g], &st.entry[g], sizeof(rt_vi));
    }
    if (counts->per_lane)
        for (int l = 0; l < L; l++) {
            counts->c[l].rays += (rt_u32)((valid >> l) & 1u);
            counts->c[l].box_tests += (rt_u32)st.box[l / N][l % N];
            counts->c[l].tri_tests += (rt_u32)st.tri[l / N][l % N];
        }
}

extern const rt_pk_tracer RT_ISA_SYMBOL(rt_pk_tracer);
const rt_pk_tracer RT_ISA_SYMBOL(rt_pk_tracer) = {RT_VN, RT_PK_TRACE};
