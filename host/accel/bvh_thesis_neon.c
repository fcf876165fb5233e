/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_thesis_neon.c - the thesis builder's inner loops, scalar and NEON.
 *
 * The NEON loops take four primitives per step from the structure-of-arrays
 * centroids and finish the last 0..3 with the scalar code. */
#include "accel/bvh_thesis_kernels.h"

/* Off ARM, SIMDe reproduces NEON's answers for NaN operands and for float to
 * int conversions out of range, at a cost. Neither happens here: boxes are
 * checked finite before building, and (c - cmin) * scale is in [0, bins). So
 * SIMDe may use the plain x86 instructions. (No effect on ARM.) */
#define SIMDE_FAST_NANS
#define SIMDE_FAST_CONVERSION_RANGE
#include "base/simd_neon.h"

#include <string.h>

/* Widens [*lo, *hi] over c[i] for i in [from, end). */
static void widen_scalar(const float *c, uint32_t from, uint32_t end, float *lo, float *hi) {
    float l = *lo, h = *hi;
    for (uint32_t i = from; i < end; i++) {
        l = c[i] < l ? c[i] : l;
        h = c[i] > h ? c[i] : h;
    }
    *lo = l;
    *hi = h;
}

void rt_thesis_centroid_bounds_scalar(float *const cent[3], uint32_t start, uint32_t end,
                                      float cmin[3], float cmax[3]) {
    for (int k = 0; k < 3; k++) {
        cmin[k] = cmax[k] = cent[k][start];
        widen_scalar(cent[k], start + 1, end, &cmin[k], &cmax[k]);
    }
}

void rt_thesis_bin_ids_scalar(const float *c, uint32_t start, uint32_t end, float cmin, float scale,
                              int32_t last, uint8_t *ids) {
    for (uint32_t i = start; i < end; i++)
        ids[i] = (uint8_t)rt_thesis_bin_of(c[i], cmin, scale, last);
}

/* Minimum and maximum of the four lanes (min/max are exact, so the order of
 * the reduction does not matter). */
static float lanes_min(float32x4_t v) {
    float32x2_t m = vmin_f32(vget_low_f32(v), vget_high_f32(v));
    m = vpmin_f32(m, m);
    return vget_lane_f32(m, 0);
}

static float lanes_max(float32x4_t v) {
    float32x2_t m = vmax_f32(vget_low_f32(v), vget_high_f32(v));
    m = vpmax_f32(m, m);
    return vget_lane_f32(m, 0);
}

void rt_thesis_centroid_bounds_neon(float *const cent[3], uint32_t start, uint32_t end,
                                    float cmin[3], float cmax[3]) {
    if (end - start < 8) {
        rt_thesis_centroid_bounds_scalar(cent, start, end, cmin, cmax);
        return;
    }
    for (int k = 0; k < 3; k++) {
        const float *c = cent[k];
        float32x4_t lo = vld1q_f32(c + start), hi = lo;
        uint32_t i = start + 4;
        for (; i + 4 <= end; i += 4) {
            float32x4_t v = vld1q_f32(c + i);
            lo = vminq_f32(lo, v);
            hi = vmaxq_f32(hi, v);
        }
        cmin[k] = lanes_min(lo);
        cmax[k] = lanes_max(hi);
        widen_scalar(c, i, end, &cmin[k], &cmax[k]);
    }
}

void rt_thesis_bin_ids_neon(const float *c, uint32_t start, uint32_t end, float cmin, float scale,
                            int32_t last, uint8_t *ids) {
    const float32x4_t vmin = vdupq_n_f32(cmin), vscale = vdupq_n_f32(scale);
    const int32x4_t vlast = vdupq_n_s32(last);
    uint32_t i = start;
    for (; i + 4 <= end; i += 4) {
        /* Same operations as rt_thesis_bin_of: subtract, multiply, truncate
         * toward zero (vcvtq_s32_f32 truncates like a C cast), clamp. */
        float32x4_t t = vmulq_f32(vsubq_f32(vld1q_f32(c + i), vmin), vscale);
        int32x4_t k = vminq_s32(vcvtq_s32_f32(t), vlast);
        /* Narrow 32 -> 16 -> 8 bits; the values are below 256. */
        uint16x4_t k16 = vmovn_u32(vreinterpretq_u32_s32(k));
        uint8x8_t k8 = vmovn_u16(vcombine_u16(k16, k16));
        uint8_t lanes[8];
        vst1_u8(lanes, k8);
        memcpy(ids + i, lanes, 4);
    }
    for (; i < end; i++) ids[i] = (uint8_t)rt_thesis_bin_of(c[i], cmin, scale, last);
}
