/* SPDX-License-Identifier: Apache-2.0 */
/* scene_boxes.h - the boxes the BVH builders take from a scene: one per
 * triangle of a mesh (a mesh BVH's input) and one per object in world space. */
#ifndef RT_SCENE_BOXES_H
#define RT_SCENE_BOXES_H

#include <stdint.h>

#include "accel/bvh.h"
#include "scene/scene.h"

/* One box per triangle of the mesh (boxes: triangle_count entries). */
void rt_mesh_tri_boxes(const rt_mesh_data *mesh, rt_aabb *boxes);

/* World-space box of an object's selected mesh, slightly widened when the
 * object has a transform. An empty mesh gives a point box at the object's
 * origin. */
void rt_object_world_box(const rt_scene *scene, uint32_t object, rt_aabb *box);

#endif /* RT_SCENE_BOXES_H */
