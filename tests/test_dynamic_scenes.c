/* SPDX-License-Identifier: Apache-2.0 */
/* test_dynamic_scenes.c - animated scenes frame by frame: on every backend
 * (cpu, packet, and opencl or, with the argument vulkan, Vulkan where a device exists), with every
 * update policy (refit, fast, auto) kept on one renderer across the frames, each frame's image is
 * bit for bit the image of a fresh SAH build of the same frame on the cpu oracle. Scenes:
 * scenes/keyframes_animated.json (blended and switched keyframes, keyed transforms, a camera path)
 * and, when the shared scenes are present, the brainstem and robot-walk animations morphing between
 * their ten keyframes. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt.h"
#include "scene/scene.h"

enum { FRAMES = 5, W = 96, H = 54 };

static rt_renderer *make(const char *backend, rt_error *err) {
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = backend;
    o.threads = 2;
    rt_renderer *r = NULL;
    if (rt_renderer_create(&o, &r, err) != RT_OK) return NULL;
    return r;
}

static void set_policy(rt_scene *s, rt_update_policy p) {
    for (uint32_t m = 0; m < s->mesh_count; m++) rt_mesh_set_update(s, m, p);
}

static rt_scene *load(const char *path) {
    rt_scene *s = NULL;
    rt_error err;
    CHECK_MSG(rt_scene_load(path, &s, &err) == RT_OK, "%s: %s", path, err.message);
    if (!s) return NULL;
    rt_camera cam;
    rt_camera_get(s, &cam);
    cam.width = W;
    cam.height = H;
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    return s;
}

static int only_vulkan, device_frames;

static void check_scene(const char *name, const char *path, double fps) {
    rt_scene *s = load(path);
    if (!s) return;
    /* The references: each frame from scratch (a fresh renderer, SAH builds),
     * on the oracle. */
    rt_framebuffer ref[FRAMES];
    memset(ref, 0, sizeof ref);
    set_policy(s, RT_UPDATE_SAH);
    for (int k = 0; k < FRAMES; k++) {
        rt_error err;
        rt_renderer *r = make("cpu", &err);
        CHECK(r != NULL);
        if (!r) continue;
        CHECK(rt_scene_set_time(s, k / fps) == RT_OK);
        CHECK_MSG(rt_render(r, s, NULL, &ref[k]) == RT_OK, "%s: %s", name, rt_renderer_error(r));
        rt_renderer_destroy(r);
    }
    /* Two frames apart must differ, or the test would prove nothing. */
    CHECK_MSG(ref[0].pixels && ref[2].pixels && !test_same_fb(&ref[0], &ref[2]),
              "%s: the animation does not move", name);
    /* Device backends (b >= 2) may be missing here: said, not hidden. */
    const char *backends[] = {"cpu", "packet", "opencl", "vulkan"};
    const int first = only_vulkan ? 3 : 0, last = only_vulkan ? 4 : 3;
    const rt_update_policy policies[] = {RT_UPDATE_REFIT, RT_UPDATE_LBVH, RT_UPDATE_AUTO};
    for (int b = first; b < last; b++) {
        rt_error err;
        rt_renderer *r = make(backends[b], &err);
        if (!r) {
            CHECK_MSG(b >= 2, "%s: %s", backends[b], err.message);
            printf("%s: %s not tested: %s\n", name, backends[b], err.message);
            continue;
        }
        uint64_t full_upload = 0;
        int in_place = 0, tested = 1;
        for (int p = 0; p < 3; p++) {
            set_policy(s, policies[p]);
            for (int k = 0; k < FRAMES; k++) {
                CHECK(rt_scene_set_time(s, k / fps) == RT_OK);
                rt_framebuffer fb;
                memset(&fb, 0, sizeof fb);
                rt_render_stats st;
                rt_render_options o = rt_render_options_default();
                o.stats = &st;
                rt_status status = rt_render(r, s, &o, &fb);
                if (status != RT_OK && b >= 2 && k == 0 && p == 0) {
                    /* No device here: said, not hidden. */
                    printf("%s: %s not tested: %s\n", name, backends[b], rt_renderer_error(r));
                    tested = 0;
                    p = 3;
                    break;
                }
                CHECK_MSG(status == RT_OK, "%s on %s: %s", name, backends[b], rt_renderer_error(r));
                device_frames += b >= 2 && status == RT_OK;
                /* Lavapipe promises no denormal mode, but these scenes have
                 * no denormal: Vulkan is held to the bits regardless, as in
                 * test_vulkan_oracle. */
                if (b == 2 && status == RT_OK && !st.exact) {
                    printf("%s: opencl device '%s' does not promise exact results: not compared\n",
                           name, st.device);
                    rt_framebuffer_free(&fb);
                    tested = 0;
                    p = 3;
                    break;
                }
                if (status == RT_OK && k > 0 && policies[p] == RT_UPDATE_REFIT) {
                    /* Refit frames rewrite the layout in place where the
                     * same meshes stay shown; a device then receives the
                     * changed ranges only. */
                    rt_update_stats us;
                    rt_renderer_update_stats(r, &us);
                    if (us.layout_in_place && b >= 2)
                        CHECK_MSG(st.upload_bytes > 0 && st.upload_bytes <= us.layout_bytes,
                                  "%s: frame %d uploaded %llu bytes, %llu changed", name, k,
                                  (unsigned long long)st.upload_bytes,
                                  (unsigned long long)us.layout_bytes);
                    if (us.layout_in_place && b >= 2 && strcmp(name, "keyframes_animated"))
                        CHECK_MSG(st.upload_bytes < full_upload * 3 / 4,
                                  "%s: frame %d uploaded %llu bytes of %llu", name, k,
                                  (unsigned long long)st.upload_bytes,
                                  (unsigned long long)full_upload);
                    in_place += us.layout_in_place;
                }
                if (k == 0 && p == 0) full_upload = st.upload_bytes;
                CHECK_MSG(status != RT_OK || test_same_fb(&fb, &ref[k]),
                          "%s on %s, policy %s, frame %d: differs from a fresh build", name,
                          backends[b], rt_update_policy_name(policies[p]), k);
                rt_framebuffer_free(&fb);
            }
        }
        if (tested && strcmp(name, "keyframes_animated"))
            CHECK_MSG(in_place >= FRAMES - 2,
                      "%s on %s: %d refit frames rewrote the layout in place", name, backends[b],
                      in_place);
        rt_renderer_destroy(r);
    }
    for (int k = 0; k < FRAMES; k++) rt_framebuffer_free(&ref[k]);
    rt_scene_destroy(s);
}

