/* SPDX-License-Identifier: Apache-2.0 */
/* kernel_maths.h - the shared maths of kernels/ (the scalar oracle, which is
 * also the OpenCL C the devices compile) as the CPU backends use it: ray
 * set-up, box and triangle tests, hit order and acceptance, traversal,
 * shading, the denormal mode. The one place cpu_ref/ includes kernels
 * headers, so that a change to how kernels/ splits its files touches only
 * this file. */
#ifndef RT_KERNEL_MATHS_H
#define RT_KERNEL_MATHS_H

#include "rt_fp_mode.h"
#include "rt_shade.h"
#include "rt_shared.h"

#endif /* RT_KERNEL_MATHS_H */
