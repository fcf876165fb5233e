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

#include "bvh.h"

typedef struct rt_embree rt_embree;

/* A device with the given thread count (<= 0: Embree's default, all cores). */
rt_status rt_embree_create(int threads, rt_embree **out, char *msg, size_t msg_size);
void rt_embree_destroy(rt_embree *em);

/* rtcBuildBVH at RTC_BUILD_QUALITY_MEDIUM, branching factor 2, leaf size
 * options->leaf_size, traversal cost options->cost_box and intersection cost
 * options->cost_tri. *ms is the time of rtcBuildBVH alone (the copy of the
 * build primitives, which Embree consumes, and the conversion into *out are
 * not timed). */
rt_status rt_embree_build_bvh(rt_embree *em, const rt_aabb *boxes, uint32_t count,
                              const rt_build_options *options, rt_bvh *out, double *ms, char *msg,
                              size_t msg_size);

/* Time of rtcCommitScene for one triangle geometry (3 floats per vertex, 3
 * indices per triangle) at low (quality 0) or medium (quality 1) build
 * quality. Buffer setup is not timed. */
rt_status rt_embree_commit_ms(rt_embree *em, const float *positions, uint32_t vertex_count,
                              const uint32_t *indices, uint32_t triangle_count, int quality,
                              double *ms, char *msg, size_t msg_size);

#endif /* RT_EMBREE_PEER_H */
