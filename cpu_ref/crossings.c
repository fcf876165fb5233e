/* SPDX-License-Identifier: Apache-2.0 */
/* crossings.c - counting the triangles a ray crosses (crossings.h).
 *
 * The watertight test (rt_tri_watertight) decides in the ray's sheared 2D
 * frame: each vertex v becomes a 2D point (v - o sheared so that the ray is
 * the z axis; every triangle computes a shared vertex's point with the same
 * operations, so it is the same point), and the ray hits a triangle when the
 * origin lies inside or on the boundary of the triangle of its three points:
 * the edge functions U, V, W (exact in sign: a zero is re-checked exactly)
 * are all >= 0 or all <= 0. On the boundary is what makes it watertight, and
 * also what makes a ray through an edge hit both triangles that share it:
 * counting those hits would count that crossing twice.
 *
 * The tie rule: an edge function that is exactly zero is decided as if the
 * origin were at (e, e*e) for an infinitesimal e > 0. An edge function is
 * affine in the point, E(P) = E(0) + g . P, so with E(0) = 0 the moved
 * origin is on the triangle's inside of that edge when s * (g.x e + g.y e^2)
 * > 0, s the sign of the triangle's non-zero edge functions: s g.x > 0, or
 * g.x = 0 and s g.y > 0. g is made of differences of the two edge points'
 * coordinates, whose signs comparisons give exactly. The moved origin is on
 * no edge line (g = 0 only for an edge of two equal points, whose triangle
 * has zero area and no hit), so it lies inside exactly the triangles it
 * would lie in for a generic ray: of two triangles on either side of a
 * shared edge exactly one counts; of a fan around a vertex the ray passes
 * through, exactly one; a silhouette edge or vertex that the ray only
 * touches, 0 or 2. Since every vertex has one 2D point whatever triangle
 * computes it, the rule sees one consistent planar mesh, and the parity of
 * a closed mesh's crossings is that of a ray in general position.
 *
 * Triangles are found by a traversal that opens every box the ray's range
 * passes (no early end: rt_box_lo(tmin) to rt_box_hi(tmax), the bounds of
 * the closest-hit traversal before any hit), and a crossing counts only
 * where rt_hit_accepted accepts it: then the count does not depend on the
 * tree (BVH, refit, LBVH, kd-tree), as the closest hit does not. A kd-tree
 * keeps a triangle in every leaf it overlaps, so a kd mesh's crossings are
 * listed and counted once per triangle. */
#include "crossings.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "kernel_maths.h"

/* The sign of a - b, exactly: -1, 0 or 1 (comparisons, so no difference is
 * rounded or flushed to zero). */
static int sign_of_difference(float a, float b) {
    return (a > b) - (a < b);
}

/* The tie rule for an edge function that is exactly zero, on the edge from
 * (px, py) to (qx, qy) whose function's gradient is (qy - py, px - qx), of a
 * triangle whose non-zero edge functions have sign s: 1 when the origin moved
 * to (e, e^2) lies on the triangle's side. */
static int tie_inside(float px, float py, float qx, float qy, int s) {
    const int gx = s * sign_of_difference(qy, py);
    if (gx != 0) return gx > 0;
    return s * sign_of_difference(px, qx) > 0;
}

