/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_single.c - the single-ray tracer over wide BVHs
 * (cpu_ref/single_trace.h) gives the scalar oracle's hits bit for bit (t,
 * u, v, prim, inst, entry; any hit: the occluded flag), with every
 * instruction-set build the CPU runs (width 4 and 8):
 * - on the built-in scenes (the shipped scenes/ are these): 10^5 random and
 *   10^5 diffuse-bounce rays each, camera rays, and rays with NaN, infinite
 *   and zero components, empty and inverted ranges, tmax = -inf;
 * - with every triangle test (the others go through the shared scalar code);
 * - on a finely tessellated surface far from the origin hit at tiny t;
 * - on the shared scenes (bunny, Sponza, Sibenik) when present: 3 10^4
 *   random and 3 10^4 diffuse-bounce rays each.
 * Also runs under qemu-aarch64, where the generic build is NEON. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "formats/obj_load.h"
#include "layout/flat.h"
#include "oracle_util.h"
#include "rt_fp_mode.h"
#include "ray_sets.h"
#include "rt.h"
#include "scene/scene_builtin.h"
#include "single_trace.h"

/* Rays per set: 10^5 on the built-in (shipped) scenes; on the large shared
 * scenes fewer, so that the test stays short under qemu and sanitizers. */
enum { RAYS = 100000, SHARED_RAYS = 30000 };

/* The oracle's hits of a ray set, closest and any. */
typedef struct expected {
    rt_hit_d *closest, *any;
} expected;

static int oracle_hits(const rt_flat *flat, const rt_ray *rays, size_t n, expected *x) {
    x->closest = malloc(sizeof(rt_hit_d) * (n ? n : 1));
    x->any = malloc(sizeof(rt_hit_d) * (n ? n : 1));
    if (!x->closest || !x->any) {
        CHECK(0);
        return 0;
    }
    rt_scene_view v = rt_flat_view(flat);
    rt_counters c = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        rt_trace(&v, &rays[i], 0, &x->closest[i], &c);
        rt_trace(&v, &rays[i], 1, &x->any[i], &c);
    }
    return 1;
}

static void expected_free(expected *x) {
    free(x->closest);
    free(x->any);
}

/* Every variant the CPU runs against the oracle's hits; returns the
 * mismatches (the first few printed). */
static int compare_all(const rt_flat *flat, const rt_ray *rays, size_t n, const expected *x,
                       const char *what) {
    int bad = 0;
    rt_hit_d *got = malloc(sizeof(rt_hit_d) * (n ? n : 1));
    if (!got) return 1;
    rt_scene_view v = rt_flat_view(flat);
    const char *isas[] = {"generic", "avx2", "avx512"};
    for (int k = 0; k < 3; k++) {
        const rt_cpu_isa *isa = rt_cpu_isa_find(isas[k]);
        if (!isa) continue;
        rt_wide_bvh b;
        if (rt_wide_build(flat, rt_sw_shape(rt_cpu_isa_width(isa)), &b) != RT_OK) {
            CHECK_MSG(0, "%s: rt_wide_build failed", what);
            bad++;
            continue;
        }
        for (int any = 0; any < 2; any++) {
            rt_counters c = {0, 0, 0};
            rt_sw_trace(isa, &v, &b, rays, n, any, got, &c);
            CHECK(c.rays == (rt_u32)n);
            for (size_t i = 0; i < n; i++) {
                const rt_hit_d *want = any ? &x->any[i] : &x->closest[i];
                int ok = any ? (got[i].prim == RT_NO_HIT) == (want->prim == RT_NO_HIT)
                             : oracle_same_hit(&got[i], want) &&
                                   (want->prim == RT_NO_HIT || got[i].entry == want->entry);
                if (ok) continue;
                if (bad++ < 5) {
                    const rt_ray *r = &rays[i];
                    fprintf(stderr,
                            "%s (%s, %s) ray %zu org %.9g %.9g %.9g dir %.9g %.9g %.9g t [%g, %g]: "
                            "single t %.9g prim %d inst %d, cpu t %.9g prim %d inst %d\n",
                            what, isas[k], any ? "any hit" : "closest", i, (double)r->org[0],
                            (double)r->org[1], (double)r->org[2], (double)r->dir[0],
                            (double)r->dir[1], (double)r->dir[2], (double)r->tmin, (double)r->tmax,
                            (double)got[i].t, (int)got[i].prim, (int)got[i].inst, (double)want->t,
                            (int)want->prim, (int)want->inst);
                }
            }
        }
        rt_wide_free(&b);
    }
    free(got);
    return bad;
}

