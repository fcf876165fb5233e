/* SPDX-License-Identifier: Apache-2.0 */
/* kd_build.c - the kd-tree recursion shared by both split finders, its
 * parallel form and the public rt_kd_build.
 *
 * Determinism for any thread count: every node's decision is a function of
 * its own input only. With a pool, the root is a task, and a worker that
 * splits a node with a large right child makes that child a task (a
 * placeholder in its own output) and goes on with the left one; each task
 * is built into its own buffer by whichever worker takes it, and the
 * buffers are then spliced into the placeholders in depth-first order. The
 * result is byte-identical for any pool and any timing.
 *
 * The reference guard: every split lowers the SAH of heavily overlapping
 * triangles (a fan of coplanar triangles sharing a vertex: the clipped ones
 * thin out away from it), so neither SAH termination nor the depth bound
 * keeps their tree small (millions of entries for a few thousand
 * triangles). The first pass counts the triangle entries of every node it
 * makes (the build's work and, at most, its memory); past
 * RT_KD_GUARD_WORK x N x the depth bound it stops, and the tree is built
 * again with a budget of RT_KD_GUARD_DUPS x N duplicates: the root gets it,
 * a split whose straddling triangles exceed its node's budget makes a leaf,
 * and what a split leaves is shared between the children in proportion to
 * their triangle counts. Both rules are functions of the input only (the
 * count's total does not depend on the order the workers add to it), so
 * the tree stays the same for any thread count; a tree under the cap is the
 * unguarded tree. */
#include "accel/kd_internal.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/thread_pool.h"

#define KD_TASK_MIN 1024 /* smaller subtrees are not worth a task */

rt_kd_options rt_kd_options_default(void) {
    rt_kd_options o;
    o.builder = RT_KD_EXACT;
    o.costs.traverse = 1.0f;
    o.costs.intersect = 1.0f;
    o.empty_bonus = 0.8f;
    o.max_depth = 0;
    o.bins = 32;
    o.ref_guard = 1;
    return o;
}

const char *rt_kd_builder_name(rt_kd_builder b) {
    return b == RT_KD_BINNED ? "kd-binned" : "kd-exact";
}

/* ---- the output buffer ----------------------------------------------------- */

static int grow_nodes(kd_out *o) {
    if (o->node_count < o->node_cap) return 1;
    uint32_t cap = o->node_cap ? 2 * o->node_cap : 64;
    rt_kd_node *n = realloc(o->nodes, sizeof(rt_kd_node) * cap);
    if (!n) {
        o->oom = 1;
        return 0;
    }
    o->nodes = n;
    o->node_cap = cap;
    return 1;
}

uint32_t rt_kd_out_inner(kd_out *o, int axis, float split) {
    if (!grow_nodes(o)) return 0;
    uint32_t bits;
    memcpy(&bits, &split, sizeof bits);
    o->nodes[o->node_count].a = bits;
    o->nodes[o->node_count].b = (uint32_t)axis;
    return o->node_count++;
}

void rt_kd_out_set_right(kd_out *o, uint32_t inner, uint32_t right) {
    if (o->oom) return;
    o->nodes[inner].b = (right << 2) | (o->nodes[inner].b & 3u);
}

void rt_kd_out_leaf(kd_out *o, const uint32_t *tris, uint32_t n) {
    if (!grow_nodes(o)) return;
    if (o->prim_count + n > o->prim_cap) {
        uint32_t cap = o->prim_cap ? o->prim_cap : 64;
        while (cap < o->prim_count + n) cap *= 2;
        uint32_t *p = realloc(o->prims, sizeof(uint32_t) * cap);
        if (!p) {
            o->oom = 1;
            return;
        }
        o->prims = p;
        o->prim_cap = cap;
    }
    if (n) memcpy(o->prims + o->prim_count, tris, sizeof(uint32_t) * n);
    o->nodes[o->node_count].a = o->prim_count;
    o->nodes[o->node_count].b = (n << 2) | RT_KD_LEAF;
    o->node_count++;
    o->prim_count += n;
}

