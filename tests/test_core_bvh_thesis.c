/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_bvh_thesis.c - the thesis builder in its three setups.
 *
 * Every tree is validated (bvh_validate.h); the NEON setup must produce the
 * scalar setup's tree byte for byte, and so must the two-phase threaded setup
 * for any thread count (bvh_thesis.c lays its nodes out in the one-thread
 * order). Degenerate inputs must build valid trees of bounded depth, and
 * non-finite boxes must be refused.
 *
 * With the shared scenes present it builds Sponza and the Bunny with each
 * setup and prints the tree figures. RT_BVH_TIMING_REPS=n also times n builds
 * of each setup (and adds the Dragon); timings are printed, never asserted.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "accel/bvh.h"
#include "bvh_validate.h"
#include "check.h"

/* The library's error of the last call a check prints. */
static rt_error lib_err;

static const rt_builder setups[3] = {RT_BUILDER_THESIS_SCALAR, RT_BUILDER_THESIS_NEON,
                                     RT_BUILDER_THESIS_MT};

static rt_build_options thesis_options(rt_builder b, int threads) {
    rt_build_options o = rt_build_options_default();
    o.builder = b;
    o.threads = threads;
    return o;
}

static int same_tree(const rt_bvh *a, const rt_bvh *b) {
    return a->node_count == b->node_count && a->prim_count == b->prim_count &&
           (a->node_count == 0 ||
            memcmp(a->nodes, b->nodes, sizeof(rt_node) * a->node_count) == 0) &&
           (a->prim_count == 0 ||
            memcmp(a->prim_indices, b->prim_indices, sizeof(uint32_t) * a->prim_count) == 0);
}

/* Builds with every setup (MT with 1, 2, 3 and all threads), validates each
 * tree and checks that all equal the scalar one. Returns the scalar tree's
 * quality. */
static rt_bvh_quality check_all_setups(const char *what, const rt_aabb *boxes, uint32_t n, int bins,
                                       int leaf_size) {
    rt_bvh ref;
    char msg[256] = "";
    rt_build_options o = thesis_options(RT_BUILDER_THESIS_SCALAR, 1);
    o.bins = bins;
    o.leaf_size = leaf_size;
    rt_status st = rt_bvh_build(boxes, n, &o, NULL, &ref, &lib_err);
    CHECK_MSG(st == RT_OK, "%s: scalar build failed: %s", what, lib_err.message);
    rt_bvh_quality q = rt_bvh_measure(&ref, o.costs);
    if (st != RT_OK) return q;
    CHECK_MSG(bvh_validate(&ref, boxes, n, (uint32_t)leaf_size, 0, msg, sizeof msg), "%s: %s", what,
              msg);

    const struct {
        rt_builder b;
        int threads;
    } others[] = {{RT_BUILDER_THESIS_NEON, 1},
                  {RT_BUILDER_THESIS_MT, 1},
                  {RT_BUILDER_THESIS_MT, 2},
                  {RT_BUILDER_THESIS_MT, 3},
                  {RT_BUILDER_THESIS_MT, 0}};
    for (size_t k = 0; k < sizeof others / sizeof others[0]; k++) {
        rt_build_options ok = o;
        ok.builder = others[k].b;
        ok.threads = others[k].threads;
        rt_bvh t;
        st = rt_bvh_build(boxes, n, &ok, NULL, &t, &lib_err);
        CHECK_MSG(st == RT_OK, "%s: %s build failed: %s", what, rt_builder_name(ok.builder),
                  lib_err.message);
        if (st != RT_OK) continue;
        CHECK_MSG(bvh_validate(&t, boxes, n, (uint32_t)leaf_size, 0, msg, sizeof msg),
                  "%s/%s/%d threads: %s", what, rt_builder_name(ok.builder), ok.threads, msg);
        CHECK_MSG(same_tree(&ref, &t), "%s: %s with %d threads differs from scalar", what,
                  rt_builder_name(ok.builder), ok.threads);
        rt_bvh_quality qt = rt_bvh_measure(&t, o.costs);
        CHECK_MSG(fabs(qt.sah - q.sah) <= 0.01 * q.sah, "%s: SAH %g vs scalar %g", what, qt.sah,
                  q.sah);
        rt_bvh_free(&t);
    }
    rt_bvh_free(&ref);
    return q;
}