/* A scene of the ten keyframes of a shared animation, blended. */
static const char *shared_anim(const char *name, const char *prefix) {
    char file[64];
    snprintf(file, sizeof file, "%s.json", name);
    return test_shared_anim(prefix, NULL, file);
}

int main(int argc, char **argv) {
    /* "vulkan": the Vulkan backend alone (ctest's test_dynamic_scenes_vulkan,
     * which the sanitizer build runs without the leak check: the Vulkan
     * loader's unloaded driver leaves allocations no suppression can name,
     * tests/CMakeLists.txt). Otherwise cpu, packet and opencl. */
    only_vulkan = argc > 1 && !strcmp(argv[1], "vulkan");
    check_scene("keyframes_animated", test_source_path("scenes/keyframes_animated.json"), 3.0);
    int shared = 0;
    const char *robot = shared_anim("robot", "robot_walk_anim/robot_walk");
    if (robot) {
        char path[4096];
        snprintf(path, sizeof path, "%s", robot);
        check_scene("robot_walk", path, 3.0);
        shared++;
    }
    const char *brain = shared_anim("brainstem", "brainstem_anim/brainstem");
    if (brain) {
        char path[4096];
        snprintf(path, sizeof path, "%s", brain);
        check_scene("brainstem", path, 3.0);
        shared++;
    }
    if (!shared) printf("the shared animations are not here: tested the shipped scene only\n");
    if (only_vulkan && !device_frames) test_skip("no Vulkan device rendered a frame (said above)");
    return TEST_END();
}
