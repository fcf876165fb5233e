/* SPDX-License-Identifier: Apache-2.0 */
/* test_scene_json.c - JSON scenes that load: every key with its value, the
 * defaults, the default view without a camera, keyframes, transforms, mesh
 * files relative to the scene file. The errors are in
 * test_scene_json_errors.c, a real scene in test_scene_json_cornell.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "formats/json_bulk.h"
#include "scene/scene.h"

#define NEAR(a, b) (fabs((double)(a) - (double)(b)) <= 1e-5 * (1.0 + fabs((double)(b))))

static rt_scene *load_text(const char *name, const char *json) {
    const char *path = test_write_temp(name, json);
    rt_scene *scene = NULL;
    rt_error err;
    rt_status st = rt_scene_load(path, &scene, &err);
    CHECK_MSG(st == RT_OK, "%s: %s", name, err.message);
    return scene;
}

static const char *full_scene =
    "{\n"
    "  \"camera\": {\"position\": [1, 2, 10], \"look_at\": [0, 1, 0], \"up\": [0, 0, 1],\n"
    "             \"fov\": 45.5, \"width\": 640, \"height\": 480},\n"
    "  \"background\": [0.2, 0.3, 0.4],\n"
    "  \"ambient\": [0.05, 0.06, 0.07],\n"
    "  \"materials\": {\n"
    "    \"red\": {\"color\": [0.9, 0.1, 0.1], \"ambient\": 0.5, \"diffuse\": 0.8,\n"
    "            \"specular\": 0.3, \"shininess\": 32, \"reflectivity\": 0.25,\n"
    "            \"transparency\": 0.5, \"ior\": 1.5},\n"
    "    \"plain\": {}\n"
    "  },\n"
    "  \"lights\": [{\"position\": [0, 5, 0], \"color\": [1, 0.5, 0.25]},\n"
    "             {\"position\": [3, 3, 3]}],\n"
    "  \"meshes\": {\n"
    "    \"tri\": {\"positions\": [0, 0, 0, 1, 0, 0, 0, 1, 0], \"triangles\": [0, 1, 2],\n"
    "            \"normals\": [0, 0, 1, 0, 0, 1, 0, 0, 1]},\n"
    "    \"quad\": {\"positions\": [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0],\n"
    "             \"triangles\": [0, 1, 2, 0, 2, 3]},\n"
    "    \"unused\": {\"positions\": [], \"triangles\": []}\n"
    "  },\n"
    "  \"objects\": [\n"
    "    {\"mesh\": \"tri\", \"material\": \"red\",\n"
    "     \"transform\": {\"translate\": [1, 2, 3]}},\n"
    "    {\"keyframes\": [\"tri\", \"quad\"], \"frame\": 1, \"material\": \"plain\"},\n"
    "    {\"mesh\": \"quad\"}\n"
    "  ]\n"
    "}\n";

static void test_full_scene(void) {
    rt_scene *s = load_text("full.json", full_scene);
    if (!s) return;
    rt_camera c;
    rt_camera_get(s, &c);
    CHECK(s->has_camera);
    CHECK(c.position[0] == 1 && c.position[1] == 2 && c.position[2] == 10);
    CHECK(c.look_at[0] == 0 && c.look_at[1] == 1 && c.look_at[2] == 0);
    CHECK(c.up[0] == 0 && c.up[1] == 0 && c.up[2] == 1);
    CHECK(c.hfov_degrees == 45.5f);
    CHECK_EQ_INT(c.width, 640);
    CHECK_EQ_INT(c.height, 480);
    CHECK(s->background[0] == 0.2f && s->background[1] == 0.3f && s->background[2] == 0.4f);
    CHECK(s->ambient[0] == 0.05f && s->ambient[1] == 0.06f && s->ambient[2] == 0.07f);

    /* red, plain, then the default white one for the third object. */
    CHECK_EQ_INT(s->material_count, 3);
    const rt_material *red = &s->materials[0];
    CHECK(red->color[0] == 0.9f && red->color[1] == 0.1f && red->color[2] == 0.1f);
    CHECK(red->ambient == 0.5f && red->diffuse == 0.8f && red->specular == 0.3f);
    CHECK_EQ_INT(red->shininess, 32);
    CHECK(red->reflectivity == 0.25f && red->transparency == 0.5f && red->ior == 1.5f);
    rt_material def = rt_material_default();
    CHECK(memcmp(&s->materials[1], &def, sizeof def) == 0);
    CHECK(memcmp(&s->materials[2], &def, sizeof def) == 0);

    CHECK_EQ_INT(s->light_count, 2);
    CHECK(s->lights[0].position[1] == 5 && s->lights[0].color[1] == 0.5f &&
          s->lights[0].color[2] == 0.25f);
    CHECK(s->lights[1].color[0] == 1 && s->lights[1].color[1] == 1 && s->lights[1].color[2] == 1);

    CHECK_EQ_INT(s->mesh_count, 3); /* the unused mesh loads too */
    CHECK_EQ_INT(s->meshes[0].triangle_count, 1);
    CHECK(s->meshes[0].normals != NULL && s->meshes[0].normals[2] == 1.0f);
    CHECK_EQ_INT(s->meshes[1].triangle_count, 2);
    CHECK(s->meshes[1].normals == NULL);
    CHECK_EQ_INT(s->meshes[2].triangle_count, 0);
    CHECK(strcmp(s->meshes[1].name, "quad") == 0);

    CHECK_EQ_INT(s->object_count, 3);
    CHECK_EQ_INT(s->objects[0].material, 0);
    CHECK(s->objects[0].transform[3] == 1 && s->objects[0].transform[7] == 2 &&
          s->objects[0].transform[11] == 3);
    CHECK(!s->objects[0].has_pending); /* committed by the loader */
    CHECK_EQ_INT(s->objects[1].mesh_count, 2);
    CHECK_EQ_INT(s->objects[1].selected, 1);
    CHECK_EQ_INT(s->objects[1].material, 1);
    CHECK_EQ_INT(s->objects[2].material, 2);
    CHECK_EQ_INT(rt_scene_triangle_count(s), 1 + 2 + 2);
    rt_scene_destroy(s);
}