int rt_crossing_test(const rt_tri *tri, const rt_ray *r, const rt_ray_pre *p, float *t) {
    float u, v;
    /* The hit, its t and the range: the shared test's own, so a crossing is
     * a hit rt_trace_rays could report. */
    if (!rt_tri_watertight(tri, r, p, r->tmin, r->tmax, t, &u, &v)) return 0;
    if (!rt_hit_accepted(tri, r, p, *t)) return 0;
    /* The edge functions again (the test's operations in its order), for the
     * tie rule where one is zero. */
    float A[3], B[3], C[3];
    for (int i = 0; i < 3; i++) {
        A[i] = tri->v0[i] - r->org[i];
        B[i] = tri->v1[i] - r->org[i];
        C[i] = tri->v2[i] - r->org[i];
    }
    const rt_i32 kx = p->kx, ky = p->ky, kz = p->kz;
    const float Ax = A[kx] - p->sx * A[kz], Ay = A[ky] - p->sy * A[kz];
    const float Bx = B[kx] - p->sx * B[kz], By = B[ky] - p->sy * B[kz];
    const float Cx = C[kx] - p->sx * C[kz], Cy = C[ky] - p->sy * C[kz];
    float U = Cx * By - Cy * Bx;
    float V = Ax * Cy - Ay * Cx;
    float W = Bx * Ay - By * Ax;
    if (U != 0.0f && V != 0.0f && W != 0.0f) return 1;
    rt_edge_recheck(Ax, Ay, Bx, By, Cx, Cy, &U, &V, &W);
    const int s = (U > 0.0f || V > 0.0f || W > 0.0f) ? 1 : -1;
    /* U belongs to edge B-C, V to C-A, W to A-B (each zero on its edge). */
    if (U == 0.0f && !tie_inside(Bx, By, Cx, Cy, s)) return 0;
    if (V == 0.0f && !tie_inside(Cx, Cy, Ax, Ay, s)) return 0;
    if (W == 0.0f && !tie_inside(Ax, Ay, Bx, By, s)) return 0;
    return 1;
}

/* A worker's list of one kd mesh's crossings (triangle ids). */
typedef struct prim_list {
    uint32_t *ids;
    size_t count, capacity;
    int out_of_memory;
} prim_list;

static void prim_list_add(prim_list *l, uint32_t id) {
    if (l->count == l->capacity) {
        size_t cap = l->capacity ? 2 * l->capacity : 64;
        uint32_t *ids = realloc(l->ids, cap * sizeof *ids);
        if (!ids) {
            l->out_of_memory = 1;
            return;
        }
        l->ids = ids;
        l->capacity = cap;
    }
    l->ids[l->count++] = id;
}

