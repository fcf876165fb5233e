/* render_internal.h - what rt_render and rt_trace_rays share: bringing the
 * scene's BVHs and flattened layout up to date. */
#ifndef RT_RENDER_INTERNAL_H
#define RT_RENDER_INTERNAL_H

#include "flatten.h"
#include "scene.h"
#include "thread_pool.h"

typedef struct rt_prepared {
    const rt_flat *flat;
    rt_pool *pool;
    double sah_cost; /* triangle-weighted mean over the objects' meshes */
    double build_ms; /* BVH builds and flattening done by this call */
} rt_prepared;

/* Applies queued transforms, rebuilds the BVHs of meshes that changed (one
 * cache entry per mesh), the object BVH when objects changed, and the layout.
 * threads <= 0: all cores. */
rt_status rt_render_prepare(rt_scene *scene, int threads, rt_prepared *out);

/* A shallow copy of flat whose header selects triangle test 'test' (the
 * arrays stay shared); an unknown test is an invalid argument. */
rt_status rt_flat_with_tri_test(rt_scene *scene, const rt_flat *flat, rt_triangle_test test,
                                rt_flat *out);

/* Milliseconds on a monotonic clock. */
double rt_now_ms(void);

#endif /* RT_RENDER_INTERNAL_H */
