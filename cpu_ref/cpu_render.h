/* SPDX-License-Identifier: Apache-2.0 */
/* cpu_render.h - the CPU backends over the flattened layout: the scalar
 * oracle ("cpu") and the packet path ("packet", cpu_ref/packet_trace.h). Both write the same
 * bits: the packet path only changes how primary rays find their hits. */
#ifndef RT_CPU_RENDER_H
#define RT_CPU_RENDER_H

#include <stdint.h>

#include "base/thread_pool.h"
#include "layout/flat.h"
#include "cpu_isa.h"
#include "packet_trace.h"
#include "rt.h"
#include "kernel_maths.h"
#include "single_trace.h"
#include "wide_bvh.h"

typedef struct rt_cpu_counts {
    uint64_t rays, primary_rays, box_tests, tri_tests;
    uint64_t packets, packet_box_tests, packet_tri_tests; /* packet path only */
} rt_cpu_counts;

typedef struct rt_cpu_frame {
    const rt_flat *flat;
    const rt_wide_bvh *wide; /* the packet backend's packet BVHs of flat (rt_pk_shape) ... */
    const rt_cpu_isa *isa;   /* ... and the build of its tracers that runs */
    rt_aov aov;
    float *pixels; /* width * height * channels */
    int channels;  /* 3 for the image and normals, else 1 */
    void (*progress)(void *user, double done);
    void *progress_user;
    int flush_denormals; /* 1: the workers flush denormals (rt_pool_run_fp) */
    /* The packet backend's single-ray BVHs of flat (rt_sw_shape of the
     * isa's width), for incoherent rays (reflections, refractions and their
     * shadow rays), or NULL. */
    const rt_wide_bvh *single;
} rt_cpu_frame;

/* Renders with the scalar oracle on the pool's workers (interleaved rows).
 * RT_ERROR_OUT_OF_MEMORY when its bookkeeping cannot be allocated. */
rt_status rt_cpu_render(const rt_cpu_frame *frame, rt_pool *pool, rt_cpu_counts *counts);

/* Renders with packets of RT_PACKET_TILE_W x RT_PACKET_TILE_H pixels (one
 * per tile) on the pool's workers, which take rows of tiles in turn. */
enum { RT_PACKET_TILE_W = 8, RT_PACKET_TILE_H = 8 };
rt_status rt_packet_render(const rt_cpu_frame *frame, rt_pool *pool, rt_cpu_counts *counts);

/* Finishes one pixel whose primary ray and hit are known: shading (or the
 * AOV) into the frame. Both backends call it. */
void rt_cpu_finish_pixel(const rt_cpu_frame *frame, const rt_scene_view *view, int x, int y,
                         const rt_ray *ray, const rt_hit_d *hit, rt_counters *c);

/* Traces n rays (closest or any hit) with the scalar code, or (the packet
 * backend) each group of RT_PK_LANES consecutive rays that is coherent
 * (cpu_ref/ray_coherence.h) as a packet and the others one by one through
 * the single-ray tracer (path RT_TRACE_PATH_PACKETS or _SINGLE forces one;
 * without tracers->single every group is a packet); misses get prim =
 * RT_NO_HIT. *packet_rays counts the rays that went in packets. masks[i]
 * is ray i's mask (rt_trace_masked; NULL: 0xffffffff for every ray). */
void rt_cpu_trace_rays(const rt_flat *flat, const rt_ray *rays, const uint32_t *masks, size_t n,
                       rt_hit_d *hits, int any_hit, rt_counters *c);
void rt_packet_trace_rays(const rt_cpu_frame *tracers, const rt_ray *rays, const uint32_t *masks,
                          size_t n, rt_hit_d *hits, int any_hit, rt_trace_path path, rt_counters *c,
                          uint64_t *packet_rays);

/* The rest of a pixel's shading tree, as rt_shade_children (rt_shade.h)
 * computes it, every ray (and shadow ray) traced by the single-ray tracer
 * of f: the same bits. */
void rt_single_shade_children(const rt_cpu_frame *f, const rt_scene_view *v,
                              const rt_shade_entry *child, int children, rt_counters *c,
                              float *rgb);

#endif /* RT_CPU_RENDER_H */
