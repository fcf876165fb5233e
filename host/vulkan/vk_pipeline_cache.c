// SPDX-License-Identifier: Apache-2.0
/* vk_pipeline_cache.c - see vk_pipeline_cache.h. */
#include "vulkan/vk_pipeline_cache.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rt.h"

/* VkPipelineCacheHeaderVersionOne: headerSize, headerVersion, vendorID,
 * deviceID (4 bytes each, little-endian on every device we run), then the
 * 16-byte pipelineCacheUUID. */
#define HEADER_ONE_BYTES 32u

static uint32_t get32(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* Whether data is a cache of this device (vk_pipeline_cache.h). */
static int header_ok(const unsigned char *data, size_t size, const VkPhysicalDeviceProperties *p) {
    if (size < HEADER_ONE_BYTES) return 0;
    uint32_t header_size = get32(data);
    return header_size >= HEADER_ONE_BYTES && header_size <= size &&
           get32(data + 4) == (uint32_t)VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
           get32(data + 8) == p->vendorID && get32(data + 12) == p->deviceID &&
           memcmp(data + 16, p->pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

static void make_key(rt_vk_pcache *c, const VkPhysicalDeviceProperties *p) {
    rt_kc_key_init(&c->key);
    rt_kc_key_add_str(&c->key, "vulkan pipeline cache");
    rt_kc_key_add_str(&c->key, rt_version());
    rt_kc_key_add_str(&c->key, p->deviceName);
    uint32_t ids[4] = {p->vendorID, p->deviceID, p->driverVersion, p->apiVersion};
    rt_kc_key_add(&c->key, ids, sizeof ids);
    rt_kc_key_add(&c->key, p->pipelineCacheUUID, VK_UUID_SIZE);
}

VkPipelineCache rt_vk_pcache_get(rt_vk_pcache *c, VkDevice device, VkPhysicalDevice phys) {
    if (c->opened) return c->cache;
    c->opened = 1;
    if (!rt_kc_folder(c->dir, sizeof c->dir)) return VK_NULL_HANDLE;
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(phys, &props);
    make_key(c, &props);
    size_t size = 0;
    unsigned char *data = rt_kc_load(c->dir, "vk", &c->key, &size);
    if (data && !header_ok(data, size, &props)) {
        free(data); /* another driver's, or damaged: start empty */
        data = NULL;
        size = 0;
    }
    VkPipelineCacheCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    ci.initialDataSize = size;
    ci.pInitialData = data;
    VkResult r = vkCreatePipelineCache(device, &ci, NULL, &c->cache);
    if (r != VK_SUCCESS && data) { /* the driver refused the data: start empty */
        free(data);
        data = NULL;
        size = 0;
        ci.initialDataSize = 0;
        ci.pInitialData = NULL;
        r = vkCreatePipelineCache(device, &ci, NULL, &c->cache);
    }
    if (r != VK_SUCCESS) c->cache = VK_NULL_HANDLE;
    c->known = data;
    c->known_size = size;
    return c->cache;
}

void rt_vk_pcache_save(rt_vk_pcache *c, VkDevice device) {
    if (!c->cache || !c->dir[0]) return;
    size_t size = 0;
    if (vkGetPipelineCacheData(device, c->cache, &size, NULL) != VK_SUCCESS || !size) return;
    unsigned char *data = malloc(size);
    if (!data) return;
    /* VK_INCOMPLETE (the cache grew in between) is a partial copy: not kept. */
    if (vkGetPipelineCacheData(device, c->cache, &size, data) != VK_SUCCESS ||
        (c->known && size == c->known_size && memcmp(data, c->known, size) == 0)) {
        free(data);
        return;
    }
    rt_kc_save(c->dir, "vk", &c->key, data, size);
    free(c->known);
    c->known = data;
    c->known_size = size;
}

void rt_vk_pcache_close(rt_vk_pcache *c, VkDevice device) {
    if (c->cache && device) vkDestroyPipelineCache(device, c->cache, NULL);
    free(c->known);
    memset(c, 0, sizeof *c);
}
