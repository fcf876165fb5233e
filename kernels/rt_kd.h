/* SPDX-License-Identifier: Apache-2.0 */
/* rt_kd.h - kd-tree traversal of one mesh (the layout of rt_layout.h,
 * RT_INST_KD), shared by the C oracle and the OpenCL kernels; rt_trace.h
 * calls it for kd meshes beside rt_bvh.h's BVH walk. Valid C99 and OpenCL C
 * under the rules of rt_math_profile.h; the GLSL mirror is
 * kernels/vulkan/rt_vk_kd.glsl.
 *
 * Front to back with an explicit stack of (node, entry t, exit t) cells
 * (Havran's recursive traversal without recursion). Exactness against the
 * BVH: a leaf tests its triangles with rt_leaf_test, the BVH's own code, over
 * the whole ray range [tmin, best t], never clipped to the cell; so a triangle
 * found in any of its leaves gives the BVH's t, u, v bits, and the total
 * order (t, instance, triangle) picks the same hit. What the tree decides is
 * only which leaves are visited, and every decision is conservative:
 * - cell intervals are widened at each split by RT_BOX_T_MARGIN relative to
 *   the plane's t (more than the rounding of the plane's t and of a
 *   triangle's t), so a triangle touching the plane is reached from both
 *   sides;
 * - a ray parallel to the split plane (1/dir infinite) goes by its origin's
 *   side, and to both children when it lies in the plane: no 0 * inf NaN is
 *   computed, and a flat cell (both planes equal) is entered like any other;
 * - early termination: after a leaf, a cell on the stack is skipped only when
 *   its entry is strictly after rt_box_hi(best t), the bound the BVH applies
 *   to its boxes; a cell entered at exactly that t is still visited, so an
 *   equal-t hit with a lower instance or triangle index is never lost.
 */
#ifndef RT_KD_TRAVERSE_H
#define RT_KD_TRAVERSE_H

#include "rt_hit.h"

/* Stack entries; host/layout/flatten.c rejects deeper trees. */
#define RT_KD_STACK 64

/* The ray's interval [*tn, *tf] in the root cell (the box of the mesh's
 * rt_node), intersected with [lo, hi]: rt_box_test's slab test, which also
 * gives the far end (rt_box_interval). 0 when the ray misses. */
RT_FN int rt_kd_root_interval(RT_GLOBAL const rt_node *n, const rt_ray *r, const rt_ray_pre *p,
                              float lo, float hi, float *tn, float *tf) {
    return rt_box_interval(n->bmin, n->bmax, r, p, lo, hi, tn, tf);
}

/* Traverses the kd-tree of the mesh whose bounding rt_node is 'root', with a
 * ray already in the mesh's space; like rt_trace_mesh, best->t is the upper
 * end of the range and the return value is 1 when any_hit found an
 * occluder. c->box_tests counts the root box and every inner node visited. */
RT_FN int rt_kd_trace_mesh(const rt_scene_view *s, rt_u32 root, rt_u32 inst, const rt_ray *r,
                           const rt_ray_pre *p, int any_hit, rt_hit_d *best, rt_counters *c) {
    RT_GLOBAL const rt_node *rn = &s->nodes[root];
    float tn, tf;
    c->box_tests++;
    if (!rt_kd_root_interval(rn, r, p, rt_box_lo(r->tmin), rt_box_hi(best->t), &tn, &tf)) return 0;
    rt_u32 st_node[RT_KD_STACK];
    float st_tn[RT_KD_STACK], st_tf[RT_KD_STACK];
    int sp = 0;
    rt_u32 node = rn->a;
    for (;;) {
        RT_GLOBAL const rt_kd_node *n = &s->kd_nodes[node];
        rt_u32 k = n->b & 3u;
        if (k == RT_KD_LEAF) {
            if (rt_leaf_test(s, n->a, n->b >> 2, inst, r, p, any_hit, best, c)) return 1;
            /* The next cell that may still hold a hit at or before best. */
            for (;;) {
                if (sp == 0) return 0;
                --sp;
                if (st_tn[sp] <= rt_box_hi(best->t)) break;
            }
            node = st_node[sp];
            tn = st_tn[sp];
            tf = st_tf[sp];
            continue;
        }
        c->box_tests++;
        float split = RT_AS_FLOAT((rt_i32)n->a);
        rt_u32 left = node + 1u, right = n->b >> 2;
        float o = r->org[k], inv = p->inv[k];
        rt_u32 first, second;
        float first_tf, second_tn;
        int go_first, go_second;
        if (!(RT_FABS(inv) < RT_INF)) {
            /* Parallel to the plane: the side of the origin, both when the
             * ray lies in the plane. */
            first = left;
            second = right;
            first_tf = tf;
            second_tn = tn;
            go_first = o <= split;
            go_second = o >= split;
        } else {
            float ts = (split - o) * inv; /* finite or +-inf, never NaN */
            float m = RT_FABS(ts) < RT_INF ? RT_FABS(ts) * RT_BOX_T_MARGIN : 0.0f;
            float ts_lo = ts - m, ts_hi = ts + m;
            /* Along the direction, the lower side of the plane comes first. */
            int left_first = inv >= 0.0f;
            first = left_first ? left : right;
            second = left_first ? right : left;
            first_tf = ts_hi < tf ? ts_hi : tf;
            second_tn = ts_lo > tn ? ts_lo : tn;
            go_first = tn <= ts_hi;
            go_second = ts_lo <= tf && second_tn <= rt_box_hi(best->t);
        }
        if (go_first && go_second) {
            st_node[sp] = second;
            st_tn[sp] = second_tn;
            st_tf[sp] = tf;
            sp++;
            node = first;
            tf = first_tf;
        } else if (go_first) {
            node = first;
            tf = first_tf;
        } else if (go_second) {
            node = second;
            tn = second_tn;
        } else {
            for (;;) {
                if (sp == 0) return 0;
                --sp;
                if (st_tn[sp] <= rt_box_hi(best->t)) break;
            }
            node = st_node[sp];
            tn = st_tn[sp];
            tf = st_tf[sp];
        }
    }
}

#endif /* RT_KD_TRAVERSE_H */
