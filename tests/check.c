/* check.c - support for the plain ctest programs. */
#include "check.h"

#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

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
