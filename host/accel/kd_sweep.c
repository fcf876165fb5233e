/* SPDX-License-Identifier: Apache-2.0 */
/* kd_sweep.c - the exact SAH split of Wald and Havran (2006) in O(N log N):
 * every node keeps its split events sorted, one list per axis (by position,
 * then type, then triangle), so the best plane is one sweep per axis; the
 * children's lists come from the parent's in order (triangles on one side
 * keep their events) plus the sorted events of the straddling triangles,
 * recomputed from their clipped boxes and merged. Only the root's lists are
 * sorted from scratch (a radix sort, see sweep_root).
 *
 * An event is 8 bytes: the position and a key holding the type above the
 * triangle index, so that within one axis the order (position, type,
 * triangle) is the position's float order, then the key's integer order. */
#include "accel/kd_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/thread_pool.h"

/* Event types in sweep order at one position: ends before planars before
 * starts, so a plane at p sees the triangles ending at p on its left. */
enum { EV_END = 0, EV_PLANAR = 1, EV_START = 2 };

#define EV_SHIFT 30
#define EV_TRI   ((1u << EV_SHIFT) - 1u)

typedef struct sw_ev {
    float pos;
    uint32_t key; /* type << EV_SHIFT | triangle */
} sw_ev;

/* A node's events: one sorted list per axis, in the same allocation as this
 * header (the node's data). */
typedef struct sw_lists {
    sw_ev *e[3];
    uint32_t n[3];
} sw_lists;

/* A block holding the header and room for cap[k] (+1, see sweep_split)
 * events on axis k; NULL when out of memory. */
static sw_lists *lists_alloc(const size_t cap[3]) {
    size_t total = cap[0] + cap[1] + cap[2] + 3;
    sw_lists *l = malloc(sizeof(sw_lists) + sizeof(sw_ev) * total);
    if (!l) return NULL;
    sw_ev *e = (sw_ev *)(l + 1);
    for (int k = 0; k < 3; k++) {
        l->e[k] = e;
        l->n[k] = 0;
        e += cap[k] + 1;
    }
    return l;
}

/* The events' order (position as floats compare, then type, then triangle)
 * as one integer: the position's float order (-0 as +0) above the key. */
static inline uint64_t ev_order(sw_ev v) {
    uint32_t u;
    memcpy(&u, &v.pos, sizeof u);
    u = (u & 0x7fffffffu) ? u : 0u;
    u ^= (uint32_t)((int32_t)u >> 31) | 0x80000000u;
    return (uint64_t)u << 32 | v.key;
}

/* After every event in ev_order: a NaN position whose order is all ones,
 * and a key no event has. */
static inline sw_ev ev_sentinel(void) {
    uint32_t u = 0x7fffffffu;
    sw_ev v;
    memcpy(&v.pos, &u, sizeof u);
    v.key = 0xffffffffu;
    return v;
}

static inline int ev_before(sw_ev a, sw_ev b) {
    return ev_order(a) < ev_order(b);
}

/* Sorts e[0..n) by ev_before: insertion sort for short runs, then
 * bottom-up merging through tmp (n entries). The order is total (a
 * triangle has one event of a type per axis), so the result is unique. */
static void ev_sort(sw_ev *e, uint32_t n, sw_ev *tmp) {
    const uint32_t run = 16;
    for (uint32_t lo = 0; lo < n; lo += run) {
        uint32_t hi = lo + run < n ? lo + run : n;
        for (uint32_t i = lo + 1; i < hi; i++) {
            sw_ev x = e[i];
            uint32_t j = i;
            while (j > lo && ev_before(x, e[j - 1])) {
                e[j] = e[j - 1];
                j--;
            }
            e[j] = x;
        }
    }
    sw_ev *src = e, *dst = tmp;
    for (uint32_t w = run; w < n; w *= 2) {
        for (uint32_t lo = 0; lo < n; lo += 2 * w) {
            uint32_t mid = lo + w < n ? lo + w : n, hi = lo + 2 * w < n ? lo + 2 * w : n;
            uint32_t i = lo, j = mid, o = lo;
            while (i < mid && j < hi) dst[o++] = ev_before(src[j], src[i]) ? src[j++] : src[i++];
            while (i < mid) dst[o++] = src[i++];
            while (j < hi) dst[o++] = src[j++];
        }
        sw_ev *t = src;
        src = dst;
        dst = t;
    }
    if (src != e) memcpy(e, src, sizeof(sw_ev) * n);
}

