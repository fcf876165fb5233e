/* SPDX-License-Identifier: Apache-2.0 */
/* bench_builders.c - BVH builders and their settings: build time against
 * tree quality (SAH) against the time to trace a frame through the tree
 * (issue 7, study b; bench/study_builders.sh runs it).
 *
 * usage: bench_builders SCENE [--width W] [--height H] [--reps N] [--threads T]
 *                       SETUP...
 * SETUP is BUILDER:BINS:LEAF, BUILDER one of thesis-scalar, thesis-neon,
 * thesis-mt, sah, embree (Embree ignores BINS: it bins by itself).
 *
 * Per setup, every mesh of the scene gets its BVH from that setup (Ct = 1,
 * Ci = 2 for all): "build ms" is the sum over the meshes of rt_bvh_build (for
 * Embree: rtcBuildBVH at medium quality, branching factor 2, maxLeafSize LEAF,
 * the time its own call takes; preparing its build primitives and converting
 * its tree into our nodes are not timed, which favours Embree slightly). SAH
 * is rt_bvh_measure's (the thesis's cost, areas relative to the root),
 * triangle-weighted over the meshes. "trace ms" is one frame of the thesis's
 * benchmark set-up (primary and shadow rays, Phong; rt_render with
 * direct_only) rendered by the scalar oracle over the flattened layout of
 * these trees (the object BVH with the default builder, not timed), W x H,
 * T threads. Every tree is traced by the same code, so the image must be the
 * library's default image bit for bit (closest hits have a total order):
 * "differ" counts the pixels that are not (it must be 0).
 *
 * Threads: thesis-scalar and thesis-neon are single-threaded setups (the
 * thesis's setups 1 and 2); thesis-mt, sah and Embree build with T threads;
 * every frame is traced with T threads. Each setup is built and traced once
 * as a warm-up (not counted), then N times, setups interleaved round by
 * round; min and median ms.
 *
 * Output: a header line, then one tab-separated line per setup:
 * setup builder bins leaf build_threads build_min build_median sah nodes
 * trace_min trace_median rays differ trace_threads tris tree (a hash of the
 * trees' bytes: setups with equal hashes built the same trees). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "accel/bvh.h"
#include "accel/scene_boxes.h"
#include "base/error.h"
#include "base/clock.h"
#include "cpu_render.h"
#include "layout/flatten.h"
#include "rt.h"
#include "scene/scene.h"
#include "base/thread_pool.h"
#include "accel/object_bvh.h"
#ifdef RT_HAVE_EMBREE
#include "peer/embree_peer.h"
#endif

enum { MAX_SETUPS = 64, MAX_REPS = 50 };

typedef struct setup {
    char text[64];
    int embree;
    rt_build_options o;
    double build[MAX_REPS], trace[MAX_REPS];
    double sah;
    uint64_t nodes, rays, differ;
    uint64_t hash; /* of the trees' bytes: equal hashes, the same trees */
} setup;

