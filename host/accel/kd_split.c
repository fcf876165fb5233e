/* SPDX-License-Identifier: Apache-2.0 */
/* kd_split.c - the SAH of a kd split (Wald and Havran 2006, section 4): the
 * cost model, the empty-space bonus and the place of planar triangles. */
#include "accel/kd_internal.h"

#include <math.h>

int rt_kd_side(float lo, float hi, float pos, int planar_left) {
    if (lo == hi) {
        if (lo < pos) return KD_LEFT;
        if (lo > pos) return KD_RIGHT;
        return planar_left ? KD_LEFT : KD_RIGHT;
    }
    if (hi <= pos) return KD_LEFT;
    if (lo >= pos) return KD_RIGHT;
    return KD_BOTH;
}

double rt_kd_area(const rt_aabb *b) {
    double dx = (double)b->bmax[0] - (double)b->bmin[0];
    double dy = (double)b->bmax[1] - (double)b->bmin[1];
    double dz = (double)b->bmax[2] - (double)b->bmin[2];
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

int rt_kd_cell_init(kd_cell *c, const rt_aabb *box) {
    c->box = box;
    for (int k = 0; k < 3; k++) c->ext[k] = (double)box->bmax[k] - (double)box->bmin[k];
    for (int k = 0; k < 3; k++) {
        double a = c->ext[(k + 1) % 3], b = c->ext[(k + 2) % 3];
        c->other_sum[k] = a + b;
        c->other_prod[k] = a * b;
    }
    double area = rt_kd_area(box);
    c->inv_area = area > 0.0 ? 1.0 / area : 0.0;
    return area > 0.0;
}
