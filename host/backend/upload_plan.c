/* SPDX-License-Identifier: Apache-2.0 */
/* upload_plan.c - see upload_plan.h. */
#include "backend/upload_plan.h"

#include <stdlib.h>
#include <string.h>

/* What identifies the mesh part of the layout (mesh BVH nodes, triangle
 * arrays, kd-tree nodes): unchanged while no mesh was rebuilt and every
 * instance still points at the same place. */
static uint32_t *mesh_signature(const rt_backend_layout *layout, size_t *len) {
    const rt_flat *f = layout->flat;
    size_t n = 6 + 3 * (size_t)f->hdr.instance_count;
    uint32_t *sig = malloc(n * sizeof *sig);
    if (!sig) return NULL;
    sig[0] = layout->mesh_generation;
    sig[1] = (f->hdr.flags & RT_SCENE_SINGLE) ? f->node_count : f->hdr.top_root;
    sig[2] = f->tri_count;
    sig[3] = f->hdr.flags & (RT_SCENE_NORMALS | RT_SCENE_TRI_MATS);
    sig[4] = f->hdr.instance_count;
    sig[5] = f->kd_node_count;
    for (uint32_t i = 0; i < f->hdr.instance_count; i++) {
        sig[6 + 3 * i] = f->instances[i].mesh;
        sig[7 + 3 * i] = f->instances[i].root;
        sig[8 + 3 * i] = f->instances[i].tri_first;
    }
    *len = n;
    return sig;
}

/* Which arrays are part of the mesh data (uploaded only when the meshes
 * changed). */
static const int is_mesh[RT_UP_COUNT] = {0, 0, 1, 1, 1, 1, 0, 0, 0, 0, 1};

/* The arrays of the layout: where and how long. */
static void arrays(const rt_flat *f, const void *data[RT_UP_COUNT], size_t bytes[RT_UP_COUNT]) {
    size_t tri_n = f->tri_count;
    const void *d[RT_UP_COUNT] = {&f->hdr,        f->nodes,    f->tris,      f->tri_ids,
                                  f->tri_normals, f->tri_mats, f->instances, f->inst_ids,
                                  f->materials,   f->lights,   f->kd_nodes};
    const size_t b[RT_UP_COUNT] = {sizeof f->hdr,
                                   sizeof(rt_node) * f->node_count,
                                   sizeof(rt_tri) * tri_n,
                                   sizeof(uint32_t) * tri_n,
                                   f->tri_normals ? 9 * sizeof(float) * tri_n : 0,
                                   f->tri_mats ? sizeof(uint32_t) * tri_n : 0,
                                   sizeof(rt_instance) * f->hdr.instance_count,
                                   sizeof(uint32_t) * f->inst_id_count,
                                   sizeof(rt_material_d) * f->hdr.material_count,
                                   sizeof(rt_light_d) * f->hdr.light_count,
                                   sizeof(rt_kd_node) * f->kd_node_count};
    for (int i = 0; i < RT_UP_COUNT; i++) {
        data[i] = d[i];
        bytes[i] = b[i];
    }
}

rt_status rt_upload_plan_make(const rt_upload_memo *memo, const rt_backend_layout *layout,
                              const size_t cap[RT_UP_COUNT], rt_upload_plan *p) {
    const rt_flat *f = layout->flat;
    memset(p, 0, sizeof *p);
    p->sig = mesh_signature(layout, &p->sig_len);
    if (!p->sig) return RT_ERROR_OUT_OF_MEMORY;
    arrays(f, p->data, p->bytes);
    p->mesh_node_bytes = sizeof(rt_node) * p->sig[1];
    p->mesh_same = memo->valid && memo->mesh_sig && memo->mesh_sig_len == p->sig_len &&
                   memcmp(memo->mesh_sig, p->sig, p->sig_len * sizeof *p->sig) == 0;
    int same_generation = p->mesh_same && memo->generation == layout->layout_generation;
    if (same_generation && memcmp(&memo->hdr, &f->hdr, sizeof f->hdr) == 0) {
        p->nothing = 1;
        return RT_OK;
    }
    if (same_generation) {
        p->header_only = 1; /* the camera moved, or a render option changed */
        return RT_OK;
    }
    /* The layout was rewritten in place from the generation the device
     * holds: the changed node and triangle ranges and the per-frame arrays
     * suffice, unless a buffer must grow. */
    p->partial =
        memo->valid && layout->base_generation && memo->generation == layout->base_generation;
    for (int i = 0; p->partial && i < RT_UP_COUNT; i++)
        p->partial = p->bytes[i] <= cap[i] || p->bytes[i] < 16;
    p->buffers = !p->partial;
    return RT_OK;
}

