/* SPDX-License-Identifier: Apache-2.0 */
/* kd_clip.c - perfect splits: a triangle's box within a cell is the box of
 * the triangle clipped to the cell (Sutherland-Hodgman against the six
 * planes), not the cell's part of the triangle's box. It is computed in
 * double and rounded outwards, so that the float box always holds the
 * triangle's part of the cell: a triangle is then never left out of a cell a
 * ray can hit it in.
 *
 * The planes are taken in one fixed order (x min, x max, y min, y max, z min,
 * z max) and a plane that keeps every vertex is skipped (clipping by it would
 * return the polygon unchanged), so a box depends only on the triangle and
 * the cell. rt_kd_clip_pair uses that: the two children of a split share the
 * planes of the axes before the split axis, which it clips by once. */
#include "accel/kd_internal.h"

#include <math.h>
#include <string.h>

#define MAX_VERTS 12 /* a triangle clipped by six planes has at most nine */

/* A polygon; bit k of exact[i] says coordinate k of vertex i is a float
 * value (a vertex's own or a clipping plane's), which needs no rounding. */
typedef struct cpoly {
    int n;
    double p[MAX_VERTS][3];
    unsigned exact[MAX_VERTS];
} cpoly;

/* nextafterf(f, INFINITY) and nextafterf(f, -INFINITY) for a float that is
 * not NaN, by its bits. */
static inline float next_up(float f) {
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    if ((u & 0x7fffffffu) == 0)
        u = 1u;
    else if (u & 0x80000000u)
        u--;
    else
        u++;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* The next float down is the next up of -f, negated (a sign flip, exact). */
static inline float next_down(float f) {
    return -next_up(-f);
}

static inline float round_down(double d, int exact) {
    float f = (float)d;
    if (exact) return f;
    d -= fabs(d) * 0x1p-40; /* margin for the double's own rounding */
    f = (float)d;
    if ((double)f > d) f = next_down(f);
    return f;
}

static inline float round_up(double d, int exact) {
    float f = (float)d;
    if (exact) return f;
    d += fabs(d) * 0x1p-40;
    f = (float)d;
    if ((double)f < d) f = next_up(f);
    return f;
}

static inline int kept(double x, double plane, int above) {
    return above ? x >= plane : x <= plane;
}

/* Keeps the part of the polygon with x[k] >= plane (above) or <= plane;
 * points on the plane are kept. Returns the polygon to continue with: in
 * itself when every vertex is kept, else out. */
static inline cpoly *clip_plane(cpoly *in, cpoly *out, int k, double plane, int above) {
    int n = in->n, all = 1;
    for (int i = 0; i < n; i++) all &= kept(in->p[i][k], plane, above);
    if (all) return in;
    int m = 0;
    for (int i = 0; i < n; i++) {
        int j = i + 1 == n ? 0 : i + 1;
        const double *a = in->p[i], *b = in->p[j];
        int ain = kept(a[k], plane, above), bin = kept(b[k], plane, above);
        if (ain) {
            memcpy(out->p[m], a, sizeof(double) * 3);
            out->exact[m++] = in->exact[i];
        }
        if (ain != bin && m < MAX_VERTS) {
            double t = (plane - a[k]) / (b[k] - a[k]);
            unsigned ex = 0;
            for (int c = 0; c < 3; c++) {
                if (a[c] == b[c]) {
                    out->p[m][c] = a[c];
                    ex |= in->exact[i] & in->exact[j] & (1u << c);
                } else {
                    out->p[m][c] = a[c] + (b[c] - a[c]) * t;
                }
            }
            out->p[m][k] = plane;
            out->exact[m++] = ex | 1u << k;
        }
    }
    out->n = m;
    return out;
}

/* Clips *cur by the two planes of axis k (min, then max); buf is the other
 * buffer. Returns the polygon to continue with (cur or buf). */
static inline cpoly *clip_axis(cpoly *cur, cpoly *buf, int k, float lo, float hi) {
    cpoly *r = clip_plane(cur, buf, k, (double)lo, 1);
    if (!r->n) return r;
    cpoly *o = r == cur ? buf : cur;
    return clip_plane(r, o, k, (double)hi, 0);
}

/* The zero at a bound of axis k (either: the rule is the same): of the
 * vertices at zero, the last inexact one after the first, else the first. */
static double zero_bound(const cpoly *a, int k) {
    double z = 0.0;
    int found = 0;
    for (int i = 0; i < a->n; i++) {
        double x = a->p[i][k];
        if (x != 0.0) continue;
        if (!found || !((a->exact[i] >> k) & 1u)) z = x;
        found = 1;
    }
    return z;
}

/* The rounded box of a clipped polygon within cell; 0 when empty. A bound
 * is exact when every vertex reaching it is exact there (a vertex's own
 * coordinate or a plane's), else it is rounded outwards. Without branches
 * (which vertex bounds a polygon is not predictable): the first vertex
 * reaching a bound gives its value (of -0 and +0, the first). */
static int poly_box(const cpoly *a, const rt_aabb *cell, rt_aabb *out) {
    int n = a->n;
    if (!n) return 0;
    for (int k = 0; k < 3; k++) {
        double lo = a->p[0][k], hi = a->p[0][k];
        for (int i = 1; i < n; i++) {
            double x = a->p[i][k];
            lo = x < lo ? x : lo;
            hi = x > hi ? x : hi;
        }
        unsigned lo_exact = 1, hi_exact = 1;
        for (int i = 0; i < n; i++) {
            double x = a->p[i][k];
            unsigned e = (a->exact[i] >> k) & 1u;
            lo_exact &= (x != lo) | e;
            hi_exact &= (x != hi) | e;
        }
        /* A zero bound: its sign as the vertex-by-vertex rule gives it (the
         * last inexact vertex at the bound, else the first), which the
         * rounding keeps. */
        if (lo == 0.0) lo = zero_bound(a, k);
        if (hi == 0.0) hi = zero_bound(a, k);
        float flo = round_down(lo, (int)lo_exact), fhi = round_up(hi, (int)hi_exact);
        out->bmin[k] = flo > cell->bmin[k] ? flo : cell->bmin[k];
        out->bmax[k] = fhi < cell->bmax[k] ? fhi : cell->bmax[k];
        if (out->bmin[k] > out->bmax[k]) return 0;
    }
    return 1;
}

static void tri_poly(const kd_tri *t, cpoly *a) {
    a->n = 3;
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++) a->p[i][k] = (double)t->v[i][k];
        a->exact[i] = 7u;
    }
}

