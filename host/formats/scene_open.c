/* SPDX-License-Identifier: Apache-2.0 */
/* scene_open.c - rt_scene_open (rt.h): a scene by the name a user gives,
 * "builtin:NAME" or a file, so that every program takes both the same way. */
#include <string.h>

#include "rt.h"

rt_status rt_scene_open(const char *source, rt_scene **out, rt_error *err) {
    static const char prefix[] = "builtin:";
    if (source && strncmp(source, prefix, sizeof prefix - 1) == 0)
        return rt_scene_builtin(source + sizeof prefix - 1, out, err);
    return rt_scene_load(source, out, err);
}
