/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_dynamic.c - deforming meshes and their update policies.
 *
 * - Every policy (refit, fast, auto, rebuild), frame after frame on one
 *   renderer, gives exactly the hits and images of a fresh SAH build of the
 *   same geometry on the cpu oracle, on the cpu and packet backends, for a
 *   mesh shown twice (once moved) beside a still floor: closest hits have a
 *   total order, so the tree's shape cannot change them.
 * - The layout rewritten in place after an update is byte for byte the
 *   layout rt_flatten makes of the same BVHs.
 * - What each policy did is reported (rt_renderer_update_stats): refit
 *   refits, fast builds the LBVH, auto refits small motions and rebuilds
 *   once the refitted tree's cost passes the bound.
 * - The LBVH is a valid tree, and the same bytes for 1, 2, 3 and 5 threads;
 *   a refit gives exactly the boxes a walk of the tree computes.
 * - rt_scene_set_time: keyframes switch at the rate and loop, blends are
 *   exact at whole keyframes, keyed transforms rotate along the shortest
 *   arc, the camera follows its path; a still scene is left as it is.
 * - kd-trees (issue 18) are for static meshes: a deforming mesh (positions
 *   set, a policy other than rebuild) keeps or gets a BVH, a still kd mesh
 *   beside a refitted one is never refitted, and a layout holding kd meshes
 *   is made anew each frame (never rewritten in place), with the oracle's
 *   hits on cpu and packet. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh_internal.h"
#include "accel/bvh_refit.h"
#include "base/thread_pool.h"
#include "bvh_validate.h"
#include "check.h"
#include "layout/flatten.h"
#include "render/renderer_internal.h"
#include "rt.h"
#include "scene/scene.h"

enum { GRID = 64 }; /* 64 x 64 quads: 8192 triangles, enough for the parallel paths */

static float *grid_positions(int frame) {
    float *p = malloc(sizeof(float) * 3 * (GRID + 1) * (GRID + 1));
    for (int y = 0; y <= GRID; y++)
        for (int x = 0; x <= GRID; x++) {
            float *v = p + 3 * (y * (GRID + 1) + x);
            float u = (float)x / GRID, w = (float)y / GRID;
            v[0] = u * 2.0f - 1.0f;
            v[1] =
                0.15f * sinf(6.0f * u + 0.7f * (float)frame) * cosf(5.0f * w - 0.4f * (float)frame);
            v[2] = w * 2.0f - 1.0f;
            if (frame == 99) { /* a violent motion: vertices thrown about */
                uint32_t h = (uint32_t)(x * 73856093u) ^ (uint32_t)(y * 19349663u);
                v[1] += (float)(h % 1000u) / 500.0f - 1.0f;
                v[0] += (float)((h >> 10) % 1000u) / 1000.0f - 0.5f;
            }
        }
    return p;
}

static uint32_t *grid_indices(void) {
    uint32_t *t = malloc(sizeof(uint32_t) * 6 * GRID * GRID), n = 0;
    for (uint32_t y = 0; y < GRID; y++)
        for (uint32_t x = 0; x < GRID; x++) {
            uint32_t a = y * (GRID + 1) + x, b = a + 1, c = a + GRID + 1, d = c + 1;
            t[n++] = a, t[n++] = c, t[n++] = b;
            t[n++] = b, t[n++] = c, t[n++] = d;
        }
    return t;
}

