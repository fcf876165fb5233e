/* SPDX-License-Identifier: Apache-2.0 */
/* vk_device.h - Vulkan devices (host/vulkan/vk_device.c): listing through the
 * loader, the float controls that decide whether the oracle's bits are
 * promised, and selection by index or name. Compiled only where the build
 * found the Vulkan loader and glslangValidator (RT_HAVE_VULKAN). No Vulkan
 * types here, so callers (rtcl devices) need no Vulkan headers. */
#ifndef RT_VK_DEVICE_H
#define RT_VK_DEVICE_H

#include <stdint.h>

#include "rt.h"

typedef struct rt_vk_device_info {
    int index; /* the loader's order: the number vulkan:N takes */
    char name[256];
    char type[24];          /* "integrated GPU", "discrete GPU", "CPU", ... */
    char api[24];           /* the device's Vulkan version, "1.3.255" */
    char driver[160];       /* driver name and info (Vulkan 1.2), or the driver version */
    uint64_t memory;        /* the largest device-local heap, bytes */
    uint64_t max_buffer;    /* maxStorageBufferRange, bytes */
    uint32_t queue_family;  /* the first family with compute */
    int timestamps;         /* the compute queue has timestamps (timestampValidBits > 0) */
    float timestamp_period; /* ns per timestamp tick */
    /* VK_KHR_shader_float_controls (core in Vulkan 1.2), for 32-bit floats;
     * float_controls is 0 when the device does not report them. */
    int float_controls;
    int denorm_preserve;     /* shaderDenormPreserveFloat32 */
    int denorm_flush;        /* shaderDenormFlushToZeroFloat32 */
    int rte;                 /* shaderRoundingModeRTEFloat32 */
    int signed_zero_inf_nan; /* shaderSignedZeroInfNanPreserveFloat32 */
    /* The oracle's bits are promised: the modules' maths is exact by
     * construction (no contraction, soft division and sqrt, no fp64) and the
     * device rounds to nearest even, keeps signed zeros, infs and NaNs, and
     * keeps denormals (exact) or flushes them (exact_flush, compared with the
     * flushing oracle of --denormals flush) when the module asks. */
    int exact;
    int exact_flush;
} rt_vk_device_info;

/* Every physical device with a compute queue. RT_ERROR_UNSUPPORTED with a
 * message when the loader finds no driver or no device; *out is then NULL.
 * free() the list. */
rt_status rt_vk_devices(rt_vk_device_info **out, int *count, rt_error *err);

/* Picks a device: selector NULL or "" is the first device (an exact one when
 * there is one), a number is an index, anything else the first device whose
 * name contains it (case-insensitive). Returns the position in devs, or -1
 * with a message. */
int rt_vk_select(const rt_vk_device_info *devs, int count, const char *selector, rt_error *err);

/* Why a device does or does not promise the oracle's bits in a denormal
 * policy (flush 0: preserve), one line. */
const char *rt_vk_exactness_note(const rt_vk_device_info *d, int flush);

/* A name for a VkResult ("VK_ERROR_DEVICE_LOST"). */
const char *rt_vk_result_name(int result);

#endif /* RT_VK_DEVICE_H */
