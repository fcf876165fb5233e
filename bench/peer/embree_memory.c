/* SPDX-License-Identifier: Apache-2.0 */
/* embree_memory.c - what Embree holds for a triangle mesh (embree_peer.h):
 * the bytes its device allocates, counted by its memory monitor callback,
 * for one triangle geometry that shares the caller's vertex and index
 * arrays (so the count is Embree's BVH and primitive data alone, as our
 * structures are counted apart from the scene's arrays). */
#include <stdatomic.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include <embree3/rtcore.h>

#include "base/error.h"
#include "embree_peer.h"

typedef struct monitor {
    _Atomic long long now, peak;
} monitor;

/* Called by Embree before (post false) and after (post true) it allocates
 * (bytes > 0) and after it frees (bytes < 0). */
static bool count_bytes(void *user, ssize_t bytes, bool post) {
    monitor *m = user;
    if (bytes > 0 && post) return true; /* counted before */
    long long now = atomic_fetch_add(&m->now, (long long)bytes) + (long long)bytes;
    long long peak = atomic_load(&m->peak);
    while (now > peak && !atomic_compare_exchange_weak(&m->peak, &peak, now)) {
    }
    return true;
}

rt_status rt_embree_memory(const float *positions, uint32_t vertex_count, const uint32_t *indices,
                           uint32_t triangle_count, int threads, int quality, int compact,
                           uint64_t *held, uint64_t *peak, rt_error *err) {
    *held = *peak = 0;
    char config[64] = "";
    if (threads > 0) snprintf(config, sizeof config, "threads=%d", threads);
    RTCDevice device = rtcNewDevice(config);
    if (!device) return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot create a device", NULL);
    monitor m;
    atomic_init(&m.now, 0);
    atomic_init(&m.peak, 0);
    rtcSetDeviceMemoryMonitorFunction(device, count_bytes, &m);
    RTCScene scene = rtcNewScene(device);
    RTCGeometry geom = scene ? rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE) : NULL;
    rt_status st = RT_OK;
    if (!scene || !geom) {
        st = rt_embree_fail(err, RT_ERROR_BACKEND, "cannot create a scene", device);
    } else {
        enum RTCBuildQuality q = quality == 2   ? RTC_BUILD_QUALITY_HIGH
                                 : quality == 1 ? RTC_BUILD_QUALITY_MEDIUM
                                                : RTC_BUILD_QUALITY_LOW;
        rtcSetSceneBuildQuality(scene, q);
        if (compact) rtcSetSceneFlags(scene, RTC_SCENE_FLAG_COMPACT);
        rtcSetGeometryBuildQuality(geom, q);
        /* Shared buffers: Embree reads 16 bytes at the last vertex, so the
         * caller's positions must have 4 bytes after them (the bench pads). */
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions, 0,
                                   3 * sizeof(float), vertex_count);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices, 0,
                                   3 * sizeof(uint32_t), triangle_count);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene, geom);
        rtcCommitScene(scene);
        if (rtcGetDeviceError(device) != RTC_ERROR_NONE)
            st = rt_embree_fail(err, RT_ERROR_BACKEND, "rtcCommitScene failed", device);
        long long now = atomic_load(&m.now);
        *held = now > 0 ? (uint64_t)now : 0;
        *peak = (uint64_t)atomic_load(&m.peak);
    }
    if (geom) rtcReleaseGeometry(geom);
    if (scene) rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return st;
}