/* The direction form of the camera, and defaults for up, fov and size. */
static void test_camera_direction_and_defaults(void) {
    rt_scene *s = load_text("dir.json", "{\"camera\": {\"position\": [1, 1, 1], "
                                        "\"direction\": [0, 0, -2]},\n"
                                        " \"meshes\": {\"t\": {\"positions\": [0,0,0, 1,0,0, "
                                        "0,1,0], \"triangles\": [0,1,2]}},\n"
                                        " \"objects\": [{\"mesh\": \"t\"}]}");
    if (!s) return;
    rt_camera c;
    rt_camera_get(s, &c);
    CHECK(c.look_at[0] == 1 && c.look_at[1] == 1 && c.look_at[2] == -1);
    CHECK(c.up[0] == 0 && c.up[1] == 1 && c.up[2] == 0);
    CHECK(c.hfov_degrees == 60.0f);
    CHECK_EQ_INT(c.width, 1024);
    CHECK_EQ_INT(c.height, 576);
    CHECK(s->background[0] == 0 && s->background[1] == 0 && s->background[2] == 0);
    CHECK(s->ambient[0] == 0.1f && s->ambient[1] == 0.1f && s->ambient[2] == 0.1f);
    CHECK_EQ_INT(s->light_count, 0); /* a camera given, no lights: none added */
    rt_scene_destroy(s);
}

/* No camera: the default view of a bare OBJ, computed here from the rule in
 * docs/SCENE_FORMAT.md, not from the library's function. */
