/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_hit_normals.c - rt_hit's geometric normal and mesh id (rt.h).
 *
 * - The normal is unit length (within float rounding) and points along the
 *   world-space triangle's winding normal (v1 - v0) x (v2 - v0), computed
 *   here independently (world vertices from the object matrix, in double),
 *   times the sign of the matrix's determinant (normals follow the surface
 *   through a mirror): for identity, rotated and translated, non-uniformly
 *   scaled and mirrored instances, and triangles from 1e-16 to 1e18 across.
 * - mesh is the instance's mesh; a miss has normal 0 and mesh UINT32_MAX.
 * - The normal and mesh of an any-hit answer are those of its triangle (or
 *   none, for the packets' answers, which name no triangle), and a coherent
 *   beam (packets) and random rays (single rays) are both answered.
 * - cpu and packet (packets and single rays) give the same rt_hit bytes, and
 *   so do 1 and 3 threads.
 * The device backends compute no normals: the host does it after their trace
 * (host/render/trace.c), so their hits' bits (test_opencl_oracle,
 * test_vulkan_oracle, tests/python) decide their normals. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt.h"

enum { RAYS = 6000, COHERENT = 256 }; /* the last COHERENT rays: two packets' worth of a beam */

/* Mesh 0: a tetrahedron with its faces wound outwards. Mesh 1: a triangle
 * 1e-16 across. Mesh 2: one 1e18 across, far out. */
static const float tet[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const uint32_t tet_idx[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
static const float tiny[9] = {0, 0, 0, 1e-16f, 0, 0, 0, 1e-16f, 0};
static const float huge[9] = {-1e18f, -1e18f, 5e18f, 1e18f, -1e18f, 5e18f, 0, 1e18f, 5e18f};
static const uint32_t one_idx[3] = {0, 1, 2};

typedef struct inst_def {
    uint32_t mesh;
    float m[16];
} inst_def;

/* The tiny triangle as it is (identity, near the origin, where its floats
 * are fine); the tetrahedron rotated 90 degrees about z and moved, scaled
 * (2, 0.5, 3) and moved, mirrored in x and moved, and only moved; the huge
 * triangle as it is. */
static const inst_def insts[] = {
    {1, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}},
    {0, {0, -1, 0, 4, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}},
    {0, {2, 0, 0, -4, 0, 0.5f, 0, 0, 0, 0, 3, 0, 0, 0, 0, 1}},
    {0, {-1, 0, 0, 0, 0, 1, 0, 4, 0, 0, 1, 0, 0, 0, 0, 1}},
    {0, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 3, 0, 0, 0, 1}},
    {2, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}},
};
enum { INSTS = sizeof insts / sizeof insts[0] };

static const float *mesh_pos(uint32_t m) {
    return m == 0 ? tet : m == 1 ? tiny : huge;
}
static const uint32_t *mesh_idx(uint32_t m) {
    return m == 0 ? tet_idx : one_idx;
}

static rt_scene *make_scene(void) {
    rt_scene *s = NULL;
    uint32_t id, mat;
    rt_material mt = rt_material_default();
    CHECK(rt_scene_create(&s) == RT_OK);
    CHECK(rt_material_add(s, &mt, &mat) == RT_OK);
    for (uint32_t m = 0; m < 3; m++) {
        CHECK(rt_mesh_create(s, &id) == RT_OK && id == m);
        CHECK(rt_mesh_add_triangles(s, m, mesh_pos(m), NULL, m == 0 ? 4 : 3, mesh_idx(m),
                                    m == 0 ? 4 : 1) == RT_OK);
    }
    for (uint32_t i = 0; i < INSTS; i++) {
        CHECK(rt_object_create(s, mat, &id) == RT_OK && id == i);
        CHECK(rt_object_add_mesh(s, i, insts[i].mesh) == RT_OK);
        CHECK(rt_object_transform(s, i, insts[i].m) == RT_OK);
    }
    CHECK_EQ_INT(rt_scene_mesh_count(s), 3);
    CHECK_EQ_INT(rt_scene_object_count(s), INSTS);
    return s;
}

