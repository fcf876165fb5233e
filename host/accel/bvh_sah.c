/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_sah.c - the default BVH builder: binned SAH (Wald 2007) on a
 * persistent thread pool, deterministic for any thread count.
 *
 * Phases
 * 1. Setup (all workers): boxes -> 32-byte references, root box and centroid
 *    bounds.
 * 2. Horizontal phase (all workers on one node at a time): every node of at
 *    least `big` primitives is binned in parallel (each worker bins a chunk,
 *    the bins are merged) and partitioned in parallel (a stable partition:
 *    each worker knows from its own bins where its chunk's left and right
 *    parts go).
 * 3. Task phase: the remaining subtrees are taken by workers through an
 *    atomic counter and built serially, each with an explicit stack.
 * 4. Compaction: nodes were written at slots fixed by the primitive counts (a
 *    subtree of n primitives owns 2n-1 slots: left child at slot+1, right
 *    child at slot+2*n_left), so no allocation order leaks into the result;
 *    a depth-first walk then numbers them densely.
 *
 * Every decision is a function of the node's primitives only (binning uses
 * exact min/max and integer counts; the SAH sweep runs on one thread in a
 * fixed order), so the tree is the same for any thread count and for the
 * scalar and NEON loops.
 *
 * Leaves: a node becomes a leaf when it holds at most leaf_size primitives
 * and its SAH cost (Ci * n * area) is not above the best split's; above
 * leaf_size it is always split (by the median of its reference order when no
 * binned split exists, e.g. all centroids equal). Depth is bounded: from
 * FORCE_MEDIAN_DEPTH on, splits are median splits, which halve the count.
 */
#include <float.h>
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh_sah_kernels.h"
#include "accel/bvh_internal.h"
#include "base/error.h"
#include "base/thread_pool.h"

enum {
    FORCE_MEDIAN_DEPTH = 32, /* depth <= 32 + log2(n) <= 64 */
    STACK_SIZE = 128,
    MIN_BIG_NODE = 4096, /* smaller nodes are not worth a parallel pass */
    SMALL_N = 4,         /* subtrees this small are built by exact SAH */
    /* Nodes under 64 primitives are binned into 8 bins: the SAH sweep and
     * the bin clearing cost in proportion to the bins, and the tree's SAH
     * moved by less than 0.1% on the shared scenes. */
    SMALL_BINS_BELOW = 64,
    SMALL_BINS = 8
};

/* Scratch memory kept between builds: the two reference buffers and the
 * slot array (128 bytes per primitive) are freshly mapped pages otherwise,
 * and first-touch page faults cost about as much as a fifth of a
 * single-threaded build. One block is kept for the process, taken and given
 * back with atomic exchanges (concurrent builds simply allocate their own);
 * blocks above KEEP_LIMIT bytes are not kept. */
#define KEEP_LIMIT ((size_t)64 << 20)

typedef struct scratch {
    uint32_t cap; /* primitives */
    rt_sah_ref *refs[2];
    rt_node *slots; /* 2 * cap - 1 */
} scratch;

static _Atomic(scratch *) kept_scratch;

static void scratch_free(scratch *s) {
    if (!s) return;
    free(s->refs[0]);
    free(s->refs[1]);
    free(s->slots);
    free(s);
}

static scratch *scratch_take(uint32_t count) {
    scratch *s = atomic_exchange(&kept_scratch, NULL);
    if (s && s->cap >= count) return s;
    scratch_free(s);
    s = calloc(1, sizeof *s);
    if (!s) return NULL;
    s->cap = count;
    s->refs[0] = malloc((size_t)count * sizeof(rt_sah_ref));
    s->refs[1] = malloc((size_t)count * sizeof(rt_sah_ref));
    s->slots = malloc((2 * (size_t)count - 1) * sizeof(rt_node));
    if (!s->refs[0] || !s->refs[1] || !s->slots) {
        scratch_free(s);
        return NULL;
    }
    return s;
}

/* Whether s is small enough to be kept for the next build. */
static int scratch_kept(const scratch *s) {
    return (size_t)s->cap * (2 * sizeof(rt_sah_ref) + 2 * sizeof(rt_node)) <= KEEP_LIMIT;
}

static void scratch_give_back(scratch *s) {
    if (!s) return;
    if (!scratch_kept(s) || !s->refs[0]) {
        scratch_free(s);
        return;
    }
    scratch_free(atomic_exchange(&kept_scratch, s));
}

void rt_bvh_sah_release_scratch(void) {
    scratch_free(atomic_exchange(&kept_scratch, NULL));
}

typedef struct task {
    uint32_t begin, end; /* reference range */
    uint32_t slot;       /* node slot in the 2n-1 layout */
    uint32_t depth;      /* root = 0 */
    int buf;             /* which reference buffer holds the range */
    float lo[3], hi[3];  /* node box */
    float cmin[3], cmax[3];
} task;

typedef enum split_kind { SPLIT_LEAF, SPLIT_MEDIAN, SPLIT_BINNED } split_kind;

