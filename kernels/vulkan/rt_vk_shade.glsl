/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_shade.glsl - the GLSL mirror of kernels/rt_shade.h: the surface at a
 * hit, Phong with shadow rays and the steps of the shading tree that
 * rt_vk_main.comp runs around its one rt_trace call. */
#ifndef RT_VK_SHADE_GLSL
#define RT_VK_SHADE_GLSL

#include "rt_vk_trace.glsl"

#define RT_SHADE_STACK 12
#define RT_SHADOW_TMAX 0.999999940395355224609375

struct rt_surface {
    float p[3];
    float ng[3];
    float ns[3];
    int front;
    uint material;
};

void rt_normal_to_world(uint inst, float n[3], out float o[3]) {
    for (int i = 0; i < 3; i++, RT_VK_TICK)
        o[i] = (instances[inst].world_to_object[i] * n[0] +
                instances[inst].world_to_object[4 + i] * n[1]) +
               instances[inst].world_to_object[8 + i] * n[2];
}

void rt_point_to_world(uint inst, float p[3], out float o[3]) {
    for (int i = 0; i < 3; i++, RT_VK_TICK)
        o[i] = ((instances[inst].object_to_world[4 * i] * p[0] +
                 instances[inst].object_to_world[4 * i + 1] * p[1]) +
                instances[inst].object_to_world[4 * i + 2] * p[2]) +
               instances[inst].object_to_world[4 * i + 3];
}

/* The hit point from the barycentrics in object space, then transformed
 * (Waechter and Binder 2019), as the C function. */
void rt_surface_at(rt_ray r, rt_hit_d h, out rt_surface sf) {
    uint e = h.entry, inst = h.inst;
    bool identity = (RT_INST_FLAGS(instances[inst].flags) & RT_INST_IDENTITY) != 0u;
    float e1[3], e2[3], n[3], ns[3], po[3];
    float b0 = (1.0 - h.u) - h.v;
    for (int k = 0; k < 3; k++, RT_VK_TICK) {
        e1[k] = tris[e].v1[k] - tris[e].v0[k];
        e2[k] = tris[e].v2[k] - tris[e].v0[k];
        po[k] = (b0 * tris[e].v0[k] + h.u * tris[e].v1[k]) + h.v * tris[e].v2[k];
    }
    if (identity) {
        for (int k = 0; k < 3; k++, RT_VK_TICK) sf.p[k] = po[k];
    } else {
        rt_point_to_world(inst, po, sf.p);
    }
    rt_cross3(e1, e2, n);
    if (identity) {
        for (int k = 0; k < 3; k++, RT_VK_TICK) sf.ng[k] = n[k];
    } else {
        rt_normal_to_world(inst, n, sf.ng);
    }
    rt_normalize3(sf.ng);
    for (int k = 0; k < 3; k++, RT_VK_TICK) sf.ns[k] = sf.ng[k];
    if ((RT_INST_FLAGS(instances[inst].flags) & RT_INST_NORMALS) != 0u) {
        uint vn = 9u * e;
        float w = (1.0 - h.u) - h.v;
        for (int k = 0; k < 3; k++, RT_VK_TICK)
            n[k] = (w * tri_normals[vn + uint(k)] + h.u * tri_normals[vn + 3u + uint(k)]) +
                   h.v * tri_normals[vn + 6u + uint(k)];
        if (identity) {
            for (int k = 0; k < 3; k++, RT_VK_TICK) ns[k] = n[k];
        } else {
            rt_normal_to_world(inst, n, ns);
        }
        rt_normalize3(ns);
        if (rt_dot3(ns, ns) > 0.0)
            for (int k = 0; k < 3; k++, RT_VK_TICK) sf.ns[k] = ns[k];
    }
    sf.front = rt_dot3(sf.ns, r.dir) < 0.0 ? 1 : 0;
    if (rt_dot3(sf.ng, r.dir) > 0.0)
        for (int k = 0; k < 3; k++, RT_VK_TICK) sf.ng[k] = -sf.ng[k];
    if (sf.front == 0)
        for (int k = 0; k < 3; k++, RT_VK_TICK) sf.ns[k] = -sf.ns[k];
    sf.material = instances[inst].material;
    if ((RT_SCENE_FLAGS() & RT_SCENE_TRI_MATS) != 0u && tri_mats[e] != RT_NO_MATERIAL)
        sf.material = tri_mats[e];
}

void rt_phong_ambient(rt_surface sf, out float o[3]) {
    uint m = sf.material;
    for (int k = 0; k < 3; k++, RT_VK_TICK)
        o[k] = materials[m].emission[k] +
               (materials[m].ambient * materials[m].color[k]) * hdr.ambient[k];
}

