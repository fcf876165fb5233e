/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_quality.c - rt_bvh_measure: the figures by which trees are compared.
 *
 * SAH cost, as the thesis's Table 6 "BVH cost" (Langr 2016), with A the
 * surface area of a node's box:
 *
 *   cost = sum over inner nodes n of  Ct * A(n) / A(root)
 *        + sum over leaves l of       Ci * count(l) * A(l) / A(root)
 *
 * The root is counted: an inner root adds Ct (A/A = 1), a leaf root adds
 * Ci * count. Where the root box has zero area (all primitives on one line or
 * one point) every ratio is taken as 1. Areas are computed in double. A tree
 * from any builder can be measured: everything but the depth is one pass over
 * the node array; the depth (root alone = 1) walks the tree from the root.
 */
#include <stdlib.h>

#include "accel/bvh.h"

static double node_area(const rt_node *n) {
    double dx = (double)n->bmax[0] - n->bmin[0];
    double dy = (double)n->bmax[1] - n->bmin[1];
    double dz = (double)n->bmax[2] - n->bmin[2];
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

/* Depth of the tree, or 0 when it cannot be walked (out of memory, or child
 * indices that do not form a tree within node_count steps). */
static uint32_t tree_depth(const rt_bvh *bvh) {
    uint32_t n = bvh->node_count;
    uint32_t *stack = malloc(sizeof(uint32_t) * 2 * ((size_t)n + 1));
    if (!stack) return 0;
    size_t top = 0, steps = 0;
    uint32_t depth = 0;
    stack[top++] = 0;
    stack[top++] = 1;
    while (top) {
        uint32_t d = stack[--top];
        uint32_t i = stack[--top];
        if (++steps > n || i >= n) {
            depth = 0;
            break;
        }
        if (d > depth) depth = d;
        const rt_node *node = &bvh->nodes[i];
        if (!(node->b & RT_NODE_LEAF_FLAG)) {
            if (top + 4 > 2 * ((size_t)n + 1)) {
                depth = 0;
                break;
            }
            stack[top++] = node->a;
            stack[top++] = d + 1;
            stack[top++] = node->b;
            stack[top++] = d + 1;
        }
    }
    free(stack);
    return depth;
}

double rt_bvh_sah_cost(const rt_bvh *bvh, rt_sah_costs costs) {
    if (!bvh || !bvh->nodes || bvh->node_count == 0) return 0.0;
    double root_area = node_area(&bvh->nodes[0]);
    double sah = 0.0;
    for (uint32_t i = 0; i < bvh->node_count; i++) {
        const rt_node *n = &bvh->nodes[i];
        double rel = root_area > 0.0 ? node_area(n) / root_area : 1.0;
        if (n->b & RT_NODE_LEAF_FLAG)
            sah += (double)costs.intersect * (double)(n->b & RT_NODE_COUNT_MASK) * rel;
        else
            sah += (double)costs.traverse * rel;
    }
    return sah;
}

rt_bvh_quality rt_bvh_measure(const rt_bvh *bvh, rt_sah_costs costs) {
    rt_bvh_quality q = {0.0, 0, 0, 0, 0};
    if (!bvh || !bvh->nodes || bvh->node_count == 0) return q;
    q.nodes = bvh->node_count;
    q.bytes =
        (size_t)bvh->node_count * sizeof(rt_node) + (size_t)bvh->prim_count * sizeof(uint32_t);
    for (uint32_t i = 0; i < bvh->node_count; i++)
        if (bvh->nodes[i].b & RT_NODE_LEAF_FLAG) q.leaves++;
    q.sah = rt_bvh_sah_cost(bvh, costs);
    q.depth = tree_depth(bvh);
    return q;
}