typedef struct split_plan {
    split_kind kind;
    int axis, bin;
    uint32_t n_left;
    float llo[3], lhi[3], rlo[3], rhi[3]; /* child boxes (binned splits) */
} split_plan;

/* A task subtree's root slot and its index in the task list. */
typedef struct slot_task {
    uint32_t slot, task;
} slot_task;

typedef struct build_ctx {
    const rt_aabb *boxes; /* the input boxes, or NULL: the triangles' (positions, indices) */
    const float *positions;
    const uint32_t *indices;
    scratch *mem; /* where refs and slots live */
    uint32_t count;
    int bins, leaf_size;
    float cost_box, cost_tri;
    int use_neon;
    int workers;
    rt_sah_ref *refs[2];
    rt_node *slots; /* 2n-1 */
    uint32_t *prim_indices;
    rt_sah_bins *worker_bins; /* one per worker */
    rt_sah_bins *merged_bins;
    rt_sah_cbounds *worker_cb; /* two per worker: left, right */
    atomic_int bad_input;
    /* current parallel job */
    const task *job;
    rt_sah_binning job_bn;
    split_plan job_plan;
    uint32_t *job_left; /* per-worker left counts, then offsets */
    /* task phase */
    task *tasks;
    uint32_t task_count, task_cap;
    atomic_uint next_task;
    atomic_int task_failed;
    /* compaction: per task (in task order) its node count, then its first
     * index in the output */
    uint32_t *task_nodes, *task_base;
    slot_task *slot_tasks; /* by slot */
    rt_node *out_nodes;
} build_ctx;

static inline float fmin_exact(float a, float b) {
    return a < b ? a : b;
}
static inline float fmax_exact(float a, float b) {
    return a > b ? a : b;
}

static double half_area(const float lo[3], const float hi[3]) {
    double dx = (double)hi[0] - lo[0], dy = (double)hi[1] - lo[1], dz = (double)hi[2] - lo[2];
    return dx * dy + dy * dz + dz * dx;
}

static void chunk_of(const task *t, int w, int n, uint32_t *b, uint32_t *e) {
    uint64_t len = t->end - t->begin;
    *b = t->begin + (uint32_t)(len * (uint64_t)w / (uint64_t)n);
    *e = t->begin + (uint32_t)(len * (uint64_t)(w + 1) / (uint64_t)n);
}

/* ---- split decisions (serial, deterministic) ---------------------------- */

/* Sets up binning; returns 0 when no axis can be binned. */
static int setup_binning(const build_ctx *c, const task *t, rt_sah_binning *bn) {
    int any = 0;
    /* No more bins than primitives: small nodes are the most numerous, and
     * clearing and sweeping 3 x 16 bins for 3 primitives cost more than the
     * binning itself. */
    uint32_t n = t->end - t->begin;
    bn->bins = n < (uint32_t)c->bins ? (int)n : c->bins;
    if (n < SMALL_BINS_BELOW && bn->bins > SMALL_BINS) bn->bins = SMALL_BINS;
    bn->cmin[3] = 0.0f;
    bn->scale[3] = 0.0f;
    for (int a = 0; a < 3; a++) {
        float ext = t->cmax[a] - t->cmin[a];
        float scale = (float)bn->bins / ext;
        bn->axis_ok[a] = ext > 0.0f && ext <= FLT_MAX && scale <= FLT_MAX;
        bn->cmin[a] = bn->axis_ok[a] ? t->cmin[a] : 0.0f;
        bn->scale[a] = bn->axis_ok[a] ? scale : 0.0f;
        any |= bn->axis_ok[a];
    }
    return any;
}

/* What to do before binning: a leaf, a median split, or bin (SPLIT_BINNED). */
static split_kind pre_decide(const build_ctx *c, const task *t, rt_sah_binning *bn) {
    uint32_t n = t->end - t->begin;
    if (n <= 1) return SPLIT_LEAF;
    int binnable = setup_binning(c, t, bn);
    if (!binnable || t->depth >= FORCE_MEDIAN_DEPTH)
        return n <= (uint32_t)c->leaf_size ? SPLIT_LEAF : SPLIT_MEDIAN;
    return SPLIT_BINNED;
}

/* A power of two that brings the largest half extent of the node box into
 * [1, 2), so that the sweep's float areas and costs cannot overflow. */
static float sweep_scale(const task *t) {
    float m = 0.0f;
    for (int j = 0; j < 3; j++) m = fmax_exact(m, t->hi[j] * 0.5f - t->lo[j] * 0.5f);
    if (!(m > 0.0f)) return 1.0f;
    int e = ilogbf(m);
    if (e < -100) e = -100;
    return ldexpf(1.0f, -e);
}

