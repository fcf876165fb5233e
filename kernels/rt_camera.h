/* SPDX-License-Identifier: Apache-2.0 */
/* rt_camera.h - the primary rays of the camera that rt_layout.h describes
 * (rt_scene_header's cam_* fields, written by the host). Valid C99 and
 * OpenCL C (rt_math_profile.h); the GLSL mirror is
 * kernels/vulkan/rt_vk_camera.glsl. */
#ifndef RT_KERNELS_CAMERA_H
#define RT_KERNELS_CAMERA_H

#include "rt_ray.h"

/* The primary ray through the centre of pixel (px, py); see rt_layout.h. Its
 * screen coordinates depend on the column and the row alone, so a caller
 * with many pixels of one row or column may compute them once. */
RT_FN float rt_camera_sx(RT_GLOBAL const rt_scene_header *h, rt_i32 px) {
    return RT_DIV(2.0f * ((float)px + 0.5f), (float)h->width) - 1.0f;
}
RT_FN float rt_camera_sy(RT_GLOBAL const rt_scene_header *h, rt_i32 py) {
    return 1.0f - RT_DIV(2.0f * ((float)py + 0.5f), (float)h->height);
}
RT_FN void rt_camera_ray_at(RT_GLOBAL const rt_scene_header *h, float sx, float sy, rt_ray *r) {
    for (int i = 0; i < 3; i++) {
        r->org[i] = h->cam_pos[i];
        r->dir[i] = (h->cam_forward[i] + sx * h->cam_right[i]) + sy * h->cam_up[i];
    }
    r->tmin = 0.0f;
    r->tmax = RT_INF;
}
RT_FN void rt_camera_ray(RT_GLOBAL const rt_scene_header *h, rt_i32 px, rt_i32 py, rt_ray *r) {
    rt_camera_ray_at(h, rt_camera_sx(h, px), rt_camera_sy(h, py), r);
}

/* The primary ray of pixel number pixel, counted row by row from the
 * top-left (the GPU kernels' tiles are ranges of these numbers). */
RT_FN void rt_camera_pixel_ray(RT_GLOBAL const rt_scene_header *h, rt_u32 pixel, rt_ray *r) {
    rt_camera_ray(h, (rt_i32)(pixel % (rt_u32)h->width), (rt_i32)(pixel / (rt_u32)h->width), r);
}

#endif /* RT_KERNELS_CAMERA_H */
