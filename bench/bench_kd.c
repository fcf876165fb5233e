/* SPDX-License-Identifier: Apache-2.0 */
/* bench_kd.c - build time of the SAH kd-tree builders (issue 18) on one scene:
 * one tree over all triangles of all meshes (as rtcl bench builds one BVH),
 * exact and binned, with 1 and 2 threads. Prints wall-clock and CPU time
 * (process CPU time over all threads, getrusage): on a machine shared with
 * other work the wall time measures the machine, the CPU time the builder.
 * Min and median of N runs after one warm-up run, runs of the four set-ups
 * interleaved round by round.
 *
 * usage: bench_kd SCENE [N]   (default N = 5) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "accel/kd.h"
#include "base/clock.h"
#include "base/thread_pool.h"
#include "rt.h"
#include "scene/scene.h"

static double cpu_ms(void) {
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return (double)(u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3 +
           (double)(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-3;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n) {
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: bench_kd SCENE [N]\n");
        return 2;
    }
    int reps = argc > 2 ? atoi(argv[2]) : 5;
    if (reps < 1 || reps > 1000) reps = 5;
    rt_scene *scene;
    rt_error err;
    if (rt_scene_load(argv[1], &scene, &err) != RT_OK) {
        fprintf(stderr, "bench_kd: %s\n", err.message);
        return 2;
    }
    /* All meshes as one triangle list. */
    uint64_t nv = 0, nt = 0;
    for (uint32_t m = 0; m < scene->mesh_count; m++) {
        nv += scene->meshes[m].vertex_count;
        nt += scene->meshes[m].triangle_count;
    }
    float *pos = malloc(sizeof(float) * 3 * (nv + 1));
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * (nt + 1));
    if (!pos || !idx || nv > UINT32_MAX || nt > UINT32_MAX) return 2;
    uint32_t vb = 0, tb = 0;
    for (uint32_t m = 0; m < scene->mesh_count; m++) {
        const rt_mesh_data *md = &scene->meshes[m];
        memcpy(pos + 3 * (size_t)vb, md->positions, sizeof(float) * 3 * md->vertex_count);
        for (uint32_t i = 0; i < 3 * md->triangle_count; i++)
            idx[3 * (size_t)tb + i] = md->indices[i] + vb;
        vb += md->vertex_count;
        tb += md->triangle_count;
    }
    rt_pool *pool2 = rt_pool_create(2);
    struct {
        rt_kd_builder b;
        int threads;
        double wall[1000], cpu[1000];
        rt_kd_quality q;
    } *set = calloc(4, sizeof *set);
    if (!set) return 2;
    for (int s = 0; s < 4; s++) {
        set[s].b = s < 2 ? RT_KD_EXACT : RT_KD_BINNED;
        set[s].threads = s % 2 ? 2 : 1;
    }
    for (int r = -1; r < reps; r++)
        for (int s = 0; s < 4; s++) {
            rt_kd_options o = rt_kd_options_default();
            o.builder = set[s].b;
            rt_kd kd;
            double c0 = cpu_ms(), t0 = rt_now_ms();
            rt_status st =
                rt_kd_build(pos, vb, idx, tb, &o, set[s].threads > 1 ? pool2 : NULL, &kd, &err);
            double t1 = rt_now_ms(), c1 = cpu_ms();
            if (st != RT_OK) {
                fprintf(stderr, "bench_kd: %s\n", err.message);
                return 2;
            }
            if (r >= 0) {
                set[s].wall[r] = t1 - t0;
                set[s].cpu[r] = c1 - c0;
            }
            if (r == reps - 1) set[s].q = rt_kd_measure(&kd, rt_sah_costs_default());
            rt_kd_free(&kd);
        }
    printf("%s: %u triangles, %d runs after 1 warm-up run\n", argv[1], tb, reps);
    printf("| builder | threads | wall min ms | wall median ms | CPU min ms | CPU median ms | SAH "
           "(Ct 1, Ci 2) | nodes | refs/triangle | depth | MiB |\n");
    printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int s = 0; s < 4; s++) {
        double wmin = 1e300, cmin = 1e300;
        for (int r = 0; r < reps; r++) {
            if (set[s].wall[r] < wmin) wmin = set[s].wall[r];
            if (set[s].cpu[r] < cmin) cmin = set[s].cpu[r];
        }
        printf("| %s | %d | %.1f | %.1f | %.1f | %.1f | %.2f | %u | %.2f | %u | %.2f |\n",
               rt_kd_builder_name(set[s].b), set[s].threads, wmin, median(set[s].wall, reps), cmin,
               median(set[s].cpu, reps), set[s].q.sah, set[s].q.nodes, set[s].q.refs_per_tri,
               set[s].q.depth, (double)set[s].q.bytes / 1048576.0);
    }
    free(set);
    free(pos);
    free(idx);
    rt_pool_destroy(pool2);
    rt_scene_destroy(scene);
    return 0;
}