/* A floor, the grid, and the grid again rotated and lifted. */
static rt_scene *make_scene(uint32_t *grid_mesh) {
    rt_scene *s;
    rt_scene_create(&s);
    rt_material m = rt_material_default();
    uint32_t mat, floor, obj;
    rt_material_add(s, &m, &mat);
    const float fp[12] = {-3, -0.5f, -3, 3, -0.5f, -3, 3, -0.5f, 3, -3, -0.5f, 3};
    const uint32_t fi[6] = {0, 2, 1, 0, 3, 2};
    rt_mesh_create(s, &floor);
    rt_mesh_add_triangles(s, floor, fp, NULL, 4, fi, 2);
    rt_mesh_create(s, grid_mesh);
    float *p = grid_positions(0);
    uint32_t *t = grid_indices();
    rt_mesh_add_triangles(s, *grid_mesh, p, NULL, (GRID + 1) * (GRID + 1), t, 2 * GRID * GRID);
    free(p);
    free(t);
    rt_object_create(s, mat, &obj);
    rt_object_add_mesh(s, obj, floor);
    rt_object_create(s, mat, &obj);
    rt_object_add_mesh(s, obj, *grid_mesh);
    rt_object_create(s, mat, &obj);
    rt_object_add_mesh(s, obj, *grid_mesh);
    const float M[16] = {0, 0, 1, 0.2f, 0, 1, 0, 0.6f, -1, 0, 0, 0, 0, 0, 0, 1};
    rt_object_transform(s, obj, M);
    rt_camera cam = {{0.3f, 1.6f, 2.8f}, {0, 0.1f, 0}, {0, 1, 0}, 60.0f, 64, 48};
    rt_camera_set(s, &cam);
    const float lp[3] = {1, 3, 2}, lc[3] = {1, 1, 1};
    uint32_t light;
    rt_light_add(s, lp, lc, &light);
    return s;
}

enum { RAYS = 4000 };

static void make_rays(rt_ray *rays) {
    uint32_t st = 12345u;
    for (int i = 0; i < RAYS; i++) {
        rt_ray *r = &rays[i];
        for (int k = 0; k < 3; k++) r->org[k] = bvh_test_uniform(&st, -1.5f, 1.5f);
        r->org[1] += 2.0f;
        for (int k = 0; k < 3; k++) r->dir[k] = bvh_test_uniform(&st, -1.0f, 1.0f);
        r->dir[1] = -fabsf(r->dir[1]) - 0.2f;
        r->tmin = 0.0f;
        r->tmax = INFINITY;
    }
}

static rt_renderer *new_renderer(const char *backend, int threads) {
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = backend;
    o.threads = threads;
    rt_error err;
    rt_renderer *r = NULL;
    CHECK_MSG(rt_renderer_create(&o, &r, &err) == RT_OK, "%s: %s", backend, err.message);
    return r;
}

/* The layout the renderer holds equals rt_flatten of its own BVHs (the
 * static meshes' ones copied back out of the layout, where they are kept). */
static void check_layout_fresh(rt_renderer *r, rt_scene *s, const char *what) {
    rt_flat f;
    rt_error err;
    CHECK(rt_accel_cache_unpark(&r->accel) == RT_OK);
    rt_status st = rt_flatten(s, r->accel.bvhs, &r->accel.top, NULL, &f, &err);
    CHECK_MSG(st == RT_OK, "%s: %s", what, err.message);
    if (st != RT_OK) return;
    const rt_flat *g = &r->accel.flat;
    int same = f.node_count == g->node_count && f.tri_count == g->tri_count &&
               memcmp(f.nodes, g->nodes, sizeof(rt_node) * f.node_count) == 0 &&
               memcmp(f.tris, g->tris, sizeof(rt_tri) * f.tri_count) == 0 &&
               memcmp(f.tri_ids, g->tri_ids, sizeof(uint32_t) * f.tri_count) == 0 &&
               memcmp(f.instances, g->instances, sizeof(rt_instance) * f.hdr.instance_count) == 0 &&
               f.inst_id_count == g->inst_id_count &&
               memcmp(f.inst_ids, g->inst_ids, sizeof(uint32_t) * f.inst_id_count) == 0 &&
               memcmp(&f.hdr, &g->hdr, sizeof f.hdr) == 0;
    CHECK_MSG(same, "%s: the layout rewritten in place differs from a fresh one", what);
    rt_flat_free(&f);
}

static const rt_update_action expected_action[] = {RT_ACTION_BUILD, RT_ACTION_REFIT, RT_ACTION_LBVH,
                                                   RT_ACTION_REFIT};

/* Frames 0..3 of a gentle wave, then a violent one (99), then gentle again. */
static const int frames[] = {0, 1, 2, 3, 99, 4};

