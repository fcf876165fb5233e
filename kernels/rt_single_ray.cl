/* SPDX-License-Identifier: Apache-2.0 */
/* rt_single_ray.cl - the OpenCL backend's one-ray-per-work-item kernels over
 * the shared maths (every device; rt_ray_packet.cl adds packets on CPUs).
 *
 * Everything that computes a value comes from the shared maths headers
 * (rt_trace.h, rt_shade.h and what they include), the headers the CPU oracle
 * compiles, so the bits are the oracle's. The host
 * builds this without the options -cl-mad-enable or fast-math and with
 * -cl-fp32-correctly-rounded-divide-sqrt, and specialises it with -D switches
 * (RT_STATIC_FLAGS, ...; see rt_view.h).
 *
 * A frame is a sequence of bounded launches over tiles of pixels (pixel index
 * first .. first + count - 1, row-major): rt_k_camera writes the tile's primary
 * rays, rt_k_trace finds their closest hits, rt_k_shade shades them (shadow
 * rays, then reflection and refraction through rt_shade_hit's explicit stack)
 * or writes an AOV. rt_k_trace alone answers ray queries.
 */
#pragma OPENCL FP_CONTRACT OFF
/* Vectors wider than the target's registers (float16 without AVX-512, float8
 * without AVX) pass between functions differently by target, and clang warns
 * about that ABI change (-Wpsabi) at every such call, the built-ins' included:
 * a couple of hundred "warnings generated" on a cold cache. The warning is
 * about linking objects built for different targets; a program is compiled
 * and linked for its one device here, so it does not apply. Only that warning
 * is off; tests/check_kernels_clang.sh builds the kernels for several x86
 * targets with every other warning an error. */
#ifdef __clang__
#pragma clang diagnostic ignored "-Wpsabi"
#endif

#include "rt_kernel_args.h" /* rt_shade.h, the view arguments, the AOV codes */

__kernel void rt_k_camera(__global const rt_scene_header *hdr, uint first, uint count,
                          __global rt_ray *rays, __global uint *done) {
    uint i = (uint)get_global_id(0);
    if (i >= count) return;
    rt_ray r;
    rt_camera_pixel_ray(hdr, first + i, &r);
    rays[i] = r;
    RT_K_DONE(done, CAMERA, i);
}

/* Closest (or any) hits of count rays; counters[i] gets the ray's tests.
 * Ray i's mask is masks[i] when masked, else 0xffffffff (rt_trace_masked). */
__kernel void rt_k_trace(RT_VIEW_ARGS, uint count, int any_hit, __global const rt_ray *rays,
                         __global rt_hit_d *hits, __global rt_counters *counters, uint masked,
                         __global const uint *masks, __global uint *done) {
    uint i = (uint)get_global_id(0);
    if (i >= count) return;
    rt_scene_view s = RT_VIEW_INIT;
    rt_ray r = rays[i];
    rt_hit_d h;
    rt_counters c = {0, 0, 0};
    rt_trace_masked(&s, &r, masked ? masks[i] : 0xffffffffu, any_hit, &h, &c);
    hits[i] = h;
    counters[i] = c;
    RT_K_DONE(done, TRACE, i);
}

/* Shades the tile's hits into fb (channels floats per pixel, the whole frame),
 * as rt_cpu_finish_pixel does; counters[i] gains the shading rays' tests. */
__kernel void rt_k_shade(RT_VIEW_ARGS, uint first, uint count, int aov, int channels,
                         __global const rt_ray *rays, __global const rt_hit_d *hits,
                         __global rt_counters *counters, __global float *fb, __global uint *done) {
    uint i = (uint)get_global_id(0);
    if (i >= count || RT_K_SKIPPED(i)) return;
    rt_scene_view s = RT_VIEW_INIT;
    rt_ray r = rays[i];
    rt_hit_d h = hits[i];
    rt_counters c = counters[i];
    __global float *out = fb + (size_t)(first + i) * (size_t)channels;
    int hit_any = h.prim != RT_NO_HIT;
    if (aov == AOV_DEPTH) {
        out[0] = hit_any ? h.t : INFINITY;
    } else if (aov == AOV_PRIMID) {
        out[0] = hit_any ? (float)h.prim : -1.0f;
    } else if (aov == AOV_INSTID) {
        out[0] = hit_any ? (float)h.inst : -1.0f;
    } else if (aov == AOV_NORMAL) {
        out[0] = out[1] = out[2] = 0.0f;
        if (hit_any) {
            rt_surface sf;
            rt_surface_at(&s, &r, &h, &sf);
            for (int k = 0; k < 3; k++) out[k] = sf.ns[k];
        }
    } else {
        float rgb[3];
        rt_shade_hit(&s, &r, &h, &c, rgb);
        if (aov == AOV_NONE)
            for (int k = 0; k < 3; k++) out[k] = rgb[k];
        else
            out[0] = (float)(aov == AOV_BOX_TESTS ? c.box_tests : c.tri_tests);
    }
    counters[i] = c;
    RT_K_DONE(done, SHADE, i);
}

