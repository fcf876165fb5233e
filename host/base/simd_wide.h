/* simd_wide.h - the widest native vectors of the build, for the packet
 * tracer.
 *
 * The packet tracer (cpu_ref/packet_trace.c) is written once over these
 * types, GCC's and Clang's vector extensions: + - * / and comparisons act on
 * every lane in IEEE single precision (-ffp-contract=off keeps them unfused),
 * one instruction per operation at the register width the build targets:
 * NEON (4 lanes) on ARM, SSE2 (4) on baseline x86-64, AVX2 (8), AVX-512 (16).
 * The packet tracer is compiled for each x86 width and the widest the CPU
 * has runs (cpu_ref/packet_dispatch.c). The one thing the extensions lack, a
 * comparison's lanes as a bit mask, is here per instruction set.
 */
#ifndef RT_SIMD_WIDE_H
#define RT_SIMD_WIDE_H

#include <stdint.h>
#include <string.h>

#if defined(__AVX512F__)
#include <immintrin.h>
#define RT_VN 16
#elif defined(__AVX2__)
#include <immintrin.h>
#define RT_VN 8
#elif defined(__SSE2__)
#include <emmintrin.h>
#define RT_VN 4
#elif defined(__aarch64__)
#include <arm_neon.h>
#define RT_VN 4
#else
#define RT_VN 4
#endif

/* RT_VN lanes of float and of int32 (a comparison's result: -1 or 0). */
typedef float rt_vf __attribute__((vector_size(4 * RT_VN)));
typedef int32_t rt_vi __attribute__((vector_size(4 * RT_VN)));

/* x in every lane, m ? a : b per lane (m a comparison result), and the
 * lanes of a bit mask as a comparison result: one instruction where the
 * instruction set has one (the extensions' generic forms compile to lane by
 * lane code for wide vectors). */
#if defined(__AVX512F__)
static inline rt_vf rt_vsplat(float x) {
    return (rt_vf)_mm512_set1_ps(x);
}
static inline rt_vi rt_vsplat_i(int32_t x) {
    return (rt_vi)_mm512_set1_epi32(x);
}
static inline rt_vf rt_vsel(rt_vi m, rt_vf a, rt_vf b) {
    return (rt_vf)_mm512_ternarylogic_epi32((__m512i)m, (__m512i)a, (__m512i)b, 0xca);
}
static inline rt_vi rt_vmask(uint32_t bits) {
    return (rt_vi)_mm512_maskz_set1_epi32((__mmask16)bits, -1);
}
#elif defined(__AVX2__)
static inline rt_vf rt_vsplat(float x) {
    return (rt_vf)_mm256_set1_ps(x);
}
static inline rt_vi rt_vsplat_i(int32_t x) {
    return (rt_vi)_mm256_set1_epi32(x);
}
static inline rt_vf rt_vsel(rt_vi m, rt_vf a, rt_vf b) {
    return (rt_vf)_mm256_blendv_ps((__m256)b, (__m256)a, (__m256)m);
}
#elif defined(__SSE2__)
static inline rt_vf rt_vsplat(float x) {
    return (rt_vf)_mm_set1_ps(x);
}
static inline rt_vi rt_vsplat_i(int32_t x) {
    return (rt_vi)_mm_set1_epi32(x);
}
#elif defined(__aarch64__)
static inline rt_vf rt_vsplat(float x) {
    return (rt_vf)vdupq_n_f32(x);
}
static inline rt_vi rt_vsplat_i(int32_t x) {
    return (rt_vi)vdupq_n_s32(x);
}
static inline rt_vf rt_vsel(rt_vi m, rt_vf a, rt_vf b) {
    return (rt_vf)vbslq_f32((uint32x4_t)m, (float32x4_t)a, (float32x4_t)b);
}
#else
static inline rt_vf rt_vsplat(float x) {
    rt_vf v;
    for (int i = 0; i < RT_VN; i++) v[i] = x;
    return v;
}
static inline rt_vi rt_vsplat_i(int32_t x) {
    rt_vi v;
    for (int i = 0; i < RT_VN; i++) v[i] = x;
    return v;
}
#endif
#if defined(__SSE2__) && !defined(__AVX2__) || !defined(__SSE2__) && !defined(__aarch64__)
static inline rt_vf rt_vsel(rt_vi m, rt_vf a, rt_vf b) {
    return (rt_vf)((m & (rt_vi)a) | (~m & (rt_vi)b));
}
#endif
#if !defined(__AVX512F__)
static inline rt_vi rt_vmask(uint32_t bits) {
    rt_vi lane_bit;
    for (int i = 0; i < RT_VN; i++) lane_bit[i] = 1 << i;
    return (rt_vsplat_i((int32_t)bits) & lane_bit) == lane_bit;
}
#endif