static uint64_t fnv1a(uint64_t h, const void *data, size_t n) {
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static int parse_setup(const char *text, setup *s) {
    char name[32];
    int bins, leaf;
    memset(s, 0, sizeof *s);
    snprintf(s->text, sizeof s->text, "%s", text);
    const char *c1 = strchr(text, ':');
    if (!c1 || (size_t)(c1 - text) >= sizeof name) return 0;
    memcpy(name, text, (size_t)(c1 - text));
    name[c1 - text] = 0;
    const char *c2 = strchr(c1 + 1, ':');
    if (!c2) return 0;
    bins = c2 == c1 + 1 ? 16 : atoi(c1 + 1); /* embree::10 leaves BINS out */
    leaf = atoi(c2 + 1);
    if (bins < 2 || bins > 256 || leaf < 1 || leaf > 64) return 0;
    s->o = rt_build_options_default();
    s->o.bins = bins;
    s->o.leaf_size = leaf;
    static const struct {
        const char *name;
        rt_builder b;
    } builders[] = {{"thesis-scalar", RT_BUILDER_THESIS_SCALAR},
                    {"thesis-neon", RT_BUILDER_THESIS_NEON},
                    {"thesis-mt", RT_BUILDER_THESIS_MT},
                    {"sah", RT_BUILDER_SAH}};
    if (!strcmp(name, "embree")) {
        s->embree = 1;
        return 1;
    }
    for (size_t i = 0; i < sizeof builders / sizeof builders[0]; i++)
        if (!strcmp(name, builders[i].name)) {
            s->o.builder = builders[i].b;
            return 1;
        }
    return 0;
}

static int single_threaded(const setup *s) {
    return !s->embree &&
           (s->o.builder == RT_BUILDER_THESIS_SCALAR || s->o.builder == RT_BUILDER_THESIS_NEON);
}

typedef struct bench {
    rt_scene *scene;
    rt_aabb **boxes; /* per mesh (NULL where no object shows it) */
    rt_bvh *bvhs;
    rt_pool *pool;
    int threads;
    float *image, *ref;
    size_t pixels;
#ifdef RT_HAVE_EMBREE
    rt_embree *em;
#endif
} bench;

/* Builds every shown mesh's BVH with the setup; *ms is the build time. */
static int build_all(bench *b, setup *s, double *ms, rt_error *msg) {
    const rt_scene *sc = b->scene;
    *ms = 0.0;
    for (uint32_t m = 0; m < sc->mesh_count; m++) {
        rt_bvh_free(&b->bvhs[m]);
        if (!b->boxes[m]) continue;
        uint32_t n = sc->meshes[m].triangle_count;
        rt_status st;
        if (s->embree) {
#ifdef RT_HAVE_EMBREE
            double t = 0.0;
            st = rt_embree_build_bvh(b->em, b->boxes[m], n, &s->o, &b->bvhs[m], &t, msg);
            *ms += t;
#else
            st = rt_fail(msg, RT_ERROR_UNSUPPORTED, "this build has no Embree");
#endif
        } else {
            rt_build_options o = s->o;
            o.threads = single_threaded(s) ? 1 : b->threads;
            double t0 = rt_now_ms();
            st = rt_bvh_build(b->boxes[m], n, &o, single_threaded(s) ? NULL : b->pool, &b->bvhs[m],
                              msg);
            *ms += rt_now_ms() - t0;
        }
        if (st != RT_OK) return 0;
    }
    return 1;
}

/* The frame through the current trees: *ms is the render time. */
static int trace_frame(bench *b, double *ms, uint64_t *rays, rt_error *msg) {
    rt_bvh top;
    if (rt_object_bvh_build(b->scene, b->bvhs, NULL, b->pool, &top, msg) != RT_OK) return 0;
    rt_flat flat;
    rt_status st = rt_flatten(b->scene, b->bvhs, &top, NULL, &flat, msg);
    rt_bvh_free(&top);
    if (st != RT_OK) return 0;
    flat.hdr.flags &= ~(uint32_t)RT_SCENE_SECONDARY; /* direct_only */
    rt_cpu_frame frame = {&flat, NULL, NULL, RT_AOV_NONE, b->image, 3, NULL, NULL, 0, NULL};
    rt_cpu_counts counts;
    double t0 = rt_now_ms();
    if (rt_cpu_render(&frame, b->pool, &counts) != RT_OK) {
        rt_flat_free(&flat);
        return rt_fail(msg, RT_ERROR_OUT_OF_MEMORY, "out of memory"), 0;
    }
    *ms = rt_now_ms() - t0;
    *rays = counts.rays;
    rt_flat_free(&flat);
    return 1;
}

int main(int argc, char **argv) {
    const char *path = NULL;
    int w = 1024, h = 576, reps = 5, threads = 2, count = 0;
    static setup setups[MAX_SETUPS];
    for (int i = 1; i < argc; i++) {
        int ok = 1;
        if (!strcmp(argv[i], "--width"))
            ok = bench_arg_int(argc, argv, &i, 1, 16384, &w);
        else if (!strcmp(argv[i], "--height"))
            ok = bench_arg_int(argc, argv, &i, 1, 16384, &h);
        else if (!strcmp(argv[i], "--reps"))
            ok = bench_arg_int(argc, argv, &i, 1, MAX_REPS, &reps);
        else if (!strcmp(argv[i], "--threads"))
            ok = bench_arg_int(argc, argv, &i, 1, 256, &threads);
        else if (argv[i][0] == '-')
            ok = 0;
        else if (!path)
            path = argv[i];
        else
            ok = count < MAX_SETUPS && parse_setup(argv[i], &setups[count++]);
        if (!ok) {
            fprintf(stderr, "bench_builders: bad argument '%s'\n", argv[i]);
            return 2;
        }
    }
    if (!path || !count) {
        fprintf(stderr, "usage: bench_builders SCENE [--width W] [--height H] [--reps N] "
                        "[--threads T] BUILDER:BINS:LEAF...\n");
        return 2;
    }
    bench b;
    memset(&b, 0, sizeof b);
    rt_error err;
    if (rt_scene_load(path, &b.scene, &err) != RT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    rt_scene *sc = b.scene;
    rt_camera cam;
    rt_camera_get(sc, &cam);
    bench_interior_view(path, &cam);
    cam.width = w;
    cam.height = h;
    if (rt_camera_set(sc, &cam) != RT_OK || rt_scene_commit(sc) != RT_OK) {
        fprintf(stderr, "%s\n", rt_scene_error(sc));
        return 1;
    }
    b.threads = threads;
    b.pool = rt_pool_create(threads);
    b.pixels = (size_t)w * h;
    b.image = calloc(3 * b.pixels, sizeof(float));
    b.boxes = calloc(sc->mesh_count, sizeof *b.boxes);
    b.bvhs = calloc(sc->mesh_count, sizeof *b.bvhs);
    if (!b.pool || !b.image || !b.boxes || !b.bvhs) return 1;
    uint64_t tris = 0;
    for (uint32_t o = 0; o < sc->object_count; o++) {
        uint32_t m = rt_object_shown_mesh(&sc->objects[o]);
        const rt_mesh_data *md = &sc->meshes[m];
        if (b.boxes[m] || !md->triangle_count) continue;
        b.boxes[m] = malloc(sizeof(rt_aabb) * md->triangle_count);
        if (!b.boxes[m]) return 1;
        rt_mesh_tri_boxes(md, b.boxes[m]);
        tris += md->triangle_count;
    }
#ifdef RT_HAVE_EMBREE
    rt_error emsg;
    memset(&emsg, 0, sizeof emsg);
    if (rt_embree_create(threads, &b.em, &emsg) != RT_OK) b.em = NULL;
#endif
    /* The library's own frame (default builder): what every tree must give. */
    rt_renderer *renderer = bench_renderer("cpu", threads);
    if (!renderer) return 1;
    rt_render_options ro = rt_render_options_default();
    ro.direct_only = 1;
    rt_framebuffer ref;
    if (rt_render(renderer, sc, &ro, &ref) != RT_OK) {
        fprintf(stderr, "%s\n", rt_renderer_error(renderer));
        return 1;
    }
    rt_renderer_destroy(renderer);
    for (int r = -1; r < reps; r++) /* r = -1: warm-up, not counted */
        for (int k = 0; k < count; k++) {
            setup *s = &setups[k];
            rt_error msg;
            memset(&msg, 0, sizeof msg);
            double bms, tms;
            uint64_t rays;
#ifdef RT_HAVE_EMBREE
            if (s->embree && !b.em) {
                fprintf(stderr, "bench_builders: %s: %s\n", s->text, emsg.message);
                return 1;
            }
#endif
            if (!build_all(&b, s, &bms, &msg) || !trace_frame(&b, &tms, &rays, &msg)) {
                fprintf(stderr, "bench_builders: %s: %s\n", s->text, msg.message);
                return 1;
            }
            if (r < 0) {
                double sah = 0.0;
                s->hash = 14695981039346656037ull;
                for (uint32_t m = 0; m < sc->mesh_count; m++) {
                    if (!b.boxes[m]) continue;
                    const rt_bvh *t = &b.bvhs[m];
                    s->hash = fnv1a(s->hash, t->nodes, sizeof(rt_node) * t->node_count);
                    s->hash = fnv1a(s->hash, t->prim_indices, sizeof(uint32_t) * t->prim_count);
                    rt_bvh_quality q = rt_bvh_measure(&b.bvhs[m], rt_sah_costs_default());
                    sah += q.sah * (double)sc->meshes[m].triangle_count;
                    s->nodes += q.nodes;
                }
                s->sah = tris ? sah / (double)tris : 0.0;
                s->rays = rays;
                for (size_t i = 0; i < b.pixels; i++)
                    s->differ +=
                        memcmp(&b.image[3 * i], &ref.pixels[3 * i], 3 * sizeof(float)) != 0;
            } else {
                s->build[r] = bms;
                s->trace[r] = tms;
            }
        }
    printf("setup\tbuilder\tbins\tleaf\tbuild_threads\tbuild_min\tbuild_median\tsah\tnodes\t"
           "trace_min\ttrace_median\trays\tdiffer\ttrace_threads\ttris\ttree\n");
    for (int k = 0; k < count; k++) {
        setup *s = &setups[k];
        double bmin, bmed, tmin, tmed;
        bench_min_median(s->build, reps, &bmin, &bmed);
        bench_min_median(s->trace, reps, &tmin, &tmed);
        printf("%s\t%s\t%d\t%d\t%d\t%.3f\t%.3f\t%.4f\t%llu\t%.2f\t%.2f\t%llu\t%llu\t%d\t%llu\t"
               "%016llx\n",
               s->text, s->embree ? "embree" : rt_builder_name(s->o.builder),
               s->embree ? 0 : s->o.bins, s->o.leaf_size, single_threaded(s) ? 1 : threads, bmin,
               bmed, s->sah, (unsigned long long)s->nodes, tmin, tmed, (unsigned long long)s->rays,
               (unsigned long long)s->differ, threads, (unsigned long long)tris,
               (unsigned long long)s->hash);
    }
    rt_framebuffer_free(&ref);
    for (uint32_t m = 0; m < sc->mesh_count; m++) {
        free(b.boxes[m]);
        rt_bvh_free(&b.bvhs[m]);
    }
    free(b.boxes);
    free(b.bvhs);
    free(b.image);
#ifdef RT_HAVE_EMBREE
    rt_embree_destroy(b.em);
#endif
    rt_pool_destroy(b.pool);
    rt_scene_destroy(sc);
    return 0;
}
