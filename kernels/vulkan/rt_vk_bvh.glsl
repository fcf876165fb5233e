/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_bvh.glsl - the GLSL mirror of kernels/rt_bvh.h: one inner-node step
 * and the walk of one mesh's BVH, with the traversal stacks in workgroup
 * memory (GLSL only, below). */
#ifndef RT_VK_BVH_GLSL
#define RT_VK_BVH_GLSL

#include "rt_vk_hit.glsl"

#define RT_STACK_SIZE 64

/* ---- traversal stacks ------------------------------------------------------
 * In workgroup-shared memory, not in per-invocation arrays: a driver keeps a
 * private array indexed at run time in scratch memory or as a chain of
 * selects (lavapipe traced 100 times slower so). Entry k of invocation l is
 * at k * RT_VK_LOCAL + l (consecutive invocations in consecutive words;
 * RT_VK_LOCAL, the work group size, is kernels/rt_interface.def's). The
 * object BVH's stack is entries 0 .. RT_STACK_SIZE - 1, a mesh BVH's the
 * next RT_STACK_SIZE. */
shared uint rt_vk_stack[2 * RT_STACK_SIZE * RT_VK_LOCAL];
#define STACK_AT(level, k) rt_vk_stack[(uint(level) * uint(RT_STACK_SIZE) + uint(k)) * RT_VK_LOCAL + gl_LocalInvocationIndex]

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

bool rt_trace_mesh(uint root, uint inst, rt_ray r, rt_ray_pre p, bool any_hit,
                   inout rt_hit_d best, inout rt_counters c) {
    int sp = 0;
    float tn;
    c.box_tests++;
    if (!rt_box_test(root, r, p, rt_box_lo(r.tmin), rt_box_hi(best.t), tn)) return false;
    uint node = root;
    for (;;) {
        uint nb = nodes[node].b;
        if ((nb & RT_NODE_LEAF_FLAG) != 0u) {
            if (rt_leaf_test(nodes[node].a, nb & RT_NODE_COUNT_MASK, inst, r, p, any_hit, best, c))
                return true;
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
    return false;
}

#endif
