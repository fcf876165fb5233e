/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_kd.c - SAH kd-trees (host/accel/kd.h, kernels/rt_kd.h).
 *
 * - Exactness: the kd traversal gives the brute-force hit over every
 *   triangle (t, u, v bits, prim, inst) and the BVH's, for both builders and
 *   every triangle test, and the packet tracer's kd traversal (every
 *   instruction-set build the CPU runs, the same rays in packets) the
 *   oracle's, on the built-in scenes and on hard synthetic meshes:
 *   axis-aligned grids and boxes whose triangles lie in split planes, rays
 *   lying in those planes or starting on them, rays with zero direction
 *   components (parallel to the planes), flat meshes (flat cells), stacks of
 *   identical triangles (equal-t ties: the lower index must win), zero-area
 *   triangles and random soups of straddling triangles.
 * - Structure: every triangle with area is in the leaf of each of its
 *   vertices; no tree is deeper than RT_KD_MAX_DEPTH.
 * - Determinism: the same bytes for any thread count.
 * - Degenerate input never crashes a build; non-finite input is refused.
 * - The reference guard: 4000 coplanar triangles sharing a vertex (every
 *   split lowers their SAH; unguarded, the build ran out of memory after
 *   minutes) build quickly into at most (1 + RT_KD_GUARD_DUPS) x N entries,
 *   the same tree for any thread count, and trace as the BVH does. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/kd.h"
#include "accel/scene_boxes.h"
#include "base/thread_pool.h"
#include "check.h"
#include "layout/flatten.h"
#include "oracle_util.h"
#include "packet_trace.h"
#include "rt_shared.h"
#include "scene/scene.h"
#include "scene/scene_builtin.h"
#include "test_bvh_simple.h"

static rt_error lib_err;

/* The layout of scene with every mesh as a kd-tree (kd: 1 exact, 2 binned)
 * or as a BVH of the test's own builder (kd: 0). */
static int build_flat(const rt_scene *scene, int kd, uint32_t method, rt_flat *flat) {
    rt_bvh *bvhs = calloc(scene->mesh_count + 1, sizeof(rt_bvh));
    rt_kd *kds = calloc(scene->mesh_count + 1, sizeof(rt_kd));
    rt_bvh top;
    memset(&top, 0, sizeof top);
    int ok = 1;
    for (uint32_t m = 0; m < scene->mesh_count; m++) {
        const rt_mesh_data *md = &scene->meshes[m];
        if (kd) {
            rt_kd_options o = rt_kd_options_default();
            o.builder = kd == 1 ? RT_KD_EXACT : RT_KD_BINNED;
            rt_status st = rt_kd_build(md->positions, md->vertex_count, md->indices,
                                       md->triangle_count, &o, NULL, &kds[m], &lib_err);
            CHECK_MSG(st == RT_OK, "kd build: %s", lib_err.message);
            ok &= st == RT_OK;
        } else if (md->triangle_count) {
            rt_aabb *boxes = malloc(sizeof(rt_aabb) * md->triangle_count);
            rt_mesh_tri_boxes(md, boxes);
            simple_bvh_build(boxes, md->triangle_count, 4, &bvhs[m]);
            free(boxes);
        }
    }
    if (scene->object_count) {
        rt_aabb *boxes = malloc(sizeof(rt_aabb) * scene->object_count);
        for (uint32_t o = 0; o < scene->object_count; o++) rt_object_world_box(scene, o, &boxes[o]);
        simple_bvh_build(boxes, scene->object_count, 1, &top);
        free(boxes);
    }
    rt_flat_options opt = rt_flat_options_default();
    opt.tri_method = method;
    if (ok) {
        rt_status st = rt_flatten_accel(scene, bvhs, kd ? kds : NULL, &top, &opt, flat, &lib_err);
        CHECK_MSG(st == RT_OK, "flatten: %s", lib_err.message);
        ok = st == RT_OK;
    }
    for (uint32_t m = 0; m < scene->mesh_count; m++) {
        rt_bvh_free(&bvhs[m]);
        rt_kd_free(&kds[m]);
    }
    free(bvhs);
    free(kds);
    rt_bvh_free(&top);
    return ok;
}

/* ---- hard rays ------------------------------------------------------------ */

/* Coordinates on the grid the synthetic meshes use (multiples of 0.5, some
 * exactly on their planes), and directions with zero components. */
