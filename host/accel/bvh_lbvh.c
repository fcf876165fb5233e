/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_lbvh.c - the per-frame builder of the "lbvh" update policy: a linear
 * BVH over Morton codes (after Lauterbach et al. 2009 and Karras 2012).
 *
 * 1. Each primitive's box centre is quantised to a 1024^3 grid over the
 *    centres' bounds and its coordinates' bits interleaved into a 30-bit
 *    Morton code (in parallel; each code depends on its primitive alone).
 * 2. The (code, primitive) pairs are radix-sorted, stably, so that equal
 *    codes stay in primitive order: the order is a total one.
 * 3. The tree is the radix tree of the sorted codes: a range splits where
 *    its highest differing code bit changes (a binary search), a range of
 *    equal codes in the middle, and a range of at most LBVH_LEAF primitives
 *    is a leaf. Each split consumes a code bit or halves a range of equal
 *    codes, so the depth stays below 30 + log2(n) <= 60 < RT_STACK_SIZE.
 *
 * Parallel and deterministic: the top of the tree (ranges above a size that
 * depends on n only) is split on this thread; the subtrees below are built
 * by the pool's workers in any order, each into its own slot of the node
 * array (a subtree of m primitives has at most 2m - 1 nodes), and the slots
 * are then packed in subtree order. The tree is therefore the same bytes for
 * any thread count. Boxes are unions of the primitives' boxes. */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh_internal.h"
#include "base/error.h"
#include "base/thread_pool.h"

enum { LBVH_LEAF = 4, LBVH_TASK_MIN = 2048, LBVH_MAX_TASKS = 256 };
#define TASK_REF 0x40000000u /* a child reference to a subtree not yet placed */

