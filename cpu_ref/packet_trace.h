/* packet_trace.h - ray packets through the two-level BVH, RT_PK_LANES rays
 * at once (an 8x8-pixel tile of the renderer, or 64 consecutive rays of a
 * query).
 *
 * The packet's lanes sit in vectors of the machine's width (host/simd_wide.h)
 * and traverse four-wide copies of the layout's BVHs (packet_wide.h): the
 * packet's bounds cull inner nodes for all its rays at once, and near the
 * leaves each vector of lanes goes on with its own box tests
 * (packet_trace.c says how).
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

#include "packet_wide.h"
#include "rt_shared.h"

enum { RT_PK_LANES = 64 };

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

/* The packet tracer is built for several instruction sets where the target
 * has them (cpu_ref/packet_dispatch.c). rt_pk_variant_find returns the build
 * named name ("generic", "avx2", "avx512"), or the widest the CPU runs for
 * NULL or "", and NULL when this build or CPU lacks it; rt_pk_isa_name(i)
 * names the build's i-th one (NULL past the last). */
typedef struct rt_pk_variant rt_pk_variant;
const rt_pk_variant *rt_pk_variant_find(const char *name);
const char *rt_pk_variant_name(const rt_pk_variant *isa);
int rt_pk_variant_lanes(const rt_pk_variant *isa); /* lanes per vector of that build */
const char *rt_pk_isa_name(int i);

/* Traces the valid lanes (closest hit, or any hit when any_hit is set)
 * through the layout s with its wide BVHs w (rt_pk_wide_build of the same
 * layout) into *hits, with the build isa; invalid lanes get a miss at
 * t = inf. The tests are added to *counts. */
void rt_pk_trace(const rt_pk_variant *isa, const rt_scene_view *s, const rt_pk_wide *w,
                 const rt_pk_rays *rays, int any_hit, rt_pk_hits *hits, rt_pk_counts *counts);

#endif /* RT_PACKET_TRACE_H */
