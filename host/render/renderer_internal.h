/* SPDX-License-Identifier: Apache-2.0 */
/* renderer_internal.h - the renderer's state (rt.h's rt_renderer), for the
 * files of host/render/ and for programs that look inside (the benchmark's
 * Embree peer traces the renderer's layout; tests check it). */
#ifndef RT_RENDERER_INTERNAL_H
#define RT_RENDERER_INTERNAL_H

#include "backend/backend.h"
#include "render/accel_cache.h"
#include "scene/scene.h"

/* A backend the renderer made, with its state: kept when the renderer
 * switches away, so that switching back costs nothing. */
typedef struct rt_backend_slot {
    char spec[160]; /* "opencl:1": the name and device it was made for */
    const rt_backend_ops *ops;
    void *state;
} rt_backend_slot;

enum { RT_RENDERER_SLOTS = 8 };

struct rt_renderer {
    int threads; /* as asked (<= 0: all cores) */
    rt_pool *pool;
    char device_options[256];
    char packet_isa[32];
    rt_opencl_tuning opencl;
    rt_device_math device_math;
    rt_denormals denormals;
    void (*on_compile)(void *user, const char *backend, const char *device, const char *cache_dir);
    void *on_compile_user;
    rt_accel_cache accel;
    rt_backend_slot slots[RT_RENDERER_SLOTS];
    int slot_count;
    int current;      /* the slot that renders */
    char notice[512]; /* why "auto" fell back to the CPU (every device backend's reason), or "" */
    rt_error error;   /* the last error */
};

/* The frame's layout for scene: queued transforms applied, BVHs and layout
 * brought up to date (*build_ms, *sah_cost: as rt_accel_cache_update). The
 * layout stays valid until the next call with this renderer. */
rt_status rt_renderer_layout(rt_renderer *r, rt_scene *scene, rt_backend_layout *out,
                             double *build_ms, double *sah_cost);

/* The current backend with its state. */
const rt_backend_slot *rt_renderer_slot(const rt_renderer *r);

#endif /* RT_RENDERER_INTERNAL_H */