/* SAH sweep over the bins of every binnable axis. */
static void choose_split(const build_ctx *c, const task *t, const rt_sah_binning *bn,
                         const rt_sah_bins *bins, split_plan *plan) {
    const int B = bn->bins;
    uint32_t n = t->end - t->begin;
    float scale = sweep_scale(t), best_f;
    int best_axis, best_bin;
    if (!rt_sah_sweep(bins, bn, scale, &best_f, &best_axis, &best_bin)) {
        plan->kind = n <= (uint32_t)c->leaf_size ? SPLIT_LEAF : SPLIT_MEDIAN;
        return;
    }
    double area = rt_sah_scaled_area(t->lo, t->hi, scale), best = best_f;
    double split_cost = c->cost_box * area + c->cost_tri * best;
    double leaf_cost = (double)c->cost_tri * n * area;
    if (n <= (uint32_t)c->leaf_size && leaf_cost <= split_cost) {
        plan->kind = SPLIT_LEAF;
        return;
    }
    plan->kind = SPLIT_BINNED;
    plan->axis = best_axis;
    plan->bin = best_bin;
    float llo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, lhi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    float rlo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, rhi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    uint32_t nl = 0;
    for (int k = 0; k < B; k++) {
        const rt_sah_box4 *b = &bins->box[best_axis][k];
        float *lo = k <= best_bin ? llo : rlo, *hi = k <= best_bin ? lhi : rhi;
        for (int j = 0; j < 3; j++) {
            lo[j] = fmin_exact(lo[j], b->lo[j]);
            hi[j] = fmax_exact(hi[j], b->hi[j]);
        }
        if (k <= best_bin) nl += bins->count[k][best_axis];
    }
    plan->n_left = nl;
    memcpy(plan->llo, llo, sizeof llo);
    memcpy(plan->lhi, lhi, sizeof lhi);
    memcpy(plan->rlo, rlo, sizeof rlo);
    memcpy(plan->rhi, rhi, sizeof rhi);
}

/* ---- node output -------------------------------------------------------- */

static void write_leaf(build_ctx *c, const task *t) {
    rt_node *node = &c->slots[t->slot];
    memcpy(node->bmin, t->lo, sizeof t->lo);
    memcpy(node->bmax, t->hi, sizeof t->hi);
    node->a = t->begin;
    node->b = (t->end - t->begin) | RT_NODE_LEAF_FLAG;
    const rt_sah_ref *refs = c->refs[t->buf];
    for (uint32_t i = t->begin; i < t->end; i++) memcpy(&c->prim_indices[i], &refs[i].lo[3], 4);
}

static void make_children(const task *t, uint32_t n_left, int buf, task *l, task *r) {
    *l = *t;
    *r = *t;
    l->end = r->begin = t->begin + n_left;
    l->slot = t->slot + 1;
    r->slot = t->slot + 2 * n_left;
    l->depth = r->depth = t->depth + 1;
    l->buf = r->buf = buf;
}

static void write_inner(build_ctx *c, const task *t, const task *l, const task *r) {
    rt_node *node = &c->slots[t->slot];
    memcpy(node->bmin, t->lo, sizeof t->lo);
    memcpy(node->bmax, t->hi, sizeof t->hi);
    node->a = l->slot;
    node->b = r->slot;
}

static void set_cbounds(task *t, const rt_sah_cbounds *cb) {
    memcpy(t->cmin, cb->cmin, sizeof t->cmin);
    memcpy(t->cmax, cb->cmax, sizeof t->cmax);
}

/* Median split in reference order: no data moves; child boxes and centroid
 * bounds come from one pass over each half. */
static void median_split(const build_ctx *c, const task *t, task *l, task *r) {
    make_children(t, (t->end - t->begin) / 2, t->buf, l, r);
    task *side[2] = {l, r};
    for (int s = 0; s < 2; s++) {
        task *ch = side[s];
        rt_sah_cbounds cb;
        rt_sah_centroid_bounds(c->refs[t->buf], ch->begin, ch->end, &cb);
        set_cbounds(ch, &cb);
        for (int j = 0; j < 3; j++) {
            ch->lo[j] = FLT_MAX;
            ch->hi[j] = -FLT_MAX;
        }
        for (uint32_t i = ch->begin; i < ch->end; i++) {
            const rt_sah_ref *ref = &c->refs[t->buf][i];
            for (int j = 0; j < 3; j++) {
                ch->lo[j] = fmin_exact(ch->lo[j], ref->lo[j]);
                ch->hi[j] = fmax_exact(ch->hi[j], ref->hi[j]);
            }
        }
    }
}

static void binned_children(const task *t, const split_plan *p, const rt_sah_cbounds *lcb,
                            const rt_sah_cbounds *rcb, task *l, task *r) {
    make_children(t, p->n_left, !t->buf, l, r);
    memcpy(l->lo, p->llo, sizeof l->lo);
    memcpy(l->hi, p->lhi, sizeof l->hi);
    memcpy(r->lo, p->rlo, sizeof r->lo);
    memcpy(r->hi, p->rhi, sizeof r->hi);
    set_cbounds(l, lcb);
    set_cbounds(r, rcb);
}

/* ---- small subtrees: exact SAH over every partition ----------------------- */

/* Nodes of at most SMALL_N primitives are the most numerous (with the
 * thesis's costs the SAH splits down to one or two triangles per leaf). For
 * them, binning costs more than trying every partition into two sets
 * (2^(n-1) - 1 of them), which also finds the exact SAH optimum. The whole
 * subtree is built from a local copy. */
