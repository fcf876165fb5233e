/* SPDX-License-Identifier: Apache-2.0 */
/* fuzz_gltf.c - libFuzzer harness of the glTF loader (the module's parser
 * and accessor reads, gltf_module.cpp; the mapping, validation and
 * animation of gltf_load.c; through rt_scene_load).
 *
 * The input is written to SCRATCH/f.glb when it starts with the binary
 * magic "glTF", else to SCRATCH/f.gltf, beside a fixed external buffer b.bin
 * (64 bytes: floats 0..15) that a .gltf may name. A scene that loads is
 * evaluated at a few times (before, inside and after its keys, in each clip)
 * and rendered at 8x8. A load that fails must name the file. Without the
 * glTF module every load fails by name, which the harness accepts. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    static int ready;
    if (!ready) {
        float b[16];
        for (int i = 0; i < 16; i++) b[i] = (float)i;
        fuzz_write(fuzz_path(1, "b.bin"), b, sizeof b);
        ready = 1;
    }
    int binary = size >= 4 && memcmp(data, "glTF", 4) == 0;
    const char *path = fuzz_path(0, binary ? "f.glb" : "f.gltf");
    remove(fuzz_path(2, binary ? "f.gltf" : "f.glb"));
    fuzz_write(path, data, size);
    rt_scene *scene = NULL;
    rt_error err;
    rt_status st = rt_scene_load(path, &scene, &err);
    if (st != RT_OK) {
        if (getenv("RT_FUZZ_VERBOSE")) fprintf(stderr, "refused: %s\n", err.message);
        fuzz_check(scene == NULL, "a failed load returned a scene");
        fuzz_check(err.status == st, "the error's status is not the one returned");
        fuzz_check(strstr(err.message, binary ? "f.glb" : "f.gltf") != NULL,
                   "a load error that names no file");
        return 0;
    }
    fuzz_check(scene != NULL, "a load succeeded without a scene");
    static const double times[] = {-1.0, 0.0, 0.37, 1.0, 1e9};
    uint32_t clips = rt_scene_clip_count(scene);
    for (uint32_t c = 0; c < clips && c < 3; c++) {
        char name[16];
        snprintf(name, sizeof name, "%u", c);
        fuzz_check(rt_scene_select_clip(scene, name) == RT_OK || rt_scene_error(scene)[0],
                   "a clip that exists was refused without a reason");
        for (size_t t = 0; t < sizeof times / sizeof times[0]; t++)
            (void)rt_scene_set_time(scene, times[t]); /* may refuse a non-finite vertex */
    }
    fuzz_render_small(scene, 8);
    rt_scene_destroy(scene);
    return 0;
}
