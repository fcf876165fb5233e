/* SPDX-License-Identifier: Apache-2.0 */
/* embree_trace.c - Embree tracing the benchmark frame as a peer
 * (embree_peer.h): the same camera rays, the same shadow rays and the same
 * Phong terms as the thesis set-up of our renderer (rt_render with
 * direct_only), so that frame times compare and the images can be checked
 * against each other. */
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <embree3/rtcore.h>

#include "base/clock.h"
#include "embree_peer.h"
#include "embree_scene.h"
#include "rt_shade.h"

/* Embree's C API names its types as struct tags only. */
typedef struct RTCRay RTCRay;
typedef struct RTCRayHit RTCRayHit;
typedef struct RTCIntersectContext RTCIntersectContext;
typedef struct RTCRay4 RTCRay4;
typedef struct RTCRay8 RTCRay8;
typedef struct RTCRay16 RTCRay16;
typedef struct RTCRayHit4 RTCRayHit4;
typedef struct RTCRayHit8 RTCRayHit8;
typedef struct RTCRayHit16 RTCRayHit16;

/* The instance's triangles in world space, three vertices each, as
 * the peer's scenes hold them (so that primID + tri_first is the layout's
 * entry). out holds 9 floats per triangle. */
void rt_embree_stage_instance(const rt_flat *flat, uint32_t inst, float *out) {
    const rt_instance *in = &flat->instances[inst];
    const float *m = in->object_to_world;
    int identity = (in->flags & RT_INST_IDENTITY) != 0;
    for (uint32_t t = 0; t < in->tri_count; t++) {
        const rt_tri *tri = &flat->tris[in->tri_first + t];
        const float *p[3] = {tri->v0, tri->v1, tri->v2};
        for (int j = 0; j < 3; j++) {
            float *o = out + 9 * (size_t)t + 3 * j;
            for (int k = 0; k < 3; k++)
                o[k] =
                    identity
                        ? p[j][k]
                        : ((m[4 * k] * p[j][0] + m[4 * k + 1] * p[j][1]) + m[4 * k + 2] * p[j][2]) +
                              m[4 * k + 3];
        }
    }
}

/* One triangle geometry per instance, in world space, so that geomID is the
 * instance and primID + tri_first the layout's entry. Instances flattened
 * into world space (no Embree instancing) are the peer's fastest case. */
static int add_instance(RTCDevice dev, RTCScene scene, const rt_flat *flat, uint32_t inst) {
    const rt_instance *in = &flat->instances[inst];
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!g) return 0;
    uint32_t n = in->tri_count;
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), 3 * (size_t)(n ? n : 1));
    uint32_t *idx = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                            3 * sizeof(uint32_t), n ? n : 1);
    if (!v || !idx) {
        rtcReleaseGeometry(g);
        return 0;
    }
    rt_embree_stage_instance(flat, inst, v);
    for (uint32_t i = 0; i < 3 * n; i++) idx[i] = i;
    rtcCommitGeometry(g);
    unsigned id = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    return id == inst;
}

rt_status rt_embree_scene_create(rt_embree *em, const rt_flat *flat, rt_embree_scene **out,
                                 double *ms, rt_error *err) {
    *out = NULL;
    RTCDevice dev = (RTCDevice)rt_embree_device(em);
    rt_embree_scene *es = calloc(1, sizeof *es);
    if (!es) return rt_embree_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory", NULL);
    double t0 = rt_now_ms();
    es->scene = rtcNewScene(dev);
    if (!es->scene) {
        free(es);
        return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot create a scene", dev);
    }
    for (uint32_t i = 0; i < flat->hdr.instance_count; i++)
        if (!add_instance(dev, es->scene, flat, i)) {
            rt_embree_scene_destroy(es);
            return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot add a geometry", dev);
        }
    rtcCommitScene(es->scene);
    *ms = rt_now_ms() - t0;
    es->flat = flat;
    es->view = rt_flat_view(flat);
    *out = es;
    return RT_OK;
}