static void check_policy(rt_update_policy policy, const char *backend) {
    uint32_t grid;
    rt_scene *s = make_scene(&grid);
    rt_renderer *r = new_renderer(backend, 2);
    rt_ray *rays = malloc(sizeof(rt_ray) * RAYS);
    rt_hit *a = malloc(sizeof(rt_hit) * RAYS), *b = malloc(sizeof(rt_hit) * RAYS);
    make_rays(rays);
    int refits = 0, rebuilds = 0;
    for (size_t fi = 0; fi < sizeof frames / sizeof frames[0] && r; fi++) {
        char what[96];
        snprintf(what, sizeof what, "%s on %s, frame %d", rt_update_policy_name(policy), backend,
                 frames[fi]);
        float *p = grid_positions(frames[fi]);
        CHECK(rt_mesh_set_positions(s, grid, p, NULL, (GRID + 1) * (GRID + 1)) == RT_OK);
        free(p);
        /* This renderer keeps its trees from frame to frame. */
        rt_mesh_set_update(s, grid, policy);
        CHECK_MSG(rt_trace_rays(r, s, rays, RAYS, a, NULL) == RT_OK, "%s: %s", what,
                  rt_renderer_error(r));
        rt_update_stats us;
        rt_renderer_update_stats(r, &us);
        int found = 0;
        for (uint32_t i = 0; i < us.mesh_count; i++) {
            if (us.meshes[i].mesh != grid) continue;
            found = 1;
            rt_update_action act = us.meshes[i].action;
            rt_update_action want =
                fi == 0 ? (policy == RT_UPDATE_LBVH ? RT_ACTION_LBVH : RT_ACTION_BUILD)
                        : expected_action[policy];
            if (policy == RT_UPDATE_AUTO && fi > 0) {
                CHECK_MSG(act == RT_ACTION_REFIT || act == RT_ACTION_REBUILD, "%s: action %d", what,
                          (int)act);
                refits += act == RT_ACTION_REFIT;
                rebuilds += act == RT_ACTION_REBUILD;
                /* The violent frame must push the refitted tree past the bound. */
                if (frames[fi] == 99) CHECK_MSG(act == RT_ACTION_REBUILD, "%s: not rebuilt", what);
            } else {
                CHECK_MSG(act == want, "%s: action %d, expected %d", what, (int)act, (int)want);
            }
        }
        CHECK_MSG(found, "%s: the grid's update is not reported", what);
        if (fi > 0)
            CHECK_MSG(us.layout_in_place || policy == RT_UPDATE_LBVH || policy == RT_UPDATE_SAH ||
                          policy == RT_UPDATE_AUTO,
                      "%s: the layout was not rewritten in place", what);
        if (fi > 0 && policy == RT_UPDATE_REFIT)
            CHECK_MSG(us.layout_in_place, "%s: a refit should rewrite the layout in place", what);
        check_layout_fresh(r, s, what);
        rt_framebuffer fa, fb;
        memset(&fa, 0, sizeof fa);
        memset(&fb, 0, sizeof fb);
        CHECK(rt_render(r, s, NULL, &fa) == RT_OK);

        /* The reference: a fresh renderer, a fresh SAH build, the oracle. */
        rt_mesh_set_update(s, grid, RT_UPDATE_SAH);
        rt_renderer *ref = new_renderer("cpu", 1);
        if (ref) {
            CHECK(rt_trace_rays(ref, s, rays, RAYS, b, NULL) == RT_OK);
            CHECK_MSG(memcmp(a, b, sizeof(rt_hit) * RAYS) == 0, "%s: hits differ from a rebuild",
                      what);
            CHECK(rt_render(ref, s, NULL, &fb) == RT_OK);
            CHECK_MSG(test_same_fb(&fa, &fb), "%s: image differs from a rebuild", what);
            rt_renderer_destroy(ref);
        }
        rt_framebuffer_free(&fa);
        rt_framebuffer_free(&fb);
        rt_mesh_set_update(s, grid, policy);
    }
    if (policy == RT_UPDATE_AUTO)
        CHECK_MSG(refits >= 4 && rebuilds >= 1,
                  "auto: %d refits, %d "
                  "rebuilds",
                  refits, rebuilds);
    free(rays);
    free(a);
    free(b);
    rt_renderer_destroy(r);
    rt_scene_destroy(s);
}

/* ---- the builders ------------------------------------------------------------ */

/* Four shifted copies of the grid's triangle boxes: enough leaves for the
 * parallel refit (4096 and more). */
