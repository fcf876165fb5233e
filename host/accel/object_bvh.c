/* SPDX-License-Identifier: Apache-2.0 */
/* object_bvh.c - the object BVH over the objects' world-space boxes (object_bvh.h). */
#include "accel/object_bvh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"

rt_aabb rt_aabb_transform(const rt_aabb *box, const float m[16]) {
    rt_aabb out;
    for (int k = 0; k < 3; k++) {
        out.bmin[k] = 0.0f;
        out.bmax[k] = 0.0f;
    }
    for (int corner = 0; corner < 8; corner++) {
        float p[3] = {(corner & 1) ? box->bmax[0] : box->bmin[0],
                      (corner & 2) ? box->bmax[1] : box->bmin[1],
                      (corner & 4) ? box->bmax[2] : box->bmin[2]};
        for (int r = 0; r < 3; r++) {
            float q = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
            if (corner == 0 || q < out.bmin[r]) out.bmin[r] = q;
            if (corner == 0 || q > out.bmax[r]) out.bmax[r] = q;
        }
    }
    return out;
}

rt_status rt_object_bvh_build(const rt_scene *scene, const rt_bvh *mesh_bvhs,
                              const rt_build_options *options, rt_pool *pool, rt_bvh *out,
                              rt_error *err) {
    if (!out) return RT_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    if (!scene || (!mesh_bvhs && scene->mesh_count)) return RT_ERROR_INVALID_ARGUMENT;
    rt_build_options o;
    if (options) {
        o = *options;
    } else {
        o = rt_build_options_default();
        o.leaf_size = 1;
    }
    uint32_t n = scene->object_count;
    rt_aabb *boxes = malloc(sizeof *boxes * (n ? n : 1));
    uint32_t *ids = malloc(sizeof *ids * (n ? n : 1));
    if (!boxes || !ids) {
        free(boxes);
        free(ids);
        rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "object BVH: out of memory");
        return RT_ERROR_OUT_OF_MEMORY;
    }
    uint32_t used = 0;
    for (uint32_t i = 0; i < n; i++) {
        const rt_object_data *obj = &scene->objects[i];
        if (obj->mesh_count == 0) continue;
        const rt_bvh *mesh = &mesh_bvhs[rt_object_shown_mesh(obj)];
        if (mesh->node_count == 0) continue;
        rt_aabb local;
        memcpy(local.bmin, mesh->nodes[0].bmin, sizeof local.bmin);
        memcpy(local.bmax, mesh->nodes[0].bmax, sizeof local.bmax);
        boxes[used] = rt_aabb_transform(&local, obj->transform);
        /* The corners were transformed with rounding, and rays are moved
         * into object space with rounding of their own: a relative 2^-20
         * keeps hits found in object space inside the box. Widened here,
         * before the build, so that every node is the exact union of its
         * objects' boxes (rt_hit_accepted relies on boxes nesting). */
        for (int k = 0; k < 3; k++) {
            rt_aabb *b = &boxes[used];
            const float pad = (fabsf(b->bmin[k]) + fabsf(b->bmax[k])) * 0x1p-20f;
            b->bmin[k] -= pad;
            b->bmax[k] += pad;
        }
        ids[used++] = i;
    }
    rt_status st = rt_bvh_build(boxes, used, &o, pool, out, err);
    if (st == RT_OK) {
        /* Leaves reference positions in the compacted box list: make them
         * object ids. */
        for (uint32_t i = 0; i < out->prim_count; i++)
            out->prim_indices[i] = ids[out->prim_indices[i]];
    }
    free(boxes);
    free(ids);
    return st;
}
