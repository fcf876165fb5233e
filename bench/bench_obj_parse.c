/* SPDX-License-Identifier: Apache-2.0 */
/* bench_obj_parse.c - OBJ load throughput: triangles per second.
 *
 * usage: bench_obj_parse [-n RUNS] FILE.obj...
 * For each file, loads it RUNS times with rt_obj_load (reading the file and
 * parsing it; after the first run the file is in the page cache) and prints
 * the min and median time and the triangles per second they give. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "formats/obj_load.h"

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int compare_doubles(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv) {
    int runs = 5;
    int first_file = 1;
    if (argc > 2 && strcmp(argv[1], "-n") == 0) {
        runs = atoi(argv[2]);
        first_file = 3;
    }
    if (runs < 1 || first_file >= argc) {
        fprintf(stderr, "usage: %s [-n RUNS] FILE.obj...\n", argv[0]);
        return 2;
    }
    double *times = malloc((size_t)runs * sizeof *times);
    if (!times) return 1;
    printf("%-40s %10s %10s %10s %14s %14s\n", "file", "triangles", "min ms", "median ms",
           "Mtri/s (min)", "Mtri/s (med)");
    int status = 0;
    for (int f = first_file; f < argc; f++) {
        uint32_t triangles = 0;
        int ok = 1;
        for (int r = 0; r < runs && ok; r++) {
            rt_obj_mesh mesh;
            rt_error err;
            double t0 = now_seconds();
            rt_status st = rt_obj_load(argv[f], &mesh, &err);
            times[r] = now_seconds() - t0;
            if (st != RT_OK) {
                fprintf(stderr, "%s\n", err.message);
                ok = 0;
                status = 1;
            }
            triangles = mesh.triangle_count;
            rt_obj_free(&mesh);
        }
        if (!ok) continue;
        qsort(times, (size_t)runs, sizeof *times, compare_doubles);
        double min = times[0], median = times[runs / 2];
        if (runs % 2 == 0) median = 0.5 * (times[runs / 2 - 1] + times[runs / 2]);
        const char *name = strrchr(argv[f], '/');
        name = name ? name + 1 : argv[f];
        printf("%-40s %10u %10.2f %10.2f %14.2f %14.2f\n", name, triangles, 1e3 * min, 1e3 * median,
               1e-6 * triangles / min, 1e-6 * triangles / median);
    }
    free(times);
    return status;
}
