/* SPDX-License-Identifier: Apache-2.0 */
/* ray_coherence.h - whether a group of rays is coherent enough for the
 * packet tracer, or goes one ray at a time through the single-ray tracer
 * (cpu_ref/single_trace.h). Either path gives the same hits; the measure
 * decides speed only. */
#ifndef RT_RAY_COHERENCE_H
#define RT_RAY_COHERENCE_H

#include <stddef.h>

#include "kernel_maths.h"

/* The widest spread of the group's unit directions over the axes above
 * which a group counts as incoherent (see rt_rays_coherent). */
#define RT_COHERENT_DIR_SPREAD 0.25f

/* Is the group rays[0 .. n-1] coherent: do all directions have the same
 * sign on every axis (as the packet tracer's interval test needs), does no
 * component of the unit directions span more than RT_COHERENT_DIR_SPREAD,
 * and do the origins lie within 'org_span' of each other on every axis?
 * A few operations per ray. Rays with NaN or infinite components make a
 * group incoherent. */
int rt_rays_coherent(const rt_ray *rays, size_t n, float org_span);

#endif /* RT_RAY_COHERENCE_H */
