/* render_internal.h - what rt_render and rt_trace_rays share: bringing the
 * scene's BVHs and flattened layout up to date. */
#ifndef RT_RENDER_INTERNAL_H
#define RT_RENDER_INTERNAL_H

#include "base/clock.h"
#include "layout/flatten.h"
#include "packet_wide.h"
#include "scene/scene.h"
#include "base/thread_pool.h"

typedef struct rt_prepared {
    const rt_flat *flat;
    rt_pool *pool;
    double sah_cost; /* triangle-weighted mean over the objects' meshes */
    double build_ms; /* BVH builds and flattening done by this call */
    /* For device backends: what changed since they last uploaded. */
    uint32_t mesh_generation; /* bumped whenever some mesh BVH is (re)built */
    uint32_t flat_version;    /* scene version the layout was made from */
    void **backend_state;     /* the backend's per-scene state (freed with the scene) */
    void (**backend_state_free)(void *state);
} rt_prepared;

/* Applies queued transforms, rebuilds the BVHs of meshes that changed (one
 * cache entry per mesh), the object BVH when objects changed, and the layout.
 * threads <= 0: all cores. */
rt_status rt_render_prepare(rt_scene *scene, int threads, rt_prepared *out);

/* A device backend (host/cl_backend.c). It is found through a weak
 * reference, so the dependency-free core links without it: the full library
 * defines it and forces its object into every program (CMakeLists.txt). */
typedef struct rt_backend_ops {
    const char *name;
    /* Renders into fb (already allocated: width x height x channels). device
     * selects a device (NULL: the default). */
    rt_status (*render)(rt_scene *scene, const rt_prepared *prep, const char *device,
                        const rt_render_options *opt, rt_framebuffer *fb, rt_render_stats *stats);
    /* device_options: extra compiler options (rt_render_options), may be NULL. */
    rt_status (*trace)(rt_scene *scene, const rt_prepared *prep, const char *device,
                       const char *device_options, const rt_ray_d *rays, size_t count,
                       rt_hit_d *hits, int any_hit);
    /* 1 when some device exists; else 0 and a reason in msg. */
    int (*available)(char *msg, size_t msg_size);
    void (*state_free)(void *state);
} rt_backend_ops;

#if defined(__GNUC__) || defined(__clang__)
extern const rt_backend_ops rt_opencl_backend __attribute__((weak));
#define RT_OPENCL_OPS (&rt_opencl_backend)
#else
#define RT_OPENCL_OPS ((const rt_backend_ops *)0)
#endif

/* Splits "name:device" (device after the first ':'); name is copied into
 * name_out. Returns the device part or NULL. */
const char *rt_backend_split(const char *backend, char *name_out, size_t name_size);

/* The packet backend's wide BVHs of prep's layout, built when the layout
 * changed (the time goes to prep->build_ms). */
rt_status rt_render_wide(rt_scene *scene, rt_prepared *prep, const rt_pk_wide **out);

/* The backend rt_trace_rays uses (a name as rt_render takes it). */
rt_status rt_trace_backend(rt_scene *scene, const char *backend, int *packet,
                           const rt_backend_ops **device_ops, const char **device);

/* A shallow copy of flat whose header selects triangle test 'test' (the
 * arrays stay shared); an unknown test is an invalid argument. */
rt_status rt_flat_with_tri_test(rt_scene *scene, const rt_flat *flat, rt_triangle_test test,
                                rt_flat *out);

#endif /* RT_RENDER_INTERNAL_H */
