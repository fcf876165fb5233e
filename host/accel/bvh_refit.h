/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_refit.h - refitting a BVH whose primitives moved: the tree's topology
 * stays, every box is recomputed bottom-up from the primitives' new boxes,
 * in parallel over the thread pool. Boxes are unions (min and max), exact in
 * any order, so the refitted tree is the same for any thread count. */
#ifndef RT_BVH_REFIT_H
#define RT_BVH_REFIT_H

#include <stdint.h>

#include "accel/bvh.h"

/* What a refit needs to know of a tree's shape, made once per build. */
typedef struct rt_bvh_refit_info {
    uint32_t *parents; /* per node; UINT32_MAX for the root */
    uint32_t *leaves;  /* the leaf nodes' indices */
    uint32_t leaf_count;
    uint32_t node_count;
    void *visits; /* per node, an atomic counter of children done */
    int ordered;  /* every child comes after its parent: one backward sweep refits */
} rt_bvh_refit_info;

/* Fills info for bvh (node_count > 0). RT_ERROR_OUT_OF_MEMORY on failure. */
rt_status rt_bvh_refit_prepare(const rt_bvh *bvh, rt_bvh_refit_info *info);
void rt_bvh_refit_info_free(rt_bvh_refit_info *info);

/* Recomputes every box of bvh from prim_boxes (indexed by the primitive ids
 * of bvh->prim_indices, as at the build) on pool's workers (pool NULL: this
 * thread). info must come from rt_bvh_refit_prepare on this tree. */
void rt_bvh_refit(rt_bvh *bvh, rt_bvh_refit_info *info, const rt_aabb *prim_boxes, rt_pool *pool);

/* The same, with each primitive a triangle (3 vertex indices into positions,
 * 3 floats per vertex): the leaves' boxes come straight from the vertices,
 * with no box per triangle in between. */
void rt_bvh_refit_tris(rt_bvh *bvh, rt_bvh_refit_info *info, const float *positions,
                       const uint32_t *indices, rt_pool *pool);

#endif /* RT_BVH_REFIT_H */
