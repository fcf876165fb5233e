/* SPDX-License-Identifier: Apache-2.0 */
/* scene_obj.h - an OBJ file into a scene as one mesh (the JSON loader's
 * meshes and a bare .obj scene both come this way). */
#ifndef RT_SCENE_OBJ_H
#define RT_SCENE_OBJ_H

#include <stdint.h>

#include "rt.h"

/* Adds an OBJ file to scene as one mesh (no object, camera or lights). The
 * materials of its .mtl, if any, become scene materials that the mesh's
 * triangles use; triangles without one take their object's material. */
rt_status rt_scene_add_obj(rt_scene *scene, const char *path, uint32_t *mesh_id, rt_error *err);

#endif /* RT_SCENE_OBJ_H */
