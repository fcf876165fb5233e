/* SPDX-License-Identifier: Apache-2.0 */
/* test_scene_json_errors.c - every kind of bad JSON scene gives an error with
 * the scene file, the line and column of the offending value (or key) and a
 * reason, and no scene. Positions were counted by hand from the texts below.
 *
 * The JSON texts are written with ' for " to keep them readable; q() swaps
 * them back. */
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "rt.h"

/* A mesh "t" with one triangle, as line 2 of a scene. */
#define MESH_T "  'meshes': {'t': {'positions': [0,0,0, 1,0,0, 0,1,0], 'triangles': [0,1,2]}},\n"
#define OBJ_T  "  'objects': [{'mesh': 't'}]\n"
#define CAMERA "  'camera': {'position': [0, 0, 5], 'look_at': [0, 0, 0]},\n"

static const char *q(const char *text) {
    static char buf[4096];
    size_t n = strlen(text);
    if (n >= sizeof buf) n = sizeof buf - 1;
    for (size_t i = 0; i < n; i++) buf[i] = text[i] == '\'' ? '"' : text[i];
    buf[n] = '\0';
    return buf;
}

typedef struct error_case {
    const char *name;
    const char *json; /* ' stands for " */
    int line, column;
    const char *reason;
} error_case;

static const error_case cases[] = {
    /* syntax, reported by jansson, placed at the start of the bad token */
    {"syntax_trailing_comma", "{'camera': {'fov': 60,}}", 1, 23, "invalid JSON: string or '}'"},
    {"syntax_missing_comma", "{\n  'ambient': [0.1, 0.1, 0.1]\n  'objects': []\n}", 3, 3,
     "invalid JSON: '}' expected"},
    {"syntax_bad_token", "{'objects': tru}", 1, 13, "invalid JSON: invalid token"},
    {"syntax_duplicate_key", "{'ambient': [0,0,0], 'ambient': [1,1,1]}", 1, 22,
     "duplicate object key"},
    {"syntax_empty_file", "", 1, 1, "invalid JSON"},
    {"not_an_object", "\n  [1, 2]", 2, 3, "a scene file holds a JSON object, found an array"},

    /* unknown keys, at every level: the key is named and the valid ones listed */
    {"unknown_top_key", "{\n  'objets': []\n}", 2, 3,
     "unknown key 'objets' in the scene (valid keys: camera, background, ambient, exposure, "
     "materials, "
     "lights, meshes, objects)"},
    {"unknown_camera_key", "{\n  'camera': {'position': [0, 0, 5], 'zoom': 2}\n}", 2, 37,
     "unknown key 'zoom' in camera (valid keys: position, look_at, direction, up, fov, width, "
     "height, path)"},
    {"unknown_material_key",
     "{\n  'materials': {'red': {'color': [1, 0, 0],\n                        'colour': [1, 0, "
     "0]}},\n" MESH_T OBJ_T "}",
     3, 25,
     "unknown key 'colour' in materials.red (valid keys: color, ambient, diffuse, specular, "
     "shininess, reflectivity, transparency, ior, emission)"},
    {"unknown_light_key", "{\n  'lights': [{'position': [0, 0, 5], 'power': 2}]\n}", 2, 38,
     "unknown key 'power' in lights[0] (valid keys: position, color)"},
    {"unknown_mesh_key", "{\n  'meshes': {'t': {'path': 'a.obj'}}\n}", 2, 20,
     "unknown key 'path' in meshes.t (valid keys: file, positions, triangles, normals, update, "
     "accel)"},
    {"unknown_object_key", "{\n" MESH_T "  'objects': [{'mesh': 't', 'visible': true}]\n}", 3, 29,
     "unknown key 'visible' in objects[0] (valid keys: mesh, keyframes, frame, material"},
    {"unknown_transform_key",
     "{\n" MESH_T "  'objects': [{'mesh': 't',\n"
     "               'transform': {'translate': [1, 0, 0], 'scale': 2}}]\n}",
     4, 54, "unknown key 'scale' in objects[0].transform (valid keys: matrix, translate, rotate)"},
    {"unknown_rotate_key",
     "{\n" MESH_T "  'objects': [{'mesh': 't',\n"
     "               'transform': {'rotate': {'axis': [0, 1, 0], 'angle': 90}}}]\n}",
     4, 60, "unknown key 'angle' in objects[0].transform.rotate (valid keys: axis, degrees)"},
    /* a key spelt with escapes is found by its decoded text */
    {"unknown_key_escaped", "{'\\u006fbjects': [], 'b\\u00e9': 1}", 1, 22,
     "unknown key 'b\xc3\xa9'"},

    /* wrong types and lengths */
    {"wrong_type_fov",
     "{\n  'camera': {'position': [0, 0, 5], 'look_at': [0, 0, 0],\n             'fov': "
     "'wide'},\n" MESH_T OBJ_T "}",
     3, 21, "camera.fov: expected a number, found a string"},
    {"wrong_type_section", "{\n  'lights': {},\n" MESH_T OBJ_T "}", 2, 13,
     "lights: expected an array, found an object"},
    {"wrong_type_mesh", "{\n  'meshes': {'t': [1, 2]},\n" OBJ_T "}", 2, 19,
     "meshes.t: expected an object, found an array"},
    {"wrong_length",
     "{\n  'camera': {'position': [0, 1], 'look_at': [0, 0, 0]},\n" MESH_T OBJ_T "}", 2, 26,
     "camera.position: expected 3 numbers, found 2"},
    {"wrong_element_type", "{\n  'lights': [{'position': [0, 'up', 0]}],\n" MESH_T OBJ_T "}", 2, 31,
     "lights[0].position[1]: expected a number, found a string"},
    {"keyframe_not_string", "{\n" MESH_T "  'objects': [{'keyframes': [1]}]\n}", 3, 30,
     "objects[0].keyframes[0]: expected a mesh name (a string), found an integer"},
    {"matrix_length",
     "{\n" MESH_T "  'objects': [{'mesh': 't', 'transform': {'matrix': [1, 0, 0]}}]\n}", 3, 53,
     "objects[0].transform.matrix: expected 16 numbers, found 3"},

    /* values out of range */
    {"mask_negative", "{\n" MESH_T "  'objects': [{'mesh': 't', 'mask': -1}]\n}", 3, 37,
     "objects[0].mask: -1 is outside 0..4294967295"},
    {"mask_too_large", "{\n" MESH_T "  'objects': [{'mesh': 't', 'mask': 4294967296}]\n}", 3, 37,
     "objects[0].mask: 4294967296 is outside 0..4294967295"},
    {"mask_fraction", "{\n" MESH_T "  'objects': [{'mesh': 't', 'mask': 1.5}]\n}", 3, 37,
     "objects[0].mask: expected an integer in 0..4294967295, found 1.5"},
    {"shininess_fraction", "{\n  'materials': {'m': {'shininess': 2.5}},\n" MESH_T OBJ_T "}", 2, 36,
     "materials.m.shininess: expected an integer in 0..100000, found 2.5"},
    {"fov_too_wide",
     "{\n  'camera': {'position': [0, 0, 5], 'look_at': [0, 0, 0],\n             'fov': "
     "180},\n" MESH_T OBJ_T "}",
     3, 21, "camera.fov: the field of view must be between 0 and 180 degrees"},
    {"width_zero",
     "{\n  'camera': {'position': [0, 0, 5], 'look_at': [0, 0, 0],\n             'width': "
     "0},\n" MESH_T OBJ_T "}",
     3, 23, "camera.width: 0 is outside 1..32768"},
    {"negative_coefficient", "{\n  'materials': {'m': {'diffuse': -0.5}},\n" MESH_T OBJ_T "}", 2,
     34, "materials.m.diffuse: must be >= 0, found -0.5"},
    {"negative_colour", "{\n  'ambient': [0.1, -1, 0.1],\n" MESH_T OBJ_T "}", 2, 20,
     "ambient[1]: a colour component must be >= 0, found -1"},
    /* issue 31: colours and intensities of 1e38 gave infinite pixels */
    {"light_colour_too_large",
     "{\n  'lights': [{'position': [0, 0, 5], 'color': [1, 1e38, 1]}],\n" MESH_T OBJ_T "}", 2, 51,
     "lights[0].color[1]: 1e+38 is outside 0..1e+06 (the colour limit)"},
    {"material_colour_too_large",
     "{\n  'materials': {'m': {'color': [2e6, 0, 0]}},\n" MESH_T OBJ_T "}", 2, 33,
     "materials.m.color[0]: 2e+06 is outside 0..1e+06 (the colour limit)"},
    {"diffuse_too_large", "{\n  'materials': {'m': {'diffuse': 1e30}},\n" MESH_T OBJ_T "}", 2, 34,
     "materials.m.diffuse: 1e+30 is outside 0..1e+06 (the colour limit)"},
    {"background_too_large", "{\n  'background': [0, 0, 1e7],\n" MESH_T OBJ_T "}", 2, 24,
     "background[2]: 1e+07 is outside 0..1e+06 (the colour limit)"},
    {"float_overflow", "{\n  'background': [1e39, 0, 0],\n" MESH_T OBJ_T "}", 2, 18,
     "background[0]: 1e+39 is out of range for a 32-bit float"},
    {"ior_zero_after_unicode", "{\n  'materials': {'caf\xc3\xa9': {'ior': 0}},\n" MESH_T OBJ_T "}",
     2, 33, "materials.caf\xc3\xa9.ior: must be > 0, found 0"},
    {"reflectivity_plus_transparency",
     "{\n  'materials': {'m': {'reflectivity': 0.6, 'transparency': 0.6}},\n" MESH_T OBJ_T "}", 2,
     22, "materials.m: reflectivity + transparency is 1.2"},
    {"frame_out_of_range", "{\n" MESH_T "  'objects': [{'keyframes': ['t', 't'], 'frame': 2}]\n}",
     3, 50, "objects[0].frame: keyframe 2 does not exist: the object has 2 keyframes (0..1)"},
    {"frame_negative", "{\n" MESH_T "  'objects': [{'keyframes': ['t', 't'], 'frame': -1}]\n}", 3,
     50, "objects[0].frame: -1 is outside 0.."},
    {"inline_index_out_of_range",
     "{\n  'meshes': {'t': {'positions': [0,0,0, 1,0,0, 0,1,0], 'triangles': [0, 1, 3]}},\n" OBJ_T
     "}",
     2, 76,
     "meshes.t.triangles[2]: vertex index 3 is out of range: the mesh has 3 vertices (0..2)"},
    {"inline_positions_length",
     "{\n  'meshes': {'t': {'positions': [0,0,0, 1,0], 'triangles': [0, 1, 3]}},\n" OBJ_T "}", 2,
     33, "meshes.t.positions: expected 3 numbers per vertex, but 5 is not a multiple of 3"},
    {"inline_normals_count",
     "{\n  'meshes': {'t': {'positions': [0,0,0, 1,0,0, 0,1,0], 'normals': [0,0,1],\n"
     "                  'triangles': [0,1,2]}},\n" OBJ_T "}",
     2, 67, "meshes.t.normals: expected one normal per vertex (9 numbers), found 3 numbers"},
    {"rotation_zero_axis",
     "{\n" MESH_T
     "  'objects': [{'mesh': 't', 'transform': {'rotate': {'axis': [0, 0, 0], 'degrees': 9}}}]\n}",
     3, 62, "objects[0].transform.rotate.axis: the rotation axis must not be zero"},
    {"matrix_last_row",
     "{\n" MESH_T
     "  'objects': [{'mesh': 't', 'transform': {'matrix': [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1]}}]"
     "\n}",
     3, 53, "objects[0].transform.matrix: object 0: the last row of a transform must be 0 0 0 1"},
    {"matrix_singular",
     "{\n" MESH_T
     "  'objects': [{'mesh': 't', 'transform': {'matrix': [1,0,0,0, 0,1,0,0, 0,0,0,0, 0,0,0,1]}}]"
     "\n}",
     3, 53, "objects[0].transform.matrix: object 0: the transform is singular"},

    /* camera rules */
    {"camera_missing_position", "{\n  'camera': {'look_at': [0, 0, 0]},\n" MESH_T OBJ_T "}", 2, 13,
     "camera: missing key 'position'"},
    {"camera_look_at_and_direction",
     "{\n  'camera': {'position': [0, 0, 5], 'look_at': [0, 0, 0], 'direction': [0, 0, -1]}\n"
     "}",
     2, 59, "'look_at' and 'direction' exclude each other"},
    {"camera_up_parallel",
     "{\n  'camera': {'position': [0, 0, 5], 'look_at': [0, 0, 0], 'up': [0, 0, 1]},\n" MESH_T OBJ_T
     "}",
     2, 13, "camera: up is zero or (nearly) parallel to the view direction"},

    /* time: animation, transform_keys, camera path (docs/SCENE_FORMAT.md, "Time") */
    {"animation_rate_zero",
     "{\n" MESH_T "  'objects': [{'mesh': 't', 'animation': {'keyframe_rate': 0}}]\n}", 3, 60,
     "objects[0].animation.keyframe_rate: must be > 0, found 0"},
    {"animation_missing_rate",
     "{\n" MESH_T "  'objects': [{'mesh': 't', 'animation': {'interpolate': true}}]\n}", 3, 42,
     "objects[0].animation: missing key 'keyframe_rate'"},
    {"animation_interpolate_not_bool",
     "{\n" MESH_T
     "  'objects': [{'mesh': 't', 'animation': {'keyframe_rate': 2, 'interpolate': 1}}]\n}",
     3, 78, "objects[0].animation.interpolate: expected true or false, found an integer"},
    {"animation_unknown_key",
     "{\n" MESH_T "  'objects': [{'mesh': 't', 'animation': {'keyframe_rate': 2, 'fps': 3}}]\n}", 3,
     63, "unknown key 'fps' in objects[0].animation (valid keys: keyframe_rate, interpolate)"},
    {"animation_and_frame",
     "{\n" MESH_T "  'objects': [{'mesh': 't', 'frame': 0, 'animation': {'keyframe_rate': 2}}]\n}",
     3, 41, "'frame' and 'animation' exclude each other"},
    {"transform_keys_not_increasing",
     "{\n" MESH_T "  'objects': [{'mesh': 't', 'transform_keys': [{'time': 1}, {'time': 1}]}]\n}",
     3, 70, "objects[0].transform_keys[1].time: key times must increase: 1 follows 1"},
    {"transform_keys_missing_time",
     "{\n" MESH_T "  'objects': [{'mesh': 't', 'transform_keys': [{'scale': 2}]}]\n}", 3, 48,
     "objects[0].transform_keys[0]: missing key 'time'"},
    {"transform_keys_bad_scale",
     "{\n" MESH_T "  'objects': [{'mesh': 't', 'transform_keys': [{'time': 0, 'scale': -1}]}]\n}",
     3, 69, "objects[0].transform_keys[0].scale: must be > 0, found -1"},
    {"transform_keys_zero_axis",
     "{\n" MESH_T
     "  'objects': [{'mesh': 't', 'transform_keys': [{'time': 0, 'rotate': {'axis': [0, 0, 0], "
     "'degrees': 9}}]}]\n}",
     3, 79, "objects[0].transform_keys[0].rotate.axis: the rotation axis must not be zero"},
    {"transform_keys_empty", "{\n" MESH_T "  'objects': [{'mesh': 't', 'transform_keys': []}]\n}",
     3, 47, "objects[0].transform_keys: expected at least one key, found an empty array"},
    {"transform_and_keys",
     "{\n" MESH_T
     "  'objects': [{'mesh': 't', 'transform': {}, 'transform_keys': [{'time': 0}]}]\n}",
     3, 46, "'transform' and 'transform_keys' exclude each other"},
    {"camera_path_and_position",
     "{\n  'camera': {'position': [0, 0, 5], 'path': [{'time': 0, 'position': [0, 0, 5], "
     "'look_at': [0, 0, 0]}]},\n" MESH_T OBJ_T "}",
     2, 14, "'path' and 'position' exclude each other"},
    {"camera_path_missing_look_at",
     "{\n  'camera': {'path': [{'time': 0, 'position': [0, 0, 5]}]},\n" MESH_T OBJ_T "}", 2, 23,
     "camera.path[0]: missing key 'look_at'"},
    {"camera_path_look_at_position",
     "{\n  'camera': {'path': [{'time': 0, 'position': [1, 2, 3], 'look_at': [1, 2, 3]}]},\n" MESH_T
         OBJ_T "}",
     2, 69, "camera.path[0].look_at: the look-at point equals the position"},
    {"camera_path_time_string",
     "{\n  'camera': {'path': [{'time': 'x', 'position': [0, 0, 5], 'look_at': [0, 0, "
     "0]}]},\n" MESH_T OBJ_T "}",
     2, 32, "camera.path[0].time: expected a number, found a string"},
    {"mesh_bad_update",
     "{\n  'meshes': {'t': {'positions': [0,0,0, 1,0,0, 0,1,0], 'triangles': [0,1,2], "
     "'update': 'lazy'}},\n" OBJ_T "}",
     2, 88,
     "meshes.t.update: expected an update policy: \"sah\", \"refit\", \"lbvh\" or \"auto\", found "
     "\"lazy\""},

    /* references */
    {"missing_mesh", "{\n" MESH_T "  'objects': [{'mesh': 'cube'}]\n}", 3, 24,
     "objects[0].mesh: no mesh named 'cube' (defined meshes: t)"},
    {"missing_material", "{\n" MESH_T "  'objects': [{'mesh': 't', 'material': 'glass'}]\n}", 3, 41,
     "objects[0].material: no material named 'glass' (defined materials: none)"},
    {"missing_keyframe_mesh", "{\n" MESH_T "  'objects': [{'keyframes': ['t', 'u']}]\n}", 3, 35,
     "objects[0].keyframes[1]: no mesh named 'u' (defined meshes: t)"},
    {"object_without_mesh", "{\n" MESH_T "  'objects': [{'material': 'm'}]\n}", 3, 15,
     "objects[0]: missing key 'mesh' or 'keyframes'"},
    {"file_and_inline",
     "{\n  'meshes': {'t': {'file': 'a.obj', 'positions': [0,0,0]}},\n" OBJ_T "}", 2, 37,
     "'file' and 'positions' exclude each other"},

    /* empty scenes */
    {"empty_objects", "{\n" MESH_T "  'objects': []\n}", 3, 14,
     "objects: the scene is empty: 'objects' lists no object"},
    {"missing_objects", "{\n" MESH_T "  'ambient': [1, 1, 1]\n}", 1, 1,
     "the scene is empty: missing key 'objects'"},
    {"no_triangles",
     "{\n  'meshes': {'e': {'positions': [], 'triangles': []}},\n  'objects': [{'mesh': 'e'}]\n}",
     3, 14, "objects: the scene is empty: no object has a triangle"},
};

