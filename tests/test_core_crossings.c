/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_crossings.c - rt_count_intersections (rt.h, cpu_ref/crossings.c).
 *
 * - The tie rule: a ray exactly through an edge shared by two triangles, or
 *   through the vertex of a fan, crosses exactly one of them (the watertight
 *   test alone hits all of them), for rays along the axes and tilted ones.
 * - Inside/outside by parity is exact on a closed, non-convex mesh whose
 *   inside is known exactly: the surface of random voxels of a 4^3 grid (its
 *   vertices on the integer lattice, or on a shifted and scaled one), for
 *   rays aimed exactly at its vertices and edge midpoints (directions whose
 *   largest component is +-1 and the others multiples of 1/8, so that the
 *   watertight test's shear maps the target exactly onto the ray), random
 *   rays from random points, and segments between two points (parity: one
 *   of the two inside). A ray from a point inside never misses the mesh.
 * - The count does not depend on the structure (BVH, exact and binned
 *   kd-tree, a refitted BVH, an LBVH) or on the thread count.
 * - Two instances count the sum of each alone; a ray that crosses counts,
 *   so it has a hit (any-hit); invalid rays count 0. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "crossings.h"
#include "rt.h"
#include "rt_shared.h"

enum { G = 4, NV = (G + 1) * (G + 1) * (G + 1) };

static uint32_t next(uint32_t *seed) {
    *seed = *seed * 1664525u + 1013904223u;
    return *seed >> 8;
}
static float uniform(uint32_t *seed) {
    return (float)next(seed) / 16777216.0f;
}

/* ---- the tie rule on single triangles ------------------------------------ */

static int crosses(const float *v0, const float *v1, const float *v2, const float *o,
                   const float *d, int *watertight) {
    rt_tri tri;
    memcpy(tri.v0, v0, sizeof tri.v0);
    memcpy(tri.v1, v1, sizeof tri.v1);
    memcpy(tri.v2, v2, sizeof tri.v2);
    rt_ray r = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, 0.0f, INFINITY};
    rt_ray_pre p;
    rt_ray_prepare(&r, &p);
    float t, u, v;
    *watertight = rt_tri_watertight(&tri, &r, &p, r.tmin, r.tmax, &t, &u, &v);
    return rt_crossing_test(&tri, &r, &p, &t);
}