void rt_kd_out_placeholder(kd_out *o, uint32_t task) {
    if (!grow_nodes(o)) return;
    if (o->ph_count == o->ph_cap) {
        uint32_t cap = o->ph_cap ? 2 * o->ph_cap : 8;
        uint32_t *ph = realloc(o->ph, sizeof(uint32_t) * 2 * cap);
        if (!ph) {
            o->oom = 1;
            return;
        }
        o->ph = ph;
        o->ph_cap = cap;
    }
    o->ph[2 * o->ph_count] = o->node_count;
    o->ph[2 * o->ph_count + 1] = o->prim_count;
    o->ph_count++;
    o->nodes[o->node_count].a = task;
    o->nodes[o->node_count].b = KD_PLACEHOLDER;
    o->node_count++;
}

void rt_kd_out_free(kd_out *o) {
    free(o->nodes);
    free(o->prims);
    free(o->ph);
    memset(o, 0, sizeof *o);
}

/* ---- the recursion ------------------------------------------------------------ */

/* A subtree built by one worker into its own buffer; its placeholders name
 * the tasks of subtrees split off from it. */
typedef struct kd_task {
    kd_node_in in;
    kd_out out;
    /* assemble: the subtree's nodes and entries (placeholders expanded) and
     * the index of its first node and first entry in the tree */
    uint64_t nodes, prims, nbase, pbase;
} kd_task;

/* The parallel build: every task made, in the order made, shared by the
 * pool's workers, which take the oldest waiting (the largest subtrees come
 * first: a worker goes on depth-first with the left children). The
 * numbering of the tasks depends on timing; the tree does not (assemble
 * follows the placeholders). */
typedef struct kd_sched {
    const kd_ctx *c;
    const kd_finder *f;
    pthread_mutex_t lock;
    pthread_cond_t wake;
    kd_task **all; /* by task number */
    uint32_t count, cap;
    uint32_t taken; /* tasks taken by a worker: all[taken..count) wait */
    uint32_t busy;  /* workers inside a task */
    int oom;
} kd_sched;

static void node_free(kd_node_in *in) {
    free(in->data);
    in->data = NULL;
}

/* Whether the first pass has made more entries than the guard allows
 * (then the rest of it is skipped). */
static int over_cap(const kd_ctx *c) {
    return c->work && atomic_load_explicit(c->work, memory_order_relaxed) > c->work_cap;
}

/* Makes in a task (taking its data) and returns its number; UINT32_MAX when
 * out of memory (in's data freed). */
static uint32_t sched_push(kd_sched *s, kd_node_in *in) {
    kd_task *t = calloc(1, sizeof *t);
    uint32_t id = UINT32_MAX;
    pthread_mutex_lock(&s->lock);
    if (t && s->count == s->cap) {
        uint32_t cap = s->cap ? 2 * s->cap : 64;
        kd_task **a = realloc(s->all, sizeof(kd_task *) * cap);
        if (a) {
            s->all = a;
            s->cap = cap;
        }
    }
    if (t && s->count < s->cap) {
        t->in = *in;
        in->data = NULL;
        id = s->count++;
        s->all[id] = t;
        pthread_cond_signal(&s->wake);
    }
    pthread_mutex_unlock(&s->lock);
    if (id == UINT32_MAX) {
        free(t);
        node_free(in);
    }
    return id;
}

/* Builds the subtree of in into o and frees in's data. With s, a right
 * child of at least KD_TASK_MIN triangles becomes a task (a placeholder
 * here) for an idle worker to take. */
