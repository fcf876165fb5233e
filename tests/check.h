/* SPDX-License-Identifier: Apache-2.0 */
/* check.h - a few assertion macros for plain ctest programs.
 *
 * A failed CHECK prints the file, line and expression and counts a failure;
 * the program goes on so that one run shows every failure. TEST_END returns
 * 1 if anything failed. A test that cannot run here calls test_skip(), which
 * prints why and exits 77 (ctest reports it as skipped). */
#ifndef RT_CHECK_H
#define RT_CHECK_H

#include <stdio.h>
#include <string.h>

#include "rt.h"

extern int test_failures;
extern int test_checks;

#define CHECK(cond)                                                                                \
    do {                                                                                           \
        test_checks++;                                                                             \
        if (!(cond)) {                                                                             \
            test_failures++;                                                                       \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);               \
        }                                                                                          \
    } while (0)

#define CHECK_MSG(cond, ...)                                                                       \
    do {                                                                                           \
        test_checks++;                                                                             \
        if (!(cond)) {                                                                             \
            test_failures++;                                                                       \
            fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);               \
            fprintf(stderr, __VA_ARGS__);                                                          \
            fputc('\n', stderr);                                                                   \
        }                                                                                          \
    } while (0)

#define CHECK_EQ_INT(a, b)                                                                         \
    do {                                                                                           \
        long long va_ = (long long)(a), vb_ = (long long)(b);                                      \
        CHECK_MSG(va_ == vb_, "%lld != %lld", va_, vb_);                                           \
    } while (0)

/* Checks that haystack contains needle. */
#define CHECK_CONTAINS(haystack, needle)                                                           \
    CHECK_MSG(strstr((haystack), (needle)) != NULL, "\"%s\" does not contain \"%s\"", (haystack),  \
              (needle))

#define TEST_END() test_report(__FILE__)

int test_report(const char *name);

/* A renderer on backend with threads (0: all cores), made at the first call
 * with these two and kept (with its BVHs) until the program exits. Fails the
 * test and returns NULL when it cannot be made. */
rt_renderer *test_renderer(const char *backend, int threads);

/* A new renderer with these options, freed when the program exits; NULL
 * (with the reason in err) when it cannot be made. */
rt_renderer *test_renderer_with(const rt_renderer_options *options, rt_error *err);

/* The flattened layout (layout/flat.h) a cpu renderer on threads threads
 * (test_renderer) makes of s, valid until that renderer renders again; NULL
 * (and a failed check) on failure. Tests of the shared maths read it. */
struct rt_flat;
const struct rt_flat *test_layout(rt_scene *s, int threads);

/* Whether two framebuffers have the same size, channels and float bits. */
int test_same_fb(const rt_framebuffer *a, const rt_framebuffer *b);

/* Prints "skipped: reason" and exits 77. */
void test_skip(const char *reason);

/* $RT_SOURCE_DIR/rel (the repository root) in a static buffer. */
const char *test_source_path(const char *rel);

/* $RT_SHARED_SCENES/rel, or NULL when the shared scenes are not present. */
const char *test_shared_scene(const char *rel);

/* Writes text to a new file in a per-process temporary folder and returns its
 * path (static buffer, valid until the next call). */
const char *test_write_temp(const char *name, const char *text);

/* The built-in scene 'name' with its camera set to width x height; NULL (and
 * a failed check) when it cannot be built. */
struct rt_scene *test_builtin_scene(const char *name, int width, int height);

/* A committed scene of one object with the default material and one mesh
 * of verts vertices (pos[3i .. 3i + 2]) and tris triangles (idx[3t ..
 * 3t + 2]); NULL after a failed CHECK. */
struct rt_scene *test_mesh_scene(const float *pos, uint32_t verts, const uint32_t *idx,
                                 uint32_t tris);

/* test_mesh_scene of tris independent triangles, triangle i at pos[9i ..
 * 9i + 8]. */
struct rt_scene *test_soup_scene(const float *pos, uint32_t tris);

/* A bumpy terrain of cells x cells square cells 0.25 across far from the
 * origin (corner (1500, 1200, -1300), heights within 0.0125 of y = 1200),
 * two triangles per cell, seen by a 64x64 camera just above it. *pos gets a
 * malloc'ed copy of its (cells + 1)^2 vertices, row by row along z. */
struct rt_scene *test_far_terrain(int cells, float **pos);

/* A JSON scene of the ten keyframes of a shared animation (prefix: the
 * path below the shared scenes without "_NN.obj", e.g.
 * "brainstem_anim/brainstem"), blended at 5 keyframes a second, beside a
 * still copy of keyframe 0; keyframe 0 gets "update": k0_update unless that
 * is NULL. Written to the temporary file named file; returns its path, or
 * NULL when the shared scenes are not here. */
const char *test_shared_anim(const char *prefix, const char *k0_update, const char *file);

#endif /* RT_CHECK_H */
