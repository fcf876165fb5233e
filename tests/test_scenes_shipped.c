/* SPDX-License-Identifier: Apache-2.0 */
/* test_scenes_shipped.c - the JSON + OBJ files in scenes/ load to exactly the
 * built-in scenes they were generated from (`rtcl generate scenes`). */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "scene/scene.h"
#include "scene/scene_builtin.h"

#define SAME_BYTES(a, b, n) (((a) == NULL && (b) == NULL) || ((a) && (b) && !memcmp((a), (b), (n))))

static void compare_scenes(const char *name, const rt_scene *a, const rt_scene *b) {
    CHECK_MSG(a->mesh_count == b->mesh_count, "%s: mesh count", name);
    for (uint32_t i = 0; i < a->mesh_count && i < b->mesh_count; i++) {
        const rt_mesh_data *x = &a->meshes[i], *y = &b->meshes[i];
        CHECK_MSG(x->vertex_count == y->vertex_count && x->triangle_count == y->triangle_count,
                  "%s: mesh %u sizes", name, i);
        if (x->vertex_count != y->vertex_count || x->triangle_count != y->triangle_count) continue;
        CHECK_MSG(SAME_BYTES(x->positions, y->positions, 12 * (size_t)x->vertex_count),
                  "%s: mesh %u positions differ", name, i);
        CHECK_MSG(SAME_BYTES(x->normals, y->normals, 12 * (size_t)x->vertex_count),
                  "%s: mesh %u normals differ", name, i);
        CHECK_MSG(SAME_BYTES(x->indices, y->indices, 12 * (size_t)x->triangle_count),
                  "%s: mesh %u indices differ", name, i);
    }
    CHECK_MSG(a->material_count == b->material_count &&
                  SAME_BYTES(a->materials, b->materials, a->material_count * sizeof(rt_material)),
              "%s: materials differ", name);
    CHECK_MSG(a->light_count == b->light_count &&
                  SAME_BYTES(a->lights, b->lights, a->light_count * sizeof(rt_light_data)),
              "%s: lights differ", name);
    CHECK_MSG(a->object_count == b->object_count, "%s: object count", name);
    for (uint32_t i = 0; i < a->object_count && i < b->object_count; i++) {
        const rt_object_data *x = &a->objects[i], *y = &b->objects[i];
        CHECK_MSG(x->mesh_count == y->mesh_count && x->selected == y->selected &&
                      x->material == y->material &&
                      SAME_BYTES(x->meshes, y->meshes, x->mesh_count * sizeof(uint32_t)) &&
                      !memcmp(x->transform, y->transform, sizeof x->transform),
                  "%s: object %u differs", name, i);
    }
    CHECK_MSG(!memcmp(&a->camera, &b->camera, sizeof a->camera), "%s: camera differs", name);
    CHECK_MSG(!memcmp(a->ambient, b->ambient, sizeof a->ambient) &&
                  !memcmp(a->background, b->background, sizeof a->background),
              "%s: ambient or background differs", name);
}

int main(void) {
    for (int k = 0; rt_builtin_scene_names[k]; k++) {
        const char *name = rt_builtin_scene_names[k];
        char rel[256];
        snprintf(rel, sizeof rel, "scenes/%s.json", name);
        rt_scene *built, *loaded;
        rt_error err;
        CHECK(rt_scene_builtin(name, &built, &err) == RT_OK);
        rt_status st = rt_scene_load(test_source_path(rel), &loaded, &err);
        CHECK_MSG(st == RT_OK, "%s", err.message);
        if (st == RT_OK) {
            compare_scenes(name, built, loaded);
            rt_scene_destroy(loaded);
        }
        rt_scene_destroy(built);
    }
    return TEST_END();
}