static rt_aabb *grid_boxes(int frame, uint32_t *count) {
    uint32_t grid;
    rt_scene *s = make_scene(&grid);
    float *p = grid_positions(frame);
    rt_mesh_set_positions(s, grid, p, NULL, (GRID + 1) * (GRID + 1));
    free(p);
    const rt_mesh_data *m = &s->meshes[grid];
    uint32_t n = m->triangle_count;
    rt_aabb *boxes = malloc(sizeof(rt_aabb) * 4 * n);
    for (uint32_t t = 0; t < n; t++) {
        float v[9];
        for (int c = 0; c < 3; c++) memcpy(v + 3 * c, m->positions + 3 * m->indices[3 * t + c], 12);
        boxes[t] = bvh_test_tri_box(v);
        for (uint32_t copy = 1; copy < 4; copy++) {
            boxes[copy * n + t] = boxes[t];
            boxes[copy * n + t].bmin[0] += 3.0f * (float)copy;
            boxes[copy * n + t].bmax[0] += 3.0f * (float)copy;
        }
    }
    *count = 4 * n;
    rt_scene_destroy(s);
    return boxes;
}

static void check_lbvh(void) {
    uint32_t n;
    rt_aabb *boxes = grid_boxes(3, &n);
    rt_build_options o = rt_build_options_default();
    o.builder = RT_BUILDER_LBVH;
    rt_bvh first;
    CHECK(rt_bvh_build(boxes, n, &o, NULL, &first, NULL) == RT_OK);
    char msg[256];
    CHECK_MSG(bvh_validate(&first, boxes, n, 4, 64, msg, sizeof msg), "lbvh: %s", msg);
    const int threads[] = {1, 2, 3, 5};
    for (int i = 0; i < 4; i++) {
        rt_pool *pool = rt_pool_create(threads[i]);
        rt_bvh b;
        CHECK(rt_bvh_build(boxes, n, &o, pool, &b, NULL) == RT_OK);
        CHECK_MSG(b.node_count == first.node_count &&
                      memcmp(b.nodes, first.nodes, sizeof(rt_node) * b.node_count) == 0 &&
                      memcmp(b.prim_indices, first.prim_indices, sizeof(uint32_t) * n) == 0,
                  "lbvh on %d threads differs from no pool", threads[i]);
        rt_bvh_free(&b);
        rt_pool_destroy(pool);
    }
    /* Refit to another frame: exactly the boxes of a walk. */
    uint32_t n2;
    rt_aabb *moved = grid_boxes(99, &n2);
    rt_bvh_refit_info info;
    CHECK(rt_bvh_refit_prepare(&first, &info) == RT_OK);
    CHECK_MSG(info.leaf_count >= 4096, "%u leaves: the parallel refit would not run",
              info.leaf_count);
    rt_pool *pool = rt_pool_create(3);
    rt_bvh_refit(&first, &info, moved, pool);
    CHECK_MSG(bvh_validate(&first, moved, n2, 4, 64, msg, sizeof msg), "refit: %s", msg);
    int tight = 1;
    for (uint32_t i = first.node_count; i-- > 0;) {
        const rt_node *nd = &first.nodes[i];
        float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        if (nd->b & RT_NODE_LEAF_FLAG) {
            for (uint32_t j = 0; j < (nd->b & RT_NODE_COUNT_MASK); j++)
                for (int k = 0; k < 3; k++) {
                    const rt_aabb *bx = &moved[first.prim_indices[nd->a + j]];
                    lo[k] = fminf(lo[k], bx->bmin[k]);
                    hi[k] = fmaxf(hi[k], bx->bmax[k]);
                }
        } else {
            for (int k = 0; k < 3; k++) {
                lo[k] = fminf(first.nodes[nd->a].bmin[k], first.nodes[nd->b].bmin[k]);
                hi[k] = fmaxf(first.nodes[nd->a].bmax[k], first.nodes[nd->b].bmax[k]);
            }
        }
        for (int k = 0; k < 3; k++) tight &= lo[k] == nd->bmin[k] && hi[k] == nd->bmax[k];
    }
    CHECK_MSG(tight, "refit boxes are not the unions of their contents");
    /* Every path gives the same boxes: one thread (a backward sweep where
     * children follow parents, else the climb), and from the vertices. */
    rt_node *pooled = malloc(sizeof(rt_node) * first.node_count);
    memcpy(pooled, first.nodes, sizeof(rt_node) * first.node_count);
    rt_bvh_refit(&first, &info, boxes, NULL);
    rt_bvh_refit(&first, &info, moved, NULL);
    CHECK_MSG(memcmp(pooled, first.nodes, sizeof(rt_node) * first.node_count) == 0,
              "refit on one thread differs from the pool's");
    CHECK(info.ordered); /* the LBVH writes children after parents */
    info.ordered = 0;
    rt_bvh_refit(&first, &info, boxes, NULL);
    rt_bvh_refit(&first, &info, moved, NULL);
    CHECK_MSG(memcmp(pooled, first.nodes, sizeof(rt_node) * first.node_count) == 0,
              "the one-thread climb differs from the pool's");
    free(pooled);
    rt_bvh_refit_info_free(&info);
    rt_pool_destroy(pool);
    rt_bvh_free(&first);
    free(moved);

    /* Equal codes everywhere, and tiny inputs. */
    for (uint32_t i = 0; i < n; i++) boxes[i] = boxes[0];
    rt_bvh same;
    CHECK(rt_bvh_build(boxes, n, &o, NULL, &same, NULL) == RT_OK);
    CHECK_MSG(bvh_validate(&same, boxes, n, 4, 64, msg, sizeof msg), "lbvh equal: %s", msg);
    rt_bvh_free(&same);
    for (uint32_t k = 1; k <= 6; k++) {
        rt_bvh small;
        CHECK(rt_bvh_build(boxes, k, &o, NULL, &small, NULL) == RT_OK);
        CHECK_MSG(bvh_validate(&small, boxes, k, 4, 64, msg, sizeof msg), "lbvh %u: %s", k, msg);
        rt_bvh_free(&small);
    }
    free(boxes);
}