static float grid_coord(float lo, float hi) {
    int steps = (int)((hi - lo) * 2.0f) + 4;
    return lo - 1.0f + 0.5f * (float)(int)(oracle_rnd() * (float)steps);
}

static void hard_ray(const float lo[3], const float hi[3], rt_ray *r) {
    float pick = oracle_rnd();
    for (int k = 0; k < 3; k++) {
        r->org[k] = grid_coord(lo[k], hi[k]);
        float d = (float)(int)(oracle_rnd() * 3.0f) - 1.0f; /* -1, 0, 1 */
        if (pick < 0.3f)
            d += (oracle_rnd() - 0.5f) * 1e-3f; /* nearly parallel */
        else if (pick < 0.5f && d != 0.0f)
            d = oracle_rnd() * 2.0f - 1.0f;
        r->dir[k] = d;
    }
    if (r->dir[0] == 0.0f && r->dir[1] == 0.0f && r->dir[2] == 0.0f) r->dir[2] = 1.0f;
    r->tmin = oracle_rnd() < 0.2f ? 0.5f : 0.0f;
    r->tmax = oracle_rnd() < 0.2f ? 1.5f : INFINITY;
}

/* The packet tracer's kd traversal (cpu_ref/packet_kd.h) on the layout f
 * against the oracle's on the same layout, for every instruction-set build
 * the CPU runs: the n rays in packets of RT_PK_LANES in their order (the
 * hard rays point every way, so a vector's lanes disagree on the side they
 * take first), closest hit (t, u, v bits, prim, inst) and any hit; the last
 * packet is partial. Then the same with instance 0 alone, as a one-mesh
 * layout (RT_SCENE_SINGLE: no object BVH, each lane starts at its tmax as
 * the oracle does), where each lane's traversal must be the oracle's step
 * for step: the same box (node) and triangle test counts. Returns the lanes
 * that differ. */
static long pk_step_lanes;
static int compare_packets(const char *name, const rt_flat *f, const rt_ray *rays, int n) {
    rt_wide_bvh w;
    if (rt_wide_build(f, rt_pk_shape(), &w) != RT_OK) {
        CHECK_MSG(0, "%s: wide BVH", name);
        return 1;
    }
    rt_flat one = *f;
    one.hdr.instance_count = 1;
    one.hdr.flags |= RT_SCENE_SINGLE;
    const int single = f->hdr.instance_count > 0 && (f->instances[0].flags & RT_INST_IDENTITY);
    int bad = 0, builds = 0;
    for (int k = 0; rt_cpu_isa_at(k); k++) {
        const rt_cpu_isa *isa = rt_cpu_isa_find(rt_cpu_isa_at(k));
        if (!isa) continue;
        builds++;
        for (int steps = 0; steps < 1 + single; steps++) {
            rt_scene_view v = rt_flat_view(steps ? &one : f);
            for (int first = 0; first < n; first += RT_PK_LANES) {
                rt_pk_rays pr;
                memset(&pr, 0, sizeof pr);
                for (int l = 0; l < RT_PK_LANES && first + l < n; l++) {
                    rt_pk_set_ray(&pr, l, &rays[first + l]);
                    pr.valid |= (rt_pk_mask)1 << l;
                }
                for (int any = 0; any < 2; any++) {
                    rt_pk_hits ph;
                    rt_pk_counts pc;
                    memset(&pc, 0, sizeof pc);
                    pc.per_lane = 1;
                    rt_pk_trace(isa, &v, &w, &pr, any, &ph, &pc);
                    for (int l = 0; l < RT_PK_LANES && first + l < n; l++) {
                        rt_hit_d want, got;
                        rt_counters c = {0, 0, 0};
                        rt_trace(&v, &rays[first + l], any, &want, &c);
                        rt_pk_get_hit(&ph, l, &got);
                        int ok = any ? (got.prim == RT_NO_HIT) == (want.prim == RT_NO_HIT)
                                     : oracle_same_hit(&got, &want);
                        if (steps) {
                            ok &= pc.c[l].box_tests == c.box_tests &&
                                  pc.c[l].tri_tests == c.tri_tests;
                            pk_step_lanes++;
                        }
                        if (!ok && bad < 5) {
                            const rt_ray *r = &rays[first + l];
                            fprintf(stderr,
                                    "%s packet %s%s ray %d any %d org (%a %a %a) dir (%a %a %a): "
                                    "packet t %a prim %u (tests %u %u), cpu t %a prim %u (%u %u)\n",
                                    name, rt_cpu_isa_name(isa), steps ? " one mesh" : "", first + l,
                                    any, (double)r->org[0], (double)r->org[1], (double)r->org[2],
                                    (double)r->dir[0], (double)r->dir[1], (double)r->dir[2],
                                    (double)got.t, got.prim, pc.c[l].box_tests, pc.c[l].tri_tests,
                                    (double)want.t, want.prim, c.box_tests, c.tri_tests);
                        }
                        bad += !ok;
                    }
                }
            }
        }
    }
    CHECK_MSG(builds > 0, "%s: no packet build runs on this CPU", name);
    rt_wide_free(&w);
    return bad;
}

