/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_ray.glsl - the GLSL mirror of kernels/rt_ray.h: the ray, its
 * prepared values and where a secondary ray starts. */
#ifndef RT_VK_RAY_GLSL
#define RT_VK_RAY_GLSL

#include "rt_vk_vec.glsl"

struct rt_ray {
    float org[3];
    float dir[3];
    float tmin;
    float tmax;
};
struct rt_ray_pre {
    float inv[3];
    int sign[3];
    int kx, ky, kz;
    float sx, sy, sz;
    float inst_lo;
};

void rt_ray_prepare(rt_ray r, out rt_ray_pre p) {
    float ax = RT_FABS(r.dir[0]), ay = RT_FABS(r.dir[1]), az = RT_FABS(r.dir[2]);
    int kz = 0;
    if (ay > ax) kz = 1;
    if (az > (kz == 1 ? ay : ax)) kz = 2;
    int kx = kz + 1 == 3 ? 0 : kz + 1;
    int ky = kx + 1 == 3 ? 0 : kx + 1;
    float dkz = rt_pick3(r.dir, kz);
    if (dkz < 0.0) {
        int tmp = kx;
        kx = ky;
        ky = tmp;
    }
    p.kx = kx;
    p.ky = ky;
    p.kz = kz;
    /* The six divisions of the C function, in one loop: one inlined copy of
     * the soft division instead of six. */
    float num[6] = float[6](1.0, 1.0, 1.0, rt_pick3(r.dir, kx), rt_pick3(r.dir, ky), 1.0);
    float den[6] = float[6](r.dir[0], r.dir[1], r.dir[2], dkz, dkz, dkz);
    float q[6];
    [[dont_unroll]] for (int i = 0; i < 6; i++, RT_VK_TICK) q[i] = RT_DIV(num[i], den[i]);
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        p.inv[i] = q[i];
        p.sign[i] = p.inv[i] < 0.0 ? 1 : 0;
    }
    p.sx = q[3];
    p.sy = q[4];
    p.sz = q[5];
    p.inst_lo = -RT_INF;
}

void rt_offset_point(float p[3], float n[3], float sign, out float o[3]) {
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        float ni = sign * n[i];
        int of = int(256.0 * ni);
        float pi = intBitsToFloat(floatBitsToInt(p[i]) + (p[i] < 0.0 ? -of : of));
        o[i] = RT_FABS(p[i]) < 0.03125 ? p[i] + 0.0000152587890625 * ni : pi;
    }
}

#endif
