/* SPDX-License-Identifier: Apache-2.0 */
/* watertight_lanes.h - rt_tri_watertight (kernels/rt_shared.h) on the RT_VN
 * lanes of rt_vf (simd.h): the one vector copy of the oracle's watertight
 * arithmetic, shared by the packet tracer (one triangle, a vector of rays)
 * and the single-ray tracer (one ray, a vector of triangles). Each lane does
 * the oracle's operations in the oracle's order, so its values are the
 * oracle's bits; a change to rt_tri_watertight's arithmetic is made here,
 * once, for both tracers.
 *
 * In steps, because a lane with an edge function of exactly zero takes the
 * oracle's exact re-check (through the shared scalar test, in the tracer)
 * after the first, and the tracer returns early where no lane is inside:
 *   rt_vwt_edges:  the sheared vertices and the edge functions U, V, W;
 *   rt_vwt_inside: the sign test and det;
 *   rt_vwt_t:      T and t;
 *   rt_vwt_unsure: the lanes whose t may be off by more than RT_T_REL_BOUND,
 *                  which the oracle recomputes from the plane: the caller
 *                  replaces their t by rt_tri_t_plane's (rt_tri_t.h), and
 *                  those of them surely crossed before tmin, which miss.
 * The range test of t and u = V / det, v = W / det are left to the tracer,
 * which divides only for the hit it keeps. */
#ifndef RT_WATERTIGHT_LANES_H
#define RT_WATERTIGHT_LANES_H

#include "simd.h"

/* One triangle test's values per lane, named as in rt_tri_watertight. */
typedef struct rt_vwt {
    rt_vf Ax, Ay, Bx, By, Cx, Cy; /* the sheared vertices */
    rt_vf Az, Bz, Cz;             /* A[kz], B[kz], C[kz] (before the scale sz) */
    rt_vf U, V, W;                /* the edge functions */
    rt_vf det, t;                 /* (U + V) + W and T / det (rt_vwt_inside, rt_vwt_t) */
} rt_vwt;

/* rt_tri_watertight up to the edge functions. a, b and c are the vertices
 * v0, v1, v2 less the ray's origin on the ray's axes kx, ky, kz (the
 * oracle's A[kx], A[ky], A[kz], ...); sx and sy the ray's shear. Returns
 * the lanes (bit l = lane l) with an edge function of exactly zero: the
 * oracle re-checks those exactly, and so must the caller (the shared scalar
 * test) before it drops them from rt_vwt_inside's lanes. */
static inline uint32_t rt_vwt_edges(const rt_vf a[3], const rt_vf b[3], const rt_vf c[3], rt_vf sx,
                                    rt_vf sy, rt_vwt *x) {
    const rt_vf Ax = a[0] - sx * a[2], Ay = a[1] - sy * a[2];
    const rt_vf Bx = b[0] - sx * b[2], By = b[1] - sy * b[2];
    const rt_vf Cx = c[0] - sx * c[2], Cy = c[1] - sy * c[2];
    x->Ax = Ax, x->Ay = Ay, x->Bx = Bx, x->By = By, x->Cx = Cx, x->Cy = Cy;
    x->Az = a[2];
    x->Bz = b[2];
    x->Cz = c[2];
    x->U = Cx * By - Cy * Bx;
    x->V = Ax * Cy - Ay * Cx;
    x->W = Bx * Ay - By * Ax;
    const rt_vf zero = rt_vsplat(0.0f);
    return rt_vbits((x->U == zero) | (x->V == zero) | (x->W == zero));
}

/* The sign test for the lanes of m (none with a zero edge function): the
 * lanes whose ray meets the triangle (the edge functions of one sign, det
 * not 0), with x->det set. */
static inline uint32_t rt_vwt_inside(rt_vwt *x, uint32_t m) {
    const rt_vf zero = rt_vsplat(0.0f);
    x->det = (x->U + x->V) + x->W;
    const rt_vi out = (((x->U < zero) | (x->V < zero) | (x->W < zero)) &
                       ((x->U > zero) | (x->V > zero) | (x->W > zero))) |
                      (x->det == zero);
    return ~rt_vbits(out) & m;
}

/* The hit distance T / det per lane, sz the ray's scale (after
 * rt_vwt_inside: where some lane is inside). The oracle's range test, t in
 * [tmin, tmax], is the caller's, with the range it has at that moment. */
static inline rt_vf rt_vwt_t(rt_vwt *x, rt_vf sz) {
    const rt_vf T = (x->U * (sz * x->Az) + x->V * (sz * x->Bz)) + x->W * (sz * x->Cz);
    x->t = T / x->det;
    return x->t;
}

