/* accel_cache.h - the acceleration structures a renderer keeps for a scene
 * between frames: one BVH per mesh (rebuilt only when the mesh changed), the
 * object BVH over the instances (rebuilt whenever the scene changed: objects
 * move), and the flattened layout that backends read.
 *
 * The stages run one way: scene -> accel (host/accel/) -> layout
 * (host/layout/) -> backend. This cache is the renderer's memory of the
 * first two steps; the scene knows nothing of it. */
#ifndef RT_ACCEL_CACHE_H
#define RT_ACCEL_CACHE_H

#include <stdint.h>

#include "accel/bvh.h"
#include "accel/kd.h"
#include "base/thread_pool.h"
#include "layout/flat.h"
#include "scene/scene.h"

typedef struct rt_accel_cache {
    uint64_t scene_uid; /* the scene these structures belong to (0: none) */
    uint32_t mesh_count;
    rt_bvh *bvhs;            /* per mesh (empty where the mesh has a kd-tree) */
    rt_kd *kds;              /* per mesh (empty where the mesh has a BVH) */
    uint32_t *built_version; /* the mesh version its BVH was built from */
    uint8_t *built;
    double *sah; /* per mesh: its BVH's SAH cost, measured once per build */
    rt_bvh top;  /* the object BVH */
    rt_flat flat;
    int flat_valid;
    uint32_t flat_scene_version; /* the scene version flat was made from */
    uint32_t layout_generation;  /* bumped by every flatten */
    uint32_t mesh_generation;    /* bumped by every mesh BVH (re)build */
} rt_accel_cache;

/* Brings the cache up to date with scene (whose queued transforms must be
 * applied): rebuilds the structures (BVH or kd-tree, as each mesh's accel
 * says) of meshes that changed, the object BVH and the
 * layout when the scene changed. A scene other than the cached one starts
 * afresh. *build_ms gets the time spent, *sah_cost the triangle-weighted mean
 * SAH cost of the shown meshes' BVHs. */
rt_status rt_accel_cache_update(rt_accel_cache *cache, const rt_scene *scene, rt_pool *pool,
                                double *build_ms, double *sah_cost, rt_error *err);

/* Frees everything; the cache is then empty (and may be used again). */
void rt_accel_cache_clear(rt_accel_cache *cache);

#endif /* RT_ACCEL_CACHE_H */
