/* SPDX-License-Identifier: Apache-2.0 */
/* check.c - support for the plain ctest programs. */
#include "check.h"

#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "render/renderer_internal.h"
#include "rt.h"
#include "scene/scene_builtin.h"

int test_failures = 0;
int test_checks = 0;

int test_report(const char *name) {
    printf("%s: %d checks, %d failed\n", name, test_checks, test_failures);
    return test_failures ? 1 : 0;
}

void test_skip(const char *reason) {
    printf("skipped: %s\n", reason);
    fflush(stdout);
    exit(77);
}

const char *test_source_path(const char *rel) {
    static char path[4096];
    const char *root = getenv("RT_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/%s", root ? root : ".", rel);
    return path;
}

const char *test_shared_scene(const char *rel) {
    static char path[4096];
    const char *root = getenv("RT_SHARED_SCENES");
    if (!root) return NULL;
    snprintf(path, sizeof path, "%s/%s", root, rel);
    if (access(path, R_OK) != 0) return NULL;
    return path;
}

const char *test_write_temp(const char *name, const char *text) {
    static char dir[256];
    static char path[4096];
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "/tmp/rt_test_%ld", (long)getpid());
        mkdir(dir, 0700);
    }
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return NULL;
    fputs(text, f);
    fclose(f);
    return path;
}

rt_scene *test_builtin_scene(const char *name, int width, int height) {
    rt_scene *s = NULL;
    rt_error err;
    CHECK_MSG(rt_scene_builtin(name, &s, &err) == RT_OK, "%s", err.message);
    if (!s) return NULL;
    rt_camera cam;
    rt_camera_get(s, &cam);
    cam.width = width;
    cam.height = height;
    CHECK_MSG(rt_camera_set(s, &cam) == RT_OK, "%s", rt_scene_error(s));
    return s;
}

rt_scene *test_mesh_scene(const float *pos, uint32_t verts, const uint32_t *idx, uint32_t tris) {
    rt_scene *s = NULL;
    uint32_t mesh, mat, obj;
    rt_material m = rt_material_default();
    CHECK(rt_scene_create(&s) == RT_OK);
    if (!s) return NULL;
    CHECK(rt_mesh_create(s, &mesh) == RT_OK);
    CHECK(rt_mesh_add_triangles(s, mesh, pos, NULL, verts, idx, tris) == RT_OK);
    CHECK(rt_material_add(s, &m, &mat) == RT_OK);
    CHECK(rt_object_create(s, mat, &obj) == RT_OK);
    CHECK(rt_object_add_mesh(s, obj, mesh) == RT_OK);
    CHECK(rt_scene_commit(s) == RT_OK);
    return s;
}

rt_scene *test_soup_scene(const float *pos, uint32_t tris) {
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * (size_t)tris);
    CHECK(idx != NULL);
    if (!idx) return NULL;
    for (uint32_t i = 0; i < 3 * tris; i++) idx[i] = i;
    rt_scene *s = test_mesh_scene(pos, 3 * tris, idx, tris);
    free(idx);
    return s;
}

rt_scene *test_far_terrain(int cells, float **pos_out) {
    const float base[3] = {1500.0f, 1200.0f, -1300.0f}, cell = 0.25f;
    const uint32_t n = (uint32_t)(cells + 1);
    float *pos = malloc(sizeof(float) * 3 * n * n);
    uint32_t *idx = malloc(sizeof(uint32_t) * 6 * (size_t)cells * (size_t)cells);
    *pos_out = NULL;
    CHECK(pos && idx);
    if (!pos || !idx) {
        free(pos), free(idx);
        return NULL;
    }
    uint32_t seed = 4242u;
    for (uint32_t j = 0; j < n; j++)
        for (uint32_t i = 0; i < n; i++) {
            float *p = pos + 3 * (j * n + i);
            seed = seed * 1664525u + 1013904223u;
            p[0] = base[0] + cell * (float)i;
            p[1] = base[1] + 0.1f * cell * ((float)(seed >> 8) / 16777216.0f - 0.5f);
            p[2] = base[2] + cell * (float)j;
        }
    for (uint32_t j = 0, t = 0; j < (uint32_t)cells; j++)
        for (uint32_t i = 0; i < (uint32_t)cells; i++, t += 6) {
            uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
            const uint32_t q[6] = {a, b, d, a, d, c};
            memcpy(idx + t, q, sizeof q);
        }
    rt_scene *s = test_mesh_scene(pos, n * n, idx, 2 * (uint32_t)cells * (uint32_t)cells);
    free(idx);
    rt_camera cam = {{base[0], base[1] + 5.0f, base[2] - 5.0f},
                     {base[0] + 12.0f, base[1], base[2] + 12.0f},
                     {0, 1, 0},
                     60.0f,
                     64,
                     64};
    if (s) CHECK(rt_camera_set(s, &cam) == RT_OK);
    if (!s) {
        free(pos);
        return NULL;
    }
    *pos_out = pos;
    return s;
}

