/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_main.comp - the Vulkan backend's one shader: a frame's tile (one
 * pixel per invocation) or ray queries (one ray per invocation).
 *
 * Frames: the primary ray (rt_camera_ray), its closest hit, then an AOV, or
 * the colour of rt_shade_hit: each node of the shading tree (its ray's
 * closest hit, rt_shade_begin, one shadow ray per light with rt_phong_light
 * and rt_phong_add, rt_shade_end) with reflection and refraction rays on an
 * explicit stack, depth-first, terms added in rt_shade_hit's order. Written
 * as one loop around a single rt_trace call (primary, shadow and secondary
 * rays alike), so that the driver compiles one copy of the traversal
 * instead of one per kind of ray, and the invocations of a SIMD group trace
 * together whatever kind of ray each is at. The operations and their order
 * are the C functions' (kernels/rt_shade.h), so the bits are the oracle's.
 *
 * Ray queries: rays[i] -> hits[i] (closest or any hit), counters[i].
 * Frames: pixels pc.first .. pc.first + pc.count - 1 (row-major), pixel
 * first + i at fb[i * channels], counters[i] its ray and test counts.
 *
 * The loop-limit canary. llvmpipe and lavapipe (gallivm) give a shader one
 * iteration budget, 65535, shared by every loop of the whole shader and by
 * the invocations of a SIMD group: once it is spent, each loop stops after
 * its current iteration, silently, and a traversal returns a wrong hit. A
 * group of rays that diverge can spend it where each ray alone would not.
 * The budget never grows back, so a loop of pc.canary = 2 iterations at the
 * end runs both only when no loop before it was cut: items[i] = 1 marks an
 * item whose result cannot be trusted, and the host traces it again alone
 * in its work group (pc.stride), or reports it. Other drivers have no such
 * limit; there the canary costs two loop iterations. */
#version 450
#extension GL_GOOGLE_include_directive : require

#include "rt_vk_io.glsl"

layout(local_size_x = RT_VK_LOCAL) in;

/* What the next rt_trace is for. */
#define STEP_QUERY  0 /* a ray query: write its hit, done */
#define STEP_NODE   1 /* the closest hit of a shading node's ray */
#define STEP_SHADOW 2 /* light li's shadow ray of the current node */

/* ---- the shading state in ST_MAIN (rt_vk_resume.glsl), as bits ---------- */

void st_put_entry(inout uint w, rt_shade_entry x) {
    st_put_ray(w, x.ray);
    st_put3(w, x.w);
    st_put(w, x.depth);
}
void st_get_entry(inout uint w, out rt_shade_entry x) {
    st_get_ray(w, x.ray);
    st_get3(w, x.w);
    x.depth = st_get(w);
}
void st_put_node(inout uint w, rt_shade_node x) {
    st_put3(w, x.sf.p);
    st_put3(w, x.sf.ng);
    st_put3(w, x.sf.ns);
    st_put(w, uint(x.sf.front));
    st_put(w, x.sf.material);
    st_put3(w, x.dn);
    st_put3(w, x.lit);
    st_putf(w, x.lw);
}
void st_get_node(inout uint w, out rt_shade_node x) {
    st_get3(w, x.sf.p);
    st_get3(w, x.sf.ng);
    st_get3(w, x.sf.ns);
    x.sf.front = int(st_get(w));
    x.sf.material = st_get(w);
    st_get3(w, x.dn);
    st_get3(w, x.lit);
    x.lw = st_getf(w);
}

/* main()'s whole state: where it is (where: 0 before the next rt_trace, 1
 * inside it, whose own state is ST_TOP's and below, 2 in the scan for the
 * next light with a shadow ray, before light li), the ray
 * kind, the shading node and its hit, the light, the shadow ray, the colour
 * so far, the stack of children and the counters (at most 204 words). */
