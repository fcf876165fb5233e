// SPDX-License-Identifier: Apache-2.0
/* cl_program_cache.h - OpenCL program binaries kept on disk
 * (base/kernel_cache.h), so that a run after the first loads the kernels
 * instead of compiling them.
 *
 * The key is every input of the build: the whole source text, the build
 * options, the device's name and driver version, the platform's name and
 * version, and this library's version. A binary is the driver's own output
 * for those inputs, so the kernels it gives compute the same bits as a build
 * from source. A binary the driver refuses (clCreateProgramWithBinary or
 * clBuildProgram fails) is deleted and the caller builds from source. */
#ifndef RT_CL_PROGRAM_CACHE_H
#define RT_CL_PROGRAM_CACHE_H

#include <CL/cl.h>

#include "base/kernel_cache.h"
#include "opencl/cl_device.h"

typedef struct rt_cl_cache {
    char dir[4096]; /* the cache folder; "" when the cache is off or unusable */
    rt_kc_key key;
} rt_cl_cache;

/* Finds the folder and makes the key of a build of count sources with
 * options on dev. */
void rt_cl_cache_open(rt_cl_cache *c, const rt_cl_device_info *dev, cl_uint count,
                      const char *const *sources, const char *options);

/* The program built from the cached binary, or NULL (no entry, a damaged
 * one, or one the driver refuses: then it is deleted). */
cl_program rt_cl_cache_load(const rt_cl_cache *c, cl_context ctx, cl_device_id device,
                            const char *options);

/* Saves the binary of a program built (and best after its kernels ran once:
 * a driver such as PoCL then includes their machine code). Silent on
 * failure. */
void rt_cl_cache_store(const rt_cl_cache *c, cl_program program);

/* Deletes the entry (a cached program whose kernels could not be made). */
void rt_cl_cache_forget(const rt_cl_cache *c);

#endif /* RT_CL_PROGRAM_CACHE_H */