/* The offers of one axis, in the sweep's order (kd_offer keeps the earlier
 * of equal offers, so the order is part of the result): one per position,
 * with the events there counted by type (they are consecutive). */
static void sweep_axis(const kd_ctx *c, const kd_cell *cell, int k, const sw_ev *e, uint32_t m,
                       uint32_t n, kd_split *best) {
    kd_axis x;
    kd_axis_init(&x, c, cell, k);
    uint32_t nl = 0, nr = n, i = 0;
    /* A flat cell on this axis can still separate planar triangles from
     * others lying beside them; kd_offer refuses splits without progress. */
    while (i < m) {
        float p = e[i].pos;
        uint32_t j = i + 1;
        while (j < m && e[j].pos == p) j++;
        uint32_t pe = 0, pp = 0, ps = 0;
        for (; i < j; i++) {
            uint32_t type = e[i].key >> EV_SHIFT;
            pe += type == EV_END;
            pp += type == EV_PLANAR;
            ps += type == EV_START;
        }
        nr -= pp + pe;
        kd_offer_axis(&x, p, nl, nr, pp, n, best);
        nl += ps + pp;
    }
}

static void sweep_find(const kd_ctx *c, const kd_node_in *in, kd_split *best) {
    const sw_lists *L = in->data;
    kd_cell cell;
    best->cost = INFINITY;
    if (!rt_kd_cell_init(&cell, &in->cell)) return;
    for (int k = 0; k < 3; k++) sweep_axis(c, &cell, k, L->e[k], L->n[k], in->tris, best);
}

/* Appends the events of one triangle's box on axis k: a planar event where
 * the box is flat, else a start and an end (in sorted order). */
static uint32_t box_events(const rt_aabb *b, int k, uint32_t tri, sw_ev *e, uint32_t n) {
    if (b->bmin[k] == b->bmax[k]) {
        e[n++] = (sw_ev){b->bmin[k], (uint32_t)EV_PLANAR << EV_SHIFT | tri};
    } else {
        e[n++] = (sw_ev){b->bmin[k], (uint32_t)EV_START << EV_SHIFT | tri};
        e[n++] = (sw_ev){b->bmax[k], (uint32_t)EV_END << EV_SHIFT | tri};
    }
    return n;
}

