/* SPDX-License-Identifier: Apache-2.0 */
/* backend_registry.h - every backend the renderer knows, by name: those this
 * build has, and those it lacks with the reason (host/render/backend_registry.c). */
#ifndef RT_BACKEND_REGISTRY_H
#define RT_BACKEND_REGISTRY_H

#include <stddef.h>

#include "backend/backend.h"

/* The backend called name ("cpu", "packet", "opencl", ...). NULL when the
 * build lacks it or the name is unknown; the reason is then in err
 * (RT_ERROR_UNSUPPORTED). */
const rt_backend_ops *rt_backend_find(const char *name, rt_error *err);

/* The first device backend (in the registry's order) that this build has and
 * that finds a device here; NULL, with the reasons in why, when none does. */
const rt_backend_ops *rt_backend_auto(rt_error *why);

/* Whether a backend selects a device ("opencl:1"). */
int rt_backend_takes_device(const rt_backend_ops *ops);

/* The backends of this build, for messages: "cpu, packet, opencl[:DEVICE]". */
void rt_backend_names(char *out, size_t size);

#endif /* RT_BACKEND_REGISTRY_H */
