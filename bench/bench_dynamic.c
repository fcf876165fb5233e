/* SPDX-License-Identifier: Apache-2.0 */
/* bench_dynamic.c - the keyframe benchmark of Langr 2016 (section 4.1) for
 * deforming meshes: an animated scene morphing between its keyframes, frame
 * by frame, with each update policy of ours on one renderer, beside Embree
 * committing the same positions into a dynamic scene at build quality REFIT,
 * LOW (Morton) and MEDIUM (binned SAH), tracing them too. Engines are
 * interleaved frame by frame so that the machine's noise spreads over all.
 *
 * The measuring is 'rtcl bench --animate's (bench/engines/bench_animate.c,
 * built into this program too); this program prints its table and, from
 * the same samples, the study behind RT_UPDATE_AUTO_BOUND below. Frame 0
 * (the first build) is left out.
 * Also the study behind RT_UPDATE_AUTO_BOUND: per frame, the refitted tree's
 * SAH cost and render time against the rebuilt tree's of the same frame.
 *
 * usage: bench_dynamic [--threads N] [--runs R] [--frames F] [--fps X]
 *                      [--backend B] [--width W --height H] SCENE.json... */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engines/bench_animate.h"
#include "bench_util.h"

static double ms_min, ms_med;

/* Min and median of v[0..n) into ms_min, ms_med (v is left as it was). */
static void stat(const double *v, int n) {
    double *c = malloc(sizeof(double) * (size_t)(n ? n : 1));
    memcpy(c, v, sizeof(double) * (size_t)n);
    if (n)
        bench_min_median(c, n, &ms_min, &ms_med);
    else
        ms_min = ms_med = 0.0;
    free(c);
}

/* All counted samples (frames 1 .. frames of every run) of v. */
static int counted(const bench_anim_result *res, const double *v, double *out) {
    int n = 0;
    for (int run = 0; run < res->runs; run++)
        for (int k = 1; k <= res->frames; k++) out[n++] = v[bench_anim_index(res, run, k)];
    return n;
}

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
                   bench_arg_int(argc, argv, &i, 2, 100000, &frames)) {
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
    printf("threads %d, %d runs interleaved, %d frames at %g fps (frame 0, the first build, left "
           "out), %s backend, %dx%d, primary and shadow rays, one light\n\n",
           threads, runs, frames, fps, backend, width, height);
    for (int si = first_scene; si < argc; si++) {
        bench_anim_setup su = {runs,   frames - 1, fps, threads, width,
                               height, backend,    1,   NULL,    NULL};
        bench_anim_result res;
        char err[400];
        if (!bench_animate(argv[si], &su, &res, err, sizeof err)) {
            fprintf(stderr, "%s\n", err);
            return 2;
        }
        bench_anim_print_text(argv[si], &res);
        const bench_anim_row *rebuild = &res.rows[0], *refit = &res.rows[1];
        if (res.n_rows == 7 && !res.rows[4].error[0] && !res.rows[5].error[0] &&
            !res.rows[6].error[0])
            printf("\nMedian BVH update, ours / Embree's: refit / REFIT %.2f, fast / LOW %.2f, "
                   "rebuild / MEDIUM %.2f\n",
                   refit->update_ms_median / res.rows[4].update_ms_median,
                   res.rows[2].update_ms_median / res.rows[5].update_ms_median,
                   rebuild->update_ms_median / res.rows[6].update_ms_median);
        if (rebuild->error[0] || refit->error[0]) {
            bench_anim_free(&res);
            return 2;
        }
        /* The refit study: per frame, medians over the runs of refit over
         * rebuild (the counts are the same in every run). */
        printf("\nRefit against rebuild, frame by frame: the refitted tree's SAH cost, its "
               "counted traversal work (box tests + 2 x triangle tests, all rays) and its "
               "render time (median over the runs), each over the rebuilt tree's\n\n"
               "| frame | time s | SAH | tests | render ms |\n|---:|---:|---:|---:|---:|\n");
        double sxy = 0.0, sxx = 0.0, max_sah = 0.0;
        for (int k = 1; k <= res.frames; k++) {
            double rr[100], ss[100];
            for (int run = 0; run < res.runs; run++) {
                size_t i = bench_anim_index(&res, run, k);
                rr[run] = refit->trace[i] / rebuild->trace[i];
                ss[run] = refit->sah_f[i] / rebuild->sah_f[i];
            }
            size_t i0 = bench_anim_index(&res, 0, k);
            double tr = refit->tests[i0] / rebuild->tests[i0];
            stat(ss, res.runs);
            double sm = ms_med;
            stat(rr, res.runs);
            printf("| %d | %.2f | %.3f | %.3f | %.3f |\n", k, k / fps, sm, tr, ms_med);
            sxy += (sm - 1.0) * (tr - 1.0);
            sxx += (sm - 1.0) * (sm - 1.0);
            if (sm > max_sah) max_sah = sm;
        }
        /* Where refitting stops paying: the extra traversal of the refitted
         * tree costs as much as a rebuild saves. With the minima of the runs:
         * tests ratio r* = 1 + (rebuild - refit update) / rebuilt render time;
         * and through the fitted slope of tests over SAH, the SAH ratio. */
        double *v = malloc(sizeof(double) * (size_t)res.runs * (size_t)res.frames);
        if (!v) return 2;
        stat(v, counted(&res, rebuild->update, v));
        double rebuild_ms = ms_min;
        stat(v, counted(&res, refit->update, v));
        double refit_ms = ms_min;
        stat(v, counted(&res, rebuild->trace, v));
        double render_ms = ms_min;
        free(v);
        double slope = sxx > 0.0 ? sxy / sxx : 0.0;
        double r_star = 1.0 + (rebuild_ms - refit_ms) / render_ms;
        printf("\nBreak-even: a rebuild saves %.2f ms over a refit (minima) against %.2f ms of "
               "rendering on the rebuilt tree (minimum): refitting pays while the counted work "
               "stays below %.3f x the rebuilt tree's; the work grows %.2f times as fast as the "
               "SAH cost (least squares through 1), so the break-even SAH ratio is %.3f. The "
               "largest SAH ratio of a refitted tree here: %.3f.\n\n",
               rebuild_ms - refit_ms, render_ms, r_star, slope,
               slope > 0.0 ? 1.0 + (r_star - 1.0) / slope : 0.0, max_sah);
        bench_anim_free(&res);
    }
    return 0;
}
