/* scene_save.h - a scene as a JSON scene file plus one OBJ file per mesh. */
#ifndef RT_SCENE_SAVE_H
#define RT_SCENE_SAVE_H

#include "rt.h"

/* Writes dir/name.json and dir/name_MESH.obj for each mesh. MESH is the
 * mesh's name when every mesh has a plain name (letters, digits, '_', '-',
 * '.', not starting with '.') and no two are alike, else mesh_INDEX for
 * every mesh. Floats are written with %.9g so that loading the files gives
 * the same bits. Meshes with per-triangle materials are RT_ERROR_UNSUPPORTED.
 * Everything the JSON reader reads about time is written: objects'
 * "animation" and "transform_keys", the camera's "path", meshes' "update"
 * and "accel"; the blend meshes of morphing objects are left out (the loader
 * makes them again), so that the saved scene renders at every time as the
 * scene does. Each file is written whole or not at all
 * (base/atomic_file.h), the OBJ files first and the JSON file, which names
 * them, last; a scene that cannot be saved (per-triangle materials, a path
 * too long) is refused before any file is written. */
rt_status rt_scene_save_json(const rt_scene *scene, const char *dir, const char *name,
                             rt_error *err);

/* Whether rt_scene_save_json could write into dir (checked before the work
 * that makes the scene): dir is an existing, writable folder and
 * dir/name.json fits a path. RT_OK, or the fault with the folder named. */
rt_status rt_scene_save_check(const char *dir, const char *name, rt_error *err);

#endif /* RT_SCENE_SAVE_H */
