/* SPDX-License-Identifier: Apache-2.0 */
/* bvh.h - bounding volume hierarchy builders and tree quality figures.
 *
 * Every builder takes one axis-aligned box per primitive (a triangle's box, or
 * an object's world-space box for the object BVH) and produces the thesis's
 * 32-byte nodes (kernels/rt_layout.h) plus a primitive index array that leaves
 * reference. Builders never print; failures come back as an rt_status with a
 * message.
 */
#ifndef RT_BVH_H
#define RT_BVH_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "rt.h"
#include "rt_layout.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rt_pool rt_pool; /* thread_pool.h */

typedef struct rt_aabb {
    float bmin[3];
    float bmax[3];
} rt_aabb;

typedef enum rt_builder {
    RT_BUILDER_THESIS_SCALAR = 0, /* thesis setup 1: one thread, scalar */
    RT_BUILDER_THESIS_NEON = 1,   /* thesis setup 2: one thread, NEON binning */
    RT_BUILDER_THESIS_MT = 2,     /* thesis setup 3: two-phase threaded */
    RT_BUILDER_SAH = 3,           /* the default: pooled, parallel binning, SAH leaves */
    RT_BUILDER_LBVH = 4           /* Morton-code LBVH (bvh_lbvh.c): the "lbvh" update policy */
} rt_builder;

/* The constants of the surface area heuristic, for every structure: the
 * cost of one node step (Ct) and of one triangle test (Ci). Builders take
 * them from their options; every SAH figure (rt_bvh_sah_cost, rt_bvh_measure,
 * rt_kd_measure) takes them as one value, so trees are judged alike. */
typedef struct rt_sah_costs {
    float traverse;  /* Ct */
    float intersect; /* Ci */
} rt_sah_costs;

/* The thesis's costs, Ct = 1, Ci = 2: the BVH builders' default and the
 * one every reported SAH figure uses. */
rt_sah_costs rt_sah_costs_default(void);

typedef struct rt_build_options {
    rt_builder builder;
    int threads;        /* worker count for threaded builders; <= 0: all cores */
    int bins;           /* SAH bins (thesis: 16) */
    int leaf_size;      /* maximum primitives per leaf (thesis: 10) */
    rt_sah_costs costs; /* [rt_sah_costs_default()] */
} rt_build_options;

/* The thesis's settings with the SAH builder. */
rt_build_options rt_build_options_default(void);

typedef struct rt_bvh {
    rt_node *nodes;
    uint32_t node_count;
    uint32_t *prim_indices; /* leaf entries -> input primitive index */
    uint32_t prim_count;
} rt_bvh;

/* Builds a BVH over count boxes. pool may be NULL (the builder then uses a
 * pool of its own where it needs threads). On failure *out is left empty and
 * err (if not NULL) holds the reason; a box with a NaN or infinite coordinate
 * is refused (RT_ERROR_INVALID_ARGUMENT).
 * count 0 gives the empty tree: node_count 0, nodes NULL, prim_count 0 (a
 * traversal must check node_count before reading the root). */
rt_status rt_bvh_build(const rt_aabb *boxes, uint32_t count, const rt_build_options *options,
                       rt_pool *pool, rt_bvh *out, rt_error *err);

/* The box of the triangle whose three vertex indices are at tri, as every
 * mesh BVH's input is computed (scene_boxes.h's rt_mesh_tri_boxes and
 * rt_bvh_build_tris: one definition, so both give the same bits). */
static inline void rt_tri_box(const float *positions, const uint32_t *tri, rt_aabb *b) {
    for (int k = 0; k < 3; k++) {
        b->bmin[k] = INFINITY;
        b->bmax[k] = -INFINITY;
    }
    for (int v = 0; v < 3; v++) {
        const float *p = positions + 3 * (size_t)tri[v];
        for (int k = 0; k < 3; k++) {
            if (p[k] < b->bmin[k]) b->bmin[k] = p[k];
            if (p[k] > b->bmax[k]) b->bmax[k] = p[k];
        }
    }
}

/* rt_bvh_build over the boxes of count triangles (vertex indices, 3 per
 * triangle, into positions), the same tree as rt_bvh_build of the boxes
 * rt_tri_box gives. With the fast builder no box array is made: the
 * builder reads the triangles as it sets up, which saves a box per triangle
 * at the build's peak of memory (issue 31); other builders get a temporary
 * box array. */
rt_status rt_bvh_build_tris(const float *positions, const uint32_t *indices, uint32_t count,
                            const rt_build_options *options, rt_pool *pool, rt_bvh *out,
                            rt_error *err);

void rt_bvh_free(rt_bvh *bvh);

typedef struct rt_bvh_quality {
    double sah; /* thesis Table 6 'BVH cost': Ct, Ci, areas relative to the root */
    uint32_t nodes;
    uint32_t leaves;
    uint32_t depth; /* the root alone has depth 1 */
    size_t bytes;   /* nodes + primitive indices */
} rt_bvh_quality;

rt_bvh_quality rt_bvh_measure(const rt_bvh *bvh, rt_sah_costs costs);

/* rt_bvh_measure's SAH cost alone (one pass over the nodes, no depth): cheap
 * enough for the renderer to judge a refitted tree every frame. */
double rt_bvh_sah_cost(const rt_bvh *bvh, rt_sah_costs costs);

/* Names as rtcl bench prints them: thesis-scalar, thesis-neon, thesis-mt, sah, lbvh. */
const char *rt_builder_name(rt_builder builder);

#ifdef __cplusplus
}
#endif
#endif /* RT_BVH_H */
