/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_sah_kernels.h - the inner loops of the SAH builder: binning and
 * partitioning one range of primitive references, in a scalar and a NEON
 * version that produce the same bits.
 *
 * Why the two paths agree bit for bit: the centroid (lo * 0.5 + hi * 0.5),
 * the bin index ((c - cmin) * scale, truncated) and the bin bounds (min/max)
 * are the same IEEE operations in the same order in both, FMA contraction is
 * off, inputs are finite and negative zeros are turned into positive zeros on
 * the way in (so min/max never has to choose between -0 and +0). Min and max
 * are exact, so merging the bins of several threads cannot change a bit
 * either, whatever the chunking.
 */
#ifndef RT_BVH_SAH_KERNELS_H
#define RT_BVH_SAH_KERNELS_H

#include <stdint.h>

enum { FAST_MAX_BINS = 256 };

/* One primitive reference, 32 bytes: its box, with the primitive index stored
 * in the bits of lo[3] (hi[3] is 0). References move with the partition so
 * that the loops stream through memory instead of gathering. */
typedef struct rt_sah_ref {
    float lo[4];
    float hi[4];
} rt_sah_ref;

typedef struct rt_sah_box4 {
    float lo[4];
    float hi[4];
} rt_sah_box4;

/* Bins over all three axes; lane 3 of the boxes is unused. count[k][a] is
 * bin k of axis a (the three axes side by side for the vector sweep; lane 3
 * unused). */
typedef struct rt_sah_bins {
    rt_sah_box4 box[3][FAST_MAX_BINS];
    uint32_t count[FAST_MAX_BINS][4];
} rt_sah_bins;

/* How centroids map to bins in one node: bin = min((c - cmin) * scale, B-1).
 * An axis that cannot be binned (zero or non-finite extent) has cmin = 0 and
 * scale = 0, so every centroid lands in bin 0 there. Lane 3 is 0. */
typedef struct rt_sah_binning {
    float cmin[4];
    float scale[4];
    int bins;
    int axis_ok[3];
} rt_sah_binning;

/* Centroid bounds of a partition side (lane 3 unused). */
typedef struct rt_sah_cbounds {
    float cmin[4];
    float cmax[4];
} rt_sah_cbounds;

void rt_sah_bins_clear(rt_sah_bins *bins, int bin_count);

/* The SAH sweep over the bins of the three axes at once (one code path,
 * NEON, for the scalar and NEON builds alike). The cost of splitting after
 * bin k of axis a is area(left) * n_left + area(right) * n_right with the
 * areas (half surface areas) of boxes scaled by `scale` (a power of two per
 * node that keeps the float sums far from overflow) after halving.
 * Returns 0 when no axis has a split with both sides non-empty; otherwise
 * the lowest cost, ties going to the lower axis, then the lower bin. Axes
 * with axis_ok[a] == 0 are skipped. */
int rt_sah_sweep(const rt_sah_bins *bins, const rt_sah_binning *bn, float scale, float *best_cost,
                 int *best_axis, int *best_bin);

/* The scaled half area, as rt_sah_sweep computes it, of one box. */
float rt_sah_scaled_area(const float lo[3], const float hi[3], float scale);

/* Adds refs[begin, end) to bins. */
void rt_sah_bin_range(const rt_sah_ref *refs, uint32_t begin, uint32_t end,
                      const rt_sah_binning *bn, rt_sah_bins *bins, int use_neon);

/* Copies src[begin, end) to dst: references whose bin on axis is <= split go
 * to dst[left...], the others to dst[right...], both in their original order
 * (a stable partition, so the result does not depend on chunking). Grows the
 * two sides' centroid bounds. */
void rt_sah_partition_range(const rt_sah_ref *src, uint32_t begin, uint32_t end, rt_sah_ref *dst,
                            uint32_t left, uint32_t right, const rt_sah_binning *bn, int axis,
                            int split, rt_sah_cbounds *lcb, rt_sah_cbounds *rcb, int use_neon);

/* Centroid bounds of refs[begin, end) (scalar; used on the rare median
 * splits and at the root). */
void rt_sah_centroid_bounds(const rt_sah_ref *refs, uint32_t begin, uint32_t end,
                            rt_sah_cbounds *cb);

void rt_sah_cbounds_empty(rt_sah_cbounds *cb);
void rt_sah_cbounds_merge(rt_sah_cbounds *into, const rt_sah_cbounds *from);

#endif /* RT_BVH_SAH_KERNELS_H */
