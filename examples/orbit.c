/* SPDX-License-Identifier: Apache-2.0 */
/* orbit.c - a small program on rtcl's C API (rt.h), built against the
 * installed package (examples/CMakeLists.txt, or pkg-config rtcl).
 *
 * It builds a scene by hand, as the thesis's library does: meshes, a
 * material and a light, a floor and an object with two keyframes (a low and a
 * tall pyramid), then renders three frames with a renderer it owns. Between
 * frames it queues rigid transforms for the object (the transform queue,
 * applied at the next frame), switches its keyframe and moves the camera. Each
 * frame is written as a PPM image; a ray query checks the geometry.
 *
 * usage: orbit [OUT_DIR [BACKEND]]   (BACKEND: cpu, packet, opencl, auto) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <rtcl/rt.h>

/* Stops with the message when a call fails. */
static void check(rt_status status, const char *what, const char *message) {
    if (status == RT_OK) return;
    fprintf(stderr, "orbit: %s: %s (%s)\n", what, message, rt_status_string(status));
    exit(1);
}

/* A square pyramid of the given height on the unit square around the origin. */
static uint32_t add_pyramid(rt_scene *scene, float height) {
    const float p[] = {-0.5f, 0,     -0.5f, 0.5f, 0, -0.5f,  0.5f, 0,
                       0.5f,  -0.5f, 0,     0.5f, 0, height, 0};
    const uint32_t tri[] = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4, 0, 2, 1, 0, 3, 2};
    uint32_t mesh;
    check(rt_mesh_create(scene, &mesh), "mesh", rt_scene_error(scene));
    check(rt_mesh_add_triangles(scene, mesh, p, NULL, 5, tri, 6), "pyramid", rt_scene_error(scene));
    return mesh;
}

/* Row-major 4x4: a turn of 'degrees' about the y axis, then a move by (x, 0, z). */
static void turn_and_move(float degrees, float x, float z, float m[16]) {
    float c = cosf(degrees * 3.14159265f / 180.0f), s = sinf(degrees * 3.14159265f / 180.0f);
    const float r[16] = {c, 0, s, x, 0, 1, 0, 0, -s, 0, c, z, 0, 0, 0, 1};
    memcpy(m, r, sizeof r);
}

/* Writes the framebuffer's colours as an 8-bit binary PPM. */
static int write_ppm(const char *path, const rt_framebuffer *fb) {
    FILE *f = fopen(path, "wb");
    if (!f) return 0;
    fprintf(f, "P6\n%d %d\n255\n", fb->width, fb->height);
    for (size_t i = 0; i < (size_t)fb->width * fb->height * 3; i++) {
        float v = fb->pixels[i];
        fputc(v > 0.0f ? (v < 1.0f ? (int)(v * 255.0f + 0.5f) : 255) : 0, f);
    }
    return fclose(f) == 0;
}

