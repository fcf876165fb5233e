/* SPDX-License-Identifier: Apache-2.0 */
/* scene_load.c - rt_scene_load: a scene file into a new scene, all or nothing. */
#include "formats/scene_load.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/error.h"
#include "formats/gltf_load.h"
#include "formats/scene_obj.h"
#include "scene/scene.h"
#include "scene/scene_default_view.h"

static int has_extension(const char *path, const char *ext) {
    size_t n = strlen(path), e = strlen(ext);
    return n >= e && strcasecmp(path + n - e, ext) == 0;
}

/* A bare OBJ: one object with the default material and the default view. */
static rt_status load_bare_obj(rt_scene *scene, const char *path, rt_error *err) {
    rt_material white = rt_material_default();
    uint32_t mat, mesh, obj;
    rt_status st = rt_material_add(scene, &white, &mat);
    if (st == RT_OK) st = rt_scene_add_obj(scene, path, &mesh, err);
    if (st != RT_OK) return st;
    st = rt_object_create(scene, mat, &obj);
    if (st == RT_OK) st = rt_object_add_mesh(scene, obj, mesh);
    if (st == RT_OK) st = rt_scene_apply_default_view(scene, 0, 0);
    if (st != RT_OK) return rt_error_set(err, st, path, 0, 0, "%s", scene->error.message);
    return RT_OK;
}

rt_scene_load_options rt_scene_load_options_default(void) {
    rt_scene_load_options o;
    memset(&o, 0, sizeof o);
    return o;
}

rt_status rt_scene_load(const char *path, rt_scene **out, rt_error *err) {
    return rt_scene_load_with(path, NULL, out, err);
}

rt_status rt_scene_load_with(const char *path, const rt_scene_load_options *options, rt_scene **out,
                             rt_error *err) {
    rt_error_clear(err);
    if (!out) return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, NULL, 0, 0, "no output scene");
    *out = NULL;
    if (!path) return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, NULL, 0, 0, "no scene path");
    rt_scene *scene;
    if (rt_scene_create(&scene) != RT_OK)
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0, "out of memory");
    /* The loaders give the default view through rt_scene_apply_default_view,
     * which reads this. */
    scene->no_default_light = options && options->no_default_light;
    rt_status st;
    if (has_extension(path, ".json"))
#ifdef RT_HAVE_JANSSON
        st = rt_scene_load_json(scene, path, err);
#else
        st = rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                          "this build has no JSON scene loader: jansson was not found when it "
                          "was configured (install libjansson-dev and configure again); .obj "
                          "scenes load without it");
#endif
    else if (has_extension(path, ".obj"))
        st = load_bare_obj(scene, path, err);
    else if (rt_gltf_is_gltf_path(path))
        st = rt_scene_load_gltf(scene, path, err);
    else
        st = rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, path, 0, 0,
                          "unknown scene type: expected a .json, .obj, .gltf or .glb file");
    if (st == RT_OK && rt_scene_triangle_count(scene) == 0)
        st = rt_error_set(err, RT_ERROR_PARSE, path, 0, 0,
                          "the scene is empty: no object has a triangle");
    if (st != RT_OK) {
        rt_scene_destroy(scene); /* nothing half-loaded */
        return st;
    }
    snprintf(scene->source, sizeof scene->source, "%s", path);
    *out = scene;
    return RT_OK;
}
