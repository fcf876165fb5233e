// SPDX-License-Identifier: Apache-2.0
/* cl_program_cache.c - see cl_program_cache.h. */
#include "opencl/cl_program_cache.h"

#include <stdlib.h>
#include <string.h>

#include "rt.h"

void rt_cl_cache_open(rt_cl_cache *c, const rt_cl_device_info *dev, cl_uint count,
                      const char *const *sources, const char *options) {
    if (!rt_kc_folder(c->dir, sizeof c->dir)) c->dir[0] = '\0';
    rt_kc_key_init(&c->key);
    rt_kc_key_add_str(&c->key, "opencl program");
    rt_kc_key_add_str(&c->key, rt_version());
    rt_kc_key_add_str(&c->key, dev->platform);
    rt_kc_key_add_str(&c->key, dev->version); /* the device's OpenCL version and driver string */
    rt_kc_key_add_str(&c->key, dev->name);
    rt_kc_key_add_str(&c->key, dev->vendor);
    rt_kc_key_add_str(&c->key, dev->driver);
    rt_kc_key_add_str(&c->key, options);
    rt_kc_key_add(&c->key, &count, sizeof count);
    for (cl_uint i = 0; i < count; i++) rt_kc_key_add_str(&c->key, sources[i]);
    /* The platform's version is not in rt_cl_device_info: asked here. */
    char pver[256] = "";
    clGetPlatformInfo((cl_platform_id)dev->platform_id, CL_PLATFORM_VERSION, sizeof pver - 1, pver,
                      NULL);
    pver[sizeof pver - 1] = '\0';
    rt_kc_key_add_str(&c->key, pver);
}

cl_program rt_cl_cache_load(const rt_cl_cache *c, cl_context ctx, cl_device_id device,
                            const char *options) {
    size_t size;
    unsigned char *bin = rt_kc_load(c->dir, "cl", &c->key, &size);
    if (!bin) return NULL;
    const unsigned char *bins[1] = {bin};
    cl_int status = CL_SUCCESS, ce;
    cl_program p = clCreateProgramWithBinary(ctx, 1, &device, &size, bins, &status, &ce);
    free(bin);
    if (p && (ce != CL_SUCCESS || status != CL_SUCCESS ||
              clBuildProgram(p, 1, &device, options, NULL, NULL) != CL_SUCCESS)) {
        clReleaseProgram(p);
        p = NULL;
    }
    if (!p) rt_cl_cache_forget(c);
    return p;
}

void rt_cl_cache_store(const rt_cl_cache *c, cl_program program) {
    if (!c->dir[0]) return;
    size_t size = 0;
    if (clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, NULL) !=
            CL_SUCCESS ||
        !size)
        return;
    unsigned char *bin = malloc(size);
    if (!bin) return;
    unsigned char *bins[1] = {bin};
    if (clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof bins, bins, NULL) == CL_SUCCESS)
        rt_kc_save(c->dir, "cl", &c->key, bin, size);
    free(bin);
}

void rt_cl_cache_forget(const rt_cl_cache *c) {
    rt_kc_remove(c->dir, "cl", &c->key);
}
