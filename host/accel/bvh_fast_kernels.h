/* bvh_fast_kernels.h - the inner loops of the fast builder: binning and
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
#ifndef RT_BVH_FAST_KERNELS_H
#define RT_BVH_FAST_KERNELS_H

#include <stdint.h>

enum { FAST_MAX_BINS = 256 };

/* One primitive reference, 32 bytes: its box, with the primitive index stored
 * in the bits of lo[3] (hi[3] is 0). References move with the partition so
 * that the loops stream through memory instead of gathering. */
typedef struct fast_ref {
    float lo[4];
    float hi[4];
} fast_ref;

typedef struct fast_box4 {
    float lo[4];
    float hi[4];
} fast_box4;

/* Bins over all three axes; lane 3 of the boxes is unused. count[k][a] is
 * bin k of axis a (the three axes side by side for the vector sweep; lane 3
 * unused). */
typedef struct fast_bins {
    fast_box4 box[3][FAST_MAX_BINS];
    uint32_t count[FAST_MAX_BINS][4];
} fast_bins;

/* How centroids map to bins in one node: bin = min((c - cmin) * scale, B-1).
 * An axis that cannot be binned (zero or non-finite extent) has cmin = 0 and
 * scale = 0, so every centroid lands in bin 0 there. Lane 3 is 0. */
typedef struct fast_binning {
    float cmin[4];
    float scale[4];
    int bins;
    int axis_ok[3];
} fast_binning;

/* Centroid bounds of a partition side (lane 3 unused). */
typedef struct fast_cbounds {
    float cmin[4];
    float cmax[4];
} fast_cbounds;

void fast_bins_clear(fast_bins *bins, int bin_count);

/* The SAH sweep over the bins of the three axes at once (one code path,
 * NEON, for the scalar and NEON builds alike). The cost of splitting after
 * bin k of axis a is area(left) * n_left + area(right) * n_right with the
 * areas (half surface areas) of boxes scaled by `scale` (a power of two per
 * node that keeps the float sums far from overflow) after halving.
 * Returns 0 when no axis has a split with both sides non-empty; otherwise
 * the lowest cost, ties going to the lower axis, then the lower bin. Axes
 * with axis_ok[a] == 0 are skipped. */
int fast_sweep(const fast_bins *bins, const fast_binning *bn, float scale, float *best_cost,
               int *best_axis, int *best_bin);

/* The scaled half area, as fast_sweep computes it, of one box. */
float fast_scaled_area(const float lo[3], const float hi[3], float scale);

/* Adds refs[begin, end) to bins. */
void fast_bin_range(const fast_ref *refs, uint32_t begin, uint32_t end, const fast_binning *bn,
                    fast_bins *bins, int use_neon);

/* Copies src[begin, end) to dst: references whose bin on axis is <= split go
 * to dst[left...], the others to dst[right...], both in their original order
 * (a stable partition, so the result does not depend on chunking). Grows the
 * two sides' centroid bounds. */
void fast_partition_range(const fast_ref *src, uint32_t begin, uint32_t end, fast_ref *dst,
                          uint32_t left, uint32_t right, const fast_binning *bn, int axis,
                          int split, fast_cbounds *lcb, fast_cbounds *rcb, int use_neon);

/* Centroid bounds of refs[begin, end) (scalar; used on the rare median
 * splits and at the root). */
void fast_centroid_bounds(const fast_ref *refs, uint32_t begin, uint32_t end, fast_cbounds *cb);

void fast_cbounds_empty(fast_cbounds *cb);
void fast_cbounds_merge(fast_cbounds *into, const fast_cbounds *from);

#endif /* RT_BVH_FAST_KERNELS_H */
