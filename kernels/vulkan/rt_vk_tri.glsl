/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_tri.glsl - the GLSL mirror of kernels/rt_tri.h: the four
 * ray/triangle tests (a triangle passed by index) and the choice between
 * them. */
#ifndef RT_VK_TRI_GLSL
#define RT_VK_TRI_GLSL

#include "rt_vk_ray.glsl"
#include "rt_vk_tri_t.glsl"
#include "rt_vk_view.glsl"

void rt_edge_recheck(float Ax, float Ay, float Bx, float By, float Cx, float Cy, out float U,
                     out float V, out float W) {
    U = RT_DOP(Cx, By, Cy, Bx);
    V = RT_DOP(Ax, Cy, Ay, Cx);
    W = RT_DOP(Bx, Ay, By, Ax);
}

bool rt_tri_watertight(uint e, rt_ray r, rt_ray_pre p, float tmin, float tmax, out float t,
                       out float u, out float v) {
    float A[3], B[3], C[3];
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        A[i] = tris[e].v0[i] - r.org[i];
        B[i] = tris[e].v1[i] - r.org[i];
        C[i] = tris[e].v2[i] - r.org[i];
    }
    int kx = p.kx, ky = p.ky, kz = p.kz;
    float Akx = rt_pick3(A, kx), Aky = rt_pick3(A, ky), Akz = rt_pick3(A, kz);
    float Bkx = rt_pick3(B, kx), Bky = rt_pick3(B, ky), Bkz = rt_pick3(B, kz);
    float Ckx = rt_pick3(C, kx), Cky = rt_pick3(C, ky), Ckz = rt_pick3(C, kz);
    float Ax = Akx - p.sx * Akz, Ay = Aky - p.sy * Akz;
    float Bx = Bkx - p.sx * Bkz, By = Bky - p.sy * Bkz;
    float Cx = Ckx - p.sx * Ckz, Cy = Cky - p.sy * Ckz;
    float U = Cx * By - Cy * Bx;
    float V = Ax * Cy - Ay * Cx;
    float W = Bx * Ay - By * Ax;
    if (U == 0.0 || V == 0.0 || W == 0.0) rt_edge_recheck(Ax, Ay, Bx, By, Cx, Cy, U, V, W);
    t = 0.0;
    u = 0.0;
    v = 0.0;
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    float det = (U + V) + W;
    if (det == 0.0) return false;
    float Az = p.sz * Akz, Bz = p.sz * Bkz, Cz = p.sz * Ckz;
    float T = (U * Az + V * Bz) + W * Cz;
    float tt = RT_DIV(T, det);
    int check = rt_tri_t_check(Akz, Bkz, Ckz, p.sx, p.sy, Ax, Ay, Bx, By, Cx, Cy, Az, Bz, Cz, det,
                               tt, tmin);
    if (check == RT_T_BEFORE) return false;
    if (check == RT_T_PLANE) tt = rt_tri_t_plane(e, r, tt);
    if (!(tt >= tmin && tt <= tmax)) return false;
    t = tt;
    u = RT_DIV(V, det);
    v = RT_DIV(W, det);
    return true;
}

bool rt_tri_moller(uint e, rt_ray r, float tmin, float tmax, out float t, out float u,
                   out float v) {
    float e1[3], e2[3], s[3], pv[3], q[3];
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        e1[i] = tris[e].v1[i] - tris[e].v0[i];
        e2[i] = tris[e].v2[i] - tris[e].v0[i];
        s[i] = r.org[i] - tris[e].v0[i];
    }
    t = 0.0;
    u = 0.0;
    v = 0.0;
    rt_cross3(r.dir, e2, pv);
    float det = rt_dot3(e1, pv);
    if (det == 0.0) return false;
    float inv = RT_DIV(1.0, det);
    float uu = rt_dot3(s, pv) * inv;
    if (!(uu >= 0.0 && uu <= 1.0)) return false;
    rt_cross3(s, e1, q);
    float vv = rt_dot3(r.dir, q) * inv;
    if (!(vv >= 0.0 && uu + vv <= 1.0)) return false;
    float tt = rt_dot3(e2, q) * inv;
    if (!(tt >= tmin && tt <= tmax)) return false;
    t = tt;
    u = uu;
    v = vv;
    return true;
}

