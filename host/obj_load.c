/* obj_load.c - placeholder until the OBJ loader lands. */
#include "obj_load.h"

#include <string.h>

#include "error.h"

rt_status rt_obj_parse(const char *text, size_t len, const char *name, const char *base_dir,
                       rt_obj_mesh *out, rt_error *err) {
    memset(out, 0, sizeof *out);
    return rt_error_set(err, RT_ERROR_UNSUPPORTED, name, 0, 0, "OBJ loading is not built yet");
}

rt_status rt_obj_load(const char *path, rt_obj_mesh *out, rt_error *err) {
    return rt_obj_parse(NULL, 0, path, NULL, out, err);
}

void rt_obj_free(rt_obj_mesh *mesh) {
    memset(mesh, 0, sizeof *mesh);
}
