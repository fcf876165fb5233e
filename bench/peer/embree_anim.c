/* SPDX-License-Identifier: Apache-2.0 */
/* embree_anim.c - the peer of 'rtcl bench --animate' (embree_peer.h): the
 * benchmark frame's scene kept in a dynamic Embree scene, updated frame by
 * frame at one build quality, and traced by embree_trace.c. */
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/error.h"
#include "embree_peer.h"
#include "embree_scene.h"

typedef struct geom_slot {
    RTCGeometry geom;
    float *vertices; /* Embree's vertex buffer */
    float *stage;    /* the instance's world-space triangles last written */
    float *next;     /* this frame's, before the comparison */
    uint32_t tris;
    int changed;
} geom_slot;

struct rt_embree_anim {
    rt_embree_scene es; /* first: rt_embree_anim_scene hands it out */
    RTCDevice device;
    int quality;
    uint32_t count;
    geom_slot *slots;
};

static enum RTCBuildQuality geometry_quality(int quality) {
    return quality == RT_EMBREE_REFIT ? RTC_BUILD_QUALITY_REFIT
           : quality == RT_EMBREE_LOW ? RTC_BUILD_QUALITY_LOW
                                      : RTC_BUILD_QUALITY_MEDIUM;
}

/* A new geometry for slot s (tris triangles, vertices from s->stage),
 * attached as geomID id. */
static int slot_geometry(rt_embree_anim *a, geom_slot *s, uint32_t id) {
    RTCGeometry g = rtcNewGeometry(a->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!g) return 0;
    /* Every geometry's quality, not only the scene's: a geometry defaults to
     * MEDIUM, and Embree would then build SAH trees whatever the scene says. */
    rtcSetGeometryBuildQuality(g, geometry_quality(a->quality));
    uint32_t n = s->tris ? s->tris : 1;
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), 3 * (size_t)n);
    uint32_t *idx = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                            3 * sizeof(uint32_t), n);
    if (!v || !idx) {
        rtcReleaseGeometry(g);
        return 0;
    }
    memset(v, 0, sizeof(float) * 9 * (size_t)n);
    memcpy(v, s->stage, sizeof(float) * 9 * (size_t)s->tris);
    for (uint32_t i = 0; i < 3 * n; i++) idx[i] = i;
    rtcCommitGeometry(g);
    if (s->geom) {
        rtcDetachGeometry(a->es.scene, id);
        rtcReleaseGeometry(s->geom);
    }
    rtcAttachGeometryByID(a->es.scene, g, id);
    s->geom = g;
    s->vertices = v;
    return 1;
}

rt_status rt_embree_anim_create(rt_embree *em, const rt_flat *flat, int quality,
                                rt_embree_anim **out, double *ms, rt_error *err) {
    *out = NULL;
    rt_embree_anim *a = calloc(1, sizeof *a);
    if (!a) return rt_embree_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory", NULL);
    RTCDevice dev = rt_embree_device(em);
    a->device = dev;
    a->quality = quality;
    a->count = flat->hdr.instance_count;
    a->slots = calloc(a->count ? a->count : 1, sizeof *a->slots);
    a->es.scene = rtcNewScene(a->device);
    if (!a->slots || !a->es.scene) {
        rt_embree_anim_destroy(a);
        return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot create a scene", dev);
    }
    /* Embree's advice for geometry that changes every frame: a dynamic
     * scene; its quality must not ask for more than LOW for REFIT and LOW. */
    rtcSetSceneFlags(a->es.scene, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(a->es.scene, quality == RT_EMBREE_MEDIUM ? RTC_BUILD_QUALITY_MEDIUM
                                                                     : RTC_BUILD_QUALITY_LOW);
    for (uint32_t i = 0; i < a->count; i++) {
        geom_slot *s = &a->slots[i];
        s->tris = flat->instances[i].tri_count;
        s->stage = malloc(sizeof(float) * 9 * (size_t)(s->tris ? s->tris : 1));
        if (!s->stage) {
            rt_embree_anim_destroy(a);
            return rt_embree_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory", NULL);
        }
        rt_embree_stage_instance(flat, i, s->stage);
        if (!slot_geometry(a, s, i)) {
            rt_embree_anim_destroy(a);
            return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot add a geometry", dev);
        }
    }
    double t0 = rt_now_ms();
    rtcCommitScene(a->es.scene);
    *ms = rt_now_ms() - t0;
    if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) {
        rt_embree_anim_destroy(a);
        return rt_embree_fail(err, RT_ERROR_BACKEND, "rtcCommitScene failed", dev);
    }
    a->es.flat = flat;
    a->es.view = rt_flat_view(flat);
    *out = a;
    return RT_OK;
}

