/* SPDX-License-Identifier: Apache-2.0 */
/* rt_ray.h - the ray and what every test reuses of it: rt_ray, its
 * prepared values (rt_ray_pre: reciprocal direction, the watertight test's
 * shear), and where a secondary ray starts (rt_offset_point). Valid C99 and
 * OpenCL C (rt_math_profile.h); the GLSL mirror is
 * kernels/vulkan/rt_vk_ray.glsl. The direction is not normalised and t is
 * in units of its length; [tmin, tmax] is inclusive. */
#ifndef RT_KERNELS_RAY_H
#define RT_KERNELS_RAY_H

#include "rt_math_profile.h"

/* A ray o + t d, t in [tmin, tmax]: the public rt_ray of host/rt.h, defined
 * in both headers under one guard so that C code including both sees one
 * type (and the library passes the caller's rays to the backends as they
 * are); the layouts must stay equal. */
#ifndef RT_RAY_DEFINED
#define RT_RAY_DEFINED
typedef struct rt_ray {
    float org[3];
    float dir[3];
    float tmin;
    float tmax;
} rt_ray;
#endif

/* Per-ray values both tests reuse. */
typedef struct rt_ray_pre {
    float inv[3];   /* 1 / dir (inf for a zero component) */
    rt_i32 sign[3]; /* inv < 0 */
    rt_i32 kx, ky, kz;
    float sx, sy, sz; /* watertight shear */
    /* The entry distance of the ray's instance box (rt_inst_enter), -inf
     * outside an object BVH: a hit at t is accepted only where
     * inst_lo <= rt_box_hi(t) (rt_hit_accepted). */
    float inst_lo;
} rt_ray_pre;

RT_FN void rt_ray_prepare(const rt_ray *r, rt_ray_pre *p) {
    for (int i = 0; i < 3; i++) {
        p->inv[i] = RT_DIV(1.0f, r->dir[i]);
        p->sign[i] = p->inv[i] < 0.0f;
    }
    /* Watertight test: kz is the axis where |dir| is largest. */
    float ax = RT_FABS(r->dir[0]), ay = RT_FABS(r->dir[1]), az = RT_FABS(r->dir[2]);
    rt_i32 kz = 0;
    if (ay > ax) kz = 1;
    if (az > (kz == 1 ? ay : ax)) kz = 2;
    rt_i32 kx = kz + 1 == 3 ? 0 : kz + 1;
    rt_i32 ky = kx + 1 == 3 ? 0 : kx + 1;
    if (r->dir[kz] < 0.0f) { /* keep the winding */
        rt_i32 tmp = kx;
        kx = ky;
        ky = tmp;
    }
    p->kx = kx;
    p->ky = ky;
    p->kz = kz;
    p->sx = RT_DIV(r->dir[kx], r->dir[kz]);
    p->sy = RT_DIV(r->dir[ky], r->dir[kz]);
    p->sz = p->inv[kz]; /* 1 / dir[kz], the same operation: one division less */
    p->inst_lo = -RT_INF;
}

/* Waechter and Binder 2019 (Ray Tracing Gems, ch. 6): moves p off the surface
 * along n by a fixed number of ulps (256 |n|), which scales with p's magnitude;
 * near the origin, where ulps are tiny, by a fixed 2^-16 |n| instead.
 * n is a unit normal (the shading's are). For any other n (a ray file's
 * normal can be anything) a component beyond +-1 moves at most 256 ulps, a
 * NaN in n or p gives NaN, and the bit arithmetic is unsigned, so nothing is
 * undefined for any input (the float-to-int conversion was, for |n| >= 2^23
 * and infinities, and the add for -0 and large NaN payloads: found by
 * tests/fuzz/fuzz_rays). For unit normals and finite p the bits are those of
 * the plain signed formula. rt_ray_packet.cl's pk_offset_point sees unit normals
 * and finite points only. */
RT_FN void rt_offset_point(const float *p, const float *n, float sign, float *out) {
    for (int i = 0; i < 3; i++) {
        float ni = sign * n[i];
        float s = 256.0f * ni;
        rt_i32 of = s >= 256.0f ? 256 : (s <= -256.0f ? -256 : (s == s ? (rt_i32)s : 0));
        float pi =
            RT_AS_FLOAT((rt_i32)((rt_u32)RT_AS_INT(p[i]) + (rt_u32)(p[i] < 0.0f ? -of : of)));
        out[i] = RT_FABS(p[i]) < 0.03125f ? p[i] + 0.0000152587890625f * ni
                                          : (s == s && p[i] == p[i] ? pi : p[i] + s);
    }
}

#endif /* RT_KERNELS_RAY_H */