#define MAIN_SAVE()                                                                                \
    {                                                                                              \
        uint w = ST_MAIN;                                                                          \
        st_put(w, where);                                                                          \
        st_put(w, uint(step));                                                                     \
        st_put(w, primary ? 1u : 0u);                                                              \
        st_put(w, begun ? 1u : 0u);                                                                \
        st_put(w, li);                                                                             \
        st_put(w, uint(sp));                                                                       \
        st_put(w, c.box_tests);                                                                    \
        st_put(w, c.tri_tests);                                                                    \
        st_put(w, c.rays);                                                                         \
        st_putf(w, ndl);                                                                           \
        st_put3(w, Ln);                                                                            \
        st_put3(w, rgb);                                                                           \
        st_put_entry(w, e);                                                                        \
        st_put_hit(w, h);                                                                          \
        st_put_node(w, nd);                                                                        \
        st_put_ray(w, sr);                                                                         \
        for (int k = 0; k < sp; k++, RT_VK_TICK) st_put_entry(w, stack[k]);                        \
    }
#define MAIN_LOAD()                                                                                \
    {                                                                                              \
        uint w = ST_MAIN;                                                                          \
        where = st_get(w);                                                                         \
        step = int(st_get(w));                                                                     \
        primary = st_get(w) != 0u;                                                                 \
        begun = st_get(w) != 0u;                                                                   \
        li = st_get(w);                                                                            \
        sp = int(st_get(w));                                                                       \
        c.box_tests = st_get(w);                                                                   \
        c.tri_tests = st_get(w);                                                                   \
        c.rays = st_get(w);                                                                        \
        ndl = st_getf(w);                                                                          \
        st_get3(w, Ln);                                                                            \
        st_get3(w, rgb);                                                                           \
        st_get_entry(w, e);                                                                        \
        st_get_hit(w, h);                                                                          \
        st_get_node(w, nd);                                                                        \
        st_get_ray(w, sr);                                                                         \
        for (int k = 0; k < sp; k++, RT_VK_TICK) st_get_entry(w, stack[k]);                        \
    }

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (pc.stride > 1u) {
        if (i % pc.stride != 0u || i / pc.stride >= pc.count) return;
        /* Alone in its work group (pc.stride = RT_VK_LOCAL): it may
         * suspend (rt_vk_resume.glsl), in its slot of the state buffer. */
        uint j = pc.list_at + 2u * (i / pc.stride);
        i = items[j];
        rt_vk_slot = items[j + 1u] * RT_VK_STATE_WORDS;
        rt_vk_limit = RT_VK_TICK_LIMIT;
        rt_vk_resuming = SC_RESUME != 0u && pc.resume != 0u;
    } else if (i >= pc.count) {
        return;
    }
    /* A test's fault injection: iterations spent from the loop budget. */
    uint spent = 0u;
    for (uint k = 0u; k < pc.ballast; k++, RT_VK_TICK) spent++;
    rt_counters c;
    c.box_tests = 0u;
    c.tri_tests = 0u;
    c.rays = 0u;
    uint pixel = pc.first + i;
    uint o = i * uint(pc.channels); /* fb holds the tile (vk_render copies it out) */
    int step = pc.query != 0 ? STEP_QUERY : STEP_NODE;
    bool primary = true;
    /* The node being shaded (rt_shade_step's state), and the stack of
     * rt_shade_children. */
    rt_shade_entry e;
    rt_hit_d h;
    rt_shade_node nd;
    bool begun = false;
    uint li = 0u;
    rt_ray sr;
    float Ln[3], ndl;
    float rgb[3] = float[3](0.0, 0.0, 0.0);
    rt_shade_entry stack[RT_SHADE_STACK];
    int sp = 0;
    uint where = 0u; /* where a suspended item stopped: MAIN_SAVE */
    if (rt_vk_resuming) {
        MAIN_LOAD()
        if (where != 1u) rt_vk_resuming = false;
    } else if (step == STEP_QUERY) {
        e.ray = rays[i];
    } else {
        rt_camera_pixel_ray(pixel, e.ray);
        e.w[0] = 1.0;
        e.w[1] = 1.0;
        e.w[2] = 1.0;
        e.depth = 0u;
    }
    for (;; RT_VK_TICK) {
        /* Resumed in the light scan (where 2): straight back to it. */
        if (where != 2u) {
            /* Passive while resuming into rt_trace (where 1). */
            if (rt_vk_checkpoint()) {
                where = 0u;
                break;
            }
            bool any = step == STEP_SHADOW || (step == STEP_QUERY && pc.any_hit != 0);
            rt_hit_d th;
            /* A query's ray mask (masks[i] when the caller gave masks); every
             * ray of a frame has mask 0xffffffff. */
            uint mask = step == STEP_QUERY && pc.masked != 0u ? masks[i] : 0xffffffffu;
            bool occluded = rt_trace_masked(step == STEP_SHADOW ? sr : e.ray, mask, any, th, c);
            if (rt_vk_suspended) {
                where = 1u;
                break;
            }
            if (step == STEP_QUERY) {
                hits[i] = th;
                break;
            }
            if (step == STEP_NODE) {
                h = th;
                if (primary && pc.aov != AOV_NONE && pc.aov != AOV_BOX_TESTS &&
                    pc.aov != AOV_TRI_TESTS) {
                    /* rt_cpu_finish_pixel's AOVs of the primary hit. */
                    bool hit_any = h.prim != RT_NO_HIT;
                    if (pc.aov == AOV_DEPTH) {
                        fb[o] = hit_any ? h.t : RT_INF;
                    } else if (pc.aov == AOV_PRIMID) {
                        fb[o] = hit_any ? float(h.prim) : -1.0;
                    } else if (pc.aov == AOV_INSTID) {
                        fb[o] = hit_any ? float(h.inst) : -1.0;
                    } else {
                        fb[o] = 0.0;
                        fb[o + 1u] = 0.0;
                        fb[o + 2u] = 0.0;
                        if (hit_any) {
                            rt_surface sf;
                            rt_surface_at(e.ray, h, sf);
                            for (int k = 0; k < 3; k++, RT_VK_TICK) fb[o + uint(k)] = sf.ns[k];
                        }
                    }
                    break;
                }
                begun = rt_shade_begin(e, h, nd);
                li = 0u;
            } else {
                /* rt_shade_step: a light whose shadow ray finds no occluder. */
                if (!occluded) rt_phong_add(nd.sf, li, Ln, ndl, nd.dn, nd.lit);
                li++;
            }
        }
        where = 0u;
        /* The next light with a shadow ray (rt_phong_light), if any; a
         * checkpoint before each light, so that many lights cost resumes. */
        step = STEP_NODE;
        if (begun) {
            while (li < hdr.light_count) {
                RT_VK_TICK;
                if (rt_vk_checkpoint()) {
                    where = 2u;
                    break;
                }
                if (rt_phong_light(nd.sf, li, sr, Ln, ndl)) {
                    step = STEP_SHADOW;
                    break;
                }
                li++;
            }
        }
        if (where == 2u) break;
        if (step == STEP_SHADOW) continue;
        /* The node is done: its term, then its children on the stack. */
        float term[3];
        bool has_term;
        rt_shade_entry child[2];
        int children;
        rt_shade_end(e, h, nd, term, has_term, child, children);
        if (has_term)
            for (int k = 0; k < 3; k++, RT_VK_TICK) rgb[k] = rgb[k] + term[k];
        for (int j = 0; j < children; j++, RT_VK_TICK)
            if (sp < RT_SHADE_STACK) stack[sp++] = child[j];
        primary = false;
        begun = false;
        if (sp == 0) break;
        e = stack[--sp];
    }
    if (rt_vk_suspended) {
        /* Nothing to write yet: a later dispatch goes on from the slot. */
        MAIN_SAVE()
    } else if (pc.query == 0) {
        if (pc.aov == AOV_NONE)
            for (int k = 0; k < 3; k++, RT_VK_TICK) fb[o + uint(k)] = rgb[k];
        else if (pc.aov == AOV_BOX_TESTS || pc.aov == AOV_TRI_TESTS)
            fb[o] = float(pc.aov == AOV_BOX_TESTS ? c.box_tests : c.tri_tests);
    }
    if (!rt_vk_suspended) counters[i] = c;
    uint runs = 0u;
    for (uint k = 0u; k < pc.canary; k++, RT_VK_TICK) runs++;
    /* Cut (1) wins over suspended (2): a state saved after a cut is not
     * trusted (the host traces the item again from its start, or reports
     * it). */
    bool cut = runs != pc.canary || spent != pc.ballast;
    items[i] = cut ? 1u : (rt_vk_suspended ? 2u : 0u);
}
