/* SPDX-License-Identifier: Apache-2.0 */
/* packet_trace.h - ray packets through the two-level BVH, RT_PK_LANES rays
 * at once (an 8x8-pixel tile of the renderer, or 64 consecutive rays of a
 * query).
 *
 * The packet's lanes sit in vectors of the machine's width (simd.h) and
 * traverse four-wide copies of the layout's BVHs (wide_bvh.h, shaped by
 * rt_pk_shape): the packet's bounds cull inner nodes for all its rays at
 * once, and near the leaves each vector of lanes goes on with its own box
 * tests (packet_trace.c says how).
 *
 * Each lane performs exactly the scalar oracle's box and triangle arithmetic
 * (kernels/rt_shared.h: the same operations in the same order, no FMA), and
 * every culling of a node by the packet is conservative for every lane, so a
 * lane visits a superset of the nodes its scalar traversal would and tests
 * every candidate triangle the same way; with the total hit order (t, then
 * instance, then primitive) its closest hit is the oracle's, bit for bit, and
 * an any-hit lane's occluded flag is the oracle's.
 */
#ifndef RT_PACKET_TRACE_H
#define RT_PACKET_TRACE_H

#include <stdint.h>

#include "cpu_isa.h"
#include "kernel_maths.h"
#include "wide_bvh.h"

enum { RT_PK_LANES = 64 };

/* Children per node of the packet tracer's trees. */
#ifndef RT_PK_WIDTH
#define RT_PK_WIDTH 4
#endif

/* Subtrees of at most this many primitives (one run of entries) become one
 * leaf of the packet tracer's trees. */
#ifndef RT_PK_LEAF_MERGE
#define RT_PK_LEAF_MERGE 4
#endif

/* The packet tracer's trees: RT_PK_WIDTH children, leaves that are entry
 * ranges, subtrees of up to RT_PK_LEAF_MERGE triangles (or instances) as
 * one leaf, opened when there is room. A packet tests a few triangles at
 * the cost of a box, and every box test saved is a node load saved. */
static inline rt_wide_shape rt_pk_shape(void) {
    const rt_wide_shape s = {RT_PK_WIDTH, RT_PK_LEAF_MERGE, 1, 0, 0};
    return s;
}

/* A node of those trees, field by field (wide_bvh.h's node layout at width
 * RT_PK_WIDTH): up to RT_PK_WIDTH children in the binary tree's
 * left-to-right order; slots past the last child have ref RT_WIDE_EMPTY. A
 * child is a leaf when its count has RT_NODE_LEAF_FLAG: ref and count are
 * then its first entry and count | flag; else ref is the child's node index
 * and count 0. */
typedef struct rt_pk_node {
    float bmin[3][RT_PK_WIDTH];
    float bmax[3][RT_PK_WIDTH];
    uint32_t ref[RT_PK_WIDTH];
    uint32_t count[RT_PK_WIDTH];
} rt_pk_node; /* 32 bytes a child, allocated on 64-byte lines */
_Static_assert(sizeof(rt_pk_node) == 4 * RT_WIDE_NODE_WORDS(RT_PK_WIDTH), "wide_bvh.h's node");

/* A set of a packet's lanes: bit l is lane l. */
typedef uint64_t rt_pk_mask;
#define RT_PK_ALL (~(rt_pk_mask)0 >> (64 - RT_PK_LANES))

/* The rays of a packet, field by field (the tracer loads them as vectors);
 * lanes outside 'valid' (bit l = lane l) are ignored and need not hold a
 * ray. The closer the rays, the fewer nodes the packet visits. */
typedef struct rt_pk_rays {
    float org[3][RT_PK_LANES], dir[3][RT_PK_LANES];
    float tmin[RT_PK_LANES], tmax[RT_PK_LANES];
    rt_pk_mask valid;
} rt_pk_rays;

static inline void rt_pk_set_ray(rt_pk_rays *p, int l, const rt_ray *r) {
    for (int k = 0; k < 3; k++) {
        p->org[k][l] = r->org[k];
        p->dir[k][l] = r->dir[k];
    }
    p->tmin[l] = r->tmin;
    p->tmax[l] = r->tmax;
}

static inline void rt_pk_get_ray(const rt_pk_rays *p, int l, rt_ray *r) {
    for (int k = 0; k < 3; k++) {
        r->org[k] = p->org[k][l];
        r->dir[k] = p->dir[k][l];
    }
    r->tmin = p->tmin[l];
    r->tmax = p->tmax[l];
}

/* What a packet trace finds, field by field: per lane the closest hit
 * (prim == RT_NO_HIT on a miss, with t the ray's tmax, u = v = 0; for any hit
 * only whether prim != RT_NO_HIT is defined). */
typedef struct rt_pk_hits {
    float t[RT_PK_LANES], u[RT_PK_LANES], v[RT_PK_LANES];
    uint32_t prim[RT_PK_LANES], inst[RT_PK_LANES], entry[RT_PK_LANES];
} rt_pk_hits;

static inline void rt_pk_get_hit(const rt_pk_hits *h, int l, rt_hit_d *out) {
    out->t = h->t[l];
    out->u = h->u[l];
    out->v = h->v[l];
    out->prim = h->prim[l];
    out->inst = h->inst[l];
    out->entry = h->entry[l];
}

/* What packets traced: rays and the tests performed for them, as the oracle
 * counts them (one per lane a test was performed for), in all and, when
 * per_lane is set, per lane; and the tests of whole packets (one vector test
 * each, however many lanes it served). */
typedef struct rt_pk_counts {
    int per_lane;
    rt_counters c[RT_PK_LANES];
    uint64_t rays, box_tests, tri_tests;
    uint64_t group_box_tests, group_tri_tests;
} rt_pk_counts;

/* One instruction-set build of the packet tracer (cpu_isa.h): its lanes
 * per vector and its entry point. */
typedef struct rt_pk_tracer {
    int lanes;
    void (*trace)(const rt_scene_view *s, const rt_wide_bvh *w, const rt_pk_rays *rays,
                  const uint32_t *masks, int any_hit, rt_pk_hits *hits, rt_pk_counts *counts);
} rt_pk_tracer;

/* Traces the valid lanes (closest hit, or any hit when any_hit is set)
 * through the layout s with its wide BVHs w (rt_wide_build of the same
 * layout with rt_pk_shape()) into *hits, with the build isa; invalid lanes
 * get a miss at t = inf. The tests are added to *counts. */
void rt_pk_trace(const rt_cpu_isa *isa, const rt_scene_view *s, const rt_wide_bvh *w,
                 const rt_pk_rays *rays, int any_hit, rt_pk_hits *hits, rt_pk_counts *counts);

/* rt_pk_trace with a ray mask per lane (masks[l] for lane l, RT_PK_LANES of
 * them; NULL: 0xffffffff for every lane): a lane skips each instance whose
 * mask has no bit of its own, as rt_trace_masked does. */
void rt_pk_trace_masked(const rt_cpu_isa *isa, const rt_scene_view *s, const rt_wide_bvh *w,
                        const rt_pk_rays *rays, const uint32_t *masks, int any_hit,
                        rt_pk_hits *hits, rt_pk_counts *counts);

#endif /* RT_PACKET_TRACE_H */
