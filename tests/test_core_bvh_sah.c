/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_bvh_sah.c - the SAH builder: valid trees, the same bytes for
 * every thread count and for the scalar and NEON loops, degenerate inputs,
 * and the parameter ranges of the builder study (bins 2..256, leaf sizes 1 to
 * 16): valid trees within the leaf size, traversal equal to brute force. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/scene_boxes.h"
#include "accel/bvh_internal.h"
#include "bvh_validate.h"
#include "check.h"
#include "layout/flatten.h"
#include "oracle_util.h"
#include "scene/scene.h"
#include "base/thread_pool.h"

/* The library's error of the last call a check prints. */
static rt_error lib_err;

/* A triangle soup: n random small triangles in a cube, plus a dense cluster
 * so that the tree is not uniform. */
static rt_aabb *make_soup(uint32_t n, uint32_t seed) {
    rt_aabb *boxes = malloc(sizeof *boxes * (n ? n : 1));
    uint32_t s = seed;
    for (uint32_t i = 0; i < n; i++) {
        float scale = (i % 5 == 0) ? 100.0f : 10.0f;
        float base[3];
        for (int k = 0; k < 3; k++) base[k] = bvh_test_uniform(&s, -scale, scale);
        float v[9];
        for (int j = 0; j < 9; j++) v[j] = base[j % 3] + bvh_test_uniform(&s, -0.5f, 0.5f);
        boxes[i] = bvh_test_tri_box(v);
    }
    return boxes;
}

static rt_build_options opts(int threads) {
    rt_build_options o = rt_build_options_default();
    o.threads = threads;
    return o;
}

static int build(const rt_aabb *boxes, uint32_t n, int threads, int neon, rt_bvh *out) {
    rt_build_options o = opts(threads);
    rt_pool *pool = threads > 1 ? rt_pool_create(threads) : NULL;
    rt_status st = rt_bvh_build_sah(boxes, n, &o, pool, neon, out, &lib_err);
    rt_pool_destroy(pool);
    CHECK_MSG(st == RT_OK, "build of %u boxes with %d threads: %s", n, threads, lib_err.message);
    return st == RT_OK;
}

static void check_valid(const rt_bvh *bvh, const rt_aabb *boxes, uint32_t n, uint32_t max_leaf,
                        const char *what) {
    char msg[256] = "";
    int ok = bvh_validate(bvh, boxes, n, max_leaf, 0, msg, sizeof msg);
    CHECK_MSG(ok, "%s: %s", what, msg);
}

static int same_bvh(const rt_bvh *a, const rt_bvh *b) {
    if (a->node_count != b->node_count || a->prim_count != b->prim_count) return 0;
    if (a->node_count == 0) return 1; /* the empty tree: no arrays to compare */
    return memcmp(a->nodes, b->nodes, sizeof(rt_node) * a->node_count) == 0 &&
           memcmp(a->prim_indices, b->prim_indices, sizeof(uint32_t) * a->prim_count) == 0;
}

static void test_determinism(void) {
    const uint32_t n = 60000;
    rt_aabb *boxes = make_soup(n, 7);
    rt_bvh ref;
    if (!build(boxes, n, 1, 0, &ref)) return;
    check_valid(&ref, boxes, n, 10, "soup, 1 thread, scalar");
    CHECK(ref.node_count > n / 10);
    const int threads[] = {1, 2, 3, 4, 8};
    for (int t = 0; t < 5; t++) {
        for (int neon = 0; neon < 2; neon++) {
            rt_bvh other;
            if (!build(boxes, n, threads[t], neon, &other)) continue;
            CHECK_MSG(same_bvh(&ref, &other), "%d threads, neon %d differ from 1 thread scalar",
                      threads[t], neon);
            rt_bvh_free(&other);
        }
    }
    /* Through the public entry point, with no pool given. */
    rt_build_options o = opts(2);
    rt_bvh pub;
    CHECK(rt_bvh_build(boxes, n, &o, NULL, &pub, NULL) == RT_OK);
    CHECK(same_bvh(&ref, &pub));
    rt_bvh_free(&pub);
    rt_bvh_free(&ref);
    free(boxes);
}

/* rt_bvh_build_tris (issue 31: no box array at the build's peak) gives the
 * very tree rt_bvh_build gives of rt_tri_box's boxes, for the fast builder
 * (which reads the triangles itself, on 1 and 3 threads, above and below
 * the size whose scratch is kept between builds) and for the LBVH (a
 * temporary box array). */