/* rt_tri_t_max per lane: a > b ? a : b, as the oracle picks on NaN. */
static inline rt_vf rt_vwt_max(rt_vf a, rt_vf b) {
    return rt_vsel(a > b, a, b);
}

/* rt_tri_t_check per lane (after rt_vwt_t), a, b and c as for rt_vwt_edges,
 * sx, sy, sz the ray's shear and scale, tmin its start: the lanes of m whose
 * t the oracle takes from the plane (RT_T_PLANE), by the oracle's operations
 * in the oracle's order; *before gets the lanes of m that it drops as
 * RT_T_BEFORE (misses: the caller takes them out of m). */
static inline uint32_t rt_vwt_unsure(const rt_vwt *x, const rt_vf a[3], const rt_vf b[3],
                                     const rt_vf c[3], rt_vf sx, rt_vf sy, rt_vf sz, rt_vf tmin,
                                     uint32_t m, uint32_t *before) {
    const rt_vf S = rt_vwt_max(rt_vabs(sx), rt_vabs(sy));
    const rt_vf K = rt_vwt_max(rt_vabs(a[2]), rt_vwt_max(rt_vabs(b[2]), rt_vabs(c[2])));
    const rt_vf P = rt_vwt_max(rt_vwt_max(rt_vabs(x->Ax), rt_vabs(x->Ay)),
                               rt_vwt_max(rt_vwt_max(rt_vabs(x->Bx), rt_vabs(x->By)),
                                          rt_vwt_max(rt_vabs(x->Cx), rt_vabs(x->Cy))));
    const rt_vf Az = sz * x->Az, Bz = sz * x->Bz, Cz = sz * x->Cz;
    const rt_vf zmax = rt_vwt_max(Az, rt_vwt_max(Bz, Cz));
    const rt_vf zmin = -rt_vwt_max(-Az, rt_vwt_max(-Bz, -Cz));
    const rt_vf Z = rt_vwt_max(zmax, -zmin);
    const rt_vf adet = rt_vabs(x->det);
    const rt_vf lhs = (((S * K + rt_vsplat(0.75f) * P) * P) * (zmax - zmin)) * rt_vsplat(0.5f) +
                      (adet * Z) * rt_vsplat(0.0625f);
    const uint32_t unsure = rt_vbits(lhs > rt_vabs(x->t) * adet) & m;
    *before = unsure ? rt_vbits((((tmin - x->t) * adet) * rt_vsplat(32768.0f) > lhs) &
                                (lhs > rt_vsplat(RT_T_BEFORE_FLOOR))) &
                           unsure
                     : 0;
    return unsure & ~*before;
}

/* The ray's part of rt_tri_t_plane's first tier per lane (the plane in
 * float, within its bound), from each lane's a = p - o, n, m (the
 * triangle's part, rt_tri_t_normal) and direction d, by the oracle's
 * operations in its order. Sets the lanes of un it settles to their t and
 * returns the lanes it did not settle, which take the scalar function.
 * Both CPU tracers call it: the packet tracer with one triangle's n and m
 * for a packet's rays, the single-ray tracer with a block's triangles. */
static inline uint32_t rt_vwt_plane1(const rt_vf a[3], const rt_vf n[3], const rt_vf m[3],
                                     const rt_vf d[3], uint32_t un, rt_vf *t) {
    const rt_vf zero = rt_vsplat(0.0f);
    rt_vf N = zero, D = zero, bn = zero, bd = zero;
    for (int i = 0; i < 3; i++) {
        N = N + n[i] * a[i];
        D = D + n[i] * d[i];
        bn = bn + (rt_vabs(n[i]) + m[i]) * rt_vabs(a[i]);
        bd = bd + (rt_vsplat(3.0f) * rt_vabs(n[i]) + rt_vsplat(4.0f) * m[i]) * rt_vabs(d[i]);
    }
    const rt_vf aN = rt_vabs(N), aD = rt_vabs(D), t1 = N / D;
    const rt_vi ok =
        ((rt_vsplat(4.0f) * bn) * aD + bd * aN + aN * aD <= rt_vsplat(128.0f) * (aN * aD)) &
        (t1 - t1 == zero) & (aN * aD > zero);
    const uint32_t good = rt_vbits(ok) & un;
    *t = rt_vsel(rt_vmask(good), t1, *t);
    return un & ~good;
}

#endif /* RT_WATERTIGHT_LANES_H */
