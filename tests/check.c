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
