/* packet_trace.h - ray packets through the two-level BVH with NEON.
 *
 * A packet is RT_PK_LANES rays in RT_PK_GROUPS groups of four (one NEON
 * vector each). It traverses the tree together: a node is entered when some
 * ray's box test passes, found by testing the groups in order from the first
 * group still inside the parent ("first active group", as in Wald, Boulos and
 * Shirley 2007); at a leaf every group is box-tested and only the lanes that
 * pass test the triangles, four rays per triangle test.
 *
 * Each lane performs exactly the scalar oracle's box and triangle arithmetic
 * (kernels/rt_shared.h: the same operations in the same order, no FMA), so a
 * lane visits a superset of the nodes its scalar traversal would and tests
 * every candidate triangle the same way; with the total hit order (t, then
 * instance, then primitive) its closest hit is the oracle's, bit for bit, and
 * an any-hit lane's occluded flag is the oracle's.
 */
#ifndef RT_PACKET_TRACE_H
#define RT_PACKET_TRACE_H

#include <stdint.h>

#include "rt_shared.h"

enum { RT_PK_LANES = 16, RT_PK_GROUPS = RT_PK_LANES / 4 };

/* The rays of a packet; lanes outside 'valid' (bit l = lane l) are ignored
 * and need not hold a ray. Lanes 4g .. 4g + 3 form group g: the closer
 * their rays, the fewer nodes the packet visits. */
typedef struct rt_pk_rays {
    rt_ray_d ray[RT_PK_LANES];
    uint32_t valid;
} rt_pk_rays;

/* The tests a packet performed: per lane (as the oracle counts them, for the
 * lanes a test was performed for) and per group of four. */
typedef struct rt_pk_counts {
    rt_counters c[RT_PK_LANES];
    uint64_t group_box_tests, group_tri_tests;
} rt_pk_counts;

/* Traces the valid lanes (closest hit, or any hit when any_hit is set) into
 * hits[0 .. RT_PK_LANES - 1] (prim == RT_NO_HIT on a miss; for any_hit only
 * whether prim != RT_NO_HIT is defined); invalid lanes get a miss. The tests
 * are added to *counts. */
void rt_pk_trace(const rt_scene_view *s, const rt_pk_rays *rays, int any_hit, rt_hit_d *hits,
                 rt_pk_counts *counts);

#endif /* RT_PACKET_TRACE_H */
