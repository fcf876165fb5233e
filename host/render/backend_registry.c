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
} registry_entry;

static const registry_entry registry[] = {
#ifdef RT_HAVE_OPENCL
    {"opencl", &rt_backend_opencl, NULL, 1},
#else
    {"opencl", NULL,
     "this build has no OpenCL backend (configure with -DRT_OPENCL=ON and the OpenCL ICD loader "
     "installed: ocl-icd-opencl-dev, opencl-c-headers)",
     1},
#endif
#ifdef RT_HAVE_VULKAN
    {"vulkan", &rt_backend_vulkan, NULL, 1},
#else
    {"vulkan", NULL,
     "this build has no Vulkan backend (configure with -DRT_VULKAN=ON and the Vulkan loader and "
     "glslang installed: libvulkan-dev, glslang-tools)",
     1},
#endif
    {"cpu", &rt_backend_cpu, NULL, 0},
    {"packet", &rt_backend_packet, NULL, 0},
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
