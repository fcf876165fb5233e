/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_thesis.c - the thesis's binned SAH builder (Langr 2016, section 3.4,
 * Algorithms 3 and 4; binning after Wald 2007), in its three setups.
 *
 * For each node: the bounds of the primitives' centroids (box centres), the
 * widest axis of those bounds, 16 equal bins over it, one pass that drops
 * every primitive into its bin (count and box), a sweep over the 15 planes
 * between bins for the least Ci * (A_L N_L + A_R N_R) / A, and an in-place
 * partition of the reference array. The loop is non-recursive: it keeps an
 * explicit stack, pushes the right child and goes on with the left one. The
 * node pool holds 2N - 1 nodes from the start (a binary tree with at least one
 * primitive per leaf never needs more) and is shrunk to the nodes used.
 *
 * Leaf rule (the thesis's): a node with at most leaf_size primitives is a
 * leaf, every larger node is split. The split is never weighed against a leaf,
 * so Ct and Ci choose nothing here (the best plane minimises A_L N_L + A_R N_R
 * for any positive costs); they only enter the quality figures.
 *
 * Where binning finds no plane with primitives on both sides (all centroids
 * in one bin: equal centroids, or a centroid extent too small or too large to
 * bin in float), the node is split in the middle of its list. From depth
 * ceil(log2 N) + 48 on, every split is such a middle split, which halves the
 * count, so no tree is deeper than 2 ceil(log2 N) + 50 and the explicit stack
 * (sized from that bound) cannot overflow.
 *
 * Setups:
 * - RT_BUILDER_THESIS_SCALAR: one thread, scalar loops.
 * - RT_BUILDER_THESIS_NEON: one thread; centroid bounds and bin indices four at
 *   a time through simd_neon.h. The same tree, node for node, as the scalar
 *   setup (see bvh_thesis_kernels.h).
 * - RT_BUILDER_THESIS_MT: two phases. One thread splits until subtrees hold
 *   fewer than N / n_S primitives (n_S = 8); then options.threads threads
 *   (created for this build, as in the thesis; <= 0: one per core) take those
 *   subtrees through an atomic counter, each into its own reserved part of the
 *   node pool. The subtrees see the same splits as in the one-thread setups,
 *   and a last pass lays the nodes out in the one-thread order, so the output
 *   is identical to the scalar setup's, nodes and indices, for any thread
 *   count. (The thesis did not need that last pass; it costs one copy of the
 *   nodes and makes the setups comparable byte for byte.)
 *
 * The empty input gives the empty tree: node_count 0, nodes NULL.
 */
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "accel/bvh_internal.h"
#include "base/error.h"
#include "accel/bvh_thesis_kernels.h"

#define SUBTREE_SPLIT_FACTOR 8 /* n_S of the thesis's second phase */
#define MAX_THREADS          256
#define BIN_EPSILON          1e-6f /* keeps the top centroid inside the last bin */

typedef struct range_item {
    uint32_t node, start, end, depth;
} range_item;

typedef struct subtree_task {
    range_item root;
    uint32_t region; /* first node of its reserved part of the pool */
    uint32_t used;   /* nodes it used there */
} subtree_task;

typedef struct build_ctx {
    uint32_t count;
    uint32_t leaf_size;
    int bins;
    int use_neon;
    uint32_t force_middle_depth; /* from this depth on, split in the middle */
    uint32_t stack_cap;
    rt_aabb *ref_box; /* per reference slot, partitioned with prim_indices */
    float *cent[3];   /* per slot, structure of arrays for NEON loads */
    uint32_t *prims;  /* per slot: the primitive index (the output array) */
    uint8_t *bin_ids; /* per slot scratch: bin of the current node's split */
    rt_node *nodes;   /* the pool */
    /* The second phase of the MT setup: nodes smaller than defer_below become
     * subtree tasks instead of being split. 0 when not deferring. */
    uint32_t defer_below;
    subtree_task *tasks;
    uint32_t task_count;
} build_ctx;

typedef struct bin {
    rt_aabb box;
    uint32_t count;
} bin;

static const rt_aabb empty_box = {{INFINITY, INFINITY, INFINITY},
                                  {-INFINITY, -INFINITY, -INFINITY}};

static void box_grow(rt_aabb *b, const rt_aabb *x) {
    for (int k = 0; k < 3; k++) {
        b->bmin[k] = x->bmin[k] < b->bmin[k] ? x->bmin[k] : b->bmin[k];
        b->bmax[k] = x->bmax[k] > b->bmax[k] ? x->bmax[k] : b->bmax[k];
    }
}

/* Half the surface area, in double so that huge coordinates do not overflow. */
static double box_half_area(const rt_aabb *b) {
    double dx = (double)b->bmax[0] - b->bmin[0];
    double dy = (double)b->bmax[1] - b->bmin[1];
    double dz = (double)b->bmax[2] - b->bmin[2];
    return dx * dy + dy * dz + dz * dx;
}

static void set_node_box(rt_node *node, const rt_aabb *b) {
    memcpy(node->bmin, b->bmin, sizeof node->bmin);
    memcpy(node->bmax, b->bmax, sizeof node->bmax);
}

static uint32_t ceil_log2(uint32_t n) {
    uint32_t k = 0;
    while (k < 32 && ((uint64_t)1 << k) < n) k++;
    return k;
}

static void swap_slots(build_ctx *c, uint32_t i, uint32_t j) {
    rt_aabb b = c->ref_box[i];
    c->ref_box[i] = c->ref_box[j];
    c->ref_box[j] = b;
    uint32_t p = c->prims[i];
    c->prims[i] = c->prims[j];
    c->prims[j] = p;
    for (int k = 0; k < 3; k++) {
        float f = c->cent[k][i];
        c->cent[k][i] = c->cent[k][j];
        c->cent[k][j] = f;
    }
}

/* Splits [start, end) in the middle of the list; returns the middle. */
static uint32_t split_middle(build_ctx *c, uint32_t start, uint32_t end, rt_aabb *left,
                             rt_aabb *right) {
    uint32_t mid = start + (end - start) / 2;
    *left = empty_box;
    *right = empty_box;
    for (uint32_t i = start; i < mid; i++) box_grow(left, &c->ref_box[i]);
    for (uint32_t i = mid; i < end; i++) box_grow(right, &c->ref_box[i]);
    return mid;
}

/* Chooses the binned SAH split of [start, end), partitions the slots and
 * returns the first slot of the right part, with both parts' boxes. */
static uint32_t split_node(build_ctx *c, uint32_t start, uint32_t end, uint32_t depth,
                           rt_aabb *left, rt_aabb *right) {
    if (depth >= c->force_middle_depth) return split_middle(c, start, end, left, right);

    float cmin[3], cmax[3];
    if (c->use_neon)
        rt_thesis_centroid_bounds_neon(c->cent, start, end, cmin, cmax);
    else
        rt_thesis_centroid_bounds_scalar(c->cent, start, end, cmin, cmax);
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (cmax[k] - cmin[k] > cmax[axis] - cmin[axis]) axis = k;
    float extent = cmax[axis] - cmin[axis];
    float scale = ((float)c->bins * (1.0f - BIN_EPSILON)) / extent;
    if (!(extent > 0.0f) || !isfinite(scale)) return split_middle(c, start, end, left, right);

    const int nb = c->bins;
    if (c->use_neon)
        rt_thesis_bin_ids_neon(c->cent[axis], start, end, cmin[axis], scale, nb - 1, c->bin_ids);
    else
        rt_thesis_bin_ids_scalar(c->cent[axis], start, end, cmin[axis], scale, nb - 1, c->bin_ids);

    bin bins[256];
    for (int b = 0; b < nb; b++) {
        bins[b].box = empty_box;
        bins[b].count = 0;
    }
    for (uint32_t i = start; i < end; i++) {
        bin *b = &bins[c->bin_ids[i]];
        b->count++;
        box_grow(&b->box, &c->ref_box[i]);
    }

    /* Plane p (1..nb-1) puts bins [0, p) left and [p, nb) right. */
    rt_aabb right_box[256];
    double right_area[256];
    uint32_t right_count[256];
    rt_aabb acc = empty_box;
    uint32_t n = 0;
    for (int p = nb - 1; p >= 1; p--) {
        box_grow(&acc, &bins[p].box);
        n += bins[p].count;
        right_box[p] = acc;
        right_count[p] = n;
        right_area[p] = n ? box_half_area(&acc) : 0.0;
    }
    int best = 0;
    double best_cost = INFINITY;
    rt_aabb left_acc = empty_box, best_left = empty_box;
    n = 0;
    for (int p = 1; p < nb; p++) {
        box_grow(&left_acc, &bins[p - 1].box);
        n += bins[p - 1].count;
        if (!n || !right_count[p]) continue;
        double cost = box_half_area(&left_acc) * n + right_area[p] * right_count[p];
        if (cost < best_cost) {
            best_cost = cost;
            best = p;
            best_left = left_acc;
        }
    }
    if (!best) return split_middle(c, start, end, left, right);

    /* In-place partition: slots with a bin below the plane go left. */
    uint32_t i = start, j = end;
    while (i < j) {
        if (c->bin_ids[i] < best) {
            i++;
        } else {
            j--;
            swap_slots(c, i, j);
            c->bin_ids[i] = c->bin_ids[j];
        }
    }
    *left = best_left;
    *right = right_box[best];
    return i;
}

/* Builds the subtree whose root node (box already set) covers root.start..end,
 * taking nodes from *next up to limit. Returns 0, or -1 if the pool or the
 * stack would overflow (the bounds above say it cannot). */
static int build_subtree(build_ctx *c, range_item item, uint32_t *next, uint32_t limit,
                         range_item *stack) {
    uint32_t top = 0;
    for (;;) {
        uint32_t n = item.end - item.start;
        rt_node *node = &c->nodes[item.node];
        if (n <= c->leaf_size) {
            node->a = item.start;
            node->b = n | RT_NODE_LEAF_FLAG;
        } else if (n < c->defer_below) {
            c->tasks[c->task_count].root = item;
            c->task_count++;
        } else {
            if (*next + 2 > limit || top + 1 >= c->stack_cap) return -1;
            rt_aabb lb, rb;
            uint32_t mid = split_node(c, item.start, item.end, item.depth, &lb, &rb);
            uint32_t l = (*next)++, r = (*next)++;
            node->a = l;
            node->b = r;
            set_node_box(&c->nodes[l], &lb);
            set_node_box(&c->nodes[r], &rb);
            stack[top++] = (range_item){r, mid, item.end, item.depth + 1};
            item = (range_item){l, item.start, mid, item.depth + 1};
            continue;
        }
        if (!top) return 0;
        item = stack[--top];
    }
}

/* ---- the MT setup's second phase -------------------------------------------- */

typedef struct phase2 {
    build_ctx *ctx;
    range_item **stacks;
    atomic_uint next_task;
    atomic_int failed;
} phase2;

typedef struct phase2_worker {
    phase2 *shared;
    int index;
} phase2_worker;

static void *phase2_run(void *arg) {
    phase2_worker *w = arg;
    phase2 *s = w->shared;
    build_ctx *c = s->ctx;
    for (;;) {
        unsigned t = atomic_fetch_add(&s->next_task, 1u);
        if (t >= c->task_count) break;
        subtree_task *task = &c->tasks[t];
        uint32_t n = task->root.end - task->root.start;
        uint32_t next = task->region;
        if (build_subtree(c, task->root, &next, task->region + 2 * n - 2, s->stacks[w->index]))
            atomic_store(&s->failed, 1);
        task->used = next - task->region;
    }
    return NULL;
}

static int cmp_task_size_desc(const void *a, const void *b) {
    const subtree_task *x = a, *y = b;
    uint32_t nx = x->root.end - x->root.start, ny = y->root.end - y->root.start;
    if (nx != ny) return nx > ny ? -1 : 1;
    return x->root.start < y->root.start ? -1 : x->root.start > y->root.start;
}

static int thread_count(int requested) {
    if (requested > 0) return requested < MAX_THREADS ? requested : MAX_THREADS;
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > MAX_THREADS ? MAX_THREADS : (int)n;
}

/* Copies the pool's tree into out in the order the one-thread setups number
 * nodes: children in pairs, in preorder, left subtree first. Returns the
 * number of nodes written, or 0 if the stack would overflow. */
static uint32_t lay_out_like_scalar(const build_ctx *c, rt_node *out, uint32_t cap,
                                    range_item *stack) {
    uint32_t top = 0, next = 1;
    uint32_t from = 0, to = 0; /* pool node, output node */
    for (;;) {
        rt_node node = c->nodes[from];
        if (!(node.b & RT_NODE_LEAF_FLAG)) {
            if (top + 1 >= c->stack_cap || next + 2 > cap) return 0;
            uint32_t l = next++, r = next++;
            stack[top++] = (range_item){node.b, r, 0, 0};
            from = node.a;
            node.a = l;
            node.b = r;
            out[to] = node;
            to = l;
            continue;
        }
        out[to] = node;
        if (!top) return next;
        top--;
        from = stack[top].node;
        to = stack[top].start;
    }
}

static rt_status run_mt(build_ctx *c, const rt_build_options *o, uint32_t *node_count,
                        rt_node **final_nodes, range_item *stack0, rt_error *err) {
    uint32_t n = c->count;
    c->defer_below = n / SUBTREE_SPLIT_FACTOR;
    c->tasks = malloc(sizeof(subtree_task) * (n / (c->leaf_size + 1) + 1));
    if (!c->tasks) return RT_ERROR_OUT_OF_MEMORY;
    uint32_t next = 1;
    if (build_subtree(c, (range_item){0, 0, n, 1}, &next, 2 * n - 1, stack0)) {
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                       "thesis builder: node pool or stack overflow");
    }
    c->defer_below = 0;
    uint32_t first_phase_nodes = next;
    qsort(c->tasks, c->task_count, sizeof *c->tasks, cmp_task_size_desc);
    for (uint32_t t = 0; t < c->task_count; t++) {
        c->tasks[t].region = next;
        next += 2 * (c->tasks[t].root.end - c->tasks[t].root.start) - 2;
    }

    int workers = thread_count(o->threads);
    if ((uint32_t)workers > c->task_count) workers = c->task_count ? (int)c->task_count : 1;
    phase2 shared;
    shared.ctx = c;
    atomic_init(&shared.next_task, 0u);
    atomic_init(&shared.failed, 0);
    range_item *stacks[MAX_THREADS];
    phase2_worker info[MAX_THREADS];
    pthread_t threads[MAX_THREADS];
    int started = 0;
    rt_status status = RT_OK;
    stacks[0] = stack0;
    for (int w = 1; w < workers; w++) {
        stacks[w] = malloc(sizeof(range_item) * c->stack_cap);
        if (!stacks[w]) {
            workers = w; /* fewer threads, same result */
            break;
        }
    }
    shared.stacks = stacks;
    for (int w = 0; w < workers; w++) info[w] = (phase2_worker){&shared, w};
    for (int w = 1; w < workers; w++) {
        if (pthread_create(&threads[w], NULL, phase2_run, &info[w]) != 0) break;
        started = w;
    }
    phase2_run(&info[0]);
    for (int w = 1; w <= started; w++) pthread_join(threads[w], NULL);
    for (int w = 1; w < workers; w++) free(stacks[w]);
    if (atomic_load(&shared.failed)) {
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                       "thesis builder: node pool or stack overflow");
    }

    uint32_t total = first_phase_nodes;
    for (uint32_t t = 0; t < c->task_count; t++) total += c->tasks[t].used;
    rt_node *out = malloc(sizeof(rt_node) * total);
    if (!out) return RT_ERROR_OUT_OF_MEMORY;
    uint32_t written = lay_out_like_scalar(c, out, total, stack0);
    if (written != total) {
        free(out);
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "thesis builder: subtree layout mismatch");
    }
    *final_nodes = out;
    *node_count = total;
    return status;
}

