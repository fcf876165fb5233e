/* SPDX-License-Identifier: Apache-2.0 */
/* simd.h - the CPU tracers' one door to vectors: 4, 8 or 16 lanes of float
 * or int32.
 *
 * The packet tracer (packet_trace.c, packet_kd.h), the single-ray tracer
 * (single_trace.c) and their shared triangle test (watertight_lanes.h) are
 * written over these types, GCC's and Clang's vector extensions: + - * /
 * and comparisons act on every lane in IEEE single precision
 * (-ffp-contract=off keeps them unfused) and compile to one instruction per
 * operation at the widths the target has (two halves, or four quarters,
 * where it has narrower registers). What the extensions lack or compile
 * poorly (a broadcast, a select, min and max with x86's NaN rule, a
 * comparison's lanes as a bit mask) is one SIMDe x86 intrinsic of the
 * lane width: the instruction itself where the build's target has it (each
 * tracer is compiled once per instruction set, cpu_isa.h), SIMDe's exact
 * translation elsewhere (SSE2 halves for 8 lanes, NEON on aarch64). Where a
 * target has a shorter idiom than SIMDe's translation (a select without
 * blendv, NEON's lane mask, AVX-512's reductions), the function says so.
 *
 * rt_vN* (N = 4, 8, 16) exist in every build; rt_vf, rt_vi and the
 * unsuffixed operations (rt_vsplat, rt_vmin_of, ...) have RT_VN lanes: the
 * widest native vector of the build (16 with AVX-512, 8 with AVX2, else 4)
 * unless the includer defines RT_VN first (the single-ray tracer: its node
 * width). RT_VOP(N, op) names rt_vN_op, RT_VF(N) and RT_VI(N) its types. */
#ifndef RT_CPU_SIMD_H
#define RT_CPU_SIMD_H

#include <stdint.h>
#include <string.h>

#include <simde/x86/avx.h>
#include <simde/x86/avx512/cmpgt.h>
#include <simde/x86/avx512/max.h>
#include <simde/x86/avx512/min.h>
#include <simde/x86/avx512/set1.h>
#include <simde/x86/avx512/setzero.h>
#include <simde/x86/avx512/ternarylogic.h>
#include <simde/x86/sse2.h>

#ifndef RT_VN
#if defined(SIMDE_X86_AVX512F_NATIVE)
#define RT_VN 16
#elif defined(SIMDE_X86_AVX2_NATIVE)
#define RT_VN 8
#else
#define RT_VN 4
#endif
#endif

#define RT_VCAT_(a, b, c) a##b##c
#define RT_VCAT(a, b, c)  RT_VCAT_(a, b, c)
#define RT_VOP(n, op)     RT_VCAT(rt_v, n, _##op)
#define RT_VF(n)          RT_VCAT(rt_v, n, f)
#define RT_VI(n)          RT_VCAT(rt_v, n, i)

/* Lanes of float and of int32 (a comparison's result: -1 or 0 per lane). */
typedef float rt_v4f __attribute__((vector_size(16)));
typedef int32_t rt_v4i __attribute__((vector_size(16)));
typedef float rt_v8f __attribute__((vector_size(32)));
typedef int32_t rt_v8i __attribute__((vector_size(32)));
typedef float rt_v16f __attribute__((vector_size(64)));
typedef int32_t rt_v16i __attribute__((vector_size(64)));

/* ---- per width: the operations that take an intrinsic --------------------
 *
 * rt_vN_splat(x), rt_vN_splat_i(x): x in every lane (bit for bit: -0 stays
 *   -0).
 * rt_vN_min_of(a, b), rt_vN_max_of(a, b): the oracle's 'a < b ? a : b' and
 *   'a > b ? a : b' per lane (b where they are equal or either is NaN):
 *   exactly what x86's min and max instructions compute.
 * These are the same SIMDe call at every width (P the intrinsics' prefix,
 * T SIMDe's vector type):
 */
