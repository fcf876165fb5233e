/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_box.glsl - the GLSL mirror of kernels/rt_box.h: the robust slab
 * test (a node passed by index) and the widened t range of box tests. */
#ifndef RT_VK_BOX_GLSL
#define RT_VK_BOX_GLSL

#include "rt_vk_ray.glsl"
#include "rt_vk_view.glsl"

#define RT_BOX_FAR_SCALE     1.000000476837158203125
#define RT_BOX_FAR_SCALE_NEG 0.999999523162841796875
#define RT_BOX_T_MARGIN      0.015625

void rt_slab(float a, float b, float org, float inv, inout float lo, inout float hi) {
    float t0 = (a - org) * inv;
    float t1 = (b - org) * inv;
    lo = t0 > lo ? t0 : lo;
    hi = t1 < hi ? t1 : hi;
}

float rt_slab_far(float hi, float tmax) {
    hi = hi * (hi < 0.0 ? RT_BOX_FAR_SCALE_NEG : RT_BOX_FAR_SCALE);
    return tmax < hi ? tmax : hi;
}

bool rt_slab_end(float lo, float hi, float tmax, out float tnear) {
    hi = rt_slab_far(hi, tmax);
    tnear = lo;
    return lo <= hi;
}

/* The C function on the box of node (GLSL has no pointer to a buffer's
 * array). */
bool rt_box_interval(uint node, rt_ray r, rt_ray_pre p, float tmin, float tmax, out float tnear,
                     out float tfar) {
    float lo = tmin, hi = RT_INF;
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        float a = p.sign[i] != 0 ? nodes[node].bmax[i] : nodes[node].bmin[i];
        float b = p.sign[i] != 0 ? nodes[node].bmin[i] : nodes[node].bmax[i];
        rt_slab(a, b, r.org[i], p.inv[i], lo, hi);
    }
    tfar = rt_slab_far(hi, tmax);
    tnear = lo;
    return lo <= tfar;
}

bool rt_box_test(uint node, rt_ray r, rt_ray_pre p, float tmin, float tmax, out float tnear) {
    float tfar;
    return rt_box_interval(node, r, p, tmin, tmax, tnear, tfar);
}

float rt_box_lo(float tmin) {
    return tmin - RT_FABS(tmin) * RT_BOX_T_MARGIN;
}
float rt_box_hi(float tmax) {
    return tmax + RT_FABS(tmax) * RT_BOX_T_MARGIN;
}

#endif
