/* SPDX-License-Identifier: Apache-2.0 */
/* rt_tri_t.h - an accurate hit distance for the watertight test: when the
 * fast t = T / det may be off by more than RT_T_REL_BOUND of itself
 * (rt_tri_t_unsure, a cheap a-priori error bound), t is taken from the
 * triangle's plane evaluated in float-float arithmetic (rt_tri_t_plane).
 * Valid C99 and OpenCL C (rt_math_profile.h); the GLSL mirror is
 * kernels/vulkan/rt_vk_tri_t.glsl. Only +, -, * and RT_DIV, in a fixed
 * order, so every device that rounds these correctly (OpenCL and Vulkan
 * both require it; contraction is off everywhere) gives the same bits.
 * docs/ROBUSTNESS.md, "Accurate t", states the bounds and the measurements. */
#ifndef RT_KERNELS_TRI_T_H
#define RT_KERNELS_TRI_T_H

#include "rt_ray.h"

/* ---- the fast t's error bound -------------------------------------------
 *
 * Notation of rt_tri_watertight: A, B, C the vertices less the origin,
 * (Ax, Ay) ... their sheared 2D coordinates, Az = sz A[kz] ... their
 * distances along the ray, U, V, W the edge functions, det = U + V + W,
 * t = T / det with T = U Az + V Bz + W Cz; u = 2^-24. Let S = max(|sx|, |sy|)
 * (<= 1: kz is the dominant axis), K bound |A[kz]|, |B[kz]|, |C[kz]|, P bound
 * |Ax| ... |Cy|, Z bound |Az|, |Bz|, |Cz|, R = max(Az, Bz, Cz) - min(...).
 *
 * Claim: |t_computed - t_exact| <= u ((64 S K + 48 P) P R / |det| + 8 Z).
 * Proof, to first order in u (the constants leave room for the rest):
 * - a sheared coordinate Ax = A[kx] - sx A[kz] carries the rounding of
 *   A[kx] and A[kz] (v - o), of the product and of the difference:
 *   u (|A[kx]| + 2 |sx A[kz]| + |Ax|) <= u (3 S K + 2 P), as |A[kx]| <=
 *   |Ax| + |sx A[kz]|;
 * - an edge function, say U = Cx By - Cy Bx, then errs by 4 P times that
 *   from its inputs and by 4 u P^2 from its products and difference:
 *   u (12 S K P + 12 P^2); the three together u (36 S K P + 36 P^2);
 * - t = sum U_k z_k / sum U_k moves by sum dU_k (z_k - t) / det, and for a
 *   ray that crosses the triangle the exact t lies in [min z_k, max z_k]
 *   (a convex combination), so |z_k - t| <= R;
 * - the rounded shear sx, sy tilts the ray: at the hit (|t d[kz]| <= K, the
 *   hit lies in the triangle) it is at most u S K off in x and in y, and z
 *   changes across the triangle by at most 6 R P / |det| per unit of x or of
 *   y (z = sum b_k z_k, |grad b_k| <= 2 P / |det|, sum grad b_k = 0):
 *   12 u S K R P / |det|; with the above, the first term (48 S K + 36 P
 *   rounded up to 64 and 48);
 * - the z_k carry 2 u |z_k| (v - o and the product with sz), T's three
 *   products and two sums 3 u sum |U_k z_k| <= 3 u |det| Z, the division and
 *   the rounding of sz u |t| each: below 8 u Z, the second term.
 * The triangle's extent along the ray (R) and its distance along the ray
 * (K, Z) against t are what make long triangles crossed near the origin
 * lose t: the bound grows with exactly these. */

/* The fast t is trusted where the bound above is at most this fraction of
 * |t|: 2^-17 = 7.6e-6. */
#define RT_T_REL_BOUND 7.62939453125e-06f

/* 2^-100 (exactly, in every language's decimal reading): below it
 * rt_tri_t_check does not conclude RT_T_BEFORE. */
#define RT_T_BEFORE_FLOOR 7.88860905221011805411728565283e-31f

/* The larger of a and b, written out so that every language and SIMD layer
 * picks the same operand (max() differs on NaN). */
RT_FN float rt_tri_t_max(float a, float b) {
    return a > b ? a : b;
}

/* What rt_tri_t_check says of the fast t. */
#define RT_T_FAST   0 /* within RT_T_REL_BOUND of the exact t: keep it */
#define RT_T_PLANE  1 /* maybe not: take t from the plane (rt_tri_t_plane) */
#define RT_T_BEFORE 2 /* the exact t is surely below tmin: a miss, no plane needed */

