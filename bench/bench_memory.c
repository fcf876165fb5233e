/* SPDX-License-Identifier: Apache-2.0 */
/* bench_memory.c - memory per triangle of each backend and structure,
 * beside Embree's footprint for the same mesh (docs/BENCHMARKS.md, "Memory
 * per triangle"; bench/memory_section.sh makes the section).
 *
 * usage: bench_memory (SCENE | --grid N) [--backend B]... [--accel bvh|kd]
 *                     [--threads T] [--no-rays] [--no-embree] [--json]
 *
 * The mesh is a scene file's or a height field of N triangles made here (a
 * terrain of about N/2 vertices). For each backend a fresh renderer renders
 * one 64x64 frame (direct rays) and rt_renderer_memory says what the scene
 * and the renderer hold, by part, then (unless --no-rays) traces 64 ray
 * queries, which make the packet backend's single-ray trees, and says it
 * again; the process's resident memory is read
 * before the renderer is made, after the frame and at its peak (VmHWM, reset
 * first through /proc/self/clear_refs). Embree (when the build has it) gets
 * the same triangles in one geometry that shares our arrays, at its default
 * (medium) quality and with RTC_SCENE_FLAG_COMPACT; its memory monitor
 * callback counts what it allocates. --backend none measures Embree alone.
 * One backend per run gives clean resident figures (memory a backend freed
 * stays with the allocator for the next). Memory is counted, not timed: the
 * figures do not depend on the machine's load. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rt.h"
#include "scene/scene.h"
#ifdef RT_HAVE_EMBREE
#include "peer/embree_peer.h"
#endif

/* VmRSS or VmHWM of this process, in bytes (0 when /proc is not there). */
static uint64_t proc_bytes(const char *field) {
    FILE *f = fopen("/proc/self/status", "r");
    if (!f) return 0;
    char line[256];
    unsigned long long kb = 0;
    size_t n = strlen(field);
    while (fgets(line, sizeof line, f))
        if (strncmp(line, field, n) == 0 && line[n] == ':') sscanf(line + n + 1, "%llu", &kb);
    fclose(f);
    return (uint64_t)kb * 1024;
}

/* Resets VmHWM to the current resident size (Linux >= 4.0). */
static void reset_peak(void) {
    FILE *f = fopen("/proc/self/clear_refs", "w");
    if (!f) return;
    fputs("5", f);
    fclose(f);
}

/* A height field of about triangles triangles over [-1,1]^2, as one mesh
 * of a new scene with a camera looking down on it. */
static rt_scene *grid_scene(uint32_t triangles) {
    uint32_t n = (uint32_t)sqrt((double)triangles / 2.0);
    if (n < 1) n = 1;
    uint32_t nv = (n + 1) * (n + 1), nt = 2 * n * n;
    /* One float more: Embree reads 16 bytes at the last vertex. */
    float *pos = malloc(((size_t)nv * 3 + 1) * sizeof *pos);
    uint32_t *idx = malloc((size_t)nt * 3 * sizeof *idx);
    rt_scene *s = NULL;
    if (!pos || !idx || rt_scene_create(&s) != RT_OK) goto done;
    for (uint32_t y = 0; y <= n; y++)
        for (uint32_t x = 0; x <= n; x++) {
            float *p = pos + 3 * ((size_t)y * (n + 1) + x);
            p[0] = 2.0f * (float)x / (float)n - 1.0f;
            p[2] = 2.0f * (float)y / (float)n - 1.0f;
            p[1] = 0.1f * sinf(9.0f * p[0]) * cosf(7.0f * p[2]) + 0.05f * sinf(31.0f * p[0] * p[2]);
        }
    size_t k = 0;
    for (uint32_t y = 0; y < n; y++)
        for (uint32_t x = 0; x < n; x++) {
            uint32_t a = y * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
            uint32_t q[6] = {a, c, b, b, c, d};
            memcpy(idx + k, q, sizeof q);
            k += 6;
        }
    uint32_t mesh, mat, obj;
    rt_material m = rt_material_default();
    const float light[3] = {0, 5, 0}, white[3] = {1, 1, 1};
    rt_camera cam = {{0, 2.5f, 2.5f}, {0, 0, 0}, {0, 1, 0}, 60.0f, 64, 64};
    uint32_t light_id;
    if (rt_mesh_create(s, &mesh) != RT_OK ||
        rt_mesh_add_triangles(s, mesh, pos, NULL, nv, idx, nt) != RT_OK ||
        rt_material_add(s, &m, &mat) != RT_OK || rt_object_create(s, mat, &obj) != RT_OK ||
        rt_object_add_mesh(s, obj, mesh) != RT_OK || rt_camera_set(s, &cam) != RT_OK ||
        rt_light_add(s, light, white, &light_id) != RT_OK) {
        rt_scene_destroy(s);
        s = NULL;
    }
done:
    free(pos);
    free(idx);
    return s;
}

