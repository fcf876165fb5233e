/* SPDX-License-Identifier: Apache-2.0 */
/* fuzz_json.c - libFuzzer harness of the JSON scene loader (scene_json.c,
 * json_locate.c, through rt_scene_load).
 *
 * The input is written to SCRATCH/s.json beside fixed files it may name:
 * m.obj (two triangles, with "mtllib m.mtl"), m.mtl (one material) and
 * p.obj (a plain tetrahedron), so that "file" meshes load. A scene that loads is rendered at 16x16
 * (BVH builds, object transforms and keyframes, lights, materials), then saved with
 * rt_scene_save_json (which refuses meshes with per-triangle materials, such as m.obj's) and loaded
 * again: what the library writes, it must read, with the same triangle, object and light counts. A
 * load that fails must name the file in its message. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "formats/scene_save.h"
#include "fuzz_util.h"
#include "scene/scene.h"

static const char mesh_obj[] = "mtllib m.mtl\n"
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                               "vn 0 0 1\n"
                               "usemtl red\n"
                               "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";
static const char plain_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
static const char mesh_mtl[] = "newmtl red\nKd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nNs 20\nd 0.5\nNi 1.5\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    static int ready;
    if (!ready) {
        fuzz_write(fuzz_path(0, "m.obj"), mesh_obj, sizeof mesh_obj - 1);
        fuzz_write(fuzz_path(0, "m.mtl"), mesh_mtl, sizeof mesh_mtl - 1);
        fuzz_write(fuzz_path(0, "p.obj"), plain_obj, sizeof plain_obj - 1);
        ready = 1;
    }
    const char *json = fuzz_path(0, "s.json");
    fuzz_write(json, data, size);
    rt_scene *scene = NULL;
    rt_error err;
    rt_status st = rt_scene_load(json, &scene, &err);
    if (st != RT_OK) {
        fuzz_check(scene == NULL, "a failed load returned a scene");
        fuzz_check(err.status == st, "the error's status is not the one returned");
        fuzz_check(strstr(err.message, "s.json") != NULL || strstr(err.message, "m.obj") != NULL ||
                       strstr(err.message, "m.mtl") != NULL || strstr(err.message, "p.obj") != NULL,
                   "a load error that names no file");
        return 0;
    }
    fuzz_render_small(scene, 16);

    /* Saved, the scene loads again. */
    const char *saved = fuzz_path(1, "r.json");
    if (rt_scene_save_json(scene, fuzz_dir(), "r", &err) == RT_OK) {
        rt_scene *again = NULL;
        rt_error err2;
        if (rt_scene_load(saved, &again, &err2) != RT_OK) {
            fprintf(stderr, "the saved scene does not load: %s\n", err2.message);
            fuzz_check(0, "a saved scene does not load");
        }
        fuzz_check(rt_scene_triangle_count(again) == rt_scene_triangle_count(scene),
                   "the saved scene has another triangle count");
        fuzz_check(again->object_count == scene->object_count,
                   "the saved scene has another object count");
        fuzz_check(again->light_count == scene->light_count,
                   "the saved scene has another light count");
        rt_scene_destroy(again);
    }
    rt_scene_destroy(scene);
    return 0;
}
