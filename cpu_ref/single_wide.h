/* single_wide.h - the single-ray tracer's view of the layout's BVHs: the
 * binary trees collapsed into nodes of 4 or 8 children (one per vector lane
 * of the build that traces them, cpu_ref/single_trace.h), and the leaves'
 * triangles copied into blocks of 4 or 8, one triangle per lane.
 *
 * One incoherent ray then tests all children of a node with one vector box
 * test and several triangles with one vector triangle test, where the binary
 * oracle takes a node (and a triangle) at a time. The boxes are the layout's
 * boxes, bit for bit, and a leaf holds exactly the entries of the layout's
 * leaves below it, so the tests a ray performs are the oracle's; skipping
 * the collapsed inner levels only lets it test more triangles, never fewer
 * (single_trace.h says why the hits stay exact).
 */
#ifndef RT_SINGLE_WIDE_H
#define RT_SINGLE_WIDE_H

#include <stdint.h>

#include "layout/flat.h"

/* A slot of a node without a child; a block lane without a triangle. */
#define RT_SW_EMPTY 0xffffffffu

/* Subtrees of at most RT_SW_LEAF_MERGE times the width triangles (one run of
 * entries) become one leaf of the wide tree. */
#ifndef RT_SW_LEAF_MERGE
#define RT_SW_LEAF_MERGE 1
#endif

/* Node i of width W is 8 W 32-bit words at nodes + 8 W i (aligned to 64
 * bytes): bmin[3][W] and bmax[3][W] (floats; an empty slot's box is
 * inverted, +inf to -inf), then child[W] and info[W] (uint32). Children fill
 * the first slots; an empty slot has child RT_SW_EMPTY. For an inner child
 * info is 0 and child its node index; for a leaf info is its count |
 * RT_NODE_LEAF_FLAG and child its first block (a mesh BVH: count blocks) or
 * its first entry into the layout's inst_ids (the object BVH: count
 * instances).
 *
 * Block j is 10 W words at blocks + 10 W j: v0[3][W], v1[3][W], v2[3][W]
 * (floats, the layout's triangle of that lane, bit for bit) and entry[W]
 * (uint32: the triangle's index into the layout's tris, RT_SW_EMPTY for a
 * lane without one, whose vertices repeat a real triangle's). */
typedef struct rt_sw_bvh {
    int width;       /* W: 4 or 8 */
    uint32_t *nodes; /* node_count nodes (floats and uint32s as words) */
    uint32_t node_count;
    uint32_t *blocks; /* block_count blocks */
    uint32_t block_count;
    uint32_t top;        /* the object BVH's entry node (RT_SW_EMPTY without one) */
    uint32_t *inst_root; /* per instance: its mesh BVH's entry node */
    uint32_t inst_count;
} rt_sw_bvh;

/* Words per node and per block of width w. */
static inline uint32_t rt_sw_node_words(int w) {
    return 8u * (uint32_t)w;
}
static inline uint32_t rt_sw_block_words(int w) {
    return 10u * (uint32_t)w;
}

/* Builds the wide BVHs (width 4 or 8) of every tree in flat: the object
 * BVH, and each instance's mesh BVH once however many instances share it.
 * Each tree starts at an entry node whose one child is the binary root, so
 * that the root's box is tested first, as the oracle tests it.
 * RT_ERROR_OUT_OF_MEMORY or RT_ERROR_INVALID_ARGUMENT (a width other than 4
 * or 8); *out is then empty. */
rt_status rt_sw_build(const rt_flat *flat, int width, rt_sw_bvh *out);
void rt_sw_free(rt_sw_bvh *bvh);

#endif /* RT_SINGLE_WIDE_H */