typedef struct totals {
    uint64_t triangles, vertices;
} totals;

static totals count(const rt_scene *s) {
    totals t = {0, 0};
    for (uint32_t m = 0; m < s->mesh_count; m++) {
        t.triangles += s->meshes[m].triangle_count;
        t.vertices += s->meshes[m].vertex_count;
    }
    return t;
}

static double per(uint64_t bytes, uint64_t tris) {
    return tris ? (double)bytes / (double)tris : 0.0;
}

static void print_row(int json, const char *what, const char *accel, uint64_t tris,
                      const rt_memory_stats *m, uint64_t rss_delta, uint64_t peak_delta) {
    uint64_t ours = m->mesh_bvhs + m->object_bvh + m->kept + m->layout + m->backend;
    if (json) {
        printf("{\"what\": \"%s\", \"accel\": \"%s\", \"triangles\": %llu, \"scene\": %llu, "
               "\"mesh_bvhs\": %llu, \"object_bvh\": %llu, \"kept\": %llu, \"layout\": %llu, "
               "\"backend\": %llu, \"device\": %llu, \"structures\": %llu, \"rss_delta\": %llu, "
               "\"peak_delta\": %llu}\n",
               what, accel, (unsigned long long)tris, (unsigned long long)m->scene,
               (unsigned long long)m->mesh_bvhs, (unsigned long long)m->object_bvh,
               (unsigned long long)m->kept, (unsigned long long)m->layout,
               (unsigned long long)m->backend, (unsigned long long)m->device,
               (unsigned long long)ours, (unsigned long long)rss_delta,
               (unsigned long long)peak_delta);
        return;
    }
    printf("%-12s %-4s scene %6.1f  BVHs %6.1f  kept %6.1f  layout %6.1f  backend %6.1f  device "
           "%6.1f | structures %6.1f  RSS +%6.1f  peak +%6.1f bytes/triangle\n",
           what, accel, per(m->scene, tris), per(m->mesh_bvhs + m->object_bvh, tris),
           per(m->kept, tris), per(m->layout, tris), per(m->backend, tris), per(m->device, tris),
           per(ours, tris), per(rss_delta, tris), per(peak_delta, tris));
}