rt_status rt_embree_anim_update(rt_embree_anim *a, const rt_flat *flat, double *copy_ms,
                                double *commit_ms, rt_error *err) {
    *copy_ms = *commit_ms = 0.0;
    if (flat->hdr.instance_count != a->count)
        return rt_embree_fail(err, RT_ERROR_INVALID_ARGUMENT,
                              "the number of instances changed between frames", NULL);
    /* Not timed: the world-space triangles of every instance, and which of
     * them changed (a program knows that without looking). */
    for (uint32_t i = 0; i < a->count; i++) {
        geom_slot *s = &a->slots[i];
        uint32_t n = flat->instances[i].tri_count;
        free(s->next);
        s->next = malloc(sizeof(float) * 9 * (size_t)(n ? n : 1));
        if (!s->next) return rt_embree_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory", NULL);
        rt_embree_stage_instance(flat, i, s->next);
        s->changed =
            n != s->tris ? 2 : memcmp(s->next, s->stage, sizeof(float) * 9 * (size_t)n) != 0;
        if (s->changed) {
            float *t = s->stage;
            s->stage = s->next;
            s->next = t;
            s->tris = n;
        }
    }
    /* Timed: the new vertices into Embree's buffers ... */
    double t0 = rt_now_ms();
    for (uint32_t i = 0; i < a->count; i++) {
        geom_slot *s = &a->slots[i];
        if (s->changed == 1) memcpy(s->vertices, s->stage, sizeof(float) * 9 * (size_t)s->tris);
    }
    double t1 = rt_now_ms();
    /* ... and the update: the changed geometries committed (a new geometry
     * where the instance's triangle count changed), then the scene. */
    for (uint32_t i = 0; i < a->count; i++) {
        geom_slot *s = &a->slots[i];
        if (s->changed == 2) {
            if (!slot_geometry(a, s, i))
                return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot add a geometry", a->device);
        } else if (s->changed) {
            rtcUpdateGeometryBuffer(s->geom, RTC_BUFFER_TYPE_VERTEX, 0);
            rtcCommitGeometry(s->geom);
        }
    }
    rtcCommitScene(a->es.scene);
    double t2 = rt_now_ms();
    *copy_ms = t1 - t0;
    *commit_ms = t2 - t1;
    if (rtcGetDeviceError(a->device) != RTC_ERROR_NONE)
        return rt_embree_fail(err, RT_ERROR_BACKEND, "rtcCommitScene failed", a->device);
    a->es.flat = flat;
    a->es.view = rt_flat_view(flat);
    return RT_OK;
}

const rt_embree_scene *rt_embree_anim_scene(const rt_embree_anim *a) {
    return &a->es;
}

void rt_embree_anim_destroy(rt_embree_anim *a) {
    if (!a) return;
    for (uint32_t i = 0; a->slots && i < a->count; i++) {
        if (a->slots[i].geom) rtcReleaseGeometry(a->slots[i].geom);
        free(a->slots[i].stage);
        free(a->slots[i].next);
    }
    if (a->es.scene) rtcReleaseScene(a->es.scene);
    free(a->slots);
    free(a);
}
