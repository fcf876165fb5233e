// SPDX-License-Identifier: Apache-2.0
/* vk_pipeline_cache.h - the Vulkan backend's VkPipelineCache, kept on disk
 * (base/kernel_cache.h: the same folder, file rules and off switch as the
 * OpenCL program binaries), so that a run after the first need not compile
 * its pipelines again where the driver's cache holds their code.
 *
 * One entry per device and driver: the key is this library's version, the
 * device's name, vendor and device ids, driver version, API version and
 * pipelineCacheUUID. The driver's data is checked before it is handed back
 * to the driver: its VkPipelineCacheHeaderVersionOne must have a plausible
 * length, header version one, and the vendorID, deviceID and
 * pipelineCacheUUID of VkPhysicalDeviceProperties; anything else is dropped
 * silently (an empty cache is made and the entry is rewritten). The driver
 * compiles the same SPIR-V with the same specialisation either way, so the
 * pipelines compute the same bits. */
#ifndef RT_VK_PIPELINE_CACHE_H
#define RT_VK_PIPELINE_CACHE_H

#include <stddef.h>
#include <vulkan/vulkan.h>

#include "base/kernel_cache.h"

typedef struct rt_vk_pcache {
    VkPipelineCache cache; /* VK_NULL_HANDLE until opened, or when none could be made */
    int opened;            /* 1 once rt_vk_pcache_get was tried on the device */
    char dir[4096];        /* the cache folder; "" when the cache is off or unusable */
    rt_kc_key key;
    void *known; /* the data as loaded or last saved (NULL: none), to see a change */
    size_t known_size;
} rt_vk_pcache;

/* The pipeline cache to pass to vkCreateComputePipelines: made at the first
 * call on device from the disk entry when it is valid, else empty.
 * VK_NULL_HANDLE when the cache is off or none could be made (pipelines are
 * then made without one). */
VkPipelineCache rt_vk_pcache_get(rt_vk_pcache *c, VkDevice device, VkPhysicalDevice phys);

/* Writes the cache's data to disk (atomically) when it changed since it was
 * loaded or last saved; silent on failure. */
void rt_vk_pcache_save(rt_vk_pcache *c, VkDevice device);

/* Destroys the cache (before the device goes) and forgets it, so that the
 * next device opens it afresh. Safe on a zeroed c. */
void rt_vk_pcache_close(rt_vk_pcache *c, VkDevice device);

#endif /* RT_VK_PIPELINE_CACHE_H */
