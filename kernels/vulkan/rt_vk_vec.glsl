/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_vec.glsl - the GLSL mirror of kernels/rt_vec.h: small vector
 * helpers with their order of operations written out, and rt_pick3 (GLSL
 * only: an element by selects instead of a run-time index). */
#ifndef RT_VK_VEC_GLSL
#define RT_VK_VEC_GLSL

#include "rt_vk_math_profile.glsl"

/* a[k] for k in 0..2, by selects: a local array indexed at run time stays in
 * memory (scratch) in many drivers, and with it every access to the array,
 * which made lavapipe trace several times slower. */
float rt_pick3(float a[3], int k) {
    return k == 0 ? a[0] : (k == 1 ? a[1] : a[2]);
}

float rt_dot3(float a[3], float b[3]) {
    return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

void rt_cross3(float a[3], float b[3], out float o[3]) {
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

void rt_normalize3(inout float v[3]) {
    float len = RT_SQRT(rt_dot3(v, v));
    if (len > 0.0) {
        [[dont_unroll]] for (int i = 0; i < 3; i++, RT_VK_TICK) v[i] = RT_DIV(v[i], len);
    }
}

float rt_min3(float a, float b, float c) {
    float m = a < b ? a : b;
    return c < m ? c : m;
}
float rt_max3(float a, float b, float c) {
    float m = a > b ? a : b;
    return c > m ? c : m;
}

#endif
