/* SPDX-License-Identifier: Apache-2.0 */
/* kernel_maths.h - the shared maths of kernels/ (the scalar oracle, which is
 * also the OpenCL C the devices compile) as the CPU backends use it: ray
 * set-up, box and triangle tests, hit order and acceptance, traversal,
 * shading, the denormal mode. The one place cpu_ref/ includes kernels
 * headers, so that a change to how kernels/ splits its files touches only
 * this file; and the instance entry the single-ray walks share. */
#ifndef RT_KERNEL_MATHS_H
#define RT_KERNEL_MATHS_H

#include "rt_fp_mode.h"
#include "rt_shade.h"
#include "rt_shared.h"

/* A ray entering instance in as rt_trace_instance enters it: its set-up for
 * the mesh in *op (p's for an identity instance, else that of the object-
 * space ray, made in *o) with inst_lo, the instance box's entry distance.
 * Returns the ray in the mesh's space: r itself, or o. */
static inline const rt_ray *rt_cpu_instance_ray(const rt_instance *in, const rt_ray *r,
                                                const rt_ray_pre *p, float inst_lo, rt_ray *o,
                                                rt_ray_pre *op) {
    const rt_ray *ray = r;
    if (RT_INST_FLAGS(in) & RT_INST_IDENTITY) {
        *op = *p;
    } else {
        rt_ray_to_object(in, r, o);
        rt_ray_prepare(o, op);
        ray = o;
    }
    op->inst_lo = inst_lo;
    return ray;
}

#endif /* RT_KERNEL_MATHS_H */
