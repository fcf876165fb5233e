/* SPDX-License-Identifier: Apache-2.0 */
/* scene_save.h - a scene as a JSON scene file plus one OBJ file per mesh. */
#ifndef RT_SCENE_SAVE_H
#define RT_SCENE_SAVE_H

#include "rt.h"

/* rt_scene_save_json, a scene as dir/name.json plus one OBJ file per mesh,
 * is public: declared (with its contract) in rt.h. */

/* rt_scene_save_check (whether it could write into dir) too. */

#endif /* RT_SCENE_SAVE_H */
