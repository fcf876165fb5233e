/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_tri_t.glsl - the GLSL mirror of kernels/rt_tri_t.h: the fast t's
 * error bound and the plane's t in float-float arithmetic (the bounds and
 * their proofs are there). spv_precise decorates every operation
 * NoContraction, so the two-sum and the split keep their meaning. */
#ifndef RT_VK_TRI_T_GLSL
#define RT_VK_TRI_T_GLSL

#include "rt_vk_ray.glsl"
#include "rt_vk_view.glsl"

#define RT_T_REL_BOUND 7.62939453125e-06
#define RT_T_BEFORE_FLOOR 7.88860905221011805411728565283e-31
#define RT_T_FAST   0
#define RT_T_PLANE  1
#define RT_T_BEFORE 2

float rt_tri_t_max(float a, float b) {
    return a > b ? a : b;
}

int rt_tri_t_check(float Akz, float Bkz, float Ckz, float sx, float sy, float Ax, float Ay,
                   float Bx, float By, float Cx, float Cy, float Az, float Bz, float Cz, float det,
                   float t, float tmin) {
    float S = rt_tri_t_max(RT_FABS(sx), RT_FABS(sy));
    float K = rt_tri_t_max(RT_FABS(Akz), rt_tri_t_max(RT_FABS(Bkz), RT_FABS(Ckz)));
    float P = rt_tri_t_max(rt_tri_t_max(RT_FABS(Ax), RT_FABS(Ay)),
                           rt_tri_t_max(rt_tri_t_max(RT_FABS(Bx), RT_FABS(By)),
                                        rt_tri_t_max(RT_FABS(Cx), RT_FABS(Cy))));
    float zmax = rt_tri_t_max(Az, rt_tri_t_max(Bz, Cz));
    float zmin = -rt_tri_t_max(-Az, rt_tri_t_max(-Bz, -Cz));
    float Z = rt_tri_t_max(zmax, -zmin);
    float adet = RT_FABS(det);
    float lhs = (((S * K + 0.75 * P) * P) * (zmax - zmin)) * 0.5 + (adet * Z) * 0.0625;
    if (!(lhs > RT_FABS(t) * adet)) return RT_T_FAST;
    if (((tmin - t) * adet) * 32768.0 > lhs && lhs > RT_T_BEFORE_FLOOR) return RT_T_BEFORE;
    return RT_T_PLANE;
}

void rt_ff_two_sum(float a, float b, out float s, out float e) {
    float x = a + b;
    float bv = x - a;
    float av = x - bv;
    s = x;
    e = (a - av) + (b - bv);
}

void rt_ff_split(float a, out float hi, out float lo) {
    float c = 4097.0 * a;
    float h = c - (c - a);
    hi = h;
    lo = a - h;
}

void rt_ff_mul(float a, float alo, float as, float al2, float b, float blo, float bs, float bl2,
               out float ph, out float pl) {
    float x = a * b;
    float e = ((((as * bs - x) + as * bl2) + al2 * bs) + al2 * bl2) + (a * blo + alo * b);
    float h = x + e;
    ph = h;
    pl = e - (h - x);
}

void rt_ff_add(float ah, float al, float bh, float bl, out float sh, out float sl) {
    float s, e;
    rt_ff_two_sum(ah, bh, s, e);
    e = e + (al + bl);
    rt_ff_two_sum(s, e, sh, sl);
}

float rt_ff_sum_err(float a, float b, float s) {
    float bv = s - a;
    float av = s - bv;
    return (a - av) + (b - bv);
}

/* The triangle's k-th coordinate of 9 (v0, v1, v2), by selects: C indexes
 * the struct's floats in a row. */
float rt_tri_coord(uint e, int k) {
    int i = k % 3, w = k / 3;
    return w == 0 ? tris[e].v0[i] : (w == 1 ? tris[e].v1[i] : tris[e].v2[i]);
}

int rt_tri_t_apex(uint tri) {
    float l0 = 0.0, l1 = 0.0, l2 = 0.0;
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        float a = tris[tri].v1[i] - tris[tri].v2[i], b = tris[tri].v2[i] - tris[tri].v0[i];
        float c = tris[tri].v0[i] - tris[tri].v1[i];
        l0 = l0 + a * a;
        l1 = l1 + b * b;
        l2 = l2 + c * c;
    }
    return (l0 >= l1 && l0 >= l2) ? 0 : (l1 >= l2 ? 3 : 6);
}

