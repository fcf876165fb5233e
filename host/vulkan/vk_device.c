/* SPDX-License-Identifier: Apache-2.0 */
/* vk_device.c - Vulkan devices through the loader: listing, float controls,
 * selection (vk_device.h). */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/device_select.h"
#include "base/error.h"
#include "vulkan/vk_internal.h"

/* The codes it names and their names (vk_result_names.def). */
static const rt_code_name vk_result_names[] = {
#define RT_VK_RESULT(name) {name, #name},
#include "vulkan/vk_result_names.def"
#undef RT_VK_RESULT
};

const char *rt_vk_result_name(int r) {
    return rt_code_name_find(vk_result_names, sizeof vk_result_names / sizeof *vk_result_names, r,
                             "VK_ERROR_UNKNOWN");
}

rt_status rt_vk_instance(VkInstance *out, rt_error *err) {
    *out = VK_NULL_HANDLE;
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "rtcl";
    app.apiVersion = VK_API_VERSION_1_2;
    VkInstanceCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    VkResult r = vkCreateInstance(&ci, NULL, out);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
        return rt_fail(err, RT_ERROR_UNSUPPORTED,
                       "no Vulkan driver found by the loader (install one, e.g. "
                       "mesa-vulkan-drivers for lavapipe; VK_ICD_FILENAMES selects one)");
    if (r != VK_SUCCESS)
        return rt_fail(err, RT_ERROR_UNSUPPORTED, "Vulkan instance: %s", rt_vk_result_name(r));
    return RT_OK;
}

/* What each VkPhysicalDeviceType is, by its value (OTHER = 0 to CPU = 4). */
static const char *const type_names[] = {[VK_PHYSICAL_DEVICE_TYPE_OTHER] = "other",
                                         [VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU] =
                                             "integrated GPU",
                                         [VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU] = "discrete GPU",
                                         [VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU] = "virtual GPU",
                                         [VK_PHYSICAL_DEVICE_TYPE_CPU] = "CPU"};

static const char *type_name(VkPhysicalDeviceType t) {
    return (unsigned)t < sizeof type_names / sizeof *type_names ? type_names[t] : "other";
}

