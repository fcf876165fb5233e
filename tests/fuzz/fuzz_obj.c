/* SPDX-License-Identifier: Apache-2.0 */
/* fuzz_obj.c - libFuzzer harness of the OBJ and MTL readers.
 *
 * The input is an OBJ file, optionally followed by the line "#mtl" and an
 * MTL file: the OBJ part is written to SCRATCH/f.obj and the MTL part to
 * SCRATCH/f.mtl (which an "mtllib f.mtl" line of the OBJ reads; without the
 * separator there is no f.mtl, the unreadable-mtllib path). The pair is
 * loaded as a bare OBJ scene (rt_scene_load: obj_load.c, mtl_load.c,
 * scene_obj.c, the scene's validation). A scene that loads is rendered at
 * 8x8 (BVH build, flattening, shading with the MTL materials). A load that
 * fails must say where: the message names the file. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"

static const char separator[] = "\n#mtl\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const char *obj = fuzz_path(0, "f.obj"), *mtl = fuzz_path(1, "f.mtl");
    const uint8_t *split = NULL;
    const size_t sep = sizeof separator - 1;
    for (size_t i = 0; i + sep <= size && !split; i++)
        if (data[i] == '\n' && memcmp(data + i, separator, sep) == 0) split = data + i;
    if (split) {
        fuzz_write(obj, data, (size_t)(split - data) + 1); /* with its newline */
        fuzz_write(mtl, split + sep, size - (size_t)(split - data) - sep);
    } else {
        fuzz_write(obj, data, size);
        remove(mtl);
    }
    rt_scene *scene = NULL;
    rt_error err;
    rt_status st = rt_scene_load(obj, &scene, &err);
    if (st != RT_OK) {
        fuzz_check(scene == NULL, "a failed load returned a scene");
        fuzz_check(err.status == st, "the error's status is not the one returned");
        fuzz_check(strstr(err.message, "f.obj") != NULL || strstr(err.message, "f.mtl") != NULL,
                   "a load error that names no file");
        return 0;
    }
    fuzz_check(scene != NULL, "a load succeeded without a scene");
    fuzz_render_small(scene, 8);
    rt_scene_destroy(scene);
    return 0;
}
