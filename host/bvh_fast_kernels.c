/* bvh_fast_kernels.c - binning and partitioning loops of the fast builder,
 * scalar and NEON (see bvh_fast_kernels.h for why they agree bit for bit). */
#include "bvh_fast_kernels.h"

#include <float.h>

/* Inputs are finite and in range (checked at setup), so SIMDe may skip the
 * NaN and saturation fix-ups it otherwise adds to min/max and conversions on
 * x86; on ARM these macros do nothing. */
#define SIMDE_FAST_NANS
#define SIMDE_FAST_CONVERSION_RANGE
#include "simd_neon.h"

static inline float fmin_exact(float a, float b) {
    return a < b ? a : b;
}
static inline float fmax_exact(float a, float b) {
    return a > b ? a : b;
}

static inline float centroid_scalar(const fast_ref *r, int axis) {
    return r->lo[axis] * 0.5f + r->hi[axis] * 0.5f;
}

static inline int bin_scalar(float c, const fast_binning *bn, int axis) {
    int k = (int)((c - bn->cmin[axis]) * bn->scale[axis]);
    return k < bn->bins - 1 ? k : bn->bins - 1;
}

void fast_bins_clear(fast_bins *bins, int bin_count) {
    for (int a = 0; a < 3; a++) {
        for (int k = 0; k < bin_count; k++) {
            for (int i = 0; i < 4; i++) {
                bins->box[a][k].lo[i] = FLT_MAX;
                bins->box[a][k].hi[i] = -FLT_MAX;
            }
            bins->count[a][k] = 0;
        }
    }
}

void fast_cbounds_empty(fast_cbounds *cb) {
    for (int i = 0; i < 4; i++) {
        cb->cmin[i] = FLT_MAX;
        cb->cmax[i] = -FLT_MAX;
    }
}

void fast_cbounds_merge(fast_cbounds *into, const fast_cbounds *from) {
    for (int i = 0; i < 3; i++) {
        into->cmin[i] = fmin_exact(into->cmin[i], from->cmin[i]);
        into->cmax[i] = fmax_exact(into->cmax[i], from->cmax[i]);
    }
}

void fast_centroid_bounds(const fast_ref *refs, uint32_t begin, uint32_t end, fast_cbounds *cb) {
    fast_cbounds_empty(cb);
    for (uint32_t i = begin; i < end; i++) {
        for (int a = 0; a < 3; a++) {
            float c = centroid_scalar(&refs[i], a);
            cb->cmin[a] = fmin_exact(cb->cmin[a], c);
            cb->cmax[a] = fmax_exact(cb->cmax[a], c);
        }
    }
}

/* ---- scalar ----------------------------------------------------------- */

static void bin_range_scalar(const fast_ref *refs, uint32_t begin, uint32_t end,
                             const fast_binning *bn, fast_bins *bins) {
    for (uint32_t i = begin; i < end; i++) {
        const fast_ref *r = &refs[i];
        for (int a = 0; a < 3; a++) {
            int k = bin_scalar(centroid_scalar(r, a), bn, a);
            fast_box4 *b = &bins->box[a][k];
            for (int j = 0; j < 3; j++) {
                b->lo[j] = fmin_exact(b->lo[j], r->lo[j]);
                b->hi[j] = fmax_exact(b->hi[j], r->hi[j]);
            }
            bins->count[a][k]++;
        }
    }
}

static void partition_range_scalar(const fast_ref *src, uint32_t begin, uint32_t end, fast_ref *dst,
                                   uint32_t left, uint32_t right, const fast_binning *bn, int axis,
                                   int split, fast_cbounds *lcb, fast_cbounds *rcb) {
    for (uint32_t i = begin; i < end; i++) {
        const fast_ref *r = &src[i];
        float c[3] = {centroid_scalar(r, 0), centroid_scalar(r, 1), centroid_scalar(r, 2)};
        fast_cbounds *cb;
        if (bin_scalar(c[axis], bn, axis) <= split) {
            dst[left++] = *r;
            cb = lcb;
        } else {
            dst[right++] = *r;
            cb = rcb;
        }
        for (int a = 0; a < 3; a++) {
            cb->cmin[a] = fmin_exact(cb->cmin[a], c[a]);
            cb->cmax[a] = fmax_exact(cb->cmax[a], c[a]);
        }
    }
}

/* ---- NEON --------------------------------------------------------------- */

