/* SPDX-License-Identifier: Apache-2.0 */
/* kd.h - SAH kd-trees over a mesh's triangles (Rahikainen 2013, chapters 4-5).
 *
 * Two builders share one tree format and the same split rules:
 * - exact: the O(N log N) event sweep of Wald and Havran (2006): sorted split
 *   events (start, end, planar) per axis, swept once per node, with perfect
 *   splits (a triangle that straddles the plane is clipped to each child
 *   cell and its events recomputed from the clipped box), planar triangles
 *   placed on the cheaper side, and the empty-space bonus;
 * - binned: the same recursion, but the plane is chosen among bin boundaries
 *   from two histograms per axis (the scanning approximation of Hunt et al.
 *   and Shevtsov et al.).
 * Both end a node when the best split costs at least as much as the leaf
 * (SAH termination) or at the depth bound. Subtrees (from the root's
 * children down) are built in parallel on a thread pool and assembled in
 * depth-first order, so the tree is byte-identical for any thread count.
 *
 * Zero-area triangles (edge cross product exactly zero, the layout's
 * "degenerate": no triangle test can hit them) are left out of the tree; a
 * non-finite coordinate is refused.
 */
#ifndef RT_KD_H
#define RT_KD_H

#include <stddef.h>
#include <stdint.h>

#include "accel/bvh.h"
#include "rt.h"
#include "rt_layout.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rt_kd_builder {
    RT_KD_EXACT = 0, /* Wald and Havran 2006 event sweep */
    RT_KD_BINNED = 1 /* SAH over bin boundaries */
} rt_kd_builder;

typedef struct rt_kd_options {
    rt_kd_builder builder;
    rt_sah_costs costs; /* KT (traverse) and KI (intersect) [1, 1] */
    float empty_bonus;  /* the cost factor of a split with an empty side [0.8] */
    int max_depth;      /* <= 0: 8 + 1.3 log2 N, at most RT_KD_MAX_DEPTH */
    int bins;           /* binned builder: bins per axis [32], 2..256 */
    int ref_guard;      /* the reference guard (below) [1]; 0: off, for measurements
                           only (overlapping coplanar input may then take minutes
                           and gigabytes) */
} rt_kd_options;

/* The reference guard, for input whose every split lowers the SAH (many
 * overlapping coplanar triangles): a build whose nodes hold more than
 * RT_KD_GUARD_WORK x N x the depth bound triangle entries in all (N: the
 * triangles with area) stops and builds again with a budget: the tree may
 * then hold at most RT_KD_GUARD_DUPS x N duplicate entries (at most
 * (1 + RT_KD_GUARD_DUPS) x N entries). A tree under the first limit is the
 * tree without the guard. docs/KD_TREES.md has the rule. */
#define RT_KD_GUARD_WORK 8.0
#define RT_KD_GUARD_DUPS 4.0

/* The traversal stack (kernels/rt_kd.h) holds this many entries; no tree
 * is deeper. */
#define RT_KD_MAX_DEPTH 60

rt_kd_options rt_kd_options_default(void);

/* A kd-tree as built: nodes in the layout's format (kernels/rt_layout.h) with
 * indices relative to this tree (right children into nodes, leaf entries into
 * prims). An empty tree (no triangle with area) is one leaf with no entries. */
typedef struct rt_kd {
    rt_kd_node *nodes;
    uint32_t node_count;
    uint32_t *prims; /* leaf entries -> triangle index in the mesh */
    uint32_t prim_count;
    rt_aabb bounds; /* the root cell: the box of the triangles with area */
} rt_kd;

/* Builds a kd-tree over triangle_count triangles (vertex indices into
 * positions, 3 floats per vertex; at most 2^30 - 1 triangles). pool may be
 * NULL (one thread). On failure *out is empty and err holds the reason. */
rt_status rt_kd_build(const float *positions, uint32_t vertex_count, const uint32_t *indices,
                      uint32_t triangle_count, const rt_kd_options *options, rt_pool *pool,
                      rt_kd *out, rt_error *err);

void rt_kd_free(rt_kd *kd);

typedef struct rt_kd_quality {
    double sah;          /* KT per inner node and KI per entry, cells' areas relative to the root */
    uint32_t nodes;      /* inner + leaves */
    uint32_t leaves;     /* including empty ones */
    uint32_t empty;      /* leaves with no entry */
    uint32_t depth;      /* the root alone has depth 1 */
    uint32_t refs;       /* leaf entries (a straddling triangle counts once per leaf) */
    size_t bytes;        /* nodes + entries */
    double refs_per_tri; /* refs / triangles with area */
} rt_kd_quality;

/* Figures of a tree under the SAH costs given (rt_sah_costs_default() for
 * the figure comparable with a BVH's rt_bvh_measure). */
rt_kd_quality rt_kd_measure(const rt_kd *kd, rt_sah_costs costs);

/* Names as rtcl bench prints them: kd-exact, kd-binned. */
const char *rt_kd_builder_name(rt_kd_builder builder);

#ifdef __cplusplus
}
#endif
#endif /* RT_KD_H */
