/* SPDX-License-Identifier: Apache-2.0 */
/* bench_tri_study.c - the triangle tests' speed against their error on real
 * rays (issue 7, study a; bench/study_tri_tests.sh runs it).
 *
 * usage: bench_tri_study SCENE [--width W] [--height H] [--runs N] [--threads T]
 *                        [--sample S]
 *
 * Rays: the primary rays of the scene's camera through pixel centres (Sponza
 * and Sibenik as bare OBJ files get the interior views of VIEWS.md), the same
 * rays for every test.
 *
 * Speed: rt_trace_rays_with on the scalar oracle ("cpu") with T threads (all
 * tests the same T). Each test traces once as a warm-up (the first one also
 * builds the BVH and layout), not counted; then N timed runs, interleaved test
 * by test so that load drifts hit all tests alike; min and median ms.
 *
 * Error of t: for every ray a test reports a hit for, t is recomputed in
 * double precision for the triangle it reported (the plane crossing
 * dot(n, v0 - o) / dot(n, d), n = (v1 - v0) x (v2 - v0), from the same float
 * inputs, which double holds exactly; instances' vertices moved by their
 * transform in double); relative error |t - t_ref| / |t_ref|, its maximum and
 * mean over all hits.
 *
 * Closest hit: on every k-th ray (about S of them) a double-precision
 * reference over every triangle of the scene (brute force, Moller-Trumbore in
 * double, edges inclusive, ties to the lower object, then triangle). A test
 * agrees when both miss, or both hit and the double-precision t of the
 * triangle the test reported is within 2^-16 (relative) of the reference's t
 * (the same surface point; at a shared edge either neighbour). The reference
 * is "at an edge" when growing and shrinking every triangle by 2^-16 in
 * barycentric coordinates changes it (to another surface, or hit to miss);
 * disagreements are counted on those rays and on the others (decisive rays)
 * apart.
 *
 * Output: a header line, then one tab-separated line per test:
 * test rays hits min_ms median_ms t_max_rel t_mean_rel sample ref_hits
 * differ_decisive differ_edge edge_rays threads. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "base/clock.h"
#include "rt.h"
#include "scene/scene.h"
#include "base/thread_pool.h"

enum { TESTS = 4, MAX_RUNS = 100 };
static const char *const test_names[TESTS] = {"watertight", "mt", "pluecker", "badouel"};

/* 2^-16: the relative t window of "the same surface point" and the
 * barycentric band of "at an edge". */
#define SAME_T   (1.0 / 65536.0)
#define EDGE_BAR (1.0 / 65536.0)

/* The scene's triangles in world space, in double, object by object. */
typedef struct world_tris {
    double *v;        /* 9 per triangle */
    uint32_t *first;  /* per object: its first triangle */
    uint32_t *object; /* per triangle */
    uint32_t *prim;   /* per triangle: index in its mesh */
    uint32_t count;
} world_tris;

static int gather_world(const rt_scene *s, world_tris *w) {
    memset(w, 0, sizeof *w);
    uint64_t n = 0;
    for (uint32_t o = 0; o < s->object_count; o++) {
        const rt_object_data *ob = &s->objects[o];
        n += s->meshes[rt_object_shown_mesh(ob)].triangle_count;
    }
    w->v = malloc(sizeof(double) * 9 * (n ? n : 1));
    w->first = malloc(sizeof(uint32_t) * (s->object_count + 1));
    w->object = malloc(sizeof(uint32_t) * (n ? n : 1));
    w->prim = malloc(sizeof(uint32_t) * (n ? n : 1));
    if (!w->v || !w->first || !w->object || !w->prim) return 0;
    uint32_t t = 0;
    for (uint32_t o = 0; o < s->object_count; o++) {
        const rt_object_data *ob = &s->objects[o];
        const rt_mesh_data *m = &s->meshes[rt_object_shown_mesh(ob)];
        const float *M = ob->transform;
        w->first[o] = t;
        for (uint32_t i = 0; i < m->triangle_count; i++, t++) {
            for (int j = 0; j < 3; j++) {
                const float *p = m->positions + 3 * (size_t)m->indices[3 * i + j];
                for (int k = 0; k < 3; k++)
                    w->v[9 * (size_t)t + 3 * j + k] =
                        (double)M[4 * k] * p[0] + (double)M[4 * k + 1] * p[1] +
                        (double)M[4 * k + 2] * p[2] + (double)M[4 * k + 3];
            }
            w->object[t] = o;
            w->prim[t] = i;
        }
    }
    w->first[s->object_count] = t;
    w->count = t;
    return 1;
}

static void free_world(world_tris *w) {
    free(w->v);
    free(w->first);
    free(w->object);
    free(w->prim);
}