/* A ray set against the oracle, with a count of hits so that a set that
 * misses everything cannot pass unnoticed. */
static void check_set(const rt_flat *flat, const rt_ray *rays, size_t n, const char *what,
                      size_t min_hits) {
    expected x;
    if (!oracle_hits(flat, rays, n, &x)) return;
    size_t hits = 0;
    for (size_t i = 0; i < n; i++) hits += x.closest[i].prim != RT_NO_HIT;
    CHECK_MSG(hits >= min_hits, "%s: only %zu of %zu rays hit", what, hits, n);
    int bad = compare_all(flat, rays, n, &x, what);
    CHECK_MSG(bad == 0, "%s: %d rays differ from the oracle", what, bad);
    printf("%s: %zu rays, %zu hit, %d differ\n", what, n, hits, bad);
    expected_free(&x);
}

/* n random and n diffuse-bounce rays. */
static void check_incoherent(const rt_flat *flat, const char *name, uint32_t seed, size_t n) {
    rt_ray *rays = malloc(sizeof(rt_ray) * n);
    if (!rays) {
        CHECK(0);
        return;
    }
    char what[128];
    rt_rays_random(flat, seed, n, rays);
    snprintf(what, sizeof what, "%s random", name);
    check_set(flat, rays, n, what, n / 100);
    rt_rays_diffuse(flat, seed + 1, n, rays);
    snprintf(what, sizeof what, "%s diffuse", name);
    check_set(flat, rays, n, what, n / 100);
    free(rays);
}

/* Ray k of the odd kinds (as tests/test_core_packet.c's). */
static void odd_ray(int k, rt_ray *r) {
    const float nan = NAN, inf = INFINITY;
    switch (k % 15) {
    case 0:
        r->tmax = -inf;
        break;
    case 1:
        r->tmax = nan;
        break;
    case 2:
        r->tmin = nan;
        break;
    case 3:
        r->tmin = inf;
        break;
    case 4:
        r->tmin = -inf;
        break;
    case 5:
        r->tmin = 2.0f, r->tmax = 1.0f;
        break;
    case 6:
        r->tmin = r->tmax = 0.5f;
        break;
    case 7:
        r->dir[0] = r->dir[1] = r->dir[2] = nan;
        break;
    case 8:
        r->org[1] = nan;
        break;
    case 9:
        r->dir[2] = inf;
        break;
    case 10:
        r->org[0] = -inf;
        break;
    case 11:
        r->dir[0] = r->dir[1] = r->dir[2] = 0.0f;
        break;
    case 12:
        r->dir[0] = 0.0f, r->dir[1] = -0.0f;
        break;
    case 13:
        r->tmin = -inf, r->tmax = -inf;
        break;
    default:
        r->org[0] = 0.0f, r->org[1] = -0.0f;
        r->dir[0] = 0.0f;
        break;
    }
}