/* ---- the time ---------------------------------------------------------------- */

static void check_time(void) {
    rt_scene *s;
    rt_scene_create(&s);
    rt_material m = rt_material_default();
    uint32_t mat, k[3], obj, obj2;
    rt_material_add(s, &m, &mat);
    const uint32_t idx[3] = {0, 1, 2};
    const float tri[3][9] = {
        {0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 1, 1, 0, 1, 0, 1, 1}, {0, 0, 2, 1, 0, 2, 0, 1, 2}};
    for (int i = 0; i < 3; i++) {
        rt_mesh_create(s, &k[i]);
        rt_mesh_add_triangles(s, k[i], tri[i], NULL, 3, idx, 1);
    }
    rt_object_create(s, mat, &obj);
    for (int i = 0; i < 3; i++) rt_object_add_mesh(s, obj, k[i]);
    CHECK(!rt_scene_is_animated(s));
    uint32_t v = s->version;
    CHECK(rt_scene_set_time(s, 3.0) == RT_OK);
    CHECK_MSG(s->version == v, "a still scene changed with the time");
    CHECK(rt_object_set_animation(s, obj, 0.0f, 0) != RT_OK);
    CHECK(rt_object_set_animation(s, obj, 2.0f, 0) == RT_OK);
    CHECK(rt_scene_is_animated(s));
    /* Switching: keyframe floor(t * 2) mod 3. */
    const double times[] = {0.0, 0.49, 0.5, 1.2, 1.5, -0.25};
    const uint32_t want[] = {0, 0, 1, 2, 0, 2};
    for (int i = 0; i < 6; i++) {
        CHECK(rt_scene_set_time(s, times[i]) == RT_OK);
        CHECK_MSG(rt_object_shown_mesh(&s->objects[obj]) == k[want[i]], "t %g: mesh %u", times[i],
                  rt_object_shown_mesh(&s->objects[obj]));
    }
    /* Blending: exact at whole keyframes, halfway between at half. */
    CHECK(rt_object_set_animation(s, obj, 2.0f, 1) == RT_OK);
    CHECK(rt_scene_set_time(s, 0.5) == RT_OK);
    uint32_t shown = rt_object_shown_mesh(&s->objects[obj]);
    CHECK(shown != k[0] && shown != k[1] && shown != k[2]);
    CHECK(memcmp(s->meshes[shown].positions, tri[1], sizeof tri[1]) == 0);
    CHECK(rt_scene_set_time(s, 0.75) == RT_OK);
    shown = rt_object_shown_mesh(&s->objects[obj]);
    CHECK(s->meshes[shown].positions[2] == 1.5f);
    CHECK(rt_scene_set_time(s, 1.25) == RT_OK); /* the last blends into the first */
    shown = rt_object_shown_mesh(&s->objects[obj]);
    CHECK(s->meshes[shown].positions[2] == 1.0f);
    v = s->version;
    CHECK(rt_scene_set_time(s, 1.25) == RT_OK);
    CHECK_MSG(s->version == v, "setting the same time again changed the scene");

    /* Keyed transforms: the shortest arc from 0 to 270 degrees about y is
     * -90, so halfway is -45 degrees. */
    rt_object_create(s, mat, &obj2);
    rt_object_add_mesh(s, obj2, k[0]);
    rt_transform_key keys[2];
    memset(keys, 0, sizeof keys);
    for (int i = 0; i < 2; i++) {
        keys[i].axis[1] = 1.0f;
        keys[i].scale = 1.0f;
    }
    keys[1].time = 2.0;
    keys[1].degrees = 270.0f;
    keys[1].translate[0] = 4.0f;
    keys[1].scale = 3.0f;
    CHECK(rt_object_set_transform_keys(s, obj2, keys, 2) == RT_OK);
    CHECK(rt_scene_set_time(s, 1.0) == RT_OK);
    const float *M = s->objects[obj2].transform;
    double c = cos(-45.0 * 3.14159265358979 / 180.0) * 2.0;
    CHECK_MSG(fabs(M[0] - c) < 1e-5 && fabs(M[2] + c) < 1e-5 && M[3] == 2.0f && M[5] == 2.0f,
              "halfway: %g %g %g %g", M[0], M[2], M[3], M[5]);
    CHECK(rt_scene_set_time(s, 5.0) == RT_OK); /* held after the last key */
    CHECK(M[3] == 4.0f && fabsf(M[5] - 3.0f) < 1e-6f);
    keys[1].time = 0.0;
    CHECK(rt_object_set_transform_keys(s, obj2, keys, 2) != RT_OK);

    /* The camera's path. */
    rt_camera_key ck[2] = {{0.0, {0, 0, 5}, {0, 0, 0}}, {4.0, {4, 0, 5}, {4, 0, 0}}};
    CHECK(rt_camera_set_path(s, ck, 2) == RT_OK);
    CHECK(rt_scene_set_time(s, 1.0) == RT_OK);
    rt_camera cam;
    rt_camera_get(s, &cam);
    CHECK(cam.position[0] == 1.0f && cam.look_at[0] == 1.0f && cam.position[2] == 5.0f);
    CHECK(rt_scene_set_time(s, NAN) != RT_OK);
    /* Positions: the vertex count must match, values must be finite. */
    const float bad[9] = {0, 0, 0, NAN, 0, 0, 0, 1, 0};
    CHECK(rt_mesh_set_positions(s, k[0], bad, NULL, 3) != RT_OK);
    CHECK(rt_mesh_set_positions(s, k[0], tri[0], NULL, 2) != RT_OK);
    CHECK(rt_mesh_set_positions(s, k[0], tri[0], tri[0], 3) != RT_OK); /* it has no normals */
    CHECK(rt_mesh_set_update(s, k[0], (rt_update_policy)7) != RT_OK);
    rt_scene_destroy(s);
}

