/* SPDX-License-Identifier: Apache-2.0 */
/* rt_shade.h - Whitted shading over the shared traversal (Langr 2016,
 * sections 3.2.5 and 3.2.6): Phong (ambient + diffuse + specular), one shadow
 * ray per light, reflection and refraction through an explicit stack.
 *
 * Valid C99 and OpenCL C, under the rules of rt_math_profile.h. The packet path
 * traces primary rays in packets and then calls rt_shade_hit per lane, so its
 * images are bit-identical to the scalar renderer's.
 */
#ifndef RT_SHADE_H
#define RT_SHADE_H

#include "rt_trace.h"

/* Shadow rays run from the offset surface point (t = 0) to the light (t = 1),
 * excluding the light itself. */
#define RT_SHADOW_TMAX 0.999999940395355224609375f /* 1 - 2^-24 */

/* Shading stack: depth-first, each bounce pushes at most two rays, so
 * max_depth + 2 entries suffice; flatten caps max_depth at RT_MAX_DEPTH
 * (rt_layout.h). */
#define RT_SHADE_STACK 12

/* The surface at a hit, in world space. */
typedef struct rt_surface {
    float p[3];   /* the hit point: see rt_surface_at */
    float ng[3];  /* unit geometric normal, facing the ray's origin side */
    float ns[3];  /* unit shading normal (interpolated when the mesh has
                     normals), facing the ray's origin side */
    rt_i32 front; /* the ray arrived on the outside (the side the
                     unflipped shading normal points to) */
    rt_u32 material;
} rt_surface;

/* n_world = (M^-1)^T n for a normal in object space. */
RT_FN void rt_normal_to_world(RT_GLOBAL const rt_instance *in, const float *n, float *out) {
    RT_GLOBAL const float *m = in->world_to_object;
    for (int i = 0; i < 3; i++) out[i] = (m[i] * n[0] + m[4 + i] * n[1]) + m[8 + i] * n[2];
}

/* p_world = M p + m for a point in object space (M | m: object_to_world). */
RT_FN void rt_point_to_world(RT_GLOBAL const rt_instance *in, const float *p, float *out) {
    RT_GLOBAL const float *m = in->object_to_world;
    for (int i = 0; i < 3; i++)
        out[i] = ((m[4 * i] * p[0] + m[4 * i + 1] * p[1]) + m[4 * i + 2] * p[2]) + m[4 * i + 3];
}

/* The hit point is the barycentric combination of the triangle's vertices in
 * object space, then transformed (Waechter and Binder 2019), not o + t d:
 * that point's rounding error grows with the distance the ray travelled,
 * while rt_offset_point moves the point off the surface by an amount sized
 * for the point's own magnitude, so a ray from afar left points below the
 * surface and their shadow rays hit it (tests/test_surface_points.c). */
RT_FN void rt_surface_at(const rt_scene_view *s, const rt_ray *r, const rt_hit_d *h,
                         rt_surface *sf) {
    RT_GLOBAL const rt_tri *tri = &s->tris[h->entry];
    RT_GLOBAL const rt_instance *in = &s->instances[h->inst];
    int identity = (RT_INST_FLAGS(in) & RT_INST_IDENTITY) != 0;
    float e1[3], e2[3], n[3], ns[3], po[3];
    float b0 = (1.0f - h->u) - h->v;
    for (int k = 0; k < 3; k++) {
        e1[k] = tri->v1[k] - tri->v0[k];
        e2[k] = tri->v2[k] - tri->v0[k];
        po[k] = (b0 * tri->v0[k] + h->u * tri->v1[k]) + h->v * tri->v2[k];
    }
    if (identity) {
        for (int k = 0; k < 3; k++) sf->p[k] = po[k];
    } else {
        rt_point_to_world(in, po, sf->p);
    }
    rt_cross3(e1, e2, n);
    if (identity) {
        for (int k = 0; k < 3; k++) sf->ng[k] = n[k];
    } else {
        rt_normal_to_world(in, n, sf->ng);
    }
    rt_normalize3(sf->ng);
    for (int k = 0; k < 3; k++) sf->ns[k] = sf->ng[k];
    if (RT_INST_FLAGS(in) & RT_INST_NORMALS) {
        RT_GLOBAL const float *vn = s->tri_normals + 9 * h->entry;
        float w = (1.0f - h->u) - h->v;
        for (int k = 0; k < 3; k++) n[k] = (w * vn[k] + h->u * vn[3 + k]) + h->v * vn[6 + k];
        if (identity) {
            for (int k = 0; k < 3; k++) ns[k] = n[k];
        } else {
            rt_normal_to_world(in, n, ns);
        }
        rt_normalize3(ns);
        if (rt_dot3(ns, ns) > 0.0f)
            for (int k = 0; k < 3; k++) sf->ns[k] = ns[k];
    }
    sf->front = rt_dot3(sf->ns, r->dir) < 0.0f;
    if (rt_dot3(sf->ng, r->dir) > 0.0f)
        for (int k = 0; k < 3; k++) sf->ng[k] = -sf->ng[k];
    if (!sf->front)
        for (int k = 0; k < 3; k++) sf->ns[k] = -sf->ns[k];
    sf->material = in->material;
    if ((RT_SCENE_FLAGS(s) & RT_SCENE_TRI_MATS) && s->tri_mats[h->entry] != RT_NO_MATERIAL)
        sf->material = s->tri_mats[h->entry];
}

