/* SPDX-License-Identifier: Apache-2.0 */
/* ray_sets.h - reproducible sets of incoherent rays over a layout, for the
 * tests and benchmarks of the single-ray tracer (and the Embree peer beside
 * it): random rays inside the scene, and diffuse bounces from the closest
 * hits of the camera's rays. */
#ifndef RT_RAY_SETS_H
#define RT_RAY_SETS_H

#include <stddef.h>
#include <stdint.h>

#include "layout/flat.h"
#include "rt.h"

/* n rays with origins uniform in the scene's bounding box and directions
 * uniform on the sphere, t in [0, inf]; the same seed gives the same rays.
 * A scene without triangles gets rays from the unit cube. */
void rt_rays_random(const rt_flat *flat, uint32_t seed, size_t n, rt_ray *out);

/* n diffuse bounces: the camera ray through a random pixel, its closest hit
 * (the scalar oracle), and from there a cosine-distributed direction about
 * the geometric normal on the side the camera ray came from, the origin
 * moved off the surface as the renderer moves secondary rays' origins
 * (rt_offset_point), t in [0, inf]. Pixels whose camera ray misses are drawn
 * again (up to 64 times, then a random ray of rt_rays_random takes the
 * place). */
void rt_rays_diffuse(const rt_flat *flat, uint32_t seed, size_t n, rt_ray *out);

/* Whether two answers of rt_trace_rays are the same bit for bit: the hit
 * flag, and for a closest hit t, u, v (bits), prim and inst (any: the flag
 * alone, as any-hit queries promise no particular hit). */
int rt_api_hits_same(const rt_hit *a, const rt_hit *b, int any);

#endif /* RT_RAY_SETS_H */
