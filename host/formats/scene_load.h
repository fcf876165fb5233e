/* SPDX-License-Identifier: Apache-2.0 */
/* scene_load.h - scene files into a scene: .json scenes and bare .obj files. */
#ifndef RT_SCENE_LOAD_H
#define RT_SCENE_LOAD_H

#include "rt.h"

/* Loads a JSON scene into scene (which must be new and empty). path names the
 * file for messages and its folder resolves relative mesh paths. */
rt_status rt_scene_load_json(rt_scene *scene, const char *path, rt_error *err);

#endif /* RT_SCENE_LOAD_H */