static void check_case(const error_case *c) {
    char name[128];
    snprintf(name, sizeof name, "%s.json", c->name);
    const char *path = test_write_temp(name, q(c->json));
    CHECK(path != NULL);
    if (!path) return;
    char where[4200];
    snprintf(where, sizeof where, "%s:%d:%d: ", path, c->line, c->column);
    rt_scene *scene = (rt_scene *)&scene; /* must come back NULL */
    rt_error err;
    rt_status st = rt_scene_load(path, &scene, &err);
    CHECK_MSG(st == RT_ERROR_PARSE, "%s: status %d: %s", c->name, (int)st, err.message);
    CHECK_MSG(scene == NULL, "%s: a scene came back", c->name);
    CHECK_MSG(err.line == c->line && err.column == c->column, "%s: at %d:%d, expected %d:%d (%s)",
              c->name, err.line, err.column, c->line, c->column, err.message);
    CHECK_MSG(strncmp(err.message, where, strlen(where)) == 0, "%s: \"%s\" does not start \"%s\"",
              c->name, err.message, where);
    CHECK_MSG(strstr(err.message, c->reason) != NULL, "%s: \"%s\" lacks \"%s\"", c->name,
              err.message, c->reason);
}

static void test_missing_and_unreadable_scene(void) {
    rt_scene *scene = NULL;
    rt_error err;
    const char *dir = test_write_temp("probe.txt", "");
    char path[4200];
    snprintf(path, sizeof path, "%.*s/no_such_scene.json", (int)(strrchr(dir, '/') - dir), dir);
    CHECK(rt_scene_load(path, &scene, &err) == RT_ERROR_IO);
    CHECK(scene == NULL);
    CHECK(strcmp(err.file, path) == 0);
    CHECK_CONTAINS(err.message, "cannot open the scene file");
    CHECK_CONTAINS(err.message, "no_such_scene.json");

    /* A folder opens but cannot be read. */
    snprintf(path, sizeof path, "%.*s/folder.json", (int)(strrchr(dir, '/') - dir), dir);
    mkdir(path, 0700);
    CHECK(rt_scene_load(path, &scene, &err) == RT_ERROR_IO);
    CHECK(scene == NULL);
    CHECK_CONTAINS(err.message, "cannot read the scene file");
}

