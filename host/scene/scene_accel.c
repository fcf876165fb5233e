/* SPDX-License-Identifier: Apache-2.0 */
/* scene_accel.c - the per-mesh choice of acceleration structure (rt.h). */
#include <string.h>

#include "scene/scene.h"

rt_status rt_mesh_set_accel(rt_scene *scene, uint32_t mesh_id, rt_accel accel) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (mesh_id >= scene->mesh_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "mesh %u does not exist", mesh_id);
    if (accel != RT_ACCEL_BVH && accel != RT_ACCEL_KD && accel != RT_ACCEL_KD_BINNED)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "unknown structure %d", (int)accel);
    rt_mesh_data *m = &scene->meshes[mesh_id];
    if (m->accel == (uint32_t)accel) return RT_OK;
    m->accel = (uint32_t)accel;
    /* The renderer rebuilds what a mesh's version says is stale. */
    m->version++;
    scene->version++;
    return RT_OK;
}

rt_status rt_scene_set_static_accel(rt_scene *scene, rt_accel accel) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    for (uint32_t m = 0; m < scene->mesh_count; m++) {
        int deforming = 0;
        for (uint32_t o = 0; o < scene->object_count && !deforming; o++) {
            const rt_object_data *ob = &scene->objects[o];
            if (ob->mesh_count < 2) continue;
            for (uint32_t k = 0; k < ob->mesh_count; k++) deforming |= ob->meshes[k] == m;
        }
        /* A morph target's blend and a mesh with a refitting policy deform too. */
        for (uint32_t o = 0; o < scene->object_count && !deforming; o++)
            deforming |= scene->objects[o].morph_mesh == m;
        deforming |= scene->meshes[m].update_policy != RT_UPDATE_SAH;
        if (deforming) continue;
        rt_status st = rt_mesh_set_accel(scene, m, accel);
        if (st != RT_OK) return st;
    }
    return RT_OK;
}

rt_accel rt_mesh_data_structure(const rt_mesh_data *m) {
    if (m->update_policy != RT_UPDATE_SAH) return RT_ACCEL_BVH;
    return (rt_accel)m->accel;
}

rt_accel rt_mesh_accel(const rt_scene *scene, uint32_t mesh_id) {
    if (!scene || mesh_id >= scene->mesh_count) return RT_ACCEL_BVH;
    return rt_mesh_data_structure(&scene->meshes[mesh_id]);
}

const char *rt_accel_name(rt_accel accel) {
    return accel == RT_ACCEL_KD ? "kd" : accel == RT_ACCEL_KD_BINNED ? "kd-binned" : "bvh";
}

int rt_accel_parse(const char *name, rt_accel *accel) {
    static const rt_accel all[] = {RT_ACCEL_BVH, RT_ACCEL_KD, RT_ACCEL_KD_BINNED};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        if (name && !strcmp(name, rt_accel_name(all[i]))) {
            *accel = all[i];
            return 1;
        }
    return 0;
}