static void test_default_view(void) {
    const char *mesh = "\"meshes\": {\"t\": {\"positions\": [0,0,0, 2,0,0, 0,2,0, 9,9,9], "
                       "\"triangles\": [0,1,2]}},\n \"objects\": [{\"mesh\": \"t\"}]";
    char json[1024];
    snprintf(json, sizeof json, "{%s}", mesh);
    rt_scene *s = load_text("default.json", json);
    if (!s) return;
    /* The unused vertex (9,9,9) does not count: box (0,0,0)-(2,2,0). */
    double c[3] = {1, 1, 0}, d = sqrt(8.0);
    double dir[3] = {0.3, 0.35, 1.0}, len = sqrt(0.09 + 0.1225 + 1.0);
    rt_camera cam;
    rt_camera_get(s, &cam);
    CHECK(s->has_camera);
    for (int k = 0; k < 3; k++) {
        CHECK_MSG(NEAR(cam.position[k], c[k] + dir[k] / len * 0.9 * d), "eye[%d] = %g", k,
                  (double)cam.position[k]);
        CHECK(NEAR(cam.look_at[k], c[k]));
    }
    CHECK(cam.up[0] == 0 && cam.up[1] == 1 && cam.up[2] == 0);
    CHECK(cam.hfov_degrees == 60.0f);
    CHECK_EQ_INT(cam.width, 1024);
    CHECK_EQ_INT(cam.height, 576);
    CHECK_EQ_INT(s->light_count, 1);
    /* The default light beside the eye: eye + (0.3 u + 0.2 r) |c - eye|, with
     * the camera's up u and right r (docs/SCENE_FORMAT.md, the default view). */
    double f[3], r[3], u[3], eye[3];
    for (int k = 0; k < 3; k++) eye[k] = c[k] + dir[k] / len * 0.9 * d, f[k] = -dir[k] / len;
    r[0] = -f[2], r[1] = 0.0, r[2] = f[0]; /* f x (0, 1, 0) */
    double rl = sqrt(r[0] * r[0] + r[2] * r[2]);
    r[0] /= rl, r[2] /= rl;
    u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2],
    u[2] = r[0] * f[1] - r[1] * f[0]; /* r x f */
    for (int k = 0; k < 3; k++) {
        CHECK_MSG(NEAR(s->lights[0].position[k], eye[k] + (0.3 * u[k] + 0.2 * r[k]) * 0.9 * d),
                  "light[%d] = %g", k, (double)s->lights[0].position[k]);
        CHECK(s->lights[0].color[k] == 1.0f);
        CHECK(s->ambient[k] == 0.1f);
    }
    CHECK_EQ_INT(s->material_count, 1);
    rt_material def = rt_material_default();
    CHECK(memcmp(&s->materials[0], &def, sizeof def) == 0);
    rt_scene_destroy(s);

    /* Lights and ambient given without a camera stay as given. */
    snprintf(json, sizeof json,
             "{%s,\n \"lights\": [{\"position\": [5, 5, 5], \"color\": [0.5, 0.5, 0.5]}],\n"
             " \"ambient\": [0.3, 0.2, 0.1]}",
             mesh);
    s = load_text("default_lights.json", json);
    if (!s) return;
    CHECK(s->has_camera);
    CHECK_EQ_INT(s->light_count, 1);
    CHECK(s->lights[0].position[0] == 5 && s->lights[0].color[0] == 0.5f);
    CHECK(s->ambient[0] == 0.3f && s->ambient[1] == 0.2f && s->ambient[2] == 0.1f);
    rt_scene_destroy(s);

    /* An empty light list means no light at all. */
    snprintf(json, sizeof json, "{%s, \"lights\": []}", mesh);
    s = load_text("default_nolights.json", json);
    if (!s) return;
    CHECK_EQ_INT(s->light_count, 0);
    rt_scene_destroy(s);

    /* The default view frames the object where its transform puts it. */
    snprintf(json, sizeof json,
             "{\"meshes\": {\"t\": {\"positions\": [0,0,0, 2,0,0, 0,2,0], "
             "\"triangles\": [0,1,2]}},\n \"objects\": [{\"mesh\": \"t\", "
             "\"transform\": {\"translate\": [10, 0, 0]}}]}");
    s = load_text("default_moved.json", json);
    if (!s) return;
    CHECK(NEAR(s->camera.look_at[0], 11.0) && NEAR(s->camera.look_at[1], 1.0));
    rt_scene_destroy(s);
}

