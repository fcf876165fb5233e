/* SPDX-License-Identifier: Apache-2.0 */
/* vk_internal.h - what vk_device.c gives vk_backend.c: an instance and the
 * physical device behind a rt_vk_device_info. Vulkan types; for host/vulkan/
 * alone. */
#ifndef RT_VK_INTERNAL_H
#define RT_VK_INTERNAL_H

#include <vulkan/vulkan.h>

#include "vulkan/vk_device.h"

/* A Vulkan 1.1 instance (1.2 asked for; the loader accepts either) for
 * compute only: no layers, no extensions. */
rt_status rt_vk_instance(VkInstance *out, rt_error *err);

/* The devices of instance (as rt_vk_devices) and their handles, in the same
 * order. free() both lists. */
rt_status rt_vk_enumerate(VkInstance instance, rt_vk_device_info **out, VkPhysicalDevice **handles,
                          int *count, rt_error *err);

#endif /* RT_VK_INTERNAL_H */
