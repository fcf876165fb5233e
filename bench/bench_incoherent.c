/* SPDX-License-Identifier: Apache-2.0 */
/* bench_incoherent.c - the incoherent-ray benchmark as a program of its own
 * (the same code as 'rtcl bench --incoherent': bench/engines/incoherent_bench.h),
 * with the interior views of VIEWS.md for the bare OBJ files of Sponza and
 * Sibenik, and no Whitted frames unless --whitted.
 *
 * usage: bench_incoherent [--rays N] [--reps R] [--threads T] [--whitted] [--json] SCENE... */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "engines/incoherent_bench.h"

enum { MAX_REPS = 64 };

static void interior(const char *path, rt_camera *cam) {
    bench_interior_view(path, cam);
}

int main(int argc, char **argv) {
    incoh_setup su = incoh_setup_default();
    su.whitted = 0;
    su.camera = interior;
    int rays = (int)su.rays, json = 0, bad = 0, n = 0;
    const char **scenes = calloc((size_t)argc, sizeof *scenes);
    if (!scenes) return 2;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--rays")) {
            if (!bench_arg_int(argc, argv, &i, 1, 100000000, &rays)) bad = 1;
        } else if (!strcmp(argv[i], "--reps")) {
            if (!bench_arg_int(argc, argv, &i, 1, MAX_REPS, &su.reps)) bad = 1;
        } else if (!strcmp(argv[i], "--threads")) {
            if (!bench_arg_int(argc, argv, &i, 1, 256, &su.threads)) bad = 1;
        } else if (!strcmp(argv[i], "--whitted")) {
            su.whitted = 1;
        } else if (!strcmp(argv[i], "--json")) {
            json = 1;
        } else if (argv[i][0] == '-') {
            bad = 1;
        } else {
            scenes[n++] = argv[i];
        }
    }
    if (bad || !n) {
        fprintf(stderr, "usage: bench_incoherent [--rays N] [--reps R] [--threads T] [--whitted] "
                        "[--json] SCENE...\n");
        free(scenes);
        return 2;
    }
    su.rays = (size_t)rays;
    int rc = incoh_run(scenes, n, &su, json, "bench_incoherent");
    free(scenes);
    return rc;
}
