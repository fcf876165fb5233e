/* SPDX-License-Identifier: Apache-2.0 */
/* fuzz_util.h - what the libFuzzer harnesses of tests/fuzz/ share: a private
 * scratch folder for the loaders that read files, and small renders.
 *
 * Each harness defines LLVMFuzzerTestOneInput. Built with RT_FUZZ=ON (clang)
 * it links libFuzzer; in every build it also links replay_main.c, which
 * runs the seed corpus and the regression inputs (tests/fuzz/regress/) as a
 * ctest. A harness aborts (abort(), or a sanitizer report) on a finding. */
#ifndef RT_FUZZ_UTIL_H
#define RT_FUZZ_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include "rt.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A scratch folder of this process (made at the first call, removed with its
 * files at exit), and a path name inside it (a static buffer per slot 0..3). */
const char *fuzz_dir(void);
const char *fuzz_path(int slot, const char *name);

/* Writes size bytes to path (aborts if it cannot: the harness is broken,
 * not the library). */
void fuzz_write(const char *path, const void *data, size_t size);

/* Renders scene at most side x side pixels (the camera's aspect kept only
 * roughly) on a 1-thread cpu renderer made once; returns rt_render's status.
 * A small image keeps every input fast while still building the BVHs,
 * flattening the scene and shading with its materials and lights. */
rt_status fuzz_render_small(rt_scene *scene, int side);

/* Aborts with a message on stderr when cond is false: a finding. */
void fuzz_check(int cond, const char *what);

#endif /* RT_FUZZ_UTIL_H */
