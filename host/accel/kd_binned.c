/* SPDX-License-Identifier: Apache-2.0 */
/* kd_binned.c - the approximate SAH split: per axis, the cell is cut into
 * bins and two histograms (where boxes begin, where they end) price every bin
 * boundary in one pass (the scanning/binning approximation of Hunt et al.
 * 2006 and Shevtsov et al. 2007). Only the choice of plane is approximate:
 * triangles are then classified by rt_kd_side and clipped exactly, as in the
 * exact builder. */
#include "accel/kd_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct kd_item {
    rt_aabb box; /* clipped to the node's cell */
    uint32_t tri;
} kd_item;

#define MAX_BINS 256

static int bin_of(float x, float lo, double scale, int bins) {
    double b = ((double)x - (double)lo) * scale;
    int i = b > 0.0 ? (int)b : 0;
    return i < bins ? i : bins - 1;
}

static void binned_find(const kd_ctx *c, const kd_node_in *in, kd_split *best) {
    const kd_item *it = in->data;
    uint32_t n = in->tris;
    int bins = c->opt.bins;
    kd_cell cell;
    best->cost = INFINITY;
    if (!rt_kd_cell_init(&cell, &in->cell)) return;
    for (int k = 0; k < 3; k++) {
        float lo = in->cell.bmin[k], hi = in->cell.bmax[k];
        if (!(hi > lo)) continue;
        uint32_t begin[MAX_BINS], end[MAX_BINS];
        memset(begin, 0, sizeof(uint32_t) * (size_t)bins);
        memset(end, 0, sizeof(uint32_t) * (size_t)bins);
        double scale = (double)bins / ((double)hi - (double)lo);
        for (uint32_t i = 0; i < n; i++) {
            begin[bin_of(it[i].box.bmin[k], lo, scale, bins)]++;
            end[bin_of(it[i].box.bmax[k], lo, scale, bins)]++;
        }
        /* Boundary j (between bins j-1 and j): boxes beginning in bins < j
         * reach left of it, boxes ending in bins >= j reach right. */
        uint32_t left = 0, right = n;
        for (int j = 1; j < bins; j++) {
            left += begin[j - 1];
            right -= end[j - 1];
            float pos = (float)((double)lo + ((double)hi - (double)lo) * j / bins);
            if (!(pos > lo && pos < hi)) continue;
            kd_offer(c, &cell, k, pos, left, right, 0, n, best);
        }
    }
}

static int binned_split(const kd_ctx *c, kd_node_in *in, const kd_split *s, kd_scratch *w,
                        kd_node_in *l, kd_node_in *r) {
    (void)w;
    const kd_item *it = in->data;
    uint32_t n = in->tris;
    memset(l, 0, sizeof *l);
    memset(r, 0, sizeof *r);
    l->cell = in->cell;
    l->cell.bmax[s->axis] = s->pos;
    r->cell = in->cell;
    r->cell.bmin[s->axis] = s->pos;
    l->depth = r->depth = in->depth + 1;
    kd_item *li = malloc(sizeof(kd_item) * ((size_t)n + 1));
    kd_item *ri = malloc(sizeof(kd_item) * ((size_t)n + 1));
    int ok = li && ri;
    uint32_t nl = 0, nr = 0;
    for (uint32_t i = 0; ok && i < n; i++) {
        int side =
            rt_kd_side(it[i].box.bmin[s->axis], it[i].box.bmax[s->axis], s->pos, s->planar_left);
        if (side == KD_LEFT) {
            li[nl++] = it[i];
        } else if (side == KD_RIGHT) {
            ri[nr++] = it[i];
        } else {
            kd_item x = it[i], y = it[i];
            int got = rt_kd_clip_pair(&c->tris[x.tri], &in->cell, s->axis, s->pos, &x.box, &y.box);
            if (got & KD_LEFT) li[nl++] = x;
            if (got & KD_RIGHT) ri[nr++] = y;
        }
    }
    free(in->data);
    in->data = NULL;
    if (!ok) {
        free(li);
        free(ri);
        return 0;
    }
    l->data = li;
    l->size = l->tris = nl;
    r->data = ri;
    r->size = r->tris = nr;
    return 1;
}

static int u32_cmp(const void *pa, const void *pb) {
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return a < b ? -1 : a > b;
}

static uint32_t binned_leaf(const kd_ctx *c, const kd_node_in *in, kd_scratch *w) {
    (void)c;
    const kd_item *it = in->data;
    if (!rt_kd_scratch_list(w, in->tris)) return UINT32_MAX;
    for (uint32_t i = 0; i < in->tris; i++) w->list[i] = it[i].tri;
    if (in->tris) qsort(w->list, in->tris, sizeof(uint32_t), u32_cmp);
    return in->tris;
}

static int binned_root(const kd_ctx *c, const uint32_t *ids, const rt_aabb *boxes, uint32_t n,
                       const rt_aabb *cell, rt_pool *pool, kd_node_in *out) {
    (void)c;
    (void)pool;
    memset(out, 0, sizeof *out);
    kd_item *it = malloc(sizeof(kd_item) * ((size_t)n + 1));
    if (!it) return 0;
    for (uint32_t i = 0; i < n; i++) {
        it[i].box = boxes[i];
        it[i].tri = ids[i];
    }
    out->cell = *cell;
    out->data = it;
    out->size = out->tris = n;
    return 1;
}

const kd_finder rt_kd_finder_binned = {binned_find, binned_split, binned_leaf, binned_root};
