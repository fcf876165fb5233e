/* SPDX-License-Identifier: Apache-2.0 */
/* device_list.h - each device backend's devices as rt_device_info (rt.h),
 * for rt_devices; compiled in where the backend is (RT_HAVE_OPENCL,
 * RT_HAVE_VULKAN). selector NULL lists every device, else only the one it
 * picks (an index or part of a name); errors as rt_devices says. */
#ifndef RT_DEVICE_LIST_H
#define RT_DEVICE_LIST_H

#include "rt.h"

rt_status rt_opencl_device_list(const char *selector, rt_device_info **out, int *count,
                                rt_error *err);
rt_status rt_vulkan_device_list(const char *selector, rt_device_info **out, int *count,
                                rt_error *err);

#endif /* RT_DEVICE_LIST_H */