static void check_tie_rule(void) {
    /* Two triangles sharing the edge (1,0,0)-(0,1,0), and a hexagonal fan
     * around the origin, all in z = 0 (and the same turned into x = 0). */
    const float quad[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const int pair[2][3] = {{0, 1, 3}, {1, 2, 3}};
    const float hex[6][3] = {{2, 0, 0}, {1, 2, 0}, {-1, 2, 0}, {-2, 0, 0}, {-1, -2, 0}, {1, -2, 0}};
    const float centre[3] = {0, 0, 0};
    const float through_edge[3][2] = {{0.5f, 0.5f}, {0.25f, 0.75f}, {0.875f, 0.125f}};
    const float dirs[6][3] = {{0, 0, -1},         {0, 0, 1},           {0.5f, 0.25f, -1},
                              {-0.5f, 0.125f, 1}, {0.875f, -0.75f, 1}, {0, 0.5f, -1}};
    for (int swap = 0; swap < 2; swap++)
        for (int e = 0; e < 3; e++)
            for (int k = 0; k < 6; k++) {
                /* The ray through the edge point (x, y, 0): o = point - 2 d. */
                float d[3], o[3], a[2][3][3];
                for (int i = 0; i < 3; i++) d[i] = dirs[k][i];
                const float q[3] = {through_edge[e][0], through_edge[e][1], 0.0f};
                for (int i = 0; i < 3; i++) o[i] = q[i] - 2.0f * d[i];
                for (int t = 0; t < 2; t++)
                    for (int j = 0; j < 3; j++) memcpy(a[t][j], quad[pair[t][j]], sizeof a[t][j]);
                if (swap) { /* the same triangles as (z, x, y): another shear axis */
                    for (int t = 0; t < 2; t++)
                        for (int j = 0; j < 3; j++) {
                            float x = a[t][j][0], y = a[t][j][1], z = a[t][j][2];
                            a[t][j][0] = z, a[t][j][1] = x, a[t][j][2] = y;
                        }
                    float x = o[0], y = o[1], z = o[2];
                    o[0] = z, o[1] = x, o[2] = y;
                    x = d[0], y = d[1], z = d[2];
                    d[0] = z, d[1] = x, d[2] = y;
                }
                int w0, w1;
                int c = crosses(a[0][0], a[0][1], a[0][2], o, d, &w0) +
                        crosses(a[1][0], a[1][1], a[1][2], o, d, &w1);
                CHECK_MSG(c == 1, "edge point %d, direction %d, swap %d: %d crossings", e, k, swap,
                          c);
                CHECK_MSG(w0 && w1, "edge point %d, direction %d: watertight hits %d %d", e, k, w0,
                          w1);
            }
    for (int k = 0; k < 6; k++) {
        float o[3];
        for (int i = 0; i < 3; i++) o[i] = centre[i] - 2.0f * dirs[k][i];
        int c = 0, hits = 0, w;
        for (int j = 0; j < 6; j++) {
            c += crosses(centre, hex[j], hex[(j + 1) % 6], o, dirs[k], &w);
            hits += w;
        }
        CHECK_MSG(c == 1, "fan, direction %d: %d crossings (watertight hits %d)", k, c, hits);
        CHECK(hits >= 2);
    }
}

/* ---- a closed voxel surface ------------------------------------------------ */

typedef struct voxels {
    int full[G][G][G];
    float scale, offset; /* vertex (i, j, k) at offset + scale * (i, j, k) */
    float pos[3 * NV];
    uint32_t *idx;
    uint32_t tris;
} voxels;

static int full_at(const voxels *v, int x, int y, int z) {
    if (x < 0 || y < 0 || z < 0 || x >= G || y >= G || z >= G) return 0;
    return v->full[x][y][z];
}

static uint32_t vid(int x, int y, int z) {
    return (uint32_t)((x * (G + 1) + y) * (G + 1) + z);
}

static void make_voxels(voxels *v, uint32_t seed, float scale, float offset) {
    memset(v->full, 0, sizeof v->full);
    for (int x = 0; x < G; x++)
        for (int y = 0; y < G; y++)
            for (int z = 0; z < G; z++) v->full[x][y][z] = next(&seed) % 100 < 55;
    v->scale = scale;
    v->offset = offset;
    for (int x = 0; x <= G; x++)
        for (int y = 0; y <= G; y++)
            for (int z = 0; z <= G; z++) {
                float *p = v->pos + 3 * vid(x, y, z);
                p[0] = offset + scale * (float)x;
                p[1] = offset + scale * (float)y;
                p[2] = offset + scale * (float)z;
            }
    v->idx = malloc(sizeof(uint32_t) * 6 * 6 * G * G * G);
    v->tris = 0;
    for (int x = 0; x < G; x++)
        for (int y = 0; y < G; y++)
            for (int z = 0; z < G; z++) {
                if (!v->full[x][y][z]) continue;
                for (int axis = 0; axis < 3; axis++)
                    for (int side = 0; side < 2; side++) {
                        int n[3] = {x, y, z};
                        n[axis] += side ? 1 : -1;
                        if (full_at(v, n[0], n[1], n[2])) continue;
                        /* The face in the plane axis = c, corners over the other two axes. */
                        int b = (axis + 1) % 3, c = (axis + 2) % 3, q[4][3];
                        for (int k = 0; k < 4; k++) {
                            q[k][0] = x, q[k][1] = y, q[k][2] = z;
                            q[k][axis] += side;
                            q[k][b] += k == 1 || k == 2;
                            q[k][c] += k >= 2;
                        }
                        const int order[6] = {0, 1, 2, 0, 2, 3};
                        for (int k = 0; k < 6; k++)
                            v->idx[3 * v->tris + (uint32_t)k] =
                                vid(q[order[k]][0], q[order[k]][1], q[order[k]][2]);
                        v->tris += 2;
                    }
            }
}

/* Whether p is inside (1), outside (0) or on a lattice plane (-1). */
static int inside(const voxels *v, const float *p) {
    int cell[3];
    for (int k = 0; k < 3; k++) {
        float u = (p[k] - v->offset) / v->scale; /* exact: dyadic values */
        float f = floorf(u);
        if (u == f) return -1;
        cell[k] = (int)f;
    }
    return full_at(v, cell[0], cell[1], cell[2]);
}

/* Whether p lies within 1e-3 cells of a lattice plane (there a crossing's
 * t is a few ulps from 0, and the random rays leave such points out). */
static int near_plane(const voxels *v, const float *p) {
    int near = 0;
    for (int k = 0; k < 3; k++) {
        float u = (p[k] - v->offset) / v->scale;
        near |= fabsf(u - roundf(u)) < 1e-3f;
    }
    return near;
}

/* A ray from p along d over [0, tmax]. */
static void set_ray(rt_ray *r, const float *p, const float *d, float tmax) {
    memcpy(r->org, p, sizeof r->org);
    memcpy(r->dir, d, sizeof r->dir);
    r->tmin = 0.0f;
    r->tmax = tmax;
}

static rt_scene *scene_of(const voxels *v, rt_accel accel, const float *matrix, int twice) {
    rt_scene *s = NULL;
    uint32_t mesh, mat, obj;
    rt_material m = rt_material_default();
    CHECK(rt_scene_create(&s) == RT_OK);
    CHECK(rt_mesh_create(s, &mesh) == RT_OK);
    CHECK(rt_mesh_add_triangles(s, mesh, v->pos, NULL, NV, v->idx, v->tris) == RT_OK);
    CHECK(rt_mesh_set_accel(s, mesh, accel) == RT_OK);
    CHECK(rt_material_add(s, &m, &mat) == RT_OK);
    for (int i = 0; i < (twice ? 2 : 1); i++) {
        CHECK(rt_object_create(s, mat, &obj) == RT_OK);
        CHECK(rt_object_add_mesh(s, obj, mesh) == RT_OK);
        if (matrix && (i == 1 || !twice)) CHECK(rt_object_transform(s, obj, matrix) == RT_OK);
    }
    return s;
}

enum { MAX_RAYS = 40000 };

typedef struct ray_set {
    rt_ray rays[MAX_RAYS];
    int expect[MAX_RAYS]; /* parity: 1 odd, 0 even */
    int from_inside[MAX_RAYS];
    size_t n, exact_targets;
} ray_set;

/* Rays aimed exactly at every vertex and edge midpoint of the surface, then
 * random rays and segments. */
static void make_rays(const voxels *v, ray_set *set, uint32_t seed) {
    set->n = 0;
    const float steps[6] = {0.25f, 0.375f, 0.5f, 0.75f, 1.25f, 2.25f};
    for (uint32_t t = 0; t < v->tris && set->n < MAX_RAYS / 2; t++)
        for (int j = 0; j < 6; j++) {
            const float *a = v->pos + 3 * v->idx[3 * t + (uint32_t)(j % 3)];
            const float *b = v->pos + 3 * v->idx[3 * t + (uint32_t)((j + 1) % 3)];
            float q[3];
            for (int k = 0; k < 3; k++) q[k] = j < 3 ? a[k] : 0.5f * (a[k] + b[k]);
            for (int tries = 0; tries < 4; tries++) {
                float d[3];
                int kz = (int)(next(&seed) % 3);
                for (int k = 0; k < 3; k++)
                    d[k] = k == kz ? (next(&seed) & 1 ? 1.0f : -1.0f)
                                   : (float)((int)(next(&seed) % 15) - 7) / 8.0f;
                float s = steps[next(&seed) % 6] * v->scale, p[3];
                for (int k = 0; k < 3; k++) p[k] = q[k] - s * d[k];
                int in = inside(v, p);
                if (in < 0) continue;
                set_ray(&set->rays[set->n], p, d, INFINITY);
                set->expect[set->n] = in;
                set->from_inside[set->n] = in;
                set->n++;
            }
        }
    set->exact_targets = set->n;
    const float lo = v->offset - 0.5f * v->scale, span = (G + 1) * v->scale;
    while (set->n < MAX_RAYS) {
        float p[3], d[3], e[3];
        for (int k = 0; k < 3; k++) p[k] = lo + span * uniform(&seed);
        for (int k = 0; k < 3; k++) d[k] = uniform(&seed) - 0.5f;
        int in = inside(v, p);
        if (in < 0 || near_plane(v, p) || (d[0] == 0.0f && d[1] == 0.0f && d[2] == 0.0f)) continue;
        rt_ray *r = &set->rays[set->n];
        set_ray(r, p, d, INFINITY);
        set->from_inside[set->n] = in;
        if (set->n % 2) { /* a segment to another point: parity of one inside */
            float tmax = 0.5f + 4.0f * uniform(&seed);
            for (int k = 0; k < 3; k++) e[k] = p[k] + tmax * d[k];
            int in2 = inside(v, e);
            if (in2 < 0 || near_plane(v, e)) continue;
            r->tmax = tmax;
            in ^= in2;
        }
        set->expect[set->n] = in;
        set->n++;
    }
}

static void check_parity(const char *what, const ray_set *set, const uint32_t *counts) {
    int wrong = 0, wrong_exact = 0;
    for (size_t i = 0; i < set->n; i++)
        if ((int)(counts[i] & 1u) != set->expect[i]) {
            wrong++;
            wrong_exact += i < set->exact_targets;
            if (wrong <= 5)
                fprintf(stderr, "%s: ray %zu (%s): %u crossings, parity %d expected\n", what, i,
                        i < set->exact_targets ? "through a vertex or edge" : "random", counts[i],
                        set->expect[i]);
        }
    CHECK_MSG(wrong == 0, "%s: %d of %zu rays (%d of %zu exact targets) with the wrong parity",
              what, wrong, set->n, wrong_exact, set->exact_targets);
}

static void check_voxels(const voxels *v, ray_set *set, uint32_t seed) {
    make_rays(v, set, seed);
    CHECK_MSG(set->exact_targets > 2000, "only %zu exact rays", set->exact_targets);
    uint32_t *want = malloc(sizeof(uint32_t) * set->n), *got = malloc(sizeof(uint32_t) * set->n);
    rt_hit *hits = malloc(sizeof(rt_hit) * set->n);
    CHECK(want && got && hits);
    if (!want || !got || !hits) return;

    rt_scene *s = scene_of(v, RT_ACCEL_BVH, NULL, 0);
    CHECK(rt_count_intersections(test_renderer("cpu", 1), s, set->rays, set->n, want) == RT_OK);
    check_parity("bvh", set, want);

    /* From inside, the closest hit never misses; a crossing is a hit. */
    rt_trace_options opt;
    memset(&opt, 0, sizeof opt);
    CHECK(rt_trace_rays(test_renderer("packet", 0), s, set->rays, set->n, hits, &opt) == RT_OK);
    int leaks = 0, unhit = 0;
    for (size_t i = 0; i < set->n; i++) {
        leaks += set->rays[i].tmax == INFINITY && set->from_inside[i] && !hits[i].hit;
        unhit += want[i] > 0 && !hits[i].hit;
    }
    CHECK_MSG(leaks == 0, "%d rays from inside missed the closed mesh", leaks);
    CHECK_MSG(unhit == 0, "%d rays with crossings have no hit", unhit);

    /* Every structure, update and thread count: the same counts. */
    const rt_accel accels[3] = {RT_ACCEL_BVH, RT_ACCEL_KD, RT_ACCEL_KD_BINNED};
    for (int a = 0; a < 3; a++)
        for (int threads = 1; threads <= 3; threads += 2) {
            rt_scene *o = scene_of(v, accels[a], NULL, 0);
            memset(got, 0xff, sizeof(uint32_t) * set->n);
            CHECK(rt_count_intersections(test_renderer("cpu", threads), o, set->rays, set->n,
                                         got) == RT_OK);
            CHECK_MSG(memcmp(got, want, sizeof(uint32_t) * set->n) == 0,
                      "%s, %d threads: counts differ from the BVH's", rt_accel_name(accels[a]),
                      threads);
            rt_scene_destroy(o);
        }
    const rt_update_policy policies[2] = {RT_UPDATE_REFIT, RT_UPDATE_FAST};
    for (int k = 0; k < 2; k++) {
        rt_scene *o = scene_of(v, RT_ACCEL_BVH, NULL, 0);
        rt_renderer *r = test_renderer("packet", 2);
        CHECK(rt_count_intersections(r, o, set->rays, 1, got) == RT_OK);
        CHECK(rt_mesh_set_update(o, 0, policies[k]) == RT_OK);
        CHECK(rt_mesh_set_positions(o, 0, v->pos, NULL, NV) == RT_OK);
        CHECK(rt_count_intersections(r, o, set->rays, set->n, got) == RT_OK);
        CHECK_MSG(memcmp(got, want, sizeof(uint32_t) * set->n) == 0,
                  "%s: counts differ from the BVH's", rt_update_policy_name(policies[k]));
        rt_scene_destroy(o);
    }

    /* Two instances (one turned 90 degrees about z and moved beside the
     * other): the sum of each alone. */
    const float m[16] = {
        0, -1, 0, 2.0f * v->offset + (2 * G + 2) * v->scale, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    rt_scene *both = scene_of(v, RT_ACCEL_BVH, m, 1), *moved = scene_of(v, RT_ACCEL_KD, m, 0);
    uint32_t *second = malloc(sizeof(uint32_t) * set->n);
    for (size_t i = 0; i < set->n; i += 2) set->rays[i].dir[0] = fabsf(set->rays[i].dir[0]);
    CHECK(rt_count_intersections(test_renderer("cpu", 2), s, set->rays, set->n, want) == RT_OK);
    CHECK(rt_count_intersections(test_renderer("cpu", 2), moved, set->rays, set->n, second) ==
          RT_OK);
    CHECK(rt_count_intersections(test_renderer("cpu", 2), both, set->rays, set->n, got) == RT_OK);
    size_t wrong = 0, through_both = 0;
    for (size_t i = 0; i < set->n; i++) {
        wrong += got[i] != want[i] + second[i];
        through_both += want[i] && second[i];
    }
    CHECK_MSG(wrong == 0, "two instances: %zu rays count other than the sum", wrong);
    CHECK_MSG(through_both > 100, "only %zu rays cross both instances", through_both);
    free(second);
    rt_scene_destroy(both);
    rt_scene_destroy(moved);
    rt_scene_destroy(s);
    free(want);
    free(got);
    free(hits);
}

int main(void) {
    check_tie_rule();
    static ray_set set;
    static voxels v;
    /* The lattice at integers; then shifted and scaled (still exact). */
    make_voxels(&v, 7u, 1.0f, 0.0f);
    check_voxels(&v, &set, 99u);
    free(v.idx);
    make_voxels(&v, 31u, 0.125f, 96.0f);
    check_voxels(&v, &set, 5u);
    free(v.idx);

    /* Invalid rays count 0, and zero rays are fine. */
    make_voxels(&v, 7u, 1.0f, 0.0f);
    rt_scene *s = scene_of(&v, RT_ACCEL_BVH, NULL, 0);
    rt_ray bad[3] = {{{NAN, 1, 1}, {1, 0, 0}, 0, INFINITY},
                     {{1.5f, 1.5f, 1.5f}, {0, 0, 0}, 0, INFINITY},
                     {{1.5f, 1.5f, 1.5f}, {1, 0, 0}, NAN, INFINITY}};
    uint32_t counts[3] = {7, 7, 7};
    CHECK(rt_count_intersections(test_renderer("cpu", 1), s, bad, 3, counts) == RT_OK);
    CHECK(counts[0] == 0 && counts[1] == 0 && counts[2] == 0);
    CHECK(rt_count_intersections(test_renderer("cpu", 1), s, NULL, 0, NULL) == RT_OK);
    CHECK(rt_count_intersections(test_renderer("cpu", 1), s, NULL, 1, counts) ==
          RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_count_intersections(NULL, s, bad, 1, counts) == RT_ERROR_INVALID_ARGUMENT);
    rt_scene_destroy(s);
    free(v.idx);
    return TEST_END();
}
