/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_thesis_kernels.h - the two inner loops of the thesis builder, scalar and
 * NEON (Langr 2016 setup 2 vectorises exactly these: the centroid bounds and
 * the bin indices, four primitives at a time).
 *
 * Both versions must give identical results so that the two setups build the
 * same tree node for node: min/max are exact, and the bin index is the same
 * three float operations (subtract, multiply, truncate) in the same order, with
 * no fused multiply-add (-ffp-contract=off, and no vfmaq).
 */
#ifndef RT_BVH_THESIS_KERNELS_H
#define RT_BVH_THESIS_KERNELS_H

#include <stdint.h>

/* The bin of one centroid coordinate c: (int)((c - cmin) * scale), at most
 * last. c >= cmin and scale = bins * (1 - eps) / extent keep the product in
 * [0, bins), so the conversion never overflows. */
static inline uint32_t rt_thesis_bin_of(float c, float cmin, float scale, int32_t last) {
    int32_t k = (int32_t)((c - cmin) * scale);
    return (uint32_t)(k < last ? k : last);
}

/* Bounds of the centroids cent[axis][start..end) on each axis. */
void rt_thesis_centroid_bounds_scalar(float *const cent[3], uint32_t start, uint32_t end,
                                      float cmin[3], float cmax[3]);
void rt_thesis_centroid_bounds_neon(float *const cent[3], uint32_t start, uint32_t end,
                                    float cmin[3], float cmax[3]);

/* ids[i] = rt_thesis_bin_of(c[i], cmin, scale, last) for i in start..end. */
void rt_thesis_bin_ids_scalar(const float *c, uint32_t start, uint32_t end, float cmin, float scale,
                              int32_t last, uint8_t *ids);
void rt_thesis_bin_ids_neon(const float *c, uint32_t start, uint32_t end, float cmin, float scale,
                            int32_t last, uint8_t *ids);

#endif /* RT_BVH_THESIS_KERNELS_H */
