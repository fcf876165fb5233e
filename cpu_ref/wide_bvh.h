/* SPDX-License-Identifier: Apache-2.0 */
/* wide_bvh.h - the CPU tracers' view of the layout's BVHs: the binary trees
 * collapsed into nodes of 4 or 8 children whose boxes sit in the parent (as
 * in Embree's and tinybvh's wide BVHs), one collapse for both tracers,
 * shaped by rt_wide_shape:
 * - the packet tracer's (packet_trace.h, rt_pk_shape): 4 children, leaves
 *   that are entry ranges of the layout;
 * - the single-ray tracer's (single_trace.h, rt_sw_shape): 4 or 8
 *   children, one per vector lane of the build that traces them, and the
 *   leaves' triangles copied into blocks of 4 or 8, one triangle per lane.
 *
 * A tracer then tests all children of a node from one node's cache lines
 * (and a single ray several triangles with one vector test) instead of
 * walking two levels of separate nodes. The boxes are the layout's boxes,
 * bit for bit, and a leaf holds exactly the entries of the layout's leaves
 * below it, so the tests a ray performs are the oracle's; skipping the
 * collapsed inner levels only lets it test more, never fewer (the tracers'
 * headers say why the hits stay exact). */
#ifndef RT_WIDE_BVH_H
#define RT_WIDE_BVH_H

#include <stdint.h>

#include "layout/flat.h"

/* A slot of a node without a child; a block lane without a triangle. */
#define RT_WIDE_EMPTY 0xffffffffu

/* Children per node at most (the widest shape). */
enum { RT_WIDE_MAX = 8 };

/* Words per node and per triangle block of width w. */
#define RT_WIDE_NODE_WORDS(w)  (8u * (uint32_t)(w))
#define RT_WIDE_BLOCK_WORDS(w) (10u * (uint32_t)(w))

/* How the binary trees are collapsed. Each wide node takes a binary inner
 * node's two children and opens the child of largest surface area while it
 * has fewer than 'width' children and some child may be opened. */
typedef struct rt_wide_shape {
    int width; /* children per node: 4 or 8 */
    /* A mesh subtree whose entries are one run of at most this many becomes
     * one leaf; in the object BVH too (its entries are instances) where
     * merge_top is set. */
    uint32_t leaf_entries;
    int merge_top;
    /* Such a subtree is never opened to fill a node (it stays one leaf);
     * otherwise the collapse may open it like any inner node. */
    int keep_leaf_subtrees;
    /* Mesh leaves as triangle blocks (else entry ranges). */
    int blocks;
} rt_wide_shape;

/* Node i of width w is RT_WIDE_NODE_WORDS(w) 32-bit words at
 * nodes + RT_WIDE_NODE_WORDS(w) i (aligned to 64 bytes): bmin[3][w] and
 * bmax[3][w] (floats; an empty slot's box is inverted, +inf to -inf), then
 * child[w] and info[w] (uint32). Children fill the first slots, in the
 * binary tree's left-to-right order; an empty slot has child RT_WIDE_EMPTY
 * and info 0. For an inner child info is 0 and child its node index; for a
 * leaf info is its count | RT_NODE_LEAF_FLAG and child either its first
 * entry (an entry range: count entries into the layout's tris, or in the
 * object BVH into its inst_ids) or, for a mesh leaf of a shape with blocks,
 * its first block (count blocks).
 *
 * Block j is RT_WIDE_BLOCK_WORDS(w) words at blocks + RT_WIDE_BLOCK_WORDS(w)
 * j: v0[3][w], v1[3][w], v2[3][w] (floats, the layout's triangle of that
 * lane, bit for bit) and entry[w] (uint32: the triangle's index into the
 * layout's tris, RT_WIDE_EMPTY for a lane without one, whose vertices repeat
 * the block's last real lane's). */
typedef struct rt_wide_bvh {
    rt_wide_shape shape;
    uint32_t *nodes; /* node_count nodes (floats and uint32s as words) */
    uint32_t node_count;
    uint32_t *blocks; /* block_count blocks (NULL without blocks) */
    uint32_t block_count;
    uint32_t top;        /* the object BVH's entry node (RT_WIDE_EMPTY without one) */
    uint32_t *inst_root; /* per instance: its mesh BVH's entry node */
    uint32_t inst_count;
    uint32_t *src;      /* per node and child slot: the binary node it copies (refits) */
    uint32_t top_first; /* the object BVH's nodes start here (after every mesh's) */
} rt_wide_bvh;

/* Builds the wide BVHs of every tree in flat: the object BVH, and each
 * instance's mesh BVH once however many instances share it. Each tree starts
 * at an entry node whose one child is the binary root, so that the root's
 * box is tested first, as the oracle tests it. RT_ERROR_OUT_OF_MEMORY, or
 * RT_ERROR_INVALID_ARGUMENT for a shape of another width than 4 or 8 or
 * with leaf_entries 0; *out is then empty. */
rt_status rt_wide_build(const rt_flat *flat, rt_wide_shape shape, rt_wide_bvh *out);

/* Brings wide (built from an earlier layout) up to date with flat when the
 * mesh trees kept their shapes (only refitted): the mesh nodes' boxes are
 * copied again from the binary nodes they came from, the blocks' vertices
 * from the triangles they hold, and the object BVH's wide tree is built
 * anew. The result is what rt_wide_build would give but for the collapse
 * choices of the mesh trees, which decide only how many boxes a ray tests,
 * never its hits. RT_ERROR_OUT_OF_MEMORY leaves wide unusable (free it). */
rt_status rt_wide_refit(const rt_flat *flat, rt_wide_bvh *wide);

void rt_wide_free(rt_wide_bvh *wide);

#endif /* RT_WIDE_BVH_H */
