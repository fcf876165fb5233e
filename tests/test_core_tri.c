/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_tri.c - the ray/box and ray/triangle tests of kernels/rt_box.h and rt_tri.h
 * on hand-made cases: hit, miss, edge, vertex, parallel, degenerate, the
 * inclusive [tmin, tmax], both faces, watertightness on a shared edge, and
 * rt_tri_t_check's early miss (RT_T_BEFORE) against the exact t. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt_shared.h"

static const char *const method_names[] = {"watertight", "moller", "pluecker", "badouel"};

static rt_tri make_tri(float ax, float ay, float az, float bx, float by, float bz, float cx,
                       float cy, float cz) {
    rt_tri t = {{ax, ay, az}, {bx, by, bz}, {cx, cy, cz}};
    return t;
}

static rt_ray make_ray(float ox, float oy, float oz, float dx, float dy, float dz, float tmin,
                       float tmax) {
    rt_ray r = {{ox, oy, oz}, {dx, dy, dz}, tmin, tmax};
    return r;
}

static int hit(int method, const rt_tri *tri, const rt_ray *r, float *t, float *u, float *v) {
    rt_ray_pre p;
    rt_ray_prepare(r, &p);
    return rt_tri_test((rt_u32)method, tri, r, &p, r->tmin, r->tmax, t, u, v);
}

