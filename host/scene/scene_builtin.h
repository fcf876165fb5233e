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

/* Builds the named scene into a new scene. */
rt_status rt_scene_builtin(const char *name, rt_scene **out, rt_error *err);

#endif /* RT_SCENE_BUILTIN_H */
