/* kd_sweep.c - the exact SAH split of Wald and Havran (2006) in O(N log N):
 * every node keeps its split events sorted (by axis, position, type), so the
 * best plane is one sweep; the children's lists come from the parent's in
 * order (triangles on one side keep their events) plus the sorted events of
 * the straddling triangles, recomputed from their clipped boxes and merged.
 * Only the root's list is sorted from scratch. */
#include "accel/kd_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Event types in sweep order at one position: ends before planars before
 * starts, so a plane at p sees the triangles ending at p on its left. */
enum { EV_END = 0, EV_PLANAR = 1, EV_START = 2 };

typedef struct kd_event {
    float pos;
    uint32_t tri;
    uint8_t axis;
    uint8_t type;
} kd_event;

static int ev_before(const kd_event *a, const kd_event *b) {
    if (a->axis != b->axis) return a->axis < b->axis;
    if (a->pos != b->pos) return a->pos < b->pos;
    if (a->type != b->type) return a->type < b->type;
    return a->tri < b->tri;
}

/* Sorts e[0..n) by ev_before: insertion sort for short runs, then
 * bottom-up merging through tmp (n entries). The order is total (the
 * triangle index breaks ties), so the result is unique. Faster than qsort,
 * whose comparison goes through a function pointer. */
static void ev_sort(kd_event *e, uint32_t n, kd_event *tmp) {
    const uint32_t run = 16;
    for (uint32_t lo = 0; lo < n; lo += run) {
        uint32_t hi = lo + run < n ? lo + run : n;
        for (uint32_t i = lo + 1; i < hi; i++) {
            kd_event x = e[i];
            uint32_t j = i;
            while (j > lo && ev_before(&x, &e[j - 1])) {
                e[j] = e[j - 1];
                j--;
            }
            e[j] = x;
        }
    }
    kd_event *src = e, *dst = tmp;
    for (uint32_t w = run; w < n; w *= 2) {
        for (uint32_t lo = 0; lo < n; lo += 2 * w) {
            uint32_t mid = lo + w < n ? lo + w : n, hi = lo + 2 * w < n ? lo + 2 * w : n;
            uint32_t i = lo, j = mid, o = lo;
            while (i < mid && j < hi) dst[o++] = ev_before(&src[j], &src[i]) ? src[j++] : src[i++];
            while (i < mid) dst[o++] = src[i++];
            while (j < hi) dst[o++] = src[j++];
        }
        kd_event *t = src;
        src = dst;
        dst = t;
    }
    if (src != e) memcpy(e, src, sizeof(kd_event) * n);
}

/* Appends the events of one triangle's box: a planar event on an axis where
 * the box is flat, else a start and an end. Returns the new count. */
static uint32_t box_events(const rt_aabb *b, uint32_t tri, kd_event *e, uint32_t n) {
    for (int k = 0; k < 3; k++) {
        if (b->bmin[k] == b->bmax[k]) {
            e[n++] = (kd_event){b->bmin[k], tri, (uint8_t)k, EV_PLANAR};
        } else {
            e[n++] = (kd_event){b->bmin[k], tri, (uint8_t)k, EV_START};
            e[n++] = (kd_event){b->bmax[k], tri, (uint8_t)k, EV_END};
        }
    }
    return n;
}

static void sweep_find(const kd_ctx *c, const kd_node_in *in, kd_split *best) {
    const kd_event *e = in->data;
    uint32_t n = in->tris, size = in->size;
    kd_cell cell;
    best->cost = INFINITY;
    if (!kd_cell_init(&cell, &in->cell)) return;
    uint32_t i = 0;
    while (i < size) {
        int k = e[i].axis;
        uint32_t nl = 0, nr = n;
        /* A flat cell on this axis can still separate planar triangles from
         * others lying beside them; kd_offer refuses splits without progress. */
        while (i < size && e[i].axis == k) {
            float p = e[i].pos;
            uint32_t pe = 0, pp = 0, ps = 0;
            while (i < size && e[i].axis == k && e[i].pos == p && e[i].type == EV_END) pe++, i++;
            while (i < size && e[i].axis == k && e[i].pos == p && e[i].type == EV_PLANAR) pp++, i++;
            while (i < size && e[i].axis == k && e[i].pos == p && e[i].type == EV_START) ps++, i++;
            nr -= pp + pe;
            kd_offer(c, &cell, k, p, nl, nr, pp, n, best);
            nl += ps + pp;
        }
    }
}

/* Merges two sorted lists into out. */
static void merge(const kd_event *a, uint32_t na, const kd_event *b, uint32_t nb, kd_event *out) {
    uint32_t i = 0, j = 0, o = 0;
    while (i < na && j < nb) out[o++] = ev_before(&b[j], &a[i]) ? b[j++] : a[i++];
    while (i < na) out[o++] = a[i++];
    while (j < nb) out[o++] = b[j++];
}