static void triangle_cases(int m) {
    const char *name = method_names[m];
    rt_tri tri = make_tri(0, 0, 0, 1, 0, 0, 0, 1, 0);
    float t = -1, u = -1, v = -1;

    rt_ray r = make_ray(0.25f, 0.5f, 1, 0, 0, -1, 0, INFINITY);
    CHECK_MSG(hit(m, &tri, &r, &t, &u, &v), "%s: plain hit", name);
    CHECK_MSG(t == 1.0f && u == 0.25f && v == 0.5f, "%s: t %g u %g v %g", name, t, u, v);

    /* t is in units of the (unnormalised) direction. */
    r = make_ray(0.25f, 0.5f, 1, 0, 0, -2, 0, INFINITY);
    CHECK_MSG(hit(m, &tri, &r, &t, &u, &v) && t == 0.5f, "%s: t in direction units: %g", name, t);

    /* Back face counts too. */
    r = make_ray(0.25f, 0.25f, -1, 0, 0, 1, 0, INFINITY);
    CHECK_MSG(hit(m, &tri, &r, &t, &u, &v) && t == 1.0f, "%s: back face", name);

    r = make_ray(0.75f, 0.75f, 1, 0, 0, -1, 0, INFINITY);
    CHECK_MSG(!hit(m, &tri, &r, &t, &u, &v), "%s: miss beyond the hypotenuse", name);
    r = make_ray(-0.1f, 0.5f, 1, 0, 0, -1, 0, INFINITY);
    CHECK_MSG(!hit(m, &tri, &r, &t, &u, &v), "%s: miss left", name);
    r = make_ray(0.25f, 0.25f, 1, 0, 0, 1, 0, INFINITY);
    CHECK_MSG(!hit(m, &tri, &r, &t, &u, &v), "%s: triangle behind the origin", name);

    /* Edges and vertices are inside. */
    r = make_ray(0.5f, 0, 1, 0, 0, -1, 0, INFINITY);
    CHECK_MSG(hit(m, &tri, &r, &t, &u, &v) && u == 0.5f && v == 0.0f, "%s: edge v0-v1", name);
    r = make_ray(0, 0.5f, 1, 0, 0, -1, 0, INFINITY);
    CHECK_MSG(hit(m, &tri, &r, &t, &u, &v) && u == 0.0f && v == 0.5f, "%s: edge v0-v2", name);
    r = make_ray(0.5f, 0.5f, 1, 0, 0, -1, 0, INFINITY);
    CHECK_MSG(hit(m, &tri, &r, &t, &u, &v), "%s: hypotenuse", name);
    r = make_ray(0, 0, 1, 0, 0, -1, 0, INFINITY);
    CHECK_MSG(hit(m, &tri, &r, &t, &u, &v) && u == 0.0f && v == 0.0f, "%s: vertex v0", name);
    r = make_ray(1, 0, 1, 0, 0, -1, 0, INFINITY);
    CHECK_MSG(hit(m, &tri, &r, &t, &u, &v) && u == 1.0f && v == 0.0f, "%s: vertex v1", name);

    /* A ray in the triangle's plane misses, through its inside or not. */
    r = make_ray(-1, 0.25f, 0, 1, 0, 0, -INFINITY, INFINITY);
    CHECK_MSG(!hit(m, &tri, &r, &t, &u, &v), "%s: ray in the plane", name);
    r = make_ray(-1, -1, 0, 1, 1, 0, -INFINITY, INFINITY);
    CHECK_MSG(!hit(m, &tri, &r, &t, &u, &v), "%s: diagonal ray in the plane", name);
    r = make_ray(-1, 0.25f, 1, 1, 0, 0, -INFINITY, INFINITY);
    CHECK_MSG(!hit(m, &tri, &r, &t, &u, &v), "%s: parallel above", name);

    /* Degenerate triangles: collinear, and collapsed to a point (how the
     * layout stores every zero-area triangle). */
    rt_tri line = make_tri(0, 0, 0, 1, 1, 0, 2, 2, 0);
    r = make_ray(1, 1, 1, 0, 0, -1, 0, INFINITY);
    CHECK_MSG(!hit(m, &line, &r, &t, &u, &v), "%s: collinear triangle", name);
    rt_tri point = make_tri(1, 1, 0, 1, 1, 0, 1, 1, 0);
    CHECK_MSG(!hit(m, &point, &r, &t, &u, &v), "%s: point triangle", name);
    r = make_ray(0, 0, 1, 1, 1, -1, 0, INFINITY);
    CHECK_MSG(!hit(m, &point, &r, &t, &u, &v), "%s: point triangle, oblique", name);

    /* [tmin, tmax] is inclusive at both ends. */
    r = make_ray(0.25f, 0.25f, 1, 0, 0, -1, 0, 1.0f);
    CHECK_MSG(hit(m, &tri, &r, &t, &u, &v), "%s: t == tmax hits", name);
    r.tmax = nextafterf(1.0f, 0.0f);
    CHECK_MSG(!hit(m, &tri, &r, &t, &u, &v), "%s: t just above tmax misses", name);
    r = make_ray(0.25f, 0.25f, 1, 0, 0, -1, 1.0f, INFINITY);
    CHECK_MSG(hit(m, &tri, &r, &t, &u, &v), "%s: t == tmin hits", name);
    r.tmin = nextafterf(1.0f, 2.0f);
    CHECK_MSG(!hit(m, &tri, &r, &t, &u, &v), "%s: t just below tmin misses", name);

    /* An oblique hit in 3D, all tests agree with the exact answer closely. */
    rt_tri sk = make_tri(1, 0, 0, 0, 1, 0, 0, 0, 1);
    r = make_ray(0, 0, 0, 1, 1, 1, 0, INFINITY);
    CHECK_MSG(hit(m, &sk, &r, &t, &u, &v), "%s: oblique hit", name);
    CHECK_MSG(fabsf(t - 1.0f / 3.0f) < 1e-6f && fabsf(u - 1.0f / 3.0f) < 1e-6f &&
                  fabsf(v - 1.0f / 3.0f) < 1e-6f,
              "%s: oblique t %g u %g v %g", name, t, u, v);
}

/* Rays through points of the edge shared by two triangles hit at least one of
 * them with the watertight test, from any origin. */
