/* SPDX-License-Identifier: Apache-2.0 */
/* scene_describe.c - what a scene holds, for programs on rt.h
 * (rt_scene_describe, rt_mesh_describe, rt_object_describe): the scene's
 * own counts and features, read here so that nothing outside the library
 * reads struct rt_scene. */
#include <string.h>

#include "scene/scene.h"

rt_status rt_scene_describe(const rt_scene *scene, rt_scene_info *out) {
    if (!scene || !out) return RT_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    out->meshes = scene->mesh_count;
    out->objects = scene->object_count;
    out->materials = scene->material_count;
    out->lights = scene->light_count;
    out->triangles = rt_scene_triangle_count(scene);
    for (uint32_t i = 0; i < scene->mesh_count; i++)
        out->all_triangles += scene->meshes[i].triangle_count;
    rt_scene_features f = rt_scene_features_of(scene);
    out->reflection = f.reflection;
    out->refraction = f.refraction;
    out->instancing = f.instancing;
    out->normals = f.normals;
    out->keyframes = f.keyframes;
    out->tri_materials = f.tri_materials;
    out->animated = rt_scene_is_animated(scene);
    for (uint32_t i = 0; i < scene->object_count; i++) {
        const rt_object_data *o = &scene->objects[i];
        out->keyed_objects += o->transform_key_count > 0;
        if (o->keyframe_rate > 0.0f && o->mesh_count > 1) {
            out->blended_objects += o->interpolate != 0;
            out->switched_objects += o->interpolate == 0;
        }
    }
    out->camera_path_keys = scene->camera_path_count;
    return RT_OK;
}

rt_status rt_mesh_describe(const rt_scene *scene, uint32_t mesh_id, rt_mesh_info *out) {
    if (!scene || !out || mesh_id >= scene->mesh_count) return RT_ERROR_INVALID_ARGUMENT;
    const rt_mesh_data *m = &scene->meshes[mesh_id];
    memset(out, 0, sizeof *out);
    out->name = m->name;
    out->triangles = m->triangle_count;
    out->vertices = m->vertex_count;
    out->normals = m->normals != NULL;
    out->update = (rt_update_policy)m->update_policy;
    out->accel = rt_mesh_accel(scene, mesh_id);
    return RT_OK;
}

rt_status rt_object_describe(const rt_scene *scene, uint32_t object_id, rt_object_info *out) {
    if (!scene || !out || object_id >= scene->object_count) return RT_ERROR_INVALID_ARGUMENT;
    const rt_object_data *o = &scene->objects[object_id];
    memset(out, 0, sizeof *out);
    out->keyframes = o->mesh_count;
    out->selected = o->selected;
    out->material = o->material;
    out->keyframe_rate = o->keyframe_rate;
    out->interpolate = o->interpolate;
    out->morphing = o->morphing;
    out->transform_keys = o->transform_key_count;
    out->mask = o->mask;
    return RT_OK;
}
