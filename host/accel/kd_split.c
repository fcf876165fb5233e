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

int kd_cell_init(kd_cell *c, const rt_aabb *box) {
    c->box = box;
    for (int k = 0; k < 3; k++) c->ext[k] = (double)box->bmax[k] - (double)box->bmin[k];
    double area = kd_area(box);
    c->inv_area = area > 0.0 ? 1.0 / area : 0.0;
    return area > 0.0;
}

void kd_offer(const kd_ctx *c, const kd_cell *v, int k, float pos, uint32_t nl, uint32_t nr,
              uint32_t np, uint32_t n, kd_split *best) {
    /* The children's areas: the cell's with the extent on k cut at pos. */
    double a = v->ext[(k + 1) % 3], b = v->ext[(k + 2) % 3];
    double l = (double)pos - (double)v->box->bmin[k], r = (double)v->box->bmax[k] - (double)pos;
    double pl = 2.0 * (l * (a + b) + a * b) * v->inv_area;
    double pr = 2.0 * (r * (a + b) + a * b) * v->inv_area;
    /* A plane on a face of the cell leaves one child equal to the cell. */
    int left_is_cell = pos == v->box->bmax[k], right_is_cell = pos == v->box->bmin[k];
    double kt = (double)c->opt.cost_traverse, ki = (double)c->opt.cost_intersect;
    for (int side = 0; side < 2; side++) {
        int planar_left = side == 0;
        uint32_t na = nl + (planar_left ? np : 0u), nb = nr + (planar_left ? 0u : np);
        if ((left_is_cell && na == n) || (right_is_cell && nb == n)) continue;
        double bonus = (na == 0 || nb == 0) ? (double)c->opt.empty_bonus : 1.0;
        double cost = bonus * (kt + ki * (pl * (double)na + pr * (double)nb));
        if (cost < best->cost) {
            best->cost = cost;
            best->axis = k;
            best->pos = pos;
            best->planar_left = planar_left;
        }
        if (!np) break; /* the same price both ways */
    }
}