static void build_rec(const kd_ctx *c, const kd_finder *f, kd_node_in *in, kd_scratch *w, kd_out *o,
                      kd_sched *s) {
    for (;;) {
        if (o->oom || over_cap(c)) {
            node_free(in);
            return;
        }
        kd_split sp;
        sp.cost = INFINITY;
        if (in->tris && in->depth < c->max_depth) f->find(c, in, &sp);
        /* SAH termination: split only when it is cheaper than the leaf; in
         * the budget pass, also only when the node's budget pays its
         * duplicates. */
        if (!(sp.cost < (double)c->opt.costs.intersect * (double)in->tris) ||
            (c->budget && sp.both > in->allow)) {
            uint32_t n = f->leaf(c, in, w);
            if (n == UINT32_MAX)
                o->oom = 1;
            else
                rt_kd_out_leaf(o, w->list, n);
            node_free(in);
            return;
        }
        kd_node_in l, r;
        uint64_t left_over = c->budget ? in->allow - sp.both : 0;
        if (!f->split(c, in, &sp, w, &l, &r)) {
            o->oom = 1;
            return;
        }
        uint64_t made = (uint64_t)l.tris + r.tris;
        if (c->work) atomic_fetch_add_explicit(c->work, made, memory_order_relaxed);
        l.allow = made ? left_over * l.tris / made : 0;
        r.allow = left_over - l.allow;
        uint32_t inner = rt_kd_out_inner(o, sp.axis, sp.pos);
        if (s && r.tris >= KD_TASK_MIN) {
            /* Offered before the left subtree is built, placed after it. */
            uint32_t id = sched_push(s, &r);
            build_rec(c, f, &l, w, o, s);
            rt_kd_out_set_right(o, inner, o->node_count);
            if (id == UINT32_MAX)
                o->oom = 1;
            else
                rt_kd_out_placeholder(o, id);
            return;
        }
        build_rec(c, f, &l, w, o, s);
        rt_kd_out_set_right(o, inner, o->node_count);
        /* The right child in this frame: no recursion on the longer side. */
        *in = r;
    }
}

static void run_tasks(void *ctx, int worker, int workers) {
    (void)worker;
    (void)workers;
    kd_sched *s = ctx;
    kd_scratch w = {calloc(s->c->tri_total ? s->c->tri_total : 1, 1), NULL, 0, NULL, 0};
    pthread_mutex_lock(&s->lock);
    for (;;) {
        while (s->taken == s->count && s->busy) pthread_cond_wait(&s->wake, &s->lock);
        if (s->taken == s->count) break;
        kd_task *t = s->all[s->taken++];
        s->busy++;
        pthread_mutex_unlock(&s->lock);
        if (w.flags)
            build_rec(s->c, s->f, &t->in, &w, &t->out, s);
        else
            t->out.oom = 1;
        node_free(&t->in);
        pthread_mutex_lock(&s->lock);
        s->oom |= t->out.oom;
        /* The last busy worker with nothing waiting ends everyone's loop. */
        if (--s->busy == 0 && s->taken == s->count) pthread_cond_broadcast(&s->wake);
    }
    pthread_mutex_unlock(&s->lock);
    rt_kd_scratch_free(&w);
}

/* Sets the nodes and entries of task id's subtree, placeholders expanded,
 * and of the subtrees below it (from the placeholders' records). */
static void task_totals(const kd_sched *s, uint32_t id) {
    kd_task *t = s->all[id];
    t->nodes = t->out.node_count - t->out.ph_count;
    t->prims = t->out.prim_count;
    for (uint32_t j = 0; j < t->out.ph_count; j++) {
        uint32_t child = t->out.nodes[t->out.ph[2 * j]].a;
        task_totals(s, child);
        t->nodes += s->all[child]->nodes;
        t->prims += s->all[child]->prims;
    }
}

/* Sets where task id's subtree and those below it begin in the tree: a
 * child after the parent's nodes and entries made before its placeholder,
 * and after the earlier children's subtrees. */
static void task_bases(const kd_sched *s, uint32_t id, uint64_t nbase, uint64_t pbase) {
    kd_task *t = s->all[id];
    t->nbase = nbase;
    t->pbase = pbase;
    uint64_t more_nodes = 0, more_prims = 0;
    for (uint32_t j = 0; j < t->out.ph_count; j++) {
        uint32_t at = t->out.ph[2 * j], prims = t->out.ph[2 * j + 1];
        const kd_task *c = s->all[t->out.nodes[at].a];
        task_bases(s, t->out.nodes[at].a, nbase + at + more_nodes, pbase + prims + more_prims);
        more_nodes += c->nodes - 1;
        more_prims += c->prims;
    }
}

