/* SPDX-License-Identifier: Apache-2.0 */
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
 * same ray transform, triangle test and acceptance (rt_hit_accepted, with
 * the instance's box under an object BVH) as the traversal. */
static inline void oracle_brute_force(const rt_scene_view *s, const rt_ray *r, int any_hit,
                                      rt_hit_d *best) {
    rt_counters c = {0, 0, 0};
    rt_hit_init(best, r);
    rt_ray_pre world;
    rt_ray_prepare(r, &world);
    for (rt_u32 i = 0; i < s->hdr->instance_count; i++) {
        const rt_instance *in = &s->instances[i];
        float inst_lo = -INFINITY;
        if (!(s->hdr->flags & RT_SCENE_SINGLE) && !rt_inst_enter(in, r, &world, &inst_lo)) continue;
        rt_ray o = *r;
        rt_ray_pre p;
        if (!(in->flags & RT_INST_IDENTITY)) rt_ray_to_object(in, r, &o);
        rt_ray_prepare(&o, &p);
        p.inst_lo = inst_lo;
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
                              rt_ray *r) {
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

/* A nasty ray: through a vertex of a random triangle (from a random point,
 * or starting on the vertex), its direction scaled by 2^-s for s in
 * {0, 40, 70, 100, 130} (tiny and denormal directions: t's rounding then
 * dwarfs the boxes' slabs), sometimes with a range reaching below zero. */
static inline void oracle_vertex_ray(const rt_scene_view *s, const float lo[3], const float hi[3],
                                     rt_ray *r) {
    const rt_u32 n = s->hdr->instance_count;
    const rt_instance *in = &s->instances[(rt_u32)(oracle_rnd() * (float)n) % (n ? n : 1)];
    float v[3] = {0, 0, 0};
    if (n && in->tri_count) {
        const rt_tri *t =
            &s->tris[in->tri_first + (rt_u32)(oracle_rnd() * (float)in->tri_count) % in->tri_count];
        const int which = (int)(oracle_rnd() * 3.0f) % 3;
        const float *p = which == 0 ? t->v0 : which == 1 ? t->v1 : t->v2;
        const float *m = in->object_to_world;
        for (int k = 0; k < 3; k++)
            v[k] = ((m[4 * k] * p[0] + m[4 * k + 1] * p[1]) + m[4 * k + 2] * p[2]) + m[4 * k + 3];
    }
    const int on_vertex = oracle_rnd() < 0.3f;
    for (int k = 0; k < 3; k++) {
        const float ext = hi[k] - lo[k];
        const float o = lo[k] - 0.25f * ext + 1.5f * ext * oracle_rnd();
        r->org[k] = on_vertex ? v[k] : o;
        r->dir[k] = on_vertex ? (lo[k] + ext * oracle_rnd()) - v[k] : v[k] - o;
    }
    static const float scale[5] = {1.0f, 0x1p-40f, 0x1p-70f, 0x1p-100f, 0x1p-126f};
    const int si = (int)(oracle_rnd() * 5.0f) % 5;
    for (int k = 0; k < 3; k++) r->dir[k] *= scale[si] * (si == 4 ? 0x1p-4f : 1.0f);
    r->tmin = oracle_rnd() < 0.3f ? -oracle_rnd() : 0.0f;
    r->tmax = oracle_rnd() < 0.2f ? 3.0f * oracle_rnd() : INFINITY;
}

#endif