#define RT_SIMD_X86(N, P, T)                                                                       \
    static inline rt_v##N##f rt_v##N##_splat(float x) {                                            \
        return (rt_v##N##f)simde_##P##_set1_ps(x);                                                 \
    }                                                                                              \
    static inline rt_v##N##i rt_v##N##_splat_i(int32_t x) {                                        \
        return (rt_v##N##i)simde_##P##_set1_epi32(x);                                              \
    }                                                                                              \
    static inline rt_v##N##f rt_v##N##_min_of(rt_v##N##f a, rt_v##N##f b) {                        \
        return (rt_v##N##f)simde_##P##_min_ps((T)a, (T)b);                                         \
    }                                                                                              \
    static inline rt_v##N##f rt_v##N##_max_of(rt_v##N##f a, rt_v##N##f b) {                        \
        return (rt_v##N##f)simde_##P##_max_ps((T)a, (T)b);                                         \
    }
RT_SIMD_X86(4, mm, simde__m128)
RT_SIMD_X86(8, mm256, simde__m256)
RT_SIMD_X86(16, mm512, simde__m512)
#undef RT_SIMD_X86

/* rt_vN_sel(m, a, b): m ? a : b per lane, m a comparison result: blendv
 * (AVX), a ternary-logic instruction (AVX-512) or NEON's bit select where
 * the build has them, else and, and-not and or (SSE2 has no blendv; SIMDe's
 * stands in with one more instruction). */
static inline rt_v4f rt_v4_sel(rt_v4i m, rt_v4f a, rt_v4f b) {
#if defined(SIMDE_ARM_NEON_A32V7_NATIVE)
    return (rt_v4f)vbslq_f32((uint32x4_t)m, (float32x4_t)a, (float32x4_t)b);
#else
    return (rt_v4f)((m & (rt_v4i)a) | (~m & (rt_v4i)b));
#endif
}
static inline rt_v8f rt_v8_sel(rt_v8i m, rt_v8f a, rt_v8f b) {
#if defined(SIMDE_X86_AVX_NATIVE)
    return (rt_v8f)simde_mm256_blendv_ps((simde__m256)b, (simde__m256)a, (simde__m256)m);
#else
    return (rt_v8f)((m & (rt_v8i)a) | (~m & (rt_v8i)b));
#endif
}
static inline rt_v16f rt_v16_sel(rt_v16i m, rt_v16f a, rt_v16f b) {
#if defined(SIMDE_X86_AVX512F_NATIVE)
    return (rt_v16f)simde_mm512_ternarylogic_epi32((simde__m512i)m, (simde__m512i)a,
                                                   (simde__m512i)b, 0xca);
#else
    return (rt_v16f)((m & (rt_v16i)a) | (~m & (rt_v16i)b));
#endif
}

/* rt_vN_bits(m): bit l set where lane l of m (a comparison result) is: the
 * sign bits by movemask, by a compare into a mask register (16 lanes), or on
 * aarch64 each lane masked to its bit and the lanes added (shorter than
 * SIMDe's movemask, which shifts and extracts). */
static inline uint32_t rt_v4_bits(rt_v4i m) {
#if defined(SIMDE_ARM_NEON_A64V8_NATIVE)
    static const uint32_t bit[4] = {1, 2, 4, 8};
    return vaddvq_u32(vandq_u32((uint32x4_t)m, vld1q_u32(bit)));
#else
    return (uint32_t)simde_mm_movemask_ps((simde__m128)m);
#endif
}
static inline uint32_t rt_v8_bits(rt_v8i m) {
    return (uint32_t)simde_mm256_movemask_ps((simde__m256)m);
}
static inline uint32_t rt_v16_bits(rt_v16i m) {
    return (uint32_t)simde_mm512_cmpgt_epi32_mask(simde_mm512_setzero_si512(), (simde__m512i)m);
}