void rt_embree_scene_destroy(rt_embree_scene *es) {
    if (!es) return;
    if (es->scene) rtcReleaseScene(es->scene);
    free(es);
}

/* ---- one block of pixels: 1 ray, or a packet of 4 (2x2), 8 (4x2), 16 (4x4) */

enum { MAX_LANES = 16 };

typedef struct block {
    int lanes, count;
    rt_ray ray[MAX_LANES];
    rt_hit_d hit[MAX_LANES];
    int occluded[MAX_LANES];
    _Alignas(64) int valid[MAX_LANES]; /* Embree's masks (-1 active, 0 not), aligned as
                                          rtcIntersect16 loads them */
} block;

static void to_rtc_ray(const rt_ray *r, RTCRay *out) {
    out->org_x = r->org[0];
    out->org_y = r->org[1];
    out->org_z = r->org[2];
    out->tnear = r->tmin;
    out->dir_x = r->dir[0];
    out->dir_y = r->dir[1];
    out->dir_z = r->dir[2];
    out->time = 0.0f;
    out->tfar = r->tmax;
    out->mask = 0xFFFFFFFFu;
    out->id = 0;
    out->flags = 0;
}

/* Embree's hit as the layout's hit record (entry, inst, prim in file order). */
static void from_rtc_hit(const rt_embree_scene *es, float t, float u, float v, unsigned geom,
                         unsigned prim, rt_hit_d *h) {
    if (geom == RTC_INVALID_GEOMETRY_ID) {
        h->t = RT_INF;
        h->u = h->v = 0.0f;
        h->prim = h->inst = h->entry = RT_NO_HIT;
        return;
    }
    h->t = t;
    h->u = u;
    h->v = v;
    h->inst = geom;
    h->entry = es->flat->instances[geom].tri_first + prim;
    h->prim = es->flat->tri_ids[h->entry];
}

/* Packets of N rays: fill the SoA structure from b's rays, call Embree, read
 * the results back. A macro, because Embree has one type and one entry
 * point per width. */
#define RT_EMBREE_PACKET(N)                                                                        \
    static void intersect##N(const rt_embree_scene *es, RTCIntersectContext *ctx, block *b) {      \
        RTCRayHit##N rh;                                                                           \
        for (int i = 0; i < N; i++) {                                                              \
            RTCRay r1;                                                                             \
            to_rtc_ray(&b->ray[i], &r1);                                                           \
            rh.ray.org_x[i] = r1.org_x, rh.ray.org_y[i] = r1.org_y, rh.ray.org_z[i] = r1.org_z;    \
            rh.ray.dir_x[i] = r1.dir_x, rh.ray.dir_y[i] = r1.dir_y, rh.ray.dir_z[i] = r1.dir_z;    \
            rh.ray.tnear[i] = r1.tnear, rh.ray.tfar[i] = r1.tfar, rh.ray.time[i] = 0.0f;           \
            rh.ray.mask[i] = r1.mask, rh.ray.id[i] = 0, rh.ray.flags[i] = 0;                       \
            rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;                                            \
            rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;                                         \
        }                                                                                          \
        rtcIntersect##N(b->valid, es->scene, ctx, &rh);                                            \
        for (int i = 0; i < N; i++)                                                                \
            from_rtc_hit(es, rh.ray.tfar[i], rh.hit.u[i], rh.hit.v[i], rh.hit.geomID[i],           \
                         rh.hit.primID[i], &b->hit[i]);                                            \
    }                                                                                              \
    static void occluded##N(const rt_embree_scene *es, RTCIntersectContext *ctx, block *b) {       \
        RTCRay##N r;                                                                               \
        for (int i = 0; i < N; i++) {                                                              \
            RTCRay r1;                                                                             \
            to_rtc_ray(&b->ray[i], &r1);                                                           \
            r.org_x[i] = r1.org_x, r.org_y[i] = r1.org_y, r.org_z[i] = r1.org_z;                   \
            r.dir_x[i] = r1.dir_x, r.dir_y[i] = r1.dir_y, r.dir_z[i] = r1.dir_z;                   \
            r.tnear[i] = r1.tnear, r.tfar[i] = r1.tfar, r.time[i] = 0.0f;                          \
            r.mask[i] = r1.mask, r.id[i] = 0, r.flags[i] = 0;                                      \
        }                                                                                          \
        rtcOccluded##N(b->valid, es->scene, ctx, &r);                                              \
        for (int i = 0; i < N; i++) b->occluded[i] = b->valid[i] && r.tfar[i] < 0.0f;              \
    }

