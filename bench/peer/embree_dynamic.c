/* SPDX-License-Identifier: Apache-2.0 */
/* embree_dynamic.c - Embree updating one deforming triangle geometry per
 * frame, the peer of our update policies (embree_peer.h). */
#include <stdlib.h>
#include <string.h>

#include <embree3/rtcore.h>

#include "base/clock.h"
#include "base/error.h"
#include "embree_peer.h"

struct rt_embree_dynamic {
    RTCDevice device;
    RTCScene scene;
    RTCGeometry geom;
    float *vertices;
    uint32_t vertex_count;
};

rt_status rt_embree_dynamic_create(rt_embree *em, const float *positions, uint32_t vertex_count,
                                   const uint32_t *indices, uint32_t triangle_count, int quality,
                                   rt_embree_dynamic **out, double *ms, rt_error *err) {
    *out = NULL;
    RTCDevice dev = rt_embree_device(em);
    rt_embree_dynamic *d = calloc(1, sizeof *d);
    if (!d) return rt_embree_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory", NULL);
    d->device = dev;
    d->vertex_count = vertex_count;
    d->scene = rtcNewScene(dev);
    d->geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!d->scene || !d->geom) {
        rt_embree_dynamic_destroy(d);
        return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot create a scene", dev);
    }
    /* Embree's advice for geometry that changes every frame: a dynamic
     * scene; the geometry's quality selects refit (REFIT), the Morton
     * builder (LOW) or the binned SAH builder (MEDIUM), and the scene's
     * quality must not ask for more than LOW for the first two. */
    enum RTCBuildQuality q = quality == RT_EMBREE_REFIT ? RTC_BUILD_QUALITY_REFIT
                             : quality == RT_EMBREE_LOW ? RTC_BUILD_QUALITY_LOW
                                                        : RTC_BUILD_QUALITY_MEDIUM;
    rtcSetSceneFlags(d->scene, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(d->scene, quality == RT_EMBREE_MEDIUM ? RTC_BUILD_QUALITY_MEDIUM
                                                                  : RTC_BUILD_QUALITY_LOW);
    rtcSetGeometryBuildQuality(d->geom, q);
    d->vertices = rtcSetNewGeometryBuffer(d->geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                          3 * sizeof(float), vertex_count);
    unsigned *ix = rtcSetNewGeometryBuffer(d->geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), triangle_count);
    if (!d->vertices || !ix) {
        rt_embree_dynamic_destroy(d);
        return rt_embree_fail(err, RT_ERROR_OUT_OF_MEMORY, "cannot allocate buffers", dev);
    }
    memcpy(d->vertices, positions, sizeof(float) * 3 * vertex_count);
    memcpy(ix, indices, sizeof(unsigned) * 3 * triangle_count);
    rtcCommitGeometry(d->geom);
    rtcAttachGeometry(d->scene, d->geom);
    double t0 = rt_now_ms();
    rtcCommitScene(d->scene);
    *ms = rt_now_ms() - t0;
    if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) {
        rt_embree_dynamic_destroy(d);
        return rt_embree_fail(err, RT_ERROR_BACKEND, "rtcCommitScene failed", dev);
    }
    *out = d;
    return RT_OK;
}

rt_status rt_embree_dynamic_update(rt_embree_dynamic *d, const float *positions, double *ms,
                                   rt_error *err) {
    memcpy(d->vertices, positions, sizeof(float) * 3 * d->vertex_count);
    double t0 = rt_now_ms();
    rtcUpdateGeometryBuffer(d->geom, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(d->geom);
    rtcCommitScene(d->scene);
    *ms = rt_now_ms() - t0;
    if (rtcGetDeviceError(d->device) != RTC_ERROR_NONE)
        return rt_embree_fail(err, RT_ERROR_BACKEND, "rtcCommitScene failed", d->device);
    return RT_OK;
}

void rt_embree_dynamic_destroy(rt_embree_dynamic *d) {
    if (!d) return;
    if (d->geom) rtcReleaseGeometry(d->geom);
    if (d->scene) rtcReleaseScene(d->scene);
    free(d);
}