/* ---- per width: the same code at every width ------------------------------
 *
 * rt_vN_sel_i(m, a, b): rt_vN_sel of int32 lanes.
 * rt_vN_sel_sign(s, a, b): a where the sign bit of s is set, else b (-0 and
 *   a NaN with its sign bit count as negative).
 * rt_vN_mask(bits): the lanes of a bit mask as a comparison result.
 * rt_vN_abs(a): fabsf per lane, the sign bit cleared.
 * rt_vN_hmin(v), rt_vN_hmax(v): the least and the greatest lane (no lane
 *   NaN), by halving.
 * rt_vN_load(p), rt_vN_load_i(p): N floats or int32s from p (any
 *   alignment, any type of storage: through a may_alias type, one unaligned
 *   load; GCC compiles a memcpy from uint32_t words into a float vector as a
 *   load, a store and a reload). */
#define RT_SIMD_COMMON(N)                                                                          \
    static inline rt_v##N##i rt_v##N##_sel_i(rt_v##N##i m, rt_v##N##i a, rt_v##N##i b) {           \
        return (rt_v##N##i)rt_v##N##_sel(m, (rt_v##N##f)a, (rt_v##N##f)b);                         \
    }                                                                                              \
    static inline rt_v##N##i rt_v##N##_mask_generic(uint32_t bits) {                               \
        rt_v##N##i lane_bit;                                                                       \
        for (int i = 0; i < N; i++) lane_bit[i] = 1 << i;                                          \
        return (rt_v##N##_splat_i((int32_t)bits) & lane_bit) == lane_bit;                          \
    }                                                                                              \
    static inline rt_v##N##f rt_v##N##_abs(rt_v##N##f a) {                                         \
        return (rt_v##N##f)((rt_v##N##i)a & rt_v##N##_splat_i(0x7fffffff));                        \
    }                                                                                              \
    static inline float rt_v##N##_hmin_generic(rt_v##N##f v) {                                     \
        float a[N];                                                                                \
        memcpy(a, &v, sizeof a);                                                                   \
        for (int w = N / 2; w > 0; w /= 2)                                                         \
            for (int i = 0; i < w; i++) a[i] = a[i + w] < a[i] ? a[i + w] : a[i];                  \
        return a[0];                                                                               \
    }                                                                                              \
    static inline float rt_v##N##_hmax_generic(rt_v##N##f v) {                                     \
        float a[N];                                                                                \
        memcpy(a, &v, sizeof a);                                                                   \
        for (int w = N / 2; w > 0; w /= 2)                                                         \
            for (int i = 0; i < w; i++) a[i] = a[i + w] > a[i] ? a[i + w] : a[i];                  \
        return a[0];                                                                               \
    }                                                                                              \
    typedef float rt_v##N##f_any __attribute__((vector_size(4 * N), aligned(4), may_alias));       \
    typedef int32_t rt_v##N##i_any __attribute__((vector_size(4 * N), aligned(4), may_alias));     \
    static inline rt_v##N##f rt_v##N##_load(const void *p) {                                       \
        return *(const rt_v##N##f_any *)p;                                                         \
    }                                                                                              \
    static inline rt_v##N##i rt_v##N##_load_i(const void *p) {                                     \
        return *(const rt_v##N##i_any *)p;                                                         \
    }
RT_SIMD_COMMON(4)
RT_SIMD_COMMON(8)
RT_SIMD_COMMON(16)
#undef RT_SIMD_COMMON

static inline rt_v4i rt_v4_mask(uint32_t bits) {
    return rt_v4_mask_generic(bits);
}
static inline rt_v8i rt_v8_mask(uint32_t bits) {
    return rt_v8_mask_generic(bits);
}
static inline rt_v16i rt_v16_mask(uint32_t bits) {
#if defined(SIMDE_X86_AVX512F_NATIVE)
    return (rt_v16i)simde_mm512_maskz_set1_epi32((simde__mmask16)bits, -1);
#else
    return rt_v16_mask_generic(bits);
#endif
}