/* Camera rays, axis-parallel rays, odd rays, every triangle test. */
static void check_special(const rt_flat *flat, const char *name) {
    enum { N = 6000 };
    rt_ray *rays = malloc(sizeof(rt_ray) * N);
    if (!rays) {
        CHECK(0);
        return;
    }
    float lo[3], hi[3];
    rt_ray b[1];
    rt_rays_random(flat, 5, 1, b);
    for (int k = 0; k < 3; k++) lo[k] = b->org[k] - 2.0f, hi[k] = b->org[k] + 2.0f;
    oracle_rng = 99;
    for (int i = 0; i < N; i++) {
        rt_ray *r = &rays[i];
        oracle_ray(&flat->hdr, lo, hi, i, r);
        if (i % 3 == 1) { /* axis-parallel: on slab planes, zero components */
            const int axis = i % 9 / 3;
            for (int k = 0; k < 3; k++) r->dir[k] = k == axis ? (i % 2 ? 1.0f : -1.0f) : 0.0f;
        }
        if (i % 7 == 3) odd_ray(i / 7, r);
        if (i % 11 == 5) { /* rt_hit_accepted's cases: see oracle_vertex_ray */
            const rt_scene_view v = rt_flat_view(flat);
            oracle_vertex_ray(&v, lo, hi, r);
        }
    }
    char what[128];
    for (rt_u32 m = 0; m < 4; m++) {
        rt_flat f = *flat;
        f.hdr.tri_method = m;
        snprintf(what, sizeof what, "%s special (triangle test %u)", name, (unsigned)m);
        check_set(&f, rays, N, what, N / 50);
    }
    /* The same rays with flushed denormals, as the 'flush' policy traces. */
    if (rt_fp_can_flush()) {
        const rt_fp_saved saved = rt_fp_set_flush(1);
        for (rt_u32 m = 0; m < 4; m += 2) {
            rt_flat f = *flat;
            f.hdr.tri_method = m;
            snprintf(what, sizeof what, "%s special, flushed (triangle test %u)", name,
                     (unsigned)m);
            check_set(&f, rays, N, what, N / 50);
        }
        rt_fp_restore(saved);
    } else {
        printf("%s: flush-to-zero not settable on this CPU, flushed rays not tested\n", name);
    }
    free(rays);
}

/* A bumpy surface of small cells far from the origin, and bounce-like rays
 * just above it: the next triangle a fraction of a cell away, tiny t. */
static void check_far_surface(void) {
    enum { CELLS = 96 };
    const float cell = 0.25f; /* test_far_terrain's */
    float *pos;
    rt_ray *rays = malloc(sizeof(rt_ray) * 20000);
    rt_scene *s = rays ? test_far_terrain(CELLS, &pos) : NULL;
    CHECK(rays != NULL);
    if (!s) {
        free(rays);
        return;
    }
    oracle_rng = 4242;
    const rt_flat *flat = test_layout(s, 1);
    if (flat) {
        for (int i = 0; i < 20000; i++) {
            const int ci = 2 + (int)(oracle_rnd() * (CELLS - 4)),
                      cj = 2 + (int)(oracle_rnd() * (CELLS - 4));
            const float *p00 = pos + 3 * (cj * (CELLS + 1) + ci);
            rt_ray *r = &rays[i];
            r->org[0] = p00[0] + oracle_rnd() * cell, r->org[2] = p00[2] + oracle_rnd() * cell;
            r->org[1] = p00[1] + 0.002f + 0.01f * oracle_rnd();
            r->dir[0] = oracle_rnd() - 0.5f, r->dir[2] = oracle_rnd() - 0.5f;
            r->dir[1] = -0.02f - 0.3f * oracle_rnd();
            r->tmin = 0.0f;
            r->tmax = INFINITY;
        }
        check_set(flat, rays, 20000, "far surface", 15000);
    }
    rt_scene_destroy(s);
    free(pos), free(rays);
}

/* A shared OBJ scene as one object, with the given camera (or one that
 * looks at the model's centre from the front). */