int main(int argc, char **argv) {
    const char *path = NULL, *backends[8];
    int nb = 0, json = 0, threads = 0, grid = 0, rays_too = 1, embree = 1;
    rt_accel accel = RT_ACCEL_BVH;
    for (int i = 1; i < argc; i++) {
        int ok = 1;
        if (!strcmp(argv[i], "--grid"))
            ok = bench_arg_int(argc, argv, &i, 2, 200000000, &grid);
        else if (!strcmp(argv[i], "--threads"))
            ok = bench_arg_int(argc, argv, &i, 0, 1024, &threads);
        else if (!strcmp(argv[i], "--backend") && i + 1 < argc && nb < 8)
            backends[nb++] = argv[++i];
        else if (!strcmp(argv[i], "--accel") && i + 1 < argc)
            ok = rt_accel_parse(argv[++i], &accel);
        else if (!strcmp(argv[i], "--json"))
            json = 1;
        else if (!strcmp(argv[i], "--no-rays"))
            rays_too = 0;
        else if (!strcmp(argv[i], "--no-embree"))
            embree = 0;
        else if (argv[i][0] != '-' && !path)
            path = argv[i];
        else
            ok = 0;
        if (!ok) {
            fprintf(stderr, "bench_memory: bad argument '%s'\n", argv[i]);
            return 2;
        }
    }
    if (!path && !grid) {
        fprintf(stderr, "usage: bench_memory (SCENE | --grid N) [--backend B]... [--accel "
                        "bvh|kd] [--threads T] [--no-rays] [--no-embree] [--json]\n");
        return 2;
    }
    if (!nb) backends[nb++] = "packet";
    rt_scene *scene = NULL;
    rt_error err;
    if (grid) {
        scene = grid_scene((uint32_t)grid);
    } else if (rt_scene_load(path, &scene, &err) != RT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    if (!scene) {
        fprintf(stderr, "bench_memory: out of memory\n");
        return 1;
    }
    rt_camera cam;
    rt_camera_get(scene, &cam);
    cam.width = cam.height = 64;
    rt_camera_set(scene, &cam);
    rt_scene_set_static_accel(scene, accel);
    totals t = count(scene);
    if (!json)
        printf("%s: %llu triangles, %llu vertices; bytes per triangle:\n", path ? path : "grid",
               (unsigned long long)t.triangles, (unsigned long long)t.vertices);
    for (int b = 0; b < nb; b++) {
        if (!strcmp(backends[b], "none")) continue; /* Embree alone */
        uint64_t rss0 = proc_bytes("VmRSS");
        reset_peak();
        rt_renderer *r = bench_renderer(backends[b], threads);
        if (!r) continue;
        rt_render_options opt = rt_render_options_default();
        opt.direct_only = 1;
        rt_framebuffer fb;
        memset(&fb, 0, sizeof fb);
        if (rt_render(r, scene, &opt, &fb) != RT_OK) {
            fprintf(stderr, "bench_memory: %s: %s\n", backends[b], rt_renderer_error(r));
            rt_renderer_destroy(r);
            continue;
        }
        rt_framebuffer_free(&fb);
        uint64_t rss1 = proc_bytes("VmRSS"), peak = proc_bytes("VmHWM");
        rt_memory_stats m;
        rt_renderer_memory(r, scene, &m);
        print_row(json, backends[b], rt_accel_name(accel), t.triangles, &m,
                  rss1 > rss0 ? rss1 - rss0 : 0, peak > rss0 ? peak - rss0 : 0);
        /* Ray queries make the packet backend's single-ray trees too. */
        rt_ray rays[64];
        rt_hit hits[64];
        for (int k = 0; k < 64; k++) {
            rays[k] = (rt_ray){
                {0, 2.0f, 0}, {0.01f * (float)(k - 32), -1, 0.013f * (float)k}, 0.0f, INFINITY};
        }
        rt_trace_options to;
        memset(&to, 0, sizeof to);
        if (rays_too && rt_trace_rays(r, scene, rays, 64, hits, &to) == RT_OK) {
            rss1 = proc_bytes("VmRSS");
            peak = proc_bytes("VmHWM");
            rt_renderer_memory(r, scene, &m);
            char what[64];
            snprintf(what, sizeof what, "%s+rays", backends[b]);
            print_row(json, what, rt_accel_name(accel), t.triangles, &m,
                      rss1 > rss0 ? rss1 - rss0 : 0, peak > rss0 ? peak - rss0 : 0);
        }
        rt_renderer_destroy(r);
    }
#ifdef RT_HAVE_EMBREE
    if (embree && scene->mesh_count == 1 && scene->object_count == 1) {
        const rt_mesh_data *md = &scene->meshes[0];
        /* Embree loads 16 bytes at a vertex: a copy with one float more. */
        float *pos = malloc(((size_t)md->vertex_count * 3 + 1) * sizeof *pos);
        for (int compact = 0; pos && compact < 2; compact++) {
            memcpy(pos, md->positions, (size_t)md->vertex_count * 3 * sizeof *pos);
            pos[(size_t)md->vertex_count * 3] = 0.0f;
            uint64_t held, peak_bytes;
            uint64_t rss0 = proc_bytes("VmRSS");
            if (rt_embree_memory(pos, md->vertex_count, md->indices, md->triangle_count, threads, 1,
                                 compact, &held, &peak_bytes, &err) != RT_OK) {
                fprintf(stderr, "%s\n", err.message);
                break;
            }
            (void)rss0;
            rt_memory_stats m;
            memset(&m, 0, sizeof m);
            m.scene = (uint64_t)md->vertex_count * 12 + (uint64_t)md->triangle_count * 12;
            m.backend = held;
            print_row(json, compact ? "embree-c" : "embree", "bvh", t.triangles, &m, 0, peak_bytes);
        }
        free(pos);
    }
#else
    (void)embree;
#endif
    rt_scene_destroy(scene);
    return 0;
}
