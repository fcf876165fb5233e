/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_hit.glsl - the GLSL mirror of kernels/rt_hit.h: the hit record and
 * counters, the total order of hits, hit acceptance (rt_hit.h says why) and
 * the test of one leaf's triangles (resumable: rt_vk_resume.glsl). */
#ifndef RT_VK_HIT_GLSL
#define RT_VK_HIT_GLSL

#include "rt_vk_box.glsl"
#include "rt_vk_tri.glsl"

#define RT_NO_HIT 0xffffffffu

struct rt_hit_d {
    float t, u, v;
    uint prim;
    uint inst;
    uint entry;
};
struct rt_counters {
    uint box_tests;
    uint tri_tests;
    uint rays;
};

#include "rt_vk_resume.glsl" /* the stacks, the per-dispatch buffers, checkpoints */

bool rt_hit_before(float t, uint inst, uint prim, rt_hit_d best) {
    if (t != best.t) return t < best.t;
    if (inst != best.inst) return inst < best.inst;
    return prim < best.prim;
}

void rt_hit_init(out rt_hit_d h, rt_ray r) {
    h.t = r.tmax;
    h.u = 0.0;
    h.v = 0.0;
    h.prim = RT_NO_HIT;
    h.inst = RT_NO_HIT;
    h.entry = RT_NO_HIT;
}

bool rt_inst_enter(uint inst, rt_ray r, rt_ray_pre p, out float inst_lo) {
    float lo = rt_box_lo(r.tmin), hi = RT_INF;
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        float mn = instances[inst].bmin[i], mx = instances[inst].bmax[i];
        rt_slab(p.sign[i] != 0 ? mx : mn, p.sign[i] != 0 ? mn : mx, r.org[i], p.inv[i], lo, hi);
    }
    return rt_slab_end(lo, hi, RT_INF, inst_lo);
}

bool rt_hit_accepted(uint e, rt_ray r, rt_ray_pre p, float t) {
    float hi_t = rt_box_hi(t);
    if (hi_t < p.inst_lo) return false;
    float lo = rt_box_lo(r.tmin), hi = RT_INF, tn;
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        float mn = rt_min3(tris[e].v0[i], tris[e].v1[i], tris[e].v2[i]);
        float mx = rt_max3(tris[e].v0[i], tris[e].v1[i], tris[e].v2[i]);
        rt_slab(p.sign[i] != 0 ? mx : mn, p.sign[i] != 0 ? mn : mx, r.org[i], p.inv[i], lo, hi);
    }
    return rt_slab_end(lo, hi, hi_t, tn);
}

bool rt_leaf_test(uint first, uint count, uint inst, rt_ray r, rt_ray_pre p, bool any_hit,
                  inout rt_hit_d best, inout rt_counters c) {
    uint method = RT_TRI_METHOD();
    uint e0 = first;
    if (rt_vk_resuming) {
        /* Resumed inside this leaf: at the triangle it stopped before. */
        uint w = ST_LEAF;
        e0 = st_get(w);
        rt_vk_resuming = false;
    }
    for (uint e = e0; e < first + count; e++, RT_VK_TICK) {
        if (rt_vk_checkpoint()) {
            uint w = ST_LEAF;
            st_put(w, e);
            return false;
        }
        float t, u, v;
        c.tri_tests++;
        if (!rt_tri_test(method, e, r, p, r.tmin, best.t, t, u, v)) continue;
        if (!rt_hit_accepted(e, r, p, t)) continue;
        uint prim = tri_ids[e];
        if (any_hit || rt_hit_before(t, inst, prim, best)) {
            best.t = t;
            best.u = u;
            best.v = v;
            best.prim = prim;
            best.inst = inst;
            best.entry = e;
            if (any_hit) return true;
        }
    }
    return false;
}

#endif
