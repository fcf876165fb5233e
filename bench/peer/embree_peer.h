/* SPDX-License-Identifier: Apache-2.0 */
/* embree_peer.h - Embree as a peer in benchmarks (only when CMake found it:
 * RT_HAVE_EMBREE=1).
 *
 * Two reference points: Embree's own BVH builder through rtcBuildBVH, set up
 * like ours (binary, the same leaf size and costs) and converted into an
 * rt_bvh so that rt_bvh_measure judges both trees the same way; and the time
 * of rtcCommitScene for one triangle geometry, Embree's full production path.
 */
#ifndef RT_EMBREE_PEER_H
#define RT_EMBREE_PEER_H

#include <stddef.h>
#include <stdint.h>

#include "accel/bvh.h"
#include "layout/flat.h"
#include "base/thread_pool.h"

/* The peer's errors: "embree: WHAT (error N)", N from the device if any. */
rt_status rt_embree_fail(rt_error *err, rt_status st, const char *what, void *device);

typedef struct rt_embree rt_embree;

/* A device with the given thread count (<= 0: Embree's default, all cores). */
rt_status rt_embree_create(int threads, rt_embree **out, rt_error *err);
void rt_embree_destroy(rt_embree *em);

/* rtcBuildBVH at RTC_BUILD_QUALITY_MEDIUM, branching factor 2, leaf size
 * options->leaf_size, traversal cost options->costs.traverse and intersection cost
 * options->costs.intersect. *ms is the time of rtcBuildBVH alone (the copy of the
 * build primitives, which Embree consumes, and the conversion into *out are
 * not timed). */
rt_status rt_embree_build_bvh(rt_embree *em, const rt_aabb *boxes, uint32_t count,
                              const rt_build_options *options, rt_bvh *out, double *ms,
                              rt_error *err);

/* Time of rtcCommitScene for one triangle geometry (3 floats per vertex, 3
 * indices per triangle) at low (quality 0) or medium (quality 1) build
 * quality. Buffer setup is not timed. */
rt_status rt_embree_commit_ms(rt_embree *em, const float *positions, uint32_t vertex_count,
                              const uint32_t *indices, uint32_t triangle_count, int quality,
                              double *ms, rt_error *err);

/* What Embree holds for one triangle geometry sharing the caller's arrays
 * (embree_memory.c): *held, the bytes its device has allocated once
 * rtcCommitScene returned (BVH and primitive data; the shared arrays are
 * not Embree's), and *peak, the most it held during the build, both from
 * its memory monitor callback. quality: 0 low, 1 medium (Embree's
 * default), 2 high; compact: RTC_SCENE_FLAG_COMPACT. positions must be
 * readable 4 bytes past the last vertex (Embree loads 16 bytes). */
rt_status rt_embree_memory(const float *positions, uint32_t vertex_count, const uint32_t *indices,
                           uint32_t triangle_count, int threads, int quality, int compact,
                           uint64_t *held, uint64_t *peak, rt_error *err);

/* The RTCDevice (as void *, so that this header needs no Embree header). */
void *rt_embree_device(rt_embree *em);

/* ---- tracing: the benchmark frame (embree_trace.c) ------------------------ */

typedef struct rt_embree_scene rt_embree_scene;

/* An Embree scene of the layout's triangles: one triangle geometry per
 * instance, transformed into world space (no Embree instancing: the peer's
 * fastest case), committed at Embree's default (medium) quality. flat must
 * outlive the scene. *ms: the whole set-up, rtcCommitScene included. */
rt_status rt_embree_scene_create(rt_embree *em, const rt_flat *flat, rt_embree_scene **out,
                                 double *ms, rt_error *err);
void rt_embree_scene_destroy(rt_embree_scene *es);

/* One frame of the thesis set-up, as rt_render with direct_only renders it:
 * the camera's primary rays (rt_camera_ray) through rtcIntersect1 (lanes 1)
 * or packets of 2x2 (4), 4x2 (8) or 4x4 (16) pixels through rtcIntersect4/8/16,
 * then per light the shadow rays of rt_phong (same origin offset, same
 * t range) through rtcOccluded1/4/8/16, then the same Phong terms. Rows of
 * blocks are shared among the pool's workers. rgb (width x height x 3) may
 * be NULL. *rays counts primary plus shadow rays; *ms is the frame's wall
 * time. */
rt_status rt_embree_render(const rt_embree_scene *es, int lanes, rt_pool *pool, float *rgb,
                           uint64_t *rays, double *ms);