const char *test_shared_anim(const char *prefix, const char *k0_update, const char *file) {
    char rel[256];
    snprintf(rel, sizeof rel, "%s_00.obj", prefix);
    const char *first = test_shared_scene(rel);
    if (!first) return NULL;
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", first);
    *strrchr(dir, '/') = '\0';
    const char *base = strrchr(prefix, '/') + 1;
    char update[64] = "";
    if (k0_update) snprintf(update, sizeof update, ", \"update\": \"%s\"", k0_update);
    char json[16384];
    size_t n = (size_t)snprintf(json, sizeof json, "{\"meshes\": {");
    for (int i = 0; i < 10; i++)
        n += (size_t)snprintf(json + n, sizeof json - n,
                              "%s\"k%d\": {\"file\": \"%s/%s_%02d.obj\"%s}", i ? ", " : "", i, dir,
                              base, i, i ? "" : update);
    snprintf(json + n, sizeof json - n,
             "}, \"objects\": [{\"keyframes\": [\"k0\", \"k1\", \"k2\", \"k3\", "
             "\"k4\", \"k5\", \"k6\", \"k7\", \"k8\", \"k9\"], \"animation\": "
             "{\"keyframe_rate\": 5, \"interpolate\": true}}, {\"mesh\": \"k0\", "
             "\"transform\": {\"translate\": [1.5, 0, 0]}}]}\n");
    return test_write_temp(file, json);
}

int test_same_fb(const rt_framebuffer *a, const rt_framebuffer *b) {
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           memcmp(a->pixels, b->pixels,
                  sizeof(float) * (size_t)a->width * a->height * a->channels) == 0;
}

enum { TEST_RENDERERS = 32 };
static struct {
    char backend[64];
    int threads;
    rt_renderer *r;
} test_renderers[TEST_RENDERERS];
static int test_renderer_count;

static void destroy_renderers(void) {
    for (int i = 0; i < test_renderer_count; i++) rt_renderer_destroy(test_renderers[i].r);
    test_renderer_count = 0;
}

static rt_renderer *keep(const char *backend, int threads, rt_renderer *r) {
    if (test_renderer_count == 0) atexit(destroy_renderers);
    if (test_renderer_count == TEST_RENDERERS) {
        fprintf(stderr, "check.c: more than %d renderers\n", TEST_RENDERERS);
        exit(1);
    }
    snprintf(test_renderers[test_renderer_count].backend, sizeof test_renderers[0].backend, "%s",
             backend ? backend : "");
    test_renderers[test_renderer_count].threads = threads;
    test_renderers[test_renderer_count++].r = r;
    return r;
}

rt_renderer *test_renderer(const char *backend, int threads) {
    for (int i = 0; i < test_renderer_count; i++)
        if (test_renderers[i].threads == threads && strcmp(test_renderers[i].backend, backend) == 0)
            return test_renderers[i].r;
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = backend;
    o.threads = threads;
    rt_renderer *r = NULL;
    rt_error err;
    if (rt_renderer_create(&o, &r, &err) != RT_OK) {
        CHECK_MSG(0, "renderer '%s': %s", backend, err.message);
        return NULL;
    }
    return keep(backend, threads, r);
}

rt_renderer *test_renderer_with(const rt_renderer_options *options, rt_error *err) {
    rt_renderer *r = NULL;
    if (rt_renderer_create(options, &r, err) != RT_OK) return NULL;
    return keep("", -1, r); /* never found by test_renderer */
}

const struct rt_flat *test_layout(rt_scene *s, int threads) {
    rt_renderer *r = test_renderer("cpu", threads);
    if (!r) return NULL;
    rt_backend_layout layout;
    double build_ms, sah;
    rt_status st = rt_renderer_layout(r, s, &layout, &build_ms, &sah);
    CHECK_MSG(st == RT_OK, "layout: %s", rt_renderer_error(r));
    return st == RT_OK ? layout.flat : NULL;
}
