/* packet_wide.h - the packet tracer's view of the layout's BVHs: the same
 * binary trees collapsed into nodes of up to four children whose boxes sit in
 * the parent (as in Embree's and tinybvh's wide BVHs).
 *
 * A packet then tests up to four children per step from one node's cache
 * lines instead of walking two levels of separate nodes: fewer dependent
 * loads and branches per ray. The boxes are the layout's boxes, copied
 * bit for bit, and the leaves are the layout's leaves (entries into its
 * triangles or object ids), so the tests a lane performs are the oracle's;
 * skipping the collapsed inner levels only lets a lane visit more leaves,
 * never fewer (packet_trace.h says why that keeps the hits exact).
 */
#ifndef RT_PACKET_WIDE_H
#define RT_PACKET_WIDE_H

#include <stdint.h>

#include "layout/flat.h"

#define RT_PK_NO_CHILD 0xffffffffu

/* Children per wide node. */
#ifndef RT_PK_WIDTH
#define RT_PK_WIDTH 4
#endif

/* Subtrees of at most this many primitives (one run of entries) become one
 * leaf of the wide tree. */
#ifndef RT_PK_LEAF_MERGE
#define RT_PK_LEAF_MERGE 4
#endif

/* Up to four children, in the binary tree's left-to-right order; slots
 * past the last child have ref RT_PK_NO_CHILD. A child is a leaf when its
 * count has RT_NODE_LEAF_FLAG: ref and count are then the layout leaf's a and
 * b (first entry, count | flag); else ref is the child's node index and
 * count 0. */
typedef struct rt_pk_node {
    float bmin[3][RT_PK_WIDTH];
    float bmax[3][RT_PK_WIDTH];
    uint32_t ref[RT_PK_WIDTH];
    uint32_t count[RT_PK_WIDTH];
} rt_pk_node; /* 32 bytes a child, allocated on 64-byte lines */

/* Every BVH of a layout. Each tree starts at an entry node whose one child
 * is the binary root (its box is the root's box, tested first, as the oracle
 * tests the root). */
typedef struct rt_pk_wide {
    rt_pk_node *nodes;
    uint32_t node_count;
    uint32_t top;        /* the object BVH's entry node (RT_PK_NO_CHILD without one) */
    uint32_t *inst_root; /* per instance: its mesh BVH's entry node */
    uint32_t inst_count;
    uint32_t *src;      /* per node and child slot: the binary node it copies (refits) */
    uint32_t top_first; /* the object BVH's nodes start here (after every mesh's) */
} rt_pk_wide;

/* Builds the wide BVHs of every tree in flat (the object BVH, and each
 * instance's mesh BVH once however many instances share it). */
rt_status rt_pk_wide_build(const rt_flat *flat, rt_pk_wide *out);
void rt_pk_wide_free(rt_pk_wide *wide);

/* Brings wide (built from an earlier layout) up to date with flat when the
 * mesh trees kept their shapes (only refitted): the mesh nodes' boxes are
 * copied again from the binary nodes they came from, and the object BVH's
 * wide tree is built anew. The result is what rt_pk_wide_build would give
 * but for the collapse choices of the mesh trees, which only decide how many
 * boxes a packet tests, never its hits. */
rt_status rt_pk_wide_refit(const rt_flat *flat, rt_pk_wide *wide);

#endif /* RT_PACKET_WIDE_H */
