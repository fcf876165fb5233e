/* scene_json.c - placeholder until the JSON scene loader lands. */
#include "scene_load.h"

#include "error.h"

rt_status rt_scene_load_json(rt_scene *scene, const char *path, rt_error *err) {
    (void)scene;
    return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0, "JSON scenes are not built yet");
}