static inline rt_vi rt_vsel_i(rt_vi m, rt_vi a, rt_vi b) {
    return (rt_vi)rt_vsel(m, (rt_vf)a, (rt_vf)b);
}

/* The oracle's 'a > b ? a : b' and 'a < b ? a : b' per lane (b where they
 * are equal or either is NaN): exactly what x86's max and min instructions
 * compute. */
static inline rt_vf rt_vmax_of(rt_vf a, rt_vf b) {
#if defined(__AVX512F__)
    return (rt_vf)_mm512_max_ps((__m512)a, (__m512)b);
#elif defined(__AVX2__)
    return (rt_vf)_mm256_max_ps((__m256)a, (__m256)b);
#elif defined(__SSE2__)
    return (rt_vf)_mm_max_ps((__m128)a, (__m128)b);
#else
    return rt_vsel(a > b, a, b);
#endif
}

static inline rt_vf rt_vmin_of(rt_vf a, rt_vf b) {
#if defined(__AVX512F__)
    return (rt_vf)_mm512_min_ps((__m512)a, (__m512)b);
#elif defined(__AVX2__)
    return (rt_vf)_mm256_min_ps((__m256)a, (__m256)b);
#elif defined(__SSE2__)
    return (rt_vf)_mm_min_ps((__m128)a, (__m128)b);
#else
    return rt_vsel(a < b, a, b);
#endif
}

/* The least and the greatest lane of v (no lane NaN). */
static inline float rt_vhmin(rt_vf v) {
#if defined(__AVX512F__)
    return _mm512_reduce_min_ps((__m512)v);
#else
    float a[RT_VN];
    memcpy(a, &v, sizeof a);
    for (int w = RT_VN / 2; w > 0; w /= 2)
        for (int i = 0; i < w; i++) a[i] = a[i + w] < a[i] ? a[i + w] : a[i];
    return a[0];
#endif
}

static inline float rt_vhmax(rt_vf v) {
#if defined(__AVX512F__)
    return _mm512_reduce_max_ps((__m512)v);
#else
    float a[RT_VN];
    memcpy(a, &v, sizeof a);
    for (int w = RT_VN / 2; w > 0; w /= 2)
        for (int i = 0; i < w; i++) a[i] = a[i + w] > a[i] ? a[i + w] : a[i];
    return a[0];
#endif
}

/* fabsf per lane: the sign bit cleared. */
static inline rt_vf rt_vabs(rt_vf a) {
    return (rt_vf)((rt_vi)a & rt_vsplat_i(0x7fffffff));
}

/* Bit l set where lane l of m (a comparison result) is. */
static inline uint32_t rt_vbits(rt_vi m) {
#if defined(__AVX512F__)
    return (uint32_t)_mm512_cmplt_epi32_mask((__m512i)m, _mm512_setzero_si512());
#elif defined(__AVX2__)
    return (uint32_t)_mm256_movemask_ps((__m256)m);
#elif defined(__SSE2__)
    return (uint32_t)_mm_movemask_ps((__m128)m);
#elif defined(__aarch64__)
    static const uint32_t bit[4] = {1, 2, 4, 8};
    return vaddvq_u32(vandq_u32((uint32x4_t)m, vld1q_u32(bit)));
#else
    uint32_t bits = 0;
    for (int i = 0; i < RT_VN; i++) bits |= (uint32_t)(m[i] & 1) << i;
    return bits;
#endif
}