int main(int argc, char **argv) {
    const char *out_dir = argc > 1 ? argv[1] : ".";
    const char *backend = argc > 2 ? argv[2] : "cpu";

    rt_scene *scene;
    check(rt_scene_create(&scene), "scene", "out of memory");

    /* The floor: one quad of two triangles. */
    const float floor_p[] = {-4, 0, -4, 4, 0, -4, 4, 0, 4, -4, 0, 4};
    const uint32_t floor_t[] = {0, 2, 1, 0, 3, 2};
    uint32_t floor_mesh;
    check(rt_mesh_create(scene, &floor_mesh), "mesh", rt_scene_error(scene));
    check(rt_mesh_add_triangles(scene, floor_mesh, floor_p, NULL, 4, floor_t, 2), "floor",
          rt_scene_error(scene));

    /* The object's keyframes: a low pyramid, then a tall one. */
    uint32_t low = add_pyramid(scene, 0.6f), tall = add_pyramid(scene, 1.5f);

    rt_material grey = rt_material_default(), red = rt_material_default();
    grey.ambient = 0.1f;
    red.color[1] = red.color[2] = 0.2f;
    red.ambient = 0.1f;
    red.specular = 0.5f;
    red.shininess = 20;
    uint32_t grey_id, red_id, floor_obj, pyramid;
    check(rt_material_add(scene, &grey, &grey_id), "material", rt_scene_error(scene));
    check(rt_material_add(scene, &red, &red_id), "material", rt_scene_error(scene));
    check(rt_object_create(scene, grey_id, &floor_obj), "object", rt_scene_error(scene));
    check(rt_object_add_mesh(scene, floor_obj, floor_mesh), "object", rt_scene_error(scene));
    check(rt_object_create(scene, red_id, &pyramid), "object", rt_scene_error(scene));
    check(rt_object_add_mesh(scene, pyramid, low), "keyframe", rt_scene_error(scene));
    check(rt_object_add_mesh(scene, pyramid, tall), "keyframe", rt_scene_error(scene));

    const float light_pos[3] = {2, 5, 3}, white[3] = {1, 1, 1}, sky[3] = {0.2f, 0.3f, 0.5f};
    uint32_t light;
    check(rt_light_add(scene, light_pos, white, &light), "light", rt_scene_error(scene));
    check(rt_scene_set_background(scene, sky), "background", rt_scene_error(scene));
    rt_camera cam = {{0, 2, 6}, {0, 0.5f, 0}, {0, 1, 0}, 50.0f, 160, 120};
    check(rt_camera_set(scene, &cam), "camera", rt_scene_error(scene));

    /* The renderer: the caller's, kept across frames (BVHs, threads, device). */
    rt_renderer_options ro = rt_renderer_options_default();
    ro.backend = backend;
    rt_renderer *renderer;
    rt_error err;
    check(rt_renderer_create(&ro, &renderer, &err), "renderer", err.message);

    rt_framebuffer fb = {0};
    for (int frame = 0; frame < 3; frame++) {
        if (frame > 0) {
            /* Queued now, applied by the next rt_render, in this order. */
            float m[16];
            turn_and_move(30.0f, 0.3f, 0.0f, m);
            check(rt_object_transform(scene, pyramid, m), "transform", rt_scene_error(scene));
            check(rt_object_select_mesh(scene, pyramid, (uint32_t)(frame % 2)), "keyframe",
                  rt_scene_error(scene));
            check(rt_camera_move(scene, 0.5f, 0.0f, 0.5f), "camera", rt_scene_error(scene));
            check(rt_camera_rotate(scene, -5.0f, 0.0f), "camera", rt_scene_error(scene));
        }
        check(rt_render(renderer, scene, NULL, &fb), "render", rt_renderer_error(renderer));
        char path[1024];
        snprintf(path, sizeof path, "%s/orbit_%d.ppm", out_dir, frame);
        if (!write_ppm(path, &fb)) {
            fprintf(stderr, "orbit: cannot write %s\n", path);
            return 1;
        }
        printf("frame %d: %dx%d on %s -> %s\n", frame, fb.width, fb.height,
               rt_renderer_backend(renderer), path);
        rt_framebuffer_free(&fb);
    }

    /* A ray straight down onto the floor beside the pyramid hits it at t = 2. */
    rt_ray down = {{-3, 2, -3}, {0, -1, 0}, 0.0f, INFINITY};
    rt_hit hit;
    check(rt_trace_rays(renderer, scene, &down, 1, &hit, NULL), "trace",
          rt_renderer_error(renderer));
    printf("ray: hit %d t %g object %u\n", hit.hit, hit.t, hit.inst);
    int ok = hit.hit && hit.t == 2.0f && hit.inst == floor_obj;

    rt_renderer_destroy(renderer);
    rt_scene_destroy(scene);
    if (!ok) fprintf(stderr, "orbit: the ray should hit the floor at t = 2\n");
    return ok ? 0 : 1;
}
