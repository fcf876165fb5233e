/* SPDX-License-Identifier: Apache-2.0 */
/* fuzz_util.c - see fuzz_util.h. */
#include "fuzz_util.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[64];
static char paths[4][128];

static void remove_dir(void) {
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *e;
        char p[512];
        while ((e = readdir(d)) != NULL) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
            snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
            unlink(p);
        }
        closedir(d);
    }
    rmdir(dir);
}

const char *fuzz_dir(void) {
    if (!dir[0]) {
        const char *tmp = getenv("TMPDIR");
        snprintf(dir, sizeof dir, "%s/rtcl-fuzz-XXXXXX",
                 tmp && *tmp && strlen(tmp) < 40 ? tmp : "/tmp");
        if (!mkdtemp(dir)) {
            perror("fuzz: mkdtemp");
            abort();
        }
        atexit(remove_dir);
    }
    return dir;
}

const char *fuzz_path(int slot, const char *name) {
    snprintf(paths[slot], sizeof paths[slot], "%s/%s", fuzz_dir(), name);
    return paths[slot];
}

void fuzz_write(const char *path, const void *data, size_t size) {
    FILE *f = fopen(path, "wb");
    if (!f || (size && fwrite(data, 1, size, f) != size) || fclose(f) != 0) {
        perror(path);
        abort();
    }
}

rt_status fuzz_render_small(rt_scene *scene, int side) {
    static rt_renderer *renderer;
    if (!renderer) {
        rt_renderer_options o = rt_renderer_options_default();
        o.threads = 1;
        rt_error err;
        if (rt_renderer_create(&o, &renderer, &err) != RT_OK) {
            fprintf(stderr, "fuzz: %s\n", err.message);
            abort();
        }
    }
    rt_camera cam;
    if (rt_camera_get(scene, &cam) != RT_OK) return RT_ERROR_INVALID_ARGUMENT;
    if (cam.width > side) cam.width = side;
    if (cam.height > side) cam.height = side;
    rt_status st = rt_camera_set(scene, &cam);
    if (st != RT_OK) return st;
    rt_framebuffer fb;
    memset(&fb, 0, sizeof fb);
    st = rt_render(renderer, scene, NULL, &fb);
    rt_framebuffer_free(&fb);
    return st;
}

void fuzz_check(int cond, const char *what) {
    if (cond) return;
    fprintf(stderr, "fuzz finding: %s\n", what);
    abort();
}
