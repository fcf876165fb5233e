/* bench_dynamic.c - the keyframe benchmark of Langr 2016 (section 4.1) for
 * deforming meshes: an animated scene morphing between its keyframes, frame
 * by frame, with each update policy of ours on one renderer, beside Embree
 * committing the same positions into a dynamic scene at build quality REFIT,
 * LOW (Morton) and MEDIUM (binned SAH). Runs are interleaved (every engine
 * once per run) so that the machine's noise spreads over all of them.
 *
 * Per policy: the BVH update (the mesh's refit or build, as the renderer
 * reports it), the host update of the frame (that, plus the object BVH, the
 * layout rewritten in place and the packet backend's wide BVH), the whole
 * frame (host update plus rendering, primary and shadow rays, one light),
 * and the SAH cost of the tree. Frame 0 (the first build) is left out.
 * Also the study behind RT_UPDATE_AUTO_BOUND: per frame, the refitted tree's
 * SAH cost and render time against the rebuilt tree's of the same frame.
 *
 * usage: bench_dynamic [--threads N] [--runs R] [--frames F] [--fps X]
 *                      [--backend B] [--width W --height H] SCENE.json... */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "bench_util.h"
#include "rt.h"
#include "scene/scene.h"
#ifdef RT_HAVE_EMBREE
#include "peer/embree_peer.h"
#endif

enum { OURS = 4, ENGINES = 7, MAX_FRAMES = 400 };
static const char *const engine_names[ENGINES] = {"rtcl rebuild", "rtcl refit",   "rtcl fast",
                                                  "rtcl auto",    "embree REFIT", "embree LOW",
                                                  "embree MEDIUM"};
static const rt_update_policy policies[OURS] = {RT_UPDATE_REBUILD, RT_UPDATE_REFIT, RT_UPDATE_FAST,
                                                RT_UPDATE_AUTO};

typedef struct samples {
    double *update, *host, *frame, *sah, *render; /* runs x frames */
    int n;
} samples;

static double ms_min, ms_med;

static void stat(double *v, int n) {
    double *c = malloc(sizeof(double) * (size_t)(n ? n : 1));
    memcpy(c, v, sizeof(double) * (size_t)n);
    if (n)
        bench_min_median(c, n, &ms_min, &ms_med);
    else
        ms_min = ms_med = 0.0;
    free(c);
}

/* The mesh the first morphing object shows (its blend), or UINT32_MAX. */
static uint32_t morph_mesh(const rt_scene *s) {
    for (uint32_t o = 0; o < s->object_count; o++)
        if (s->objects[o].morphing) return s->objects[o].morph_mesh;
    return UINT32_MAX;
}

static int run_ours(rt_scene *s, rt_update_policy p, const char *backend, int threads, int frames,
                    double fps, samples *out, double *render_of_frame, double *sah_of_frame,
                    double *tests_of_frame) {
    rt_renderer *r = bench_renderer(backend, threads);
    if (!r) return 0;
    for (uint32_t m = 0; m < s->mesh_count; m++) rt_mesh_set_update(s, m, p);
    rt_render_options o = rt_render_options_default();
    rt_render_stats st;
    o.stats = &st;
    o.direct_only = 1;
    o.reuse_framebuffer = 1;
    rt_framebuffer fb;
    memset(&fb, 0, sizeof fb);
    for (int k = 0; k < frames; k++) {
        rt_scene_set_time(s, k / fps); /* the blend is the scene's work, not timed */
        double t0 = rt_now_ms();
        if (rt_render(r, s, &o, &fb) != RT_OK) {
            fprintf(stderr, "%s\n", rt_renderer_error(r));
            rt_renderer_destroy(r);
            return 0;
        }
        double frame = rt_now_ms() - t0;
        rt_update_stats us;
        rt_renderer_update_stats(r, &us);
        double upd = 0.0;
        for (uint32_t i = 0; i < us.mesh_count; i++) upd += us.meshes[i].ms;
        render_of_frame[k] = st.render_ms;
        sah_of_frame[k] = st.sah_cost;
        /* The traversal work the SAH predicts, counted (Ct = 1, Ci = 2). */
        tests_of_frame[k] = (double)st.box_tests + 2.0 * (double)st.tri_tests;
        if (k == 0) continue; /* the first build */
        out->update[out->n] = upd;
        out->host[out->n] = st.build_ms;
        out->frame[out->n] = frame;
        out->sah[out->n] = st.sah_cost;
        out->render[out->n] = st.render_ms;
        out->n++;
    }
    rt_framebuffer_free(&fb);
    rt_renderer_destroy(r);
    return 1;
}

