/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_camera.glsl - the GLSL mirror of kernels/rt_camera.h: the primary
 * rays of the scene header's camera. */
#ifndef RT_VK_CAMERA_GLSL
#define RT_VK_CAMERA_GLSL

#include "rt_vk_ray.glsl"
#include "rt_vk_view.glsl"

float rt_camera_sx(int px) {
    return RT_DIV(2.0 * (float(px) + 0.5), float(hdr.width)) - 1.0;
}
float rt_camera_sy(int py) {
    return 1.0 - RT_DIV(2.0 * (float(py) + 0.5), float(hdr.height));
}
void rt_camera_ray(int px, int py, out rt_ray r) {
    float sx = rt_camera_sx(px), sy = rt_camera_sy(py);
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        r.org[i] = hdr.cam_pos[i];
        r.dir[i] = (hdr.cam_forward[i] + sx * hdr.cam_right[i]) + sy * hdr.cam_up[i];
    }
    r.tmin = 0.0;
    r.tmax = RT_INF;
}
void rt_camera_pixel_ray(uint pixel, out rt_ray r) {
    rt_camera_ray(int(pixel % uint(hdr.width)), int(pixel / uint(hdr.width)), r);
}

#endif