/* A ray at the fan (x = 0, test_guard): from either side or from within its
 * plane, to a point of its box or its shared vertex (the origin). */
static void fan_ray(const float lo[3], const float hi[3], rt_ray *r) {
    float to[3] = {0.0f, 0.0f, 0.0f},
          ext = hi[1] - lo[1] > hi[2] - lo[2] ? hi[1] - lo[1] : hi[2] - lo[2];
    if (oracle_rnd() < 0.8f)
        for (int k = 1; k < 3; k++) to[k] = lo[k] + (hi[k] - lo[k]) * oracle_rnd();
    float side = oracle_rnd();
    r->org[0] = ext * (side < 0.1f    ? 0.0f
                       : side < 0.55f ? -0.5f - oracle_rnd()
                                      : 0.5f + oracle_rnd());
    for (int k = 1; k < 3; k++)
        r->org[k] = lo[k] - ext + (hi[k] - lo[k] + 2.0f * ext) * oracle_rnd();
    for (int k = 0; k < 3; k++) r->dir[k] = to[k] - r->org[k];
    if (r->dir[0] == 0.0f && r->dir[1] == 0.0f && r->dir[2] == 0.0f) r->dir[0] = 1.0f;
    r->tmin = oracle_rnd() < 0.2f ? 0.5f : 0.0f; /* the point aimed at is at t = 1 */
    r->tmax = oracle_rnd() < 0.2f ? 1.5f : INFINITY;
}

/* Traces rays through the kd layouts and the BVH layout of scene and against
 * brute force (hard: 1 adds hard rays, 2 fan rays), and the kd layouts
 * through the packet tracer; returns the mismatches. */
static int compare(const char *name, const rt_scene *scene, uint32_t method, int rays, int hard) {
    rt_flat fb, fk, fkb;
    if (!build_flat(scene, 0, method, &fb)) return 1;
    if (!build_flat(scene, 1, method, &fk)) return 1;
    if (!build_flat(scene, 2, method, &fkb)) return 1;
    rt_scene_view vb = rt_flat_view(&fb), vk = rt_flat_view(&fk), vkb = rt_flat_view(&fkb);
    float lo[3], hi[3];
    rt_scene_bounds(scene, lo, hi);
    int bad = 0, hits = 0;
    rt_ray *all = malloc(sizeof(rt_ray) * (size_t)rays);
    for (int i = 0; i < rays; i++) {
        rt_ray r;
        if (hard == 2 && i % 4 != 0)
            fan_ray(lo, hi, &r);
        else if (hard && i % 3 != 0)
            hard_ray(lo, hi, &r);
        else
            oracle_ray(&fb.hdr, lo, hi, i, &r);
        all[i] = r;
        /* A few lanes whose range limits nothing (rt_box_hi(tmax) NaN) for
         * the packets: they never hit but still walk the tree. */
        if (i % 50 == 7) all[i].tmax = i % 100 == 7 ? NAN : -INFINITY;
        for (int any = 0; any < 2; any++) {
            rt_hit_d brute, hb, hk, hkb;
            rt_counters c = {0, 0, 0};
            oracle_brute_force(&vb, &r, any, &brute);
            rt_trace(&vb, &r, any, &hb, &c);
            rt_trace(&vk, &r, any, &hk, &c);
            rt_trace(&vkb, &r, any, &hkb, &c);
            int ok;
            if (any) /* any hit: occlusion agrees (which hit is free) */
                ok = (brute.prim == RT_NO_HIT) == (hk.prim == RT_NO_HIT) &&
                     (brute.prim == RT_NO_HIT) == (hkb.prim == RT_NO_HIT);
            else
                ok = oracle_same_hit(&brute, &hk) && oracle_same_hit(&brute, &hkb) &&
                     oracle_same_hit(&brute, &hb);
            hits += !any && brute.prim != RT_NO_HIT;
            if (!ok && bad < 5)
                fprintf(stderr,
                        "%s method %u ray %d any %d org (%a %a %a) dir (%a %a %a) [%a %a]: "
                        "brute t %a prim %u inst %u; kd t %a prim %u inst %u; binned t %a "
                        "prim %u; bvh t %a prim %u\n",
                        name, method, i, any, (double)r.org[0], (double)r.org[1], (double)r.org[2],
                        (double)r.dir[0], (double)r.dir[1], (double)r.dir[2], (double)r.tmin,
                        (double)r.tmax, (double)brute.t, brute.prim, brute.inst, (double)hk.t,
                        hk.prim, hk.inst, (double)hkb.t, hkb.prim, (double)hb.t, hb.prim);
            bad += !ok;
        }
    }
    /* The packets with the watertight test (their vector test) and with
     * Moller-Trumbore (lane by lane through the shared test, as the other
     * two): CI's qemu and sanitizer runs are slow. */
    const int pk_bad = method <= RT_TRI_MOLLER ? compare_packets(name, &fk, all, rays) +
                                                     compare_packets(name, &fkb, all, rays)
                                               : 0;
    free(all);
    printf("%-28s method %u: %d rays, %d closest hits, %d mismatches, %d packet lanes differ%s\n",
           name, method, rays, hits, bad, pk_bad,
           method <= RT_TRI_MOLLER ? "" : " (packets not run)");
    bad += pk_bad;
    CHECK_MSG(hits > rays / 20, "%s: too few hits (%d) for the test to mean much", name, hits);
    rt_flat_free(&fb);
    rt_flat_free(&fk);
    rt_flat_free(&fkb);
    return bad;
}