/* Spreads the low 10 bits of v to every third bit. */
static uint32_t spread3(uint32_t v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

typedef struct lbvh {
    const rt_aabb *boxes;
    uint32_t count;
    float cmin[3], scale[3]; /* centre -> grid */
    uint32_t *codes, *ids;   /* sorted pairs */
    uint32_t *codes_tmp, *ids_tmp;
    rt_node *nodes; /* slots: top nodes, then one slot per task */
    uint32_t top_count;
    struct task {
        uint32_t lo, hi; /* primitive range in sorted order */
        uint32_t slot;   /* first node of its slot */
        uint32_t used;   /* nodes it built */
        uint32_t parent; /* the top node that refers to it, UINT32_MAX: it is the root */
        int right;       /* which child of parent */
    } tasks[LBVH_MAX_TASKS];
    uint32_t task_count;
    atomic_uint next_task;
} lbvh;

static void centre(const rt_aabb *b, float c[3]) {
    for (int k = 0; k < 3; k++) c[k] = 0.5f * b->bmin[k] + 0.5f * b->bmax[k];
}

static void codes_worker(void *ctx, int w, int n) {
    lbvh *L = ctx;
    uint32_t from = (uint32_t)((uint64_t)L->count * (uint64_t)w / (uint64_t)n);
    uint32_t to = (uint32_t)((uint64_t)L->count * (uint64_t)(w + 1) / (uint64_t)n);
    for (uint32_t i = from; i < to; i++) {
        float c[3];
        centre(&L->boxes[i], c);
        uint32_t q[3];
        for (int k = 0; k < 3; k++) {
            float g = (c[k] - L->cmin[k]) * L->scale[k];
            q[k] = g <= 0.0f ? 0u : g >= 1023.0f ? 1023u : (uint32_t)g;
        }
        L->codes_tmp[i] = spread3(q[0]) << 2 | spread3(q[1]) << 1 | spread3(q[2]);
    }
}

/* Stable LSD radix sort of (codes_tmp, identity) by code into (codes, ids). */
static void sort_codes(lbvh *L) {
    uint32_t n = L->count;
    uint32_t *src_c = L->codes_tmp, *src_i = L->ids_tmp, *dst_c = L->codes, *dst_i = L->ids;
    for (uint32_t i = 0; i < n; i++) src_i[i] = i;
    static const int shifts[3] = {0, 10, 20};
    for (int pass = 0; pass < 3; pass++) {
        uint32_t hist[1024] = {0};
        int s = shifts[pass];
        for (uint32_t i = 0; i < n; i++) hist[(src_c[i] >> s) & 1023u]++;
        uint32_t sum = 0;
        for (int b = 0; b < 1024; b++) {
            uint32_t h = hist[b];
            hist[b] = sum;
            sum += h;
        }
        for (uint32_t i = 0; i < n; i++) {
            uint32_t d = hist[(src_c[i] >> s) & 1023u]++;
            dst_c[d] = src_c[i];
            dst_i[d] = src_i[i];
        }
        uint32_t *t = src_c;
        src_c = dst_c;
        dst_c = t;
        t = src_i;
        src_i = dst_i;
        dst_i = t;
    }
    /* After three passes the result is in the _tmp arrays: swap the roles. */
    L->codes = src_c;
    L->ids = src_i;
    L->codes_tmp = dst_c;
    L->ids_tmp = dst_i;
}

/* Where [lo, hi) (hi - lo >= 2) splits: the first index of the right half. */
static uint32_t split_of(const uint32_t *codes, uint32_t lo, uint32_t hi) {
    uint32_t diff = codes[lo] ^ codes[hi - 1];
    if (!diff) return lo + (hi - lo) / 2;
    uint32_t bit = 1u << (31 - __builtin_clz(diff));
    uint32_t a = lo, b = hi - 1; /* codes[a] lacks bit, codes[b] has it */
    while (b - a > 1) {
        uint32_t m = a + (b - a) / 2;
        if (codes[m] & bit)
            b = m;
        else
            a = m;
    }
    return b;
}

static void box_union(rt_node *n, const rt_node *l, const rt_node *r) {
    for (int k = 0; k < 3; k++) {
        n->bmin[k] = l->bmin[k] < r->bmin[k] ? l->bmin[k] : r->bmin[k];
        n->bmax[k] = l->bmax[k] > r->bmax[k] ? l->bmax[k] : r->bmax[k];
    }
}

/* Builds [lo, hi) into nodes[*used...] (node indices relative to base) and
 * returns the index of its root. */
static uint32_t build_range(const lbvh *L, rt_node *nodes, uint32_t base, uint32_t *used,
                            uint32_t lo, uint32_t hi) {
    uint32_t me = (*used)++;
    rt_node *n = &nodes[me];
    if (hi - lo <= LBVH_LEAF) {
        const rt_aabb *b = &L->boxes[L->ids[lo]];
        memcpy(n->bmin, b->bmin, sizeof n->bmin);
        memcpy(n->bmax, b->bmax, sizeof n->bmax);
        for (uint32_t i = lo + 1; i < hi; i++) {
            b = &L->boxes[L->ids[i]];
            for (int k = 0; k < 3; k++) {
                if (b->bmin[k] < n->bmin[k]) n->bmin[k] = b->bmin[k];
                if (b->bmax[k] > n->bmax[k]) n->bmax[k] = b->bmax[k];
            }
        }
        n->a = lo;
        n->b = (hi - lo) | RT_NODE_LEAF_FLAG;
        return me;
    }
    uint32_t mid = split_of(L->codes, lo, hi);
    uint32_t l = build_range(L, nodes, base, used, lo, mid);
    uint32_t r = build_range(L, nodes, base, used, mid, hi);
    n = &nodes[me];
    n->a = base + l;
    n->b = base + r;
    box_union(n, &nodes[l], &nodes[r]);
    return me;
}

static void task_worker(void *ctx, int w, int n) {
    (void)w;
    (void)n;
    lbvh *L = ctx;
    for (;;) {
        uint32_t t = atomic_fetch_add_explicit(&L->next_task, 1u, memory_order_relaxed);
        if (t >= L->task_count) break;
        struct task *k = &L->tasks[t];
        uint32_t used = 0;
        build_range(L, L->nodes + k->slot, k->slot, &used, k->lo, k->hi);
        k->used = used;
    }
}

/* Splits the top of the tree on this thread: a range larger than the task
 * size becomes a top node, a smaller one a task. */
static void split_top(lbvh *L, uint32_t lo, uint32_t hi, uint32_t task_size, uint32_t parent,
                      int right, uint32_t *next_slot) {
    if (hi - lo > task_size && L->top_count + 1 < LBVH_MAX_TASKS - 1) {
        uint32_t me = L->top_count++;
        if (parent != UINT32_MAX) {
            if (right)
                L->nodes[parent].b = me;
            else
                L->nodes[parent].a = me;
        }
        uint32_t mid = split_of(L->codes, lo, hi);
        split_top(L, lo, mid, task_size, me, 0, next_slot);
        split_top(L, mid, hi, task_size, me, 1, next_slot);
        return;
    }
    struct task *k = &L->tasks[L->task_count];
    k->lo = lo;
    k->hi = hi;
    k->slot = *next_slot;
    *next_slot += 2 * (hi - lo) - 1;
    k->parent = parent;
    k->right = right;
    if (parent != UINT32_MAX) {
        if (right)
            L->nodes[parent].b = TASK_REF | L->task_count;
        else
            L->nodes[parent].a = TASK_REF | L->task_count;
    }
    L->task_count++;
}

/* Boxes of the top nodes, from their children (children come later in the
 * top, or are tasks' roots), in reverse order. */
static void top_boxes(lbvh *L) {
    for (uint32_t i = L->top_count; i-- > 0;)
        box_union(&L->nodes[i], &L->nodes[L->nodes[i].a], &L->nodes[L->nodes[i].b]);
}

rt_status rt_bvh_build_lbvh(const rt_aabb *boxes, uint32_t count, const rt_build_options *options,
                            rt_pool *pool, rt_bvh *out, rt_error *err) {
    (void)options;
    memset(out, 0, sizeof *out);
    if (!count) return RT_OK;
    lbvh *L = calloc(1, sizeof *L);
    if (!L) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "LBVH: out of memory");
    L->boxes = boxes;
    L->count = count;
    float cmax[3];
    for (uint32_t i = 0; i < count; i++) {
        float c[3];
        centre(&boxes[i], c);
        for (int k = 0; k < 3; k++) {
            if (!(c[k] == c[k]) || c[k] - c[k] != 0.0f) { /* NaN or infinite */
                free(L);
                return rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                               "LBVH: box %u has a NaN or infinite coordinate", i);
            }
            if (i == 0 || c[k] < L->cmin[k]) L->cmin[k] = c[k];
            if (i == 0 || c[k] > cmax[k]) cmax[k] = c[k];
        }
    }
    for (int k = 0; k < 3; k++) {
        float ext = cmax[k] - L->cmin[k];
        L->scale[k] = ext > 0.0f ? 1024.0f / ext : 0.0f;
    }
    size_t max_nodes = 2 * (size_t)count + 2 * LBVH_MAX_TASKS;
    L->codes = malloc(sizeof(uint32_t) * count);
    L->ids = malloc(sizeof(uint32_t) * count);
    L->codes_tmp = malloc(sizeof(uint32_t) * count);
    L->ids_tmp = malloc(sizeof(uint32_t) * count);
    L->nodes = malloc(sizeof(rt_node) * max_nodes);
    rt_status st = RT_OK;
    if (!L->codes || !L->ids || !L->codes_tmp || !L->ids_tmp || !L->nodes) {
        st = rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "LBVH: out of memory");
        goto done;
    }
    int parallel = pool && rt_pool_size(pool) > 1 && count >= 2 * LBVH_TASK_MIN;
    if (parallel)
        rt_pool_run(pool, codes_worker, L);
    else
        codes_worker(L, 0, 1);
    sort_codes(L);

    /* The task size depends on count alone, so the tree does not depend on
     * the number of threads. */
    uint32_t task_size = count / 64 > LBVH_TASK_MIN ? count / 64 : LBVH_TASK_MIN;
    /* Fewer than LBVH_MAX_TASKS top nodes; the slots follow the top. */
    uint32_t top_reserve = LBVH_MAX_TASKS;
    uint32_t next_slot = top_reserve;
    split_top(L, 0, count, task_size, UINT32_MAX, 0, &next_slot);
    atomic_init(&L->next_task, 0u);
    if (parallel && L->task_count > 1)
        rt_pool_run(pool, task_worker, L);
    else
        task_worker(L, 0, 1);

    /* Pack: the top nodes, then each task's nodes in task order. */
    uint32_t *place = malloc(sizeof(uint32_t) * L->task_count);
    if (!place) {
        st = rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "LBVH: out of memory");
        goto done;
    }
    uint32_t total = L->top_count;
    for (uint32_t t = 0; t < L->task_count; t++) {
        place[t] = total;
        total += L->tasks[t].used;
    }
    rt_node *nodes = malloc(sizeof(rt_node) * total);
    uint32_t *prims = malloc(sizeof(uint32_t) * count);
    if (!nodes || !prims) {
        free(nodes);
        free(prims);
        free(place);
        st = rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "LBVH: out of memory");
        goto done;
    }
    for (uint32_t t = 0; t < L->task_count; t++) {
        const struct task *k = &L->tasks[t];
        int32_t shift = (int32_t)place[t] - (int32_t)k->slot;
        for (uint32_t i = 0; i < k->used; i++) {
            rt_node n = L->nodes[k->slot + i];
            if (!(n.b & RT_NODE_LEAF_FLAG)) {
                n.a = (uint32_t)((int32_t)n.a + shift);
                n.b = (uint32_t)((int32_t)n.b + shift);
            }
            nodes[place[t] + i] = n;
        }
    }
    for (uint32_t i = 0; i < L->top_count; i++) {
        rt_node n = L->nodes[i];
        if (n.a & TASK_REF) n.a = place[n.a & ~TASK_REF];
        if (n.b & TASK_REF) n.b = place[n.b & ~TASK_REF];
        nodes[i] = n;
    }
    free(place);
    /* Boxes of the top nodes now that their children are placed. */
    L->nodes = (free(L->nodes), nodes);
    top_boxes(L);
    memcpy(prims, L->ids, sizeof(uint32_t) * count);
    out->nodes = nodes;
    out->node_count = total;
    out->prim_indices = prims;
    out->prim_count = count;
    L->nodes = NULL;
done:
    free(L->codes);
    free(L->ids);
    free(L->codes_tmp);
    free(L->ids_tmp);
    free(L->nodes);
    free(L);
    return st;
}
