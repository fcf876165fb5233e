/* rt_render.cl - the OpenCL backend's kernels over the shared maths.
 *
 * Everything that computes a value comes from rt_shared.h and rt_shade.h, the
 * headers the CPU oracle compiles, so the bits are the oracle's. The host
 * builds this without -cl-mad-enable or fast-math and with
 * -cl-fp32-correctly-rounded-divide-sqrt, and specialises it with -D switches
 * (RT_STATIC_FLAGS, ...; see rt_shared.h).
 *
 * A frame is a sequence of bounded launches over tiles of pixels (pixel index
 * first .. first + count - 1, row-major): rt_k_camera writes the tile's primary
 * rays, rt_k_trace finds their closest hits, rt_k_shade shades them (shadow
 * rays, then reflection and refraction through rt_shade_hit's explicit stack)
 * or writes an AOV. rt_k_trace alone answers ray queries.
 */
#pragma OPENCL FP_CONTRACT OFF

#include "rt_shade.h"

/* The view arguments every tracing kernel takes, in this order. */
#define RT_VIEW_ARGS                                                                               \
    __global const rt_scene_header *hdr, __global const rt_node *nodes,                            \
        __global const rt_tri *tris, __global const uint *tri_ids,                                 \
        __global const float *tri_normals, __global const uint *tri_mats,                          \
        __global const rt_instance *instances, __global const uint *inst_ids,                      \
        __global const rt_material_d *materials, __global const rt_light_d *lights

#define RT_VIEW_INIT                                                                               \
    {hdr, nodes, tris, tri_ids, tri_normals, tri_mats, instances, inst_ids, materials, lights}

/* AOV codes (rt_aov in rt.h). */
#define AOV_NONE      0
#define AOV_DEPTH     1
#define AOV_PRIMID    2
#define AOV_INSTID    3
#define AOV_NORMAL    4
#define AOV_BOX_TESTS 5
#define AOV_TRI_TESTS 6

__kernel void rt_k_camera(__global const rt_scene_header *hdr, uint first, uint count,
                          __global rt_ray_d *rays) {
    uint i = (uint)get_global_id(0);
    if (i >= count) return;
    uint pixel = first + i;
    rt_ray_d r;
    rt_camera_ray(hdr, (rt_i32)(pixel % (uint)hdr->width), (rt_i32)(pixel / (uint)hdr->width), &r);
    rays[i] = r;
}

/* Closest (or any) hits of count rays; counters[i] gets the ray's tests. */
__kernel void rt_k_trace(RT_VIEW_ARGS, uint count, int any_hit, __global const rt_ray_d *rays,
                         __global rt_hit_d *hits, __global rt_counters *counters) {
    uint i = (uint)get_global_id(0);
    if (i >= count) return;
    rt_scene_view s = RT_VIEW_INIT;
    rt_ray_d r = rays[i];
    rt_hit_d h;
    rt_counters c = {0, 0, 0};
    rt_trace(&s, &r, any_hit, &h, &c);
    hits[i] = h;
    counters[i] = c;
}

/* Shades the tile's hits into fb (channels floats per pixel, the whole frame),
 * as rt_cpu_finish_pixel does; counters[i] gains the shading rays' tests. */
__kernel void rt_k_shade(RT_VIEW_ARGS, uint first, uint count, int aov, int channels,
                         __global const rt_ray_d *rays, __global const rt_hit_d *hits,
                         __global rt_counters *counters, __global float *fb) {
    uint i = (uint)get_global_id(0);
    if (i >= count) return;
    rt_scene_view s = RT_VIEW_INIT;
    rt_ray_d r = rays[i];
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
}
