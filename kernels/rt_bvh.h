/* SPDX-License-Identifier: Apache-2.0 */
/* rt_bvh.h - BVH traversal: one inner-node step (rt_descend, shared with
 * the object BVH of rt_trace.h) and the walk of one mesh's BVH
 * (rt_trace_mesh). Valid C99 and OpenCL C (rt_math_profile.h); the GLSL
 * mirror is kernels/vulkan/rt_vk_bvh.glsl. */
#ifndef RT_KERNELS_BVH_H
#define RT_KERNELS_BVH_H

#include "rt_hit.h"

/* Traversal stack entries; host/flatten.c rejects deeper trees. */
#define RT_STACK_SIZE 64

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

#endif /* RT_KERNELS_BVH_H */
