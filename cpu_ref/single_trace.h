/* single_trace.h - incoherent rays one at a time through the two-level BVH
 * as 4- or 8-wide nodes (single_wide.h): one vector box test for all
 * children of a node, the hit children taken nearest first (any-hit rays
 * take leaves first, then the farthest, and stop at the first hit), one
 * vector triangle test for a block of 4 or 8 triangles.
 *
 * Exact: each lane of a box test performs rt_box_test's operations on its
 * child (the same box, the same ray range [rt_box_lo(tmin),
 * rt_box_hi(best t)], the same order, no FMA), and each lane of a triangle
 * test rt_tri_watertight's on its triangle (the other triangle tests, and a
 * watertight edge function of exactly zero, go through the shared scalar
 * code itself). A node is culled only when its box test fails for the ray's
 * range at that moment, whose upper end never lies below the final hit's:
 * as rt_box_test is conservative (Ize, and the t margins), the triangles
 * that hold the closest hit are always tested, and with the total hit order
 * (t, then instance, then triangle) the result is the oracle's, bit for bit;
 * an any-hit ray's occluded flag is the oracle's.
 *
 * Built for several instruction sets like the packet tracer
 * (cpu_ref/single_dispatch.c): "generic" (SSE2 or NEON, width 4), "avx2"
 * and "avx512" (width 8).
 */
#ifndef RT_SINGLE_TRACE_H
#define RT_SINGLE_TRACE_H

#include <stddef.h>

#include "rt_shared.h"
#include "single_wide.h"

typedef struct rt_sw_variant rt_sw_variant;

/* The build named name ("generic", "avx2", "avx512"), or the widest the CPU
 * runs for NULL or ""; NULL when this build or CPU lacks it. */
const rt_sw_variant *rt_sw_variant_find(const char *name);
const char *rt_sw_variant_name(const rt_sw_variant *v);
/* The node width its BVHs must have (rt_sw_build's width). */
int rt_sw_variant_width(const rt_sw_variant *v);

/* Traces rays[0 .. n-1] (closest hit, or any hit when any_hit is set)
 * through the layout s with its wide BVHs b (rt_sw_build of the same layout
 * with rt_sw_variant_width(v)) into hits, as rt_trace fills them (for any
 * hit only whether prim != RT_NO_HIT is defined). Adds rays and tests to *c
 * (box tests: one per child tested; triangle tests: one per triangle). */
void rt_sw_trace(const rt_sw_variant *v, const rt_scene_view *s, const rt_sw_bvh *b,
                 const rt_ray *rays, size_t n, int any_hit, rt_hit_d *hits, rt_counters *c);

#endif /* RT_SINGLE_TRACE_H */
