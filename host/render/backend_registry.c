/* SPDX-License-Identifier: Apache-2.0 */
/* backend_registry.c - the one place that lists the backends. A backend is
 * a line here (and its folder and build rule); nothing else names it. A
 * backend the build leaves out keeps a line with the reason, so that asking
 * for it says what to install instead of "unknown". */
#include "render/backend_registry.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "cpu_backends.h"
#include "render/device_list.h"
#ifdef RT_HAVE_OPENCL
#include "opencl/cl_backend.h"
#endif
#ifdef RT_HAVE_VULKAN
#include "vulkan/vk_backend.h"
#endif

typedef struct registry_entry {
    const char *name;
    const rt_backend_ops *ops; /* NULL: not in this build */
    const char *missing;       /* why not */
    int device;                /* a device backend: "auto" tries it, it takes ":DEVICE" */
    const char *summary;       /* what it is, one line (rt_backend_info) */
    /* Its devices (rt_devices): device backends that this build has. */
    rt_status (*devices)(const char *selector, rt_device_info **out, int *count, rt_error *err);
} registry_entry;

#define OPENCL_SUMMARY "OpenCL kernels on a device"
#define VULKAN_SUMMARY "Vulkan compute shaders on a device (always the portable maths)"

static const registry_entry registry[] = {
#ifdef RT_HAVE_OPENCL
    {"opencl", &rt_backend_opencl, NULL, 1, OPENCL_SUMMARY, rt_opencl_device_list},
#else
    {"opencl", NULL,
     "this build has no OpenCL backend (configure with -DRT_OPENCL=ON and the OpenCL ICD loader "
     "installed: ocl-icd-opencl-dev, opencl-c-headers)",
     1, OPENCL_SUMMARY, NULL},
#endif
#ifdef RT_HAVE_VULKAN
    {"vulkan", &rt_backend_vulkan, NULL, 1, VULKAN_SUMMARY, rt_vulkan_device_list},
#else
    {"vulkan", NULL,
     "this build has no Vulkan backend (configure with -DRT_VULKAN=ON and the Vulkan loader and "
     "glslang installed: libvulkan-dev, glslang-tools)",
     1, VULKAN_SUMMARY, NULL},
#endif
    {"cpu", &rt_backend_cpu, NULL, 0, "the scalar CPU oracle, one ray at a time", NULL},
    {"packet", &rt_backend_packet, NULL, 0,
     "SIMD ray packets (and single rays through wide BVHs) on the CPU", NULL},
};
enum { ENTRIES = sizeof registry / sizeof registry[0] };

const rt_backend_ops *rt_backend_find(const char *name, rt_error *err) {
    for (int i = 0; i < ENTRIES; i++) {
        if (strcmp(registry[i].name, name) != 0) continue;
        if (!registry[i].ops) rt_fail(err, RT_ERROR_UNSUPPORTED, "%s", registry[i].missing);
        return registry[i].ops;
    }
    char names[160];
    rt_backend_names(names, sizeof names);
    rt_fail(err, RT_ERROR_UNSUPPORTED, "unknown backend '%s' (this build has: %s, auto)", name,
            names);
    return NULL;
}

const rt_backend_ops *rt_backend_auto(rt_error *why) {
    /* Every device backend's reason, in order: the notice names them all. */
    char reasons[sizeof why->message] = "";
    int devices = 0;
    for (int k = 0; k < ENTRIES; k++) {
        if (!registry[k].device) continue;
        devices++;
        size_t used = strlen(reasons);
        const char *sep = used ? "; " : "";
        if (!registry[k].ops) {
            snprintf(reasons + used, sizeof reasons - used, "%s%s", sep, registry[k].missing);
            continue;
        }
        rt_error reason;
        rt_error_clear(&reason);
        if (registry[k].ops->available(&reason)) return registry[k].ops;
        snprintf(reasons + used, sizeof reasons - used, "%s%s not available (%.400s)", sep,
                 registry[k].name, reason.message);
    }
    if (!devices)
        rt_fail(why, RT_ERROR_UNSUPPORTED, "this build has no device backend");
    else
        rt_fail(why, RT_ERROR_UNSUPPORTED, "%s", reasons);
    return NULL;
}

int rt_backend_takes_device(const rt_backend_ops *ops) {
    for (int k = 0; k < ENTRIES; k++)
        if (registry[k].ops == ops) return registry[k].device;
    return 0;
}

void rt_backend_names(char *out, size_t size) {
    if (!size) return;
    out[0] = 0;
    /* The CPU backends first: they are always there. */
    for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < ENTRIES; k++) {
            if (!registry[k].ops || registry[k].device != pass) continue;
            if (out[0]) strncat(out, ", ", size - strlen(out) - 1);
            strncat(out, registry[k].name, size - strlen(out) - 1);
            if (registry[k].device) strncat(out, "[:DEVICE]", size - strlen(out) - 1);
        }
}

/* "auto" is no backend of its own: it picks the first device backend with a
 * device (rt_backend_auto), else cpu. It is listed last. */
static const rt_backend_info auto_info = {
    "auto", "the first device backend that finds a device (in this order), else cpu with a notice",
    1,      "",
    1,      0};

const char *rt_backend_name(int index) {
    /* As rt_backend_names lists them: the CPU backends first. */
    for (int pass = 0, i = 0; pass < 2; pass++)
        for (int k = 0; k < ENTRIES; k++)
            if (registry[k].device == pass && i++ == index) return registry[k].name;
    return index == ENTRIES ? auto_info.name : NULL;
}

rt_status rt_backend_describe(const char *name, rt_backend_info *out, rt_error *err) {
    if (!name || !out) return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "rt_backend_describe: NULL");
    if (!strcmp(name, auto_info.name)) {
        *out = auto_info;
        return RT_OK;
    }
    for (int k = 0; k < ENTRIES; k++) {
        if (strcmp(registry[k].name, name) != 0) continue;
        out->name = registry[k].name;
        out->summary = registry[k].summary;
        out->built = registry[k].ops != NULL;
        out->missing = registry[k].ops ? "" : registry[k].missing;
        out->takes_device = registry[k].device;
        /* The CPU backends run the oracle's own code; a device backend's
         * promise depends on the device (rt_devices). */
        out->exact_always = !registry[k].device;
        return RT_OK;
    }
    char names[160];
    rt_backend_names(names, sizeof names);
    return rt_fail(err, RT_ERROR_UNSUPPORTED, "unknown backend '%s' (this build has: %s, auto)",
                   name, names);
}

rt_status rt_devices(const char *backend, const char *selector, rt_device_info **out, int *count,
                     rt_error *err) {
    rt_error_clear(err);
    if (!backend || !out || !count)
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "rt_devices: NULL argument");
    *out = NULL;
    *count = 0;
    for (int k = 0; k < ENTRIES; k++) {
        if (strcmp(registry[k].name, backend) != 0) continue;
        if (!registry[k].device)
            return rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                           "backend '%s' runs on the CPU: it has no devices", backend);
        if (!registry[k].ops) return rt_fail(err, RT_ERROR_UNSUPPORTED, "%s", registry[k].missing);
        return registry[k].devices(selector, out, count, err);
    }
    rt_backend_info unused;
    return rt_backend_describe(backend, &unused, err); /* the unknown-name error */
}