static void test_keyframes(void) {
    const char *json =
        "{\"meshes\": {\n"
        "  \"a\": {\"positions\": [0,0,0, 1,0,0, 0,1,0], \"triangles\": [0,1,2]},\n"
        "  \"b\": {\"positions\": [0,0,0, 1,0,0, 0,1,0, 1,1,0], \"triangles\": [0,1,2, 1,3,2]},\n"
        "  \"c\": {\"positions\": [0,0,0, 1,0,0, 0,1,0], \"triangles\": [0,1,2, 0,2,1, 0,1,2]}},\n"
        " \"objects\": [{\"keyframes\": [\"a\", \"b\", \"c\", \"b\"], \"frame\": 2},\n"
        "             {\"keyframes\": [\"b\", \"a\"]},\n"
        "             {\"mesh\": \"a\", \"frame\": 0}]}";
    rt_scene *s = load_text("keyframes.json", json);
    if (!s) return;
    CHECK_EQ_INT(s->objects[0].mesh_count, 4);
    CHECK_EQ_INT(s->objects[0].meshes[0], 0);
    CHECK_EQ_INT(s->objects[0].meshes[3], 1); /* the same mesh may appear twice */
    CHECK_EQ_INT(s->objects[0].selected, 2);
    CHECK_EQ_INT(s->objects[1].selected, 0); /* frame defaults to 0 */
    CHECK_EQ_INT(s->objects[1].meshes[0], 1);
    CHECK_EQ_INT(rt_scene_triangle_count(s), 3 + 2 + 1);
    /* Keyframes remain selectable after loading. */
    CHECK(rt_object_select_mesh(s, 0, 3) == RT_OK);
    CHECK_EQ_INT(rt_scene_triangle_count(s), 2 + 2 + 1);
    rt_scene_destroy(s);
}

static void test_transforms(void) {
    const char *json =
        "{\"meshes\": {\"t\": {\"positions\": [0,0,0, 1,0,0, 0,1,0], \"triangles\": [0,1,2]}},\n"
        " \"objects\": [\n"
        "  {\"mesh\": \"t\", \"transform\": {\"rotate\": {\"axis\": [0, 0, 2], \"degrees\": 90},\n"
        "                                \"translate\": [1, 2, 3]}},\n"
        "  {\"mesh\": \"t\", \"transform\": {\"matrix\": [0, -1, 0, 5,  1, 0, 0, 6,\n"
        "                                           0, 0, 2, 7,  0, 0, 0, 1]}},\n"
        "  {\"mesh\": \"t\", \"transform\": {\"rotate\": {\"axis\": [1, 0, 0], \"degrees\": "
        "-90}}},\n"
        "  {\"mesh\": \"t\", \"transform\": {}}\n"
        " ]}";
    rt_scene *s = load_text("transforms.json", json);
    if (!s) return;
    /* Rotate then translate: x -> y, then + (1,2,3). */
    const float *m = s->objects[0].transform;
    const double want0[16] = {0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1};
    for (int i = 0; i < 16; i++)
        CHECK_MSG(fabs(m[i] - want0[i]) < 1e-6, "m[%d] = %g, want %g", i, (double)m[i], want0[i]);
    /* A matrix is taken as given (row-major, p' = M p), scale included. */
    const float want1[16] = {0, -1, 0, 5, 1, 0, 0, 6, 0, 0, 2, 7, 0, 0, 0, 1};
    CHECK(memcmp(s->objects[1].transform, want1, sizeof want1) == 0);
    /* -90 degrees about x: y -> -z. */
    m = s->objects[2].transform;
    CHECK(fabs(m[1 * 4 + 1]) < 1e-6 && fabs(m[2 * 4 + 1] + 1.0f) < 1e-6);
    float id[16];
    rt_mat4_identity(id);
    CHECK(memcmp(s->objects[3].transform, id, sizeof id) == 0);
    rt_scene_destroy(s);
}

/* Mesh files are relative to the scene file's folder, and loading the same
 * file twice gives two meshes. */
