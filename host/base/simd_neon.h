/* SPDX-License-Identifier: Apache-2.0 */
/* simd_neon.h - the one door to SIMD: NEON intrinsics everywhere.
 *
 * On ARM this is <arm_neon.h>; elsewhere SIMDe's NEON implementation provides
 * the same names, so the NEON code is the code that runs on every machine. */
#ifndef RT_SIMD_NEON_H
#define RT_SIMD_NEON_H

#if defined(__ARM_NEON) || defined(__aarch64__)
#include <arm_neon.h>
#define RT_NEON_NATIVE 1
#else
#define SIMDE_ENABLE_NATIVE_ALIASES
#include <simde/arm/neon.h>
#define RT_NEON_NATIVE 0
#endif

#include <stdint.h>

/* Bit l of the result is set when lane l of m (a comparison result: all ones
 * or all zeros per lane) is set. NEON has no movemask: aarch64 adds the lanes
 * after masking them to their bit; on x86 SIMDe's vector is an SSE register,
 * whose sign bits movemask reads in one instruction. */
static inline uint32_t rt_lane_bits(uint32x4_t m) {
#if defined(__aarch64__)
    static const uint32_t bit[4] = {1, 2, 4, 8};
    return vaddvq_u32(vandq_u32(m, vld1q_u32(bit)));
#elif !RT_NEON_NATIVE && defined(SIMDE_X86_SSE2_NATIVE)
    return (uint32_t)_mm_movemask_ps(_mm_castsi128_ps(simde_uint32x4_to_m128i(m)));
#else
    return (vgetq_lane_u32(m, 0) & 1u) | (vgetq_lane_u32(m, 1) & 2u) | (vgetq_lane_u32(m, 2) & 4u) |
           (vgetq_lane_u32(m, 3) & 8u);
#endif
}

/* IEEE division of four lanes (aarch64's vdivq_f32, which this SIMDe
 * lacks): correctly rounded, so each lane equals the scalar a / b. */
static inline float32x4_t rt_div_f32(float32x4_t a, float32x4_t b) {
#if defined(__aarch64__)
    return vdivq_f32(a, b);
#elif !RT_NEON_NATIVE && defined(SIMDE_X86_SSE_NATIVE)
    return simde_float32x4_from_m128(
        _mm_div_ps(simde_float32x4_to_m128(a), simde_float32x4_to_m128(b)));
#else
    float x[4], y[4];
    vst1q_f32(x, a);
    vst1q_f32(y, b);
    for (int i = 0; i < 4; i++) x[i] = x[i] / y[i];
    return vld1q_f32(x);
#endif
}

#endif /* RT_SIMD_NEON_H */