rt_status rt_upload_plan_run(const rt_upload_plan *p, const rt_backend_layout *layout,
                             const int remade[RT_UP_COUNT],
                             rt_status (*emit)(void *user, const rt_upload_copy *c), void *user) {
    const rt_flat *f = layout->flat;
    const void *const *data = p->data;
    const size_t *bytes = p->bytes;
    rt_status st = RT_OK;
    rt_upload_copy c;
    if (p->nothing) return RT_OK;
    if (p->header_only) {
        c = (rt_upload_copy){RT_UP_HDR, 0, &f->hdr, sizeof f->hdr};
        return emit(user, &c);
    }
    if (p->partial) {
        for (uint32_t r = 0; r < layout->dirty_node_ranges && st == RT_OK; r++) {
            const rt_flat_range *g = &layout->dirty_nodes[r];
            c = (rt_upload_copy){RT_UP_NODES, sizeof(rt_node) * g->first, f->nodes + g->first,
                                 sizeof(rt_node) * g->count};
            st = emit(user, &c);
        }
        for (uint32_t r = 0; r < layout->dirty_tri_ranges && st == RT_OK; r++) {
            const rt_flat_range *g = &layout->dirty_tris[r];
            rt_upload_copy run[4] = {{RT_UP_TRIS, sizeof(rt_tri) * g->first, f->tris + g->first,
                                      sizeof(rt_tri) * g->count},
                                     /* A refit moved vertices only: ids and materials stayed. */
                                     {RT_UP_TRI_IDS, sizeof(uint32_t) * g->first,
                                      f->tri_ids + g->first,
                                      g->moved ? 0 : sizeof(uint32_t) * g->count},
                                     {RT_UP_NORMALS, 9 * sizeof(float) * g->first,
                                      f->tri_normals ? f->tri_normals + 9 * (size_t)g->first : NULL,
                                      f->tri_normals ? 9 * sizeof(float) * g->count : 0},
                                     {RT_UP_TRI_MATS, sizeof(uint32_t) * g->first,
                                      f->tri_mats ? f->tri_mats + g->first : NULL,
                                      f->tri_mats && !g->moved ? sizeof(uint32_t) * g->count : 0}};
            for (int k = 0; k < 4 && st == RT_OK; k++)
                if (run[k].bytes) st = emit(user, &run[k]);
        }
    }
    for (int i = 0; i < RT_UP_COUNT && st == RT_OK; i++) {
        if (!bytes[i]) continue;
        if (p->partial && (is_mesh[i] || i == RT_UP_NODES)) continue;
        int all = (p->buffers && remade[i]) || !p->mesh_same;
        if (i == RT_UP_NODES) {
            /* Mesh BVH nodes first, then the object BVH: only the latter
             * moves with the objects. */
            size_t from = all ? 0 : p->mesh_node_bytes;
            c = (rt_upload_copy){i, from, (const char *)data[i] + from, bytes[i] - from};
            if (c.bytes) st = emit(user, &c);
        } else if (!is_mesh[i] || all) {
            c = (rt_upload_copy){i, 0, data[i], bytes[i]};
            st = emit(user, &c);
        }
    }
    return st;
}

void rt_upload_plan_finish(rt_upload_plan *p, rt_upload_memo *memo, const rt_backend_layout *layout,
                           int ok) {
    if (!ok) {
        memo->valid = 0;
    } else if (!p->nothing) {
        if (!p->header_only) {
            free(memo->mesh_sig);
            memo->mesh_sig = p->sig;
            memo->mesh_sig_len = p->sig_len;
            p->sig = NULL;
            memo->valid = 1;
            memo->generation = layout->layout_generation;
        }
        memo->hdr = layout->flat->hdr;
    }
    free(p->sig);
    p->sig = NULL;
}

void rt_upload_memo_free(rt_upload_memo *memo) {
    free(memo->mesh_sig);
    memset(memo, 0, sizeof *memo);
}