/* Writes task id's own nodes and entries to their places in out (task_bases
 * done); its placeholders' subtrees are other tasks'. Returns 0 when out of
 * memory. */
static int place(const kd_sched *s, uint32_t id, rt_kd *out) {
    const kd_task *t = s->all[id];
    const kd_out *o = &t->out;
    uint32_t n = o->node_count;
    uint32_t *at = malloc(sizeof(uint32_t) * ((size_t)n + 1)); /* new index of o's nodes */
    if (!at) return 0;
    uint32_t next = (uint32_t)t->nbase, pn = (uint32_t)t->pbase;
    for (uint32_t i = 0; i < n; i++) {
        at[i] = next;
        if (o->nodes[i].b == KD_PLACEHOLDER)
            next += (uint32_t)s->all[o->nodes[i].a]->nodes;
        else
            next++;
    }
    for (uint32_t i = 0; i < n; i++) {
        const rt_kd_node *d = &o->nodes[i];
        rt_kd_node *dst = out->nodes + at[i];
        if (d->b == KD_PLACEHOLDER) {
            pn += (uint32_t)s->all[d->a]->prims;
        } else if ((d->b & 3u) == RT_KD_LEAF) {
            uint32_t cnt = d->b >> 2;
            if (cnt) memcpy(out->prims + pn, o->prims + d->a, sizeof(uint32_t) * cnt);
            dst->a = pn;
            dst->b = d->b;
            pn += cnt;
        } else {
            dst->a = d->a;
            dst->b = (at[d->b >> 2] << 2) | (d->b & 3u);
        }
    }
    free(at);
    return 1;
}

typedef struct kd_place_job {
    const kd_sched *s;
    rt_kd *out;
    atomic_uint next;
    atomic_int failed;
} kd_place_job;

static void place_tasks(void *ctx, int worker, int workers) {
    (void)worker;
    (void)workers;
    kd_place_job *j = ctx;
    for (;;) {
        uint32_t i = atomic_fetch_add(&j->next, 1u);
        if (i >= j->s->count) break;
        if (!place(j->s, i, j->out)) atomic_store(&j->failed, 1);
    }
}

/* Splices the tasks' subtrees into their placeholders from task 0 (the
 * root) on, each task's part copied by a worker of pool. */
static int assemble(const kd_sched *s, rt_pool *pool, rt_kd *out) {
    task_totals(s, 0);
    uint64_t nodes = s->all[0]->nodes, prims = s->all[0]->prims;
    if (nodes >= (1u << 30) || prims >= (1u << 30)) return 0;
    task_bases(s, 0, 0, 0);
    out->nodes = malloc(sizeof(rt_kd_node) * (nodes + 1));
    out->prims = malloc(sizeof(uint32_t) * (prims + 1));
    if (!out->nodes || !out->prims) return 0;
    kd_place_job j;
    j.s = s;
    j.out = out;
    atomic_init(&j.next, 0u);
    atomic_init(&j.failed, 0);
    rt_pool_run(pool, place_tasks, &j);
    if (atomic_load(&j.failed)) return 0;
    out->node_count = (uint32_t)nodes;
    out->prim_count = (uint32_t)prims;
    return 1;
}

/* Builds the tree of root into out: on the calling thread, or on pool's
 * workers from one queue of subtree tasks. Returns 1, 0 when out of memory,
 * or -1 when the first pass went over the guard's cap (out untouched). */
