/* flatten.h - the scene and its BVHs as the device layout of
 * kernels/rt_layout.h: plain arrays with absolute indices, no pointers. Every
 * backend reads only this, so every backend traces the same bytes. */
#ifndef RT_FLATTEN_H
#define RT_FLATTEN_H

#include <stddef.h>
#include <stdint.h>

#include "accel/bvh.h"
#include "rt_shared.h"
#include "scene/scene.h"

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
} rt_flat;

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
                     const rt_flat_options *options, rt_flat *out, char *msg, size_t msg_size);

void rt_flat_free(rt_flat *flat);

/* The view the shared traversal reads. */
rt_scene_view rt_flat_view(const rt_flat *flat);

/* Is the object's transform exactly the identity? */
int rt_transform_is_identity(const float m[16]);

/* One box per triangle of the mesh (boxes: triangle_count entries). */
void rt_mesh_tri_boxes(const rt_mesh_data *mesh, rt_aabb *boxes);

/* World-space box of an object's selected mesh, slightly widened when the
 * object has a transform (the input of the object BVH). An empty mesh gives a
 * point box at the object's origin. */
void rt_object_world_box(const rt_scene *scene, uint32_t object, rt_aabb *box);

#endif /* RT_FLATTEN_H */
