/* SPDX-License-Identifier: Apache-2.0 */
/* scene_remove.c - removing lights and objects (rt_light_remove,
 * rt_object_remove).
 *
 * Ids stay dense: the ones after the removed entry move down by one, so the
 * scene is the scene that was built without it (same ids, same order, and
 * so the same object BVH and the same image). The scene's version is
 * bumped; a renderer then sees other light or object counts and makes its
 * layout anew (render/accel_cache.c), while its per-mesh BVHs, keyed by mesh
 * id, stay valid: no mesh is removed. */
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

rt_status rt_light_remove(rt_scene *scene, uint32_t light_id) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (light_id >= scene->light_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "light %u does not exist (%u lights)", light_id, scene->light_count);
    memmove(&scene->lights[light_id], &scene->lights[light_id + 1],
            sizeof(rt_light_data) * (scene->light_count - light_id - 1));
    scene->light_count--;
    scene->version++;
    return RT_OK;
}

/* Frees a blend mesh's arrays and leaves it empty (no vertices, no
 * triangles): shown by no object, it costs nothing, and removing it would
 * move every later mesh's id. */
static void empty_blend_mesh(rt_mesh_data *m) {
    rt_mesh_data_free_arrays(m);
    m->vertex_count = m->vertex_capacity = 0;
    m->triangle_count = m->triangle_capacity = 0;
    m->version++;
    m->topology_version++;
}

rt_status rt_object_remove(rt_scene *scene, uint32_t object_id) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (object_id >= scene->object_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "object %u does not exist (%u objects)", object_id,
                             scene->object_count);
    rt_object_data *o = &scene->objects[object_id];
    if (o->morph_mesh < scene->mesh_count) empty_blend_mesh(&scene->meshes[o->morph_mesh]);
    free(o->meshes);
    free(o->transform_keys);
    memmove(o, o + 1, sizeof(rt_object_data) * (scene->object_count - object_id - 1));
    scene->object_count--;
    scene->version++;
    return RT_OK;
}
