/* SPDX-License-Identifier: Apache-2.0 */
/* cpu_backends.h - the CPU backends as host/backend/backend.h implementations:
 * "cpu" (the scalar oracle) and "packet" (ray packets). */
#ifndef RT_CPU_BACKENDS_H
#define RT_CPU_BACKENDS_H

#include "backend/backend.h"

extern const rt_backend_ops rt_backend_cpu;
extern const rt_backend_ops rt_backend_packet;

#endif /* RT_CPU_BACKENDS_H */