/* Phong, in three steps so that a packet tracer (and the Embree peer) can
 * trace the shadow rays of many pixels together and still add exactly
 * rt_phong's terms in rt_phong's order: the ambient term, then per light
 * rt_phong_light (is the light in front of the shading normal? its shadow
 * ray) and, when the shadow ray finds no occluder, rt_phong_add (diffuse and
 * specular, integer shininess by repeated multiplication). rt_shade_step
 * runs them with one scalar shadow ray at a time. */
RT_FN void rt_phong_ambient(const rt_scene_view *s, const rt_surface *sf, float *out) {
    RT_GLOBAL const rt_material_d *m = &s->materials[sf->material];
    /* The emission first: 0 + x is x, so a surface that gives off no light
     * keeps the bits it had before emission was modelled. */
    for (int k = 0; k < 3; k++)
        out[k] = m->emission[k] + (m->ambient * m->color[k]) * s->hdr->ambient[k];
}

/* Light li seen from the surface: 0 when it cannot contribute (it is at the
 * point or behind the shading normal); else 1 with the unit direction Ln to
 * it, ndl = ns . Ln and the shadow ray from the offset point to the light
 * (t = 1 at the light, excluded). */
RT_FN int rt_phong_light(const rt_scene_view *s, const rt_surface *sf, rt_u32 li, rt_ray *sr,
                         float *Ln, float *ndl) {
    RT_GLOBAL const rt_light_d *light = &s->lights[li];
    float L[3];
    for (int k = 0; k < 3; k++) L[k] = light->position[k] - sf->p[k];
    float dist = RT_SQRT(rt_dot3(L, L));
    if (!(dist > 0.0f)) return 0;
    for (int k = 0; k < 3; k++) Ln[k] = RT_DIV(L[k], dist);
    *ndl = rt_dot3(sf->ns, Ln);
    if (!(*ndl > 0.0f)) return 0;
    rt_offset_point(sf->p, sf->ng, rt_dot3(sf->ng, L) >= 0.0f ? 1.0f : -1.0f, sr->org);
    for (int k = 0; k < 3; k++) sr->dir[k] = light->position[k] - sr->org[k];
    sr->tmin = 0.0f;
    sr->tmax = RT_SHADOW_TMAX;
    return 1;
}

/* Adds light li's diffuse and specular terms for a surface seen along unit
 * direction dn (the light's shadow ray found no occluder). */
RT_FN void rt_phong_add(const rt_scene_view *s, const rt_surface *sf, rt_u32 li, const float *Ln,
                        float ndl, const float *dn, float *out) {
    RT_GLOBAL const rt_material_d *m = &s->materials[sf->material];
    RT_GLOBAL const rt_light_d *light = &s->lights[li];
    for (int k = 0; k < 3; k++)
        out[k] = out[k] + ((m->diffuse * m->color[k]) * light->color[k]) * ndl;
    if (m->specular > 0.0f) {
        float R[3];
        for (int k = 0; k < 3; k++) R[k] = (2.0f * ndl) * sf->ns[k] - Ln[k];
        float rv = -rt_dot3(R, dn); /* R . V with V = -dn */
        if (rv > 0.0f) {
            float pw = 1.0f;
            for (rt_i32 i = 0; i < m->shininess; i++) pw = pw * rv;
            for (int k = 0; k < 3; k++) out[k] = out[k] + (m->specular * light->color[k]) * pw;
        }
    }
}