/* Fills d from p; 0 when the device has no compute queue. */
static int describe(VkPhysicalDevice p, rt_vk_device_info *d) {
    memset(d, 0, sizeof *d);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(p, &props);
    snprintf(d->name, sizeof d->name, "%s", props.deviceName);
    snprintf(d->type, sizeof d->type, "%s", type_name(props.deviceType));
    snprintf(d->api, sizeof d->api, "%u.%u.%u", VK_API_VERSION_MAJOR(props.apiVersion),
             VK_API_VERSION_MINOR(props.apiVersion), VK_API_VERSION_PATCH(props.apiVersion));
    d->max_buffer = props.limits.maxStorageBufferRange;
    d->timestamp_period = props.limits.timestampPeriod;
    snprintf(d->driver, sizeof d->driver, "driver version 0x%x", props.driverVersion);
    /* Float controls and the driver's name: Vulkan 1.2 (core) structures. */
    if (props.apiVersion >= VK_API_VERSION_1_2) {
        VkPhysicalDeviceFloatControlsProperties fc = {
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES};
        VkPhysicalDeviceDriverProperties drv = {
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        fc.pNext = &drv;
        VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
        p2.pNext = &fc;
        vkGetPhysicalDeviceProperties2(p, &p2);
        d->float_controls = 1;
        d->denorm_preserve = fc.shaderDenormPreserveFloat32 == VK_TRUE;
        d->denorm_flush = fc.shaderDenormFlushToZeroFloat32 == VK_TRUE;
        d->rte = fc.shaderRoundingModeRTEFloat32 == VK_TRUE;
        d->signed_zero_inf_nan = fc.shaderSignedZeroInfNanPreserveFloat32 == VK_TRUE;
        snprintf(d->driver, sizeof d->driver, "%.60s %.90s", drv.driverName, drv.driverInfo);
    }
    d->exact = d->float_controls && d->denorm_preserve && d->rte && d->signed_zero_inf_nan;
    d->exact_flush = d->float_controls && d->denorm_flush && d->rte && d->signed_zero_inf_nan;
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(p, &mem);
    for (uint32_t i = 0; i < mem.memoryHeapCount; i++)
        if ((mem.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) &&
            mem.memoryHeaps[i].size > d->memory)
            d->memory = mem.memoryHeaps[i].size;
    uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(p, &nq, NULL);
    VkQueueFamilyProperties *q = calloc(nq ? nq : 1, sizeof *q);
    int found = 0;
    if (q) {
        vkGetPhysicalDeviceQueueFamilyProperties(p, &nq, q);
        for (uint32_t i = 0; i < nq && !found; i++)
            if (q[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
                d->queue_family = i;
                d->timestamps = q[i].timestampValidBits > 0;
                found = 1;
            }
        free(q);
    }
    return found;
}

rt_status rt_vk_enumerate(VkInstance instance, rt_vk_device_info **out, VkPhysicalDevice **handles,
                          int *count, rt_error *err) {
    *out = NULL;
    *handles = NULL;
    *count = 0;
    uint32_t n = 0;
    VkResult r = vkEnumeratePhysicalDevices(instance, &n, NULL);
    if (r != VK_SUCCESS)
        return rt_fail(err, RT_ERROR_UNSUPPORTED, "Vulkan devices: %s", rt_vk_result_name(r));
    if (n == 0) return rt_fail(err, RT_ERROR_UNSUPPORTED, "the Vulkan loader finds no device");
    VkPhysicalDevice *all = calloc(n, sizeof *all);
    rt_vk_device_info *devs = calloc(n, sizeof *devs);
    VkPhysicalDevice *kept = calloc(n, sizeof *kept);
    if (!all || !devs || !kept) {
        free(all);
        free(devs);
        free(kept);
        return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    r = vkEnumeratePhysicalDevices(instance, &n, all);
    int k = 0;
    for (uint32_t i = 0; r == VK_SUCCESS && i < n; i++) {
        if (!describe(all[i], &devs[k])) continue;
        devs[k].index = k;
        kept[k++] = all[i];
    }
    free(all);
    if (k == 0) {
        free(devs);
        free(kept);
        return rt_fail(err, RT_ERROR_UNSUPPORTED, "no Vulkan device with a compute queue");
    }
    *out = devs;
    *handles = kept;
    *count = k;
    return RT_OK;
}

rt_status rt_vk_devices(rt_vk_device_info **out, int *count, rt_error *err) {
    VkInstance inst;
    *out = NULL;
    *count = 0;
    rt_status st = rt_vk_instance(&inst, err);
    if (st != RT_OK) return st;
    VkPhysicalDevice *handles;
    st = rt_vk_enumerate(inst, out, &handles, count, err);
    if (st == RT_OK) free(handles);
    vkDestroyInstance(inst, NULL);
    return st;
}

int rt_vk_select(const rt_vk_device_info *devs, int count, const char *sel, rt_error *err) {
    const rt_device_fields fields = {sizeof *devs, offsetof(rt_vk_device_info, name),
                                     offsetof(rt_vk_device_info, exact)};
    return rt_device_select("Vulkan", devs, count, fields, sel, err);
}

const char *rt_vk_exactness_note(const rt_vk_device_info *d, int flush) {
    if (flush ? d->exact_flush : d->exact)
        return flush ? "bit-exact with the flushing CPU oracle (portable maths: no contraction, "
                       "software division and sqrt, no fp64; the shader asks for round to "
                       "nearest even, denormals flushed, signed zeros, infs and NaNs kept)"
                     : "bit-exact with the CPU oracle (portable maths: no contraction, software "
                       "division and sqrt, no fp64; the shader asks for round to nearest even, "
                       "denormals and signed zeros, infs and NaNs kept)";
    if (!d->float_controls)
        return "exactness NOT promised: the device reports no float controls (Vulkan 1.2), so "
               "its rounding and denormal handling are unknown";
    if (d->rte && d->signed_zero_inf_nan)
        return flush ? "exactness NOT promised: the device cannot be asked to flush denormals, "
                       "so results may differ from the flushing oracle where a denormal occurs"
                     : "exactness NOT promised: the device cannot be asked to keep denormals (it "
                       "may flush them), so results may differ from the oracle where a denormal "
                       "occurs; elsewhere the oracle's bits (portable maths, round to nearest "
                       "even, signed zeros kept)";
    return "exactness NOT promised: the device cannot be asked to round to nearest even or keep "
           "signed zeros, infs and NaNs";
}
