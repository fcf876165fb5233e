/* SPDX-License-Identifier: Apache-2.0 */
/* cl_backend.h - the OpenCL backend (host/backend/backend.h), built where the
 * build found the OpenCL ICD loader (RT_HAVE_OPENCL). */
#ifndef RT_CL_BACKEND_H
#define RT_CL_BACKEND_H

#include "backend/backend.h"

extern const rt_backend_ops rt_backend_opencl;

#endif /* RT_CL_BACKEND_H */
