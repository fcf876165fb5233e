/* SPDX-License-Identifier: Apache-2.0 */
/* device_select.h - picking a device from a listing by the user's selector,
 * shared by the OpenCL and Vulkan backends (rtcl --device, --backend
 * opencl:D and vulkan:D). */
#ifndef RT_DEVICE_SELECT_H
#define RT_DEVICE_SELECT_H

#include <stddef.h>

#include "rt.h"

/* Where a listing's entries keep what selection reads: each entry is
 * stride bytes; the name (a char array) at name, the promise of the
 * oracle's results (an int) at exact, as offsetof gives them. */
typedef struct rt_device_fields {
    size_t stride, name, exact;
} rt_device_fields;

/* The index of the device that selector sel names among count devices,
 * laid out as fields says: NULL or "" the
 * first device whose results are promised to be the oracle's (else the
 * first device; -1 when there is none); a decimal number that index; any
 * other text the first device whose name contains it, ignoring case. An
 * index out of range or a name no device has returns -1 with the reason in
 * err, naming the API (api: "OpenCL", "Vulkan"). */
int rt_device_select(const char *api, const void *devs, int count, rt_device_fields fields,
                     const char *sel, rt_error *err);

#endif /* RT_DEVICE_SELECT_H */