static inline float32x4_t centroid_neon(const fast_ref *r, float32x4_t *lo_out,
                                        float32x4_t *hi_out) {
    /* lo[3] carries the primitive index: clear it so that no lane computes
     * with arbitrary bits (denormals would be slow, and lane 3 must stay 0). */
    static const uint32_t keep_xyz[4] = {~0u, ~0u, ~0u, 0u};
    float32x4_t lo = vreinterpretq_f32_u32(
        vandq_u32(vreinterpretq_u32_f32(vld1q_f32(r->lo)), vld1q_u32(keep_xyz)));
    float32x4_t hi = vld1q_f32(r->hi);
    const float32x4_t half = vdupq_n_f32(0.5f);
    *lo_out = lo;
    *hi_out = hi;
    return vaddq_f32(vmulq_f32(lo, half), vmulq_f32(hi, half));
}

static void bin_range_neon(const fast_ref *refs, uint32_t begin, uint32_t end,
                           const fast_binning *bn, fast_bins *bins) {
    const float32x4_t cmin = vld1q_f32(bn->cmin);
    const float32x4_t scale = vld1q_f32(bn->scale);
    const int32x4_t last = vdupq_n_s32(bn->bins - 1);
    for (uint32_t i = begin; i < end; i++) {
        float32x4_t lo, hi;
        float32x4_t c = centroid_neon(&refs[i], &lo, &hi);
        int32x4_t k = vminq_s32(vcvtq_s32_f32(vmulq_f32(vsubq_f32(c, cmin), scale)), last);
        int32_t kk[4];
        vst1q_s32(kk, k);
        for (int a = 0; a < 3; a++) {
            fast_box4 *b = &bins->box[a][kk[a]];
            vst1q_f32(b->lo, vminq_f32(vld1q_f32(b->lo), lo));
            vst1q_f32(b->hi, vmaxq_f32(vld1q_f32(b->hi), hi));
            bins->count[a][kk[a]]++;
        }
    }
}

static void partition_range_neon(const fast_ref *src, uint32_t begin, uint32_t end, fast_ref *dst,
                                 uint32_t left, uint32_t right, const fast_binning *bn, int axis,
                                 int split, fast_cbounds *lcb, fast_cbounds *rcb) {
    const float32x4_t cmin = vld1q_f32(bn->cmin);
    const float32x4_t scale = vld1q_f32(bn->scale);
    const int32x4_t last = vdupq_n_s32(bn->bins - 1);
    float32x4_t lmin = vld1q_f32(lcb->cmin), lmax = vld1q_f32(lcb->cmax);
    float32x4_t rmin = vld1q_f32(rcb->cmin), rmax = vld1q_f32(rcb->cmax);
    for (uint32_t i = begin; i < end; i++) {
        float32x4_t lo, hi;
        float32x4_t c = centroid_neon(&src[i], &lo, &hi);
        int32x4_t k = vminq_s32(vcvtq_s32_f32(vmulq_f32(vsubq_f32(c, cmin), scale)), last);
        int32_t kk[4];
        vst1q_s32(kk, k);
        if (kk[axis] <= split) {
            dst[left++] = src[i];
            lmin = vminq_f32(lmin, c);
            lmax = vmaxq_f32(lmax, c);
        } else {
            dst[right++] = src[i];
            rmin = vminq_f32(rmin, c);
            rmax = vmaxq_f32(rmax, c);
        }
    }
    vst1q_f32(lcb->cmin, lmin);
    vst1q_f32(lcb->cmax, lmax);
    vst1q_f32(rcb->cmin, rmin);
    vst1q_f32(rcb->cmax, rmax);
}

void fast_bin_range(const fast_ref *refs, uint32_t begin, uint32_t end, const fast_binning *bn,
                    fast_bins *bins, int use_neon) {
    if (use_neon)
        bin_range_neon(refs, begin, end, bn, bins);
    else
        bin_range_scalar(refs, begin, end, bn, bins);
}

void fast_partition_range(const fast_ref *src, uint32_t begin, uint32_t end, fast_ref *dst,
                          uint32_t left, uint32_t right, const fast_binning *bn, int axis,
                          int split, fast_cbounds *lcb, fast_cbounds *rcb, int use_neon) {
    if (use_neon)
        partition_range_neon(src, begin, end, dst, left, right, bn, axis, split, lcb, rcb);
    else
        partition_range_scalar(src, begin, end, dst, left, right, bn, axis, split, lcb, rcb);
}
