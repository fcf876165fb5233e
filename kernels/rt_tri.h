/* SPDX-License-Identifier: Apache-2.0 */
/* rt_tri.h - the four ray/triangle tests (RT_TRI_* of rt_layout.h) and the
 * choice between them (rt_tri_test). Valid C99 and OpenCL C
 * (rt_math_profile.h); the GLSL mirror is kernels/vulkan/rt_vk_tri.glsl. */
#ifndef RT_KERNELS_TRI_H
#define RT_KERNELS_TRI_H

#include "rt_ray.h"
#include "rt_tri_t.h"
#include "rt_vec.h"

/* Each returns 1 and sets t, u, v when the ray hits the triangle with t in
 * [tmin, tmax]. Both faces count. A ray in the triangle's plane and a
 * zero-area triangle give a zero determinant: a miss. */

/* Woop, Benthin and Wald 2013: shear and scale so the ray is the +z axis, then
 * 2D edge functions. Watertight: a ray through a shared edge or vertex hits at
 * least one of the triangles. Edge functions that come out exactly zero are
 * recomputed exactly (rt_edge_recheck); a t whose error bound exceeds
 * RT_T_REL_BOUND is recomputed from the plane (rt_tri_t.h). */
/* An edge function of exactly zero may be rounding (two equal products):
 * all three are recomputed as a*b - c*d with exact products, rounded once
 * (rt_soft_math.h: integer operations, no fp64, the same bits on every
 * device), as the paper does in double. Without this, sliver triangles of
 * scanned meshes report hits for rays that pass far from them. */
RT_FN void rt_edge_recheck(float Ax, float Ay, float Bx, float By, float Cx, float Cy, float *U,
                           float *V, float *W) {
    *U = RT_DOP(Cx, By, Cy, Bx);
    *V = RT_DOP(Ax, Cy, Ay, Cx);
    *W = RT_DOP(Bx, Ay, By, Ax);
}

RT_FN int rt_tri_watertight(RT_GLOBAL const rt_tri *tri, const rt_ray *r, const rt_ray_pre *p,
                            float tmin, float tmax, float *t, float *u, float *v) {
    float A[3], B[3], C[3];
    for (int i = 0; i < 3; i++) {
        A[i] = tri->v0[i] - r->org[i];
        B[i] = tri->v1[i] - r->org[i];
        C[i] = tri->v2[i] - r->org[i];
    }
    const rt_i32 kx = p->kx, ky = p->ky, kz = p->kz;
    float Ax = A[kx] - p->sx * A[kz], Ay = A[ky] - p->sy * A[kz];
    float Bx = B[kx] - p->sx * B[kz], By = B[ky] - p->sy * B[kz];
    float Cx = C[kx] - p->sx * C[kz], Cy = C[ky] - p->sy * C[kz];
    float U = Cx * By - Cy * Bx;
    float V = Ax * Cy - Ay * Cx;
    float W = Bx * Ay - By * Ax;
    if (U == 0.0f || V == 0.0f || W == 0.0f) rt_edge_recheck(Ax, Ay, Bx, By, Cx, Cy, &U, &V, &W);
    if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return 0;
    float det = (U + V) + W;
    if (det == 0.0f) return 0;
    float Az = p->sz * A[kz], Bz = p->sz * B[kz], Cz = p->sz * C[kz];
    float T = (U * Az + V * Bz) + W * Cz;
    float tt = RT_DIV(T, det);
    /* A t that may be off by more than RT_T_REL_BOUND (long triangles crossed
     * near the origin) is taken from the plane instead, unless the crossing
     * is surely before tmin (rt_tri_t.h). */
    const int check = rt_tri_t_check(A[kz], B[kz], C[kz], p->sx, p->sy, Ax, Ay, Bx, By, Cx, Cy, Az,
                                     Bz, Cz, det, tt, tmin);
    if (check == RT_T_BEFORE) return 0;
    if (check == RT_T_PLANE) tt = rt_tri_t_plane(tri, r, tt);
    if (!(tt >= tmin && tt <= tmax)) return 0;
    *t = tt;
    *u = RT_DIV(V, det);
    *v = RT_DIV(W, det);
    return 1;
}