/* The rays rays[0 .. n-1] as ray queries: closest hits through
 * rtcIntersect1 (lanes 1) or rtcIntersect4/8/16 on consecutive rays (lanes
 * 4, 8, 16: Embree's packets as streams of incoherent rays), or for any_hit
 * rtcOccluded1/4/8/16 (then only whether hits[i].prim != RT_NO_HIT is
 * set), with Embree's incoherent-ray hint, chunks of rays shared among the
 * pool's workers. *ms is the wall time of the whole. */
rt_status rt_embree_trace_rays(const rt_embree_scene *es, const rt_ray *rays, size_t n, int any_hit,
                               int lanes, rt_pool *pool, rt_hit_d *hits, double *ms);

/* Does the device trace packets of this width natively (1 always)? */
int rt_embree_native_lanes(rt_embree *em, int lanes);

/* Instance inst of flat's triangles in world space, three vertices (9
 * floats) each, to out: the vertex data of the peer's per-instance
 * geometries (embree_trace.c, embree_anim.c). */
void rt_embree_stage_instance(const rt_flat *flat, uint32_t inst, float *out);

/* ---- deforming geometry: the peer of the update policies (embree_dynamic.c) -- */

typedef struct rt_embree_dynamic rt_embree_dynamic;

enum { RT_EMBREE_REFIT = 0, RT_EMBREE_LOW = 1, RT_EMBREE_MEDIUM = 2 };

/* A dynamic scene (RTC_SCENE_FLAG_DYNAMIC) of one triangle geometry whose
 * build quality is REFIT, LOW (Morton) or MEDIUM (binned SAH), the scene's
 * LOW for the first two and MEDIUM for the last; *ms is the first commit. */
rt_status rt_embree_dynamic_create(rt_embree *em, const float *positions, uint32_t vertex_count,
                                   const uint32_t *indices, uint32_t triangle_count, int quality,
                                   rt_embree_dynamic **out, double *ms, rt_error *err);

/* New positions (same count): *ms times rtcUpdateGeometryBuffer,
 * rtcCommitGeometry and rtcCommitScene (not the copy into Embree's buffer). */
rt_status rt_embree_dynamic_update(rt_embree_dynamic *d, const float *positions, double *ms,
                                   rt_error *err);
void rt_embree_dynamic_destroy(rt_embree_dynamic *d);

/* rt_embree_build_bvh at quality RT_EMBREE_LOW (rtcBuildBVH's Morton
 * builder) or RT_EMBREE_MEDIUM (its binned SAH builder, as
 * rt_embree_build_bvh): the trees Embree's commits of those qualities are
 * made by, as binary trees our measures read (embree_build.c). */
rt_status rt_embree_build_bvh_quality(rt_embree *em, const rt_aabb *boxes, uint32_t count,
                                      const rt_build_options *options, int quality, rt_bvh *out,
                                      double *ms, rt_error *err);

/* ---- a traced scene that changes per frame (embree_anim.c) ----------------- */

typedef struct rt_embree_anim rt_embree_anim;

/* The layout's instances in world space, one triangle geometry each (as
 * rt_embree_scene_create), in a dynamic scene (RTC_SCENE_FLAG_DYNAMIC)
 * where every geometry has build quality REFIT, LOW (Morton) or MEDIUM
 * (binned SAH) by quality (RT_EMBREE_*), the scene LOW for the first two and
 * MEDIUM for the last. flat must stay valid until the next update. *ms: the
 * first rtcCommitScene. */
rt_status rt_embree_anim_create(rt_embree *em, const rt_flat *flat, int quality,
                                rt_embree_anim **out, double *ms, rt_error *err);

/* The next frame's layout (the same instances; a triangle count may
 * change). Instances whose world-space triangles changed are written into
 * Embree's buffers and committed. Not timed: computing the world-space
 * triangles and which changed. *copy_ms: the copy into Embree's buffers;
 * *commit_ms: rtcUpdateGeometryBuffer and rtcCommitGeometry of the changed
 * geometries and rtcCommitScene. */
rt_status rt_embree_anim_update(rt_embree_anim *a, const rt_flat *flat, double *copy_ms,
                                double *commit_ms, rt_error *err);

/* The scene to trace (rt_embree_render), valid until the next update. */
const rt_embree_scene *rt_embree_anim_scene(const rt_embree_anim *a);
void rt_embree_anim_destroy(rt_embree_anim *a);

#endif /* RT_EMBREE_PEER_H */
