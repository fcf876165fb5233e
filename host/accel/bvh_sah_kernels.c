/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_sah_kernels.c - binning and partitioning loops of the SAH builder,
 * scalar and NEON (see bvh_sah_kernels.h for why they agree bit for bit). */
#include "accel/bvh_sah_kernels.h"

#include <float.h>
#include <stddef.h>

/* Inputs are finite and in range (checked at setup), so SIMDe may skip the
 * NaN and saturation fix-ups it otherwise adds to min/max and conversions on
 * x86; on ARM these macros do nothing. */
#define SIMDE_FAST_NANS
#define SIMDE_FAST_CONVERSION_RANGE
#include "base/simd_neon.h"

static inline float fmin_exact(float a, float b) {
    return a < b ? a : b;
}
static inline float fmax_exact(float a, float b) {
    return a > b ? a : b;
}

static inline float centroid_scalar(const rt_sah_ref *r, int axis) {
    return r->lo[axis] * 0.5f + r->hi[axis] * 0.5f;
}

static inline int bin_scalar(float c, const rt_sah_binning *bn, int axis) {
    int k = (int)((c - bn->cmin[axis]) * bn->scale[axis]);
    return k < bn->bins - 1 ? k : bn->bins - 1;
}

void rt_sah_bins_clear(rt_sah_bins *bins, int bin_count) {
    for (int a = 0; a < 3; a++) {
        for (int k = 0; k < bin_count; k++) {
            for (int i = 0; i < 4; i++) {
                bins->box[a][k].lo[i] = FLT_MAX;
                bins->box[a][k].hi[i] = -FLT_MAX;
            }
            bins->count[k][a] = 0;
        }
    }
}

/* ---- SAH sweep ------------------------------------------------------------ */

/* Scaled half extents of a box: (hi * 0.5 - lo * 0.5) * scale (halved first
 * so that no finite box overflows). */
static inline float32x4_t scaled_extent(float32x4_t lo, float32x4_t hi, float32x4_t scale) {
    const float32x4_t half = vdupq_n_f32(0.5f);
    return vmulq_f32(vsubq_f32(vmulq_f32(hi, half), vmulq_f32(lo, half)), scale);
}

/* Half areas of three boxes given by their extents: lane a is box a's.
 * The transposition uses full-width zips only (they map to single
 * unpack instructions on x86 through SIMDe, unlike 64-bit halves). */
static inline float32x4_t areas3(float32x4_t d0, float32x4_t d1, float32x4_t d2) {
    float32x4_t z0 = vzip1q_f32(d0, d2); /* x0 x2 y0 y2 */
    float32x4_t z1 = vzip2q_f32(d0, d2); /* z0 z2 w0 w2 */
    float32x4_t z2 = vzip1q_f32(d1, d1); /* x1 x1 y1 y1 */
    float32x4_t z3 = vzip2q_f32(d1, d1); /* z1 z1 w1 w1 */
    float32x4_t dx = vzip1q_f32(z0, z2); /* x0 x1 x2 x1 */
    float32x4_t dy = vzip2q_f32(z0, z2); /* y0 y1 y2 y1 */
    float32x4_t dz = vzip1q_f32(z1, z3); /* z0 z1 z2 z1 */
    return vaddq_f32(vaddq_f32(vmulq_f32(dx, dy), vmulq_f32(dy, dz)), vmulq_f32(dz, dx));
}

float rt_sah_scaled_area(const float lo[3], const float hi[3], float scale) {
    float d[3];
    for (int j = 0; j < 3; j++) d[j] = (hi[j] * 0.5f - lo[j] * 0.5f) * scale;
    return (d[0] * d[1] + d[1] * d[2]) + d[2] * d[0];
}

