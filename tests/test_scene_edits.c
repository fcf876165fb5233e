/* SPDX-License-Identifier: Apache-2.0 */
/* test_scene_edits.c - lights moved and removed, objects removed and replaced
 * (rt_light_set, rt_light_remove, rt_object_remove), on one renderer kept
 * across the edits: after each edit the image (and the object-id AOV) is bit
 * for bit the image of a scene built from scratch without the removed parts,
 * rendered by a fresh renderer on the cpu oracle. On cpu, packet and opencl
 * or, with the argument vulkan, on Vulkan (a missing device is said, not
 * hidden). Also: the errors of bad ids, the loader's option for no default
 * light (rt_scene_load_with), and a removed morphing object's blend mesh
 * (emptied, and not saved by rt_scene_save_json). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt.h"

enum { W = 64, H = 48 };

/* What a scene is built with: which object and light are left out, and the
 * edits a test made to the edited scene, made here from the start. */
typedef struct recipe {
    int skip_object[5]; /* 1: object i is not created */
    int skip_light[3];  /* 1: light i is not created */
    int light1_moved;   /* light 1 at its second place and colour */
    int replaced;       /* object 4 replaced by another instance of the box, created last */
} recipe;

static const float light_pos[3][3] = {{2, 4, 3}, {-3, 3, 1}, {0, 5, -2}};
static const float light_col[3][3] = {{0.8f, 0.8f, 0.8f}, {0.3f, 0.4f, 0.9f}, {0.5f, 0.2f, 0.2f}};
static const float moved_pos[3] = {-1, 2, 4}, moved_col[3] = {0.9f, 0.6f, 0.1f};

static void translate(float m[16], float x, float y, float z, float scale) {
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = scale;
    m[15] = 1;
    m[3] = x, m[7] = y, m[11] = z;
}

/* A floor, a box shown by three objects (one of them glass), a mirror
 * pyramid; three lights. Meshes are always all created (objects are
 * removed, meshes are not), so mesh ids agree with the edited scene. */
