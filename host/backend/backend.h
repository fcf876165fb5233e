/* SPDX-License-Identifier: Apache-2.0 */
/* backend.h - the one interface every backend implements (cpu, packet,
 * opencl; vulkan next), and all that a backend sees of a scene.
 *
 * A backend gets the flattened layout (layout/flat.h) and never the scene's
 * structs, so every backend traces exactly the same bytes, and a backend can
 * be written, tested and replaced without knowing how scenes are stored. It
 * reports a failure as a status and a message in the rt_error it is given;
 * the renderer forwards it to the caller.
 *
 * Lifetime: the renderer calls create once, when the backend is first
 * chosen; then per frame prepare (bring the backend's copy of the layout up
 * to date: a device uploads what changed, the packet backend widens the
 * BVHs) followed by render or trace; destroy when the renderer goes. State
 * is the backend's own; nothing is global.
 *
 * Adding a backend: a folder host/NAME/ with one rt_backend_ops, a line in
 * host/render/backend_registry.c, and its sources in CMakeLists.txt
 * (docs/ARCHITECTURE.md). */
#ifndef RT_BACKEND_H
#define RT_BACKEND_H

#include <stddef.h>
#include <stdint.h>

#include "base/thread_pool.h"
#include "layout/flat.h"
#include "rt.h"

/* What a backend is made with (from rt_renderer_options). */
typedef struct rt_backend_config {
    const char *device;         /* the part after "name:" (NULL: the default device) */
    const char *device_options; /* extra kernel compiler options (at most 255 characters:
                                   the renderer refuses longer ones), or NULL */
    const char *packet_isa;     /* the packet backend's instruction set, or NULL */
    rt_opencl_tuning opencl;
    rt_device_math device_math;
    int flush_denormals; /* rt_denormals: 1 for RT_DENORMALS_FLUSH */
    /* rt_renderer_options.on_compile (NULL: none): called before a kernel
     * build from source, never on a cached binary. */
    void (*on_compile)(void *user, const char *backend, const char *device, const char *cache_dir);
    void *on_compile_user;
} rt_backend_config;

/* The layout of the frame and what changed since the backend last saw one. */
typedef struct rt_backend_layout {
    /* The header selects this frame's triangle test and features (a
     * direct-only frame clears RT_SCENE_SECONDARY); the arrays are shared. */
    const rt_flat *flat;
    rt_pool *pool; /* the renderer's workers: the CPU backends run on them */
    /* Counters that change whenever the layout was remade, and whenever some
     * mesh BVH was rebuilt (then the mesh part of the layout moved too). */
    uint32_t layout_generation;
    uint32_t mesh_generation;
    /* When the layout was rewritten in place from generation base_generation
     * (0: made anew), what changed since: node ranges (the updated meshes'
     * and the object BVH's) and triangle ranges (the updated meshes'; their
     * tris and normals entries, and their tri_ids and materials unless the
     * range says only the vertices moved). Instances, materials,
     * lights and the header are rewritten every time. A backend holding
     * generation base_generation may copy only these. */
    uint32_t base_generation;
    const rt_flat_range *dirty_nodes;
    uint32_t dirty_node_ranges;
    const rt_flat_range *dirty_tris;
    uint32_t dirty_tri_ranges;
    /* 1 when, besides, every mesh tree kept its shape (it was refitted, not
     * rebuilt): structures derived from the mesh trees can be refitted too. */
    int shapes_kept;
} rt_backend_layout;

/* One frame's request. pixels is width x height x channels floats of the
 * layout's camera, allocated by the renderer; every pixel is written. */
typedef struct rt_backend_frame {
    rt_aov aov;
    int channels; /* 3 for the image and normals, else 1 */
    float *pixels;
    int want_counts; /* 1: fill the ray and test counts of the statistics */
    void (*progress)(void *user, double done);
    void *progress_user;
} rt_backend_frame;

typedef struct rt_backend_ops {
    const char *name;
    /* 1 when the backend can run on this machine; else 0 with the reason in
     * *why (NULL allowed). Called for "auto"; cheap enough for a listing. */
    int (*available)(rt_error *why);
    rt_status (*create)(const rt_backend_config *config, void **state, rt_error *err);
    /* Brings the backend's copy of the layout up to date and opens the
     * device. Adds to stats: build_ms (host work such as wide BVHs),
     * compile_ms, upload_ms and upload_bytes, and the device fields. */
    rt_status (*prepare)(void *state, const rt_backend_layout *layout, rt_render_stats *stats,
                         rt_error *err);
    /* Renders one frame after prepare. Fills render_ms, the counts when
     * frame->want_counts, and the backend's own statistics fields. */
    rt_status (*render)(void *state, const rt_backend_layout *layout, const rt_backend_frame *frame,
                        rt_render_stats *stats, rt_error *err);
    /* Traces count rays (closest hit, or any hit) after prepare; a miss has
     * prim = RT_NO_HIT. Invalid rays were made empty ranges by the caller.
     * path is the caller's rt_trace_options.packet_path (the packet
     * backend's; others ignore it). masks: ray i's mask masks[i]
     * (rt_trace_masked in kernels/rt_trace.h), or NULL for 0xffffffff on
     * every ray. Adds to stats (zeroed by the caller) build_ms for host
     * builds it did, and the packet backend packet_rays, single_rays and
     * isa. */
    rt_status (*trace)(void *state, const rt_backend_layout *layout, const rt_ray *rays,
                       const uint32_t *masks, size_t count, rt_hit_d *hits, int any_hit,
                       rt_trace_path path, rt_trace_stats *stats, rt_error *err);
    void (*destroy)(void *state);
    /* The device compiler's messages of the last program build: its log, then
     * what the driver printed on stderr meanwhile (the library keeps that off
     * the terminal); "" when none. NULL for backends that compile nothing. */
    const char *(*build_log)(void *state);
    /* The bytes the backend holds between frames (rt_renderer_memory): its
     * host copies (the packet backend's wide BVHs) and device memory. NULL
     * for a backend that keeps no copy of its own. */
    void (*memory)(void *state, uint64_t *host_bytes, uint64_t *device_bytes);
} rt_backend_ops;

#endif /* RT_BACKEND_H */