static void test_mesh_files(void) {
    const char *obj = test_write_temp("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                                  "f 1 2 3 4\n");
    CHECK(obj != NULL);
    rt_scene *s = load_text("files.json", "{\"meshes\": {\"q\": {\"file\": \"quad.obj\"},\n"
                                          "            \"q2\": {\"file\": \"./quad.obj\"}},\n"
                                          " \"objects\": [{\"mesh\": \"q\"}, {\"mesh\": \"q2\"}]}");
    if (!s) return;
    CHECK_EQ_INT(s->mesh_count, 2);
    CHECK_EQ_INT(s->meshes[0].triangle_count, 2);
    CHECK_EQ_INT(rt_scene_triangle_count(s), 4);
    rt_scene_destroy(s);
}

/* Issue 31: big inline arrays are read from the text (formats/json_bulk.h),
 * not as a JSON value per number. The same numbers read that way and read
 * by jansson (the key written with an escape, which the bulk scan does not
 * take) give the same bits, tricky ones included (-0, denormals, values
 * rounded twice, long integers, exponents); errors inside a bulk array name
 * the element and its place; a placeholder written by hand is no array. */
static void test_bulk_arrays(void) {
    const char *numbers = "-0, 1e-45, 1.4e-45, 3.4028235e38, 1.0000000596046448, "
                          "0.1, 12345678901234567, -7, 2.5E+3, 0.000001, 1e-300, 9.999999e-39";
    char json[4096];
    snprintf(json, sizeof json,
             "{\"meshes\": {\"b\": {\"positions\": [%s], \"triangles\": [0, 1, 2, 3, 2, 1, "
             "0, 0, 0, 1, 2, 3, 0, 1, 2, 3, 2, 1, 0, 0, 0, 1, 2, 3]},\n"
             " \"j\": {\"posit\\u0069ons\": [%s], \"tri\\u0061ngles\": [0, 1, 2, 3, 2, 1, 0, 0, "
             "0, 1, 2, 3, 0, 1, 2, 3, 2, 1, 0, 0, 0, 1, 2, 3]}},\n"
             " \"objects\": [{\"mesh\": \"b\"}, {\"mesh\": \"j\"}]}\n",
             numbers, numbers);
    rt_json_bulk_table table;
    CHECK(rt_json_bulk_scan(json, strlen(json), &table));
    CHECK_EQ_INT(table.count, 2); /* b's positions and triangles; j's keys are escaped */
    rt_json_bulk_free(&table);
    rt_scene *s = load_text("bulk.json", json);
    if (s) {
        CHECK(s->mesh_count == 2 && s->meshes[0].vertex_count == 4 &&
              s->meshes[1].vertex_count == 4 && s->meshes[0].triangle_count == 8);
        CHECK(memcmp(s->meshes[0].positions, s->meshes[1].positions, 12 * sizeof(float)) == 0);
        CHECK(memcmp(s->meshes[0].indices, s->meshes[1].indices, 24 * sizeof(uint32_t)) == 0);
        CHECK(signbit(s->meshes[0].positions[0]) == 0); /* -0 is the integer 0, as jansson has it */
        rt_scene_destroy(s);
    }
    /* Errors at the element, with its place. */
    const char *head = "{\"meshes\": {\"m\": {\"positions\": [0.00000, 0.00000, 0.00000, 1.00000, "
                       "0.00000, 0.00000, 0.00000, 1.00000, 0.00000, 1.00000, 1.00000, ";
    struct {
        const char *rest, *reason;
        int column;
    } bad[] = {
        {"1e39], \"triangles\": [0, 1, 2]}}, \"objects\": [{\"mesh\": \"m\"}]}",
         "meshes.m.positions[11]: 1e+39 is out of range for a 32-bit float", 132},
        {"1], \"triangles\": [0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 3, 1, 4]}}, "
         "\"objects\": [{\"mesh\": \"m\"}]}",
         "meshes.m.triangles[20]: vertex index 4 is out of range: the mesh has 4 vertices", 210},
        {"1], \"triangles\": [0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 3, 1.0, 2]}}, "
         "\"objects\": [{\"mesh\": \"m\"}]}",
         "meshes.m.triangles[19]: expected a vertex index (an integer), found a number", 207},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        snprintf(json, sizeof json, "%s%s", head, bad[k].rest);
        const char *path = test_write_temp("bulk_bad.json", json);
        rt_scene *none = NULL;
        rt_error err;
        CHECK(rt_scene_load(path, &none, &err) == RT_ERROR_PARSE && none == NULL);
        CHECK_CONTAINS(err.message, bad[k].reason);
        CHECK_MSG(err.line == 1 && err.column == bad[k].column, "case %zu: at %d:%d: %s", k,
                  err.line, err.column, err.message);
    }
    const char *forged = test_write_temp(
        "forged.json", "{\"meshes\": {\"m\": {\"positions\": [{\"\": 0}], \"triangles\": [0]}},"
                       " \"objects\": [{\"mesh\": \"m\"}]}");
    rt_scene *none = NULL;
    rt_error err;
    CHECK(rt_scene_load(forged, &none, &err) == RT_ERROR_PARSE && none == NULL);
    CHECK_CONTAINS(err.message, "meshes.m.positions");
}

int main(void) {
    test_full_scene();
    test_camera_direction_and_defaults();
    test_default_view();
    test_keyframes();
    test_transforms();
    test_mesh_files();
    test_bulk_arrays();
    return TEST_END();
}
