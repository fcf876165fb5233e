/* kd_clip.c - perfect splits: a triangle's box within a cell is the box of
 * the triangle clipped to the cell (Sutherland-Hodgman against the six
 * planes), not the cell's part of the triangle's box. It is computed in
 * double and rounded outwards, so that the float box always holds the
 * triangle's part of the cell: a triangle is then never left out of a cell a
 * ray can hit it in. */
#include "accel/kd_internal.h"

#include <math.h>

/* A polygon vertex; bit k of exact says coordinate k is a float value
 * (a vertex's own or a clipping plane's), which needs no rounding. */
typedef struct cvert {
    double p[3];
    unsigned exact;
} cvert;

#define MAX_VERTS 12 /* a triangle clipped by six planes has at most nine */

static float round_down(double d, int exact) {
    float f = (float)d;
    if (exact) return f;
    d -= fabs(d) * 0x1p-40; /* margin for the double's own rounding */
    f = (float)d;
    if ((double)f > d) f = nextafterf(f, -INFINITY);
    return f;
}

static float round_up(double d, int exact) {
    float f = (float)d;
    if (exact) return f;
    d += fabs(d) * 0x1p-40;
    f = (float)d;
    if ((double)f < d) f = nextafterf(f, INFINITY);
    return f;
}

/* Whether every vertex is on the kept side of the plane (then clip_plane
 * would return the polygon unchanged). */
static int all_kept(const cvert *in, int n, int k, double plane, int keep_above) {
    for (int i = 0; i < n; i++)
        if (!(keep_above ? in[i].p[k] >= plane : in[i].p[k] <= plane)) return 0;
    return 1;
}

/* Keeps the part of the polygon with x[k] >= plane (keep_above) or <= plane;
 * points on the plane are kept. Returns the new vertex count. */
static int clip_plane(const cvert *in, int n, cvert *out, int k, double plane, int keep_above) {
    int m = 0;
    for (int i = 0; i < n; i++) {
        const cvert *a = &in[i], *b = &in[i + 1 == n ? 0 : i + 1];
        int ain = keep_above ? a->p[k] >= plane : a->p[k] <= plane;
        int bin = keep_above ? b->p[k] >= plane : b->p[k] <= plane;
        if (ain) out[m++] = *a;
        if (ain != bin && m < MAX_VERTS) {
            double t = (plane - a->p[k]) / (b->p[k] - a->p[k]);
            cvert x;
            x.exact = 0;
            for (int j = 0; j < 3; j++) {
                if (a->p[j] == b->p[j]) {
                    x.p[j] = a->p[j];
                    x.exact |= a->exact & b->exact & (1u << j);
                } else {
                    x.p[j] = a->p[j] + (b->p[j] - a->p[j]) * t;
                }
            }
            x.p[k] = plane;
            x.exact |= 1u << k;
            out[m++] = x;
        }
    }
    return m;
}

int kd_clip_box(const kd_tri *t, const rt_aabb *cell, rt_aabb *out) {
    cvert buf[2][MAX_VERTS];
    cvert *a = buf[0];
    int n = 3;
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++) a[i].p[k] = (double)t->v[i][k];
        a[i].exact = 7u;
    }
    /* Most planes of a cell miss a straddling triangle (often all but the
     * split plane): those are skipped, which clip_plane would have done
     * too, copying the polygon unchanged. */
    cvert *cur = buf[0], *other = buf[1];
    for (int k = 0; k < 3 && n; k++)
        for (int side = 0; side < 2 && n; side++) {
            double plane = (double)(side ? cell->bmax[k] : cell->bmin[k]);
            if (all_kept(cur, n, k, plane, !side)) continue;
            n = clip_plane(cur, n, other, k, plane, !side);
            cvert *swap = cur;
            cur = other;
            other = swap;
        }
    if (!n) return 0;
    a = cur;
    for (int k = 0; k < 3; k++) {
        double lo = a[0].p[k], hi = a[0].p[k];
        int lo_exact = (a[0].exact >> k) & 1, hi_exact = lo_exact;
        for (int i = 1; i < n; i++) {
            double x = a[i].p[k];
            int e = (a[i].exact >> k) & 1;
            if (x < lo || (x == lo && !e)) {
                lo = x;
                lo_exact = e;
            }
            if (x > hi || (x == hi && !e)) {
                hi = x;
                hi_exact = e;
            }
        }
        float flo = round_down(lo, lo_exact), fhi = round_up(hi, hi_exact);
        out->bmin[k] = flo > cell->bmin[k] ? flo : cell->bmin[k];
        out->bmax[k] = fhi < cell->bmax[k] ? fhi : cell->bmax[k];
        if (out->bmin[k] > out->bmax[k]) return 0;
    }
    return 1;
}