static void test_from_triangles(void) {
    const uint32_t counts[] = {5000, 700000};
    for (int c = 0; c < 2; c++) {
        const uint32_t n = counts[c], nv = n + 2;
        float *pos = malloc(sizeof *pos * 3 * nv);
        uint32_t *idx = malloc(sizeof *idx * 3 * n);
        rt_aabb *boxes = malloc(sizeof *boxes * n);
        uint32_t s = 11;
        for (uint32_t v = 0; v < 3 * nv; v++) pos[v] = bvh_test_uniform(&s, -50.0f, 50.0f);
        for (uint32_t t = 0; t < n; t++) {
            idx[3 * t] = t;
            idx[3 * t + 1] = (t * 7 + 1) % nv;
            idx[3 * t + 2] = (t * 13 + 2) % nv;
            rt_tri_box(pos, idx + 3 * t, &boxes[t]);
        }
        const rt_builder builders[2] = {RT_BUILDER_SAH, RT_BUILDER_LBVH};
        for (int b = 0; b < 2; b++)
            for (int threads = 1; threads <= 3; threads += 2) {
                rt_build_options o = opts(threads);
                o.builder = builders[b];
                rt_bvh from_boxes, from_tris;
                CHECK(rt_bvh_build(boxes, n, &o, NULL, &from_boxes, NULL) == RT_OK);
                CHECK(rt_bvh_build_tris(pos, idx, n, &o, NULL, &from_tris, NULL) == RT_OK);
                CHECK_MSG(same_bvh(&from_boxes, &from_tris), "%u triangles, %s, %d threads", n,
                          rt_builder_name(builders[b]), threads);
                rt_bvh_free(&from_boxes);
                rt_bvh_free(&from_tris);
            }
        free(pos);
        free(idx);
        free(boxes);
    }
}

/* SAH leaves: a leaf never exceeds leaf_size, and with a huge leaf size the
 * SAH still splits a spread-out input (leaves are not simply as large as
 * allowed). */
static void test_sah_leaves(void) {
    const uint32_t n = 5000;
    rt_aabb *boxes = make_soup(n, 3);
    rt_build_options o = opts(1);
    o.leaf_size = 64;
    rt_bvh bvh;
    CHECK(rt_bvh_build_sah(boxes, n, &o, NULL, 1, &bvh, NULL) == RT_OK);
    check_valid(&bvh, boxes, n, 64, "leaf size 64");
    uint32_t leaves = 0, biggest = 0;
    for (uint32_t i = 0; i < bvh.node_count; i++) {
        if (!(bvh.nodes[i].b & RT_NODE_LEAF_FLAG)) continue;
        uint32_t c = bvh.nodes[i].b & RT_NODE_COUNT_MASK;
        leaves++;
        biggest = c > biggest ? c : biggest;
    }
    CHECK_MSG(leaves > n / 16, "%u leaves for %u primitives at leaf size 64", leaves, n);
    CHECK(biggest <= 64);
    rt_bvh_free(&bvh);
    free(boxes);
}

static void check_degenerate(const rt_aabb *boxes, uint32_t n, const char *what) {
    rt_bvh a, b;
    if (!build(boxes, n, 1, 0, &a)) return;
    check_valid(&a, boxes, n, 10, what);
    if (build(boxes, n, 3, 1, &b)) {
        CHECK_MSG(same_bvh(&a, &b), "%s: 3 threads NEON differ", what);
        rt_bvh_free(&b);
    }
    rt_bvh_free(&a);
}

