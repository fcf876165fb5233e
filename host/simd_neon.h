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

#endif /* RT_SIMD_NEON_H */