bool rt_tri_pluecker(uint e, rt_ray r, float tmin, float tmax, out float t, out float u,
                     out float v) {
    float a[3], b[3], c[3], bc[3], ca[3], ab[3];
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        a[i] = tris[e].v0[i] - r.org[i];
        b[i] = tris[e].v1[i] - r.org[i];
        c[i] = tris[e].v2[i] - r.org[i];
    }
    t = 0.0;
    u = 0.0;
    v = 0.0;
    rt_cross3(b, c, bc);
    rt_cross3(c, a, ca);
    rt_cross3(a, b, ab);
    float U = rt_dot3(r.dir, bc), V = rt_dot3(r.dir, ca), W = rt_dot3(r.dir, ab);
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    float det = (U + V) + W;
    if (det == 0.0) return false;
    float tt = RT_DIV(rt_dot3(a, bc), det);
    if (!(tt >= tmin && tt <= tmax)) return false;
    t = tt;
    u = RT_DIV(V, det);
    v = RT_DIV(W, det);
    return true;
}

bool rt_tri_badouel(uint e, rt_ray r, float tmin, float tmax, out float t, out float u,
                    out float v) {
    float e1[3], e2[3], n[3], a[3];
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        e1[i] = tris[e].v1[i] - tris[e].v0[i];
        e2[i] = tris[e].v2[i] - tris[e].v0[i];
        a[i] = tris[e].v0[i] - r.org[i];
    }
    t = 0.0;
    u = 0.0;
    v = 0.0;
    rt_cross3(e1, e2, n);
    float nd = rt_dot3(n, r.dir);
    if (nd == 0.0) return false;
    float tt = RT_DIV(rt_dot3(n, a), nd);
    if (!(tt >= tmin && tt <= tmax)) return false;
    float nx = RT_FABS(n[0]), ny = RT_FABS(n[1]), nz = RT_FABS(n[2]);
    int k = 0;
    if (ny > nx) k = 1;
    if (nz > (k == 1 ? ny : nx)) k = 2;
    int i1 = k == 0 ? 1 : 0, i2 = k == 2 ? 1 : 2;
    float e1i1 = rt_pick3(e1, i1), e1i2 = rt_pick3(e1, i2);
    float e2i1 = rt_pick3(e2, i1), e2i2 = rt_pick3(e2, i2);
    float p1 = (rt_pick3(r.org, i1) + tt * rt_pick3(r.dir, i1)) - tris[e].v0[i1];
    float p2 = (rt_pick3(r.org, i2) + tt * rt_pick3(r.dir, i2)) - tris[e].v0[i2];
    float det = e1i1 * e2i2 - e1i2 * e2i1;
    float uu = RT_DIV(p1 * e2i2 - p2 * e2i1, det);
    float vv = RT_DIV(e1i1 * p2 - e1i2 * p1, det);
    if (!(uu >= 0.0 && vv >= 0.0 && uu + vv <= 1.0)) return false;
    t = tt;
    u = uu;
    v = vv;
    return true;
}

bool rt_tri_test(uint method, uint e, rt_ray r, rt_ray_pre p, float tmin, float tmax,
                 out float t, out float u, out float v) {
    if (method == RT_TRI_MOLLER) return rt_tri_moller(e, r, tmin, tmax, t, u, v);
    if (method == RT_TRI_PLUECKER) return rt_tri_pluecker(e, r, tmin, tmax, t, u, v);
    if (method == RT_TRI_BADOUEL) return rt_tri_badouel(e, r, tmin, tmax, t, u, v);
    return rt_tri_watertight(e, r, p, tmin, tmax, t, u, v);
}

#endif