static void test_degenerate(void) {
    rt_aabb one = {{1, 2, 3}, {4, 5, 6}};
    check_degenerate(NULL, 0, "empty");
    check_degenerate(&one, 1, "one box");

    const uint32_t n = 20000;
    rt_aabb *boxes = malloc(sizeof *boxes * n);
    /* All centroids equal (every box the same). */
    for (uint32_t i = 0; i < n; i++) boxes[i] = one;
    check_degenerate(boxes, n, "identical boxes");
    /* Zero-area boxes: points on a line, and flat boxes with negative zeros. */
    for (uint32_t i = 0; i < n; i++) {
        float x = (float)(i % 97);
        boxes[i] = (rt_aabb){{x, -0.0f, 0.0f}, {x, 0.0f, -0.0f}};
    }
    check_degenerate(boxes, n, "points on a line");
    /* Huge offsets: small triangles far from the origin. */
    uint32_t s = 11;
    for (uint32_t i = 0; i < n; i++) {
        float v[9];
        for (int j = 0; j < 9; j++) v[j] = 1e30f + bvh_test_uniform(&s, -1e25f, 1e25f);
        boxes[i] = bvh_test_tri_box(v);
    }
    check_degenerate(boxes, n, "huge offsets");
    /* Boxes near the largest floats on both sides (extents overflow). */
    for (uint32_t i = 0; i < n; i++) {
        float x = (i & 1) ? 3e38f : -3e38f;
        float y = bvh_test_uniform(&s, 0, 1);
        boxes[i] = (rt_aabb){{x, y, 0}, {x, y, 0}};
    }
    check_degenerate(boxes, n, "extreme coordinates");
    /* Exponentially spaced centroids: each binned split could peel off one
     * box; the depth bound must still hold. */
    for (uint32_t i = 0; i < n; i++) {
        float x = ldexpf(1.0f, (int)(i % 250) - 125);
        boxes[i] = (rt_aabb){{x, 0, 0}, {x, 0, 0}};
    }
    check_degenerate(boxes, n, "exponential spacing");
    free(boxes);
}