#ifdef RT_HAVE_EMBREE
static int run_embree(rt_embree *em, rt_scene *s, int quality, int frames, double fps,
                      samples *out) {
    rt_scene_set_time(s, 0.0);
    uint32_t m = morph_mesh(s);
    const rt_mesh_data *md = &s->meshes[m];
    rt_embree_dynamic *d;
    rt_error err;
    double ms;
    if (rt_embree_dynamic_create(em, md->positions, md->vertex_count, md->indices,
                                 md->triangle_count, quality, &d, &ms, &err) != RT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    for (int k = 1; k < frames; k++) {
        rt_scene_set_time(s, k / fps);
        md = &s->meshes[m];
        if (rt_embree_dynamic_update(d, md->positions, &ms, &err) != RT_OK) {
            fprintf(stderr, "%s\n", err.message);
            rt_embree_dynamic_destroy(d);
            return 0;
        }
        out->update[out->n] = out->host[out->n] = ms;
        out->frame[out->n] = out->sah[out->n] = out->render[out->n] = 0.0;
        out->n++;
    }
    rt_embree_dynamic_destroy(d);
    return 1;
}
#endif

int main(int argc, char **argv) {
    int threads = 2, runs = 3, frames = 50, width = 1024, height = 576;
    double fps = 25.0;
    const char *backend = "packet";
    int first_scene = argc;
    for (int i = 1; i < argc; i++) {
        int v;
        if (!strcmp(argv[i], "--threads") && bench_arg_int(argc, argv, &i, 1, 256, &threads)) {
        } else if (!strcmp(argv[i], "--runs") && bench_arg_int(argc, argv, &i, 1, 100, &runs)) {
        } else if (!strcmp(argv[i], "--frames") &&
                   bench_arg_int(argc, argv, &i, 2, MAX_FRAMES, &frames)) {
        } else if (!strcmp(argv[i], "--fps") && bench_arg_int(argc, argv, &i, 1, 1000, &v)) {
            fps = v;
        } else if (!strcmp(argv[i], "--width") && bench_arg_int(argc, argv, &i, 1, 8192, &width)) {
        } else if (!strcmp(argv[i], "--height") &&
                   bench_arg_int(argc, argv, &i, 1, 8192, &height)) {
        } else if (!strcmp(argv[i], "--backend") && i + 1 < argc) {
            backend = argv[++i];
        } else if (argv[i][0] == '-') {
            fprintf(stderr, "usage: bench_dynamic [--threads N] [--runs R] [--frames F] [--fps X] "
                            "[--backend B] [--width W --height H] SCENE.json...\n");
            return 2;
        } else {
            first_scene = i;
            break;
        }
    }
    if (first_scene >= argc) {
        fprintf(stderr, "bench_dynamic: no scene given\n");
        return 2;
    }
#ifdef RT_HAVE_EMBREE
    rt_embree *em = NULL;
    rt_error eerr;
    if (rt_embree_create(threads, &em, &eerr) != RT_OK) {
        fprintf(stderr, "%s\n", eerr.message);
        return 2;
    }
#endif
    printf("threads %d, %d runs interleaved, %d frames at %g fps (frame 0, the first build, left "
           "out), %s backend, %dx%d, primary and shadow rays, one light\n\n",
           threads, runs, frames, fps, backend, width, height);
    for (int si = first_scene; si < argc; si++) {
        rt_scene *s;
        rt_error err;
        if (rt_scene_load(argv[si], &s, &err) != RT_OK) {
            fprintf(stderr, "%s\n", err.message);
            return 2;
        }
        rt_camera cam;
        rt_camera_get(s, &cam);
        cam.width = width;
        cam.height = height;
        rt_camera_set(s, &cam);
        uint32_t mm = morph_mesh(s);
        if (mm == UINT32_MAX) {
            fprintf(stderr, "%s: no object morphs between keyframes\n", argv[si]);
            return 2;
        }
        samples smp[ENGINES];
        size_t cap = (size_t)runs * (size_t)frames;
        for (int e = 0; e < ENGINES; e++) {
            smp[e].update = calloc(cap, sizeof(double));
            smp[e].host = calloc(cap, sizeof(double));
            smp[e].frame = calloc(cap, sizeof(double));
            smp[e].sah = calloc(cap, sizeof(double));
            smp[e].render = calloc(cap, sizeof(double));
            smp[e].n = 0;
        }
        /* Per frame, per run: render ms and SAH of rebuild (0) and refit (1). */
        double *render_f[2], *sah_f[2], *tests_f[2];
        for (int j = 0; j < 2; j++) {
            render_f[j] = calloc(cap, sizeof(double));
            sah_f[j] = calloc(cap, sizeof(double));
            tests_f[j] = calloc(cap, sizeof(double));
        }
        double scratch_r[MAX_FRAMES], scratch_s[MAX_FRAMES], scratch_t[MAX_FRAMES];
        for (int run = 0; run < runs; run++) {
            for (int e = 0; e < OURS; e++) {
                double *rf = e < 2 ? render_f[e] + (size_t)run * frames : scratch_r;
                double *sf = e < 2 ? sah_f[e] + (size_t)run * frames : scratch_s;
                double *tf = e < 2 ? tests_f[e] + (size_t)run * frames : scratch_t;
                if (!run_ours(s, policies[e], backend, threads, frames, fps, &smp[e], rf, sf, tf))
                    return 2;
            }
#ifdef RT_HAVE_EMBREE
            for (int q = 0; q < 3; q++)
                if (!run_embree(em, s, q, frames, fps, &smp[OURS + q])) return 2;
#endif
        }
        printf("### %s: %u triangles morphing\n\n", argv[si], s->meshes[mm].triangle_count);
        printf("| engine | BVH update ms min | median | host update ms min | median | frame ms "
               "min | median | SAH mean |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
        double med_update[ENGINES] = {0};
        for (int e = 0; e < ENGINES; e++) {
            if (!smp[e].n) continue;
            stat(smp[e].update, smp[e].n);
            double umin = ms_min, umed = ms_med;
            med_update[e] = umed;
            stat(smp[e].host, smp[e].n);
            double hmin = ms_min, hmed = ms_med;
            if (e < OURS) {
                stat(smp[e].frame, smp[e].n);
                double sah = 0.0;
                for (int k = 0; k < smp[e].n; k++) sah += smp[e].sah[k];
                printf("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", engine_names[e],
                       umin, umed, hmin, hmed, ms_min, ms_med, sah / smp[e].n);
            } else {
                printf("| %s | %.2f | %.2f | %.2f | %.2f | | | |\n", engine_names[e], umin, umed,
                       hmin, hmed);
            }
        }
        if (smp[OURS].n)
            printf("\nMedian BVH update, ours / Embree's: refit / REFIT %.2f, fast / LOW %.2f, "
                   "rebuild / MEDIUM %.2f\n",
                   med_update[1] / med_update[OURS], med_update[2] / med_update[OURS + 1],
                   med_update[0] / med_update[OURS + 2]);
        /* The refit study: per frame, medians over the runs (the counts are
         * the same in every run). */
        printf("\nRefit against rebuild, frame by frame: the refitted tree's SAH cost, its "
               "counted traversal work (box tests + 2 x triangle tests, all rays) and its "
               "render time (median over the runs), each over the rebuilt tree's\n\n"
               "| frame | time s | SAH | tests | render ms |\n|---:|---:|---:|---:|---:|\n");
        double sxy = 0.0, sxx = 0.0, max_sah = 0.0;
        for (int k = 1; k < frames; k++) {
            double rr[100], ss[100];
            for (int run = 0; run < runs; run++) {
                size_t i = (size_t)run * frames + k;
                rr[run] = render_f[1][i] / render_f[0][i];
                ss[run] = sah_f[1][i] / sah_f[0][i];
            }
            double tr = tests_f[1][k] / tests_f[0][k];
            stat(ss, runs);
            double sm = ms_med;
            stat(rr, runs);
            printf("| %d | %.2f | %.3f | %.3f | %.3f |\n", k, k / fps, sm, tr, ms_med);
            sxy += (sm - 1.0) * (tr - 1.0);
            sxx += (sm - 1.0) * (sm - 1.0);
            if (sm > max_sah) max_sah = sm;
        }
        /* Where refitting stops paying: the extra traversal of the refitted
         * tree costs as much as a rebuild saves. With the minima of the runs:
         * tests ratio r* = 1 + (rebuild - refit update) / rebuilt render time;
         * and through the fitted slope of tests over SAH, the SAH ratio. */
        stat(smp[0].update, smp[0].n);
        double rebuild_ms = ms_min;
        stat(smp[1].update, smp[1].n);
        double refit_ms = ms_min;
        stat(smp[0].render, smp[0].n);
        double render_ms = ms_min;
        double slope = sxx > 0.0 ? sxy / sxx : 0.0;
        double r_star = 1.0 + (rebuild_ms - refit_ms) / render_ms;
        printf("\nBreak-even: a rebuild saves %.2f ms over a refit (minima) against %.2f ms of "
               "rendering on the rebuilt tree (minimum): refitting pays while the counted work "
               "stays below %.3f x the rebuilt tree's; the work grows %.2f times as fast as the "
               "SAH cost (least squares through 1), so the break-even SAH ratio is %.3f. The "
               "largest SAH ratio of a refitted tree here: %.3f.\n",
               rebuild_ms - refit_ms, render_ms, r_star, slope,
               slope > 0.0 ? 1.0 + (r_star - 1.0) / slope : 0.0, max_sah);
        printf("\n");
        for (int e = 0; e < ENGINES; e++) {
            free(smp[e].update);
            free(smp[e].host);
            free(smp[e].frame);
            free(smp[e].sah);
            free(smp[e].render);
        }
        for (int j = 0; j < 2; j++) {
            free(render_f[j]);
            free(sah_f[j]);
            free(tests_f[j]);
        }
        rt_scene_destroy(s);
    }
#ifdef RT_HAVE_EMBREE
    rt_embree_destroy(em);
#endif
    return 0;
}