int rt_sah_sweep(const rt_sah_bins *bins, const rt_sah_binning *bn, float scale, float *best_cost,
                 int *best_axis, int *best_bin) {
    const int B = bn->bins;
    const float32x4_t s = vdupq_n_f32(scale);
    const float32x4_t inf = vdupq_n_f32(__builtin_inff());
    float32x4_t right_area[FAST_MAX_BINS];
    uint32x4_t right_count[FAST_MAX_BINS];
    /* right_*[k]: bins k+1..B-1, for the three axes in lanes 0..2. */
    float32x4_t lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = vdupq_n_f32(FLT_MAX);
        hi[a] = vdupq_n_f32(-FLT_MAX);
    }
    uint32x4_t cnt = vdupq_n_u32(0);
    for (int k = B - 1; k > 0; k--) {
        for (int a = 0; a < 3; a++) {
            lo[a] = vminq_f32(lo[a], vld1q_f32(bins->box[a][k].lo));
            hi[a] = vmaxq_f32(hi[a], vld1q_f32(bins->box[a][k].hi));
        }
        cnt = vaddq_u32(cnt, vld1q_u32(bins->count[k]));
        right_count[k - 1] = cnt;
        right_area[k - 1] = areas3(scaled_extent(lo[0], hi[0], s), scaled_extent(lo[1], hi[1], s),
                                   scaled_extent(lo[2], hi[2], s));
    }
    const uint32_t ok_bits[4] = {bn->axis_ok[0] ? ~0u : 0u, bn->axis_ok[1] ? ~0u : 0u,
                                 bn->axis_ok[2] ? ~0u : 0u, 0u};
    const uint32x4_t axis_ok = vld1q_u32(ok_bits);
    const uint32x4_t zero = vdupq_n_u32(0);
    float32x4_t best = inf;
    uint32x4_t best_k = zero;
    for (int a = 0; a < 3; a++) {
        lo[a] = vdupq_n_f32(FLT_MAX);
        hi[a] = vdupq_n_f32(-FLT_MAX);
    }
    cnt = zero;
    for (int k = 0; k < B - 1; k++) {
        for (int a = 0; a < 3; a++) {
            lo[a] = vminq_f32(lo[a], vld1q_f32(bins->box[a][k].lo));
            hi[a] = vmaxq_f32(hi[a], vld1q_f32(bins->box[a][k].hi));
        }
        cnt = vaddq_u32(cnt, vld1q_u32(bins->count[k]));
        float32x4_t left_area =
            areas3(scaled_extent(lo[0], hi[0], s), scaled_extent(lo[1], hi[1], s),
                   scaled_extent(lo[2], hi[2], s));
        float32x4_t cost = vaddq_f32(
            vmulq_f32(left_area, vcvtq_f32_s32(vreinterpretq_s32_u32(cnt))),
            vmulq_f32(right_area[k], vcvtq_f32_s32(vreinterpretq_s32_u32(right_count[k]))));
        /* Both sides non-empty, axis binnable; the empty sides' areas are
         * not finite, so those lanes are replaced before the compare. */
        uint32x4_t valid =
            vandq_u32(axis_ok, vandq_u32(vmvnq_u32(vceqq_u32(cnt, zero)),
                                         vmvnq_u32(vceqq_u32(right_count[k], zero))));
        cost = vbslq_f32(valid, cost, inf);
        uint32x4_t better = vcltq_f32(cost, best);
        best = vbslq_f32(better, cost, best);
        best_k = vbslq_u32(better, vdupq_n_u32((uint32_t)k), best_k);
    }
    float bc[4];
    uint32_t bk[4];
    vst1q_f32(bc, best);
    vst1q_u32(bk, best_k);
    int axis = -1;
    for (int a = 0; a < 3; a++)
        if (bc[a] < __builtin_inff() && (axis < 0 || bc[a] < bc[axis])) axis = a;
    if (axis < 0) return 0;
    *best_cost = bc[axis];
    *best_axis = axis;
    *best_bin = (int)bk[axis];
    return 1;
}

void rt_sah_cbounds_empty(rt_sah_cbounds *cb) {
    for (int i = 0; i < 4; i++) {
        cb->cmin[i] = FLT_MAX;
        cb->cmax[i] = -FLT_MAX;
    }
}

void rt_sah_cbounds_merge(rt_sah_cbounds *into, const rt_sah_cbounds *from) {
    for (int i = 0; i < 3; i++) {
        into->cmin[i] = fmin_exact(into->cmin[i], from->cmin[i]);
        into->cmax[i] = fmax_exact(into->cmax[i], from->cmax[i]);
    }
}

void rt_sah_centroid_bounds(const rt_sah_ref *refs, uint32_t begin, uint32_t end,
                            rt_sah_cbounds *cb) {
    rt_sah_cbounds_empty(cb);
    for (uint32_t i = begin; i < end; i++) {
        for (int a = 0; a < 3; a++) {
            float c = centroid_scalar(&refs[i], a);
            cb->cmin[a] = fmin_exact(cb->cmin[a], c);
            cb->cmax[a] = fmax_exact(cb->cmax[a], c);
        }
    }
}

/* ---- scalar ----------------------------------------------------------- */

static void bin_range_scalar(const rt_sah_ref *refs, uint32_t begin, uint32_t end,
                             const rt_sah_binning *bn, rt_sah_bins *bins) {
    for (uint32_t i = begin; i < end; i++) {
        const rt_sah_ref *r = &refs[i];
        for (int a = 0; a < 3; a++) {
            int k = bin_scalar(centroid_scalar(r, a), bn, a);
            rt_sah_box4 *b = &bins->box[a][k];
            for (int j = 0; j < 3; j++) {
                b->lo[j] = fmin_exact(b->lo[j], r->lo[j]);
                b->hi[j] = fmax_exact(b->hi[j], r->hi[j]);
            }
            bins->count[k][a]++;
        }
    }
}