static void test_bad_input(void) {
    rt_aabb boxes[3] = {{{0, 0, 0}, {1, 1, 1}}, {{0, NAN, 0}, {1, 1, 1}}, {{0, 0, 0}, {1, 1, 1}}};
    rt_build_options o = opts(1);
    rt_bvh bvh;
    CHECK(rt_bvh_build_sah(boxes, 3, &o, NULL, 1, &bvh, &lib_err) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(lib_err.message, "finite");
    CHECK(bvh.nodes == NULL && bvh.node_count == 0);
    boxes[1] = (rt_aabb){{2, 0, 0}, {1, 1, 1}}; /* min > max */
    CHECK(rt_bvh_build_sah(boxes, 3, &o, NULL, 0, &bvh, &lib_err) == RT_ERROR_INVALID_ARGUMENT);
}

/* The scratch memory kept between builds: a smaller build in between, and a
 * build after it was released, give the same tree as a fresh one. */
static void test_scratch_reuse(void) {
    const uint32_t n = 20000, small = 300;
    rt_aabb *boxes = make_soup(n, 11);
    rt_bvh first, tiny, again, fresh;
    rt_bvh_sah_release_scratch();
    if (!build(boxes, n, 2, 1, &first)) return;
    if (build(boxes + 5, small, 1, 0, &tiny)) {
        check_valid(&tiny, boxes + 5, small, 10, "small build on kept scratch");
        rt_bvh_free(&tiny);
    }
    if (build(boxes, n, 1, 0, &again)) {
        CHECK_MSG(same_bvh(&first, &again), "rebuild on kept scratch differs");
        rt_bvh_free(&again);
    }
    rt_bvh_sah_release_scratch();
    if (build(boxes, n, 2, 1, &fresh)) {
        CHECK_MSG(same_bvh(&first, &fresh), "build after release differs");
        rt_bvh_free(&fresh);
    }
    rt_bvh_free(&first);
    free(boxes);
}

/* Largest leaf, and whether any leaf of more than one primitive exists. */
static uint32_t largest_leaf(const rt_bvh *bvh) {
    uint32_t biggest = 0;
    for (uint32_t i = 0; i < bvh->node_count; i++)
        if (bvh->nodes[i].b & RT_NODE_LEAF_FLAG) {
            uint32_t c = bvh->nodes[i].b & RT_NODE_COUNT_MASK;
            biggest = c > biggest ? c : biggest;
        }
    return biggest;
}

/* The study's settings (bins 4..64, leaf sizes 1..16) and the ends of the
 * accepted range: every tree is valid, no leaf exceeds the leaf size, the
 * same bytes for 1 and 3 threads and for the scalar and NEON loops, and the
 * settings change the tree (they are not ignored). */
static void test_parameter_ranges(void) {
    const uint32_t n = 12000; /* above MIN_BIG_NODE: the parallel phase runs too */
    rt_aabb *boxes = make_soup(n, 5);
    const int bins[] = {2, 4, 8, 16, 32, 64, 256};
    const int leaves[] = {1, 2, 4, 8, 10, 16};
    rt_bvh by_bins[7], by_leaf[6];
    for (int b = 0; b < 7; b++) {
        for (int l = 0; l < 6; l++) {
            rt_build_options o = opts(1);
            o.bins = bins[b];
            o.leaf_size = leaves[l];
            rt_bvh one, three;
            rt_status st = rt_bvh_build_sah(boxes, n, &o, NULL, 0, &one, &lib_err);
            CHECK_MSG(st == RT_OK, "bins %d leaf %d: %s", bins[b], leaves[l], lib_err.message);
            if (st != RT_OK) continue;
            char what[64];
            snprintf(what, sizeof what, "bins %d, leaf size %d", bins[b], leaves[l]);
            check_valid(&one, boxes, n, (uint32_t)leaves[l], what);
            CHECK_MSG(largest_leaf(&one) <= (uint32_t)leaves[l], "%s: a leaf of %u", what,
                      largest_leaf(&one));
            o.threads = 3;
            rt_pool *pool = rt_pool_create(3);
            CHECK(rt_bvh_build_sah(boxes, n, &o, pool, 1, &three, &lib_err) == RT_OK);
            rt_pool_destroy(pool);
            CHECK_MSG(same_bvh(&one, &three), "%s: 3 threads NEON differ from 1 thread scalar",
                      what);
            rt_bvh_free(&three);
            if (leaves[l] == 10)
                by_bins[b] = one;
            else if (bins[b] == 16)
                by_leaf[l] = one;
            else
                rt_bvh_free(&one);
        }
        if (bins[b] == 16) by_leaf[4] = by_bins[b]; /* leaf 10 at 16 bins */
    }
    /* Different bin counts give different trees (bins 2 against 4, ..., 64
     * against 256: nodes of 64 and more primitives use them all). */
    for (int b = 0; b + 1 < 7; b++)
        CHECK_MSG(!same_bvh(&by_bins[b], &by_bins[b + 1]), "bins %d and %d give the same tree",
                  bins[b], bins[b + 1]);
    /* Leaf size 1: one primitive per leaf. */
    CHECK_EQ_INT(largest_leaf(&by_leaf[0]), 1);
    CHECK_EQ_INT(by_leaf[0].node_count, 2 * n - 1);
    for (int b = 0; b < 7; b++)
        if (bins[b] != 16) rt_bvh_free(&by_bins[b]);
    for (int l = 0; l < 6; l++) rt_bvh_free(&by_leaf[l]);
    free(boxes);
}

/* Every leaf size from 1 to 16 is used up to its limit: clusters of 1 to 17
 * nearly coincident boxes, where the SAH prefers one leaf (splitting does not
 * shrink the areas), so the largest leaf holds exactly leaf_size primitives. */
static void test_leaf_sizes_used(void) {
    const uint32_t n = 9 * (17 * 18 / 2); /* 9 rounds of clusters of 1..17 */
    rt_aabb *boxes = malloc(sizeof *boxes * n);
    uint32_t i = 0, s = 21;
    for (int round = 0; round < 9; round++)
        for (int size = 1; size <= 17; size++) {
            float c[3] = {(float)(size * 10), (float)(round * 10), 0.0f};
            for (int k = 0; k < size; k++, i++) {
                float v[9];
                for (int j = 0; j < 9; j++)
                    v[j] = c[j % 3] + (j < 3 ? 0.0f : 1.0f) * (j % 3 == j / 3 - 1 ? 1.0f : 0.0f) +
                           bvh_test_uniform(&s, 0.0f, 1e-3f);
                boxes[i] = bvh_test_tri_box(v);
            }
        }
    for (int leaf = 1; leaf <= 16; leaf++) {
        rt_build_options o = opts(1);
        o.leaf_size = leaf;
        rt_bvh bvh;
        CHECK(rt_bvh_build_sah(boxes, n, &o, NULL, 1, &bvh, NULL) == RT_OK);
        char what[64];
        snprintf(what, sizeof what, "clusters, leaf size %d", leaf);
        check_valid(&bvh, boxes, n, (uint32_t)leaf, what);
        CHECK_MSG(largest_leaf(&bvh) == (uint32_t)leaf, "%s: largest leaf %u", what,
                  largest_leaf(&bvh));
        rt_bvh_free(&bvh);
    }
    free(boxes);
}

/* A one-mesh scene of random small triangles (and a few large ones). */
static rt_scene *soup_scene(uint32_t tris, uint32_t seed) {
    rt_scene *s;
    if (rt_scene_create(&s) != RT_OK) return NULL;
    float *pos = malloc(sizeof(float) * 9 * tris);
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * tris);
    uint32_t st = seed;
    for (uint32_t i = 0; i < tris; i++) {
        float size = (i % 97 == 0) ? 6.0f : 0.4f, base[3];
        for (int k = 0; k < 3; k++) base[k] = bvh_test_uniform(&st, -5.0f, 5.0f);
        for (int j = 0; j < 9; j++) pos[9 * i + j] = base[j % 3] + bvh_test_uniform(&st, 0, size);
        for (int j = 0; j < 3; j++) idx[3 * i + j] = 3 * i + (uint32_t)j;
    }
    uint32_t mesh, mat, obj;
    rt_material m = rt_material_default();
    rt_material_add(s, &m, &mat);
    rt_mesh_create(s, &mesh);
    rt_mesh_add_triangles(s, mesh, pos, NULL, 3 * tris, idx, tris);
    rt_object_create(s, mat, &obj);
    rt_object_add_mesh(s, obj, mesh);
    rt_camera cam = {{0, 0, 14}, {0, 0, 0}, {0, 1, 0}, 60, 64, 48};
    rt_camera_set(s, &cam);
    free(pos);
    free(idx);
    return s;
}

