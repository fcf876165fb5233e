/* scene_load.h - scene files into a scene: .json scenes and bare .obj files. */
#ifndef RT_SCENE_LOAD_H
#define RT_SCENE_LOAD_H

#include "rt.h"

/* Loads a JSON scene into scene (which must be new and empty). path names the
 * file for messages and its folder resolves relative mesh paths. */
rt_status rt_scene_load_json(rt_scene *scene, const char *path, rt_error *err);

/* Adds an OBJ file to scene as one mesh (no object, camera or lights). The
 * materials of its .mtl, if any, become scene materials that the mesh's
 * triangles use; triangles without one take their object's material. */
rt_status rt_scene_add_obj(rt_scene *scene, const char *path, uint32_t *mesh_id, rt_error *err);

#endif /* RT_SCENE_LOAD_H */
