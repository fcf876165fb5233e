/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_internal.h - entry points of the individual builders behind rt_bvh_build. */
#ifndef RT_BVH_INTERNAL_H
#define RT_BVH_INTERNAL_H

#include "accel/bvh.h"

/* The thesis builder (bvh_thesis.c): setups RT_BUILDER_THESIS_SCALAR, _NEON, _MT. */
rt_status rt_bvh_build_thesis(const rt_aabb *boxes, uint32_t count, const rt_build_options *options,
                              rt_pool *pool, rt_bvh *out, rt_error *err);

/* The SAH builder (bvh_sah.c). use_neon selects the NEON binning path; the
 * output is identical either way and for any thread count. */
rt_status rt_bvh_build_sah(const rt_aabb *boxes, uint32_t count, const rt_build_options *options,
                           rt_pool *pool, int use_neon, rt_bvh *out, rt_error *err);

/* The same over count triangles' boxes (rt_tri_box), computed as the build
 * sets up instead of read from an array. */
rt_status rt_bvh_build_sah_tris(const float *positions, const uint32_t *indices, uint32_t count,
                                const rt_build_options *options, rt_pool *pool, int use_neon,
                                rt_bvh *out, rt_error *err);

/* The Morton-code LBVH (bvh_lbvh.c): leaves of at most 4 primitives; the
 * same tree for any thread count. options' bins and leaf size are unused. */
rt_status rt_bvh_build_lbvh(const rt_aabb *boxes, uint32_t count, const rt_build_options *options,
                            rt_pool *pool, rt_bvh *out, rt_error *err);

/* The SAH builder keeps its scratch memory (up to 64 MiB) between builds;
 * this frees it now (it is otherwise reused or held until exit). */
void rt_bvh_sah_release_scratch(void);

#endif /* RT_BVH_INTERNAL_H */
