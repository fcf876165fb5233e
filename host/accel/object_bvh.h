/* SPDX-License-Identifier: Apache-2.0 */
/* object_bvh.h - the object BVH (Langr 2016, section 3.2.1): a BVH over the
 * objects' world-space boxes, rebuilt every frame.
 *
 * Each object's box is the root box of its selected keyframe's mesh BVH,
 * transformed by the object's matrix and boxed again (the 8 corners), so a
 * moved object costs no mesh rebuild. The tree is built by rt_bvh_build, the
 * same code as the mesh BVHs; its leaves reference object ids.
 */
#ifndef RT_OBJECT_BVH_H
#define RT_OBJECT_BVH_H

#include "accel/bvh.h"
#include "scene/scene.h"

/* World box of box under the row-major affine matrix m (p' = M p). */
rt_aabb rt_aabb_transform(const rt_aabb *box, const float m[16]);

/* Builds the object BVH of scene. mesh_bvhs is indexed by mesh id (one BVH
 * per mesh, mesh_count of them). Objects whose mesh is empty (no nodes) are
 * left out, so out->prim_count may be below object_count; out->prim_indices
 * holds object ids. options NULL: the default builder with one object per
 * leaf. Queued transforms are not applied here (rt_scene_commit does that). */
rt_status rt_object_bvh_build(const rt_scene *scene, const rt_bvh *mesh_bvhs,
                              const rt_build_options *options, rt_pool *pool, rt_bvh *out,
                              rt_error *err);

#endif /* RT_OBJECT_BVH_H */
