/* SPDX-License-Identifier: Apache-2.0 */
/* rt_shared.h - the shared ray tracing maths in one include, for code that
 * uses most of it: rays, the camera, box and triangle tests, hits, and the
 * BVH and kd-tree traversals (rt_trace.h); shading is rt_shade.h. Each part
 * is a header of its own (docs/ARCHITECTURE.md, "kernels/"), each with its
 * GLSL mirror in kernels/vulkan/; the rules that make them give the same
 * bits everywhere are in rt_math_profile.h. Kept for the includers that
 * want all of it (cpu_ref/, host/layout/, the tests); new code includes the
 * part it uses. */
#ifndef RT_SHARED_H
#define RT_SHARED_H

#include "rt_camera.h"
#include "rt_trace.h"

#endif /* RT_SHARED_H */