typedef struct rt_shade_entry {
    rt_ray ray;
    float w[3];
    rt_u32 depth;
} rt_shade_entry;

RT_FN int rt_weight_counts(const float *w, float min_weight) {
    return w[0] >= min_weight || w[1] >= min_weight || w[2] >= min_weight;
}

/* A shading-tree node between its two halves (rt_shade_begin and
 * rt_shade_end): the surface at the hit, the unit ray direction and the
 * Phong sum so far. Between them the caller adds each light whose shadow ray
 * is unoccluded (rt_phong_light, then rt_phong_add), light by light in index
 * order; rt_shade_step does exactly that with one scalar shadow ray at a
 * time, a packet tracer with the shadow rays of many pixels at once. */
typedef struct rt_shade_node {
    rt_surface sf;
    float dn[3];
    float lit[3];
    float lw; /* the local weight, 1 - reflectivity - transparency */
} rt_shade_node;

/* The first half of the node of entry e with closest hit h: returns 1 when
 * the node has a Phong term, i.e. the caller must now add the lights; 0 for
 * a miss or a surface without local weight. */
RT_FN int rt_shade_begin(const rt_scene_view *s, const rt_shade_entry *e, const rt_hit_d *h,
                         rt_shade_node *nd) {
    if (h->prim == RT_NO_HIT) return 0;
    rt_surface_at(s, &e->ray, h, &nd->sf);
    RT_GLOBAL const rt_material_d *m = &s->materials[nd->sf.material];
    for (int k = 0; k < 3; k++) nd->dn[k] = e->ray.dir[k];
    rt_normalize3(nd->dn);
    nd->lw = (1.0f - m->reflectivity) - m->transparency;
    if (!(nd->lw > 0.0f)) return 0;
    rt_phong_ambient(s, &nd->sf, nd->lit);
    return 1;
}

/* The second half: term gets what the node adds to the pixel (has_term says
 * whether it adds anything: a miss adds the weighted background, a hit its
 * weighted Phong term when the material keeps local weight), child[0 ..
 * *children - 1] the secondary rays in the order they are pushed:
 * refraction, then reflection (so reflection is popped, and its subtree
 * added, first). */
RT_FN void rt_shade_end(const rt_scene_view *s, const rt_shade_entry *e, const rt_hit_d *h,
                        const rt_shade_node *nd, float *term, int *has_term, rt_shade_entry *child,
                        int *children) {
    *has_term = 0;
    *children = 0;
    term[0] = term[1] = term[2] = 0.0f; /* defined even when not added */
    if (h->prim == RT_NO_HIT) {
        for (int k = 0; k < 3; k++) term[k] = e->w[k] * s->hdr->background[k];
        *has_term = 1;
        return;
    }
    RT_GLOBAL const rt_material_d *m = &s->materials[nd->sf.material];
    if (nd->lw > 0.0f) {
        for (int k = 0; k < 3; k++) term[k] = (e->w[k] * nd->lw) * nd->lit[k];
        *has_term = 1;
    }
    if (!(RT_SCENE_FLAGS(s) & RT_SCENE_SECONDARY) || e->depth >= s->hdr->max_depth) return;
    const rt_surface *sf = &nd->sf;
    float refl = m->reflectivity;
    float cosi = -rt_dot3(nd->dn, sf->ns);
    if (m->transparency > 0.0f) {
        float eta = sf->front ? RT_DIV(1.0f, m->ior) : m->ior;
        float k2 = 1.0f - (eta * eta) * (1.0f - cosi * cosi);
        if (k2 < 0.0f) {
            refl = refl + m->transparency; /* total internal reflection */
        } else {
            rt_shade_entry t;
            float a = eta * cosi - RT_SQRT(k2);
            for (int k = 0; k < 3; k++) {
                t.ray.dir[k] = eta * nd->dn[k] + a * sf->ns[k];
                t.w[k] = e->w[k] * m->transparency;
            }
            rt_offset_point(sf->p, sf->ng, -1.0f, t.ray.org);
            t.ray.tmin = 0.0f;
            t.ray.tmax = RT_INF;
            t.depth = e->depth + 1;
            if (rt_weight_counts(t.w, s->hdr->min_weight)) child[(*children)++] = t;
        }
    }
    if (refl > 0.0f) {
        rt_shade_entry t;
        for (int k = 0; k < 3; k++) {
            t.ray.dir[k] = nd->dn[k] + (2.0f * cosi) * sf->ns[k];
            t.w[k] = e->w[k] * refl;
        }
        rt_offset_point(sf->p, sf->ng, 1.0f, t.ray.org);
        t.ray.tmin = 0.0f;
        t.ray.tmax = RT_INF;
        t.depth = e->depth + 1;
        if (rt_weight_counts(t.w, s->hdr->min_weight)) child[(*children)++] = t;
    }
}