/* Clips cur by the planes of the axes from k on; returns the result. */
static cpoly *clip_from(cpoly *cur, cpoly *buf, const rt_aabb *cell, int k) {
    for (; k < 3 && cur->n; k++) {
        cpoly *r = clip_axis(cur, buf, k, cell->bmin[k], cell->bmax[k]);
        if (r != cur) {
            buf = cur;
            cur = r;
        }
    }
    return cur;
}

int rt_kd_clip_box(const kd_tri *t, const rt_aabb *cell, rt_aabb *out) {
    cpoly a, b;
    tri_poly(t, &a);
    return poly_box(clip_from(&a, &b, cell, 0), cell, out);
}

int rt_kd_clip_pair(const kd_tri *t, const rt_aabb *cell, int axis, float pos, rt_aabb *left,
                    rt_aabb *right) {
    cpoly a, b, c, d;
    tri_poly(t, &a);
    /* The planes before the split axis: the same for both children. */
    cpoly *shared = &a, *buf = &b;
    for (int k = 0; k < axis && shared->n; k++) {
        cpoly *r = clip_axis(shared, buf, k, cell->bmin[k], cell->bmax[k]);
        if (r != shared) {
            buf = shared;
            shared = r;
        }
    }
    rt_aabb lc = *cell, rc = *cell;
    lc.bmax[axis] = pos;
    rc.bmin[axis] = pos;
    int got = 0;
    if (shared->n) {
        /* The right child from a copy; the left one in place. */
        c.n = shared->n;
        memcpy(c.p, shared->p, sizeof(c.p[0]) * (size_t)c.n);
        memcpy(c.exact, shared->exact, sizeof(c.exact[0]) * (size_t)c.n);
        if (poly_box(clip_from(&c, &d, &rc, axis), &rc, right)) got |= KD_RIGHT;
        if (poly_box(clip_from(shared, buf, &lc, axis), &lc, left)) got |= KD_LEFT;
    }
    return got;
}