RT_EMBREE_PACKET(4)
RT_EMBREE_PACKET(8)
RT_EMBREE_PACKET(16)

static void intersect(const rt_embree_scene *es, RTCIntersectContext *ctx, block *b) {
    switch (b->lanes) {
    case 4:
        intersect4(es, ctx, b);
        return;
    case 8:
        intersect8(es, ctx, b);
        return;
    case 16:
        intersect16(es, ctx, b);
        return;
    default:
        break;
    }
    for (int i = 0; i < b->count; i++) {
        if (!b->valid[i]) continue;
        RTCRayHit rh;
        to_rtc_ray(&b->ray[i], &rh.ray);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(es->scene, ctx, &rh);
        from_rtc_hit(es, rh.ray.tfar, rh.hit.u, rh.hit.v, rh.hit.geomID, rh.hit.primID, &b->hit[i]);
    }
}

static void occluded(const rt_embree_scene *es, RTCIntersectContext *ctx, block *b) {
    switch (b->lanes) {
    case 4:
        occluded4(es, ctx, b);
        return;
    case 8:
        occluded8(es, ctx, b);
        return;
    case 16:
        occluded16(es, ctx, b);
        return;
    default:
        break;
    }
    for (int i = 0; i < b->count; i++) {
        b->occluded[i] = 0;
        if (!b->valid[i]) continue;
        RTCRay r;
        to_rtc_ray(&b->ray[i], &r);
        rtcOccluded1(es->scene, ctx, &r);
        b->occluded[i] = r.tfar < 0.0f;
    }
}

/* ---- the frame ------------------------------------------------------------- */

typedef struct frame_job {
    const rt_embree_scene *es;
    int lanes, bw, bh; /* block width x height = lanes */
    int blocks_x, blocks;
    atomic_int next;
    atomic_ullong rays;
    float *rgb;
} frame_job;

/* One block: primary rays, then per light the shadow rays of the lanes that
 * face it, traced as one packet, then the Phong terms. The shading is
 * rt_phong's own steps (kernels/rt_shade.h: rt_phong_ambient, rt_phong_light,
 * rt_phong_add), so that Embree does the same work and its image can be
 * compared with ours. */
