/* SPDX-License-Identifier: Apache-2.0 */
/* scene_builtin.h - the scenes the project ships, generated in code.
 *
 * The generator is the single source of these scenes: `rtcl generate DIR`
 * writes them as JSON + OBJ (the files in scenes/), and tests that must run
 * without file I/O (the aarch64 core build) build them here directly. */
#ifndef RT_SCENE_BUILTIN_H
#define RT_SCENE_BUILTIN_H

#include "rt.h"

/* Names of the built-in scenes, NULL-terminated. */
extern const char *const rt_builtin_scene_names[];

/* rt_scene_builtin and rt_builtin_scene_name are public (rt.h). */

#endif /* RT_SCENE_BUILTIN_H */