static void watertight_shared_edge(void) {
    rt_tri a = make_tri(0, 0, 0, 1, 0, 0, 1, 1, 0), b = make_tri(0, 0, 0, 1, 1, 0, 0, 1, 0);
    srand(7);
    int misses = 0;
    for (int i = 0; i < 20000; i++) {
        float s = (float)rand() / (float)RAND_MAX;
        float o[3] = {(float)rand() / RAND_MAX * 4 - 2, (float)rand() / RAND_MAX * 4 - 2,
                      0.1f + (float)rand() / RAND_MAX * 3};
        rt_ray r = make_ray(o[0], o[1], o[2], s - o[0], s - o[1], -o[2], 0, INFINITY);
        float t, u, v;
        int ha = hit(RT_TRI_WATERTIGHT, &a, &r, &t, &u, &v);
        int hb = hit(RT_TRI_WATERTIGHT, &b, &r, &t, &u, &v);
        if (!ha && !hb) misses++;
    }
    CHECK_MSG(misses == 0, "watertight: %d rays slipped through a shared edge", misses);
}

static int box_hit(const rt_node *n, const rt_ray *r) {
    rt_ray_pre p;
    float tn;
    rt_ray_prepare(r, &p);
    return rt_box_test(n, r, &p, r->tmin, r->tmax, &tn);
}

static void box_cases(void) {
    rt_node n = {{0, 0, 0}, {1, 1, 1}, 0, 0};
    rt_ray r = make_ray(-1, 0.5f, 0.5f, 1, 0, 0, 0, INFINITY);
    CHECK(box_hit(&n, &r));
    r = make_ray(-1, 2, 0.5f, 1, 0, 0, 0, INFINITY);
    CHECK(!box_hit(&n, &r));
    r = make_ray(2, 0.5f, 0.5f, 1, 0, 0, 0, INFINITY);
    CHECK_MSG(!box_hit(&n, &r), "box behind the ray");
    /* Origin on a slab plane, direction parallel to it (0 * inf = NaN). */
    r = make_ray(-1, 0, 0.5f, 1, 0, 0, 0, INFINITY);
    CHECK_MSG(box_hit(&n, &r), "ray along the face y = 0");
    r = make_ray(-1, 1, 1, 1, 0, 0, 0, INFINITY);
    CHECK_MSG(box_hit(&n, &r), "ray along the edge y = z = 1");
    r = make_ray(-1, 0.5f, 0.5f, 1, -0.0f, 0, 0, INFINITY);
    CHECK_MSG(box_hit(&n, &r), "negative zero direction");
    /* Inclusive ends: the box starts exactly at tmax. */
    r = make_ray(-1, 0.5f, 0.5f, 1, 0, 0, 0, 1.0f);
    CHECK_MSG(box_hit(&n, &r), "box entry == tmax");
    r.tmax = 0.5f;
    CHECK_MSG(!box_hit(&n, &r), "box beyond tmax");
    /* A flat box (one triangle in a plane). */
    rt_node flat = {{0, 0, 0}, {1, 1, 0}, 0, 0};
    r = make_ray(0.5f, 0.5f, 1, 0, 0, -1, 0, INFINITY);
    CHECK_MSG(box_hit(&flat, &r), "flat box");
    r = make_ray(0.5f, 0.5f, 1, 0.001f, 0.002f, -1, 0, INFINITY);
    CHECK_MSG(box_hit(&flat, &r), "flat box, oblique");
}

/* The surface offset moves a point to the normal's side by a distance that
 * scales with its magnitude, also far from the origin. */
static void offset_cases(void) {
    const float n[3] = {0, 0, 1};
    const float far_p[3] = {1e5f, -1e5f, 1e5f}, near_p[3] = {0.001f, 0, 0};
    float o[3];
    rt_offset_point(far_p, n, 1.0f, o);
    CHECK(o[0] == far_p[0] && o[1] == far_p[1] && o[2] > far_p[2]);
    CHECK_MSG(o[2] - far_p[2] > 1.0f, "offset at 1e5: %g", o[2] - far_p[2]);
    rt_offset_point(far_p, n, -1.0f, o);
    CHECK(o[2] < far_p[2]);
    rt_offset_point(near_p, n, 1.0f, o);
    CHECK(o[2] > 0.0f && o[2] < 1e-4f);
    const float neg[3] = {0, 0, -5e4f};
    rt_offset_point(neg, n, 1.0f, o);
    CHECK(o[2] > neg[2]);
}

