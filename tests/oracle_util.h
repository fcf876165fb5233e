/* oracle_util.h - brute force over every triangle and random rays, for the
 * tests that hold the BVH traversal (scalar and packet) to it. */
#ifndef RT_TEST_ORACLE_UTIL_H
#define RT_TEST_ORACLE_UTIL_H

#include <math.h>
#include <string.h>

#include "rt_shared.h"

static uint32_t oracle_rng = 12345;
static inline float oracle_rnd(void) { /* xorshift, uniform in [0, 1) */
    oracle_rng ^= oracle_rng << 13;
    oracle_rng ^= oracle_rng >> 17;
    oracle_rng ^= oracle_rng << 5;
    return (float)(oracle_rng >> 8) / 16777216.0f;
}

/* The closest (or any) hit over every triangle of every instance, with the
 * same ray transform and triangle test as the traversal. */
static inline void oracle_brute_force(const rt_scene_view *s, const rt_ray_d *r, int any_hit,
                                      rt_hit_d *best) {
    rt_counters c = {0, 0, 0};
    rt_hit_init(best, r);
    for (rt_u32 i = 0; i < s->hdr->instance_count; i++) {
        const rt_instance *in = &s->instances[i];
        rt_ray_d o = *r;
        rt_ray_pre p;
        if (!(in->flags & RT_INST_IDENTITY)) rt_ray_to_object(in, r, &o);
        rt_ray_prepare(&o, &p);
        if (rt_leaf_test(s, in->tri_first, in->tri_count, i, &o, &p, any_hit, best, &c) && any_hit)
            return;
    }
}

static inline int oracle_same_hit(const rt_hit_d *a, const rt_hit_d *b) {
    return memcmp(&a->t, &b->t, sizeof(float)) == 0 && a->prim == b->prim && a->inst == b->inst &&
           (a->prim == RT_NO_HIT ||
            (memcmp(&a->u, &b->u, sizeof(float)) == 0 && memcmp(&a->v, &b->v, sizeof(float)) == 0));
}

/* Even i: a camera ray through a random pixel; odd i: from a random point of
 * the (grown) bounds towards another, sometimes with a short t range. */
static inline void oracle_ray(const rt_scene_header *h, const float lo[3], const float hi[3], int i,
                              rt_ray_d *r) {
    if (i % 2 == 0) {
        int px = (int)(oracle_rnd() * (float)h->width), py = (int)(oracle_rnd() * (float)h->height);
        rt_camera_ray(h, px, py, r);
        return;
    }
    for (int k = 0; k < 3; k++) {
        float ext = hi[k] - lo[k];
        r->org[k] = lo[k] - 0.25f * ext + 1.5f * ext * oracle_rnd();
        r->dir[k] = (lo[k] + ext * oracle_rnd()) - r->org[k];
    }
    r->tmin = oracle_rnd() < 0.2f ? 0.5f * oracle_rnd() : 0.0f;
    r->tmax = oracle_rnd() < 0.2f ? 0.3f + oracle_rnd() : INFINITY;
}

#endif
