/* SPDX-License-Identifier: Apache-2.0 */
/* scene_boxes.c - triangle and object boxes of a scene for the builders. */
#include "accel/scene_boxes.h"

#include <math.h>

void rt_mesh_tri_boxes(const rt_mesh_data *m, rt_aabb *boxes) {
    for (uint32_t t = 0; t < m->triangle_count; t++)
        rt_tri_box(m->positions, m->indices + 3 * (size_t)t, &boxes[t]);
}

void rt_object_world_box(const rt_scene *scene, uint32_t object, rt_aabb *box) {
    const rt_object_data *ob = &scene->objects[object];
    const rt_mesh_data *m = &scene->meshes[rt_object_shown_mesh(ob)];
    const float *M = ob->transform;
    for (int k = 0; k < 3; k++) {
        box->bmin[k] = INFINITY;
        box->bmax[k] = -INFINITY;
    }
    /* Transforms every vertex (tighter than the 8 corners of the mesh box);
     * then widens by a few ulps so that rounding in the ray transform cannot
     * miss a surface on the box's edge. */
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *p = m->positions + 3 * (size_t)v;
        for (int k = 0; k < 3; k++) {
            float w =
                ((M[4 * k] * p[0] + M[4 * k + 1] * p[1]) + M[4 * k + 2] * p[2]) + M[4 * k + 3];
            if (w < box->bmin[k]) box->bmin[k] = w;
            if (w > box->bmax[k]) box->bmax[k] = w;
        }
    }
    if (!m->vertex_count)
        for (int k = 0; k < 3; k++) box->bmin[k] = box->bmax[k] = M[4 * k + 3];
    if (!rt_transform_is_identity(M))
        for (int k = 0; k < 3; k++) {
            float pad = (fabsf(box->bmin[k]) + fabsf(box->bmax[k])) * 1e-6f;
            box->bmin[k] -= pad;
            box->bmax[k] += pad;
        }
}