bool rt_phong_light(rt_surface sf, uint li, out rt_ray sr, out float Ln[3], out float ndl) {
    float L[3];
    for (int k = 0; k < 3; k++, RT_VK_TICK) L[k] = lights[li].position[k] - sf.p[k];
    float dist = RT_SQRT(rt_dot3(L, L));
    ndl = 0.0;
    if (!(dist > 0.0)) return false;
    for (int k = 0; k < 3; k++, RT_VK_TICK) Ln[k] = RT_DIV(L[k], dist);
    ndl = rt_dot3(sf.ns, Ln);
    if (!(ndl > 0.0)) return false;
    rt_offset_point(sf.p, sf.ng, rt_dot3(sf.ng, L) >= 0.0 ? 1.0 : -1.0, sr.org);
    for (int k = 0; k < 3; k++, RT_VK_TICK) sr.dir[k] = lights[li].position[k] - sr.org[k];
    sr.tmin = 0.0;
    sr.tmax = RT_SHADOW_TMAX;
    return true;
}

void rt_phong_add(rt_surface sf, uint li, float Ln[3], float ndl, float dn[3], inout float o[3]) {
    uint m = sf.material;
    for (int k = 0; k < 3; k++, RT_VK_TICK)
        o[k] = o[k] + ((materials[m].diffuse * materials[m].color[k]) * lights[li].color[k]) * ndl;
    if (materials[m].specular > 0.0) {
        float R[3];
        for (int k = 0; k < 3; k++, RT_VK_TICK) R[k] = (2.0 * ndl) * sf.ns[k] - Ln[k];
        float rv = -rt_dot3(R, dn);
        if (rv > 0.0) {
            float pw = 1.0;
            for (int i = 0; i < materials[m].shininess; i++, RT_VK_TICK) pw = pw * rv;
            for (int k = 0; k < 3; k++, RT_VK_TICK)
                o[k] = o[k] + (materials[m].specular * lights[li].color[k]) * pw;
        }
    }
}

struct rt_shade_entry {
    rt_ray ray;
    float w[3];
    uint depth;
};

bool rt_weight_counts(float w[3], float min_weight) {
    return w[0] >= min_weight || w[1] >= min_weight || w[2] >= min_weight;
}

struct rt_shade_node {
    rt_surface sf;
    float dn[3];
    float lit[3];
    float lw;
};

bool rt_shade_begin(rt_shade_entry e, rt_hit_d h, out rt_shade_node nd) {
    nd.lw = 0.0;
    if (h.prim == RT_NO_HIT) return false;
    rt_surface_at(e.ray, h, nd.sf);
    uint m = nd.sf.material;
    for (int k = 0; k < 3; k++, RT_VK_TICK) nd.dn[k] = e.ray.dir[k];
    rt_normalize3(nd.dn);
    nd.lw = (1.0 - materials[m].reflectivity) - materials[m].transparency;
    if (!(nd.lw > 0.0)) return false;
    rt_phong_ambient(nd.sf, nd.lit);
    return true;
}

void rt_shade_end(rt_shade_entry e, rt_hit_d h, rt_shade_node nd, out float term[3],
                  out bool has_term, out rt_shade_entry child[2], out int children) {
    has_term = false;
    children = 0;
    term[0] = 0.0;
    term[1] = 0.0;
    term[2] = 0.0;
    if (h.prim == RT_NO_HIT) {
        for (int k = 0; k < 3; k++, RT_VK_TICK) term[k] = e.w[k] * hdr.background[k];
        has_term = true;
        return;
    }
    uint m = nd.sf.material;
    if (nd.lw > 0.0) {
        for (int k = 0; k < 3; k++, RT_VK_TICK) term[k] = (e.w[k] * nd.lw) * nd.lit[k];
        has_term = true;
    }
    if ((RT_SCENE_FLAGS() & RT_SCENE_SECONDARY) == 0u || e.depth >= hdr.max_depth) return;
    float refl = materials[m].reflectivity;
    float cosi = -rt_dot3(nd.dn, nd.sf.ns);
    if (materials[m].transparency > 0.0) {
        float ior = materials[m].ior;
        float eta = nd.sf.front != 0 ? RT_DIV(1.0, ior) : ior;
        float k2 = 1.0 - (eta * eta) * (1.0 - cosi * cosi);
        if (k2 < 0.0) {
            refl = refl + materials[m].transparency;
        } else {
            rt_shade_entry t;
            float a = eta * cosi - RT_SQRT(k2);
            for (int k = 0; k < 3; k++, RT_VK_TICK) {
                t.ray.dir[k] = eta * nd.dn[k] + a * nd.sf.ns[k];
                t.w[k] = e.w[k] * materials[m].transparency;
            }
            rt_offset_point(nd.sf.p, nd.sf.ng, -1.0, t.ray.org);
            t.ray.tmin = 0.0;
            t.ray.tmax = RT_INF;
            t.depth = e.depth + 1u;
            if (rt_weight_counts(t.w, hdr.min_weight)) child[children++] = t;
        }
    }
    if (refl > 0.0) {
        rt_shade_entry t;
        for (int k = 0; k < 3; k++, RT_VK_TICK) {
            t.ray.dir[k] = nd.dn[k] + (2.0 * cosi) * nd.sf.ns[k];
            t.w[k] = e.w[k] * refl;
        }
        rt_offset_point(nd.sf.p, nd.sf.ng, 1.0, t.ray.org);
        t.ray.tmin = 0.0;
        t.ray.tmax = RT_INF;
        t.depth = e.depth + 1u;
        if (rt_weight_counts(t.w, hdr.min_weight)) child[children++] = t;
    }
}

#endif