static rt_aabb *random_boxes(uint32_t n, uint32_t seed, float world, float size) {
    rt_aabb *b = malloc(sizeof *b * (n ? n : 1));
    for (uint32_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            float lo = bvh_test_uniform(&seed, -world, world);
            b[i].bmin[k] = lo;
            b[i].bmax[k] = lo + bvh_test_uniform(&seed, 0.0f, size);
        }
    }
    return b;
}

static rt_aabb *triangle_soup(uint32_t n, uint32_t seed) {
    rt_aabb *b = malloc(sizeof *b * n);
    for (uint32_t i = 0; i < n; i++) {
        float v[9], c[3];
        for (int k = 0; k < 3; k++) c[k] = bvh_test_uniform(&seed, -50.0f, 50.0f);
        /* Mostly small triangles, every 16th a long sliver across the soup. */
        float reach = (i % 16 == 0) ? 40.0f : 1.0f;
        for (int j = 0; j < 9; j++) v[j] = c[j % 3] + bvh_test_uniform(&seed, -reach, reach);
        b[i] = bvh_test_tri_box(v);
    }
    return b;
}

static void test_random_inputs(void) {
    /* Odd counts exercise the NEON loops' tails. */
    const uint32_t counts[] = {2, 3, 11, 17, 100, 1001, 20003};
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        rt_aabb *b = random_boxes(counts[i], 1234u + (uint32_t)i, 100.0f, 5.0f);
        check_all_setups("random boxes", b, counts[i], 16, 10);
        free(b);
    }
    rt_aabb *soup = triangle_soup(30001, 99);
    rt_bvh_quality q = check_all_setups("triangle soup", soup, 30001, 16, 10);
    CHECK(q.leaves > 30001 / 10);
    /* Other bin counts and leaf sizes, including the extremes the options allow. */
    const int bins[] = {2, 3, 7, 64, 256};
    for (size_t i = 0; i < sizeof bins / sizeof bins[0]; i++)
        check_all_setups("soup, other bins", soup, 5003, bins[i], 4);
    check_all_setups("soup, leaf size 1", soup, 4099, 16, 1);
    free(soup);
}

