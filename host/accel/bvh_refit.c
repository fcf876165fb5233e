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
    for (uint32_t i = 0; i < n; i++) info->parents[i] = UINT32_MAX;
    for (uint32_t i = 0; i < n; i++) {
        const rt_node *node = &bvh->nodes[i];
        if (node->b & RT_NODE_LEAF_FLAG) {
            info->leaves[info->leaf_count++] = i;
        } else {
            info->parents[node->a] = i;
            info->parents[node->b] = i;
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
    const rt_aabb *boxes;
} refit_job;

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
        leaf_box(&nodes[i], j->bvh->prim_indices, j->boxes);
        for (uint32_t p = j->info->parents[i]; p != UINT32_MAX; p = j->info->parents[p]) {
            /* The first child to arrive stops; the second computes p. */
            if (atomic_fetch_add_explicit(&visits[p], 1u, memory_order_acq_rel) == 0) break;
            inner_box(nodes, p);
        }
    }
}

void rt_bvh_refit(rt_bvh *bvh, rt_bvh_refit_info *info, const rt_aabb *prim_boxes, rt_pool *pool) {
    atomic_uint *visits = info->visits;
    for (uint32_t i = 0; i < info->node_count; i++)
        atomic_store_explicit(&visits[i], 0u, memory_order_relaxed);
    refit_job job = {bvh, info, prim_boxes};
    /* Below a few thousand leaves waking the workers costs more than it saves. */
    if (pool && rt_pool_size(pool) > 1 && info->leaf_count >= 2048)
        rt_pool_run(pool, refit_worker, &job);
    else
        refit_worker(&job, 0, 1);
}

static double area(const rt_node *n) {
    double dx = (double)n->bmax[0] - n->bmin[0];
    double dy = (double)n->bmax[1] - n->bmin[1];
    double dz = (double)n->bmax[2] - n->bmin[2];
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

double rt_bvh_sah(const rt_bvh *bvh, float cost_box, float cost_tri) {
    if (!bvh->node_count) return 0.0;
    double root = area(&bvh->nodes[0]), sum = 0.0;
    for (uint32_t i = 0; i < bvh->node_count; i++) {
        const rt_node *n = &bvh->nodes[i];
        double a = root > 0.0 ? area(n) / root : 1.0;
        if (n->b & RT_NODE_LEAF_FLAG)
            sum += (double)cost_tri * (double)(n->b & RT_NODE_COUNT_MASK) * a;
        else
            sum += (double)cost_box * a;
    }
    return sum;
}