/* ---- reflection and refraction as wavefront passes -------------------------
 *
 * For images of scenes with secondary rays, a tile is shaded level by level:
 * rt_k_wave_camera queues the primary rays, then per level rt_k_wave_trace
 * finds the queued rays' hits and rt_k_wave_shade shades them with
 * rt_shade_step, appending the secondary rays to the next queue (an atomic
 * counter), until the queue is empty. Float addition is not associative, so
 * a node does not add its term to the pixel: it stores it in the pixel's
 * record slot, the node's pre-order index in the full binary tree of depth
 * max_depth (the child popped first by rt_shade_hit at slot + 1, the other at
 * slot + 2^(max_depth - depth)), and rt_k_wave_sum adds the terms in
 * rt_shade_hit's order by walking the records depth-first. Only slots of
 * nodes that exist are read, so the records need no clearing. The records are
 * slot-major (record of pixel p, slot k at k * stride + p, stride = the
 * largest tile): the slots near the root, which most pixels have, are then
 * contiguous across the tile instead of a kilobyte apart. */

__kernel void rt_k_wave_camera(__global const rt_scene_header *hdr, uint first, uint count,
                               __global rt_wave_entry *queue, __global uint *done) {
    uint i = (uint)get_global_id(0);
    if (i >= count) return;
    rt_wave_entry q;
    rt_camera_pixel_ray(hdr, first + i, &q.e.ray);
    q.e.w[0] = q.e.w[1] = q.e.w[2] = 1.0f;
    q.e.depth = 0;
    q.pixel = i;
    q.slot = 0;
    queue[i] = q;
    RT_K_DONE(done, WCAM, i);
}

/* Adds c to the pixel's counters (several rays of a pixel may be in one pass:
 * integer sums, so the order does not matter). */
static void add_counters(__global uint *counters, uint pixel, const rt_counters *c) {
    if (c->box_tests) atomic_add(&counters[3 * pixel + 0], c->box_tests);
    if (c->tri_tests) atomic_add(&counters[3 * pixel + 1], c->tri_tests);
    if (c->rays) atomic_add(&counters[3 * pixel + 2], c->rays);
}

__kernel void rt_k_wave_trace(RT_VIEW_ARGS, uint count, __global const rt_wave_entry *queue,
                              __global rt_hit_d *hits, __global uint *counters,
                              __global uint *done) {
    uint i = (uint)get_global_id(0);
    if (i >= count) return;
    rt_scene_view s = RT_VIEW_INIT;
    rt_ray r = queue[i].e.ray;
    rt_hit_d h;
    rt_counters c = {0, 0, 0};
    rt_trace(&s, &r, 0, &h, &c);
    hits[i] = h;
    add_counters(counters, queue[i].pixel, &c);
    RT_K_DONE(done, WTRACE, i);
}

__kernel void rt_k_wave_shade(RT_VIEW_ARGS, uint count, __global const rt_wave_entry *queue,
                              __global const rt_hit_d *hits, __global uint *counters,
                              __global rt_wave_record *records, uint stride,
                              __global rt_wave_entry *next, __global uint *next_count,
                              uint next_cap, __global uint *done) {
    uint i = (uint)get_global_id(0);
    if (i >= count) return;
    rt_scene_view s = RT_VIEW_INIT;
    rt_wave_entry q = queue[i];
    rt_hit_d h = hits[i];
    rt_counters c = {0, 0, 0};
    rt_wave_record rec;
    rt_shade_entry child[2];
    int has_term, children;
    rt_shade_step(&s, &q.e, &h, &c, rec.term, &has_term, child, &children);
    rec.flags = (has_term ? 1u : 0u) | ((uint)children << 1);
    records[(size_t)q.slot * stride + q.pixel] = rec;
    add_counters(counters, q.pixel, &c);
    for (int j = 0; j < children; j++) {
        rt_wave_entry n;
        n.e = child[j];
        n.pixel = q.pixel;
        /* rt_shade_hit pops the last pushed child first. */
        n.slot = j == children - 1 ? q.slot + 1u : q.slot + (1u << (hdr->max_depth - q.e.depth));
        uint at = atomic_inc(next_count);
        if (at < next_cap) next[at] = n; /* the host sees the overflow and redoes the tile */
    }
    RT_K_DONE(done, WSHADE, i);
}

__kernel void rt_k_wave_sum(uint first, uint count, __global const rt_scene_header *hdr,
                            __global const rt_wave_record *records, uint stride, int channels,
                            __global float *fb, __global uint *done) {
    uint i = (uint)get_global_id(0);
    if (i >= count || RT_K_SKIPPED(i)) return;
    uint stack_slot[RT_SHADE_STACK], stack_depth[RT_SHADE_STACK];
    int sp = 0;
    float rgb[3] = {0.0f, 0.0f, 0.0f};
    stack_slot[0] = 0;
    stack_depth[0] = 0;
    sp = 1;
    while (sp > 0) {
        sp--;
        uint slot = stack_slot[sp], depth = stack_depth[sp];
        rt_wave_record r = records[(size_t)slot * stride + i];
        if (r.flags & 1u)
            for (int k = 0; k < 3; k++) rgb[k] = rgb[k] + r.term[k];
        uint children = (r.flags >> 1) & 3u;
        if (children == 2u) {
            stack_slot[sp] = slot + (1u << (hdr->max_depth - depth));
            stack_depth[sp++] = depth + 1u;
        }
        if (children >= 1u) {
            stack_slot[sp] = slot + 1u;
            stack_depth[sp++] = depth + 1u;
        }
    }
    __global float *out = fb + (size_t)(first + i) * (size_t)channels;
    for (int k = 0; k < 3; k++) out[k] = rgb[k];
    RT_K_DONE(done, WSUM, i);
}