static rt_scene *obj_scene(const char *rel, const float *eye, const float *at, float fov) {
    const char *path = test_shared_scene(rel);
    if (!path) return NULL;
    rt_obj_mesh m;
    rt_error err;
    if (rt_obj_load(path, &m, &err) != RT_OK) {
        CHECK_MSG(0, "%s", err.message);
        return NULL;
    }
    rt_scene *s = NULL;
    uint32_t mesh, mat, obj;
    rt_material mtl = rt_material_default();
    CHECK(rt_scene_create(&s) == RT_OK);
    CHECK(rt_mesh_create(s, &mesh) == RT_OK);
    CHECK(rt_mesh_add_triangles(s, mesh, m.positions, NULL, m.vertex_count, m.indices,
                                m.triangle_count) == RT_OK);
    CHECK(rt_material_add(s, &mtl, &mat) == RT_OK);
    CHECK(rt_object_create(s, mat, &obj) == RT_OK);
    CHECK(rt_object_add_mesh(s, obj, mesh) == RT_OK);
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < m.vertex_count; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], m.positions[3 * i + k]);
            hi[k] = fmaxf(hi[k], m.positions[3 * i + k]);
        }
    rt_camera cam = {{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, fov, 256, 144};
    for (int k = 0; k < 3; k++) {
        cam.look_at[k] = at ? at[k] : 0.5f * (lo[k] + hi[k]);
        cam.position[k] = eye ? eye[k] : cam.look_at[k];
    }
    if (!eye) cam.position[2] += 2.0f * (hi[1] - lo[1]);
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    rt_obj_free(&m);
    return s;
}

int main(void) {
    /* The builds this CPU runs, and their widths. */
    int runs = 0;
    const char *isas[] = {"generic", "avx2", "avx512"};
    for (int k = 0; k < 3; k++) {
        const rt_cpu_isa *v = rt_cpu_isa_find(isas[k]);
        if (!v) {
            printf("single build %s: not run (not in this build or not run by this CPU)\n",
                   isas[k]);
            continue;
        }
        printf("single build %s: width %d\n", rt_cpu_isa_name(v), rt_cpu_isa_width(v));
        CHECK(rt_cpu_isa_width(v) == (k == 0 ? 4 : 8));
        runs++;
    }
    CHECK(runs > 0 && rt_cpu_isa_find(NULL) != NULL && rt_cpu_isa_find("mmx") == NULL);
    rt_scene *small = test_builtin_scene("cornell", 8, 8);
    const rt_flat *small_flat = small ? test_layout(small, 1) : NULL;
    rt_wide_bvh none;
    if (small_flat)
        CHECK(rt_wide_build(small_flat, rt_sw_shape(5), &none) == RT_ERROR_INVALID_ARGUMENT);
    rt_scene_destroy(small);

    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        const char *name = rt_builtin_scene_names[i];
        rt_scene *s = test_builtin_scene(name, 64, 48);
        if (!s) continue;
        const rt_flat *flat = test_layout(s, 2);
        if (flat) {
            check_incoherent(flat, name, 11u + (uint32_t)i, RAYS);
            check_special(flat, name);
        }
        rt_scene_destroy(s);
    }
    check_far_surface();

    const float sponza_eye[3] = {-14, 3, 0}, sponza_at[3] = {10, 5, 0};
    const float sibenik_eye[3] = {-17, -10, 0}, sibenik_at[3] = {10, -7, 0};
    struct {
        const char *rel;
        const float *eye, *at;
    } shared[] = {{"stanford_bunny/stanford-bunny.obj", NULL, NULL},
                  {"sponza_dabrovic/sponza.obj", sponza_eye, sponza_at},
                  {"sibenik/sibenik.obj", sibenik_eye, sibenik_at}};
    int found = 0;
    for (size_t i = 0; i < sizeof shared / sizeof shared[0]; i++) {
        rt_scene *s = obj_scene(shared[i].rel, shared[i].eye, shared[i].at, 75.0f);
        if (!s) {
            printf("%s: not present, not tested\n", shared[i].rel);
            continue;
        }
        found++;
        const rt_flat *flat = test_layout(s, 2);
        if (flat) check_incoherent(flat, shared[i].rel, 21u + (uint32_t)i, SHARED_RAYS);
        rt_scene_destroy(s);
    }
    printf("shared scenes tested: %d of 3\n", found);
    return TEST_END();
}