/* A kd-tree floor beside the refitted grid, frame after frame. */
static void check_kd_static(const char *backend) {
    uint32_t grid;
    rt_scene *s = make_scene(&grid);
    const uint32_t floor = 0;
    CHECK(rt_mesh_set_update(s, grid, RT_UPDATE_REFIT) == RT_OK);
    CHECK(rt_scene_set_static_accel(s, RT_ACCEL_KD) == RT_OK);
    CHECK(rt_mesh_accel(s, floor) == RT_ACCEL_KD);
    CHECK_MSG(rt_mesh_accel(s, grid) == RT_ACCEL_BVH, "a refitted mesh must keep its BVH");
    /* Asked for explicitly, a refitting mesh still gets a BVH. */
    CHECK(rt_mesh_set_accel(s, grid, RT_ACCEL_KD) == RT_OK);
    CHECK(rt_mesh_accel(s, grid) == RT_ACCEL_BVH);
    rt_renderer *r = new_renderer(backend, 2);
    rt_ray *rays = malloc(sizeof(rt_ray) * RAYS);
    rt_hit *a = malloc(sizeof(rt_hit) * RAYS), *b = malloc(sizeof(rt_hit) * RAYS);
    make_rays(rays);
    for (int fi = 0; fi < 4 && r; fi++) {
        char what[96];
        snprintf(what, sizeof what, "kd floor beside a refitted grid on %s, frame %d", backend, fi);
        float *p = grid_positions(fi);
        CHECK(rt_mesh_set_positions(s, grid, p, NULL, (GRID + 1) * (GRID + 1)) == RT_OK);
        free(p);
        CHECK_MSG(rt_trace_rays(r, s, rays, RAYS, a, NULL) == RT_OK, "%s: %s", what,
                  rt_renderer_error(r));
        CHECK_MSG(r->accel.kds[floor].node_count > 0 && r->accel.kds[grid].node_count == 0,
                  "%s: the floor should be a kd-tree, the grid a BVH", what);
        CHECK_MSG(r->accel.flat.kd_node_count > 0, "%s: no kd nodes in the layout", what);
        rt_update_stats us;
        rt_renderer_update_stats(r, &us);
        CHECK_MSG(!us.layout_in_place, "%s: a layout with kd meshes was rewritten in place", what);
        for (uint32_t i = 0; i < us.mesh_count; i++) {
            if (fi > 0)
                CHECK_MSG(us.meshes[i].mesh == grid, "%s: the still kd floor was updated", what);
            if (fi > 0 && us.meshes[i].mesh == grid)
                CHECK_MSG(us.meshes[i].action == RT_ACTION_REFIT, "%s: the grid was not refitted",
                          what);
        }
        /* The reference: the same geometry with BVHs only, a fresh
         * renderer, the oracle. */
        uint32_t ref_grid;
        rt_scene *rs = make_scene(&ref_grid);
        p = grid_positions(fi);
        CHECK(rt_mesh_set_positions(rs, ref_grid, p, NULL, (GRID + 1) * (GRID + 1)) == RT_OK);
        free(p);
        rt_renderer *ref = new_renderer("cpu", 1);
        if (ref) {
            CHECK(rt_trace_rays(ref, rs, rays, RAYS, b, NULL) == RT_OK);
            CHECK_MSG(memcmp(a, b, sizeof(rt_hit) * RAYS) == 0,
                      "%s: hits differ from the BVH oracle's", what);
            rt_renderer_destroy(ref);
        }
        rt_scene_destroy(rs);
    }
    /* Positions given to a kd mesh make it a BVH: it deforms. */
    CHECK(rt_mesh_set_update(s, floor, RT_UPDATE_SAH) == RT_OK);
    const float fp[12] = {-3, -0.6f, -3, 3, -0.6f, -3, 3, -0.6f, 3, -3, -0.6f, 3};
    CHECK(rt_mesh_set_positions(s, floor, fp, NULL, 4) == RT_OK);
    CHECK(rt_mesh_accel(s, floor) == RT_ACCEL_BVH);
    if (r) {
        CHECK(rt_trace_rays(r, s, rays, RAYS, a, NULL) == RT_OK);
        CHECK_MSG(r->accel.kds[floor].node_count == 0 && r->accel.flat.kd_node_count == 0,
                  "a kd mesh given positions should have become a BVH (%s)", backend);
    }
    free(rays);
    free(a);
    free(b);
    rt_renderer_destroy(r);
    rt_scene_destroy(s);
}

int main(void) {
    check_time();
    check_kd_static("cpu");
    check_kd_static("packet");
    check_lbvh();
    const rt_update_policy policies[] = {RT_UPDATE_REFIT, RT_UPDATE_LBVH, RT_UPDATE_AUTO,
                                         RT_UPDATE_SAH};
    for (int i = 0; i < 4; i++) {
        check_policy(policies[i], "cpu");
        check_policy(policies[i], "packet");
    }
    return TEST_END();
}
