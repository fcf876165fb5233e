/* SPDX-License-Identifier: Apache-2.0 */
/* accel_cache.h - the acceleration structures a renderer keeps for a scene
 * between frames: one BVH per mesh (updated only when the mesh changed, by
 * the mesh's update policy: rebuilt, refitted or built by the LBVH), the
 * object BVH over the instances (rebuilt whenever the scene changed: objects
 * move), and the flattened layout that backends read (rewritten in place
 * where only boxes and vertices moved).
 *
 * The stages run one way: scene -> accel (host/accel/) -> layout
 * (host/layout/) -> backend. This cache is the renderer's memory of the
 * first two steps; the scene knows nothing of it. */
#ifndef RT_ACCEL_CACHE_H
#define RT_ACCEL_CACHE_H

#include <stdint.h>

#include "accel/bvh.h"
#include "accel/kd.h"
#include "accel/bvh_refit.h"
#include "base/thread_pool.h"
#include "layout/flat.h"
#include "layout/flatten.h"
#include "scene/scene.h"

typedef struct rt_accel_cache {
    uint64_t scene_uid; /* the scene these structures belong to (0: none) */
    uint32_t mesh_count;
    rt_bvh *bvhs;             /* per mesh (one root box where the mesh has a kd-tree) */
    rt_kd *kds;               /* per mesh (empty where the mesh has a BVH) */
    uint32_t *built_version;  /* the mesh version its structure was made from */
    uint32_t *built_topology; /* ... and its topology version */
    uint8_t *built;
    uint8_t *dirty; /* its BVH or vertices changed since the layout was made */
    /* 1: the mesh is static and its tree lives only in the layout (its BVH
     * keeps the root node, for the object BVH); rt_accel_cache_unpark
     * copies it back out when the layout is to be made anew. One copy of a
     * static mesh's tree instead of two (issue 31). */
    uint8_t *parked;
    double *sah;              /* per mesh: its BVH's SAH cost, measured at each update */
    double *sah_rebuilt;      /* ... at its last SAH build (the "auto" policy's reference) */
    rt_bvh_refit_info *refit; /* per mesh: the tree's shape, made at the first refit */
    rt_mesh_update *updates;  /* the last frame's updates */
    uint32_t update_count;
    rt_aabb *boxes; /* scratch: triangle boxes */
    size_t boxes_cap;
    rt_bvh top; /* the object BVH */
    rt_flat flat;
    rt_flat_shape shape; /* what flat was made of, to know when it can be rewritten in place */
    int flat_valid;
    uint32_t flat_scene_version;  /* the scene version flat was made from */
    uint32_t flat_camera_version; /* ... and the camera version its header holds */
    uint32_t layout_generation;   /* bumped by every change of flat */
    uint32_t mesh_generation;     /* bumped by every mesh BVH update */
    /* After an in-place rewrite: what changed since generation base_generation. */
    uint32_t base_generation;
    rt_flat_range *dirty_nodes, *dirty_tris;
    uint32_t dirty_node_ranges, dirty_tri_ranges;
    int shapes_kept; /* ... and no mesh tree changed shape */
    double object_bvh_ms, layout_ms;
    int layout_in_place;
    int camera_only; /* the last update rewrote only the header's camera */
    uint64_t layout_bytes;
} rt_accel_cache;

/* Brings the cache up to date with scene (whose queued transforms must be
 * applied): updates the structures of meshes that changed (a BVH by its
 * update policy; a kd-tree, for static meshes only, is rebuilt whole), the
 * object BVH and the layout when the scene changed (a layout with kd-tree
 * meshes is always made anew). When only the camera changed (its own
 * version), only the header's camera is rewritten: no BVH is touched and
 * layout_generation stays, so backends keep every array and send the header
 * alone. A scene other than the cached one starts
 * afresh. *build_ms gets the time spent, *sah_cost the triangle-weighted mean
 * SAH cost of the shown meshes' structures. */
rt_status rt_accel_cache_update(rt_accel_cache *cache, const rt_scene *scene, rt_pool *pool,
                                double *build_ms, double *sah_cost, rt_error *err);

/* Gives every parked mesh its whole BVH again, copied out of the layout
 * (the tree it was flattened from, bit for bit). RT_ERROR_OUT_OF_MEMORY on
 * failure. For a layout to be made anew, and for tests that flatten the
 * cache's BVHs themselves. */
rt_status rt_accel_cache_unpark(rt_accel_cache *cache);

/* The bytes the cache holds, by part (rt_memory_stats's mesh_bvhs,
 * object_bvh, kept, layout and triangles). */
void rt_accel_cache_memory(const rt_accel_cache *cache, rt_memory_stats *out);

/* Frees everything; the cache is then empty (and may be used again). */
void rt_accel_cache_clear(rt_accel_cache *cache);

#endif /* RT_ACCEL_CACHE_H */