/* ---- synthetic meshes ----------------------------------------------------------- */

static uint32_t add_mesh(rt_scene *s, const float *pos, uint32_t nv, const uint32_t *idx,
                         uint32_t nt) {
    uint32_t m, o;
    CHECK(rt_mesh_create(s, &m) == RT_OK);
    if (nt) CHECK(rt_mesh_add_triangles(s, m, pos, NULL, nv, idx, nt) == RT_OK);
    CHECK(rt_object_create(s, 0, &o) == RT_OK);
    CHECK(rt_object_add_mesh(s, o, m) == RT_OK);
    return m;
}

static rt_scene *new_scene(void) {
    rt_scene *s;
    CHECK(rt_scene_create(&s) == RT_OK);
    rt_material mat = rt_material_default();
    uint32_t id;
    CHECK(rt_material_add(s, &mat, &id) == RT_OK);
    return s;
}

/* An n x n grid of unit quads in the plane axis = c (two triangles each). */
static void grid(rt_scene *s, int axis, float c, int n) {
    float *pos = malloc(sizeof(float) * 3 * (size_t)(n + 1) * (size_t)(n + 1));
    uint32_t *idx = malloc(sizeof(uint32_t) * 6 * (size_t)n * (size_t)n);
    int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (int i = 0; i <= n; i++)
        for (int j = 0; j <= n; j++) {
            float *p = pos + 3 * (i * (n + 1) + j);
            p[axis] = c;
            p[a] = (float)i;
            p[b] = (float)j;
        }
    uint32_t t = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            uint32_t v = (uint32_t)(i * (n + 1) + j), w = v + (uint32_t)(n + 1);
            uint32_t q[6] = {v, w, w + 1, v, w + 1, v + 1};
            memcpy(idx + 6 * t, q, sizeof q);
            t++;
        }
    add_mesh(s, pos, (uint32_t)((n + 1) * (n + 1)), idx, 2 * t);
    free(pos);
    free(idx);
}

/* Axis-aligned boxes on the half-integer grid: triangles in split planes,
 * edges on planes, flat cells between touching faces. */