static void world_point(const float *m, const float *p, double *out) {
    for (int r = 0; r < 3; r++)
        out[r] = (double)m[4 * r] * p[0] + (double)m[4 * r + 1] * p[1] +
                 (double)m[4 * r + 2] * p[2] + (double)m[4 * r + 3];
}

/* The reference: the world triangle's winding normal, unit, times the
 * determinant's sign. */
static void reference_normal(uint32_t inst, uint32_t prim, double n[3]) {
    const inst_def *d = &insts[inst];
    const float *pos = mesh_pos(d->mesh);
    const uint32_t *idx = mesh_idx(d->mesh) + 3 * prim;
    double w[3][3];
    for (int k = 0; k < 3; k++) world_point(d->m, pos + 3 * idx[k], w[k]);
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) e1[k] = w[1][k] - w[0][k], e2[k] = w[2][k] - w[0][k];
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const float *m = d->m;
    double det = m[0] * ((double)m[5] * m[10] - (double)m[6] * m[9]) -
                 m[1] * ((double)m[4] * m[10] - (double)m[6] * m[8]) +
                 m[2] * ((double)m[4] * m[9] - (double)m[5] * m[8]);
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) n[k] = n[k] / len * (det < 0 ? -1.0 : 1.0);
}

static uint32_t next(uint32_t *seed) {
    *seed = *seed * 1664525u + 1013904223u;
    return *seed >> 8;
}
static float uniform(uint32_t *seed) {
    return (float)next(seed) / 16777216.0f;
}

/* Rays at random points of random instances' triangles (so the tiny and the
 * huge one are hit too), from random directions, and some random rays that
 * mostly miss. */
static void make_rays(rt_ray *rays) {
    uint32_t seed = 12345u;
    for (int i = 0; i < RAYS; i++) {
        rt_ray *r = &rays[i];
        uint32_t inst = next(&seed) % INSTS;
        const inst_def *d = &insts[inst];
        uint32_t prim = d->mesh == 0 ? next(&seed) % 4 : 0;
        const float *pos = mesh_pos(d->mesh);
        const uint32_t *idx = mesh_idx(d->mesh) + 3 * prim;
        float a = uniform(&seed), b = uniform(&seed) * (1.0f - a);
        float p[3];
        for (int k = 0; k < 3; k++)
            p[k] = (1.0f - a - b) * pos[3 * idx[0] + k] + a * pos[3 * idx[1] + k] +
                   b * pos[3 * idx[2] + k];
        double w[3];
        world_point(d->m, p, w);
        float dir[3] = {uniform(&seed) - 0.5f, uniform(&seed) - 0.5f, uniform(&seed) - 0.5f};
        const double back = d->mesh == 1 ? 1e-15 : d->mesh == 2 ? 1e17 : 3.0;
        for (int k = 0; k < 3; k++) {
            r->org[k] = (float)(w[k] - back * dir[k]);
            r->dir[k] = (float)(back * dir[k]);
        }
        r->tmin = 0.0f;
        r->tmax = INFINITY;
        if (i % 10 == 9) { /* a random ray: a hit or a miss */
            for (int k = 0; k < 3; k++) r->org[k] = 20.0f * uniform(&seed) - 10.0f;
        }
        if (i >= RAYS - COHERENT) { /* a beam down onto the rotated tetrahedron */
            const int j = i - (RAYS - COHERENT);
            *r = (rt_ray){{3.7f + 0.01f * (float)(j % 16), 0.1f + 0.01f * (float)(j / 16), 5.0f},
                          {0.0f, 0.0f, -1.0f},
                          0.0f,
                          INFINITY};
        }
    }
}

