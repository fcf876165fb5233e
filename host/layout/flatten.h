/* SPDX-License-Identifier: Apache-2.0 */
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
/* As rt_flatten_accel without kd-trees, taking the trees of the meshes
 * marked in take (indexed by mesh id; shown BVH meshes with triangles):
 * their nodes and entries go into the layout (a mesh that starts the
 * layout, as a one-mesh scene's does, gives it its arrays without a copy;
 * the others are freed as soon as they are copied), so that the tree is
 * never held twice (issue 31). Each taken BVH is then left as its root node
 * alone (node_count 1, no entries), for the object BVH; the layout holds
 * the rest. On failure a taken BVH may be left empty (node_count 0): the
 * caller builds it again. */
rt_status rt_flatten_take(const rt_scene *scene, rt_bvh *mesh_bvhs, const uint8_t *take,
                          const rt_bvh *top, const rt_flat_options *options, rt_flat *out,
                          rt_error *err);

/* What a layout was made of: which mesh each object shows, where each
 * shown mesh's nodes and triangles start and how many there are, and the
 * object BVH's size. While these stay, a new frame's layout is the old one
 * with some ranges rewritten (rt_flatten_update). */
typedef struct rt_flat_shape {
    uint32_t object_count, mesh_count;
    uint32_t *shown;                /* per object */
    uint32_t *node_base, *tri_base; /* per mesh; node_base UINT32_MAX: not in the layout */
    uint32_t *node_count, *tri_count;
    int single;
    uint32_t top_root, top_nodes, top_prims;
    uint32_t material_count, light_count;
} rt_flat_shape;

/* The shape of the layout rt_flatten makes of the same arguments. */
rt_status rt_flat_shape_of(const rt_scene *scene, const rt_bvh *mesh_bvhs, const rt_bvh *top,
                           rt_flat_shape *shape);
void rt_flat_shape_free(rt_flat_shape *shape);

/* What changed of a mesh since its layout was written. */
enum {
    RT_DIRTY_NONE = 0,
    RT_DIRTY_MOVED = 1, /* refitted: vertices and boxes moved, the tree's shape stayed */
    RT_DIRTY_ALL = 2    /* a new tree */
};

/* Rewrites flat (made by rt_flatten, of the given shape) in place for the
 * scene's new state: the nodes and triangles of the meshes marked dirty
 * (RT_DIRTY_*, indexed by mesh id), then the object BVH, instances,
 * materials, lights and header. RT_ERROR_UNSUPPORTED, with flat untouched, when the shape
 * changed (another mesh shown, a tree of another size, ...) or the layout
 * holds kd-tree meshes (static: always flattened anew): then flatten anew. *bytes gets the bytes
 * rewritten. */
rt_status rt_flatten_update(const rt_scene *scene, const rt_bvh *mesh_bvhs, const rt_bvh *top,
                            const uint8_t *dirty, rt_flat_shape *shape, rt_flat *flat,
                            uint64_t *bytes);

/* Rewrites the camera of flat's header (position, frame, size) from the
 * scene's camera, as rt_flatten writes it; nothing else changes. For a frame
 * where only the camera moved: the arrays stay valid as they are. */
void rt_flatten_camera(const rt_scene *scene, rt_flat *flat);

/* The layout's size in bytes, all arrays. */
uint64_t rt_flat_bytes(const rt_flat *flat);

#endif /* RT_FLATTEN_H */