/* One node of the shading tree, whole: the ray of entry e and its closest
 * hit h, with each light's shadow ray traced here (see rt_shade_end for
 * term, has_term and child). Shared by rt_shade_hit (depth-first with a
 * stack) and the OpenCL wavefront, which keeps each node's term and adds them
 * in rt_shade_hit's order at the end. */
RT_FN void rt_shade_step(const rt_scene_view *s, const rt_shade_entry *e, const rt_hit_d *h,
                         rt_counters *c, float *term, int *has_term, rt_shade_entry *child,
                         int *children) {
    rt_shade_node nd;
    if (rt_shade_begin(s, e, h, &nd)) {
        for (rt_u32 li = 0; li < s->hdr->light_count; li++) {
            rt_ray sr;
            rt_hit_d sh;
            float Ln[3], ndl;
            if (!rt_phong_light(s, &nd.sf, li, &sr, Ln, &ndl)) continue;
            if (rt_trace(s, &sr, 1, &sh, c)) continue;
            rt_phong_add(s, &nd.sf, li, Ln, ndl, nd.dn, nd.lit);
        }
    }
    rt_shade_end(s, e, h, &nd, term, has_term, child, children);
}

/* The rest of a pixel's shading tree once its root node is done: rgb holds
 * the root's term (added to 0), child[0 .. children - 1] its secondary rays
 * as rt_shade_end gave them. Depth-first with an explicit stack, up to
 * hdr->max_depth bounces and while a ray's weight reaches hdr->min_weight;
 * each node's term is added in the same order on every backend: a node's own
 * term, then its reflection subtree, then its refraction subtree. The stack
 * never overflows (max_depth + 2 entries suffice, RT_MAX_DEPTH + 2 <=
 * RT_SHADE_STACK), so the wavefront needs no equivalent of the sp check. */
RT_FN void rt_shade_children(const rt_scene_view *s, const rt_shade_entry *child, int children,
                             rt_counters *c, float *rgb) {
    rt_shade_entry stack[RT_SHADE_STACK];
    int sp = 0;
    for (int i = 0; i < children; i++) stack[sp++] = child[i];
    while (sp > 0) {
        rt_shade_entry e = stack[--sp];
        rt_hit_d h;
        rt_trace(s, &e.ray, 0, &h, c);
        float term[3];
        rt_shade_entry next[2];
        int has_term, n;
        rt_shade_step(s, &e, &h, c, term, &has_term, next, &n);
        if (has_term)
            for (int k = 0; k < 3; k++) rgb[k] = rgb[k] + term[k];
        for (int i = 0; i < n; i++)
            if (sp < RT_SHADE_STACK) stack[sp++] = next[i];
    }
}

/* The colour seen along a primary ray whose closest hit is already known
 * (the root node, then rt_shade_children). */
RT_FN void rt_shade_hit(const rt_scene_view *s, const rt_ray *primary, const rt_hit_d *primary_hit,
                        rt_counters *c, float *rgb) {
    rt_shade_entry root;
    root.ray = *primary;
    root.w[0] = root.w[1] = root.w[2] = 1.0f;
    root.depth = 0;
    float term[3];
    rt_shade_entry child[2];
    int has_term, children;
    rt_shade_step(s, &root, primary_hit, c, term, &has_term, child, &children);
    rgb[0] = rgb[1] = rgb[2] = 0.0f;
    if (has_term)
        for (int k = 0; k < 3; k++) rgb[k] = rgb[k] + term[k];
    rt_shade_children(s, child, children, c, rgb);
}

/* The OpenCL wavefront's queue entry and per-node record (see
 * kernels/rt_single_ray.cl); here so the host sizes their buffers with the
 * device's layout (4-byte fields only, so no padding differs). */
typedef struct rt_wave_entry {
    rt_shade_entry e;
    rt_u32 pixel; /* within the tile */
    rt_u32 slot;  /* the node's place in the pixel's tree (pre-order) */
} rt_wave_entry;

typedef struct rt_wave_record {
    float term[3];
    rt_u32 flags; /* bit 0: term is added; bits 1-2: number of children */
} rt_wave_record;

#endif /* RT_SHADE_H */