static void check_hits(const rt_hit *h, const rt_ray *rays, int any_hit, int *hits_seen) {
    for (int i = 0; i < RAYS; i++) {
        if (!h[i].hit) {
            CHECK_MSG(h[i].mesh == UINT32_MAX && h[i].normal[0] == 0.0f && h[i].normal[1] == 0.0f &&
                          h[i].normal[2] == 0.0f,
                      "ray %d: a miss with mesh %u", i, h[i].mesh);
            continue;
        }
        ++*hits_seen;
        if (any_hit && h[i].inst == UINT32_MAX) { /* a packet's any hit names no triangle */
            CHECK_MSG(h[i].mesh == UINT32_MAX && h[i].normal[0] == 0.0f && h[i].normal[1] == 0.0f &&
                          h[i].normal[2] == 0.0f,
                      "ray %d: an any hit without a triangle has mesh %u", i, h[i].mesh);
            continue;
        }
        CHECK_MSG(h[i].inst < INSTS && h[i].mesh == insts[h[i].inst].mesh,
                  "ray %d: mesh %u for instance %u", i, h[i].mesh, h[i].inst);
        if (h[i].inst >= INSTS) continue;
        const float *n = h[i].normal;
        double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        CHECK_MSG(fabs(len - 1.0) < 4e-7, "ray %d: |normal| = %.9g", i, len);
        double ref[3];
        reference_normal(h[i].inst, h[i].prim, ref);
        double dot = n[0] * ref[0] + n[1] * ref[1] + n[2] * ref[2];
        CHECK_MSG(dot > 1.0 - 1e-6, "ray %d (%s, inst %u prim %u): normal %g %g %g, want %g %g %g",
                  i, any_hit ? "any hit" : "closest", h[i].inst, h[i].prim, n[0], n[1], n[2],
                  ref[0], ref[1], ref[2]);
    }
    (void)rays;
}

int main(void) {
    rt_scene *s = make_scene();
    rt_ray *rays = malloc(sizeof *rays * RAYS);
    rt_hit *want = malloc(sizeof *want * RAYS), *got = malloc(sizeof *got * RAYS);
    CHECK(s && rays && want && got);
    if (!s || !rays || !want || !got) return TEST_END();
    make_rays(rays);

    rt_renderer *cpu = test_renderer("cpu", 1);
    rt_trace_options opt;
    memset(&opt, 0, sizeof opt);
    CHECK(rt_trace_rays(cpu, s, rays, RAYS, want, &opt) == RT_OK);
    int hits_seen = 0;
    check_hits(want, rays, 0, &hits_seen);
    CHECK_MSG(hits_seen > RAYS / 2, "only %d of %d rays hit", hits_seen, RAYS);
    int tiny_hits = 0, huge_hits = 0, mirror_hits = 0;
    for (int i = 0; i < RAYS; i++) {
        tiny_hits += want[i].hit && want[i].mesh == 1;
        huge_hits += want[i].hit && want[i].mesh == 2;
        mirror_hits += want[i].hit && want[i].inst == 3;
    }
    CHECK_MSG(tiny_hits > 50 && huge_hits > 50 && mirror_hits > 50,
              "hits: tiny %d, huge %d, mirrored %d", tiny_hits, huge_hits, mirror_hits);

    /* Every CPU backend, path and thread count: the same bytes. */
    const char *backends[] = {"cpu", "packet", "packet", "packet"};
    const rt_trace_path paths[] = {RT_TRACE_PATH_AUTO, RT_TRACE_PATH_AUTO, RT_TRACE_PATH_PACKETS,
                                   RT_TRACE_PATH_SINGLE};
    for (int b = 0; b < 4; b++)
        for (int threads = 1; threads <= 3; threads += 2) {
            rt_renderer *r = test_renderer(backends[b], threads);
            memset(got, 0xab, sizeof *got * RAYS);
            opt.packet_path = paths[b];
            CHECK(rt_trace_rays(r, s, rays, RAYS, got, &opt) == RT_OK);
            CHECK_MSG(memcmp(got, want, sizeof *got * RAYS) == 0,
                      "%s (path %d), %d threads: hits differ from the oracle's", backends[b],
                      (int)paths[b], threads);
        }
    opt.packet_path = RT_TRACE_PATH_AUTO;

    /* Any hit: the normal and mesh of the triangle it reports. */
    opt.any_hit = 1;
    for (int b = 0; b < 2; b++) {
        CHECK(rt_trace_rays(test_renderer(backends[b], 1), s, rays, RAYS, got, &opt) == RT_OK);
        int seen = 0;
        check_hits(got, rays, 1, &seen);
        CHECK_EQ_INT(seen, hits_seen);
    }
    free(rays);
    free(want);
    free(got);
    rt_scene_destroy(s);
    return TEST_END();
}
