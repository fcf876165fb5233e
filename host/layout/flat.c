/* SPDX-License-Identifier: Apache-2.0 */
/* flat.c - the layout's lifetime and its view for the shared traversal. */
#include "layout/flat.h"

#include <stdlib.h>
#include <string.h>

void rt_flat_free(rt_flat *f) {
    if (!f) return;
    free(f->nodes);
    free(f->tris);
    free(f->tri_ids);
    free(f->tri_normals);
    free(f->tri_mats);
    free(f->instances);
    free(f->inst_ids);
    free(f->materials);
    free(f->lights);
    free(f->kd_nodes);
    memset(f, 0, sizeof *f);
}

rt_scene_view rt_flat_view(const rt_flat *f) {
    rt_scene_view v;
    v.hdr = &f->hdr;
    v.nodes = f->nodes;
    v.tris = f->tris;
    v.tri_ids = f->tri_ids;
    v.tri_normals = f->tri_normals;
    v.tri_mats = f->tri_mats;
    v.instances = f->instances;
    v.inst_ids = f->inst_ids;
    v.materials = f->materials;
    v.lights = f->lights;
    v.kd_nodes = f->kd_nodes;
    return v;
}
