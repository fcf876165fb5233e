/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_validate.h - checks that any rt_bvh is a well-formed tree over its input.
 *
 * Header-only (static inline) so that every BVH test can include it. The check
 * walks the tree from the root and fails, with a message naming the node, on:
 * - a child index out of range, a node reached twice (not a tree) or a node
 *   never reached (node_count counts unused nodes);
 * - a primitive index out of range, missing, or listed twice; a leaf range
 *   outside the index array, or two leaves sharing an entry;
 * - a node box that does not contain its children's boxes or its primitives'
 *   boxes (exact float comparison: unions of boxes are exact);
 * - an empty leaf (except the empty tree), a leaf holding more than max_leaf
 *   primitives unless all of its primitives have the same centroid (where no
 *   split by position exists), a depth above max_depth.
 * The empty tree may be node_count 0 or one empty leaf.
 */
#ifndef RT_BVH_VALIDATE_H
#define RT_BVH_VALIDATE_H

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "accel/bvh.h"

/* ceil(log2(n)) for n >= 1. */
static inline uint32_t bvh_validate_ceil_log2(uint32_t n) {
    uint32_t k = 0;
    while (k < 32 && ((uint64_t)1 << k) < n) k++;
    return k;
}

/* The depth every builder must stay within: 2 * ceil(log2(N)) + 64. */
static inline uint32_t bvh_validate_depth_bound(uint32_t count) {
    return 2 * bvh_validate_ceil_log2(count ? count : 1) + 64;
}

static inline int bvh_validate_fail(char *msg, size_t msg_size, const char *fmt, ...) {
    if (msg && msg_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, msg_size, fmt, ap);
        va_end(ap);
    }
    return 0;
}

static inline int bvh_validate_contains(const float outer_min[3], const float outer_max[3],
                                        const float inner_min[3], const float inner_max[3]) {
    for (int k = 0; k < 3; k++)
        if (!(outer_min[k] <= inner_min[k]) || !(outer_max[k] >= inner_max[k])) return 0;
    return 1;
}

/* Returns 1 if bvh is a valid tree over boxes[0..count), else 0 with the
 * reason in msg. max_leaf 0: no limit on leaf size; max_depth 0: the default
 * bound above. */
