/* SPDX-License-Identifier: Apache-2.0 */
/* kd_internal.h - what the kd-tree builder's files share: the build context,
 * the output buffer, the split rules (kd_split.c), perfect-split clipping
 * (kd_clip.c) and the two split finders (kd_sweep.c exact, kd_binned.c
 * approximate) behind one interface that the recursion (kd_build.c) drives. */
#ifndef RT_KD_INTERNAL_H
#define RT_KD_INTERNAL_H

#include <stdatomic.h>
#include <stdint.h>

#include "accel/kd.h"

/* One triangle's vertices, as the mesh stores them. */
typedef struct kd_tri {
    float v[3][3];
} kd_tri;

typedef struct kd_ctx {
    const kd_tri *tris; /* indexed by the mesh's triangle index */
    uint32_t tri_total; /* size of tris (and of every worker's flag array) */
    rt_kd_options opt;
    int max_depth;
    /* The reference guard (kd_build.c): the first pass counts the triangle
     * entries of the nodes it makes into *work and gives up past work_cap;
     * the second (budget) spends kd_node_in.allow on duplicates. */
    _Atomic uint64_t *work; /* NULL: no count */
    uint64_t work_cap;
    int budget;
} kd_ctx;

/* ---- output: nodes in depth-first order, indices relative to the buffer --- */

/* A placeholder leaf for a subtree built by a task (kd_build.c): b has all
 * bits set, a is the task's number. */
#define KD_PLACEHOLDER 0xffffffffu

typedef struct kd_out {
    rt_kd_node *nodes;
    uint32_t node_count, node_cap;
    uint32_t *prims;
    uint32_t prim_count, prim_cap;
    /* per placeholder, in order: its node index and prim_count when made */
    uint32_t *ph;
    uint32_t ph_count, ph_cap;
    int oom;
} kd_out;

/* Appends an inner node and returns its index; the right child is set by
 * rt_kd_out_set_right once the left subtree is complete. */
uint32_t rt_kd_out_inner(kd_out *o, int axis, float split);
void rt_kd_out_set_right(kd_out *o, uint32_t inner, uint32_t right);
/* Appends a leaf with n entries (triangle indices, kept in the given order). */
void rt_kd_out_leaf(kd_out *o, const uint32_t *tris, uint32_t n);
void rt_kd_out_placeholder(kd_out *o, uint32_t task);
void rt_kd_out_free(kd_out *o);

/* ---- split rules (kd_split.c) ---------------------------------------------- */

typedef struct kd_split {
    double cost; /* INFINITY: none found */
    int axis;
    float pos;
    int planar_left; /* triangles lying in the plane go left */
    uint32_t both;   /* triangles on both sides: the entries the split adds */
} kd_split;

/* Which child a triangle whose clipped box spans [lo, hi] on the split axis
 * belongs to: the same rule for both builders (and the one the event sweep
 * counts): lo < pos < hi straddles; a box ending at pos goes left, one
 * starting at pos goes right; a planar one (lo == hi) by its side, and by
 * planar_left when it lies in the plane. */
enum { KD_LEFT = 1, KD_RIGHT = 2, KD_BOTH = 3 };
int rt_kd_side(float lo, float hi, float pos, int planar_left);

/* Surface area of a box (double). */
double rt_kd_area(const rt_aabb *b);

/* What pricing a plane needs of a cell, computed once per node. */
typedef struct kd_cell {
    const rt_aabb *box;
    double ext[3]; /* extents */
    /* the sum and product of the other two extents, per axis k */
    double other_sum[3], other_prod[3];
    double inv_area; /* 1 / surface area (0 when the area is 0: no split) */
} kd_cell;

/* Fills c for box; returns 0 when the box has no area (a leaf). */
int rt_kd_cell_init(kd_cell *c, const rt_aabb *box);

/* What kd_offer needs of one axis of a cell and of the cost model, set once
 * per axis (kd_axis_init) for a sweep over many planes. */
typedef struct kd_axis {
    double s, p;       /* the sum and product of the other two extents */
    double lo, hi;     /* the cell's bounds on the axis */
    double inv_area;   /* 1 / the cell's area */
    double kt, ki, eb; /* costs.traverse, costs.intersect, empty_bonus */
    float flo, fhi;    /* the bounds as floats (a plane on a face) */
    int k;
} kd_axis;

static inline void kd_axis_init(kd_axis *x, const kd_ctx *c, const kd_cell *v, int k) {
    x->s = v->other_sum[k];
    x->p = v->other_prod[k];
    x->lo = (double)v->box->bmin[k];
    x->hi = (double)v->box->bmax[k];
    x->flo = v->box->bmin[k];
    x->fhi = v->box->bmax[k];
    x->inv_area = v->inv_area;
    x->kt = (double)c->opt.costs.traverse;
    x->ki = (double)c->opt.costs.intersect;
    x->eb = (double)c->opt.empty_bonus;
    x->k = k;
}

/* Offers the plane pos on axis x->k of the cell to best: nl triangles
 * reaching left of it, nr right (straddling ones in both), np lying in the
 * plane, n in all. Both
 * places for the planar ones are priced, with the empty-space bonus when a
 * side is empty; a split that leaves one child equal to the cell with every
 * triangle (a plane on the cell's face) is refused, so recursion always
 * progresses. Ties keep the earlier offer. */