static int sweep_split(const kd_ctx *c, kd_node_in *in, const kd_split *s, kd_scratch *w,
                       kd_node_in *l, kd_node_in *r) {
    sw_lists *L = in->data;
    const int a = s->axis;
    const float pos = s->pos;
    uint8_t *side = w->flags;
    memset(l, 0, sizeof *l);
    memset(r, 0, sizeof *r);
    l->cell = in->cell;
    l->cell.bmax[a] = pos;
    r->cell = in->cell;
    r->cell.bmin[a] = pos;
    l->depth = r->depth = in->depth + 1;
    if (!rt_kd_scratch_list(w, in->tris)) {
        free(in->data);
        in->data = NULL;
        return 0;
    }
    /* Classify by the split axis's events alone (the rule of rt_kd_side): a
     * triangle's start comes before its end, so the end decides. The
     * straddling triangles go to w->list. */
    const sw_ev *ea = L->e[a];
    uint32_t ma = L->n[a], nl = 0, nr = 0, nb = 0;
    for (uint32_t i = 0; i < ma; i++) {
        uint32_t t = ea[i].key & EV_TRI, type = ea[i].key >> EV_SHIFT;
        float p = ea[i].pos;
        if (type == EV_START) {
            side[t] = p >= pos ? KD_RIGHT : KD_BOTH;
        } else if (type == EV_END) {
            if (p <= pos) {
                side[t] = KD_LEFT;
                nl++;
            } else if (side[t] == KD_RIGHT) {
                nr++;
            } else {
                w->list[nb++] = t;
            }
        } else {
            int sd = rt_kd_side(p, p, pos, s->planar_left);
            side[t] = (uint8_t)sd;
            if (sd == KD_LEFT)
                nl++;
            else
                nr++;
        }
    }
    uint32_t one_l = nl, one_r = nr;
    /* The straddling triangles, clipped to each child: at most 2 events per
     * axis and side each; cl[side][k] counts them. */
    int ok = rt_kd_scratch_buf(w, sizeof(sw_ev) * (14 * (size_t)nb + 7));
    sw_ev *clip = w->buf;
    sw_lists *le = NULL, *re = NULL;
    uint32_t cl[2][3] = {{0, 0, 0}, {0, 0, 0}};
    sw_ev *cb[2][3];
    if (ok) {
        for (int sd = 0; sd < 2; sd++)
            for (int k = 0; k < 3; k++) cb[sd][k] = clip + (size_t)(3 * sd + k) * (2 * nb + 1);
        for (uint32_t j = 0; j < nb; j++) {
            uint32_t t = w->list[j];
            rt_aabb lb, rb;
            int got = rt_kd_clip_pair(&c->tris[t], &in->cell, a, pos, &lb, &rb);
            if (got & KD_LEFT) {
                for (int k = 0; k < 3; k++) cl[0][k] = box_events(&lb, k, t, cb[0][k], cl[0][k]);
                nl++;
            }
            if (got & KD_RIGHT) {
                for (int k = 0; k < 3; k++) cl[1][k] = box_events(&rb, k, t, cb[1][k], cl[1][k]);
                nr++;
            }
        }
        sw_ev *tmp = clip + 6 * (2 * (size_t)nb + 1);
        for (int sd = 0; sd < 2; sd++)
            for (int k = 0; k < 3; k++) ev_sort(cb[sd][k], cl[sd][k], tmp);
        /* Room per axis: the one-sided triangles' events (at most two each,
         * at most the parent's) and the clipped ones. */
        size_t capl[3], capr[3];
        for (int k = 0; k < 3; k++) {
            size_t m = L->n[k];
            capl[k] = (2 * (size_t)one_l < m ? 2 * (size_t)one_l : m) + cl[0][k];
            capr[k] = (2 * (size_t)one_r < m ? 2 * (size_t)one_r : m) + cl[1][k];
        }
        le = lists_alloc(capl);
        re = lists_alloc(capr);
        ok = le && re;
    }
    if (ok) {
        for (int k = 0; k < 3; k++) {
            /* The one-sided events in order, with the clipped ones (sorted,
             * ended by a sentinel) let in before the first event after
             * them. Both children's slots are written for every event and
             * the index of the triangle's side advanced (a region has a
             * spare slot). */
            const sw_ev *e = L->e[k];
            uint32_t m = L->n[k];
            sw_ev *lo = le->e[k], *ro = re->e[k];
            sw_ev *cbl = cb[0][k], *cbr = cb[1][k];
            uint32_t x = 0, y = 0, jl = 0, jr = 0;
            if (cl[0][k] | cl[1][k]) {
                cbl[cl[0][k]] = cbr[cl[1][k]] = ev_sentinel();
                uint64_t kl = ev_order(cbl[0]), kr = ev_order(cbr[0]);
                for (uint32_t i = 0; i < m; i++) {
                    sw_ev v = e[i];
                    uint64_t kv = ev_order(v);
                    while (kl < kv) {
                        lo[x++] = cbl[jl++];
                        kl = ev_order(cbl[jl]);
                    }
                    while (kr < kv) {
                        ro[y++] = cbr[jr++];
                        kr = ev_order(cbr[jr]);
                    }
                    uint8_t sd = side[v.key & EV_TRI];
                    lo[x] = v;
                    ro[y] = v;
                    x += sd == KD_LEFT;
                    y += sd == KD_RIGHT;
                }
                while (jl < cl[0][k]) lo[x++] = cbl[jl++];
                while (jr < cl[1][k]) ro[y++] = cbr[jr++];
            } else {
                for (uint32_t i = 0; i < m; i++) {
                    sw_ev v = e[i];
                    uint8_t sd = side[v.key & EV_TRI];
                    lo[x] = v;
                    ro[y] = v;
                    x += sd == KD_LEFT;
                    y += sd == KD_RIGHT;
                }
            }
            le->n[k] = x;
            re->n[k] = y;
        }
        l->data = le;
        l->size = le->n[0] + le->n[1] + le->n[2];
        l->tris = nl;
        r->data = re;
        r->size = re->n[0] + re->n[1] + re->n[2];
        r->tris = nr;
    }
    for (uint32_t i = 0; i < ma; i++) side[ea[i].key & EV_TRI] = 0;
    free(in->data);
    in->data = NULL;
    if (!ok) {
        free(le);
        free(re);
    }
    return ok;
}

static uint32_t sweep_leaf(const kd_ctx *c, const kd_node_in *in, kd_scratch *w) {
    (void)c;
    const sw_lists *L = in->data;
    if (!rt_kd_scratch_list(w, in->tris)) return UINT32_MAX;
    uint32_t n = 0;
    const sw_ev *e = L->e[0];
    for (uint32_t i = 0; i < L->n[0]; i++)
        if ((e[i].key >> EV_SHIFT) != EV_END) w->list[n++] = e[i].key & EV_TRI;
    rt_kd_sort_u32(w->list, n);
    return n;
}