static void shade_block(frame_job *job, int bx, int by, RTCIntersectContext *coherent,
                        RTCIntersectContext *incoherent) {
    const rt_embree_scene *es = job->es;
    const rt_scene_view *s = &es->view;
    const rt_scene_header *h = s->hdr;
    block b;
    b.lanes = job->lanes;
    b.count = job->lanes;
    int px[MAX_LANES], py[MAX_LANES];
    for (int i = 0; i < b.count; i++) {
        px[i] = bx * job->bw + i % job->bw;
        py[i] = by * job->bh + i / job->bw;
        b.valid[i] = px[i] < h->width && py[i] < h->height ? -1 : 0;
        rt_camera_ray(h, b.valid[i] ? px[i] : 0, b.valid[i] ? py[i] : 0, &b.ray[i]);
    }
    intersect(es, coherent, &b);
    rt_surface sf[MAX_LANES];
    float dn[MAX_LANES][3], out[MAX_LANES][3];
    const rt_material_d *mat[MAX_LANES];
    int lit[MAX_LANES]; /* hit a surface with a Phong term */
    unsigned long long rays = 0;
    for (int i = 0; i < b.count; i++) {
        lit[i] = 0;
        if (!b.valid[i]) continue;
        rays++;
        if (b.hit[i].prim == RT_NO_HIT) {
            for (int k = 0; k < 3; k++) out[i][k] = h->background[k];
            continue;
        }
        rt_surface_at(s, &b.ray[i], &b.hit[i], &sf[i]);
        mat[i] = &s->materials[sf[i].material];
        for (int k = 0; k < 3; k++) dn[i][k] = b.ray[i].dir[k];
        rt_normalize3(dn[i]);
        rt_phong_ambient(s, &sf[i], out[i]);
        lit[i] = ((1.0f - mat[i]->reflectivity) - mat[i]->transparency) > 0.0f;
        if (!lit[i])
            for (int k = 0; k < 3; k++) out[i][k] = 0.0f;
    }
    for (rt_u32 li = 0; li < h->light_count; li++) {
        float Ln[MAX_LANES][3], ndl[MAX_LANES];
        int any = 0;
        for (int i = 0; i < b.count; i++) {
            b.valid[i] =
                lit[i] && rt_phong_light(s, &sf[i], li, &b.ray[i], Ln[i], &ndl[i]) ? -1 : 0;
            if (!b.valid[i]) continue;
            any = 1;
            rays++;
        }
        if (!any) continue;
        occluded(es, incoherent, &b);
        for (int i = 0; i < b.count; i++)
            if (b.valid[i] && !b.occluded[i])
                rt_phong_add(s, &sf[i], li, Ln[i], ndl[i], dn[i], out[i]);
    }
    for (int i = 0; i < b.count; i++) {
        if (px[i] >= h->width || py[i] >= h->height) continue;
        float w = lit[i] ? (1.0f - mat[i]->reflectivity) - mat[i]->transparency : 1.0f;
        float *dst =
            job->rgb ? job->rgb + 3 * ((size_t)py[i] * (size_t)h->width + (size_t)px[i]) : NULL;
        if (dst)
            for (int k = 0; k < 3; k++) dst[k] = lit[i] ? w * out[i][k] : out[i][k];
    }
    atomic_fetch_add_explicit(&job->rays, rays, memory_order_relaxed);
}

static void frame_worker(void *ctx, int worker, int workers) {
    (void)worker;
    (void)workers;
    frame_job *job = ctx;
    RTCIntersectContext coherent, incoherent;
    rtcInitIntersectContext(&coherent);
    coherent.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcInitIntersectContext(&incoherent);
    /* Rows of blocks, taken in turn, as our renderer takes its tiles. */
    for (;;) {
        int row = atomic_fetch_add_explicit(&job->next, 1, memory_order_relaxed);
        int rows = job->blocks / job->blocks_x;
        if (row >= rows) break;
        for (int bx = 0; bx < job->blocks_x; bx++)
            shade_block(job, bx, row, &coherent, &incoherent);
    }
}

rt_status rt_embree_render(const rt_embree_scene *es, int lanes, rt_pool *pool, float *rgb,
                           uint64_t *rays, double *ms) {
    if (lanes != 1 && lanes != 4 && lanes != 8 && lanes != 16) return RT_ERROR_INVALID_ARGUMENT;
    frame_job job;
    memset(&job, 0, sizeof job);
    job.es = es;
    job.lanes = lanes;
    job.bw = lanes == 1 ? 1 : lanes == 4 ? 2 : 4;
    job.bh = lanes / job.bw;
    const rt_scene_header *h = es->view.hdr;
    job.blocks_x = (h->width + job.bw - 1) / job.bw;
    job.blocks = job.blocks_x * ((h->height + job.bh - 1) / job.bh);
    atomic_init(&job.next, 0);
    atomic_init(&job.rays, 0);
    job.rgb = rgb;
    double t0 = rt_now_ms();
    rt_pool_run(pool, frame_worker, &job);
    *ms = rt_now_ms() - t0;
    *rays = atomic_load(&job.rays);
    return RT_OK;
}