static void sub3(const double *a, const double *b, double *o) {
    for (int k = 0; k < 3; k++) o[k] = a[k] - b[k];
}
static void cross3(const double *a, const double *b, double *o) {
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double *a, const double *b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The plane crossing of the ray with triangle tri, in double (NAN when the
 * ray is parallel to the plane or the triangle has no area). */
static double plane_t(const world_tris *w, uint32_t tri, const rt_ray *r) {
    const double *v = w->v + 9 * (size_t)tri;
    double e1[3], e2[3], n[3], a[3], o[3] = {r->org[0], r->org[1], r->org[2]},
                                     d[3] = {r->dir[0], r->dir[1], r->dir[2]};
    sub3(v + 3, v, e1);
    sub3(v + 6, v, e2);
    cross3(e1, e2, n);
    sub3(v, o, a);
    double nd = dot3(n, d);
    return nd != 0.0 ? dot3(n, a) / nd : NAN;
}

/* The closest hit of a ray in double with the triangles grown (band < 0),
 * exact (0) or shrunk (band > 0) in barycentric coordinates. */
typedef struct ref_hit {
    double t;
    uint32_t tri; /* UINT32_MAX: a miss */
} ref_hit;

static void reference(const world_tris *w, const rt_ray *r, ref_hit out[3]) {
    static const double bands[3] = {-EDGE_BAR, 0.0, EDGE_BAR};
    double o[3] = {r->org[0], r->org[1], r->org[2]}, d[3] = {r->dir[0], r->dir[1], r->dir[2]};
    for (int b = 0; b < 3; b++) {
        out[b].t = INFINITY;
        out[b].tri = UINT32_MAX;
    }
    for (uint32_t t = 0; t < w->count; t++) {
        const double *v = w->v + 9 * (size_t)t;
        double e1[3], e2[3], pv[3], s[3], q[3];
        sub3(v + 3, v, e1);
        sub3(v + 6, v, e2);
        cross3(d, e2, pv);
        double det = dot3(e1, pv);
        if (det == 0.0) continue;
        sub3(o, v, s);
        double u = dot3(s, pv) / det;
        if (u < -EDGE_BAR || u > 1.0 + EDGE_BAR) continue;
        cross3(s, e1, q);
        double vv = dot3(d, q) / det, tt = dot3(e2, q) / det;
        if (!(tt >= (double)r->tmin && tt <= (double)r->tmax)) continue;
        double m = u < vv ? u : vv, wb = 1.0 - u - vv;
        m = wb < m ? wb : m;
        for (int b = 0; b < 3; b++)
            if (m >= bands[b] && tt < out[b].t) { /* t order, then the lower index */
                out[b].t = tt;
                out[b].tri = t;
            }
    }
}

static int same_surface(double a, double b) {
    return fabs(a - b) <= SAME_T * fabs(b);
}

typedef struct sample_job {
    const world_tris *w;
    const rt_ray *rays;
    const size_t *index;
    size_t count;
    ref_hit (*ref)[3];
} sample_job;

static void sample_chunk(void *ctx, int worker, int workers) {
    sample_job *j = ctx;
    for (size_t i = (size_t)worker; i < j->count; i += (size_t)workers)
        reference(j->w, &j->rays[j->index[i]], j->ref[i]);
}

int main(int argc, char **argv) {
    const char *path = NULL;
    int w = 1024, h = 576, runs = 5, threads = 2, sample = 2048;
    for (int i = 1; i < argc; i++) {
        int ok = 1;
        if (!strcmp(argv[i], "--width"))
            ok = bench_arg_int(argc, argv, &i, 1, 16384, &w);
        else if (!strcmp(argv[i], "--height"))
            ok = bench_arg_int(argc, argv, &i, 1, 16384, &h);
        else if (!strcmp(argv[i], "--runs"))
            ok = bench_arg_int(argc, argv, &i, 1, MAX_RUNS, &runs);
        else if (!strcmp(argv[i], "--threads"))
            ok = bench_arg_int(argc, argv, &i, 1, 1024, &threads);
        else if (!strcmp(argv[i], "--sample"))
            ok = bench_arg_int(argc, argv, &i, 0, 1 << 20, &sample);
        else if (argv[i][0] == '-' || path)
            ok = 0;
        else
            path = argv[i];
        if (!ok) {
            fprintf(stderr, "bench_tri_study: bad argument '%s'\n", argv[i]);
            return 2;
        }
    }
    if (!path) {
        fprintf(stderr, "usage: bench_tri_study SCENE [--width W] [--height H] [--runs N] "
                        "[--threads T] [--sample S]\n");
        return 2;
    }
    rt_scene *scene;
    rt_error err;
    if (rt_scene_load(path, &scene, &err) != RT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    rt_camera cam;
    rt_camera_get(scene, &cam);
    bench_interior_view(path, &cam);
    size_t n = (size_t)w * h;
    rt_ray *rays = malloc(n * sizeof *rays);
    rt_hit *hits[TESTS];
    for (int m = 0; m < TESTS; m++) hits[m] = malloc(n * sizeof(rt_hit));
    world_tris wt;
    if (!rays || !hits[0] || !hits[1] || !hits[2] || !hits[3] || !gather_world(scene, &wt)) {
        fprintf(stderr, "bench_tri_study: out of memory\n");
        return 1;
    }
    bench_primary_rays(&cam, w, h, rays);

    rt_renderer *renderer = bench_renderer("cpu", threads);
    if (!renderer) return 1;
    rt_trace_options opt = {0, RT_TRI_TEST_WATERTIGHT, NULL, RT_TRACE_PATH_AUTO, NULL, NULL};
    static double ms[TESTS][MAX_RUNS];
    for (int r = -1; r < runs; r++) /* r = -1: the warm-up pass, not counted */
        for (int m = 0; m < TESTS; m++) {
            opt.tri_test = (rt_triangle_test)m;
            double t0 = rt_now_ms();
            if (rt_trace_rays(renderer, scene, rays, n, hits[m], &opt) != RT_OK) {
                fprintf(stderr, "%s\n", rt_renderer_error(renderer));
                return 1;
            }
            if (r >= 0) ms[m][r] = rt_now_ms() - t0;
        }

    /* The double-precision closest-hit reference on every k-th ray. */
    size_t stride = sample > 0 && (size_t)sample < n ? n / (size_t)sample : 1, count = 0;
    size_t *index = malloc(sizeof(size_t) * (n / stride + 1));
    ref_hit(*ref)[3] = malloc(sizeof *ref * (n / stride + 1));
    if (!index || !ref) return 1;
    if (sample > 0)
        for (size_t i = stride / 2; i < n && count < (size_t)sample; i += stride)
            index[count++] = i;
    rt_pool *pool = rt_pool_create(threads);
    sample_job job = {&wt, rays, index, count, ref};
    if (count) rt_pool_run(pool, sample_chunk, &job);
    rt_pool_destroy(pool);

    printf("test\trays\thits\tmin_ms\tmedian_ms\tt_max_rel\tt_mean_rel\tsample\tref_hits\t"
           "differ_decisive\tdiffer_edge\tedge_rays\tthreads\n");
    for (int m = 0; m < TESTS; m++) {
        size_t hit_count = 0;
        double emax = 0.0, esum = 0.0;
        for (size_t i = 0; i < n; i++) {
            const rt_hit *hh = &hits[m][i];
            if (!hh->hit) continue;
            hit_count++;
            double tr = plane_t(&wt, wt.first[hh->inst] + hh->prim, &rays[i]);
            double e = tr != 0.0 ? fabs((double)hh->t - tr) / fabs(tr) : fabs((double)hh->t);
            if (!(e == e)) e = INFINITY; /* parallel in double: no reference t */
            emax = e > emax ? e : emax;
            esum += e;
        }
        size_t ref_hits = 0, differ_decisive = 0, differ_edge = 0, edge_rays = 0;
        for (size_t k = 0; k < count; k++) {
            const ref_hit *g = &ref[k][0], *x = &ref[k][1], *s = &ref[k][2];
            const rt_ray *ray = &rays[index[k]];
            const rt_hit *hh = &hits[m][index[k]];
            int decisive =
                g->tri == UINT32_MAX ||
                (s->tri != UINT32_MAX && same_surface(g->t, s->t) && same_surface(x->t, s->t));
            ref_hits += x->tri != UINT32_MAX;
            edge_rays += !decisive;
            int agree;
            if (x->tri == UINT32_MAX || !hh->hit)
                agree = (x->tri == UINT32_MAX) == !hh->hit;
            else
                agree = same_surface(plane_t(&wt, wt.first[hh->inst] + hh->prim, ray), x->t);
            if (!agree) {
                if (decisive)
                    differ_decisive++;
                else
                    differ_edge++;
            }
        }
        double min, med;
        bench_min_median(ms[m], runs, &min, &med);
        printf("%s\t%zu\t%zu\t%.3f\t%.3f\t%.3g\t%.3g\t%zu\t%zu\t%zu\t%zu\t%zu\t%d\n", test_names[m],
               n, hit_count, min, med, emax, hit_count ? esum / (double)hit_count : 0.0, count,
               ref_hits, differ_decisive, differ_edge, edge_rays, threads);
    }
    free(index);
    free(ref);
    free_world(&wt);
    for (int m = 0; m < TESTS; m++) free(hits[m]);
    free(rays);
    rt_renderer_destroy(renderer);
    rt_scene_destroy(scene);
    return 0;
}
