/* SPDX-License-Identifier: Apache-2.0 */
/* render_frame.h - what rt_render and rt_trace_rays share: the frame's
 * layout (the triangle test and features it asks for) and the backend that
 * runs it. */
#ifndef RT_RENDER_FRAME_H
#define RT_RENDER_FRAME_H

#include "render/renderer_internal.h"

typedef struct rt_frame_state {
    rt_flat flat;              /* a shallow copy of the renderer's layout ... */
    rt_backend_layout layout;  /* ... that layout.flat points at */
    const rt_backend_ops *ops; /* the renderer's backend */
    void *state;
    double build_ms; /* BVH builds and flattening done for this frame */
    double sah_cost;
} rt_frame_state;

/* Brings the renderer's layout up to date for scene and fills out; an
 * unknown triangle test is an invalid argument. Errors go to r->error. */
rt_status rt_frame_layout(rt_renderer *r, rt_scene *scene, rt_triangle_test test, int direct_only,
                          rt_frame_state *out);

/* The start of a ray query (rt_trace_rays, rt_count_intersections): clears
 * r->error and checks that scene is given, and rays and out (named
 * out_name in the message) when count > 0. what names the call. */
rt_status rt_frame_query_begin(rt_renderer *r, const char *what, const rt_scene *scene,
                               const rt_ray *rays, size_t count, const void *out,
                               const char *out_name);

/* The rays a frame's query traces: *in is rays itself when every ray is
 * valid, else a copy (*copy, for the caller to free) in which each ray with
 * a NaN or infinite component, a NaN end or a zero direction is an empty
 * range (tmin 1 > tmax 0), which every backend misses. Errors go to
 * r->error. */
rt_status rt_frame_rays(rt_renderer *r, const rt_ray *rays, size_t count, const rt_ray **in,
                        rt_ray **copy);

#endif /* RT_RENDER_FRAME_H */