static int sweep_split(const kd_ctx *c, kd_node_in *in, const kd_split *s, kd_scratch *w,
                       kd_node_in *l, kd_node_in *r) {
    kd_event *e = in->data;
    uint32_t size = in->size;
    uint8_t *side = w->flags;
    memset(l, 0, sizeof *l);
    memset(r, 0, sizeof *r);
    /* Classify: every triangle straddles until its events on the split axis
     * say otherwise (the rule of kd_side). */
    for (uint32_t i = 0; i < size; i++) side[e[i].tri] = KD_BOTH;
    uint32_t nboth = 0;
    for (uint32_t i = 0; i < size; i++) {
        const kd_event *v = &e[i];
        if (v->axis != s->axis) continue;
        if (v->type == EV_END && v->pos <= s->pos)
            side[v->tri] = KD_LEFT;
        else if (v->type == EV_START && v->pos >= s->pos)
            side[v->tri] = KD_RIGHT;
        else if (v->type == EV_PLANAR)
            side[v->tri] = (uint8_t)kd_side(v->pos, v->pos, s->pos, s->planar_left);
    }
    uint32_t nl_ev = 0, nr_ev = 0, nl = 0, nr = 0;
    for (uint32_t i = 0; i < size; i++) {
        uint8_t f = side[e[i].tri];
        int first = e[i].axis == 0 && e[i].type != EV_END; /* one per triangle */
        if (f == KD_LEFT)
            nl_ev++, nl += first;
        else if (f == KD_RIGHT)
            nr_ev++, nr += first;
        else
            nboth += first;
    }
    l->cell = in->cell;
    l->cell.bmax[s->axis] = s->pos;
    r->cell = in->cell;
    r->cell.bmin[s->axis] = s->pos;
    l->depth = r->depth = in->depth + 1;
    /* The straddling triangles, clipped to each child: at most 6 events each. */
    kd_event *bl = malloc(sizeof(kd_event) * (6 * (size_t)nboth + 1));
    kd_event *br = malloc(sizeof(kd_event) * (6 * (size_t)nboth + 1));
    kd_event *le = NULL, *re = NULL;
    int ok = bl && br;
    uint32_t nbl = 0, nbr = 0;
    for (uint32_t i = 0; ok && i < size; i++) {
        const kd_event *v = &e[i];
        if (side[v->tri] != KD_BOTH || v->axis != 0 || v->type == EV_END) continue;
        rt_aabb box;
        if (kd_clip_box(&c->tris[v->tri], &l->cell, &box)) {
            nbl = box_events(&box, v->tri, bl, nbl);
            nl++;
        }
        if (kd_clip_box(&c->tris[v->tri], &r->cell, &box)) {
            nbr = box_events(&box, v->tri, br, nbr);
            nr++;
        }
    }
    if (ok) {
        /* The children's lists, with room in front for the merge; they
         * serve as the sort's scratch first. */
        le = malloc(sizeof(kd_event) * ((size_t)nl_ev + nbl + 1));
        re = malloc(sizeof(kd_event) * ((size_t)nr_ev + nbr + 1));
        ok = le && re;
    }
    if (ok) {
        ev_sort(bl, nbl, le);
        ev_sort(br, nbr, re);
    }
    if (ok) {
        /* The one-sided events, in order, straight into the front of the
         * children's lists; then merged with the clipped ones. */
        kd_event *lo = le + nbl, *ro = re + nbr;
        uint32_t a = 0, b = 0;
        for (uint32_t i = 0; i < size; i++) {
            uint8_t f = side[e[i].tri];
            if (f == KD_LEFT)
                lo[a++] = e[i];
            else if (f == KD_RIGHT)
                ro[b++] = e[i];
        }
        /* merge() reads lo ahead of where it writes (the output index never
         * passes the input's), so it may run in place. */
        merge(lo, a, bl, nbl, le);
        merge(ro, b, br, nbr, re);
        l->data = le;
        l->size = nl_ev + nbl;
        l->tris = nl;
        r->data = re;
        r->size = nr_ev + nbr;
        r->tris = nr;
    }
    for (uint32_t i = 0; i < size; i++) side[e[i].tri] = 0;
    free(bl);
    free(br);
    free(in->data);
    in->data = NULL;
    if (!ok) {
        free(le);
        free(re);
        l->data = r->data = NULL;
    }
    return ok;
}

static int u32_cmp(const void *pa, const void *pb) {
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return a < b ? -1 : a > b;
}

static uint32_t sweep_leaf(const kd_ctx *c, const kd_node_in *in, kd_scratch *w) {
    (void)c;
    const kd_event *e = in->data;
    if (!kd_scratch_list(w, in->tris)) return UINT32_MAX;
    uint32_t n = 0;
    for (uint32_t i = 0; i < in->size; i++)
        if (e[i].axis == 0 && e[i].type != EV_END) w->list[n++] = e[i].tri;
    if (n) qsort(w->list, n, sizeof(uint32_t), u32_cmp);
    return n;
}

static int sweep_root(const kd_ctx *c, const uint32_t *ids, const rt_aabb *boxes, uint32_t n,
                      const rt_aabb *cell, kd_node_in *out) {
    (void)c;
    memset(out, 0, sizeof *out);
    kd_event *e = malloc(sizeof(kd_event) * (6 * (size_t)n + 1));
    kd_event *tmp = malloc(sizeof(kd_event) * (6 * (size_t)n + 1));
    if (!e || !tmp) {
        free(e);
        free(tmp);
        return 0;
    }
    uint32_t size = 0;
    for (uint32_t i = 0; i < n; i++) size = box_events(&boxes[i], ids[i], e, size);
    ev_sort(e, size, tmp);
    free(tmp);
    out->cell = *cell;
    out->data = e;
    out->size = size;
    out->tris = n;
    return 1;
}

const kd_finder kd_finder_sweep = {sweep_find, sweep_split, sweep_leaf, sweep_root};
