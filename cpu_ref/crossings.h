/* SPDX-License-Identifier: Apache-2.0 */
/* crossings.h - how many triangles each ray crosses (rt.h's
 * rt_count_intersections), over the flattened layout with the oracle's
 * shared maths: every hit of the watertight test in the ray's range that
 * the acceptance rule accepts (rt_hit_accepted), each triangle once, and a
 * tie rule for rays exactly through edges and vertices that makes a closed
 * mesh's crossings come in the right parity (crossings.c says why). */
#ifndef RT_CROSSINGS_H
#define RT_CROSSINGS_H

#include <stddef.h>
#include <stdint.h>

#include "base/error.h"
#include "base/thread_pool.h"
#include "layout/flat.h"
#include "rt.h"

/* Counts the crossings of each of the n rays (all valid: finite, non-zero
 * direction, no NaN end) into counts, on the pool's workers, which flush
 * denormals when flush is 1 (rt_pool_run_fp). RT_ERROR_OUT_OF_MEMORY, with
 * the message in err, when a worker's list of a kd mesh's crossings could
 * not grow; counts is then undefined. */
rt_status rt_count_crossings(rt_pool *pool, int flush, const rt_flat *flat, const rt_ray *rays,
                             size_t n, uint32_t *counts, rt_error *err);

/* One triangle: whether the ray (prepared as p, in the triangle's space)
 * crosses it for t in [r->tmin, r->tmax] by the rules above; *t is then the
 * crossing's t. For the tests. */
int rt_crossing_test(const rt_tri *tri, const rt_ray *r, const rt_ray_pre *p, float *t);

#endif /* RT_CROSSINGS_H */
