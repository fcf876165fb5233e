/* SPDX-License-Identifier: Apache-2.0 */
/* flat.h - the device layout of kernels/rt_layout.h as the host holds it:
 * plain arrays with absolute indices, no pointers between them. It is all a
 * backend sees of a scene (host/backend/backend.h), so every backend traces
 * the same bytes. layout/flatten.h makes it from a scene and its BVHs. */
#ifndef RT_FLAT_H
#define RT_FLAT_H

#include <stdint.h>

#include "rt.h"
#include "rt_shared.h"

typedef struct rt_flat {
    rt_scene_header hdr;
    rt_node *nodes;
    uint32_t node_count;
    rt_tri *tris;
    uint32_t *tri_ids;
    float *tri_normals; /* 9 per tri, or NULL when no mesh has normals */
    uint32_t *tri_mats; /* 1 per tri, or NULL when no mesh has per-triangle materials */
    uint32_t tri_count;
    rt_instance *instances;
    uint32_t *inst_ids;
    uint32_t inst_id_count;
    rt_material_d *materials;
    rt_light_d *lights;
    rt_kd_node *kd_nodes; /* every kd-tree mesh's nodes (NULL when none) */
    uint32_t kd_node_count;
} rt_flat;

/* A range of nodes or triangles of a layout (rewritten in place). */
typedef struct rt_flat_range {
    uint32_t first, count;
    uint32_t moved; /* triangles: 1 when only their vertices moved (a refit): the
                       triangle ids and materials stayed */
} rt_flat_range;

void rt_flat_free(rt_flat *flat);

/* The view the shared traversal reads. */
rt_scene_view rt_flat_view(const rt_flat *flat);

#endif /* RT_FLAT_H */
