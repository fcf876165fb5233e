/* SPDX-License-Identifier: Apache-2.0 */
/* vk_backend.h - the Vulkan compute backend (host/backend/backend.h), built
 * where the build found the Vulkan loader and glslangValidator
 * (RT_HAVE_VULKAN); and hooks for the tests. */
#ifndef RT_VK_BACKEND_H
#define RT_VK_BACKEND_H

#include <stddef.h>
#include <stdint.h>

#include "backend/backend.h"
#include "rt_interface.h"

extern const rt_backend_ops rt_backend_vulkan;

/* The shipped SPIR-V modules by name ("rt_vk_main", "rt_vk_soft_test",
 * "rt_vk_interface_test"): words and size in bytes; NULL for an unknown name. */
const uint32_t *rt_vk_module(const char *name, size_t *bytes);

/* The module words with float-control execution modes for 32-bit floats
 * added (what the backend hands the driver, with the modes the device
 * supports): round to nearest even when rte, signed zeros, infs and NaNs
 * kept when signed_zero_inf_nan, denormals kept when denorm_preserve or
 * flushed when denorm_flush. Returns a malloc'ed copy (free()), its size in
 * *out_bytes, or NULL when out of memory or not SPIR-V. */
uint32_t *rt_vk_with_float_controls(const uint32_t *words, size_t bytes, int rte,
                                    int signed_zero_inf_nan, int denorm_preserve, int denorm_flush,
                                    size_t *out_bytes);

/* Runs rt_vk_soft_test.comp on device (NULL: the default): for count cases
 * of four operand bit patterns (operands[4i .. 4i+3] = a, b, c, d) writes
 * a / b, sqrt(a) and a*b - c*d (the _ftz variants when ftz) to
 * results[3i .. 3i+2]. For the tests that hold the GLSL mirror of the soft
 * maths to rt_soft_math.h. */
rt_status rt_vk_soft_math_run(const char *device, const uint32_t *operands, size_t count, int ftz,
                              uint32_t *results, rt_error *err);

/* Runs rt_vk_interface_test.comp (one invocation) on device (NULL: the
 * default), for the test that holds the host's struct offsets to the
 * shaders': the buffer at binding b gets bytes[b] bytes (0: a stub), filled
 * from in[b] where it is not NULL, and out[b] where not NULL gets them back
 * after the dispatch; push is the push constants. */
rt_status rt_vk_interface_probe(const char *device, const void *const in[RT_VK_BUF_COUNT],
                                void *const out[RT_VK_BUF_COUNT],
                                const size_t bytes[RT_VK_BUF_COUNT], const rt_vk_push *push,
                                rt_error *err);

/* Traces count rays (closest hits, or any hits when any_hit) through the
 * layout flat on device (NULL: the default) with the kd-tree traversal
 * keeping only the first kd_shared_cells cells of its stack (0..21) in
 * shared memory and the rest in its private overflow array (the backend
 * keeps 21 there, which only trees deeper than any test scene's outgrow).
 * For the test that runs that overflow path. */
rt_status rt_vk_trace_kd_stack(const char *device, const struct rt_flat *flat, const rt_ray *rays,
                               size_t count, int any_hit, uint32_t kd_shared_cells, rt_hit_d *hits,
                               rt_error *err);

/* Fault injection for the test of the loop-limit canary (rt_vk_main.comp):
 * every first-pass dispatch of this process first spends ballast loop
 * iterations (0: none, the default), and items the canary marks are traced
 * again alone only when rerun (1, the default). Not thread-safe; tests only. */
void rt_vk_test_loop_limit(uint32_t ballast, int rerun);

/* Fault injection for the test of resumes (rt_vk_resume.glsl): every
 * dispatch that traces items alone (re-runs and resumes) first spends
 * ballast loop iterations (0: none, the default), which the shader counts
 * as its own, so that an item suspends after ballast less than half the
 * budget and small scenes resume often. Not thread-safe; tests only. */
void rt_vk_test_alone_ballast(uint32_t ballast);

/* At most slots items (1 .. 4096; anything else: 4096, the default) per
 * dispatch that traces items alone, so that a test runs several batches.
 * Not thread-safe; tests only. */
void rt_vk_test_slots(uint32_t slots);

/* What the last frame or trace of this process traced alone: *items items
 * re-run, *resumes item-dispatches that went on from a saved state, in
 * *dispatches dispatches. Not thread-safe; tests and measurements only. */
void rt_vk_test_reruns(uint32_t *items, uint32_t *resumes, uint32_t *dispatches);

#endif /* RT_VK_BACKEND_H */
