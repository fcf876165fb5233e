/* SPDX-License-Identifier: Apache-2.0 */
/* test_bvh_simple.h - a small median-split BVH builder for tests, so that
 * traversal can be tested independently of the library's builders. Not part
 * of the library. */
#ifndef RT_TEST_BVH_SIMPLE_H
#define RT_TEST_BVH_SIMPLE_H

#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"

typedef struct simple_build {
    const rt_aabb *boxes;
    rt_bvh *out;
    int leaf_size;
} simple_build;

static float simple_centre(const rt_aabb *b, int axis) {
    return 0.5f * (b->bmin[axis] + b->bmax[axis]);
}

static int simple_axis_g;
static const rt_aabb *simple_boxes_g;
static int simple_cmp(const void *a, const void *b) {
    float ca = simple_centre(&simple_boxes_g[*(const uint32_t *)a], simple_axis_g);
    float cb = simple_centre(&simple_boxes_g[*(const uint32_t *)b], simple_axis_g);
    if (ca != cb) return ca < cb ? -1 : 1;
    return *(const uint32_t *)a < *(const uint32_t *)b ? -1 : 1;
}

static void simple_node(simple_build *s, uint32_t node, uint32_t first, uint32_t count) {
    rt_node *n = &s->out->nodes[node];
    for (int k = 0; k < 3; k++) {
        n->bmin[k] = 1e30f;
        n->bmax[k] = -1e30f;
    }
    for (uint32_t i = first; i < first + count; i++) {
        const rt_aabb *b = &s->boxes[s->out->prim_indices[i]];
        for (int k = 0; k < 3; k++) {
            if (b->bmin[k] < n->bmin[k]) n->bmin[k] = b->bmin[k];
            if (b->bmax[k] > n->bmax[k]) n->bmax[k] = b->bmax[k];
        }
    }
    if (count <= (uint32_t)s->leaf_size) {
        n->a = first;
        n->b = count | RT_NODE_LEAF_FLAG;
        return;
    }
    int axis = 0;
    float ext[3];
    for (int k = 0; k < 3; k++) ext[k] = n->bmax[k] - n->bmin[k];
    if (ext[1] > ext[axis]) axis = 1;
    if (ext[2] > ext[axis]) axis = 2;
    simple_axis_g = axis;
    simple_boxes_g = s->boxes;
    qsort(s->out->prim_indices + first, count, sizeof(uint32_t), simple_cmp);
    uint32_t half = count / 2;
    uint32_t left = s->out->node_count++, right = s->out->node_count++;
    n->a = left;
    n->b = right;
    simple_node(s, left, first, half);
    simple_node(s, right, first + half, count - half);
}

/* Builds a BVH over count > 0 boxes with leaves of at most leaf_size. */
static int simple_bvh_build(const rt_aabb *boxes, uint32_t count, int leaf_size, rt_bvh *out) {
    memset(out, 0, sizeof *out);
    out->nodes = calloc(2 * (size_t)count + 1, sizeof(rt_node));
    out->prim_indices = malloc(sizeof(uint32_t) * (count ? count : 1));
    if (!out->nodes || !out->prim_indices) return 0;
    for (uint32_t i = 0; i < count; i++) out->prim_indices[i] = i;
    out->prim_count = count;
    out->node_count = 1;
    simple_build s = {boxes, out, leaf_size};
    simple_node(&s, 0, 0, count);
    return 1;
}

#endif
