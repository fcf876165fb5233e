/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_kd_clip.c - perfect-split clipping (host/accel/kd_clip.c) gives
 * the boxes of the plain rule, bit for bit: rt_kd_clip_box and rt_kd_clip_pair
 * (both children of a split at once, sharing the planes before the split
 * axis, the box taken without branches) against a reference written the
 * plain way (Sutherland-Hodgman against the six planes in order, a plane
 * that keeps every vertex skipped, the box vertex by vertex, rounding
 * outwards with nextafterf). The kd-trees depend on these boxes, so they
 * must not change. Inputs: random triangles and cells from a grid of few
 * values (vertices on planes, zeros of both signs, flat cells and
 * triangles) and from wide random ranges. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "accel/kd_internal.h"
#include "check.h"

/* ---- the reference ----------------------------------------------------------- */

typedef struct ref_vert {
    double p[3];
    unsigned exact; /* bit k: coordinate k is a float value */
} ref_vert;

static float ref_down(double d, int exact) {
    float f = (float)d;
    if (exact) return f;
    d -= fabs(d) * 0x1p-40;
    f = (float)d;
    if ((double)f > d) f = nextafterf(f, -INFINITY);
    return f;
}

static float ref_up(double d, int exact) {
    float f = (float)d;
    if (exact) return f;
    d += fabs(d) * 0x1p-40;
    f = (float)d;
    if ((double)f < d) f = nextafterf(f, INFINITY);
    return f;
}

static int ref_kept(double x, double plane, int above) {
    return above ? x >= plane : x <= plane;
}

static int ref_plane(const ref_vert *in, int n, ref_vert *out, int k, double plane, int above) {
    int m = 0;
    for (int i = 0; i < n; i++) {
        const ref_vert *a = &in[i], *b = &in[i + 1 == n ? 0 : i + 1];
        int ain = ref_kept(a->p[k], plane, above), bin = ref_kept(b->p[k], plane, above);
        if (ain) out[m++] = *a;
        if (ain != bin && m < 12) {
            double t = (plane - a->p[k]) / (b->p[k] - a->p[k]);
            ref_vert x;
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

static int ref_clip(const kd_tri *t, const rt_aabb *cell, rt_aabb *out) {
    ref_vert buf[2][12];
    ref_vert *cur = buf[0], *other = buf[1];
    int n = 3;
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++) cur[i].p[k] = (double)t->v[i][k];
        cur[i].exact = 7u;
    }
    for (int k = 0; k < 3 && n; k++)
        for (int side = 0; side < 2 && n; side++) {
            double plane = (double)(side ? cell->bmax[k] : cell->bmin[k]);
            int all = 1;
            for (int i = 0; i < n; i++) all &= ref_kept(cur[i].p[k], plane, !side);
            if (all) continue;
            n = ref_plane(cur, n, other, k, plane, !side);
            ref_vert *swap = cur;
            cur = other;
            other = swap;
        }
    if (!n) return 0;
    for (int k = 0; k < 3; k++) {
        double lo = cur[0].p[k], hi = cur[0].p[k];
        int lo_exact = (cur[0].exact >> k) & 1, hi_exact = lo_exact;
        for (int i = 1; i < n; i++) {
            double x = cur[i].p[k];
            int e = (cur[i].exact >> k) & 1;
            if (x < lo || (x == lo && !e)) {
                lo = x;
                lo_exact = e;
            }
            if (x > hi || (x == hi && !e)) {
                hi = x;
                hi_exact = e;
            }
        }
        float flo = ref_down(lo, lo_exact), fhi = ref_up(hi, hi_exact);
        out->bmin[k] = flo > cell->bmin[k] ? flo : cell->bmin[k];
        out->bmax[k] = fhi < cell->bmax[k] ? fhi : cell->bmax[k];
        if (out->bmin[k] > out->bmax[k]) return 0;
    }
    return 1;
}

/* ---- inputs ------------------------------------------------------------------ */

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static uint32_t next_u32(void) {
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng >> 11);
}

static float pick(void) {
    static const float grid[] = {-1.0f,  -0.0f,   0.0f, 0.5f, 1.0f,  0.25f, -0.5f,
                                 1e-30f, -1e-30f, 3.0f, 0.1f, -0.1f, 2.0f};
    switch (next_u32() % 4) {
    case 0:
        return grid[next_u32() % (sizeof grid / sizeof grid[0])];
    case 1:
        return (float)((int)(next_u32() % 9) - 4) * 0.25f;
    case 2:
        return ((float)(next_u32() % 2000000) / 1e6f - 1.0f) * 2.0f;
    default:
        return ldexpf((float)(next_u32() % 1000) / 1000.0f - 0.5f, (int)(next_u32() % 20) - 10);
    }
}

static int same_box(const rt_aabb *a, const rt_aabb *b) {
    return memcmp(a, b, sizeof *a) == 0;
}

int main(void) {
    const int cases = 100000;
    int bad_single = 0, bad_pair = 0, reached = 0;
    for (int it = 0; it < cases; it++) {
        kd_tri t;
        rt_aabb cell;
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) t.v[i][k] = pick();
        for (int k = 0; k < 3; k++) {
            float a = pick(), b = pick();
            cell.bmin[k] = a < b ? a : b;
            cell.bmax[k] = a < b ? b : a;
        }
        int axis = (int)(next_u32() % 3);
        float lo = cell.bmin[axis], hi = cell.bmax[axis];
        float pos =
            next_u32() % 3 == 0 ? pick() : lo + (hi - lo) * (float)(next_u32() % 1000) / 1000.0f;
        pos = pos < lo ? lo : pos > hi ? hi : pos;
        rt_aabb lc = cell, rc = cell;
        lc.bmax[axis] = pos;
        rc.bmin[axis] = pos;
        rt_aabb want, got, want_l, want_r, got_l, got_r;
        int w = ref_clip(&t, &cell, &want), g = rt_kd_clip_box(&t, &cell, &got);
        if (w != g || (w && !same_box(&want, &got))) bad_single++;
        int wl = ref_clip(&t, &lc, &want_l), wr = ref_clip(&t, &rc, &want_r);
        int gp = rt_kd_clip_pair(&t, &cell, axis, pos, &got_l, &got_r);
        int gl = (gp & KD_LEFT) != 0, gr = (gp & KD_RIGHT) != 0;
        if (wl != gl || wr != gr || (wl && !same_box(&want_l, &got_l)) ||
            (wr && !same_box(&want_r, &got_r)))
            bad_pair++;
        reached += wl + wr;
    }
    CHECK_MSG(bad_single == 0, "rt_kd_clip_box differs from the reference in %d of %d cases",
              bad_single, cases);
    CHECK_MSG(bad_pair == 0, "rt_kd_clip_pair differs from the reference in %d of %d cases",
              bad_pair, cases);
    /* The inputs exercise clipping: most children are reached, not all. */
    CHECK_MSG(reached > cases / 4 && reached < 2 * cases, "%d children reached", reached);
    return TEST_END();
}
