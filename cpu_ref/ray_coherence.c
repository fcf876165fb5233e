/* SPDX-License-Identifier: Apache-2.0 */
/* ray_coherence.c - the cheap coherence measure of a group of rays
 * (ray_coherence.h). */
#include "ray_coherence.h"

#include <math.h>

int rt_rays_coherent(const rt_ray *rays, size_t n, float org_span) {
    if (n == 0) return 1;
    float dmin[3], dmax[3], omin[3], omax[3];
    int neg[3];
    for (int k = 0; k < 3; k++) {
        dmin[k] = INFINITY, dmax[k] = -INFINITY;
        omin[k] = omax[k] = rays[0].org[k];
        neg[k] = signbit(rays[0].dir[k]) != 0;
    }
    for (size_t i = 0; i < n; i++) {
        const rt_ray *r = &rays[i];
        const float len =
            sqrtf((r->dir[0] * r->dir[0] + r->dir[1] * r->dir[1]) + r->dir[2] * r->dir[2]);
        if (!(len > 0.0f) || !isfinite(len)) return 0;
        for (int k = 0; k < 3; k++) {
            if ((signbit(r->dir[k]) != 0) != neg[k]) return 0;
            const float d = r->dir[k] / len, o = r->org[k];
            dmin[k] = d < dmin[k] ? d : dmin[k];
            dmax[k] = d > dmax[k] ? d : dmax[k];
            omin[k] = o < omin[k] ? o : omin[k];
            omax[k] = o > omax[k] ? o : omax[k];
        }
    }
    for (int k = 0; k < 3; k++)
        if (!(dmax[k] - dmin[k] <= RT_COHERENT_DIR_SPREAD) || !(omax[k] - omin[k] <= org_span))
            return 0;
    return 1;
}
