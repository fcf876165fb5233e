/* kd_build.c - the kd-tree recursion shared by both split finders, its
 * parallel phase and the public rt_kd_build.
 *
 * Determinism for any thread count: every node's decision is a function of
 * its own input only. The nodes above depth KD_TASK_DEPTH are built on the
 * calling thread; each node reaching that depth (with enough triangles)
 * becomes a task, built into its own buffer by whichever worker takes it;
 * the buffers are then spliced into the placeholders in depth-first order.
 * The result is byte-identical for any pool.
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
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/thread_pool.h"

#define KD_TASK_DEPTH 5    /* at most 32 tasks */
#define KD_TASK_MIN   1024 /* smaller subtrees are not worth a task */

rt_kd_options rt_kd_options_default(void) {
    rt_kd_options o;
    o.builder = RT_KD_EXACT;
    o.cost_traverse = 1.0f;
    o.cost_intersect = 1.0f;
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

uint32_t kd_out_inner(kd_out *o, int axis, float split) {
    if (!grow_nodes(o)) return 0;
    uint32_t bits;
    memcpy(&bits, &split, sizeof bits);
    o->nodes[o->node_count].a = bits;
    o->nodes[o->node_count].b = (uint32_t)axis;
    return o->node_count++;
}

void kd_out_set_right(kd_out *o, uint32_t inner, uint32_t right) {
    if (o->oom) return;
    o->nodes[inner].b = (right << 2) | (o->nodes[inner].b & 3u);
}

void kd_out_leaf(kd_out *o, const uint32_t *tris, uint32_t n) {
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

void kd_out_placeholder(kd_out *o, uint32_t task) {
    if (!grow_nodes(o)) return;
    o->nodes[o->node_count].a = task;
    o->nodes[o->node_count].b = KD_PLACEHOLDER;
    o->node_count++;
}

void kd_out_free(kd_out *o) {
    free(o->nodes);
    free(o->prims);
    memset(o, 0, sizeof *o);
}

/* ---- the recursion ------------------------------------------------------------ */

typedef struct kd_task {
    kd_node_in in;
    kd_out out;
    int oom;
} kd_task;

typedef struct kd_tasks {
    kd_task *t;
    uint32_t count, cap;
    int oom;
} kd_tasks;

static void node_free(kd_node_in *in) {
    free(in->data);
    in->data = NULL;
}

/* Whether the first pass has made more entries than the guard allows
 * (then the rest of it is skipped). */
static int over_cap(const kd_ctx *c) {
    return c->work && atomic_load_explicit(c->work, memory_order_relaxed) > c->work_cap;
}

/* Builds the subtree of in into o; with tasks, nodes at KD_TASK_DEPTH
 * become tasks. Frees in's data. */
static void build_rec(const kd_ctx *c, const kd_finder *f, kd_node_in *in, kd_scratch *w, kd_out *o,
                      kd_tasks *tasks) {
    if (o->oom || over_cap(c)) {
        node_free(in);
        return;
    }
    if (tasks && in->depth == KD_TASK_DEPTH && in->tris >= KD_TASK_MIN) {
        if (tasks->count == tasks->cap) {
            uint32_t cap = tasks->cap ? 2 * tasks->cap : 32;
            kd_task *t = realloc(tasks->t, sizeof(kd_task) * cap);
            if (!t) {
                o->oom = 1;
                node_free(in);
                return;
            }
            tasks->t = t;
            tasks->cap = cap;
        }
        kd_task *t = &tasks->t[tasks->count];
        memset(t, 0, sizeof *t);
        t->in = *in;
        in->data = NULL;
        kd_out_placeholder(o, tasks->count++);
        return;
    }
    kd_split s;
    s.cost = INFINITY;
    if (in->tris && in->depth < c->max_depth) f->find(c, in, &s);
    /* SAH termination: split only when it is cheaper than the leaf; in the
     * budget pass, also only when the node's budget pays its duplicates. */
    if (!(s.cost < (double)c->opt.cost_intersect * (double)in->tris) ||
        (c->budget && s.both > in->allow)) {
        uint32_t n = f->leaf(c, in, w);
        if (n == UINT32_MAX)
            o->oom = 1;
        else
            kd_out_leaf(o, w->list, n);
        node_free(in);
        return;
    }
    kd_node_in l, r;
    uint64_t left_over = c->budget ? in->allow - s.both : 0;
    if (!f->split(c, in, &s, w, &l, &r)) {
        o->oom = 1;
        return;
    }
    uint64_t made = (uint64_t)l.tris + r.tris;
    if (c->work) atomic_fetch_add_explicit(c->work, made, memory_order_relaxed);
    l.allow = made ? left_over * l.tris / made : 0;
    r.allow = left_over - l.allow;
    uint32_t inner = kd_out_inner(o, s.axis, s.pos);
    build_rec(c, f, &l, w, o, tasks);
    kd_out_set_right(o, inner, o->node_count);
    build_rec(c, f, &r, w, o, tasks);
}

typedef struct kd_job {
    const kd_ctx *c;
    const kd_finder *f;
    kd_tasks *tasks;
    atomic_uint next;
} kd_job;

static void run_tasks(void *ctx, int worker, int workers) {
    (void)worker;
    (void)workers;
    kd_job *j = ctx;
    kd_scratch w = {calloc(j->c->tri_total ? j->c->tri_total : 1, 1), NULL, 0};
    for (;;) {
        uint32_t i = atomic_fetch_add(&j->next, 1u);
        if (i >= j->tasks->count) break;
        kd_task *t = &j->tasks->t[i];
        if (!w.flags) {
            t->oom = 1;
            node_free(&t->in);
            continue;
        }
        build_rec(j->c, j->f, &t->in, &w, &t->out, NULL);
        t->oom = t->out.oom;
    }
    free(w.flags);
    free(w.list);
}

/* Frees what a pass made (tasks' inputs, buffers) and empties top and tasks. */
static void release(kd_out *top, kd_tasks *tasks) {
    for (uint32_t i = 0; i < tasks->count; i++) {
        node_free(&tasks->t[i].in);
        kd_out_free(&tasks->t[i].out);
    }
    free(tasks->t);
    memset(tasks, 0, sizeof *tasks);
    kd_out_free(top);
}

/* Splices the tasks' subtrees into the placeholders of top, depth-first. */
static int assemble(const kd_out *top, const kd_tasks *tasks, rt_kd *out) {
    uint32_t n = top->node_count;
    uint64_t nodes = 0, prims = top->prim_count;
    uint32_t *at = malloc(sizeof(uint32_t) * ((size_t)n + 1)); /* new index of top's nodes */
    if (!at) return 0;
    for (uint32_t i = 0; i < n; i++) {
        at[i] = (uint32_t)nodes;
        const rt_kd_node *d = &top->nodes[i];
        if (d->b == KD_PLACEHOLDER) {
            nodes += tasks->t[d->a].out.node_count;
            prims += tasks->t[d->a].out.prim_count;
        } else {
            nodes++;
        }
    }
    if (nodes >= (1u << 30) || prims >= (1u << 30)) {
        free(at);
        return 0;
    }
    out->nodes = malloc(sizeof(rt_kd_node) * (nodes + 1));
    out->prims = malloc(sizeof(uint32_t) * (prims + 1));
    if (!out->nodes || !out->prims) {
        free(at);
        return 0;
    }
    uint32_t pn = 0;
    for (uint32_t i = 0; i < n; i++) {
        const rt_kd_node *d = &top->nodes[i];
        rt_kd_node *dst = out->nodes + at[i];
        if (d->b == KD_PLACEHOLDER) {
            const kd_out *s = &tasks->t[d->a].out;
            for (uint32_t k = 0; k < s->node_count; k++) {
                rt_kd_node x = s->nodes[k];
                if ((x.b & 3u) == RT_KD_LEAF)
                    x.a += pn;
                else
                    x.b = (((x.b >> 2) + at[i]) << 2) | (x.b & 3u);
                dst[k] = x;
            }
            if (s->prim_count) memcpy(out->prims + pn, s->prims, sizeof(uint32_t) * s->prim_count);
            pn += s->prim_count;
        } else if ((d->b & 3u) == RT_KD_LEAF) {
            uint32_t cnt = d->b >> 2;
            if (cnt) memcpy(out->prims + pn, top->prims + d->a, sizeof(uint32_t) * cnt);
            dst->a = pn;
            dst->b = d->b;
            pn += cnt;
        } else {
            dst->a = d->a;
            dst->b = (at[d->b >> 2] << 2) | (d->b & 3u);
        }
    }
    out->node_count = (uint32_t)nodes;
    out->prim_count = pn;
    free(at);
    return 1;
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
    if (!(opt.cost_traverse > 0.0f) || !(opt.cost_intersect > 0.0f) ||
        !(opt.empty_bonus > 0.0f && opt.empty_bonus <= 1.0f) || opt.bins < 2 || opt.bins > 256 ||
        opt.max_depth > RT_KD_MAX_DEPTH ||
        (opt.builder != RT_KD_EXACT && opt.builder != RT_KD_BINNED))
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "kd-tree options out of range");
    if (triangle_count && (!positions || !indices))
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "kd-tree: no triangles given");
    kd_ctx c;
    memset(&c, 0, sizeof c);
    c.opt = opt;
    c.tri_total = triangle_count;
    kd_tri *tris = malloc(sizeof(kd_tri) * ((size_t)triangle_count + 1));
    uint32_t *ids = malloc(sizeof(uint32_t) * ((size_t)triangle_count + 1));
    rt_aabb *boxes = malloc(sizeof(rt_aabb) * ((size_t)triangle_count + 1));
    kd_scratch w = {calloc((size_t)triangle_count + 1, 1), NULL, 0};
    kd_out top;
    kd_tasks tasks;
    memset(&top, 0, sizeof top);
    memset(&tasks, 0, sizeof tasks);
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
    const kd_finder *f = opt.builder == RT_KD_BINNED ? &kd_finder_binned : &kd_finder_sweep;
    _Atomic uint64_t work;
    atomic_init(&work, 0);
    if (opt.ref_guard) {
        c.work = &work;
        c.work_cap = (uint64_t)(RT_KD_GUARD_WORK * (double)n * (double)c.max_depth);
    }
    for (;;) {
        kd_node_in root;
        if (!f->root(&c, ids, boxes, n, &cell, &root)) {
            st = rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory building a kd-tree");
            goto done;
        }
        /* At most 2^30 entries fit a tree (assemble), which also keeps the
         * children's shares (allow * tris) within 64 bits. */
        double allow = RT_KD_GUARD_DUPS * (double)n;
        root.allow = c.budget ? (allow < 0x1p30 ? (uint64_t)allow : (1ull << 30)) : 0;
        build_rec(&c, f, &root, &w, &top, &tasks);
        int oom = top.oom;
        if (!oom && tasks.count) {
            kd_job job = {&c, f, &tasks, 0};
            if (pool)
                rt_pool_run(pool, run_tasks, &job);
            else
                run_tasks(&job, 0, 1);
            for (uint32_t i = 0; i < tasks.count; i++) oom |= tasks.t[i].oom;
        }
        if (!oom && over_cap(&c)) {
            /* Too much work for the triangle count: the budget pass. */
            release(&top, &tasks);
            c.work = NULL;
            c.budget = 1;
            continue;
        }
        if (oom || !assemble(&top, &tasks, out)) {
            rt_kd_free(out);
            st = rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory building a kd-tree");
            goto done;
        }
        break;
    }
    out->bounds = cell;
done:
    release(&top, &tasks);
    free(tris);
    free(ids);
    free(boxes);
    free(w.flags);
    free(w.list);
    return st;
}
