/* SPDX-License-Identifier: Apache-2.0 */
/* single_trace.h - incoherent rays one at a time through the two-level BVH
 * as 4- or 8-wide nodes (wide_bvh.h, shaped by rt_sw_shape): one vector box
 * test for all children of a node, the hit children taken nearest first
 * (any-hit rays take leaves first, then the farthest, and stop at the first
 * hit), one vector triangle test for a block of 4 or 8 triangles.
 *
 * Exact: each lane of a box test performs rt_box_test's operations on its
 * child (the same box, the same ray range [rt_box_lo(tmin),
 * rt_box_hi(best t)], the same order, no FMA), and each lane of a triangle
 * test rt_tri_watertight's on its triangle (watertight_lanes.h; the other
 * triangle tests, and a watertight edge function of exactly zero, go
 * through the shared scalar code itself). A node is culled only when its
 * box test fails for the ray's range at that moment, whose upper end never
 * lies below the final hit's: as rt_box_test is conservative (Ize, and the
 * t margins), the triangles that hold the closest hit are always tested,
 * and with the total hit order (t, then instance, then triangle) the result
 * is the oracle's, bit for bit; an any-hit ray's occluded flag is the
 * oracle's.
 *
 * Built once per instruction set with the packet tracer (cpu_isa.h):
 * "generic" (SSE2 or NEON, width 4), "avx2" and "avx512" (width 8).
 */
#ifndef RT_SINGLE_TRACE_H
#define RT_SINGLE_TRACE_H

#include <stddef.h>

#include "cpu_isa.h"
#include "kernel_maths.h"
#include "wide_bvh.h"

/* Subtrees of at most RT_SW_LEAF_MERGE times the width triangles (one run of
 * entries) become one leaf of the single-ray tracer's trees. */
#ifndef RT_SW_LEAF_MERGE
#define RT_SW_LEAF_MERGE 1
#endif

/* The single-ray tracer's trees of width 4 or 8 (rt_cpu_isa_width): mesh
 * leaves as blocks, subtrees of up to RT_SW_LEAF_MERGE blocks of triangles
 * as one leaf, kept whole; the object BVH's leaves as the layout has them.
 * (Another width gives a shape rt_wide_build refuses.) */
static inline rt_wide_shape rt_sw_shape(int width) {
    const rt_wide_shape s = {width, (uint32_t)(RT_SW_LEAF_MERGE * width), 0, 1, 1};
    return s;
}

/* One instruction-set build of the single-ray tracer (cpu_isa.h): its node
 * width and its entry point. */
typedef struct rt_sw_tracer {
    int width;
    void (*trace)(const rt_scene_view *s, const rt_wide_bvh *b, const rt_ray *rays,
                  const uint32_t *masks, size_t n, int any_hit, rt_hit_d *hits, rt_counters *c);
} rt_sw_tracer;

/* Traces rays[0 .. n-1] (closest hit, or any hit when any_hit is set)
 * through the layout s with its wide BVHs b (rt_wide_build of the same
 * layout with rt_sw_shape(rt_cpu_isa_width(isa))) into hits, as rt_trace
 * fills them (for any hit only whether prim != RT_NO_HIT is defined). Adds
 * rays and tests to *c (box tests: one per child tested; triangle tests:
 * one per triangle). */
void rt_sw_trace(const rt_cpu_isa *isa, const rt_scene_view *s, const rt_wide_bvh *b,
                 const rt_ray *rays, size_t n, int any_hit, rt_hit_d *hits, rt_counters *c);

/* rt_sw_trace with ray i's mask masks[i] (NULL: 0xffffffff for every ray),
 * as rt_trace_masked takes it. */
void rt_sw_trace_masked(const rt_cpu_isa *isa, const rt_scene_view *s, const rt_wide_bvh *b,
                        const rt_ray *rays, const uint32_t *masks, size_t n, int any_hit,
                        rt_hit_d *hits, rt_counters *c);

#endif /* RT_SINGLE_TRACE_H */