static int compare_ids(const void *a, const void *b) {
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* The number of different ids in the list. */
static uint32_t prim_list_distinct(prim_list *l) {
    if (l->count == 0) return 0;
    qsort(l->ids, l->count, sizeof *l->ids, compare_ids);
    uint32_t distinct = 1;
    for (size_t i = 1; i < l->count; i++) distinct += l->ids[i] != l->ids[i - 1];
    return distinct;
}

/* The crossings of one leaf's entries: counted, or listed when list is not
 * NULL (kd meshes). */
static uint32_t leaf_crossings(const rt_scene_view *s, rt_u32 first, rt_u32 count, const rt_ray *r,
                               const rt_ray_pre *p, prim_list *list) {
    uint32_t n = 0;
    for (rt_u32 e = first; e < first + count; e++) {
        float t;
        if (!rt_crossing_test(&s->tris[e], r, p, &t)) continue;
        if (list)
            prim_list_add(list, s->tri_ids[e]);
        else
            n++;
    }
    return n;
}

/* A depth-first walk over a BVH's leaves whose boxes the range [lo, hi]
 * passes (both levels use it). The tree's depth bounds the stack as in
 * rt_descend: one entry per level at most (flatten refuses deeper trees). */
typedef struct bvh_walk {
    rt_u32 stack[RT_STACK_SIZE];
    int sp;
    int live; /* 0: the walk is over */
    rt_u32 node;
    float lo, hi;
} bvh_walk;

static void walk_start(bvh_walk *w, const rt_scene_view *s, rt_u32 root, const rt_ray *r,
                       const rt_ray_pre *p) {
    float t;
    w->lo = rt_box_lo(r->tmin);
    w->hi = rt_box_hi(r->tmax);
    w->sp = 0;
    w->node = root;
    w->live = rt_box_test(&s->nodes[root], r, p, w->lo, w->hi, &t);
}

/* The next leaf of the walk, or NULL when there is none. */
static const rt_node *walk_next_leaf(bvh_walk *w, const rt_scene_view *s, const rt_ray *r,
                                     const rt_ray_pre *p) {
    while (w->live) {
        const rt_node *nd = &s->nodes[w->node];
        int h0 = 0, h1 = 0;
        if (!(nd->b & RT_NODE_LEAF_FLAG)) {
            float t0, t1;
            h0 = rt_box_test(&s->nodes[nd->a], r, p, w->lo, w->hi, &t0);
            h1 = rt_box_test(&s->nodes[nd->b], r, p, w->lo, w->hi, &t1);
        }
        if (h0 && h1) {
            w->stack[w->sp++] = nd->b;
            w->node = nd->a;
        } else if (h0 || h1) {
            w->node = h0 ? nd->a : nd->b;
        } else {
            /* A leaf, or a node whose children both missed: on with the stack. */
            if (w->sp == 0)
                w->live = 0;
            else
                w->node = w->stack[--w->sp];
            if (nd->b & RT_NODE_LEAF_FLAG) return nd;
        }
    }
    return NULL;
}

/* Every leaf of a mesh BVH whose boxes the ray's range passes. */
static uint32_t bvh_mesh_crossings(const rt_scene_view *s, rt_u32 root, const rt_ray *r,
                                   const rt_ray_pre *p) {
    bvh_walk w;
    walk_start(&w, s, root, r, p);
    uint32_t n = 0;
    for (const rt_node *leaf; (leaf = walk_next_leaf(&w, s, r, p));)
        n += leaf_crossings(s, leaf->a, leaf->b & RT_NODE_COUNT_MASK, r, p, NULL);
    return n;
}

/* Every leaf of a kd mesh whose cell the ray's range passes, by
 * rt_kd_trace_mesh's conservative cell intervals with the range's end in
 * place of the best hit's; the crossings go to list. */
static void kd_mesh_crossings(const rt_scene_view *s, rt_u32 root, const rt_ray *r,
                              const rt_ray_pre *p, prim_list *list) {
    const rt_node *rn = &s->nodes[root];
    const float hi = rt_box_hi(r->tmax);
    float tn, tf;
    if (!rt_kd_root_interval(rn, r, p, rt_box_lo(r->tmin), hi, &tn, &tf)) return;
    rt_u32 st_node[RT_KD_STACK];
    float st_tn[RT_KD_STACK], st_tf[RT_KD_STACK];
    int sp = 0;
    rt_u32 node = rn->a;
    for (;;) {
        const rt_kd_node *n = &s->kd_nodes[node];
        rt_u32 k = n->b & 3u;
        int go_first = 0, go_second = 0;
        rt_u32 first = 0, second = 0;
        float first_tf = tf, second_tn = tn;
        if (k == RT_KD_LEAF) {
            leaf_crossings(s, n->a, n->b >> 2, r, p, list);
        } else {
            float split = RT_AS_FLOAT((rt_i32)n->a);
            rt_u32 left = node + 1u, right = n->b >> 2;
            float o = r->org[k], inv = p->inv[k];
            if (!(RT_FABS(inv) < RT_INF)) {
                first = left;
                second = right;
                go_first = o <= split;
                go_second = o >= split;
            } else {
                float ts = (split - o) * inv;
                float m = RT_FABS(ts) < RT_INF ? RT_FABS(ts) * RT_BOX_T_MARGIN : 0.0f;
                float ts_lo = ts - m, ts_hi = ts + m;
                int left_first = inv >= 0.0f;
                first = left_first ? left : right;
                second = left_first ? right : left;
                first_tf = ts_hi < tf ? ts_hi : tf;
                second_tn = ts_lo > tn ? ts_lo : tn;
                go_first = tn <= ts_hi;
                go_second = ts_lo <= tf && second_tn <= hi;
            }
        }
        if (go_first && go_second) {
            st_node[sp] = second;
            st_tn[sp] = second_tn;
            st_tf[sp] = tf;
            sp++;
            node = first;
            tf = first_tf;
        } else if (go_first) {
            node = first;
            tf = first_tf;
        } else if (go_second) {
            node = second;
            tn = second_tn;
        } else {
            if (sp == 0) return;
            --sp;
            node = st_node[sp];
            tn = st_tn[sp];
            tf = st_tf[sp];
        }
    }
}

/* One instance, as rt_trace_instance enters it. */
static uint32_t instance_crossings(const rt_scene_view *s, rt_u32 inst, const rt_ray *r,
                                   const rt_ray_pre *p, prim_list *list) {
    const rt_instance *in = &s->instances[inst];
    float inst_lo = -RT_INF;
    if (!(RT_SCENE_FLAGS(s) & RT_SCENE_SINGLE) && !rt_inst_enter(in, r, p, &inst_lo)) return 0;
    rt_ray o;
    rt_ray_pre op;
    const rt_ray *ray = rt_cpu_instance_ray(in, r, p, inst_lo, &o, &op);
    if (!(RT_INST_FLAGS(in) & RT_INST_KD)) return bvh_mesh_crossings(s, in->root, ray, &op);
    list->count = 0;
    kd_mesh_crossings(s, in->root, ray, &op, list);
    return prim_list_distinct(list);
}

/* One ray: the object BVH with the range's bounds, then each instance. */
static uint32_t ray_crossings(const rt_scene_view *s, const rt_ray *r, prim_list *list) {
    if (s->hdr->instance_count == 0) return 0;
    rt_ray_pre p;
    rt_ray_prepare(r, &p);
    if (RT_SCENE_FLAGS(s) & RT_SCENE_SINGLE) return instance_crossings(s, 0, r, &p, list);
    bvh_walk w;
    walk_start(&w, s, s->hdr->top_root, r, &p);
    uint32_t n = 0;
    for (const rt_node *leaf; (leaf = walk_next_leaf(&w, s, r, &p));)
        for (rt_u32 e = leaf->a; e < leaf->a + (leaf->b & RT_NODE_COUNT_MASK); e++)
            n += instance_crossings(s, s->inst_ids[e], r, &p, list);
    return n;
}

typedef struct count_job {
    rt_scene_view view;
    const rt_ray *rays;
    uint32_t *counts;
    size_t n;
    atomic_size_t next;
    atomic_int out_of_memory;
} count_job;

enum { COUNT_CHUNK = 256 };

static void count_chunk(void *ctx, int worker, int workers) {
    (void)worker;
    (void)workers;
    count_job *job = ctx;
    prim_list list = {NULL, 0, 0, 0};
    for (;;) {
        size_t first = atomic_fetch_add_explicit(&job->next, COUNT_CHUNK, memory_order_relaxed);
        if (first >= job->n) break;
        size_t end = job->n - first < COUNT_CHUNK ? job->n : first + COUNT_CHUNK;
        for (size_t i = first; i < end; i++)
            job->counts[i] = ray_crossings(&job->view, &job->rays[i], &list);
        if (list.out_of_memory) break;
    }
    if (list.out_of_memory) atomic_store(&job->out_of_memory, 1);
    free(list.ids);
}

rt_status rt_count_crossings(rt_pool *pool, int flush, const rt_flat *flat, const rt_ray *rays,
                             size_t n, uint32_t *counts, rt_error *err) {
    if (n == 0) return RT_OK;
    count_job job;
    memset(&job, 0, sizeof job);
    job.view = rt_flat_view(flat);
    job.rays = rays;
    job.counts = counts;
    job.n = n;
    atomic_init(&job.next, 0);
    atomic_init(&job.out_of_memory, 0);
    rt_pool_run_fp(pool, count_chunk, &job, flush);
    if (atomic_load(&job.out_of_memory))
        return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory for a ray's crossings");
    return RT_OK;
}