static rt_scene *scene_boxes(void) {
    rt_scene *s = new_scene();
    grid(s, 2, 0.0f, 6);
    grid(s, 0, 2.0f, 4);
    grid(s, 1, 3.0f, 5);
    /* Cubes touching face to face. */
    float pos[8 * 3 * 4];
    uint32_t idx[36 * 4];
    static const uint32_t cube[36] = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                                      2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
    for (int c = 0; c < 4; c++) {
        for (int v = 0; v < 8; v++) {
            pos[3 * (8 * c + v) + 0] = 0.5f + (float)c + (float)(v >> 2 & 1);
            pos[3 * (8 * c + v) + 1] = 0.5f + (float)(v >> 1 & 1);
            pos[3 * (8 * c + v) + 2] = 1.0f + 0.5f * (float)(v & 1);
        }
        for (int i = 0; i < 36; i++) idx[36 * c + i] = cube[i] + 8u * (uint32_t)c;
    }
    add_mesh(s, pos, 32, idx, 48);
    return s;
}

/* A flat mesh (every triangle in z = 1), a stack of identical triangles
 * (ties), zero-area triangles and a triangle twice with opposite winding. */
static rt_scene *scene_degenerate(void) {
    rt_scene *s = new_scene();
    grid(s, 2, 1.0f, 5);
    float pos[] = {0, 0, 2, 3, 0, 2, 0, 3, 2, /* the stacked triangle */
                   1, 1, 0, 1, 1, 0, 2, 2, 0, /* zero area: two equal vertices */
                   0, 0, 3, 1, 1, 3, 2, 2, 3, /* zero area: collinear */
                   0, 4, 1, 3, 4, 1, 0, 4, 4};
    uint32_t idx[3 * 40];
    uint32_t t = 0;
    for (int i = 0; i < 30; i++, t++) idx[3 * t] = 0, idx[3 * t + 1] = 1, idx[3 * t + 2] = 2;
    idx[3 * t] = 3, idx[3 * t + 1] = 4, idx[3 * t + 2] = 5, t++;
    idx[3 * t] = 6, idx[3 * t + 1] = 7, idx[3 * t + 2] = 8, t++;
    idx[3 * t] = 9, idx[3 * t + 1] = 10, idx[3 * t + 2] = 11, t++;
    idx[3 * t] = 9, idx[3 * t + 1] = 11, idx[3 * t + 2] = 10, t++;
    add_mesh(s, pos, 12, idx, t);
    /* A mesh with no triangle of any area. */
    add_mesh(s, pos + 9, 6, (const uint32_t[]){0, 1, 2, 3, 4, 5}, 2);
    return s;
}

/* Random triangles in a box: large ones straddle many cells. */
static void soup(rt_scene *s, uint32_t n, float size) {
    float *pos = malloc(sizeof(float) * 9 * n);
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * n);
    for (uint32_t t = 0; t < n; t++) {
        float c[3];
        for (int k = 0; k < 3; k++) c[k] = 8.0f * oracle_rnd();
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++)
                pos[9 * t + 3 * v + k] = c[k] + size * (oracle_rnd() - 0.5f);
        for (int v = 0; v < 3; v++) idx[3 * t + v] = 3 * t + (uint32_t)v;
    }
    add_mesh(s, pos, 3 * n, idx, n);
    free(pos);
    free(idx);
}

/* n triangles in the plane x = 0 sharing the vertex (0, 0, 0), legs of
 * scale x [1, 2] along y and z: they all overlap near the shared vertex. */
static void fan(rt_scene *s, uint32_t n, float scale) {
    float *pos = malloc(sizeof(float) * 9 * n);
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * n);
    for (uint32_t t = 0; t < n; t++) {
        float leg = scale * (1.0f + oracle_rnd());
        float v[9] = {0, 0, 0, 0, leg, 0, 0, 0, leg};
        memcpy(pos + 9 * t, v, sizeof v);
        for (int k = 0; k < 3; k++) idx[3 * t + k] = 3 * t + (uint32_t)k;
    }
    add_mesh(s, pos, 3 * n, idx, n);
    free(pos);
    free(idx);
}

/* ---- structure ---------------------------------------------------------------- */

/* Is triangle t in the leaf (or, on a split plane, a leaf) holding point p? */
static int in_leaf_at(const rt_kd *kd, uint32_t node, const float *p, uint32_t t, int depth) {
    const rt_kd_node *n = &kd->nodes[node];
    if ((n->b & 3u) == RT_KD_LEAF) {
        for (uint32_t e = n->a; e < n->a + (n->b >> 2); e++)
            if (kd->prims[e] == t) return 1;
        return 0;
    }
    if (depth > RT_KD_MAX_DEPTH) return 0;
    float split;
    memcpy(&split, &n->a, sizeof split);
    int k = (int)(n->b & 3u);
    if (p[k] < split) return in_leaf_at(kd, node + 1, p, t, depth + 1);
    if (p[k] > split) return in_leaf_at(kd, n->b >> 2, p, t, depth + 1);
    return in_leaf_at(kd, node + 1, p, t, depth + 1) || in_leaf_at(kd, n->b >> 2, p, t, depth + 1);
}