static int build_tree(const kd_ctx *c, const kd_finder *f, kd_node_in *root, kd_scratch *w,
                      rt_pool *pool, rt_kd *out) {
    if (!pool || rt_pool_size(pool) < 2) {
        kd_out o;
        memset(&o, 0, sizeof o);
        build_rec(c, f, root, w, &o, NULL);
        if (!o.oom && over_cap(c)) {
            rt_kd_out_free(&o);
            return -1;
        }
        if (o.oom || o.node_count >= (1u << 30) || o.prim_count >= (1u << 30)) {
            rt_kd_out_free(&o);
            return 0;
        }
        out->nodes = o.nodes;
        out->node_count = o.node_count;
        out->prims = o.prims ? o.prims : malloc(sizeof(uint32_t));
        out->prim_count = o.prim_count;
        return out->prims != NULL;
    }
    kd_sched s;
    memset(&s, 0, sizeof s);
    s.c = c;
    s.f = f;
    pthread_mutex_init(&s.lock, NULL);
    pthread_cond_init(&s.wake, NULL);
    int ok = sched_push(&s, root) == 0;
    if (ok) rt_pool_run(pool, run_tasks, &s);
    if (ok && !s.oom && over_cap(c))
        ok = -1;
    else
        ok = ok && !s.oom && assemble(&s, pool, out);
    for (uint32_t i = 0; i < s.count; i++) {
        node_free(&s.all[i]->in);
        rt_kd_out_free(&s.all[i]->out);
        free(s.all[i]);
    }
    free(s.all);
    pthread_mutex_destroy(&s.lock);
    pthread_cond_destroy(&s.wake);
    return ok;
}

static int finite_tri(const kd_tri *t) {
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            if (!isfinite(t->v[i][k])) return 0;
    return 1;
}

/* The layout's degenerate test (layout/flatten.c): no triangle test hits a
 * triangle whose edge cross product is exactly zero. */
static int has_area(const kd_tri *t) {
    float e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = t->v[1][k] - t->v[0][k];
        e2[k] = t->v[2][k] - t->v[0][k];
    }
    float n0 = e1[1] * e2[2] - e1[2] * e2[1];
    float n1 = e1[2] * e2[0] - e1[0] * e2[2];
    float n2 = e1[0] * e2[1] - e1[1] * e2[0];
    return !(n0 == 0.0f && n1 == 0.0f && n2 == 0.0f);
}

void rt_kd_free(rt_kd *kd) {
    if (!kd) return;
    free(kd->nodes);
    free(kd->prims);
    memset(kd, 0, sizeof *kd);
}

