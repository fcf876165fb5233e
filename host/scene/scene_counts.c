/* SPDX-License-Identifier: Apache-2.0 */
/* scene_counts.c - how many meshes and objects a scene holds (rt.h), for
 * callers that check ids before using them (the Python package). */
#include "scene/scene.h"

uint32_t rt_scene_mesh_count(const rt_scene *scene) {
    return scene ? scene->mesh_count : 0;
}

uint32_t rt_scene_object_count(const rt_scene *scene) {
    return scene ? scene->object_count : 0;
}