static void check_structure(const char *name, const rt_mesh_data *md, const rt_kd *kd) {
    rt_kd_quality q = rt_kd_measure(kd, (rt_sah_costs){1.0f, 1.5f});
    CHECK_MSG(q.depth <= RT_KD_MAX_DEPTH, "%s: depth %u", name, q.depth);
    int missing = 0;
    for (uint32_t t = 0; t < md->triangle_count; t++) {
        const float *v[3];
        for (int i = 0; i < 3; i++) v[i] = md->positions + 3 * md->indices[3 * t + i];
        float e1[3], e2[3], n[3];
        for (int k = 0; k < 3; k++) e1[k] = v[1][k] - v[0][k], e2[k] = v[2][k] - v[0][k];
        rt_cross3(e1, e2, n);
        if (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f) continue;
        for (int i = 0; i < 3; i++) missing += !in_leaf_at(kd, 0, v[i], t, 0);
    }
    CHECK_MSG(missing == 0, "%s: %d triangle vertices not in their leaves", name, missing);
}

static int same_tree(const rt_kd *a, const rt_kd *b) {
    return a->node_count == b->node_count && a->prim_count == b->prim_count &&
           !memcmp(a->nodes, b->nodes, sizeof(rt_kd_node) * a->node_count) &&
           !memcmp(a->prims, b->prims, sizeof(uint32_t) * a->prim_count) &&
           !memcmp(&a->bounds, &b->bounds, sizeof a->bounds);
}

static void test_determinism(void) {
    rt_scene *s = new_scene();
    soup(s, 12000, 0.6f);
    const rt_mesh_data *md = &s->meshes[0];
    for (int b = 0; b < 2; b++) {
        rt_kd_options o = rt_kd_options_default();
        o.builder = b ? RT_KD_BINNED : RT_KD_EXACT;
        rt_kd ref;
        CHECK(rt_kd_build(md->positions, md->vertex_count, md->indices, md->triangle_count, &o,
                          NULL, &ref, &lib_err) == RT_OK);
        check_structure(b ? "soup binned" : "soup exact", md, &ref);
        for (int threads = 1; threads <= 4; threads++) {
            rt_pool *pool = rt_pool_create(threads);
            rt_kd kd;
            CHECK(rt_kd_build(md->positions, md->vertex_count, md->indices, md->triangle_count, &o,
                              pool, &kd, &lib_err) == RT_OK);
            CHECK_MSG(same_tree(&ref, &kd), "%s tree differs with %d threads",
                      rt_kd_builder_name(o.builder), threads);
            rt_kd_free(&kd);
            rt_pool_destroy(pool);
        }
        rt_kd_free(&ref);
    }
    rt_scene_destroy(s);
}

