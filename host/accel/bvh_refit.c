/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_refit.c - bottom-up refit of a BVH (bvh_refit.h).
 *
 * Each worker takes a share of the leaves, computes their boxes and climbs
 * towards the root; at each inner node it counts itself in with an atomic
 * increment, and only the second child to arrive (which then sees both
 * children's boxes, by the acquire-release order of the increments) computes
 * the node and climbs on. Every node is computed exactly once, after its
 * children, in one pass of the pool, whatever the node order of the tree. */
#include "accel/bvh_refit.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "base/thread_pool.h"

rt_status rt_bvh_refit_prepare(const rt_bvh *bvh, rt_bvh_refit_info *info) {
    memset(info, 0, sizeof *info);
    uint32_t n = bvh->node_count;
    if (!n) return RT_ERROR_INVALID_ARGUMENT;
    info->parents = malloc(sizeof(uint32_t) * n);
    info->leaves = malloc(sizeof(uint32_t) * n);
    info->visits = malloc(sizeof(atomic_uint) * n);
    if (!info->parents || !info->leaves || !info->visits) {
        rt_bvh_refit_info_free(info);
        return RT_ERROR_OUT_OF_MEMORY;
    }
    info->node_count = n;
    info->ordered = 1;
    for (uint32_t i = 0; i < n; i++) info->parents[i] = UINT32_MAX;
    for (uint32_t i = 0; i < n; i++) {
        const rt_node *node = &bvh->nodes[i];
        if (node->b & RT_NODE_LEAF_FLAG) {
            info->leaves[info->leaf_count++] = i;
        } else {
            info->parents[node->a] = i;
            info->parents[node->b] = i;
            if (node->a <= i || node->b <= i) info->ordered = 0;
        }
    }
    return RT_OK;
}

void rt_bvh_refit_info_free(rt_bvh_refit_info *info) {
    free(info->parents);
    free(info->leaves);
    free(info->visits);
    memset(info, 0, sizeof *info);
}

typedef struct refit_job {
    rt_bvh *bvh;
    rt_bvh_refit_info *info;
    const rt_aabb *boxes;   /* per primitive, or NULL: ... */
    const float *positions; /* ... triangles of these vertices */
    const uint32_t *indices;
} refit_job;

/* A leaf's box from its triangles' vertices. */
static void leaf_box_tris(rt_node *n, const uint32_t *prims, const float *pos,
                          const uint32_t *idx) {
    uint32_t count = n->b & RT_NODE_COUNT_MASK;
    if (!count) {
        for (int k = 0; k < 3; k++) n->bmin[k] = n->bmax[k] = 0.0f;
        return;
    }
    const float *p = pos + 3 * (size_t)idx[3 * (size_t)prims[n->a]];
    float lo[3] = {p[0], p[1], p[2]}, hi[3] = {p[0], p[1], p[2]};
    for (uint32_t j = 0; j < count; j++) {
        const uint32_t *t = idx + 3 * (size_t)prims[n->a + j];
        for (int v = 0; v < 3; v++) {
            p = pos + 3 * (size_t)t[v];
            for (int k = 0; k < 3; k++) {
                lo[k] = p[k] < lo[k] ? p[k] : lo[k];
                hi[k] = p[k] > hi[k] ? p[k] : hi[k];
            }
        }
    }
    memcpy(n->bmin, lo, sizeof lo);
    memcpy(n->bmax, hi, sizeof hi);
}

static void leaf_box(rt_node *n, const uint32_t *prims, const rt_aabb *boxes) {
    float lo[3] = {boxes[prims[n->a]].bmin[0], boxes[prims[n->a]].bmin[1],
                   boxes[prims[n->a]].bmin[2]};
    float hi[3] = {boxes[prims[n->a]].bmax[0], boxes[prims[n->a]].bmax[1],
                   boxes[prims[n->a]].bmax[2]};
    uint32_t count = n->b & RT_NODE_COUNT_MASK;
    for (uint32_t j = 1; j < count; j++) {
        const rt_aabb *b = &boxes[prims[n->a + j]];
        for (int k = 0; k < 3; k++) {
            if (b->bmin[k] < lo[k]) lo[k] = b->bmin[k];
            if (b->bmax[k] > hi[k]) hi[k] = b->bmax[k];
        }
    }
    if (!count)
        for (int k = 0; k < 3; k++) lo[k] = hi[k] = 0.0f; /* an empty leaf: never built */
    memcpy(n->bmin, lo, sizeof lo);
    memcpy(n->bmax, hi, sizeof hi);
}

static void inner_box(rt_node *nodes, uint32_t i) {
    rt_node *n = &nodes[i];
    const rt_node *l = &nodes[n->a], *r = &nodes[n->b];
    for (int k = 0; k < 3; k++) {
        n->bmin[k] = l->bmin[k] < r->bmin[k] ? l->bmin[k] : r->bmin[k];
        n->bmax[k] = l->bmax[k] > r->bmax[k] ? l->bmax[k] : r->bmax[k];
    }
}

static void refit_worker(void *ctx, int worker, int workers) {
    refit_job *j = ctx;
    rt_node *nodes = j->bvh->nodes;
    atomic_uint *visits = j->info->visits;
    uint32_t L = j->info->leaf_count;
    uint32_t from = (uint32_t)((uint64_t)L * (uint64_t)worker / (uint64_t)workers);
    uint32_t to = (uint32_t)((uint64_t)L * (uint64_t)(worker + 1) / (uint64_t)workers);
    for (uint32_t k = from; k < to; k++) {
        uint32_t i = j->info->leaves[k];
        if (j->boxes)
            leaf_box(&nodes[i], j->bvh->prim_indices, j->boxes);
        else
            leaf_box_tris(&nodes[i], j->bvh->prim_indices, j->positions, j->indices);
        for (uint32_t p = j->info->parents[i]; p != UINT32_MAX; p = j->info->parents[p]) {
            /* The first child to arrive stops; the second computes p. */
            if (atomic_fetch_add_explicit(&visits[p], 1u, memory_order_acq_rel) == 0) break;
            inner_box(nodes, p);
        }
    }
}

/* One thread, children after parents: a backward sweep, no atomics. */
static void refit_sweep(const refit_job *j) {
    rt_node *nodes = j->bvh->nodes;
    for (uint32_t i = j->info->node_count; i-- > 0;) {
        rt_node *n = &nodes[i];
        if (!(n->b & RT_NODE_LEAF_FLAG))
            inner_box(nodes, i);
        else if (j->boxes)
            leaf_box(n, j->bvh->prim_indices, j->boxes);
        else
            leaf_box_tris(n, j->bvh->prim_indices, j->positions, j->indices);
    }
}

static void run(refit_job *job, rt_pool *pool) {
    rt_bvh_refit_info *info = job->info;
    /* Below a few thousand leaves waking the workers costs more than it saves. */
    if (pool && rt_pool_size(pool) > 1 && info->leaf_count >= 4096) {
        atomic_uint *visits = info->visits;
        for (uint32_t i = 0; i < info->node_count; i++)
            atomic_store_explicit(&visits[i], 0u, memory_order_relaxed);
        rt_pool_run(pool, refit_worker, job);
    } else if (info->ordered) {
        refit_sweep(job);
    } else {
        atomic_uint *visits = info->visits;
        for (uint32_t i = 0; i < info->node_count; i++)
            atomic_store_explicit(&visits[i], 0u, memory_order_relaxed);
        refit_worker(job, 0, 1);
    }
}

void rt_bvh_refit(rt_bvh *bvh, rt_bvh_refit_info *info, const rt_aabb *prim_boxes, rt_pool *pool) {
    refit_job job = {bvh, info, prim_boxes, NULL, NULL};
    run(&job, pool);
}

void rt_bvh_refit_tris(rt_bvh *bvh, rt_bvh_refit_info *info, const float *positions,
                       const uint32_t *indices, rt_pool *pool) {
    refit_job job = {bvh, info, NULL, positions, indices};
    run(&job, pool);
}
