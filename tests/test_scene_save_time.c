/* SPDX-License-Identifier: Apache-2.0 */
/* test_scene_save_time.c - rt_scene_save_json keeps time: a scene loaded,
 * saved (at some time other than 0) and loaded again renders at every time
 * exactly as the original does, bit for bit. The saved file carries the
 * objects' "animation" and "transform_keys", the camera's "path", the
 * meshes' "update" and "accel"; the blend meshes of morphing objects are
 * left out (the loader makes them again). Scenes: scenes/keyframes_animated.json
 * (blended and switched keyframes, keyed transforms, a camera path), a scene
 * with a kd-tree floor, update policies, a still keyframe object, a
 * negative zero and a rotation-and-scale key, and, when the shared scenes
 * are present, the robot-walk and brainstem animations morphing. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "formats/scene_save.h"
#include "rt.h"
#include "scene/scene.h"

enum { W = 64, H = 36 };

static const double times[] = {0.0, 0.3, 0.75, 1.3, 2.1, 3.4};
enum { TIMES = sizeof times / sizeof times[0] };

static rt_scene *load(const char *path) {
    rt_scene *s = NULL;
    rt_error err;
    CHECK_MSG(rt_scene_load(path, &s, &err) == RT_OK, "%s: %s", path, err.message);
    return s;
}

static rt_renderer *make(void) {
    rt_renderer_options o = rt_renderer_options_default();
    o.threads = 2;
    rt_renderer *r = NULL;
    rt_error err;
    CHECK_MSG(rt_renderer_create(&o, &r, &err) == RT_OK, "%s", err.message);
    return r;
}

/* The scene's frame at time t, at W x H. */
static rt_framebuffer frame(rt_renderer *r, rt_scene *s, double t) {
    rt_framebuffer fb;
    memset(&fb, 0, sizeof fb);
    CHECK(rt_scene_set_time(s, t) == RT_OK);
    rt_camera cam;
    rt_camera_get(s, &cam);
    cam.width = W;
    cam.height = H;
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    CHECK_MSG(rt_render(r, s, NULL, &fb) == RT_OK, "%s", rt_renderer_error(r));
    return fb;
}

/* The folder test_write_temp writes into. */
static const char *temp_dir(void) {
    static char dir[4096];
    snprintf(dir, sizeof dir, "%s", test_write_temp("probe.txt", "x\n"));
    *strrchr(dir, '/') = '\0';
    return dir;
}

static void check_round_trip(const char *name, const char *path) {
    rt_scene *a = load(path);
    if (!a) return;
    CHECK_MSG(rt_scene_is_animated(a), "%s: not animated", name);
    /* Saved at a time other than 0: the file must not depend on it. */
    CHECK(rt_scene_set_time(a, 1.1) == RT_OK);
    rt_error err;
    CHECK_MSG(rt_scene_save_json(a, temp_dir(), name, &err) == RT_OK, "%s: %s", name, err.message);
    char saved[4200];
    snprintf(saved, sizeof saved, "%s/%s.json", temp_dir(), name);
    rt_scene *b = load(saved);
    if (!b) {
        rt_scene_destroy(a);
        return;
    }
    CHECK_MSG(rt_scene_is_animated(b), "%s: the saved scene is not animated", name);
    CHECK_EQ_INT(a->mesh_count, b->mesh_count);
    CHECK_EQ_INT(a->object_count, b->object_count);
    CHECK_EQ_INT(a->camera_path_count, b->camera_path_count);
    for (uint32_t m = 0; m < a->mesh_count && m < b->mesh_count; m++) {
        CHECK_MSG(a->meshes[m].update_policy == b->meshes[m].update_policy,
                  "%s: mesh %u: update policy %u, saved %u", name, m, a->meshes[m].update_policy,
                  b->meshes[m].update_policy);
        CHECK_MSG(a->meshes[m].accel == b->meshes[m].accel, "%s: mesh %u: accel %u, saved %u", name,
                  m, a->meshes[m].accel, b->meshes[m].accel);
    }
    rt_renderer *ra = make(), *rb = make();
    for (int i = 0; i < TIMES && ra && rb; i++) {
        rt_framebuffer fa = frame(ra, a, times[i]), fbb = frame(rb, b, times[i]);
        CHECK_MSG(fa.pixels && fbb.pixels &&
                      memcmp(fa.pixels, fbb.pixels, sizeof(float) * 3 * W * H) == 0,
                  "%s: time %g: the saved scene renders differently", name, times[i]);
        rt_framebuffer_free(&fa);
        rt_framebuffer_free(&fbb);
    }
    rt_renderer_destroy(ra);
    rt_renderer_destroy(rb);
    rt_scene_destroy(a);
    rt_scene_destroy(b);
}

