/* scene_save.h - a scene as a JSON scene file plus one OBJ file per mesh. */
#ifndef RT_SCENE_SAVE_H
#define RT_SCENE_SAVE_H

#include "rt.h"

/* Writes dir/name.json and dir/name_MESH.obj for each mesh. Floats are
 * written with %.9g so that loading the files gives the same bits. */
rt_status rt_scene_save_json(const rt_scene *scene, const char *dir, const char *name,
                             rt_error *err);

#endif /* RT_SCENE_SAVE_H */