static rt_scene *build(const recipe *rc) {
    rt_scene *s = NULL;
    CHECK(rt_scene_create(&s) == RT_OK);
    if (!s) return NULL;
    rt_material red = rt_material_default(), mirror = rt_material_default(),
                glass = rt_material_default(), grey = rt_material_default();
    red.color[1] = red.color[2] = 0.2f;
    red.specular = 0.5f, red.shininess = 20;
    mirror.reflectivity = 0.6f;
    glass.transparency = 0.7f, glass.ior = 1.5f;
    grey.color[0] = grey.color[1] = grey.color[2] = 0.6f;
    uint32_t mats[4];
    CHECK(rt_material_add(s, &grey, &mats[0]) == RT_OK);
    CHECK(rt_material_add(s, &red, &mats[1]) == RT_OK);
    CHECK(rt_material_add(s, &mirror, &mats[2]) == RT_OK);
    CHECK(rt_material_add(s, &glass, &mats[3]) == RT_OK);

    uint32_t floor_mesh, box_mesh, pyr_mesh;
    const float floor_pos[] = {-6, 0, -6, 6, 0, -6, 6, 0, 6, -6, 0, 6};
    const uint32_t floor_idx[] = {0, 2, 1, 0, 3, 2};
    CHECK(rt_mesh_create(s, &floor_mesh) == RT_OK);
    CHECK(rt_mesh_add_triangles(s, floor_mesh, floor_pos, NULL, 4, floor_idx, 2) == RT_OK);
    const float box_pos[] = {-0.5f, 0, -0.5f, 0.5f, 0, -0.5f, 0.5f, 1, -0.5f, -0.5f, 1, -0.5f,
                             -0.5f, 0, 0.5f,  0.5f, 0, 0.5f,  0.5f, 1, 0.5f,  -0.5f, 1, 0.5f};
    const uint32_t box_idx[] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                3, 6, 2, 3, 7, 6, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
    CHECK(rt_mesh_create(s, &box_mesh) == RT_OK);
    CHECK(rt_mesh_add_triangles(s, box_mesh, box_pos, NULL, 8, box_idx, 12) == RT_OK);
    const float pyr_pos[] = {-0.7f, 0, -0.7f, 0.7f, 0, -0.7f, 0, 0, 0.8f, 0, 1.4f, 0};
    const uint32_t pyr_idx[] = {0, 1, 2, 0, 3, 1, 1, 3, 2, 2, 3, 0};
    CHECK(rt_mesh_create(s, &pyr_mesh) == RT_OK);
    CHECK(rt_mesh_add_triangles(s, pyr_mesh, pyr_pos, NULL, 4, pyr_idx, 4) == RT_OK);

    /* Objects 0..4: floor, red box, red box (scaled), mirror pyramid, glass box. */
    const uint32_t mesh_of[5] = {floor_mesh, box_mesh, box_mesh, pyr_mesh, box_mesh};
    const uint32_t mat_of[5] = {mats[0], mats[1], mats[1], mats[2], mats[3]};
    const float place[5][4] = {{0, 0, 0, 1},
                               {-1.5f, 0, 0, 1},
                               {1.4f, 0, -0.5f, 1.3f},
                               {0, 0, 0.2f, 1},
                               {0.3f, 0, 1.6f, 0.8f}};
    for (int i = 0; i < 5; i++) {
        if (rc->skip_object[i] || (i == 4 && rc->replaced)) continue;
        uint32_t o;
        CHECK(rt_object_create(s, mat_of[i], &o) == RT_OK);
        CHECK(rt_object_add_mesh(s, o, mesh_of[i]) == RT_OK);
        float m[16];
        translate(m, place[i][0], place[i][1], place[i][2], place[i][3]);
        if (i) CHECK(rt_object_transform(s, o, m) == RT_OK);
    }
    if (rc->replaced) {
        uint32_t o;
        float m[16];
        translate(m, -0.6f, 0, -1.8f, 0.6f);
        CHECK(rt_object_create(s, mats[0], &o) == RT_OK);
        CHECK(rt_object_add_mesh(s, o, box_mesh) == RT_OK);
        CHECK(rt_object_transform(s, o, m) == RT_OK);
    }
    for (int i = 0; i < 3; i++) {
        if (rc->skip_light[i]) continue;
        uint32_t id;
        const int moved = i == 1 && rc->light1_moved;
        CHECK(rt_light_add(s, moved ? moved_pos : light_pos[i], moved ? moved_col : light_col[i],
                           &id) == RT_OK);
    }
    rt_camera cam = {{0.5f, 3.0f, 6.0f}, {0, 0.5f, 0}, {0, 1, 0}, 55.0f, W, H};
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    CHECK(rt_scene_commit(s) == RT_OK);
    return s;
}

static rt_renderer *make(const char *backend, rt_error *err) {
    rt_renderer_options o = rt_renderer_options_default();
    o.backend = backend;
    o.threads = 2;
    rt_renderer *r = NULL;
    if (rt_renderer_create(&o, &r, err) != RT_OK) return NULL;
    return r;
}

/* The shaded image and the object-id AOV of a fresh scene made by rc, on a
 * fresh cpu renderer. */
static void reference(const recipe *rc, rt_framebuffer out[2]) {
    memset(out, 0, 2 * sizeof *out);
    rt_scene *s = build(rc);
    rt_error err;
    rt_renderer *r = make("cpu", &err);
    CHECK_MSG(r != NULL, "cpu: %s", err.message);
    if (s && r) {
        rt_render_options o = rt_render_options_default();
        CHECK(rt_render(r, s, &o, &out[0]) == RT_OK);
        o.aov = RT_AOV_INSTID;
        CHECK(rt_render(r, s, &o, &out[1]) == RT_OK);
    }
    rt_renderer_destroy(r);
    rt_scene_destroy(s);
}

static int only_vulkan, device_tested;

/* Renders s on r (image and object ids) and compares with rc's reference.
 * Returns 0 when the backend has no device here (said on stdout). */