void rt_tri_t_normal(uint tri, int ip, out float e[3], out float f[3], out float n[3],
                     out float m[3]) {
    int iq = ip == 6 ? 0 : ip + 3, is = iq == 6 ? 0 : iq + 3;
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        float vp = rt_tri_coord(tri, ip + i);
        e[i] = rt_tri_coord(tri, iq + i) - vp;
        f[i] = rt_tri_coord(tri, is + i) - vp;
    }
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        int j = i == 2 ? 0 : i + 1, k = j == 2 ? 0 : j + 1;
        float x = e[j] * f[k], y = e[k] * f[j];
        n[i] = x - y;
        m[i] = RT_FABS(x) + RT_FABS(y);
    }
}

void rt_tri_t_normal_ff(uint tri, int ip, float e[3], float f[3], out float nh[3],
                        out float nl[3]) {
    int iq = ip == 6 ? 0 : ip + 3, is = iq == 6 ? 0 : iq + 3;
    float el[3], es[3], et[3], fl[3], fs[3], ft[3];
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        float vp = rt_tri_coord(tri, ip + i);
        el[i] = rt_ff_sum_err(rt_tri_coord(tri, iq + i), -vp, e[i]);
        fl[i] = rt_ff_sum_err(rt_tri_coord(tri, is + i), -vp, f[i]);
        rt_ff_split(e[i], es[i], et[i]);
        rt_ff_split(f[i], fs[i], ft[i]);
    }
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        int j = i == 2 ? 0 : i + 1, k = j == 2 ? 0 : j + 1;
        float xh, xl, yh, yl;
        rt_ff_mul(e[j], el[j], es[j], et[j], f[k], fl[k], fs[k], ft[k], xh, xl);
        rt_ff_mul(e[k], el[k], es[k], et[k], f[j], fl[j], fs[j], ft[j], yh, yl);
        rt_ff_add(xh, xl, -yh, -yl, nh[i], nl[i]);
    }
}

float rt_tri_t_plane(uint tri, rt_ray r, float t_fast) {
    int ip = rt_tri_t_apex(tri);
    float e[3], f[3], a[3], n[3], m[3], vp[3];
    rt_tri_t_normal(tri, ip, e, f, n, m);
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        vp[i] = rt_tri_coord(tri, ip + i);
        a[i] = vp[i] - r.org[i];
    }
    float N = 0.0, D = 0.0, bn = 0.0, bd = 0.0;
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        N = N + n[i] * a[i];
        D = D + n[i] * r.dir[i];
        bn = bn + (RT_FABS(n[i]) + m[i]) * RT_FABS(a[i]);
        bd = bd + (3.0 * RT_FABS(n[i]) + 4.0 * m[i]) * RT_FABS(r.dir[i]);
    }
    float aN = RT_FABS(N), aD = RT_FABS(D);
    if ((4.0 * bn) * aD + bd * aN + aN * aD <= 128.0 * (aN * aD)) {
        float t = RT_DIV(N, D);
        if (t - t == 0.0 && aN * aD > 0.0) return t;
    }
    float nh[3], nl[3];
    rt_tri_t_normal_ff(tri, ip, e, f, nh, nl);
    float al[3], as[3], at[3], ds[3], dt[3];
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        al[i] = rt_ff_sum_err(vp[i], -r.org[i], a[i]);
        rt_ff_split(a[i], as[i], at[i]);
        rt_ff_split(r.dir[i], ds[i], dt[i]);
    }
    float Nh = 0.0, Nl = 0.0, Dh = 0.0, Dl = 0.0;
    for (int i = 0; i < 3; i++, RT_VK_TICK) {
        float ns, nt, ph, pl;
        rt_ff_split(nh[i], ns, nt);
        rt_ff_mul(nh[i], nl[i], ns, nt, a[i], al[i], as[i], at[i], ph, pl);
        rt_ff_add(Nh, Nl, ph, pl, Nh, Nl);
        rt_ff_mul(nh[i], nl[i], ns, nt, r.dir[i], 0.0, ds[i], dt[i], ph, pl);
        rt_ff_add(Dh, Dl, ph, pl, Dh, Dl);
    }
    float t = RT_DIV(Nh, Dh);
    return t - t == 0.0 ? t : t_fast;
}

#endif
