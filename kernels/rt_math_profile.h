/* SPDX-License-Identifier: Apache-2.0 */
/* rt_math_profile.h - how the shared maths (the kernels/ headers rt_vec.h
 * .. rt_shade.h) is written so that one text is valid C99 and valid OpenCL C
 * and gives the same bits everywhere: the language switches (RT_FN,
 * RT_GLOBAL, bit casts) and the maths profile's division, square root and
 * difference of products (RT_DIV, RT_SQRT, RT_DOP).
 *
 * The CPU oracle (cpu_ref/), the packet path and the OpenCL kernels include
 * the shared maths, so they evaluate the same operations in the same order
 * and get the same bits. Rules that keep it so:
 * - only + - * /, sqrt, comparisons, fabs (division as RT_DIV and square
 *   root as RT_SQRT: correctly rounded in every profile but the OpenCL
 *   study build with -DRT_NATIVE_MATH); minimum and maximum written as
 *   comparisons (so NaN handling is spelled out); integer powers by repeated
 *   multiplication; no vector operators; no recursion, no function pointers,
 *   no allocation; no double anywhere;
 * - C builds with -ffp-contract=off and without fast-math; OpenCL builds with
 *   '#pragma OPENCL FP_CONTRACT OFF', without the options -cl-mad-enable or
 *   fast-relaxed maths.
 *
 * Two maths profiles give the same bits (docs/PORTABLE_MATH.md):
 * - native: the device's division and sqrt, built with
 *   -cl-fp32-correctly-rounded-divide-sqrt; only where the device promises
 *   them correctly rounded (the C oracle: IEEE hardware);
 * - portable (-DRT_PORTABLE_MATH): division and sqrt in software from 32-bit
 *   integer operations (rt_soft_math.h), for devices whose division and
 *   sqrt may be off by ulps (OpenCL allows 2.5 and 3, Vulkan 2.5).
 * Denormals: -DRT_FLUSH_DENORMALS (OpenCL, with -cl-denorms-are-zero) picks
 * the flush-to-zero variants of the software functions; the C oracle follows
 * its thread's mode (rt_fp_mode.h), which the CPU backends set.
 * - the evaluation order of every sum is written out (a + b + c is (a + b) + c).
 *
 * The GLSL mirror is kernels/vulkan/rt_vk_math_profile.glsl. */
#ifndef RT_KERNELS_MATH_PROFILE_H
#define RT_KERNELS_MATH_PROFILE_H

#include "rt_layout.h"

#include "rt_soft_math.h"

#ifdef RT_OPENCL
#define RT_GLOBAL __global
#define RT_FN
#define RT_FN_RARE /* a rare path: the kernel compiler decides */
#if defined(RT_PORTABLE_MATH) && defined(RT_NATIVE_MATH)
#error "RT_PORTABLE_MATH and RT_NATIVE_MATH exclude each other"
#endif
#if defined(RT_PORTABLE_MATH) && defined(RT_FLUSH_DENORMALS)
#define RT_DIV(a, b) rt_soft_div_ftz((a), (b))
#define RT_SQRT(x)   rt_soft_sqrt_ftz(x)
#elif defined(RT_PORTABLE_MATH)
#define RT_DIV(a, b) rt_soft_div((a), (b))
#define RT_SQRT(x)   rt_soft_sqrt(x)
#elif defined(RT_NATIVE_MATH)
/* Only for the speed-versus-error study (bench/study_opencl_options.sh): the
 * device's own, faster division and square root, whose error the
 * implementation defines. Never in a build that claims the oracle's bits. */
#define RT_DIV(a, b) native_divide((a), (b))
#define RT_SQRT(x)   native_sqrt(x)
#else
#define RT_DIV(a, b) ((a) / (b))
#define RT_SQRT(x)   sqrt(x)
#endif
#ifdef RT_FLUSH_DENORMALS
#define RT_DOP(a, b, c, d) rt_soft_diff_of_products_ftz((a), (b), (c), (d))
#else
#define RT_DOP(a, b, c, d) rt_soft_diff_of_products((a), (b), (c), (d))
#endif
#define RT_FABS(x)     fabs(x)
#define RT_AS_INT(x)   as_int(x)
#define RT_AS_FLOAT(x) as_float(x)
#define RT_INF         INFINITY
#else
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "rt_fp_mode.h"
#define RT_GLOBAL
#define RT_FN          static inline
/* A rare path kept out of line, so that the hot loop that calls it stays
 * small (rt_tri_t_plane): C compilers otherwise inline it into every
 * traversal. */
#define RT_FN_RARE     static __attribute__((noinline))
#define RT_DIV(a, b)   ((a) / (b))
#define RT_SQRT(x)     sqrtf(x)
#define RT_FABS(x)     fabsf(x)
#define RT_AS_INT(x)   rt_as_int_(x)
#define RT_AS_FLOAT(x) rt_as_float_(x)
#define RT_INF         INFINITY
/* The hardware's division and sqrt flush when the thread's mode does; the
 * integer-only difference of products follows that mode explicitly. */
#define RT_DOP(a, b, c, d)                                                                         \
    (rt_fp_flushing() ? rt_soft_diff_of_products_ftz((a), (b), (c), (d))                           \
                      : rt_soft_diff_of_products((a), (b), (c), (d)))
static inline rt_i32 rt_as_int_(float f) {
    rt_i32 i;
    memcpy(&i, &f, sizeof i);
    return i;
}
static inline float rt_as_float_(rt_i32 i) {
    float f;
    memcpy(&f, &i, sizeof f);
    return f;
}
#endif

#endif /* RT_KERNELS_MATH_PROFILE_H */
