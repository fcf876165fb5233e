/* SPDX-License-Identifier: Apache-2.0 */
/* rt_box.h - ray/box: the robust slab test (Ize 2013) and the widened t
 * range boxes are tested against (rt_box_lo, rt_box_hi). Valid C99 and
 * OpenCL C (rt_math_profile.h); the GLSL mirror is
 * kernels/vulkan/rt_vk_box.glsl. */
#ifndef RT_KERNELS_BOX_H
#define RT_KERNELS_BOX_H

#include "rt_ray.h"

/* Ize 2013: the far slab distance times 1 + 2 gamma(3), gamma(n) =
 * n eps / (1 - n eps), eps = 2^-24, makes the float slab test conservative.
 * 1 + 2 gamma(3) = 1 + 3.58e-7 is rounded up to 1 + 4 * 2^-23. */
#define RT_BOX_FAR_SCALE 1.000000476837158203125f
/* The same margin for a far distance below zero (a ray range with negative
 * t): there the far end must grow towards zero, 1 - 4 * 2^-23. Without it a
 * flat box behind the origin was culled (tests/robust, grazing rays). */
#define RT_BOX_FAR_SCALE_NEG 0.999999523162841796875f

/* The t range a box is tested against is widened by this relative margin:
 * a triangle test's t has rounding errors of its own, and a hit is accepted
 * only where its t passes its triangle's box test (rt_hit_accepted), so the
 * margin is also how far a t may fall before its box and still count. The
 * watertight test's t is within 2^-17 of itself (rt_tri_t.h), far inside
 * it; the other tests' t was measured off by up to ~1e-2 relative on large
 * triangles crossed near the origin (before rt_tri_t.h the watertight test's
 * too: t error ~ eps |v - o| / |dir|), and for them 2^-16 refused 5
 * of 30k random rays and 2 of 195k diffuse bounces on Sponza (light through
 * a wall), 2^-10 the bounces; 2^-6 none of 770k on Sponza and Sibenik. It
 * costs only boxes entered up to 1.6% beyond the best hit. */
#define RT_BOX_T_MARGIN 0.015625f /* 2^-6 */

/* One slab of the test: the ray's distances to the planes a (entered) and b
 * (left) on axis i narrow [*lo, *hi]. Every box test is built from these two
 * steps, so that a box containing another never passes less (the rounding
 * is monotonic in a and b). */
RT_FN void rt_slab(float a, float b, float org, float inv, float *lo, float *hi) {
    float t0 = (a - org) * inv;
    float t1 = (b - org) * inv;
    *lo = t0 > *lo ? t0 : *lo;
    *hi = t1 < *hi ? t1 : *hi;
}

/* The far end of the test: the far distance hi made conservative (Ize),
 * cut at tmax. */
RT_FN float rt_slab_far(float hi, float tmax) {
    hi = hi * (hi < 0.0f ? RT_BOX_FAR_SCALE_NEG : RT_BOX_FAR_SCALE);
    return tmax < hi ? tmax : hi;
}

/* The end of the test: whether the entry distance lo is at or before the
 * far end (rt_slab_far); *tnear is the entry distance. */
RT_FN int rt_slab_end(float lo, float hi, float tmax, float *tnear) {
    hi = rt_slab_far(hi, tmax);
    *tnear = lo;
    return lo <= hi;
}

/* The ray's interval [*tnear, *tfar] in the box [bmin, bmax], intersected
 * with [tmin, tmax] (the far end conservative, rt_slab_far); 0 when it is
 * empty. A 0 * inf (origin on a slab plane, direction parallel to it) gives
 * NaN, which the comparisons skip, keeping the test conservative. The box
 * tests below and the kd-tree's root cell (rt_kd.h) are this. */
RT_FN int rt_box_interval(RT_GLOBAL const float *bmin, RT_GLOBAL const float *bmax, const rt_ray *r,
                          const rt_ray_pre *p, float tmin, float tmax, float *tnear, float *tfar) {
    float lo = tmin, hi = RT_INF;
    for (int i = 0; i < 3; i++)
        rt_slab(p->sign[i] ? bmax[i] : bmin[i], p->sign[i] ? bmin[i] : bmax[i], r->org[i],
                p->inv[i], &lo, &hi);
    hi = rt_slab_far(hi, tmax);
    *tnear = lo;
    *tfar = hi;
    return lo <= hi;
}

/* Tests the box [bmin, bmax] against [tmin, tmax]; *tnear is the entry
 * distance. */
RT_FN int rt_box_test_bounds(RT_GLOBAL const float *bmin, RT_GLOBAL const float *bmax,
                             const rt_ray *r, const rt_ray_pre *p, float tmin, float tmax,
                             float *tnear) {
    float tfar;
    return rt_box_interval(bmin, bmax, r, p, tmin, tmax, tnear, &tfar);
}

/* rt_box_test_bounds on a node's box. */
RT_FN int rt_box_test(RT_GLOBAL const rt_node *n, const rt_ray *r, const rt_ray_pre *p, float tmin,
                      float tmax, float *tnear) {
    return rt_box_test_bounds(n->bmin, n->bmax, r, p, tmin, tmax, tnear);
}

/* The box range for a ray whose accepted t range is [tmin, tmax]. */
RT_FN float rt_box_lo(float tmin) {
    return tmin - RT_FABS(tmin) * RT_BOX_T_MARGIN;
}
RT_FN float rt_box_hi(float tmax) {
    return tmax + RT_FABS(tmax) * RT_BOX_T_MARGIN;
}

#endif /* RT_KERNELS_BOX_H */