static inline float rt_v4_hmin(rt_v4f v) {
    return rt_v4_hmin_generic(v);
}
static inline float rt_v4_hmax(rt_v4f v) {
    return rt_v4_hmax_generic(v);
}
static inline float rt_v8_hmin(rt_v8f v) {
    return rt_v8_hmin_generic(v);
}
static inline float rt_v8_hmax(rt_v8f v) {
    return rt_v8_hmax_generic(v);
}
/* AVX-512's reductions (GCC's and Clang's immintrin.h; SIMDe 0.7 has none)
 * give the same least and greatest lane when no lane is NaN. */
static inline float rt_v16_hmin(rt_v16f v) {
#if defined(SIMDE_X86_AVX512F_NATIVE)
    return _mm512_reduce_min_ps((__m512)v);
#else
    return rt_v16_hmin_generic(v);
#endif
}
static inline float rt_v16_hmax(rt_v16f v) {
#if defined(SIMDE_X86_AVX512F_NATIVE)
    return _mm512_reduce_max_ps((__m512)v);
#else
    return rt_v16_hmax_generic(v);
#endif
}

static inline rt_v4f rt_v4_sel_sign(rt_v4f s, rt_v4f a, rt_v4f b) {
    return rt_v4_sel((rt_v4i)s < rt_v4_splat_i(0), a, b);
}
static inline rt_v8f rt_v8_sel_sign(rt_v8f s, rt_v8f a, rt_v8f b) {
#if defined(SIMDE_X86_AVX_NATIVE)
    /* blendv reads the sign bit itself. */
    return (rt_v8f)simde_mm256_blendv_ps((simde__m256)b, (simde__m256)a, (simde__m256)s);
#else
    return rt_v8_sel((rt_v8i)s < rt_v8_splat_i(0), a, b);
#endif
}
static inline rt_v16f rt_v16_sel_sign(rt_v16f s, rt_v16f a, rt_v16f b) {
    return rt_v16_sel((rt_v16i)s < rt_v16_splat_i(0), a, b);
}

/* ---- RT_VN lanes ----------------------------------------------------------- */

typedef RT_VF(RT_VN) rt_vf;
typedef RT_VI(RT_VN) rt_vi;
#define rt_vsplat    RT_VOP(RT_VN, splat)
#define rt_vsplat_i  RT_VOP(RT_VN, splat_i)
#define rt_vsel      RT_VOP(RT_VN, sel)
#define rt_vsel_i    RT_VOP(RT_VN, sel_i)
#define rt_vsel_sign RT_VOP(RT_VN, sel_sign)
#define rt_vmask     RT_VOP(RT_VN, mask)
#define rt_vmin_of   RT_VOP(RT_VN, min_of)
#define rt_vmax_of   RT_VOP(RT_VN, max_of)
#define rt_vhmin     RT_VOP(RT_VN, hmin)
#define rt_vhmax     RT_VOP(RT_VN, hmax)
#define rt_vabs      RT_VOP(RT_VN, abs)
#define rt_vbits     RT_VOP(RT_VN, bits)
#define rt_vload     RT_VOP(RT_VN, load)
#define rt_vload_i   RT_VOP(RT_VN, load_i)

/* ---- lane masks (bit l = lane l) ------------------------------------------ */

/* The lowest lane of m (m not 0). */
static inline int rt_lane_first(uint32_t m) {
    return __builtin_ctz(m);
}

/* How many of the lowest lanes are set in a row (slots and block lanes fill
 * the first lanes, so this counts them). */
static inline uint32_t rt_lane_run(uint32_t m) {
    return (uint32_t)__builtin_ctz(~m);
}

/* The number of lanes in m, a mask of RT_VN lanes (baseline x86-64 has no
 * popcount instruction, and GCC's call for it costs more than a table). */
static inline uint32_t rt_lane_count(uint32_t m) {
#if defined(__POPCNT__) || defined(__aarch64__)
    return (uint32_t)__builtin_popcount(m);
#else
    static const uint8_t n[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
    uint32_t c = 0;
    for (int i = 0; i < RT_VN; i += 4) c += n[(m >> i) & 15u];
    return c;
#endif
}

#endif /* RT_CPU_SIMD_H */
