/* SPDX-License-Identifier: Apache-2.0 */
/* device_list.c - the devices of each device backend in rt.h's one form
 * (rt_device_info), from the backends' own listings (opencl/cl_device.h,
 * vulkan/vk_device.h), so that programs list devices through rt.h alone.
 * The registry (backend_registry.c) hands each backend its lister. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "render/device_list.h"
#ifdef RT_HAVE_OPENCL
#include "opencl/cl_device.h"
#endif
#ifdef RT_HAVE_VULKAN
#include "vulkan/vk_device.h"
#endif

#if defined(RT_HAVE_OPENCL) || defined(RT_HAVE_VULKAN)
#define COPY(dst, src) snprintf((dst), sizeof(dst), "%s", (src))

/* A device record with every field "not reported". */
static void blank(rt_device_info *d, const char *backend, int index) {
    memset(d, 0, sizeof *d);
    COPY(d->backend, backend);
    d->index = index;
    d->platform_index = -1;
    d->cr_div_sqrt = d->fma = d->fp64 = d->timestamps = d->float_controls = -1;
}

/* The list of count devices (or the one at only, when only >= 0) as
 * rt_device_info, each filled by fill(d, i) after blank(); frees devs. */
static rt_status convert(void *devs, int count, int only,
                         void (*fill)(rt_device_info *, const void *, int), rt_device_info **out,
                         int *out_count, rt_error *err) {
    rt_device_info *list = calloc((size_t)(count ? count : 1), sizeof *list);
    if (!list) {
        free(devs);
        return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory listing devices");
    }
    int k = 0;
    for (int i = 0; i < count; i++)
        if (only < 0 || i == only) fill(&list[k++], devs, i);
    free(devs);
    *out = list;
    *out_count = k;
    return RT_OK;
}

/* The status of a failed selection (the backend's select filled err). */
static rt_status select_failed(void *devs, const rt_error *err) {
    free(devs);
    return err && err->status ? err->status : RT_ERROR_INVALID_ARGUMENT;
}

#endif

#ifdef RT_HAVE_OPENCL
static void opencl_fill(rt_device_info *d, const void *list, int i) {
    const rt_cl_device_info *c = (const rt_cl_device_info *)list + i;
    blank(d, "opencl", c->index);
    COPY(d->name, c->name);
    d->platform_index = c->platform_index;
    COPY(d->platform, c->platform);
    COPY(d->vendor, c->vendor);
    COPY(d->type, c->cpu ? "CPU" : "not a CPU");
    COPY(d->version, c->version);
    COPY(d->driver, c->driver);
    d->compute_units = c->compute_units;
    d->memory = c->global_mem;
    d->max_buffer = c->max_alloc;
    d->cr_div_sqrt = c->cr_div_sqrt;
    d->fma = c->fma;
    d->fp64 = c->fp64;
    rt_cl_math_plan keep = rt_cl_plan_math(c, RT_DEVICE_MATH_AUTO, 0);
    rt_cl_math_plan flush = rt_cl_plan_math(c, RT_DEVICE_MATH_AUTO, 1);
    COPY(d->math_profile, keep.portable ? "portable" : "native");
    d->exact = keep.exact;
    COPY(d->exact_note, keep.note);
    d->exact_flush = flush.exact;
    COPY(d->exact_flush_note, flush.note);
    COPY(d->denormals_note, rt_cl_denormals_note(c));
    COPY(d->kernels_note, rt_cl_kernels_note(c));
}

rt_status rt_opencl_device_list(const char *selector, rt_device_info **out, int *count,
                                rt_error *err) {
    rt_cl_device_info *devs;
    int n, only = -1;
    rt_status st = rt_cl_devices(&devs, &n, err);
    if (st != RT_OK) return st;
    if (selector && (only = rt_cl_select(devs, n, selector, err)) < 0)
        return select_failed(devs, err);
    return convert(devs, n, only, opencl_fill, out, count, err);
}
#endif

#ifdef RT_HAVE_VULKAN
static void vulkan_fill(rt_device_info *d, const void *list, int i) {
    const rt_vk_device_info *v = (const rt_vk_device_info *)list + i;
    blank(d, "vulkan", v->index);
    COPY(d->name, v->name);
    COPY(d->type, v->type);
    COPY(d->version, v->api);
    COPY(d->driver, v->driver);
    d->memory = v->memory;
    d->max_buffer = v->max_buffer;
    d->timestamps = v->timestamps;
    d->float_controls = v->float_controls;
    d->rte = v->rte;
    d->denorm_preserve = v->denorm_preserve;
    d->denorm_flush = v->denorm_flush;
    d->signed_zero_inf_nan = v->signed_zero_inf_nan;
    /* The shaders always run the portable profile (docs/VULKAN.md). */
    COPY(d->math_profile, "portable");
    d->exact = v->exact;
    COPY(d->exact_note, rt_vk_exactness_note(v, 0));
    d->exact_flush = v->exact_flush;
    COPY(d->exact_flush_note, rt_vk_exactness_note(v, 1));
}

rt_status rt_vulkan_device_list(const char *selector, rt_device_info **out, int *count,
                                rt_error *err) {
    rt_vk_device_info *devs;
    int n, only = -1;
    rt_status st = rt_vk_devices(&devs, &n, err);
    if (st != RT_OK) return st;
    if (selector && (only = rt_vk_select(devs, n, selector, err)) < 0)
        return select_failed(devs, err);
    return convert(devs, n, only, vulkan_fill, out, count, err);
}
#endif