rt_status rt_kd_build(const float *positions, uint32_t vertex_count, const uint32_t *indices,
                      uint32_t triangle_count, const rt_kd_options *options, rt_pool *pool,
                      rt_kd *out, rt_error *err) {
    memset(out, 0, sizeof *out);
    rt_kd_options opt = options ? *options : rt_kd_options_default();
    if (!(opt.costs.traverse > 0.0f) || !(opt.costs.intersect > 0.0f) ||
        !(opt.empty_bonus > 0.0f && opt.empty_bonus <= 1.0f) || opt.bins < 2 || opt.bins > 256 ||
        opt.max_depth > RT_KD_MAX_DEPTH ||
        (opt.builder != RT_KD_EXACT && opt.builder != RT_KD_BINNED))
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "kd-tree options out of range");
    if (triangle_count && (!positions || !indices))
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "kd-tree: no triangles given");
    /* The exact builder's events keep a triangle index in 30 bits; a tree
     * of more entries could not be assembled anyway (below 2^30). */
    if (triangle_count >= (1u << 30))
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "kd-tree: %u triangles, at most %u",
                       triangle_count, (1u << 30) - 1u);
    kd_ctx c;
    memset(&c, 0, sizeof c);
    c.opt = opt;
    c.tri_total = triangle_count;
    kd_tri *tris = malloc(sizeof(kd_tri) * ((size_t)triangle_count + 1));
    uint32_t *ids = malloc(sizeof(uint32_t) * ((size_t)triangle_count + 1));
    rt_aabb *boxes = malloc(sizeof(rt_aabb) * ((size_t)triangle_count + 1));
    kd_scratch w = {calloc((size_t)triangle_count + 1, 1), NULL, 0, NULL, 0};
    rt_status st = RT_OK;
    if (!tris || !ids || !boxes || !w.flags) {
        st = rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory building a kd-tree");
        goto done;
    }
    uint32_t n = 0;
    rt_aabb cell = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    for (uint32_t t = 0; t < triangle_count; t++) {
        for (int i = 0; i < 3; i++) {
            uint32_t v = indices[3 * (size_t)t + i];
            if (v >= vertex_count) {
                st = rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                             "kd-tree: triangle %u references vertex %u of %u", t, v, vertex_count);
                goto done;
            }
            memcpy(tris[t].v[i], positions + 3 * (size_t)v, 3 * sizeof(float));
        }
        if (!finite_tri(&tris[t])) {
            st = rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                         "kd-tree: triangle %u has a coordinate that is not finite", t);
            goto done;
        }
        if (!has_area(&tris[t])) continue;
        rt_aabb *b = &boxes[n];
        for (int k = 0; k < 3; k++) {
            b->bmin[k] = b->bmax[k] = tris[t].v[0][k];
            for (int i = 1; i < 3; i++) {
                float x = tris[t].v[i][k];
                if (x < b->bmin[k]) b->bmin[k] = x;
                if (x > b->bmax[k]) b->bmax[k] = x;
            }
            if (b->bmin[k] < cell.bmin[k]) cell.bmin[k] = b->bmin[k];
            if (b->bmax[k] > cell.bmax[k]) cell.bmax[k] = b->bmax[k];
        }
        ids[n++] = t;
    }
    c.tris = tris;
    if (opt.max_depth > 0) {
        c.max_depth = opt.max_depth;
    } else {
        double d = 8.0 + 1.3 * log2((double)(n ? n : 1));
        c.max_depth = d < RT_KD_MAX_DEPTH ? (int)d : RT_KD_MAX_DEPTH;
    }
    if (!n) {
        /* No triangle can be hit: one empty leaf over an empty cell. */
        memset(&out->bounds, 0, sizeof out->bounds);
        for (int k = 0; k < 3; k++) {
            out->bounds.bmin[k] = INFINITY;
            out->bounds.bmax[k] = -INFINITY;
        }
        out->nodes = malloc(sizeof(rt_kd_node));
        out->prims = malloc(sizeof(uint32_t));
        if (!out->nodes || !out->prims) {
            rt_kd_free(out);
            st = rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory building a kd-tree");
            goto done;
        }
        out->nodes[0].a = 0;
        out->nodes[0].b = RT_KD_LEAF;
        out->node_count = 1;
        goto done;
    }
    const kd_finder *f = opt.builder == RT_KD_BINNED ? &rt_kd_finder_binned : &rt_kd_finder_sweep;
    _Atomic uint64_t work;
    atomic_init(&work, 0);
    if (opt.ref_guard) {
        c.work = &work;
        c.work_cap = (uint64_t)(RT_KD_GUARD_WORK * (double)n * (double)c.max_depth);
    }
    /* The boxes stay until the end: a budget pass makes the root again. */
    for (;;) {
        kd_node_in root;
        if (!f->root(&c, ids, boxes, n, &cell, pool, &root)) {
            st = rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory building a kd-tree");
            goto done;
        }
        /* At most 2^30 entries fit a tree (assemble), which also keeps the
         * children's shares (allow * tris) within 64 bits. */
        double allow = RT_KD_GUARD_DUPS * (double)n;
        root.allow = c.budget ? (allow < 0x1p30 ? (uint64_t)allow : (1ull << 30)) : 0;
        int built = build_tree(&c, f, &root, &w, pool, out);
        if (built < 0) {
            /* Too much work for the triangle count: the budget pass. */
            c.work = NULL;
            c.budget = 1;
            continue;
        }
        if (!built) {
            rt_kd_free(out);
            st = rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory building a kd-tree");
            goto done;
        }
        break;
    }
    out->bounds = cell;
done:
    free(tris);
    free(ids);
    free(boxes);
    rt_kd_scratch_free(&w);
    return st;
}
