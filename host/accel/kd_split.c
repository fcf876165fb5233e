/* kd_split.c - the SAH of a kd split (Wald and Havran 2006, section 4): the
 * cost model, the empty-space bonus and the place of planar triangles. */
#include "accel/kd_internal.h"

#include <math.h>

int kd_side(float lo, float hi, float pos, int planar_left) {
    if (lo == hi) {
        if (lo < pos) return KD_LEFT;
        if (lo > pos) return KD_RIGHT;
        return planar_left ? KD_LEFT : KD_RIGHT;
    }
    if (hi <= pos) return KD_LEFT;
    if (lo >= pos) return KD_RIGHT;
    return KD_BOTH;
}

double kd_area(const rt_aabb *b) {
    double dx = (double)b->bmax[0] - (double)b->bmin[0];
    double dy = (double)b->bmax[1] - (double)b->bmin[1];
    double dz = (double)b->bmax[2] - (double)b->bmin[2];
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

void kd_offer(const kd_ctx *c, const rt_aabb *v, double av, int k, float pos, uint32_t nl,
              uint32_t nr, uint32_t np, uint32_t n, kd_split *best) {
    rt_aabb vl = *v, vr = *v;
    vl.bmax[k] = pos;
    vr.bmin[k] = pos;
    double pl = kd_area(&vl) / av, pr = kd_area(&vr) / av;
    /* A plane on a face of the cell leaves one child equal to the cell. */
    int left_is_cell = pos == v->bmax[k], right_is_cell = pos == v->bmin[k];
    for (int side = 0; side < 2; side++) {
        int planar_left = side == 0;
        uint32_t a = nl + (planar_left ? np : 0u), b = nr + (planar_left ? 0u : np);
        if ((left_is_cell && a == n) || (right_is_cell && b == n)) continue;
        double bonus = (a == 0 || b == 0) ? (double)c->opt.empty_bonus : 1.0;
        double cost = bonus * ((double)c->opt.cost_traverse +
                               (double)c->opt.cost_intersect * (pl * (double)a + pr * (double)b));
        if (cost < best->cost) {
            best->cost = cost;
            best->axis = k;
            best->pos = pos;
            best->planar_left = planar_left;
        }
    }
}