static void test_degenerate_builds(void) {
    rt_kd_options o = rt_kd_options_default();
    for (int b = 0; b < 2; b++) {
        o.builder = b ? RT_KD_BINNED : RT_KD_EXACT;
        rt_kd kd;
        /* Nothing at all; only zero-area triangles: one empty leaf. */
        CHECK(rt_kd_build(NULL, 0, NULL, 0, &o, NULL, &kd, &lib_err) == RT_OK);
        CHECK(kd.node_count == 1 && kd.prim_count == 0);
        rt_kd_free(&kd);
        float pts[] = {1, 1, 1, 1, 1, 1, 2, 2, 2, 0, 0, 0};
        uint32_t idx[] = {0, 1, 2, 0, 2, 3, 3, 3, 3};
        CHECK(rt_kd_build(pts, 4, idx, 3, &o, NULL, &kd, &lib_err) == RT_OK);
        CHECK(kd.node_count == 1 && kd.prim_count == 0);
        rt_kd_free(&kd);
        /* Non-finite coordinates and bad indices are refused. */
        float bad[] = {0, 0, 0, 1, 0, 0, 0, NAN, 0};
        uint32_t tri[] = {0, 1, 2};
        CHECK(rt_kd_build(bad, 3, tri, 1, &o, NULL, &kd, &lib_err) == RT_ERROR_INVALID_ARGUMENT);
        bad[7] = INFINITY;
        CHECK(rt_kd_build(bad, 3, tri, 1, &o, NULL, &kd, &lib_err) == RT_ERROR_INVALID_ARGUMENT);
        uint32_t far[] = {0, 1, 7};
        CHECK(rt_kd_build(pts, 4, far, 1, &o, NULL, &kd, &lib_err) == RT_ERROR_INVALID_ARGUMENT);
        /* More triangles than the events' 30-bit index holds: refused before
         * any is read. */
        CHECK(rt_kd_build(pts, 4, far, 1u << 30, &o, NULL, &kd, &lib_err) ==
              RT_ERROR_INVALID_ARGUMENT);
        /* 3000 copies of one triangle: the depth bound ends it. */
        uint32_t *many = malloc(sizeof(uint32_t) * 9000);
        float one[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        for (int i = 0; i < 9000; i++) many[i] = (uint32_t)(i % 3);
        CHECK(rt_kd_build(one, 3, many, 3000, &o, NULL, &kd, &lib_err) == RT_OK);
        rt_kd_quality q = rt_kd_measure(&kd, (rt_sah_costs){1.0f, 1.5f});
        CHECK(q.depth <= RT_KD_MAX_DEPTH && kd.prim_count >= 3000);
        rt_kd_free(&kd);
        free(many);
    }
}

/* The reference guard on the fan: bounded entries, the same tree for 1
 * and 2 threads, every triangle in the leaves of its vertices; and the
 * guard leaves ordinary meshes alone (a soup builds the same tree with it
 * off). */
static void test_guard(void) {
    const uint32_t n = 4000;
    rt_pool *pool = rt_pool_create(2);
    for (int b = 0; b < 2; b++) {
        rt_scene *s = new_scene();
        fan(s, n, 0.01f);
        const rt_mesh_data *md = &s->meshes[0];
        rt_kd_options o = rt_kd_options_default();
        o.builder = b ? RT_KD_BINNED : RT_KD_EXACT;
        rt_kd one, two;
        CHECK(rt_kd_build(md->positions, md->vertex_count, md->indices, md->triangle_count, &o,
                          NULL, &one, &lib_err) == RT_OK);
        CHECK(rt_kd_build(md->positions, md->vertex_count, md->indices, md->triangle_count, &o,
                          pool, &two, &lib_err) == RT_OK);
        rt_kd_quality q = rt_kd_measure(&one, (rt_sah_costs){1.0f, 1.0f});
        printf("fan of %u, %s: %u nodes, %u entries (bound %.0f), depth %u\n", n,
               rt_kd_builder_name(o.builder), one.node_count, one.prim_count,
               (1.0 + RT_KD_GUARD_DUPS) * n, q.depth);
        CHECK_MSG(one.prim_count >= n && one.prim_count <= (uint32_t)((1.0 + RT_KD_GUARD_DUPS) * n),
                  "fan %s: %u entries", rt_kd_builder_name(o.builder), one.prim_count);
        CHECK_MSG(same_tree(&one, &two), "fan %s: 2 threads give another tree",
                  rt_kd_builder_name(o.builder));
        check_structure(b ? "fan binned" : "fan exact", md, &one);
        rt_kd_free(&one);
        rt_kd_free(&two);
        rt_scene_destroy(s);
    }
    rt_pool_destroy(pool);
    rt_scene *s = new_scene();
    soup(s, 1500, 1.0f);
    const rt_mesh_data *md = &s->meshes[0];
    for (int b = 0; b < 2; b++) {
        rt_kd_options o = rt_kd_options_default();
        o.builder = b ? RT_KD_BINNED : RT_KD_EXACT;
        rt_kd on, off;
        CHECK(rt_kd_build(md->positions, md->vertex_count, md->indices, md->triangle_count, &o,
                          NULL, &on, &lib_err) == RT_OK);
        o.ref_guard = 0;
        CHECK(rt_kd_build(md->positions, md->vertex_count, md->indices, md->triangle_count, &o,
                          NULL, &off, &lib_err) == RT_OK);
        CHECK_MSG(same_tree(&on, &off), "soup %s: the guard changed the tree",
                  rt_kd_builder_name(o.builder));
        rt_kd_free(&on);
        rt_kd_free(&off);
    }
    rt_scene_destroy(s);
}

/* The per-mesh choice (rt.h): set, read, refused values, names, and the
 * static-mesh rule (keyframes of an animated object keep theirs). */
static void test_api(void) {
    rt_scene *s;
    CHECK(rt_scene_builtin("cornell", &s, &lib_err) == RT_OK);
    uint32_t v = s->meshes[0].version, sv = s->version;
    CHECK(rt_mesh_accel(s, 0) == RT_ACCEL_BVH);
    CHECK(rt_mesh_set_accel(s, 0, RT_ACCEL_KD) == RT_OK);
    CHECK(rt_mesh_accel(s, 0) == RT_ACCEL_KD);
    CHECK(s->meshes[0].version != v && s->version != sv); /* renderers rebuild it */
    CHECK(rt_mesh_set_accel(s, 0, (rt_accel)7) == RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_mesh_set_accel(s, s->mesh_count, RT_ACCEL_KD) == RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_mesh_accel(s, s->mesh_count) == RT_ACCEL_BVH);
    CHECK(rt_scene_set_static_accel(s, RT_ACCEL_KD_BINNED) == RT_OK);
    for (uint32_t o = 0; o < s->object_count; o++) {
        const rt_object_data *ob = &s->objects[o];
        for (uint32_t k = 0; k < ob->mesh_count; k++)
            CHECK(rt_mesh_accel(s, ob->meshes[k]) ==
                  (ob->mesh_count > 1 ? RT_ACCEL_BVH : RT_ACCEL_KD_BINNED));
    }
    rt_accel a;
    CHECK(rt_accel_parse("kd", &a) && a == RT_ACCEL_KD);
    CHECK(rt_accel_parse("kd-binned", &a) && a == RT_ACCEL_KD_BINNED);
    CHECK(rt_accel_parse("bvh", &a) && a == RT_ACCEL_BVH);
    CHECK(!rt_accel_parse("KD", &a) && !rt_accel_parse("", &a) && !rt_accel_parse(NULL, &a));
    rt_scene_destroy(s);
}

int main(void) {
    test_api();
    test_degenerate_builds();
    test_determinism();
    test_guard();
    int bad = 0;
    rt_scene *s;
    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        CHECK(rt_scene_builtin(rt_builtin_scene_names[i], &s, &lib_err) == RT_OK);
        for (uint32_t m = 0; m < RT_TRI_BADOUEL + 1; m++)
            bad += compare(rt_builtin_scene_names[i], s, m, m ? 800 : 3000, 0);
        rt_scene_destroy(s);
    }
    struct {
        const char *name;
        rt_scene *(*make)(void);
    } synth[] = {{"boxes (planes)", scene_boxes}, {"degenerate", scene_degenerate}};
    for (size_t i = 0; i < sizeof synth / sizeof synth[0]; i++) {
        s = synth[i].make();
        for (uint32_t m = 0; m < RT_TRI_BADOUEL + 1; m++)
            bad += compare(synth[i].name, s, m, m ? 3000 : 20000, 1);
        for (uint32_t m = 0; m < s->mesh_count; m++) {
            rt_kd kd;
            rt_kd_options o = rt_kd_options_default();
            const rt_mesh_data *md = &s->meshes[m];
            CHECK(rt_kd_build(md->positions, md->vertex_count, md->indices, md->triangle_count, &o,
                              NULL, &kd, &lib_err) == RT_OK);
            check_structure(synth[i].name, md, &kd);
            rt_kd_free(&kd);
        }
        rt_scene_destroy(s);
    }
    s = new_scene();
    soup(s, 3000, 1.5f);
    soup(s, 500, 0.05f);
    bad += compare("soup", s, RT_TRI_WATERTIGHT, 6000, 0);
    bad += compare("soup", s, RT_TRI_MOLLER, 1500, 0);
    rt_scene_destroy(s);
    /* The guarded fan of test_guard: equal-t ties between its overlapping
     * triangles go to the lowest index, as in the BVH. */
    s = new_scene();
    fan(s, 4000, 0.01f);
    bad += compare("coplanar fan (guarded)", s, RT_TRI_WATERTIGHT, 2000, 2);
    bad += compare("coplanar fan (guarded)", s, RT_TRI_MOLLER, 600, 2);
    rt_scene_destroy(s);
    CHECK_MSG(bad == 0, "%d rays differ", bad);
    printf("packet lanes with the oracle's box and triangle tests: %ld\n", pk_step_lanes);
    CHECK(pk_step_lanes > 10000);
    return TEST_END();
}