/* A float's order as an unsigned key (finite values; -0 as +0, since the
 * events compare positions as floats). */
static inline uint32_t order_key(float f) {
    if (f == 0.0f) f = 0.0f;
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

/* Stable LSD radix sort of src[0..n) by position, 11 bits a pass (one
 * pass counts all three digits; a pass where every key has the same digit
 * is skipped), alternating between src and dst; the result is in e (which
 * is src or dst). */
static void radix_by_pos(sw_ev *src, sw_ev *dst, uint32_t n, sw_ev *e) {
    enum { BITS = 11, BUCKETS = 1 << BITS };
    static const int shift[3] = {0, BITS, 2 * BITS};
    uint32_t count[3][BUCKETS];
    memset(count, 0, sizeof count);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t key = order_key(src[i].pos);
        count[0][key & (BUCKETS - 1)]++;
        count[1][(key >> BITS) & (BUCKETS - 1)]++;
        count[2][key >> (2 * BITS)]++;
    }
    for (int d = 0; d < 3; d++) {
        uint32_t *c = count[d];
        int trivial = 0;
        uint32_t sum = 0;
        for (int b = 0; b < BUCKETS; b++) {
            uint32_t x = c[b];
            trivial |= x == n;
            c[b] = sum;
            sum += x;
        }
        if (trivial) continue;
        for (uint32_t i = 0; i < n; i++)
            dst[c[(order_key(src[i].pos) >> shift[d]) & (BUCKETS - 1)]++] = src[i];
        sw_ev *t = src;
        src = dst;
        dst = t;
    }
    if (src != e) memcpy(e, src, sizeof(sw_ev) * n);
}

/* The root's lists, an axis per worker. */
typedef struct root_job {
    const uint32_t *ids;
    const rt_aabb *boxes;
    uint32_t n;
    sw_lists *L;
    sw_ev *tmp; /* 2 n events per axis */
} root_job;

static void root_axis(const root_job *j, int k) {
    /* In (type, triangle) order (ids ascending), in the scratch: the stable
     * sort by position then gives the events' order. */
    const rt_aabb *boxes = j->boxes;
    const uint32_t *ids = j->ids;
    uint32_t n = j->n, m = 0;
    sw_ev *e = j->tmp + 2 * (size_t)n * (size_t)k;
    for (uint32_t i = 0; i < n; i++)
        if (boxes[i].bmin[k] != boxes[i].bmax[k])
            e[m++] = (sw_ev){boxes[i].bmax[k], (uint32_t)EV_END << EV_SHIFT | ids[i]};
    for (uint32_t i = 0; i < n; i++)
        if (boxes[i].bmin[k] == boxes[i].bmax[k])
            e[m++] = (sw_ev){boxes[i].bmin[k], (uint32_t)EV_PLANAR << EV_SHIFT | ids[i]};
    for (uint32_t i = 0; i < n; i++)
        if (boxes[i].bmin[k] != boxes[i].bmax[k])
            e[m++] = (sw_ev){boxes[i].bmin[k], (uint32_t)EV_START << EV_SHIFT | ids[i]};
    radix_by_pos(e, j->L->e[k], m, j->L->e[k]);
    j->L->n[k] = m;
}

static void root_run(void *ctx, int worker, int workers) {
    for (int k = worker; k < 3; k += workers) root_axis(ctx, k);
}

static int sweep_root(const kd_ctx *c, const uint32_t *ids, const rt_aabb *boxes, uint32_t n,
                      const rt_aabb *cell, rt_pool *pool, kd_node_in *out) {
    (void)c;
    memset(out, 0, sizeof *out);
    size_t cap[3] = {2 * (size_t)n, 2 * (size_t)n, 2 * (size_t)n};
    sw_lists *L = lists_alloc(cap);
    sw_ev *tmp = malloc(sizeof(sw_ev) * (6 * (size_t)n + 1));
    if (!L || !tmp) {
        free(L);
        free(tmp);
        return 0;
    }
    root_job j = {ids, boxes, n, L, tmp};
    if (pool && rt_pool_size(pool) > 1)
        rt_pool_run(pool, root_run, &j);
    else
        root_run(&j, 0, 1);
    free(tmp);
    out->cell = *cell;
    out->data = L;
    out->size = L->n[0] + L->n[1] + L->n[2];
    out->tris = n;
    return 1;
}

const kd_finder rt_kd_finder_sweep = {sweep_find, sweep_split, sweep_leaf, sweep_root};