static void test_degenerate(void) {
    char msg[256];
    rt_bvh t;
    /* Empty input: the empty tree (node_count 0). */
    for (int s = 0; s < 3; s++) {
        rt_build_options o = thesis_options(setups[s], 2);
        CHECK(rt_bvh_build(NULL, 0, &o, NULL, &t, &lib_err) == RT_OK);
        CHECK_EQ_INT(t.node_count, 0);
        CHECK_EQ_INT(t.prim_count, 0);
        CHECK(bvh_validate(&t, NULL, 0, 10, 0, msg, sizeof msg));
        rt_bvh_free(&t);
    }
    /* One primitive: one leaf with the primitive's box. */
    rt_aabb one = {{1, 2, 3}, {4, 5, 6}};
    check_all_setups("one box", &one, 1, 16, 10);
    rt_build_options o = thesis_options(RT_BUILDER_THESIS_SCALAR, 1);
    CHECK(rt_bvh_build(&one, 1, &o, NULL, &t, &lib_err) == RT_OK);
    CHECK_EQ_INT(t.node_count, 1);
    CHECK(t.nodes[0].b == (1u | RT_NODE_LEAF_FLAG) && t.nodes[0].a == 0);
    CHECK(memcmp(t.nodes[0].bmin, one.bmin, 12) == 0 && memcmp(t.nodes[0].bmax, one.bmax, 12) == 0);
    rt_bvh_free(&t);

    /* 10,000 identical triangles: all centroids equal, split in the middle. */
    uint32_t n = 10000;
    rt_aabb *b = malloc(sizeof *b * n);
    for (uint32_t i = 0; i < n; i++) b[i] = (rt_aabb){{0, 0, 0}, {1, 1, 0}};
    rt_bvh_quality q = check_all_setups("identical triangles", b, n, 16, 10);
    CHECK(q.depth <= bvh_validate_depth_bound(n));
    CHECK(q.leaves >= n / 10);

    /* Zero-area boxes: points, some shared. */
    uint32_t seed = 7;
    for (uint32_t i = 0; i < n; i++) {
        float p[3];
        for (int k = 0; k < 3; k++) p[k] = (float)(bvh_test_rand(&seed) % 50);
        memcpy(b[i].bmin, p, sizeof p);
        memcpy(b[i].bmax, p, sizeof p);
    }
    check_all_setups("points", b, n, 16, 10);
    /* All on one plane and one line: zero-area root boxes. */
    for (uint32_t i = 0; i < n; i++) b[i] = (rt_aabb){{(float)i, 0, 0}, {(float)i + 0.5f, 0, 0}};
    check_all_setups("on a line", b, n, 16, 10);

    /* Huge offsets: 1e6 .. 1e30 added to unit boxes, where floats lose the
     * unit size, and boxes spanning -3e38 .. 3e38 (the centroid extent then
     * overflows to infinity). */
    const float offsets[] = {1e6f, 1e12f, 1e20f, 1e30f};
    for (size_t k = 0; k < sizeof offsets / sizeof offsets[0]; k++) {
        rt_aabb *r = random_boxes(n, 55u + (uint32_t)k, 1000.0f, 1.0f);
        for (uint32_t i = 0; i < n; i++)
            for (int a = 0; a < 3; a++) {
                r[i].bmin[a] += offsets[k];
                r[i].bmax[a] += offsets[k];
            }
        check_all_setups("huge offset", r, n, 16, 10);
        free(r);
    }
    for (uint32_t i = 0; i < n; i++) {
        float x = (i % 2) ? 3e38f : -3e38f;
        b[i] = (rt_aabb){{x, 0, 0}, {x, (float)i, 1}};
    }
    check_all_setups("extent overflows", b, n, 16, 10);
    /* Centroids a few denormals apart: the bin scale is not finite. */
    for (uint32_t i = 0; i < n; i++) {
        float x = (float)(i % 3) * 1e-44f;
        b[i] = (rt_aabb){{x, 0, 0}, {x, 0, 0}};
    }
    check_all_setups("denormal extent", b, n, 16, 10);
    /* Exponentially spaced centroids: SAH splits peel off a few primitives at
     * a time, the case the depth bound is for. */
    uint32_t m = 900;
    for (uint32_t i = 0; i < m; i++) {
        float x = powf(1.1f, (float)i);
        b[i] = (rt_aabb){{x, 0, 0}, {x, 1, 1}};
    }
    q = check_all_setups("exponential spacing", b, m, 16, 1);
    CHECK(q.depth <= bvh_validate_depth_bound(m));
    free(b);

    /* Non-finite boxes are refused with a message. */
    rt_aabb bad[3] = {{{0, 0, 0}, {1, 1, 1}}, {{0, 0, 0}, {1, NAN, 1}}, {{0, 0, 0}, {1, 1, 1}}};
    for (int s = 0; s < 3; s++) {
        rt_build_options ob = thesis_options(setups[s], 2);
        msg[0] = 0;
        CHECK(rt_bvh_build(bad, 3, &ob, NULL, &t, &lib_err) == RT_ERROR_INVALID_ARGUMENT);
        CHECK_CONTAINS(lib_err.message, "primitive 1");
        CHECK(t.node_count == 0 && t.nodes == NULL);
    }
    bad[1].bmin[0] = -INFINITY;
    bad[1].bmax[1] = 1;
    CHECK(rt_bvh_build(bad, 3, &o, NULL, &t, &lib_err) == RT_ERROR_INVALID_ARGUMENT);
}

/* ---- shared scenes ---------------------------------------------------------- */

/* Triangle boxes of an OBJ file: v and f lines only (f with v, v/t, v//n or
 * v/t/n, negative indices, polygons as fans). Returns NULL if unreadable. */
