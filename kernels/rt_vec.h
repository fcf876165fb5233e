/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vec.h - small vector helpers of the shared maths, each with its order
 * of operations written out. Valid C99 and OpenCL C (rt_math_profile.h says
 * the rules); the GLSL mirror is kernels/vulkan/rt_vk_vec.glsl. */
#ifndef RT_KERNELS_VEC_H
#define RT_KERNELS_VEC_H

#include "rt_math_profile.h"

RT_FN float rt_dot3(const float *a, const float *b) {
    return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

RT_FN void rt_cross3(const float *a, const float *b, float *out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

RT_FN void rt_normalize3(float *v) {
    float len = RT_SQRT(rt_dot3(v, v));
    if (len > 0.0f) {
        v[0] = RT_DIV(v[0], len);
        v[1] = RT_DIV(v[1], len);
        v[2] = RT_DIV(v[2], len);
    }
}

/* The least and the greatest of three, as comparisons in this order. */
RT_FN float rt_min3(float a, float b, float c) {
    float m = a < b ? a : b;
    return c < m ? c : m;
}
RT_FN float rt_max3(float a, float b, float c) {
    float m = a > b ? a : b;
    return c > m ? c : m;
}

#endif /* RT_KERNELS_VEC_H */