/* Any normal, as a ray file of rtcl trace --offset-origins may give: huge
 * and infinite components move the point at most 256 ulps, to the normal's
 * side; NaN gives NaN. Before, (int)(256 n) was undefined for them (x86-64
 * gave INT_MIN, which flipped the point's sign). */
static void offset_any_normal(void) {
    const float p[3] = {1e5f, -1e5f, 3.0f};
    const float n[3] = {INFINITY, -INFINITY, 1e30f};
    float o[3];
    rt_offset_point(p, n, 1.0f, o);
    for (int k = 0; k < 3; k++) {
        const float moved = fabsf(o[k] - p[k]),
                    ulp = nextafterf(fabsf(p[k]), INFINITY) - fabsf(p[k]);
        CHECK_MSG(moved > 0.0f && moved <= 256.0f * ulp, "axis %d: %g moved to %g", k, (double)p[k],
                  (double)o[k]);
        CHECK_MSG((o[k] > p[k]) == (n[k] > 0.0f), "axis %d: moved against the normal", k);
    }
    /* -0 (its bits are INT_MIN) and a NaN with the largest payload: the
     * bit arithmetic overflowed int (undefined; UBSan stops here). -0 is
     * near the origin: moved by 2^-16 n. */
    float edge[3] = {-0.0f, 0.0f, 0.0f};
    const uint32_t nan_bits = 0x7fffffffu;
    memcpy(&edge[1], &nan_bits, sizeof nan_bits);
    const float down[3] = {-1.0f, 1.0f, 0.0f};
    rt_offset_point(edge, down, 1.0f, o);
    CHECK(o[0] == -0x1p-16f && isnan(o[1]) && o[2] == 0.0f);
    const float nan_n[3] = {NAN, 0.0f, 0.0f};
    rt_offset_point(p, nan_n, 1.0f, o);
    CHECK(isnan(o[0]) && o[1] == p[1] && o[2] == p[2]);
}

/* A uniform float in [lo, hi) from a 64-bit LCG. */
static float rnd(uint64_t *s, float lo, float hi) {
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * (float)(*s >> 40) * 0x1p-24f;
}

/* rt_tri_t_check as rt_tri_watertight calls it (its preamble, repeated
 * here to reach the check's verdict), for a ray that crosses the triangle;
 * -1 where the edge functions say it does not. *t gets the fast t. */
static int t_check_of(const rt_tri *tri, const rt_ray *r, float *t) {
    rt_ray_pre p;
    rt_ray_prepare(r, &p);
    float A[3], B[3], C[3];
    for (int i = 0; i < 3; i++) {
        A[i] = tri->v0[i] - r->org[i];
        B[i] = tri->v1[i] - r->org[i];
        C[i] = tri->v2[i] - r->org[i];
    }
    const int kx = p.kx, ky = p.ky, kz = p.kz;
    float Ax = A[kx] - p.sx * A[kz], Ay = A[ky] - p.sy * A[kz];
    float Bx = B[kx] - p.sx * B[kz], By = B[ky] - p.sy * B[kz];
    float Cx = C[kx] - p.sx * C[kz], Cy = C[ky] - p.sy * C[kz];
    float U = Cx * By - Cy * Bx, V = Ax * Cy - Ay * Cx, W = Bx * Ay - By * Ax;
    if (U == 0.0f || V == 0.0f || W == 0.0f) rt_edge_recheck(Ax, Ay, Bx, By, Cx, Cy, &U, &V, &W);
    if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return -1;
    const float det = (U + V) + W;
    if (det == 0.0f) return -1;
    const float Az = p.sz * A[kz], Bz = p.sz * B[kz], Cz = p.sz * C[kz];
    *t = ((U * Az + V * Bz) + W * Cz) / det;
    return rt_tri_t_check(A[kz], B[kz], C[kz], p.sx, p.sy, Ax, Ay, Bx, By, Cx, Cy, Az, Bz, Cz, det,
                          *t, r->tmin);
}

/* The exact t of the ray's crossing of the triangle's plane, in long
 * double (64 significant bits: far finer than the margins tested). */