/* Whether the fast t may be off by more than RT_T_REL_BOUND |t|: the bound
 * above, multiplied out (no division) and by 2^17 u = 2^-7:
 * lhs = ((S K + 3/4 P) P R) / 2 + |det| Z / 16 > |t| |det|. The rounding of
 * this test is covered by the bound's slack. An overflow makes it 1, a NaN
 * 0; rt_tri_t_plane falls back to the fast t where its own result is not
 * finite, and a NaN t misses either way. Akz, Bkz, Ckz are A[kz], B[kz],
 * C[kz]; Az, Bz, Cz the scaled ones.
 *
 * Where the fast t is not trusted, it may still be surely below tmin:
 * RT_T_BEFORE where ((tmin - t) |det|) 2^15 > lhs and lhs > 2^-100. The
 * bound is B = 2^-17 lhs / |det|, so this says tmin - t > 4 B up to the
 * test's three roundings (each a factor 1 +- u; lhs > 2^-100 keeps the
 * product (tmin - t) |det| > 2^-115 out of the denormals, where rounding is
 * not relative, in every denormal mode): tmin - t > 3 B, and the exact
 * t <= t + B < tmin. The ray starts beyond the crossing, which is what rays
 * leaving a surface do with its triangle and the neighbours they share an
 * edge with; the plane would say the same (its t is within a few ulps of
 * the exact one) at several times the cost. A pure function of the triangle
 * and the ray (tmin is the ray's), so every traversal order agrees. */
RT_FN int rt_tri_t_check(float Akz, float Bkz, float Ckz, float sx, float sy, float Ax, float Ay,
                         float Bx, float By, float Cx, float Cy, float Az, float Bz, float Cz,
                         float det, float t, float tmin) {
    const float S = rt_tri_t_max(RT_FABS(sx), RT_FABS(sy));
    const float K = rt_tri_t_max(RT_FABS(Akz), rt_tri_t_max(RT_FABS(Bkz), RT_FABS(Ckz)));
    const float P = rt_tri_t_max(rt_tri_t_max(RT_FABS(Ax), RT_FABS(Ay)),
                                 rt_tri_t_max(rt_tri_t_max(RT_FABS(Bx), RT_FABS(By)),
                                              rt_tri_t_max(RT_FABS(Cx), RT_FABS(Cy))));
    const float zmax = rt_tri_t_max(Az, rt_tri_t_max(Bz, Cz));
    const float zmin = -rt_tri_t_max(-Az, rt_tri_t_max(-Bz, -Cz));
    const float Z = rt_tri_t_max(zmax, -zmin);
    const float adet = RT_FABS(det);
    const float lhs = (((S * K + 0.75f * P) * P) * (zmax - zmin)) * 0.5f + (adet * Z) * 0.0625f;
    if (!(lhs > RT_FABS(t) * adet)) return RT_T_FAST;
    if (((tmin - t) * adet) * 32768.0f > lhs && lhs > RT_T_BEFORE_FLOOR) return RT_T_BEFORE;
    return RT_T_PLANE;
}

/* ---- float-float arithmetic ---------------------------------------------
 *
 * A value is an unevaluated sum hi + lo of two floats. Knuth's two-sum and
 * Dekker's product with Veltkamp's split are exact for finite operands whose
 * products neither overflow nor underflow; no fused multiply-add is needed
 * (Vulkan's fma need not be fused). Each operand of a product is split once
 * (rt_ff_split) and the halves reused. */