/* ---- four lanes, one per child of a wide node --------------------------- */

typedef float rt_v4f __attribute__((vector_size(16)));
typedef int32_t rt_v4i __attribute__((vector_size(16)));

static inline rt_v4f rt_v4splat(float x) {
    return (rt_v4f){x, x, x, x};
}

/* Minimum and maximum of values that are never NaN. */
static inline rt_v4f rt_v4min(rt_v4f a, rt_v4f b) {
#if defined(__SSE2__)
    return (rt_v4f)_mm_min_ps((__m128)a, (__m128)b);
#elif defined(__aarch64__)
    return (rt_v4f)vminq_f32((float32x4_t)a, (float32x4_t)b);
#else
    return (rt_v4f)(((a < b) & (rt_v4i)a) | (~(a < b) & (rt_v4i)b));
#endif
}

static inline rt_v4f rt_v4max(rt_v4f a, rt_v4f b) {
#if defined(__SSE2__)
    return (rt_v4f)_mm_max_ps((__m128)a, (__m128)b);
#elif defined(__aarch64__)
    return (rt_v4f)vmaxq_f32((float32x4_t)a, (float32x4_t)b);
#else
    return (rt_v4f)(((a > b) & (rt_v4i)a) | (~(a > b) & (rt_v4i)b));
#endif
}

static inline uint32_t rt_v4bits(rt_v4i m) {
#if defined(__SSE2__)
    return (uint32_t)_mm_movemask_ps((__m128)m);
#elif defined(__aarch64__)
    static const uint32_t bit[4] = {1, 2, 4, 8};
    return vaddvq_u32(vandq_u32((uint32x4_t)m, vld1q_u32(bit)));
#else
    return (uint32_t)(m[0] & 1) | (uint32_t)(m[1] & 2) | (uint32_t)(m[2] & 4) |
           (uint32_t)(m[3] & 8);
#endif
}

/* ---- eight lanes, one per child of an eight-wide node -------------------- */

typedef float rt_v8f __attribute__((vector_size(32)));
typedef int32_t rt_v8i __attribute__((vector_size(32)));

static inline rt_v8f rt_v8splat(float x) {
    return (rt_v8f){x, x, x, x, x, x, x, x};
}

#if defined(__AVX__)
static inline rt_v8f rt_v8min(rt_v8f a, rt_v8f b) {
    return (rt_v8f)_mm256_min_ps((__m256)a, (__m256)b);
}
static inline rt_v8f rt_v8max(rt_v8f a, rt_v8f b) {
    return (rt_v8f)_mm256_max_ps((__m256)a, (__m256)b);
}
static inline uint32_t rt_v8bits(rt_v8i m) {
    return (uint32_t)_mm256_movemask_ps((__m256)m);
}
#else
typedef union {
    rt_v8f v;
    rt_v4f h[2];
} rt_v8split;
static inline rt_v8f rt_v8min(rt_v8f a, rt_v8f b) {
    rt_v8split x = {a}, y = {b};
    x.h[0] = rt_v4min(x.h[0], y.h[0]);
    x.h[1] = rt_v4min(x.h[1], y.h[1]);
    return x.v;
}
static inline rt_v8f rt_v8max(rt_v8f a, rt_v8f b) {
    rt_v8split x = {a}, y = {b};
    x.h[0] = rt_v4max(x.h[0], y.h[0]);
    x.h[1] = rt_v4max(x.h[1], y.h[1]);
    return x.v;
}
static inline uint32_t rt_v8bits(rt_v8i m) {
    rt_v8split x = {(rt_v8f)m};
    return rt_v4bits((rt_v4i)x.h[0]) | rt_v4bits((rt_v4i)x.h[1]) << 4;
}
#endif

#endif /* RT_SIMD_WIDE_H */
