/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_trace.glsl - the GLSL mirror of kernels/rt_trace.h: the two-level
 * traversal over the object BVH, each instance's mesh by its BVH
 * (rt_vk_bvh.glsl) or its kd-tree (rt_vk_kd.glsl), resumable at every
 * level (rt_vk_resume.glsl). */
#ifndef RT_VK_TRACE_GLSL
#define RT_VK_TRACE_GLSL

#include "rt_vk_bvh.glsl"
#include "rt_vk_kd.glsl"

void rt_ray_to_object(uint inst, rt_ray r, out rt_ray o) {
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        float m0 = instances[inst].world_to_object[4 * i];
        float m1 = instances[inst].world_to_object[4 * i + 1];
        float m2 = instances[inst].world_to_object[4 * i + 2];
        float m3 = instances[inst].world_to_object[4 * i + 3];
        o.org[i] = ((m0 * r.org[0] + m1 * r.org[1]) + m2 * r.org[2]) + m3;
        o.dir[i] = (m0 * r.dir[0] + m1 * r.dir[1]) + m2 * r.dir[2];
    }
    o.tmin = r.tmin;
    o.tmax = r.tmax;
}

/* One call of rt_trace_mesh (and of rt_kd_trace_mesh) for both cases of the
 * C function (the ray transformed or not): one inlined copy of each
 * traversal; nothing when the instance's mask has no bit of ray_mask (as in
 * rt_trace.h). Keeps no state of its own: a resumed instance enters and
 * transforms the ray again (the same operations, the same bits, no counter)
 * and its mesh traversal loads its position. */
bool rt_trace_instance(uint inst, rt_ray r, rt_ray_pre p, uint ray_mask, bool any_hit,
                       inout rt_hit_d best, inout rt_counters c) {
    if ((ray_mask & instances[inst].mask) == 0u) return false;
    uint root = instances[inst].root;
    float inst_lo = -RT_INF;
    if ((RT_SCENE_FLAGS() & RT_SCENE_SINGLE) == 0u && !rt_inst_enter(inst, r, p, inst_lo))
        return false;
    rt_ray o = r;
    rt_ray_pre op = p;
    if ((RT_INST_FLAGS(instances[inst].flags) & RT_INST_IDENTITY) == 0u) {
        rt_ray_to_object(inst, r, o);
        rt_ray_prepare(o, op);
    }
    op.inst_lo = inst_lo;
    if ((RT_INST_FLAGS(instances[inst].flags) & RT_INST_KD) != 0u)
        return rt_kd_trace_mesh(root, inst, o, op, any_hit, best, c);
    return rt_trace_mesh(root, inst, o, op, any_hit, best, c);
}

/* The closest (or any) hit of r. Resumable (rt_vk_resume.glsl): the best
 * hit and the object BVH's position are ST_TOP's: at = 0 before a node,
 * 2 before instance e of the node's leaf, 1 inside it (the mesh's position
 * deeper down). A resumed trace prepares the ray again (the same
 * operations, the same bits) and counts neither the ray nor the root box
 * again. An instance whose mask has no bit of ray_mask is skipped where the
 * traversal reaches it (rt_trace_instance, as in rt_trace.h). */
bool rt_trace_masked(rt_ray r, uint ray_mask, bool any_hit, out rt_hit_d best,
                     inout rt_counters c) {
    rt_ray_pre p;
    rt_ray_prepare(r, p);
    rt_hit_init(best, r);
    uint w = ST_TOP;
    if (rt_vk_resuming) {
        st_get_hit(w, best);
    } else {
        c.rays++;
    }
    if (hdr.instance_count == 0u) return false;
    if ((RT_SCENE_FLAGS() & RT_SCENE_SINGLE) != 0u) {
        rt_trace_instance(0u, r, p, ray_mask, any_hit, best, c);
        if (rt_vk_suspended) {
            w = ST_TOP;
            st_put_hit(w, best);
            return false;
        }
        return best.prim != RT_NO_HIT;
    }
    int sp = 0;
    uint node = hdr.top_root, at = 0u, e0 = 0u;
    if (rt_vk_resuming) {
        e0 = st_get(w);
        st_get_bvh(w, 0, node, sp, at);
        if (at != 1u) rt_vk_resuming = false;
    } else {
        float tn;
        c.box_tests++;
        if (!rt_box_test(node, r, p, rt_box_lo(r.tmin), rt_box_hi(best.t), tn)) return false;
    }
    uint stop = 0u, e = 0u;
    for (;; RT_VK_TICK) {
        /* Resumed inside a leaf: no checkpoint before the leaf's own. */
        if (at == 0u && rt_vk_checkpoint()) {
            stop = 3u;
            break;
        }
        uint nb = nodes[node].b;
        if ((nb & RT_NODE_LEAF_FLAG) != 0u) {
            uint count = nb & RT_NODE_COUNT_MASK, na = nodes[node].a;
            e = at != 0u ? e0 : na;
            at = 0u;
            for (; e < na + count; e++, RT_VK_TICK) {
                if (rt_vk_checkpoint()) {
                    stop = 2u;
                    break;
                }
                if (rt_trace_instance(inst_ids[e], r, p, ray_mask, any_hit, best, c)) return true;
                if (rt_vk_suspended) {
                    stop = 1u;
                    break;
                }
            }
            if (stop != 0u) break;
            if (sp == 0) break;
            node = STACK_AT(0, --sp);
            continue;
        }
        uint next, push;
        int d = rt_descend(node, r, p, best, c, next, push);
        if (d == 0) {
            if (sp == 0) break;
            node = STACK_AT(0, --sp);
        } else {
            if (d == 2) STACK_AT(0, sp++) = push;
            node = next;
        }
    }
    if (stop == 0u) return best.prim != RT_NO_HIT;
    /* Suspended: stop 3 before node, 2 before instance e, 1 inside it. */
    w = ST_TOP;
    st_put_hit(w, best);
    st_put(w, e);
    st_put_bvh(w, 0, node, sp, stop == 3u ? 0u : stop);
    return false;
}

/* rt_trace_masked with every mask bit: the rays of rendering. */
bool rt_trace(rt_ray r, bool any_hit, out rt_hit_d best, inout rt_counters c) {
    return rt_trace_masked(r, 0xffffffffu, any_hit, best, c);
}

#endif