static inline void kd_offer_axis(const kd_axis *x, float pos, uint32_t nl, uint32_t nr, uint32_t np,
                                 uint32_t n, kd_split *best) {
    /* The children's areas: the cell's with the extent on k cut at pos.
     * Inline: the sweep offers every event position (a quarter of the
     * exact build's time went to the calls). */
    double l = (double)pos - x->lo, r = x->hi - (double)pos;
    double pl = 2.0 * (l * x->s + x->p) * x->inv_area;
    double pr = 2.0 * (r * x->s + x->p) * x->inv_area;
    /* A plane on a face of the cell leaves one child equal to the cell. */
    int left_is_cell = pos == x->fhi, right_is_cell = pos == x->flo;
    for (int side = 0; side < 2; side++) {
        int planar_left = side == 0;
        uint32_t na = nl + (planar_left ? np : 0u), nb = nr + (planar_left ? 0u : np);
        if ((left_is_cell && na == n) || (right_is_cell && nb == n)) continue;
        double bonus = (na == 0 || nb == 0) ? x->eb : 1.0;
        double cost = bonus * (x->kt + x->ki * (pl * (double)na + pr * (double)nb));
        if (cost < best->cost) {
            best->cost = cost;
            best->axis = x->k;
            best->pos = pos;
            best->planar_left = planar_left;
            best->both = na + nb - n;
        }
        if (!np) break; /* the same price both ways */
    }
}

/* kd_offer_axis for axis k of cell v. */
static inline void kd_offer(const kd_ctx *c, const kd_cell *v, int k, float pos, uint32_t nl,
                            uint32_t nr, uint32_t np, uint32_t n, kd_split *best) {
    kd_axis x;
    kd_axis_init(&x, c, v, k);
    kd_offer_axis(&x, pos, nl, nr, np, n, best);
}

/* ---- perfect splits (kd_clip.c) --------------------------------------------- */

/* The box of triangle t clipped to cell, rounded outwards to floats (only
 * where the clipped coordinate is not already a float), within cell.
 * Returns 0 when the triangle does not reach the cell. */
int rt_kd_clip_box(const kd_tri *t, const rt_aabb *cell, rt_aabb *out);

/* rt_kd_clip_box of t for both children of cell split at pos on axis (the left
 * cell ending at pos, the right one starting there), sharing the work of
 * the planes before axis. Returns KD_LEFT | KD_RIGHT for the children t
 * reaches (their boxes set). */
int rt_kd_clip_pair(const kd_tri *t, const rt_aabb *cell, int axis, float pos, rt_aabb *left,
                    rt_aabb *right);

/* ---- the split finders ----------------------------------------------------------- */

/* Per worker scratch: a flag per triangle (zero between uses), a list and
 * a buffer (kept between nodes, so that a split allocates less). */
typedef struct kd_scratch {
    uint8_t *flags;
    uint32_t *list;
    uint32_t list_cap;
    void *buf;
    size_t buf_cap;
} kd_scratch;

/* A node's input: the cell, the depth, the triangle count, the duplicates
 * its subtree may still add (budget pass only) and the finder's own data
 * (events or boxes), which the node owns. */
typedef struct kd_node_in {
    rt_aabb cell;
    int depth;
    uint32_t tris;
    uint64_t allow;
    void *data;
    uint32_t size;
} kd_node_in;

typedef struct kd_finder {
    /* The cheapest split of the node, or best->cost INFINITY. */
    void (*find)(const kd_ctx *c, const kd_node_in *in, kd_split *best);
    /* Splits in into l and r (and frees in's data). Returns 0 when out of
     * memory (in's data freed, l and r empty). */
    int (*split)(const kd_ctx *c, kd_node_in *in, const kd_split *s, kd_scratch *w, kd_node_in *l,
                 kd_node_in *r);
    /* The node's triangles in increasing index order into w->list; returns
     * the count (or UINT32_MAX when out of memory). */
    uint32_t (*leaf)(const kd_ctx *c, const kd_node_in *in, kd_scratch *w);
    /* The root's input from the triangles with area (ids[0..n-1], their
     * boxes), on pool's workers where there are (pool may be NULL); returns
     * 0 when out of memory. */
    int (*root)(const kd_ctx *c, const uint32_t *ids, const rt_aabb *boxes, uint32_t n,
                const rt_aabb *cell, rt_pool *pool, kd_node_in *out);
} kd_finder;

extern const kd_finder rt_kd_finder_sweep;  /* kd_sweep.c */
extern const kd_finder rt_kd_finder_binned; /* kd_binned.c */

/* Grows w->list to hold n entries (and a spare one); 0 when out of memory. */
int rt_kd_scratch_list(kd_scratch *w, uint32_t n);

/* Grows w->buf to hold bytes; 0 when out of memory. */
int rt_kd_scratch_buf(kd_scratch *w, size_t bytes);

/* Frees what w holds. */
void rt_kd_scratch_free(kd_scratch *w);

/* Sorts v[0..n) ascending (a leaf's entries: insertion sort while short). */
void rt_kd_sort_u32(uint32_t *v, uint32_t n);

#endif /* RT_KD_INTERNAL_H */
