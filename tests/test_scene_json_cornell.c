/* SPDX-License-Identifier: Apache-2.0 */
/* test_scene_json_cornell.c - a real OBJ scene (with its .mtl) referenced from
 * a JSON scene by a relative path: the same geometry and default view as the
 * bare OBJ. Skips when the shared scenes are absent. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "scene/scene.h"

static rt_scene *load_text(const char *name, const char *json) {
    const char *path = test_write_temp(name, json);
    rt_scene *scene = NULL;
    rt_error err;
    rt_status st = rt_scene_load(path, &scene, &err);
    CHECK_MSG(st == RT_OK, "%s: %s", name, err.message);
    return scene;
}

/* "dir/../../x" from folder of from_file to the absolute path to. */
static void relative_path(const char *from_file, const char *to, char *out, size_t cap) {
    char from[PATH_MAX];
    if (!realpath(from_file, from)) {
        snprintf(out, cap, "%s", to);
        return;
    }
    size_t n = 0;
    out[0] = '\0';
    for (const char *p = strrchr(from, '/'); p && p > from; p--)
        if (*p == '/') n += (size_t)snprintf(out + n, cap - n, "../");
    snprintf(out + n, cap - n, "%s", to[0] == '/' ? to + 1 : to);
}

static void test_cornell_box(void) {
    const char *found = test_shared_scene("cornell_box/CornellBox-Original.obj");
    if (!found) test_skip("the shared scene cornell_box/CornellBox-Original.obj is not present");
    char obj[PATH_MAX], rel[PATH_MAX + 64], json[2 * PATH_MAX];
    if (!realpath(found, obj)) return;
    const char *probe = test_write_temp("cornell.json", "{}");
    relative_path(probe, obj, rel, sizeof rel);
    CHECK(rel[0] == '.');
    snprintf(json, sizeof json,
             "{\"meshes\": {\"box\": {\"file\": \"%s\"}},\n"
             " \"objects\": [{\"mesh\": \"box\"}]}",
             rel);
    rt_scene *s = load_text("cornell.json", json);
    if (!s) return;
    rt_scene *bare = NULL;
    rt_error err;
    CHECK_MSG(rt_scene_load(obj, &bare, &err) == RT_OK, "%s", err.message);
    if (bare) {
        CHECK(rt_scene_triangle_count(s) > 0);
        CHECK_EQ_INT(rt_scene_triangle_count(s), rt_scene_triangle_count(bare));
        /* The same default view as the bare OBJ. */
        CHECK(memcmp(&s->camera, &bare->camera, sizeof s->camera) == 0);
        rt_scene_features f = rt_scene_features_of(s);
        CHECK(f.tri_materials); /* its .mtl materials come along */
        rt_scene_destroy(bare);
    }
    rt_scene_destroy(s);
}

int main(void) {
    test_cornell_box();
    return TEST_END();
}