/* s + e = a + b exactly (Knuth). */
RT_FN void rt_ff_two_sum(float a, float b, float *s, float *e) {
    const float x = a + b;
    const float bv = x - a;
    const float av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* hi + lo = a, each with at most 12 significant bits (Veltkamp). */
RT_FN void rt_ff_split(float a, float *hi, float *lo) {
    const float c = 4097.0f * a;
    const float h = c - (c - a);
    *hi = h;
    *lo = a - h;
}

/* (a + alo)(b + blo) to float-float, (as, al2) and (bs, bl2) the splits of
 * a and b: a b exactly as x + its error (Dekker), the cross terms rounded;
 * relative error below 4 u^2. The error is below 3 u |x|, so the fast
 * two-sum renormalises it. */
RT_FN void rt_ff_mul(float a, float alo, float as, float al2, float b, float blo, float bs,
                     float bl2, float *ph, float *pl) {
    const float x = a * b;
    const float e = ((((as * bs - x) + as * bl2) + al2 * bs) + al2 * bl2) + (a * blo + alo * b);
    const float h = x + e;
    *ph = h;
    *pl = e - (h - x);
}

/* (ah + al) + (bh + bl) to float-float: error below 4 u^2 (|a| + |b|). */
RT_FN void rt_ff_add(float ah, float al, float bh, float bl, float *sh, float *sl) {
    float s, e;
    rt_ff_two_sum(ah, bh, &s, &e);
    e = e + (al + bl);
    rt_ff_two_sum(s, e, sh, sl);
}

/* ---- the plane's t --------------------------------------------------------
 *
 * t = n . (p - o) / n . d with n = (q - p) x (s - p), p the vertex opposite
 * the triangle's longest edge (its two edges meet at the largest angle, so
 * their cross product loses least). In two tiers, both from the same inputs:
 *
 * 1. In float, with its own error bound (first order, u = 2^-24): each
 *    difference errs by u of itself; n_i by 4 u m_i, m_i = |e_j f_k| +
 *    |e_k f_j|; N = n . a by 4 u sum (|n_i| + m_i) |a_i|; D = n . d by
 *    u (3 sum |n_i d_i| + 4 sum m_i |d_i|); the division by u. Taken where
 *    that is at most 2^-17 |t| (as for the fast t); this catches the large
 *    triangles near the origin for which the fast t's bound is pessimistic.
 * 2. Otherwise the differences, n, N and D in float-float (D too: a ray that
 *    grazes a long triangle's plane, as rays along a road do, cancels most
 *    of n . d). For the exact inputs n's direction errs by alpha <= 16 u^2 /
 *    sin(angle at p), so at the hit, at most the longest edge l from p, the
 *    plane is off by alpha l; N errs by at most 16 u^2 |n| |p - o| besides, D
 *    by 16 u^2 |n| |d|, and rounding N and D to floats and dividing by 3 u.
 *    So |t_computed - t| <= 3 u |t| + 16 u^2 (l / sin + |p - o| + |t| |d|) /
 *    (|d| cos), cos the cosine between the ray and the normal: a few ulps of
 *    t unless the ray grazes the plane within ~1e-7 radians, whatever the
 *    triangle's length or distance from the origin (u^2 = 3.6e-15).
 * Returns t_fast where the result is not finite: the ray parallel to the
 * plane, or coordinates so far apart (beyond about 2^40) that a product of
 * three of them overflows. */

/* The exact error of s = a + b rounded (the second half of rt_ff_two_sum). */
RT_FN float rt_ff_sum_err(float a, float b, float s) {
    const float bv = s - a;
    const float av = s - bv;
    return (a - av) + (b - bv);
}

/* The vertex at offset k (0, 3 or 6) among the triangle's nine coordinates:
 * v0, v1 or v2, each indexed 0..2 only. (Indexing the nine as one row
 * through tri->v0 reads past v0's three elements, out of that array's
 * bounds: Oclgrind reports "Index (6) exceeds static array size (3)".) */
#define RT_TRI_VERTEX(tri, k) ((k) == 0 ? (tri)->v0 : ((k) == 3 ? (tri)->v1 : (tri)->v2))

/* The apex of rt_tri_t_plane: the offset (0, 3 or 6) of the vertex opposite
 * the triangle's longest edge among its nine coordinates. */
RT_FN int rt_tri_t_apex(RT_GLOBAL const rt_tri *tri) {
    float l0 = 0.0f, l1 = 0.0f, l2 = 0.0f; /* squared lengths of the edges opposite v0, v1, v2 */
    for (int i = 0; i < 3; i++) {
        const float a = tri->v1[i] - tri->v2[i], b = tri->v2[i] - tri->v0[i],
                    c = tri->v0[i] - tri->v1[i];
        l0 = l0 + a * a;
        l1 = l1 + b * b;
        l2 = l2 + c * c;
    }
    return (l0 >= l1 && l0 >= l2) ? 0 : (l1 >= l2 ? 3 : 6);
}

/* The triangle's part of tier 1: the edges e = q - p, f = s - p from the
 * apex ip (q, s the next vertices in the triangle's order), n = e x f in
 * float and m_i = |e_j f_k| + |e_k f_j|, the scale of n_i's rounding. The
 * CPU packet tracer computes it once per triangle for a packet's rays. */
RT_FN void rt_tri_t_normal(RT_GLOBAL const rt_tri *tri, int ip, float *e, float *f, float *n,
                           float *m) {
    const int iq = ip == 6 ? 0 : ip + 3, is = iq == 6 ? 0 : iq + 3;
    RT_GLOBAL const float *p = RT_TRI_VERTEX(tri, ip), *q = RT_TRI_VERTEX(tri, iq),
                          *s = RT_TRI_VERTEX(tri, is);
    for (int i = 0; i < 3; i++) {
        e[i] = q[i] - p[i];
        f[i] = s[i] - p[i];
    }
    for (int i = 0; i < 3; i++) {
        const int j = i == 2 ? 0 : i + 1, k = j == 2 ? 0 : j + 1;
        const float x = e[j] * f[k], y = e[k] * f[j];
        n[i] = x - y;
        m[i] = RT_FABS(x) + RT_FABS(y);
    }
}

/* The triangle's part of tier 2: n = e x f in float-float (nh + nl), from
 * the edges of rt_tri_t_normal and their exact rounding errors, each
 * operand split once. */
RT_FN void rt_tri_t_normal_ff(RT_GLOBAL const rt_tri *tri, int ip, const float *e, const float *f,
                              float *nh, float *nl) {
    const int iq = ip == 6 ? 0 : ip + 3, is = iq == 6 ? 0 : iq + 3;
    RT_GLOBAL const float *p = RT_TRI_VERTEX(tri, ip), *q = RT_TRI_VERTEX(tri, iq),
                          *s = RT_TRI_VERTEX(tri, is);
    float el[3], es[3], et[3], fl[3], fs[3], ft[3];
    for (int i = 0; i < 3; i++) {
        el[i] = rt_ff_sum_err(q[i], -p[i], e[i]);
        fl[i] = rt_ff_sum_err(s[i], -p[i], f[i]);
        rt_ff_split(e[i], &es[i], &et[i]);
        rt_ff_split(f[i], &fs[i], &ft[i]);
    }
    for (int i = 0; i < 3; i++) {
        const int j = i == 2 ? 0 : i + 1, k = j == 2 ? 0 : j + 1;
        float xh, xl, yh, yl;
        rt_ff_mul(e[j], el[j], es[j], et[j], f[k], fl[k], fs[k], ft[k], &xh, &xl);
        rt_ff_mul(e[k], el[k], es[k], et[k], f[j], fl[j], fs[j], ft[j], &yh, &yl);
        rt_ff_add(xh, xl, -yh, -yl, &nh[i], &nl[i]);
    }
}

RT_FN_RARE float rt_tri_t_plane(RT_GLOBAL const rt_tri *tri, const rt_ray *r, float t_fast) {
    const int ip = rt_tri_t_apex(tri);
    RT_GLOBAL const float *p = RT_TRI_VERTEX(tri, ip);
    float e[3], f[3], a[3], n[3], m[3];
    rt_tri_t_normal(tri, ip, e, f, n, m);
    for (int i = 0; i < 3; i++) a[i] = p[i] - r->org[i];
    /* Tier 1: float, with its error bound. */
    float N = 0.0f, D = 0.0f, bn = 0.0f, bd = 0.0f;
    for (int i = 0; i < 3; i++) {
        N = N + n[i] * a[i];
        D = D + n[i] * r->dir[i];
        bn = bn + (RT_FABS(n[i]) + m[i]) * RT_FABS(a[i]);
        bd = bd + (3.0f * RT_FABS(n[i]) + 4.0f * m[i]) * RT_FABS(r->dir[i]);
    }
    /* u (4 bn / |N| + bd / |D| + 1) <= 2^-17, multiplied out by |N| |D|. */
    const float aN = RT_FABS(N), aD = RT_FABS(D);
    if ((4.0f * bn) * aD + bd * aN + aN * aD <= 128.0f * (aN * aD)) {
        const float t = RT_DIV(N, D);
        if (t - t == 0.0f && aN * aD > 0.0f) return t; /* t - t: 0 for a finite t */
    }
    /* Tier 2: float-float. */
    float nh[3], nl[3];
    rt_tri_t_normal_ff(tri, ip, e, f, nh, nl);
    float al[3], as[3], at[3], ds[3], dt[3];
    for (int i = 0; i < 3; i++) {
        al[i] = rt_ff_sum_err(p[i], -r->org[i], a[i]);
        rt_ff_split(a[i], &as[i], &at[i]);
        rt_ff_split(r->dir[i], &ds[i], &dt[i]);
    }
    float Nh = 0.0f, Nl = 0.0f, Dh = 0.0f, Dl = 0.0f;
    for (int i = 0; i < 3; i++) {
        float ns, nt, ph, pl;
        rt_ff_split(nh[i], &ns, &nt);
        rt_ff_mul(nh[i], nl[i], ns, nt, a[i], al[i], as[i], at[i], &ph, &pl);
        rt_ff_add(Nh, Nl, ph, pl, &Nh, &Nl);
        rt_ff_mul(nh[i], nl[i], ns, nt, r->dir[i], 0.0f, ds[i], dt[i], &ph, &pl);
        rt_ff_add(Dh, Dl, ph, pl, &Dh, &Dl);
    }
    const float t = RT_DIV(Nh, Dh);
    return t - t == 0.0f ? t : t_fast;
}

#endif /* RT_KERNELS_TRI_T_H */