/* A scene of the ten keyframes of a shared animation, blended. */
static const char *shared_anim(const char *name, const char *prefix) {
    char file[64];
    snprintf(file, sizeof file, "%s_src.json", name);
    return test_shared_anim(prefix, "refit", file);
}

int main(void) {
    check_round_trip("keyframes_animated", test_source_path("scenes/keyframes_animated.json"));

    /* Keyed transforms with rotation and scale, a camera path, update
     * policies, a kd floor, a still keyframe object and a negative zero. */
    char dir[1024];
    snprintf(dir, sizeof dir, "%s", test_source_path("scenes"));
    char json[16384];
    snprintf(
        json, sizeof json,
        "{\"camera\": {\"path\": [{\"time\": 0, \"position\": [0, 2, 6], \"look_at\": [0, 1, 0]},\n"
        "  {\"time\": 0.7, \"position\": [2, 2.5, 5], \"look_at\": [0.1, 1, -0.0]},\n"
        "  {\"time\": 2.5, \"position\": [-3, 1.5, 4], \"look_at\": [0, 0.5, 0]}],\n"
        "  \"fov\": 55, \"up\": [0, 1, 0.1]},\n"
        " \"lights\": [{\"position\": [2, 4, 3]}],\n"
        " \"materials\": {\"shiny\": {\"color\": [0.9, 0.5, 0.2], \"reflectivity\": 0.3}},\n"
        " \"meshes\": {\"floor\": {\"file\": \"%s/keyframes_floor.obj\", \"accel\": \"kd\"},\n"
        "  \"c0\": {\"file\": \"%s/keyframes_column_0.obj\", \"update\": \"fast\"},\n"
        "  \"c1\": {\"file\": \"%s/keyframes_column_1.obj\", \"update\": \"auto\"},\n"
        "  \"c2\": {\"file\": \"%s/keyframes_column_2.obj\"}},\n"
        " \"objects\": [{\"mesh\": \"floor\"},\n"
        "  {\"keyframes\": [\"c0\", \"c1\", \"c2\"], \"material\": \"shiny\",\n"
        "   \"animation\": {\"keyframe_rate\": 3, \"interpolate\": true},\n"
        "   \"transform_keys\": [{\"time\": 0.2, \"translate\": [-1, 0, -0.0], \"scale\": 0.9},\n"
        "     {\"time\": 1, \"translate\": [-1, 0.5, 0], \"rotate\": {\"axis\": [1, 2, 0.5], "
        "\"degrees\": 120}, \"scale\": 1.1},\n"
        "     {\"time\": 2.5, \"translate\": [0, 0, 1], \"rotate\": {\"axis\": [0, 1, 0], "
        "\"degrees\": -300}}]},\n"
        "  {\"keyframes\": [\"c0\", \"c2\"], \"frame\": 1,\n"
        "   \"transform\": {\"translate\": [1.2, 0, 0.3]}},\n"
        "  {\"keyframes\": [\"c1\", \"c2\"], \"animation\": {\"keyframe_rate\": 1.5},\n"
        "   \"transform_keys\": [{\"time\": 0, \"translate\": [0.5, 0, -1]}]}]}\n",
        dir, dir, dir, dir);
    const char *keyed = test_write_temp("keyed_src.json", json);
    char path[4096];
    snprintf(path, sizeof path, "%s", keyed);
    check_round_trip("keyed", path);

    int shared = 0;
    const char *names[2][2] = {{"robot_walk", "robot_walk_anim/robot_walk"},
                               {"brainstem", "brainstem_anim/brainstem"}};
    for (int i = 0; i < 2; i++) {
        const char *p = shared_anim(names[i][0], names[i][1]);
        if (!p) continue;
        snprintf(path, sizeof path, "%s", p);
        check_round_trip(names[i][0], path);
        shared++;
    }
    if (!shared) printf("the shared animations are not here: tested the shipped scenes only\n");
    return TEST_END();
}
