/* SPDX-License-Identifier: Apache-2.0 */
/* rt_hit.h - hits: the hit record and test counters, the total order of
 * hits, which hits are accepted, and the test of one leaf's triangles that
 * both traversals (rt_bvh.h, rt_kd.h) call.
 *
 * Closest hit has a total order: smaller t wins; equal t goes to the lower
 * instance, then the lower triangle index. The hit then does not depend on
 * traversal order, node layout or thread count. Valid C99 and OpenCL C
 * (rt_math_profile.h); the GLSL mirror is kernels/vulkan/rt_vk_hit.glsl. */
#ifndef RT_KERNELS_HIT_H
#define RT_KERNELS_HIT_H

#include "rt_box.h"
#include "rt_tri.h"
#include "rt_view.h"

#define RT_NO_HIT 0xffffffffu

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
 * the same whatever the tree, its width, its leaves or the order.
 *
 * The rule never refuses a real crossing of the watertight test: a ray that
 * crosses the triangle at exact t* > 0 enters its box at an exact t <= t*,
 * which the float slab test overstates by at most 3 ulps, and the test's t
 * is at least t* (1 - 2^-17) (rt_tri_t.h), so rt_box_hi(t) >= t* (1 - 2^-17)
 * (1 + 2^-6) > t* (1 + 2^-7) lies beyond the computed entry (the instance
 * box the same). docs/ROBUSTNESS.md, "Accurate t", names where this bound's
 * assumptions end. */

/* The instance box's entry distance for the ray r in world space, into
 * p_obj->inst_lo; returns 0 when the ray misses the box at every t (the
 * instance then has no acceptable hit). */
RT_FN int rt_inst_enter(RT_GLOBAL const rt_instance *in, const rt_ray *r, const rt_ray_pre *p,
                        float *inst_lo) {
    return rt_box_test_bounds(in->bmin, in->bmax, r, p, rt_box_lo(r->tmin), RT_INF, inst_lo);
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

#endif /* RT_KERNELS_HIT_H */
