/* flatten.h - a scene and its BVHs into the device layout (layout/flat.h). */
#ifndef RT_FLATTEN_H
#define RT_FLATTEN_H

#include <stddef.h>
#include <stdint.h>

#include "accel/bvh.h"
#include "accel/kd.h"
#include "layout/flat.h"
#include "scene/scene.h"

/* Flattening options. */
typedef struct rt_flat_options {
    uint32_t tri_method; /* RT_TRI_*, default RT_TRI_WATERTIGHT */
    uint32_t max_depth;  /* reflection/refraction bounces, <= RT_MAX_DEPTH [5] */
    float min_weight;    /* contribution cutoff [1/256] */
} rt_flat_options;

rt_flat_options rt_flat_options_default(void);

/* mesh_bvhs holds one BVH per scene mesh (indexed by mesh id; meshes that no
 * object shows may be empty) built over the mesh's triangle boxes. top is the
 * object BVH over the objects' world boxes (primitive = object index); it may
 * be NULL when the scene has one object with the identity transform. */
rt_status rt_flatten(const rt_scene *scene, const rt_bvh *mesh_bvhs, const rt_bvh *top,
                     const rt_flat_options *options, rt_flat *out, rt_error *err);

/* As rt_flatten, with a choice of structure per mesh: where mesh_kds is not
 * NULL and mesh_kds[m] has nodes, mesh m goes into the layout as that
 * kd-tree (RT_INST_KD; its leaves' entries in 'tris', a triangle once per
 * leaf) and mesh_bvhs[m] is not read. */
rt_status rt_flatten_accel(const rt_scene *scene, const rt_bvh *mesh_bvhs, const rt_kd *mesh_kds,
                           const rt_bvh *top, const rt_flat_options *options, rt_flat *out,
                           rt_error *err);

#endif /* RT_FLATTEN_H */