/* The OBJ loader's own error (its file and line) comes through, with where
 * the scene names the file. */
static void test_mesh_file_errors(void) {
    const char *obj = test_write_temp("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    CHECK(obj != NULL);
    const char *scene_path = test_write_temp(
        "bad_mesh.json", q("{\n  'meshes': {'b': {'file': 'bad.obj'}},\n  'objects': [{'mesh': "
                           "'b'}]\n}"));
    char where[4200];
    snprintf(where, sizeof where, "(mesh file named at %s:2:28)", scene_path);
    rt_scene *scene = NULL;
    rt_error err;
    CHECK(rt_scene_load(scene_path, &scene, &err) == RT_ERROR_PARSE);
    CHECK(scene == NULL);
    CHECK_MSG(strstr(err.file, "bad.obj") != NULL, "file %s", err.file);
    CHECK_EQ_INT(err.line, 3);
    CHECK_CONTAINS(err.message, "bad.obj:3");
    CHECK_CONTAINS(err.message, where);

    scene_path = test_write_temp(
        "missing_mesh_file.json",
        q("{\n  'meshes': {'b': {'file': 'nothere.obj'}},\n  'objects': [{'mesh': 'b'}]\n}"));
    snprintf(where, sizeof where, "(mesh file named at %s:2:28)", scene_path);
    CHECK(rt_scene_load(scene_path, &scene, &err) == RT_ERROR_IO);
    CHECK(scene == NULL);
    CHECK_CONTAINS(err.message, "nothere.obj");
    CHECK_CONTAINS(err.message, where);
}

int main(void) {
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) check_case(&cases[i]);
    test_missing_and_unreadable_scene();
    test_mesh_file_errors();
    return TEST_END();
}