static rt_aabb *read_obj_boxes(const char *path, uint32_t *count) {
    FILE *f = fopen(path, "r");
    if (!f) return NULL;
    size_t nv = 0, cv = 1024, nt = 0, ct = 1024;
    float *v = malloc(sizeof(float) * 3 * cv);
    rt_aabb *boxes = malloc(sizeof(rt_aabb) * ct);
    char line[4096];
    while (fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') {
            if (nv == cv) v = realloc(v, sizeof(float) * 3 * (cv *= 2));
            float *p = &v[3 * nv++];
            if (sscanf(line + 2, "%f %f %f", &p[0], &p[1], &p[2]) != 3) nv--;
        } else if (line[0] == 'f' && line[1] == ' ') {
            long idx[64];
            int k = 0;
            char *s = line + 2;
            while (k < 64) {
                char *end;
                long x = strtol(s, &end, 10);
                if (end == s) break;
                idx[k++] = x < 0 ? (long)nv + x : x - 1;
                s = end;
                while (*s && *s != ' ' && *s != '\t' && *s != '\n' && *s != '\r') s++;
            }
            for (int j = 1; j + 1 < k; j++) {
                float tri[9];
                long corner[3] = {idx[0], idx[j], idx[j + 1]};
                int valid = 1;
                for (int c = 0; c < 3; c++) {
                    if (corner[c] < 0 || (size_t)corner[c] >= nv)
                        valid = 0;
                    else
                        memcpy(&tri[3 * c], &v[3 * corner[c]], sizeof(float) * 3);
                }
                if (!valid) continue;
                if (nt == ct) boxes = realloc(boxes, sizeof(rt_aabb) * (ct *= 2));
                boxes[nt++] = bvh_test_tri_box(tri);
            }
        }
    }
    fclose(f);
    free(v);
    *count = (uint32_t)nt;
    return boxes;
}

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void scene_figures(const char *rel, int reps) {
    const char *path = test_shared_scene(rel);
    if (!path) {
        printf("%s: not present, skipped\n", rel);
        return;
    }
    uint32_t n = 0;
    rt_aabb *boxes = read_obj_boxes(path, &n);
    CHECK_MSG(boxes && n > 0, "%s: no triangles read", rel);
    if (!boxes || !n) return;
    rt_bvh ref = {0};
    for (int s = 0; s < 3; s++) {
        rt_build_options o = thesis_options(setups[s], 0);
        char msg[256];
        rt_bvh t;
        rt_status st = rt_bvh_build(boxes, n, &o, NULL, &t, &lib_err);
        CHECK_MSG(st == RT_OK, "%s: %s", rel, lib_err.message);
        if (st != RT_OK) continue;
        CHECK_MSG(bvh_validate(&t, boxes, n, 10, 0, msg, sizeof msg), "%s: %s", rel, msg);
        rt_bvh_quality q = rt_bvh_measure(&t, o.costs);
        printf("%s: %u triangles, %s: SAH %.3f, %u nodes, %u leaves, depth %u, %zu bytes\n", rel, n,
               rt_builder_name(setups[s]), q.sah, q.nodes, q.leaves, q.depth, q.bytes);
        if (s == 0)
            ref = t;
        else {
            CHECK_MSG(same_tree(&ref, &t), "%s: %s differs from scalar", rel,
                      rt_builder_name(setups[s]));
            rt_bvh_free(&t);
        }
        if (reps > 0) {
            double *ms = malloc(sizeof(double) * (size_t)reps);
            for (int r = 0; r < reps; r++) {
                double t0 = now_ms();
                rt_bvh_build(boxes, n, &o, NULL, &t, &lib_err);
                ms[r] = now_ms() - t0;
                rt_bvh_free(&t);
            }
            qsort(ms, (size_t)reps, sizeof *ms, cmp_double);
            printf("%s: %s build: min %.2f ms, median %.2f ms over %d\n", rel,
                   rt_builder_name(setups[s]), ms[0], ms[reps / 2], reps);
            free(ms);
        }
    }
    rt_bvh_free(&ref);
    free(boxes);
}

int main(void) {
    test_random_inputs();
    test_degenerate();
    const char *reps_env = getenv("RT_BVH_TIMING_REPS");
    int reps = reps_env ? atoi(reps_env) : 0;
    scene_figures("sponza_dabrovic/sponza.obj", reps);
    scene_figures("stanford_bunny/stanford-bunny.obj", reps);
    if (reps > 0) scene_figures("stanford_dragon/dragon_vrip.obj", reps);
    return TEST_END();
}