static long double exact_t(const rt_tri *tri, const rt_ray *r) {
    long double e[3], f[3], a[3], n[3];
    for (int i = 0; i < 3; i++) {
        e[i] = (long double)tri->v1[i] - tri->v0[i];
        f[i] = (long double)tri->v2[i] - tri->v0[i];
        a[i] = (long double)tri->v0[i] - r->org[i];
    }
    for (int i = 0; i < 3; i++) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        n[i] = e[j] * f[k] - e[k] * f[j];
    }
    long double N = 0, D = 0;
    for (int i = 0; i < 3; i++) N += n[i] * a[i], D += n[i] * r->dir[i];
    return N / D;
}

/* Rays that leave a surface: from a point of the triangle (small and
 * large triangles, slivers up to 1e4 long, near and far from the origin)
 * moved off it by rt_offset_point, to either side, in random directions,
 * with tmin 0. Every RT_T_BEFORE verdict must have its exact t below
 * tmin, and the plane (the answer without the early miss) must say the
 * same; and the verdict must be common here (else the test tests nothing). */
static void t_before_cases(void) {
    uint64_t s = 12345;
    int before = 0, plane = 0, wrong = 0, changed = 0;
    for (int i = 0; i < 200000; i++) {
        const float scale = powf(10.0f, rnd(&s, -3.0f, 4.0f));
        const float far = rnd(&s, 0.0f, 1.0f) < 0.5f ? 0.0f : powf(10.0f, rnd(&s, 0.0f, 4.0f));
        const int sliver = rnd(&s, 0.0f, 1.0f) < 0.3f;
        float c[3], v[3][3];
        for (int k = 0; k < 3; k++) c[k] = rnd(&s, -far, far);
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) v[j][k] = c[k] + scale * rnd(&s, -1.0f, 1.0f);
        if (sliver) /* v2 close to the segment v0 v1 */
            for (int k = 0; k < 3; k++)
                v[2][k] = 0.5f * (v[0][k] + v[1][k]) + 1e-3f * scale * rnd(&s, -1.0f, 1.0f);
        rt_tri tri = make_tri(v[0][0], v[0][1], v[0][2], v[1][0], v[1][1], v[1][2], v[2][0],
                              v[2][1], v[2][2]);
        float b0 = rnd(&s, 0.0f, 1.0f), b1 = rnd(&s, 0.0f, 1.0f);
        if (b0 + b1 > 1.0f) b0 = 1.0f - b0, b1 = 1.0f - b1;
        float pt[3], e1[3], e2[3], ng[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = v[1][k] - v[0][k];
            e2[k] = v[2][k] - v[0][k];
            pt[k] = v[0][k] + b0 * e1[k] + b1 * e2[k];
        }
        rt_cross3(e1, e2, ng);
        rt_normalize3(ng);
        rt_ray r = make_ray(0, 0, 0, rnd(&s, -1.0f, 1.0f), rnd(&s, -1.0f, 1.0f),
                            rnd(&s, -1.0f, 1.0f), 0.0f, INFINITY);
        rt_offset_point(pt, ng, rnd(&s, 0.0f, 1.0f) < 0.5f ? 1.0f : -1.0f, r.org);
        float t;
        const int check = t_check_of(&tri, &r, &t);
        if (check == RT_T_PLANE) plane++;
        if (check != RT_T_BEFORE) continue;
        before++;
        if (!(exact_t(&tri, &r) < (long double)r.tmin)) wrong++;
        if (rt_tri_t_plane(&tri, &r, t) >= r.tmin) changed++;
    }
    CHECK_MSG(wrong == 0, "RT_T_BEFORE for %d rays whose exact t is not below tmin", wrong);
    CHECK_MSG(changed == 0, "RT_T_BEFORE for %d rays the plane would have hit", changed);
    CHECK_MSG(before > 1000, "only %d RT_T_BEFORE verdicts (%d planes): the cases miss the rule",
              before, plane);
}

int main(void) {
    for (int m = 0; m < 4; m++) triangle_cases(m);
    watertight_shared_edge();
    box_cases();
    offset_cases();
    offset_any_normal();
    t_before_cases();
    return TEST_END();
}
