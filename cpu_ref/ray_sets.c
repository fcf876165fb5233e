/* SPDX-License-Identifier: Apache-2.0 */
/* ray_sets.c - random and diffuse-bounce rays (ray_sets.h). */
#include "ray_sets.h"

#include <math.h>
#include <string.h>

#include "kernel_maths.h"

/* xorshift32, uniform in [0, 1). */
static float rnd(uint32_t *s) {
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return (float)(*s >> 8) / 16777216.0f;
}

static uint32_t seed_of(uint32_t seed) {
    return seed ? seed : 0x9e3779b9u;
}

/* The scene's bounds: the object BVH's root box, or the one mesh's. */
static void bounds(const rt_flat *flat, float lo[3], float hi[3]) {
    for (int k = 0; k < 3; k++) lo[k] = 0.0f, hi[k] = 1.0f;
    if (!flat->hdr.instance_count || !flat->node_count) return;
    const uint32_t root =
        (flat->hdr.flags & RT_SCENE_SINGLE) ? flat->instances[0].root : flat->hdr.top_root;
    const rt_node *n = &flat->nodes[root];
    if (!(n->bmin[0] <= n->bmax[0] && n->bmin[1] <= n->bmax[1] && n->bmin[2] <= n->bmax[2])) return;
    for (int k = 0; k < 3; k++) lo[k] = n->bmin[k], hi[k] = n->bmax[k];
}

static void sphere_dir(uint32_t *s, float d[3]) {
    const float z = 1.0f - 2.0f * rnd(s), phi = 6.28318531f * rnd(s);
    const float r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    d[0] = r * cosf(phi), d[1] = r * sinf(phi), d[2] = z;
}

static void random_ray(uint32_t *s, const float lo[3], const float hi[3], rt_ray *r) {
    for (int k = 0; k < 3; k++) r->org[k] = lo[k] + (hi[k] - lo[k]) * rnd(s);
    sphere_dir(s, r->dir);
    r->tmin = 0.0f;
    r->tmax = INFINITY;
}

void rt_rays_random(const rt_flat *flat, uint32_t seed, size_t n, rt_ray *out) {
    uint32_t s = seed_of(seed);
    float lo[3], hi[3];
    bounds(flat, lo, hi);
    for (size_t i = 0; i < n; i++) random_ray(&s, lo, hi, &out[i]);
}

void rt_rays_diffuse(const rt_flat *flat, uint32_t seed, size_t n, rt_ray *out) {
    uint32_t s = seed_of(seed);
    float lo[3], hi[3];
    bounds(flat, lo, hi);
    rt_scene_view v = rt_flat_view(flat);
    rt_counters c = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        rt_ray cam;
        rt_hit_d h;
        h.prim = RT_NO_HIT;
        for (int tries = 0; tries < 64 && h.prim == RT_NO_HIT; tries++) {
            const int px = (int)(rnd(&s) * (float)flat->hdr.width);
            const int py = (int)(rnd(&s) * (float)flat->hdr.height);
            rt_camera_ray(&flat->hdr, px, py, &cam);
            rt_trace(&v, &cam, 0, &h, &c);
        }
        if (h.prim == RT_NO_HIT) {
            random_ray(&s, lo, hi, &out[i]);
            continue;
        }
        rt_surface sf;
        rt_surface_at(&v, &cam, &h, &sf);
        /* A basis about the normal, then a cosine-distributed direction. */
        const float *nz = sf.ng;
        float a[3] = {1.0f, 0.0f, 0.0f}, tx[3], ty[3];
        if (fabsf(nz[0]) > 0.9f) a[0] = 0.0f, a[1] = 1.0f;
        rt_cross3(nz, a, tx);
        rt_normalize3(tx);
        rt_cross3(nz, tx, ty);
        const float u1 = rnd(&s), phi = 6.28318531f * rnd(&s);
        const float r = sqrtf(u1), z = sqrtf(fmaxf(0.0f, 1.0f - u1));
        for (int k = 0; k < 3; k++)
            out[i].dir[k] = r * cosf(phi) * tx[k] + r * sinf(phi) * ty[k] + z * nz[k];
        rt_offset_point(sf.p, sf.ng, 1.0f, out[i].org);
        out[i].tmin = 0.0f;
        out[i].tmax = INFINITY;
    }
}

int rt_api_hits_same(const rt_hit *a, const rt_hit *b, int any) {
    if (a->hit != b->hit) return 0;
    if (any || !a->hit) return 1;
    return memcmp(&a->t, &b->t, sizeof a->t) == 0 && memcmp(&a->u, &b->u, sizeof a->u) == 0 &&
           memcmp(&a->v, &b->v, sizeof a->v) == 0 && a->prim == b->prim && a->inst == b->inst;
}