typedef struct small_item {
    float lo[3], hi[3];
    uint32_t index;
} small_item;

/* Subset boxes and areas of up to SMALL_N items, indexed by item mask. */
typedef struct subset_table {
    float lo[1 << SMALL_N][3], hi[1 << SMALL_N][3];
    double area[1 << SMALL_N];
} subset_table;

/* Builds the node of the items in `set` (a mask over items, in item order)
 * at slot; its children are subsets of it, so the one table built in
 * small_subtree serves the whole subtree. */
static void small_node(build_ctx *c, const small_item *items, const subset_table *tab, uint32_t set,
                       uint32_t slot, uint32_t begin) {
    rt_node *node = &c->slots[slot];
    memcpy(node->bmin, tab->lo[set], 3 * sizeof(float));
    memcpy(node->bmax, tab->hi[set], 3 * sizeof(float));
    static const uint8_t bits[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
    int n = bits[set];
    double best = DBL_MAX;
    uint32_t best_mask = 0;
    /* The set's last member always on the right: each partition once. The
     * left sides are the non-empty subsets of `rest`, in increasing order
     * ((mask - rest) & rest steps through them). */
    uint32_t last = 1u << (31 - __builtin_clz(set)), rest = set & ~last;
    for (uint32_t mask = (0u - rest) & rest; mask; mask = (mask - rest) & rest) {
        int nl = bits[mask];
        double cost = tab->area[mask] * nl + tab->area[set & ~mask] * (n - nl);
        if (cost < best) {
            best = cost;
            best_mask = mask;
        }
    }
    double area = tab->area[set];
    if (n == 1 || (n <= c->leaf_size &&
                   (double)c->cost_tri * n * area <= c->cost_box * area + c->cost_tri * best)) {
        node->a = begin;
        node->b = (uint32_t)n | RT_NODE_LEAF_FLAG;
        uint32_t k = begin;
        for (int i = 0; i < SMALL_N; i++)
            if (set >> i & 1u) c->prim_indices[k++] = items[i].index;
        return;
    }
    uint32_t nl = bits[best_mask];
    node->a = slot + 1;
    node->b = slot + 2 * nl;
    small_node(c, items, tab, best_mask, slot + 1, begin);
    small_node(c, items, tab, set & ~best_mask, slot + 2 * nl, begin + nl);
}

static void small_subtree(build_ctx *c, const task *t) {
    small_item items[SMALL_N];
    subset_table tab;
    int n = (int)(t->end - t->begin);
    const rt_sah_ref *refs = c->refs[t->buf];
    for (int i = 0; i < n; i++) {
        const rt_sah_ref *r = &refs[t->begin + (uint32_t)i];
        memcpy(items[i].lo, r->lo, sizeof items[i].lo);
        memcpy(items[i].hi, r->hi, sizeof items[i].hi);
        memcpy(&items[i].index, &r->lo[3], 4);
    }
    /* Every subset's box from a smaller subset plus one item (min/max are
     * exact: the same box as from scratch). SMALL_N = 4 keeps the masks
     * within the 16-entry bit count table of small_node. */
    uint32_t all = (1u << n) - 1u;
    for (int j = 0; j < 3; j++) {
        tab.lo[0][j] = FLT_MAX;
        tab.hi[0][j] = -FLT_MAX;
    }
    for (uint32_t m = 1; m <= all; m++) {
        uint32_t rest = m & (m - 1), i = (uint32_t)__builtin_ctz(m);
        for (int j = 0; j < 3; j++) {
            tab.lo[m][j] = fmin_exact(tab.lo[rest][j], items[i].lo[j]);
            tab.hi[m][j] = fmax_exact(tab.hi[rest][j], items[i].hi[j]);
        }
        tab.area[m] = half_area(tab.lo[m], tab.hi[m]);
    }
    /* The node box is the task's (the union of all items: the same). */
    small_node(c, items, &tab, all, t->slot, t->begin);
}

/* ---- serial subtree build (task phase) ---------------------------------- */

/* What a split does before the binned partition, serial or parallel: a
 * leaf plan writes the leaf (0); a median split writes t with its children
 * l and r (1); a binned plan is left to the caller (-1). */
static int leaf_or_median(build_ctx *c, const task *t, const split_plan *plan, task *l, task *r) {
    if (plan->kind == SPLIT_LEAF) {
        write_leaf(c, t);
        return 0;
    }
    if (plan->kind != SPLIT_MEDIAN) return -1;
    median_split(c, t, l, r);
    write_inner(c, t, l, r);
    return 1;
}

/* Splits t once, serially. Returns 1 with children in l and r, or 0 for a
 * leaf (already written). */
static int split_serial(build_ctx *c, const task *t, rt_sah_bins *bins, task *l, task *r) {
    rt_sah_binning bn;
    split_plan plan;
    if (t->end - t->begin <= SMALL_N) {
        small_subtree(c, t);
        return 0;
    }
    plan.kind = pre_decide(c, t, &bn);
    if (plan.kind == SPLIT_BINNED) {
        rt_sah_bins_clear(bins, bn.bins);
        rt_sah_bin_range(c->refs[t->buf], t->begin, t->end, &bn, bins, c->use_neon);
        choose_split(c, t, &bn, bins, &plan);
    }
    int done = leaf_or_median(c, t, &plan, l, r);
    if (done >= 0) return done;
    rt_sah_cbounds lcb, rcb;
    rt_sah_cbounds_empty(&lcb);
    rt_sah_cbounds_empty(&rcb);
    rt_sah_partition_range(c->refs[t->buf], t->begin, t->end, c->refs[!t->buf], t->begin,
                           t->begin + plan.n_left, &bn, plan.axis, plan.bin, &lcb, &rcb,
                           c->use_neon);
    binned_children(t, &plan, &lcb, &rcb, l, r);
    write_inner(c, t, l, r);
    return 1;
}

static int build_subtree(build_ctx *c, task root, rt_sah_bins *bins) {
    task stack[STACK_SIZE];
    int top = 0;
    task t = root;
    for (;;) {
        task l, r;
        if (split_serial(c, &t, bins, &l, &r)) {
            /* Continue with the smaller child, keep the larger. */
            uint32_t nl = l.end - l.begin, nr = r.end - r.begin;
            if (top == STACK_SIZE) return 0; /* cannot happen: depth is bounded */
            if (nl < nr) {
                stack[top++] = r;
                t = l;
            } else {
                stack[top++] = l;
                t = r;
            }
            continue;
        }
        if (top == 0) return 1;
        t = stack[--top];
    }
}

/* Nodes of the subtree at slot (a walk of the slot tree, done by the worker
 * that just built it, while it is in its cache). */
static uint32_t count_nodes(const rt_node *slots, uint32_t slot) {
    uint32_t stack[2 * STACK_SIZE], n = 0;
    int top = 0;
    stack[top++] = slot;
    while (top) {
        const rt_node *node = &slots[stack[--top]];
        n++;
        if (!(node->b & RT_NODE_LEAF_FLAG)) {
            stack[top++] = node->b;
            stack[top++] = node->a;
        }
    }
    return n;
}

static void task_phase_job(void *ctx, int worker, int worker_count) {
    build_ctx *c = ctx;
    for (;;) {
        uint32_t i = atomic_fetch_add(&c->next_task, 1);
        if (i >= c->task_count) return;
        if (!build_subtree(c, c->tasks[i], &c->worker_bins[worker]))
            atomic_store(&c->task_failed, 1);
        else
            c->task_nodes[i] = count_nodes(c->slots, c->tasks[i].slot);
    }
}

static int push_task(build_ctx *c, const task *t) {
    if (c->task_count == c->task_cap) {
        uint32_t cap = c->task_cap ? c->task_cap * 2 : 64;
        task *grown = realloc(c->tasks, cap * sizeof *grown);
        if (!grown) return 0;
        c->tasks = grown;
        c->task_cap = cap;
    }
    c->tasks[c->task_count++] = *t;
    return 1;
}

/* Largest subtrees first, so that no worker starts a big one last. */
static int task_order(const void *pa, const void *pb) {
    const task *a = pa, *b = pb;
    uint32_t na = a->end - a->begin, nb = b->end - b->begin;
    if (na != nb) return na > nb ? -1 : 1;
    return a->slot < b->slot ? -1 : a->slot > b->slot;
}

/* ---- horizontal phase: one big node, all workers -------------------------- */

static void bin_job(void *ctx, int worker, int worker_count) {
    build_ctx *c = ctx;
    uint32_t b, e;
    chunk_of(c->job, worker, worker_count, &b, &e);
    rt_sah_bins *bins = &c->worker_bins[worker];
    rt_sah_bins_clear(bins, c->job_bn.bins);
    rt_sah_bin_range(c->refs[c->job->buf], b, e, &c->job_bn, bins, c->use_neon);
}

static void partition_job(void *ctx, int worker, int worker_count) {
    build_ctx *c = ctx;
    const task *t = c->job;
    uint32_t b, e;
    chunk_of(t, worker, worker_count, &b, &e);
    /* job_left[w]: left entries of the chunks before w; the right entries
     * before w follow from the chunk start. */
    uint32_t left_before = c->job_left[worker];
    uint32_t right_before = (b - t->begin) - left_before;
    rt_sah_cbounds *lcb = &c->worker_cb[2 * worker], *rcb = &c->worker_cb[2 * worker + 1];
    rt_sah_cbounds_empty(lcb);
    rt_sah_cbounds_empty(rcb);
    rt_sah_partition_range(c->refs[t->buf], b, e, c->refs[!t->buf], t->begin + left_before,
                           t->begin + c->job_plan.n_left + right_before, &c->job_bn,
                           c->job_plan.axis, c->job_plan.bin, lcb, rcb, c->use_neon);
}

/* Splits one big node with all workers; children land in l and r. Returns 0
 * for a leaf. */
static int split_parallel(build_ctx *c, rt_pool *pool, const task *t, task *l, task *r) {
    const int W = c->workers;
    split_plan plan;
    rt_sah_binning bn;
    plan.kind = pre_decide(c, t, &bn);
    c->job = t;
    c->job_bn = bn;
    if (plan.kind == SPLIT_BINNED) {
        rt_pool_run(pool, bin_job, c);
        /* Merged into a separate set: each worker's own counts are needed
         * again to place its chunk in the partition. */
        rt_sah_bins *all = c->merged_bins;
        *all = c->worker_bins[0];
        for (int w = 1; w < W; w++) {
            const rt_sah_bins *o = &c->worker_bins[w];
            for (int a = 0; a < 3; a++) {
                for (int k = 0; k < bn.bins; k++) {
                    for (int j = 0; j < 3; j++) {
                        all->box[a][k].lo[j] = fmin_exact(all->box[a][k].lo[j], o->box[a][k].lo[j]);
                        all->box[a][k].hi[j] = fmax_exact(all->box[a][k].hi[j], o->box[a][k].hi[j]);
                    }
                    all->count[k][a] += o->count[k][a];
                }
            }
        }
        choose_split(c, t, &bn, all, &plan);
        if (plan.kind == SPLIT_BINNED) {
            uint32_t before = 0;
            for (int w = 0; w < W; w++) {
                uint32_t left = 0;
                for (int k = 0; k <= plan.bin; k++) left += c->worker_bins[w].count[k][plan.axis];
                c->job_left[w] = before;
                before += left;
            }
        }
    }
    int done = leaf_or_median(c, t, &plan, l, r);
    if (done >= 0) return done;
    c->job_plan = plan;
    rt_pool_run(pool, partition_job, c);
    rt_sah_cbounds lcb = c->worker_cb[0], rcb = c->worker_cb[1];
    for (int w = 1; w < W; w++) {
        rt_sah_cbounds_merge(&lcb, &c->worker_cb[2 * w]);
        rt_sah_cbounds_merge(&rcb, &c->worker_cb[2 * w + 1]);
    }
    binned_children(t, &plan, &lcb, &rcb, l, r);
    write_inner(c, t, l, r);
    return 1;
}

/* ---- setup: references, root box and centroid bounds --------------------- */

static void setup_job(void *ctx, int worker, int worker_count) {
    build_ctx *c = ctx;
    task whole = {0};
    whole.end = c->count;
    uint32_t b, e;
    chunk_of(&whole, worker, worker_count, &b, &e);
    /* The pair of bounds per worker holds the box (cmin/cmax used as lo/hi)
     * and the centroid bounds of its chunk. */
    rt_sah_cbounds *box = &c->worker_cb[2 * worker];
    rt_sah_cbounds *cb = &c->worker_cb[2 * worker + 1];
    rt_sah_cbounds_empty(box);
    rt_sah_cbounds_empty(cb);
    int bad = 0;
    for (uint32_t i = b; i < e; i++) {
        rt_sah_ref *r = &c->refs[0][i];
        rt_aabb tri;
        const rt_aabb *in = c->boxes ? &c->boxes[i] : &tri;
        if (!c->boxes) rt_tri_box(c->positions, c->indices + 3 * (size_t)i, &tri);
        for (int j = 0; j < 3; j++) {
            /* + 0.0f turns -0 into +0 (see bvh_sah_kernels.h). */
            float lo = in->bmin[j] + 0.0f, hi = in->bmax[j] + 0.0f;
            bad |= !(lo >= -FLT_MAX && hi <= FLT_MAX && lo <= hi);
            r->lo[j] = lo;
            r->hi[j] = hi;
            box->cmin[j] = fmin_exact(box->cmin[j], lo);
            box->cmax[j] = fmax_exact(box->cmax[j], hi);
            float cen = lo * 0.5f + hi * 0.5f;
            cb->cmin[j] = fmin_exact(cb->cmin[j], cen);
            cb->cmax[j] = fmax_exact(cb->cmax[j], cen);
        }
        memcpy(&r->lo[3], &i, 4);
        r->hi[3] = 0.0f;
    }
    if (bad) atomic_store(&c->bad_input, 1);
}

/* ---- compaction: dense depth-first numbering ------------------------------ */

static int slot_task_order(const void *pa, const void *pb) {
    const slot_task *a = pa, *b = pb;
    return a->slot < b->slot ? -1 : a->slot > b->slot;
}

/* The task whose subtree is rooted at slot, or UINT32_MAX. */
static uint32_t task_at_slot(const build_ctx *c, uint32_t slot) {
    uint32_t lo = 0, hi = c->task_count;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (c->slot_tasks[mid].slot < slot)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < c->task_count && c->slot_tasks[lo].slot == slot ? c->slot_tasks[lo].task
                                                                : UINT32_MAX;
}

/* Numbers the subtree at slot densely from `base` into out, depth first, left
 * child next. When `tasks` is given (the top of the tree), the roots of the
 * task subtrees are not entered: each gets its base (task_base) and the
 * range of its node count, and is copied by compact_job. */
static uint32_t compact(build_ctx *c, uint32_t slot, uint32_t base, rt_node *out, int top_level) {
    struct item {
        uint32_t slot, parent; /* parent: index whose right child this is */
    } stack[2 * STACK_SIZE];
    int top = 0;
    uint32_t next = base;
    stack[top++] = (struct item){slot, UINT32_MAX};
    while (top) {
        struct item it = stack[--top];
        uint32_t idx = next;
        if (it.parent != UINT32_MAX) out[it.parent].b = idx;
        if (top_level) {
            uint32_t t = task_at_slot(c, it.slot);
            if (t != UINT32_MAX) {
                c->task_base[t] = idx;
                next += c->task_nodes[t];
                continue;
            }
        }
        next++;
        out[idx] = c->slots[it.slot];
        if (!(out[idx].b & RT_NODE_LEAF_FLAG)) {
            uint32_t left = out[idx].a, right = out[idx].b;
            out[idx].a = idx + 1; /* the left child is numbered next */
            stack[top++] = (struct item){right, idx};
            stack[top++] = (struct item){left, UINT32_MAX};
        }
    }
    return next - base;
}

static void compact_job(void *ctx, int worker, int worker_count) {
    build_ctx *c = ctx;
    (void)worker;
    (void)worker_count;
    for (;;) {
        uint32_t i = atomic_fetch_add(&c->next_task, 1);
        if (i >= c->task_count) return;
        compact(c, c->tasks[i].slot, c->task_base[i], c->out_nodes, 0);
    }
}

/* ---- entry point ------------------------------------------------------------ */

static void free_ctx(build_ctx *c) {
    free(c->worker_bins);
    free(c->merged_bins);
    free(c->worker_cb);
    free(c->job_left);
    free(c->tasks);
    free(c->task_nodes);
    free(c->task_base);
    free(c->slot_tasks);
}

static rt_status fail(rt_error *err, rt_status st, const char *text) {
    rt_fail(err, st, "fast BVH builder: %s", text);
    return st;
}

static rt_status run_build(build_ctx *c, rt_pool *pool, rt_bvh *out, rt_error *err) {
    const uint32_t N = c->count;
    const int W = c->workers;
    rt_pool_run(pool, setup_job, c);
    if (atomic_load(&c->bad_input))
        return fail(err, RT_ERROR_INVALID_ARGUMENT, "a box is not finite or has min > max");
    task root = {0};
    root.end = N;
    {
        rt_sah_cbounds box = c->worker_cb[0], cb = c->worker_cb[1];
        for (int w = 1; w < W; w++) {
            rt_sah_cbounds_merge(&box, &c->worker_cb[2 * w]);
            rt_sah_cbounds_merge(&cb, &c->worker_cb[2 * w + 1]);
        }
        memcpy(root.lo, box.cmin, sizeof root.lo);
        memcpy(root.hi, box.cmax, sizeof root.hi);
        set_cbounds(&root, &cb);
    }

    /* Horizontal phase: big nodes with all workers; the rest become tasks.
     * Roughly 4 subtrees per worker balance the task phase. */
    uint32_t big = UINT32_MAX;
    if (W > 1) {
        big = N / (uint32_t)(4 * W);
        if (big < MIN_BIG_NODE) big = MIN_BIG_NODE;
    }
    task big_stack[STACK_SIZE];
    int top = 0;
    uint32_t top_nodes = 0;
    big_stack[top++] = root;
    while (top) {
        task t = big_stack[--top], ch[2];
        if (t.end - t.begin < big) {
            if (!push_task(c, &t)) return fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
            continue;
        }
        top_nodes++; /* split_parallel writes one node, inner or leaf */
        if (!split_parallel(c, pool, &t, &ch[0], &ch[1])) continue;
        if (top + 2 > STACK_SIZE) return fail(err, RT_ERROR_INVALID_ARGUMENT, "tree too deep");
        big_stack[top++] = ch[1];
        big_stack[top++] = ch[0];
    }
    qsort(c->tasks, c->task_count, sizeof *c->tasks, task_order);
    c->task_nodes = malloc((size_t)c->task_count * sizeof *c->task_nodes);
    c->task_base = malloc((size_t)c->task_count * sizeof *c->task_base);
    c->slot_tasks = malloc((size_t)c->task_count * sizeof *c->slot_tasks);
    if (!c->task_nodes || !c->task_base || !c->slot_tasks)
        return fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    for (uint32_t i = 0; i < c->task_count; i++)
        c->slot_tasks[i] = (slot_task){c->tasks[i].slot, i};
    qsort(c->slot_tasks, c->task_count, sizeof *c->slot_tasks, slot_task_order);
    atomic_store(&c->next_task, 0);
    rt_pool_run(pool, task_phase_job, c);
    if (atomic_load(&c->task_failed)) return fail(err, RT_ERROR_INVALID_ARGUMENT, "tree too deep");

    /* The references are done with (the leaves wrote prim_indices): a
     * block too big to be kept for the next build goes now, before the
     * compacted nodes are allocated, which lowers the build's peak of
     * memory by 64 bytes a primitive. */
    if (c->mem && !scratch_kept(c->mem)) {
        free(c->mem->refs[0]);
        free(c->mem->refs[1]);
        c->mem->refs[0] = c->mem->refs[1] = c->refs[0] = c->refs[1] = NULL;
    }
    /* Compaction: the few top nodes serially (which also gives every task
     * subtree its first index), then the task subtrees in parallel. */
    uint32_t nodes = top_nodes;
    for (uint32_t i = 0; i < c->task_count; i++) nodes += c->task_nodes[i];
    out->nodes = malloc((size_t)nodes * sizeof *out->nodes);
    if (!out->nodes) return fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    c->out_nodes = out->nodes;
    compact(c, 0, 0, out->nodes, 1);
    atomic_store(&c->next_task, 0);
    rt_pool_run(pool, compact_job, c);
    out->node_count = nodes;
    out->prim_indices = c->prim_indices;
    out->prim_count = N;
    c->prim_indices = NULL;
    return RT_OK;
}

static rt_status build_sah(const rt_aabb *boxes, const float *positions, const uint32_t *indices,
                           uint32_t count, const rt_build_options *options, rt_pool *pool,
                           int use_neon, rt_bvh *out, rt_error *err);

rt_status rt_bvh_build_sah(const rt_aabb *boxes, uint32_t count, const rt_build_options *options,
                           rt_pool *pool, int use_neon, rt_bvh *out, rt_error *err) {
    if (!out || !options || (!boxes && count)) return RT_ERROR_INVALID_ARGUMENT;
    return build_sah(boxes, NULL, NULL, count, options, pool, use_neon, out, err);
}

rt_status rt_bvh_build_sah_tris(const float *positions, const uint32_t *indices, uint32_t count,
                                const rt_build_options *options, rt_pool *pool, int use_neon,
                                rt_bvh *out, rt_error *err) {
    if (!out || !options || (count && (!positions || !indices))) return RT_ERROR_INVALID_ARGUMENT;
    return build_sah(NULL, positions, indices, count, options, pool, use_neon, out, err);
}

static rt_status build_sah(const rt_aabb *boxes, const float *positions, const uint32_t *indices,
                           uint32_t count, const rt_build_options *options, rt_pool *pool,
                           int use_neon, rt_bvh *out, rt_error *err) {
    memset(out, 0, sizeof *out);
    if (options->bins < 2 || options->bins > FAST_MAX_BINS || options->leaf_size < 1)
        return fail(err, RT_ERROR_INVALID_ARGUMENT, "bins must be 2..256, leaf size >= 1");
    if (count > RT_NODE_COUNT_MASK / 2)
        return fail(err, RT_ERROR_INVALID_ARGUMENT, "too many primitives");
    if (count == 0) return RT_OK; /* the empty tree (bvh.h): no nodes */

    /* Worker count: the given pool's, or options->threads (a pool of our own
     * is then made for this build: pass a pool to avoid creating threads).
     * Small inputs are built on the calling thread alone. */
    int threads = options->threads;
    if (threads <= 0) threads = pool ? rt_pool_size(pool) : rt_cpu_count();
    if (count < MIN_BIG_NODE) threads = 1;
    rt_pool *own = NULL;
    if (threads > 1 && (!pool || rt_pool_size(pool) != threads)) {
        own = rt_pool_create(threads);
        if (!own) return fail(err, RT_ERROR_OUT_OF_MEMORY, "cannot create threads");
        pool = own;
    }
    if (threads == 1) pool = NULL;

    build_ctx c;
    memset(&c, 0, sizeof c);
    c.boxes = boxes;
    c.positions = positions;
    c.indices = indices;
    c.count = count;
    c.bins = options->bins;
    c.leaf_size = options->leaf_size;
    c.cost_box = options->costs.traverse;
    c.cost_tri = options->costs.intersect;
    c.use_neon = use_neon;
    c.workers = threads;
    atomic_init(&c.bad_input, 0);
    atomic_init(&c.next_task, 0);
    atomic_init(&c.task_failed, 0);
    scratch *mem = scratch_take(count);
    c.mem = mem;
    if (mem) {
        c.refs[0] = mem->refs[0];
        c.refs[1] = mem->refs[1];
        c.slots = mem->slots;
    }
    c.prim_indices = malloc((size_t)count * sizeof(uint32_t));
    c.worker_bins = malloc((size_t)threads * sizeof(rt_sah_bins));
    c.merged_bins = malloc(sizeof(rt_sah_bins));
    c.worker_cb = malloc((size_t)threads * 2 * sizeof(rt_sah_cbounds));
    c.job_left = malloc((size_t)threads * sizeof(uint32_t));
    rt_status st;
    if (!c.refs[0] || !c.refs[1] || !c.slots || !c.prim_indices || !c.worker_bins ||
        !c.merged_bins || !c.worker_cb || !c.job_left)
        st = fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    else
        st = run_build(&c, pool, out, err);
    free(c.prim_indices);
    free_ctx(&c);
    scratch_give_back(mem);
    rt_pool_destroy(own);
    if (st != RT_OK) rt_bvh_free(out);
    return st;
}