static void partition_range_scalar(const rt_sah_ref *src, uint32_t begin, uint32_t end,
                                   rt_sah_ref *dst, uint32_t left, uint32_t right,
                                   const rt_sah_binning *bn, int axis, int split,
                                   rt_sah_cbounds *lcb, rt_sah_cbounds *rcb) {
    for (uint32_t i = begin; i < end; i++) {
        const rt_sah_ref *r = &src[i];
        float c[3] = {centroid_scalar(r, 0), centroid_scalar(r, 1), centroid_scalar(r, 2)};
        rt_sah_cbounds *cb;
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

static inline float32x4_t centroid_neon(const rt_sah_ref *r, float32x4_t *lo_out,
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

static void bin_range_neon(const rt_sah_ref *refs, uint32_t begin, uint32_t end,
                           const rt_sah_binning *bn, rt_sah_bins *bins) {
    const float32x4_t cmin = vld1q_f32(bn->cmin);
    const float32x4_t scale = vld1q_f32(bn->scale);
    const float32x4_t last = vdupq_n_f32((float)(bn->bins - 1));
    /* Byte offsets of the three axes' bins, computed in the vector: box k of
     * axis a is at k * 32 + a * FAST_MAX_BINS * 32; its count at half that
     * minus a * (FAST_MAX_BINS * 16 - 4). This saves the scalar address
     * arithmetic of each axis (the loop is about 60 instructions a
     * primitive). */
    enum { BOX_BYTES = (int)sizeof(rt_sah_box4), AXIS_BYTES = FAST_MAX_BINS * BOX_BYTES };
    _Static_assert(sizeof(rt_sah_box4) == 32, "box offsets are k << 5");
    const int32_t axis_bytes[4] = {0, AXIS_BYTES, 2 * AXIS_BYTES, 0};
    const int32x4_t axis_off = vld1q_s32(axis_bytes);
    char *box_base = (char *)bins->box;
    char *count_base = (char *)bins->count;
    for (uint32_t i = begin; i < end; i++) {
        float32x4_t lo, hi;
        float32x4_t c = centroid_neon(&refs[i], &lo, &hi);
        int32x4_t k = vcvtq_s32_f32(vminq_f32(vmulq_f32(vsubq_f32(c, cmin), scale), last));
        int32_t off[4];
        vst1q_s32(off, vaddq_s32(vshlq_n_s32(k, 5), axis_off));
        for (int a = 0; a < 3; a++) {
            uint32_t o = (uint32_t)off[a];
            rt_sah_box4 *b = (rt_sah_box4 *)(box_base + o);
            vst1q_f32(b->lo, vminq_f32(vld1q_f32(b->lo), lo));
            vst1q_f32(b->hi, vmaxq_f32(vld1q_f32(b->hi), hi));
            uint32_t *count = (uint32_t *)(count_base + (o >> 1) -
                                           (size_t)a * (AXIS_BYTES / 2 - sizeof(uint32_t)));
            (*count)++;
        }
    }
}

static void partition_range_neon(const rt_sah_ref *src, uint32_t begin, uint32_t end,
                                 rt_sah_ref *dst, uint32_t left, uint32_t right,
                                 const rt_sah_binning *bn, int axis, int split, rt_sah_cbounds *lcb,
                                 rt_sah_cbounds *rcb) {
    /* The side test is on the split axis only, in float: for x >= 0,
     * trunc(x) <= split exactly when x < split + 1 (split < bins - 1, so the
     * clamp to the last bin does not matter; split + 1 is exact). */
    const float limit = (float)(split + 1);
    const float cmin_a = bn->cmin[axis], scale_a = bn->scale[axis];
    float32x4_t lmin = vld1q_f32(lcb->cmin), lmax = vld1q_f32(lcb->cmax);
    float32x4_t rmin = vld1q_f32(rcb->cmin), rmax = vld1q_f32(rcb->cmax);
    for (uint32_t i = begin; i < end; i++) {
        float32x4_t lo, hi;
        float32x4_t c = centroid_neon(&src[i], &lo, &hi);
        if ((centroid_scalar(&src[i], axis) - cmin_a) * scale_a < limit) {
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

void rt_sah_bin_range(const rt_sah_ref *refs, uint32_t begin, uint32_t end,
                      const rt_sah_binning *bn, rt_sah_bins *bins, int use_neon) {
    if (use_neon)
        bin_range_neon(refs, begin, end, bn, bins);
    else
        bin_range_scalar(refs, begin, end, bn, bins);
}

void rt_sah_partition_range(const rt_sah_ref *src, uint32_t begin, uint32_t end, rt_sah_ref *dst,
                            uint32_t left, uint32_t right, const rt_sah_binning *bn, int axis,
                            int split, rt_sah_cbounds *lcb, rt_sah_cbounds *rcb, int use_neon) {
    if (use_neon)
        partition_range_neon(src, begin, end, dst, left, right, bn, axis, split, lcb, rcb);
    else
        partition_range_scalar(src, begin, end, dst, left, right, bn, axis, split, lcb, rcb);
}
