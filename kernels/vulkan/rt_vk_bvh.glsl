/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_bvh.glsl - the GLSL mirror of kernels/rt_bvh.h: one inner-node step
 * and the walk of one mesh's BVH, with the traversal stacks in workgroup
 * memory (GLSL only, rt_vk_resume.glsl); resumable (rt_vk_resume.glsl). */
#ifndef RT_VK_BVH_GLSL
#define RT_VK_BVH_GLSL

#include "rt_vk_hit.glsl"

/* The traversal stacks (RT_STACK_SIZE, STACK_AT) are rt_vk_resume.glsl's. */

/* rt_descend without the stack (GLSL has no pointer to it): returns 0 when
 * the caller must pop, 1 to go on at *next, 2 to go on at *next after
 * pushing *push. The same tests and choices as the C function. */
int rt_descend(uint node, rt_ray r, rt_ray_pre p, rt_hit_d best, inout rt_counters c,
               out uint next, out uint push) {
    float t0, t1, lo = rt_box_lo(r.tmin), hi = rt_box_hi(best.t);
    uint na = nodes[node].a, nb = nodes[node].b;
    c.box_tests += 2u;
    bool h0 = rt_box_test(na, r, p, lo, hi, t0);
    bool h1 = rt_box_test(nb, r, p, lo, hi, t1);
    next = 0u;
    push = 0u;
    if (h0 && h1) {
        bool right_first = t1 < t0;
        push = right_first ? na : nb;
        next = right_first ? nb : na;
        return 2;
    } else if (h0) {
        next = na;
        return 1;
    } else if (h1) {
        next = nb;
        return 1;
    }
    return 0;
}

/* Resumable (rt_vk_resume.glsl): suspended at a node (ST_MESH at = 0) or
 * inside its leaf (at = 1, the leaf's own position in ST_LEAF). */
bool rt_trace_mesh(uint root, uint inst, rt_ray r, rt_ray_pre p, bool any_hit,
                   inout rt_hit_d best, inout rt_counters c) {
    int sp = 0;
    uint node = root, at = 0u;
    if (rt_vk_resuming) {
        st_get_bvh(ST_MESH, 1, node, sp, at);
        if (at == 0u) rt_vk_resuming = false;
    } else {
        float tn;
        c.box_tests++;
        if (!rt_box_test(root, r, p, rt_box_lo(r.tmin), rt_box_hi(best.t), tn)) return false;
    }
    for (;; RT_VK_TICK) {
        if (rt_vk_checkpoint()) {
            at = 0u;
            break;
        }
        uint nb = nodes[node].b;
        if ((nb & RT_NODE_LEAF_FLAG) != 0u) {
            if (rt_leaf_test(nodes[node].a, nb & RT_NODE_COUNT_MASK, inst, r, p, any_hit, best, c))
                return true;
            if (rt_vk_suspended) {
                at = 1u;
                break;
            }
            if (sp == 0) return false;
            node = STACK_AT(1, --sp);
            continue;
        }
        uint next, push;
        int d = rt_descend(node, r, p, best, c, next, push);
        if (d == 0) {
            if (sp == 0) return false;
            node = STACK_AT(1, --sp);
        } else {
            if (d == 2) STACK_AT(1, sp++) = push;
            node = next;
        }
    }
    /* Suspended (the one way out of the loop). */
    st_put_bvh(ST_MESH, 1, node, sp, at);
    return false;
}

#endif