/* Moller and Trumbore 1997. */
RT_FN int rt_tri_moller(RT_GLOBAL const rt_tri *tri, const rt_ray *r, float tmin, float tmax,
                        float *t, float *u, float *v) {
    float e1[3], e2[3], s[3], pv[3], q[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = tri->v1[i] - tri->v0[i];
        e2[i] = tri->v2[i] - tri->v0[i];
        s[i] = r->org[i] - tri->v0[i];
    }
    rt_cross3(r->dir, e2, pv);
    float det = rt_dot3(e1, pv);
    if (det == 0.0f) return 0;
    float inv = RT_DIV(1.0f, det);
    float uu = rt_dot3(s, pv) * inv;
    if (!(uu >= 0.0f && uu <= 1.0f)) return 0;
    rt_cross3(s, e1, q);
    float vv = rt_dot3(r->dir, q) * inv;
    if (!(vv >= 0.0f && uu + vv <= 1.0f)) return 0;
    float tt = rt_dot3(e2, q) * inv;
    if (!(tt >= tmin && tt <= tmax)) return 0;
    *t = tt;
    *u = uu;
    *v = vv;
    return 1;
}

/* Signed volumes of the ray with each edge (the Pluecker inner products,
 * written as triple products of the vertices relative to the origin). */
RT_FN int rt_tri_pluecker(RT_GLOBAL const rt_tri *tri, const rt_ray *r, float tmin, float tmax,
                          float *t, float *u, float *v) {
    float a[3], b[3], c[3], bc[3], ca[3], ab[3];
    for (int i = 0; i < 3; i++) {
        a[i] = tri->v0[i] - r->org[i];
        b[i] = tri->v1[i] - r->org[i];
        c[i] = tri->v2[i] - r->org[i];
    }
    rt_cross3(b, c, bc);
    rt_cross3(c, a, ca);
    rt_cross3(a, b, ab);
    float U = rt_dot3(r->dir, bc), V = rt_dot3(r->dir, ca), W = rt_dot3(r->dir, ab);
    if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return 0;
    float det = (U + V) + W;
    if (det == 0.0f) return 0;
    float tt = RT_DIV(rt_dot3(a, bc), det);
    if (!(tt >= tmin && tt <= tmax)) return 0;
    *t = tt;
    *u = RT_DIV(V, det);
    *v = RT_DIV(W, det);
    return 1;
}

/* Badouel 1990 (Wald's projection variant): hit the plane, then a 2D
 * barycentric test in the projection that drops the normal's largest axis. */
RT_FN int rt_tri_badouel(RT_GLOBAL const rt_tri *tri, const rt_ray *r, float tmin, float tmax,
                         float *t, float *u, float *v) {
    float e1[3], e2[3], n[3], a[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = tri->v1[i] - tri->v0[i];
        e2[i] = tri->v2[i] - tri->v0[i];
        a[i] = tri->v0[i] - r->org[i];
    }
    rt_cross3(e1, e2, n);
    float nd = rt_dot3(n, r->dir);
    if (nd == 0.0f) return 0;
    float tt = RT_DIV(rt_dot3(n, a), nd);
    if (!(tt >= tmin && tt <= tmax)) return 0;
    float nx = RT_FABS(n[0]), ny = RT_FABS(n[1]), nz = RT_FABS(n[2]);
    rt_i32 k = 0;
    if (ny > nx) k = 1;
    if (nz > (k == 1 ? ny : nx)) k = 2;
    rt_i32 i1 = k == 0 ? 1 : 0, i2 = k == 2 ? 1 : 2;
    float p1 = (r->org[i1] + tt * r->dir[i1]) - tri->v0[i1];
    float p2 = (r->org[i2] + tt * r->dir[i2]) - tri->v0[i2];
    float det = e1[i1] * e2[i2] - e1[i2] * e2[i1];
    float uu = RT_DIV(p1 * e2[i2] - p2 * e2[i1], det);
    float vv = RT_DIV(e1[i1] * p2 - e1[i2] * p1, det);
    if (!(uu >= 0.0f && vv >= 0.0f && uu + vv <= 1.0f)) return 0;
    *t = tt;
    *u = uu;
    *v = vv;
    return 1;
}

/* The triangle test selected by method (RT_TRI_*). OpenCL kernels pass a
 * compile-time constant, so the switch folds away. */
RT_FN int rt_tri_test(rt_u32 method, RT_GLOBAL const rt_tri *tri, const rt_ray *r,
                      const rt_ray_pre *p, float tmin, float tmax, float *t, float *u, float *v) {
    if (method == RT_TRI_MOLLER) return rt_tri_moller(tri, r, tmin, tmax, t, u, v);
    if (method == RT_TRI_PLUECKER) return rt_tri_pluecker(tri, r, tmin, tmax, t, u, v);
    if (method == RT_TRI_BADOUEL) return rt_tri_badouel(tri, r, tmin, tmax, t, u, v);
    return rt_tri_watertight(tri, r, p, tmin, tmax, t, u, v);
}

#endif /* RT_KERNELS_TRI_H */
