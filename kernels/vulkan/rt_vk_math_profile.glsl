/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_math_profile.glsl - the GLSL mirror of kernels/rt_math_profile.h:
 * the portable profile's division, square root and difference of products
 * (rt_vk_soft_math.glsl), fabs as a bit operation and infinity by its bits;
 * SC_DENORM_FLUSH (a specialization constant of kernels/rt_interface.def)
 * picks the flush-to-zero variants, as -DRT_FLUSH_DENORMALS does in OpenCL. */
#ifndef RT_VK_MATH_PROFILE_GLSL
#define RT_VK_MATH_PROFILE_GLSL

#include "rt_vk_interface.glsl" /* SC_DENORM_FLUSH */
#include "rt_vk_soft_math.glsl"

#define RT_INF uintBitsToFloat(0x7f800000u)

float RT_DIV(float a, float b) {
    return uintBitsToFloat(
        rt_sm_div_bits_(floatBitsToUint(a), floatBitsToUint(b), SC_DENORM_FLUSH != 0u));
}
float RT_SQRT(float x) {
    return uintBitsToFloat(rt_sm_sqrt_bits_(floatBitsToUint(x), SC_DENORM_FLUSH != 0u));
}
float RT_DOP(float a, float b, float c, float d) {
    return uintBitsToFloat(rt_sm_dop_bits_(floatBitsToUint(a), floatBitsToUint(b),
                                           floatBitsToUint(c), floatBitsToUint(d),
                                           SC_DENORM_FLUSH != 0u));
}
/* fabs as a bit operation (as C's fabsf: the sign bit cleared, NaN kept). */
float RT_FABS(float x) {
    return uintBitsToFloat(floatBitsToUint(x) & 0x7fffffffu);
}

#endif
