/* test_core_bvh_fast.c - the fast builder: valid trees, the same bytes for
 * every thread count and for the scalar and NEON loops, degenerate inputs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh_internal.h"
#include "bvh_validate.h"
#include "check.h"
#include "thread_pool.h"

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
    char msg[256] = "";
    rt_status st = rt_bvh_build_fast(boxes, n, &o, pool, neon, out, msg, sizeof msg);
    rt_pool_destroy(pool);
    CHECK_MSG(st == RT_OK, "build of %u boxes with %d threads: %s", n, threads, msg);
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
    CHECK(rt_bvh_build(boxes, n, &o, NULL, &pub, NULL, 0) == RT_OK);
    CHECK(same_bvh(&ref, &pub));
    rt_bvh_free(&pub);
    rt_bvh_free(&ref);
    free(boxes);
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
    CHECK(rt_bvh_build_fast(boxes, n, &o, NULL, 1, &bvh, NULL, 0) == RT_OK);
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
    char msg[200] = "";
    CHECK(rt_bvh_build_fast(boxes, 3, &o, NULL, 1, &bvh, msg, sizeof msg) ==
          RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(msg, "finite");
    CHECK(bvh.nodes == NULL && bvh.node_count == 0);
    boxes[1] = (rt_aabb){{2, 0, 0}, {1, 1, 1}}; /* min > max */
    CHECK(rt_bvh_build_fast(boxes, 3, &o, NULL, 0, &bvh, msg, sizeof msg) ==
          RT_ERROR_INVALID_ARGUMENT);
}

/* The scratch memory kept between builds: a smaller build in between, and a
 * build after it was released, give the same tree as a fresh one. */
static void test_scratch_reuse(void) {
    const uint32_t n = 20000, small = 300;
    rt_aabb *boxes = make_soup(n, 11);
    rt_bvh first, tiny, again, fresh;
    rt_bvh_fast_release_scratch();
    if (!build(boxes, n, 2, 1, &first)) return;
    if (build(boxes + 5, small, 1, 0, &tiny)) {
        check_valid(&tiny, boxes + 5, small, 10, "small build on kept scratch");
        rt_bvh_free(&tiny);
    }
    if (build(boxes, n, 1, 0, &again)) {
        CHECK_MSG(same_bvh(&first, &again), "rebuild on kept scratch differs");
        rt_bvh_free(&again);
    }
    rt_bvh_fast_release_scratch();
    if (build(boxes, n, 2, 1, &fresh)) {
        CHECK_MSG(same_bvh(&first, &fresh), "build after release differs");
        rt_bvh_free(&fresh);
    }
    rt_bvh_free(&first);
    free(boxes);
}

int main(void) {
    test_determinism();
    test_scratch_reuse();
    test_sah_leaves();
    test_degenerate();
    test_bad_input();
    return TEST_END();
}