static inline int bvh_validate(const rt_bvh *bvh, const rt_aabb *boxes, uint32_t count,
                               uint32_t max_leaf, uint32_t max_depth, char *msg, size_t msg_size) {
    if (!max_depth) max_depth = bvh_validate_depth_bound(count);
    if (bvh->prim_count != count)
        return bvh_validate_fail(msg, msg_size, "prim_count %u, expected %u", bvh->prim_count,
                                 count);
    if (count == 0) {
        if (bvh->node_count == 0) return 1;
        if (bvh->node_count == 1 && (bvh->nodes[0].b & RT_NODE_LEAF_FLAG) &&
            (bvh->nodes[0].b & RT_NODE_COUNT_MASK) == 0)
            return 1;
        return bvh_validate_fail(msg, msg_size, "empty input gives %u nodes", bvh->node_count);
    }
    if (bvh->node_count == 0 || !bvh->nodes || !bvh->prim_indices)
        return bvh_validate_fail(msg, msg_size, "no nodes for %u primitives", count);
    if (bvh->node_count > 2 * count - 1)
        return bvh_validate_fail(msg, msg_size, "%u nodes for %u primitives (more than 2N-1)",
                                 bvh->node_count, count);

    int ok = 1;
    uint32_t n = bvh->node_count;
    unsigned char *node_seen = calloc(n, 1);
    unsigned char *entry_seen = calloc(count, 1);
    unsigned char *prim_seen = calloc(count, 1);
    uint32_t *stack = malloc(sizeof(uint32_t) * 2 * ((size_t)n + 1));
    if (!node_seen || !entry_seen || !prim_seen || !stack) {
        ok = bvh_validate_fail(msg, msg_size, "out of memory");
        goto done;
    }

    /* Every primitive index in range and listed once. */
    for (uint32_t i = 0; i < count && ok; i++) {
        uint32_t p = bvh->prim_indices[i];
        if (p >= count)
            ok = bvh_validate_fail(msg, msg_size, "prim_indices[%u] = %u is out of range", i, p);
        else if (prim_seen[p]++)
            ok = bvh_validate_fail(msg, msg_size, "primitive %u is listed twice", p);
    }

    size_t top = 0;
    stack[top++] = 0;
    stack[top++] = 1; /* depth of the root */
    node_seen[0] = 1;
    uint32_t visited = 1;
    while (ok && top) {
        uint32_t depth = stack[--top];
        uint32_t i = stack[--top];
        const rt_node *node = &bvh->nodes[i];
        if (depth > max_depth) {
            ok = bvh_validate_fail(msg, msg_size, "node %u at depth %u (bound %u)", i, depth,
                                   max_depth);
            break;
        }
        if (node->b & RT_NODE_LEAF_FLAG) {
            uint32_t first = node->a, c = node->b & RT_NODE_COUNT_MASK;
            if (c == 0) {
                ok = bvh_validate_fail(msg, msg_size, "leaf %u is empty", i);
                break;
            }
            if (first > count || c > count - first) {
                ok = bvh_validate_fail(msg, msg_size, "leaf %u range %u+%u exceeds %u", i, first, c,
                                       count);
                break;
            }
            int same_centroid = 1;
            const rt_aabb *b0 = &boxes[bvh->prim_indices[first]];
            for (uint32_t e = first; e < first + c && ok; e++) {
                if (entry_seen[e]++) {
                    ok = bvh_validate_fail(msg, msg_size, "entry %u in two leaves (leaf %u)", e, i);
                    break;
                }
                const rt_aabb *b = &boxes[bvh->prim_indices[e]];
                if (!bvh_validate_contains(node->bmin, node->bmax, b->bmin, b->bmax))
                    ok = bvh_validate_fail(msg, msg_size,
                                           "leaf %u box does not contain primitive %u", i,
                                           bvh->prim_indices[e]);
                for (int k = 0; k < 3; k++)
                    if ((double)b->bmin[k] + (double)b->bmax[k] !=
                        (double)b0->bmin[k] + (double)b0->bmax[k])
                        same_centroid = 0;
            }
            if (ok && max_leaf && c > max_leaf && !same_centroid)
                ok = bvh_validate_fail(msg, msg_size, "leaf %u holds %u primitives (max %u)", i, c,
                                       max_leaf);
        } else {
            uint32_t kids[2] = {node->a, node->b};
            for (int k = 0; k < 2 && ok; k++) {
                uint32_t child = kids[k];
                if (child >= n || child == 0) {
                    ok = bvh_validate_fail(msg, msg_size, "node %u has child %u of %u nodes", i,
                                           child, n);
                } else if (node_seen[child]++) {
                    ok = bvh_validate_fail(msg, msg_size, "node %u reached twice", child);
                } else {
                    const rt_node *cn = &bvh->nodes[child];
                    if (!bvh_validate_contains(node->bmin, node->bmax, cn->bmin, cn->bmax))
                        ok = bvh_validate_fail(msg, msg_size,
                                               "node %u box does not contain child %u", i, child);
                    visited++;
                    stack[top++] = child;
                    stack[top++] = depth + 1;
                }
            }
        }
    }
    if (ok && visited != n)
        ok = bvh_validate_fail(msg, msg_size, "%u of %u nodes are unreachable", n - visited, n);
    for (uint32_t e = 0; ok && e < count; e++)
        if (!entry_seen[e]) ok = bvh_validate_fail(msg, msg_size, "entry %u is in no leaf", e);

done:
    free(node_seen);
    free(entry_seen);
    free(prim_seen);
    free(stack);
    return ok;
}

/* ---- test inputs shared by the BVH tests ------------------------------------ */

/* xorshift32: a small deterministic generator for test inputs. */
static inline uint32_t bvh_test_rand(uint32_t *state) {
    uint32_t x = *state ? *state : 0x9e3779b9u;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    return x;
}

/* Uniform in [lo, hi). */
static inline float bvh_test_uniform(uint32_t *state, float lo, float hi) {
    return lo + (hi - lo) * (float)(bvh_test_rand(state) >> 8) * (1.0f / 16777216.0f);
}

/* The box of a triangle given by 9 floats. */
static inline rt_aabb bvh_test_tri_box(const float v[9]) {
    rt_aabb b;
    for (int k = 0; k < 3; k++) {
        float lo = v[k], hi = v[k];
        for (int j = 1; j < 3; j++) {
            float x = v[3 * j + k];
            lo = x < lo ? x : lo;
            hi = x > hi ? x : hi;
        }
        b.bmin[k] = lo;
        b.bmax[k] = hi;
    }
    return b;
}

#endif /* RT_BVH_VALIDATE_H */