static int compare(rt_renderer *r, const char *backend, rt_scene *s, const recipe *rc,
                   const char *step, int *layouts_in_place) {
    rt_framebuffer ref[2], fb[2];
    memset(fb, 0, sizeof fb);
    rt_render_stats st;
    rt_render_options o = rt_render_options_default();
    o.stats = &st;
    rt_status status = rt_render(r, s, &o, &fb[0]);
    if (status != RT_OK && strcmp(backend, "cpu") && strcmp(backend, "packet") &&
        !strcmp(step, "first frame")) {
        printf("%s not tested: %s\n", backend, rt_renderer_error(r));
        return 0;
    }
    CHECK_MSG(status == RT_OK, "%s, %s: %s", backend, step, rt_renderer_error(r));
    if (!strcmp(backend, "opencl") && status == RT_OK && !st.exact) {
        printf("opencl device '%s' does not promise exact results: not compared\n", st.device);
        rt_framebuffer_free(&fb[0]);
        return 0;
    }
    rt_update_stats us;
    CHECK(rt_renderer_update_stats(r, &us) == RT_OK);
    *layouts_in_place += us.layout_in_place;
    o.aov = RT_AOV_INSTID;
    o.stats = NULL;
    CHECK_MSG(rt_render(r, s, &o, &fb[1]) == RT_OK, "%s, %s: %s", backend, step,
              rt_renderer_error(r));
    reference(rc, ref);
    CHECK_MSG(test_same_fb(&fb[0], &ref[0]), "%s, %s: the image differs from a fresh scene's",
              backend, step);
    CHECK_MSG(test_same_fb(&fb[1], &ref[1]), "%s, %s: the object ids differ from a fresh scene's",
              backend, step);
    device_tested += strcmp(backend, "cpu") && strcmp(backend, "packet");
    for (int i = 0; i < 2; i++) {
        rt_framebuffer_free(&fb[i]);
        rt_framebuffer_free(&ref[i]);
    }
    return 1;
}

/* The edits, one after another on one scene and one renderer. */
static void check_backend(const char *backend) {
    rt_error err;
    rt_renderer *r = make(backend, &err);
    if (!r) {
        CHECK_MSG(strcmp(backend, "cpu") && strcmp(backend, "packet"), "%s: %s", backend,
                  err.message);
        printf("%s not tested: %s\n", backend, err.message);
        return;
    }
    recipe rc;
    memset(&rc, 0, sizeof rc);
    rt_scene *s = build(&rc);
    int in_place = 0;
    if (!s || !compare(r, backend, s, &rc, "first frame", &in_place)) goto done;

    /* A light moved: the same counts, the layout rewritten in place. */
    CHECK(rt_light_set(s, 1, moved_pos, moved_col) == RT_OK);
    rc.light1_moved = 1;
    in_place = 0;
    compare(r, backend, s, &rc, "light 1 moved", &in_place);
    CHECK_MSG(in_place == 1, "%s: moving a light did not rewrite the layout in place", backend);

    /* An instance of a mesh another object still shows. */
    CHECK(rt_object_remove(s, 2) == RT_OK);
    rc.skip_object[2] = 1;
    compare(r, backend, s, &rc, "object 2 removed", &in_place);

    CHECK(rt_light_remove(s, 0) == RT_OK);
    rc.skip_light[0] = 1;
    compare(r, backend, s, &rc, "light 0 removed", &in_place);

    /* The last object (now id 3) replaced by another: the same object count
     * and shown meshes, so the layout is rewritten in place around a new
     * object BVH. */
    CHECK(rt_object_remove(s, 3) == RT_OK);
    {
        uint32_t o;
        float m[16];
        translate(m, -0.6f, 0, -1.8f, 0.6f);
        CHECK(rt_object_create(s, 0, &o) == RT_OK);
        CHECK_EQ_INT(o, 3);
        CHECK(rt_object_add_mesh(s, o, 1) == RT_OK);
        CHECK(rt_object_transform(s, o, m) == RT_OK);
    }
    rc.replaced = 1;
    in_place = 0;
    compare(r, backend, s, &rc, "object 4 replaced", &in_place);
    CHECK_MSG(in_place == 1, "%s: replacing an object did not rewrite the layout in place",
              backend);

    /* The only object showing a mesh (the pyramid), and the first object. */
    CHECK(rt_object_remove(s, 2) == RT_OK);
    rc.skip_object[3] = 1;
    compare(r, backend, s, &rc, "the pyramid removed", &in_place);
    CHECK(rt_object_remove(s, 0) == RT_OK);
    rc.skip_object[0] = 1;
    compare(r, backend, s, &rc, "the floor removed", &in_place);

    /* No light at all: ambient and background only. */
    CHECK(rt_light_remove(s, 1) == RT_OK);
    CHECK(rt_light_remove(s, 0) == RT_OK);
    rc.skip_light[1] = rc.skip_light[2] = 1;
    compare(r, backend, s, &rc, "every light removed", &in_place);
done:
    rt_scene_destroy(s);
    rt_renderer_destroy(r);
}

