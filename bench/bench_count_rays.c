/* SPDX-License-Identifier: Apache-2.0 */
/* bench_count_rays.c - one engine tracing one incoherent ray set, for an
 * instruction counter (valgrind's cachegrind, bench/count_instructions.sh):
 * the same set-up whatever N, so that the counts of a run that traces N
 * rays and of one that traces none differ by the N rays' tracing alone.
 *
 * usage: bench_count_rays SCENE diffuse|random closest|any packet|cpu|embree N [--no-trace]
 *
 * The rays are bench --incoherent's (cpu_ref/ray_sets.h, seed 7) over the
 * layout of the scene. Every engine runs on one thread and first traces one
 * ray (the packet backend builds its wide BVHs lazily; Embree warms its
 * caches), so that neither run counts a build. Then, without --no-trace, the
 * N rays: ours through rt_trace_rays (what a user calls: the hit records
 * with normals included), Embree's through rtcIntersect1 / rtcOccluded1 one
 * ray at a time (bench/peer, its wrapper's hit copies included). Prints the
 * number of hits, so that the runs can be checked against each other. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "layout/flat.h"
#include "ray_sets.h"
#include "render/renderer_internal.h"
#include "rt.h"
#ifdef RT_HAVE_EMBREE
#include "peer/embree_peer.h"
#endif

static int usage(void) {
    fprintf(stderr, "usage: bench_count_rays SCENE diffuse|random closest|any packet|cpu|embree N "
                    "[--no-trace]\n");
    return 2;
}

int main(int argc, char **argv) {
    if (argc < 6 || argc > 7) return usage();
    const char *path = argv[1], *set = argv[2], *query = argv[3], *engine = argv[4];
    const long n = strtol(argv[5], NULL, 10);
    const int trace = !(argc == 7 && !strcmp(argv[6], "--no-trace"));
    if ((strcmp(set, "diffuse") && strcmp(set, "random")) ||
        (strcmp(query, "closest") && strcmp(query, "any")) || n < 1 || (argc == 7 && trace))
        return usage();
    const int any_hit = !strcmp(query, "any"), embree = !strcmp(engine, "embree");
    rt_scene *scene;
    rt_error err;
    if (rt_scene_load(path, &scene, &err) != RT_OK) {
        fprintf(stderr, "bench_count_rays: %s\n", err.message);
        return 2;
    }
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = embree ? "cpu" : engine;
    o.threads = 1;
    rt_renderer *r;
    if (rt_renderer_create(&o, &r, &err) != RT_OK) {
        fprintf(stderr, "bench_count_rays: %s\n", err.message);
        return 2;
    }
    rt_backend_layout layout;
    double build_ms, sah;
    if (rt_renderer_layout(r, scene, &layout, &build_ms, &sah) != RT_OK) {
        fprintf(stderr, "bench_count_rays: %s\n", rt_renderer_error(r));
        return 2;
    }
    rt_ray *rays = malloc(sizeof(rt_ray) * (size_t)(n + 1));
    rt_hit *hits = malloc(sizeof(rt_hit) * (size_t)(n + 1));
    rt_hit_d *hd = malloc(sizeof(rt_hit_d) * (size_t)(n + 1));
    if (!rays || !hits || !hd) return 2;
    if (!strcmp(set, "diffuse"))
        rt_rays_diffuse(layout.flat, 7, (size_t)n + 1, rays);
    else
        rt_rays_random(layout.flat, 7, (size_t)n + 1, rays);
    long found = 0;
    rt_trace_options topt;
    memset(&topt, 0, sizeof topt);
    topt.any_hit = any_hit;
    if (!embree) {
        /* The first ray builds what the backend builds lazily. */
        if (rt_trace_rays(r, scene, rays + n, 1, hits, &topt) != RT_OK ||
            (trace && rt_trace_rays(r, scene, rays, (size_t)n, hits, &topt) != RT_OK)) {
            fprintf(stderr, "bench_count_rays: %s\n", rt_renderer_error(r));
            return 2;
        }
        for (long i = 0; trace && i < n; i++) found += hits[i].hit != 0;
    } else {
#ifdef RT_HAVE_EMBREE
        rt_embree *em;
        rt_embree_scene *es;
        double ms;
        if (rt_embree_create(1, &em, &err) != RT_OK ||
            rt_embree_scene_create(em, layout.flat, &es, &ms, &err) != RT_OK) {
            fprintf(stderr, "bench_count_rays: %s\n", err.message);
            return 2;
        }
        if (rt_embree_trace_rays(es, rays + n, 1, any_hit, 1, layout.pool, hd, &ms) != RT_OK ||
            (trace &&
             rt_embree_trace_rays(es, rays, (size_t)n, any_hit, 1, layout.pool, hd, &ms) != RT_OK))
            return 2;
        for (long i = 0; trace && i < n; i++) found += hd[i].prim != RT_NO_HIT;
        rt_embree_scene_destroy(es);
        rt_embree_destroy(em);
#else
        fprintf(stderr, "bench_count_rays: this build has no Embree peer\n");
        return 2;
#endif
    }
    printf("%s %s %s %s: %ld rays traced, %ld hits\n", path, set, query, engine, trace ? n : 0,
           found);
    free(rays);
    free(hits);
    free(hd);
    rt_renderer_destroy(r);
    rt_scene_destroy(scene);
    return 0;
}
