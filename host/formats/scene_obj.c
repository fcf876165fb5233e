/* SPDX-License-Identifier: Apache-2.0 */
/* scene_obj.c - an OBJ file (and its MTL materials) as a mesh of a scene. */
#include "formats/scene_obj.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "formats/obj_load.h"
#include "scene/scene.h"

/* An MTL material as a Phong material. */
static rt_material material_from_mtl(const rt_obj_material *m) {
    rt_material out = rt_material_default();
    memcpy(out.color, m->kd, sizeof out.color);
    out.specular = (m->ks[0] + m->ks[1] + m->ks[2]) / 3.0f;
    out.shininess = (int)lroundf(m->ns < 0.0f ? 0.0f : (m->ns > 100000.0f ? 100000.0f : m->ns));
    out.transparency = m->d < 1.0f && m->d >= 0.0f ? 1.0f - m->d : 0.0f;
    out.ior = m->ni > 0.0f ? m->ni : 1.0f;
    memcpy(out.emission, m->ke, sizeof out.emission);
    return out;
}

rt_status rt_scene_add_obj(rt_scene *scene, const char *path, uint32_t *mesh_id, rt_error *err) {
    rt_obj_mesh obj;
    rt_status st = rt_obj_load(path, &obj, err);
    if (st != RT_OK) return st;
    if (obj.triangle_count == 0) {
        rt_obj_free(&obj);
        return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0, "the file has no faces");
    }
    uint32_t id;
    st = rt_mesh_create(scene, &id);
    if (st == RT_OK)
        st = rt_mesh_add_triangles(scene, id, obj.positions, obj.normals, obj.vertex_count,
                                   obj.indices, obj.triangle_count);
    if (st == RT_OK && obj.tri_materials && obj.material_count) {
        /* Each MTL material becomes a scene material; triangles without one
         * keep the object's. */
        uint32_t *map = malloc(obj.material_count * sizeof *map);
        uint32_t *tri = malloc((size_t)obj.triangle_count * sizeof *tri);
        if (!map || !tri) st = RT_ERROR_OUT_OF_MEMORY;
        for (uint32_t i = 0; st == RT_OK && i < obj.material_count; i++) {
            rt_material m = material_from_mtl(&obj.materials[i]);
            st = rt_material_add(scene, &m, &map[i]);
        }
        if (st == RT_OK) {
            for (uint32_t t = 0; t < obj.triangle_count; t++)
                tri[t] = obj.tri_materials[t] < obj.material_count ? map[obj.tri_materials[t]]
                                                                   : UINT32_MAX;
            scene->meshes[id].tri_materials = tri;
            tri = NULL;
        }
        free(map);
        free(tri);
    }
    if (st == RT_OK) {
        rt_scene_add_notice(scene, obj.notice);
        const char *base = strrchr(path, '/');
        snprintf(scene->meshes[id].name, sizeof scene->meshes[id].name, "%s",
                 base ? base + 1 : path);
        *mesh_id = id;
    } else {
        rt_error_set(err, st, path, 0, 0, "%s",
                     scene->error.message[0] ? scene->error.message : rt_status_string(st));
    }
    rt_obj_free(&obj);
    return st;
}