/* ---- entry point -------------------------------------------------------------- */

rt_status rt_bvh_build_thesis(const rt_aabb *boxes, uint32_t count, const rt_build_options *options,
                              rt_pool *pool, rt_bvh *out, rt_error *err) {
    memset(out, 0, sizeof *out);
    if (count == 0) return RT_OK;
    if (count > (1u << 30)) {
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "thesis builder: %u primitives is too many",
                       count);
    }
    for (uint32_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++)
            if (!isfinite(boxes[i].bmin[k]) || !isfinite(boxes[i].bmax[k])) {
                rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                        "thesis builder: primitive %u has a non-finite box", i);
                return RT_ERROR_INVALID_ARGUMENT;
            }

    build_ctx c;
    memset(&c, 0, sizeof c);
    c.count = count;
    c.leaf_size = (uint32_t)options->leaf_size;
    c.bins = options->bins;
    c.use_neon = options->builder != RT_BUILDER_THESIS_SCALAR;
    c.force_middle_depth = ceil_log2(count) + 48;
    c.stack_cap = 2 * ceil_log2(count) + 64;
    c.ref_box = malloc(sizeof(rt_aabb) * count);
    c.prims = malloc(sizeof(uint32_t) * count);
    c.bin_ids = malloc(count);
    c.nodes = malloc(sizeof(rt_node) * (2 * (size_t)count - 1));
    range_item *stack = malloc(sizeof(range_item) * c.stack_cap);
    for (int k = 0; k < 3; k++) c.cent[k] = malloc(sizeof(float) * count);
    rt_status status = RT_OK;
    if (!c.ref_box || !c.prims || !c.bin_ids || !c.nodes || !stack || !c.cent[0] || !c.cent[1] ||
        !c.cent[2]) {
        status = RT_ERROR_OUT_OF_MEMORY;
        goto done;
    }

    rt_aabb root = empty_box;
    for (uint32_t i = 0; i < count; i++) {
        c.ref_box[i] = boxes[i];
        c.prims[i] = i;
        /* Halves first: the sum of two huge coordinates would overflow. */
        for (int k = 0; k < 3; k++)
            c.cent[k][i] = 0.5f * boxes[i].bmin[k] + 0.5f * boxes[i].bmax[k];
        box_grow(&root, &boxes[i]);
    }
    set_node_box(&c.nodes[0], &root);

    if (options->builder == RT_BUILDER_THESIS_MT) {
        rt_node *final_nodes = NULL;
        status = run_mt(&c, options, &out->node_count, &final_nodes, stack, err);
        if (status != RT_OK) goto done;
        free(c.nodes);
        c.nodes = final_nodes;
    } else {
        uint32_t next = 1;
        if (build_subtree(&c, (range_item){0, 0, count, 1}, &next, 2 * count - 1, stack)) {
            rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "thesis builder: node pool or stack overflow");
            status = RT_ERROR_INVALID_ARGUMENT;
            goto done;
        }
        out->node_count = next;
        rt_node *shrunk = realloc(c.nodes, sizeof(rt_node) * next);
        if (shrunk) c.nodes = shrunk;
    }
    out->nodes = c.nodes;
    out->prim_indices = c.prims;
    out->prim_count = count;
    c.nodes = NULL;
    c.prims = NULL;

done:
    if (status == RT_ERROR_OUT_OF_MEMORY)
        rt_fail(err, status, "thesis builder: out of memory for %u primitives", count);
    if (status != RT_OK) memset(out, 0, sizeof *out);
    free(c.ref_box);
    free(c.prims);
    free(c.bin_ids);
    free(c.nodes);
    free(c.tasks);
    free(stack);
    for (int k = 0; k < 3; k++) free(c.cent[k]);
    return status;
}