/* Bad ids and values fail, name the id, and change nothing. */
static void check_errors(void) {
    recipe rc;
    memset(&rc, 0, sizeof rc);
    rt_scene *s = build(&rc);
    if (!s) return;
    rt_scene_info before, after;
    CHECK(rt_scene_describe(s, &before) == RT_OK);
    CHECK(rt_object_remove(s, 5) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "object 5 does not exist (5 objects)");
    CHECK(rt_light_remove(s, 3) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "light 3 does not exist (3 lights)");
    CHECK(rt_light_set(s, 7, moved_pos, moved_col) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "light 7 does not exist");
    const float bad_pos[3] = {0, NAN, 0}, bad_col[3] = {0, 2e6f, 0};
    CHECK(rt_light_set(s, 0, bad_pos, moved_col) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "light: position");
    CHECK(rt_light_set(s, 0, moved_pos, bad_col) == RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(rt_scene_error(s), "2e+06");
    CHECK(rt_light_set(s, 0, NULL, moved_col) == RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_object_remove(NULL, 0) == RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_light_remove(NULL, 0) == RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_scene_describe(s, &after) == RT_OK);
    CHECK(memcmp(&before, &after, sizeof before) == 0);
    rt_scene_destroy(s);
}

/* Whether this build loads JSON scenes (jansson): a build without says
 * RT_ERROR_UNSUPPORTED for any .json file. */
static int json_scenes(void) {
    rt_scene *s = NULL;
    rt_error err;
    rt_status st = rt_scene_load(test_source_path("scenes/keyframes_animated.json"), &s, &err);
    rt_scene_destroy(s);
    return st != RT_ERROR_UNSUPPORTED;
}

/* rt_scene_load_with's no_default_light: a bare OBJ and a JSON scene
 * without a camera get the default camera but no light. */
static void check_no_default_light(void) {
    const char *obj = test_write_temp("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
    rt_scene_load_options lo = rt_scene_load_options_default();
    CHECK_EQ_INT(lo.no_default_light, 0);
    for (int pass = 0; pass < 2; pass++) {
        char path[4096];
        if (pass == 0) {
            snprintf(path, sizeof path, "%s", obj);
        } else {
            /* A JSON scene without a camera, naming the OBJ above. */
            char text[4200];
            snprintf(text, sizeof text,
                     "{\"materials\": {\"w\": {\"color\": [1, 1, 1]}},\n"
                     " \"meshes\": {\"q\": {\"file\": \"%s\"}},\n"
                     " \"objects\": [{\"mesh\": \"q\", \"material\": \"w\"}]}\n",
                     obj);
            const char *json = test_write_temp("nocamera.json", text);
            snprintf(path, sizeof path, "%s", json);
        }
        rt_scene *a = NULL, *b = NULL, *c = NULL;
        rt_error err;
        if (pass == 1 && !json_scenes()) {
            printf("no JSON scenes in this build: the JSON case not tested\n");
            break;
        }
        CHECK_MSG(rt_scene_load(path, &a, &err) == RT_OK, "%s", err.message);
        CHECK_MSG(rt_scene_load_with(path, NULL, &b, &err) == RT_OK, "%s", err.message);
        lo.no_default_light = 1;
        CHECK_MSG(rt_scene_load_with(path, &lo, &c, &err) == RT_OK, "%s", err.message);
        lo.no_default_light = 0;
        rt_scene_info ia, ib, ic;
        if (a && b && c) {
            rt_scene_describe(a, &ia);
            rt_scene_describe(b, &ib);
            rt_scene_describe(c, &ic);
            CHECK_EQ_INT(ia.lights, 1);
            CHECK_EQ_INT(ib.lights, 1);
            CHECK_EQ_INT(ic.lights, 0);
            rt_camera ca, cc;
            rt_camera_get(a, &ca);
            rt_camera_get(c, &cc);
            CHECK(memcmp(&ca, &cc, sizeof ca) == 0);
        }
        rt_scene_destroy(a);
        rt_scene_destroy(b);
        rt_scene_destroy(c);
    }
    /* A bad path still names the file. */
    rt_scene *none = NULL;
    rt_error err;
    lo.no_default_light = 1;
    CHECK(rt_scene_load_with("/nonexistent/x.obj", &lo, &none, &err) != RT_OK);
    CHECK(none == NULL);
    CHECK_CONTAINS(err.message, "/nonexistent/x.obj");
}

/* A morphing object removed: its blend mesh is emptied (the other meshes
 * keep their ids) and a saved copy of the scene, which leaves blend meshes
 * out, renders as the edited scene does. */
static void check_blend_removed(void) {
    if (!json_scenes()) {
        printf("no JSON scenes in this build: the blend mesh case not tested\n");
        return;
    }
    rt_scene *s = NULL;
    rt_error err;
    const char *path = test_source_path("scenes/keyframes_animated.json");
    CHECK_MSG(rt_scene_load(path, &s, &err) == RT_OK, "%s", err.message);
    if (!s) return;
    rt_camera cam;
    rt_camera_get(s, &cam);
    cam.width = W, cam.height = H;
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    const double t = 0.5;
    CHECK(rt_scene_set_time(s, t) == RT_OK);
    uint32_t morphing = UINT32_MAX;
    for (uint32_t o = 0; o < rt_scene_object_count(s) && morphing == UINT32_MAX; o++) {
        rt_object_info oi;
        CHECK(rt_object_describe(s, o, &oi) == RT_OK);
        if (oi.morphing) morphing = o;
    }
    CHECK_MSG(morphing != UINT32_MAX, "no object of %s morphs at time %g", path, t);
    if (morphing == UINT32_MAX) {
        rt_scene_destroy(s);
        return;
    }
    uint32_t meshes = rt_scene_mesh_count(s), objects = rt_scene_object_count(s);
    CHECK(rt_object_remove(s, morphing) == RT_OK);
    CHECK_EQ_INT(rt_scene_mesh_count(s), meshes);
    CHECK_EQ_INT(rt_scene_object_count(s), objects - 1);
    uint32_t empty = 0;
    for (uint32_t m = 0; m < meshes; m++) {
        rt_mesh_info mi;
        CHECK(rt_mesh_describe(s, m, &mi) == RT_OK);
        empty += mi.triangles == 0 && strstr(mi.name, "(blend)") != NULL;
    }
    CHECK_EQ_INT(empty, 1);
    rt_renderer *r = make("cpu", &err);
    rt_framebuffer edited, saved;
    memset(&edited, 0, sizeof edited);
    memset(&saved, 0, sizeof saved);
    CHECK(r && rt_render(r, s, NULL, &edited) == RT_OK);
    const char *marker = test_write_temp("marker", "");
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", marker);
    *strrchr(dir, '/') = 0;
    CHECK_MSG(rt_scene_save_json(s, dir, "edited", &err) == RT_OK, "%s", err.message);
    char json[4200];
    snprintf(json, sizeof json, "%s/edited.json", dir);
    rt_scene *back = NULL;
    CHECK_MSG(rt_scene_load(json, &back, &err) == RT_OK, "%s", err.message);
    if (back && r) {
        CHECK(rt_scene_set_time(back, t) == RT_OK);
        CHECK_EQ_INT(rt_scene_object_count(back), objects - 1);
        CHECK(rt_render(r, back, NULL, &saved) == RT_OK);
        CHECK_MSG(test_same_fb(&edited, &saved),
                  "the saved scene without the morphing object renders otherwise");
    }
    rt_framebuffer_free(&edited);
    rt_framebuffer_free(&saved);
    rt_renderer_destroy(r);
    rt_scene_destroy(back);
    rt_scene_destroy(s);
}

int main(int argc, char **argv) {
    /* "vulkan": the Vulkan backend alone (ctest's test_scene_edits_vulkan,
     * run without the leak check in the sanitizer build, as
     * test_dynamic_scenes_vulkan). Otherwise cpu, packet and opencl. */
    only_vulkan = argc > 1 && !strcmp(argv[1], "vulkan");
    if (only_vulkan) {
        check_backend("vulkan");
        if (!device_tested) test_skip("no Vulkan device rendered a frame (said above)");
        return TEST_END();
    }
    check_errors();
    check_no_default_light();
    check_blend_removed();
    check_backend("cpu");
    check_backend("packet");
    check_backend("opencl");
    return TEST_END();
}