/* The traversal over trees of the SAH builder at bins 64 and leaf sizes 1
 * and 16 (and bins 4) finds the hits brute force finds, bit for bit. */
static void test_ranges_traverse(void) {
    rt_scene *s = soup_scene(4000, 9);
    CHECK(s != NULL);
    if (!s) return;
    const rt_mesh_data *md = &s->meshes[0];
    rt_aabb *boxes = malloc(sizeof(rt_aabb) * md->triangle_count);
    rt_mesh_tri_boxes(md, boxes);
    const int settings[][2] = {{64, 1}, {64, 16}, {4, 1}, {4, 16}};
    for (int k = 0; k < 4; k++) {
        rt_build_options o = opts(2);
        o.bins = settings[k][0];
        o.leaf_size = settings[k][1];
        rt_bvh bvh;
        char msg[256] = "";
        CHECK_MSG(rt_bvh_build(boxes, md->triangle_count, &o, NULL, &bvh, &lib_err) == RT_OK, "%s",
                  msg);
        rt_flat flat;
        rt_status st = rt_flatten(s, &bvh, NULL, NULL, &flat, &lib_err);
        CHECK_MSG(st == RT_OK, "flatten: %s", lib_err.message);
        rt_bvh_free(&bvh);
        if (st != RT_OK) continue;
        rt_scene_view v = rt_flat_view(&flat);
        float lo[3], hi[3];
        rt_scene_bounds(s, lo, hi);
        int bad = 0, hits = 0;
        for (int i = 0; i < 2000; i++) {
            rt_ray r;
            oracle_ray(&flat.hdr, lo, hi, i, &r);
            rt_hit_d a, b;
            rt_counters c = {0, 0, 0};
            rt_trace(&v, &r, 0, &a, &c);
            oracle_brute_force(&v, &r, 0, &b);
            hits += a.prim != RT_NO_HIT;
            if (!oracle_same_hit(&a, &b)) bad++;
            int occluded = rt_trace(&v, &r, 1, &a, &c);
            if (occluded != (b.prim != RT_NO_HIT)) bad++;
        }
        CHECK_MSG(bad == 0, "bins %d leaf %d: %d rays differ from brute force", settings[k][0],
                  settings[k][1], bad);
        CHECK_MSG(hits > 200, "bins %d leaf %d: only %d hits: a weak test", settings[k][0],
                  settings[k][1], hits);
        rt_flat_free(&flat);
    }
    free(boxes);
    rt_scene_destroy(s);
}

int main(void) {
    test_parameter_ranges();
    test_leaf_sizes_used();
    test_ranges_traverse();
    test_determinism();
    test_from_triangles();
    test_scratch_reuse();
    test_sah_leaves();
    test_degenerate();
    test_bad_input();
    return TEST_END();
}