int rt_embree_native_lanes(rt_embree *em, int lanes) {
    RTCDevice dev = (RTCDevice)rt_embree_device(em);
    switch (lanes) {
    case 1:
        return 1;
    case 4:
        return rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED) != 0;
    case 8:
        return rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) != 0;
    case 16:
        return rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
    default:
        return 0;
    }
}

/* ---- ray queries: the caller's rays, one at a time or 16 at once ----------- */

typedef struct rays_job {
    const rt_embree_scene *es;
    const rt_ray *rays;
    rt_hit_d *hits;
    size_t n;
    int lanes, any_hit;
    atomic_size_t next;
} rays_job;

/* Chunks of rays taken in turn (a thread that finishes early takes more). */
enum { RAYS_CHUNK = 1024 };

static void rays_worker(void *ctx, int worker, int workers) {
    (void)worker;
    (void)workers;
    rays_job *job = ctx;
    RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    ic.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    block b;
    for (;;) {
        size_t first = atomic_fetch_add_explicit(&job->next, RAYS_CHUNK, memory_order_relaxed);
        if (first >= job->n) break;
        size_t end = job->n - first < RAYS_CHUNK ? job->n : first + RAYS_CHUNK;
        for (size_t i = first; i < end; i++) {
            if (job->lanes != 1) break;
            rt_hit_d *h = &job->hits[i];
            if (job->any_hit) {
                RTCRay r;
                to_rtc_ray(&job->rays[i], &r);
                rtcOccluded1(job->es->scene, &ic, &r);
                h->prim = r.tfar < 0.0f ? 0 : RT_NO_HIT;
            } else {
                RTCRayHit rh;
                to_rtc_ray(&job->rays[i], &rh.ray);
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(job->es->scene, &ic, &rh);
                from_rtc_hit(job->es, rh.ray.tfar, rh.hit.u, rh.hit.v, rh.hit.geomID, rh.hit.primID,
                             h);
            }
        }
        for (size_t i = first; job->lanes != 1 && i < end; i += (size_t)job->lanes) {
            b.lanes = job->lanes;
            b.count = end - i < (size_t)job->lanes ? (int)(end - i) : job->lanes;
            for (int l = 0; l < b.lanes; l++) {
                b.valid[l] = l < b.count ? -1 : 0;
                b.ray[l] = job->rays[i + (size_t)(l < b.count ? l : 0)];
            }
            if (job->any_hit) {
                occluded(job->es, &ic, &b);
                for (int l = 0; l < b.count; l++)
                    job->hits[i + l].prim = b.occluded[l] ? 0 : RT_NO_HIT;
            } else {
                intersect(job->es, &ic, &b);
                for (int l = 0; l < b.count; l++) job->hits[i + l] = b.hit[l];
            }
        }
    }
}

rt_status rt_embree_trace_rays(const rt_embree_scene *es, const rt_ray *rays, size_t n, int any_hit,
                               int lanes, rt_pool *pool, rt_hit_d *hits, double *ms) {
    if (lanes != 1 && lanes != 4 && lanes != 8 && lanes != 16) return RT_ERROR_INVALID_ARGUMENT;
    rays_job job;
    memset(&job, 0, sizeof job);
    job.es = es;
    job.rays = rays;
    job.hits = hits;
    job.n = n;
    job.lanes = lanes;
    job.any_hit = any_hit;
    atomic_init(&job.next, 0);
    double t0 = rt_now_ms();
    rt_pool_run(pool, rays_worker, &job);
    *ms = rt_now_ms() - t0;
    return RT_OK;
}
