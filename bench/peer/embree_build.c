/* SPDX-License-Identifier: Apache-2.0 */
/* embree_build.c - Embree's builders as a benchmark peer (embree_peer.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <embree3/rtcore.h>

#include "base/clock.h"
#include "base/error.h"
#include "embree_peer.h"

struct rt_embree {
    RTCDevice device;
    RTCBVH bvh; /* reused, so that Embree can keep its node memory between builds */
};

/* The tree Embree's callbacks build: inner nodes and leaves share a header. */
typedef struct em_node {
    int is_leaf;
} em_node;

typedef struct em_inner {
    em_node head;
    em_node *child[2];
    float lo[2][3], hi[2][3];
} em_inner;

typedef struct em_leaf {
    em_node head;
    uint32_t count;
    uint32_t prims[]; /* primitive ids */
} em_leaf;

rt_status rt_embree_fail(rt_error *err, rt_status st, const char *what, void *device) {
    int code = device ? (int)rtcGetDeviceError((RTCDevice)device) : 0;
    return rt_fail(err, st, "embree: %s (error %d)", what, code);
}

rt_status rt_embree_create(int threads, rt_embree **out, rt_error *err) {
    *out = NULL;
    char config[64] = "";
    if (threads > 0) snprintf(config, sizeof config, "threads=%d", threads);
    rt_embree *em = calloc(1, sizeof *em);
    if (!em) return rt_embree_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory", NULL);
    em->device = rtcNewDevice(config);
    if (!em->device) {
        free(em);
        return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot create a device", NULL);
    }
    em->bvh = rtcNewBVH(em->device);
    if (!em->bvh) {
        rtcReleaseDevice(em->device);
        free(em);
        return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot create a BVH", NULL);
    }
    *out = em;
    return RT_OK;
}

void *rt_embree_device(rt_embree *em) {
    return em->device;
}

void rt_embree_destroy(rt_embree *em) {
    if (!em) return;
    rtcReleaseBVH(em->bvh);
    rtcReleaseDevice(em->device);
    free(em);
}

/* ---- rtcBuildBVH callbacks ------------------------------------------------- */

static void *create_node(RTCThreadLocalAllocator alloc, unsigned int child_count, void *user) {
    em_inner *n = rtcThreadLocalAlloc(alloc, sizeof(em_inner), 16);
    n->head.is_leaf = 0;
    n->child[0] = n->child[1] = NULL;
    return n;
}

static void set_children(void *node, void **children, unsigned int child_count, void *user) {
    em_inner *n = node;
    for (unsigned i = 0; i < child_count && i < 2; i++) n->child[i] = children[i];
}

static void set_bounds(void *node, const struct RTCBounds **bounds, unsigned int child_count,
                       void *user) {
    em_inner *n = node;
    for (unsigned i = 0; i < child_count && i < 2; i++) {
        n->lo[i][0] = bounds[i]->lower_x;
        n->lo[i][1] = bounds[i]->lower_y;
        n->lo[i][2] = bounds[i]->lower_z;
        n->hi[i][0] = bounds[i]->upper_x;
        n->hi[i][1] = bounds[i]->upper_y;
        n->hi[i][2] = bounds[i]->upper_z;
    }
}

static void *create_leaf(RTCThreadLocalAllocator alloc, const struct RTCBuildPrimitive *prims,
                         size_t count, void *user) {
    em_leaf *l = rtcThreadLocalAlloc(alloc, sizeof(em_leaf) + count * sizeof(uint32_t), 16);
    l->head.is_leaf = 1;
    l->count = (uint32_t)count;
    for (size_t i = 0; i < count; i++) l->prims[i] = prims[i].primID;
    return l;
}

/* ---- conversion into rt_bvh (depth first, left child next) ------------------ */

typedef struct conv {
    rt_bvh *out;
    const rt_aabb *boxes;
    uint32_t node_cap, next_prim;
} conv;

static int add_node(conv *cv, const em_node *node, const float lo[3], const float hi[3]) {
    /* Explicit stack: (node, box, index of the parent whose right child it is). */
    typedef struct item {
        const em_node *node;
        float lo[3], hi[3];
        uint32_t parent;
    } item;
    size_t cap = 256, top = 0;
    item *stack = malloc(cap * sizeof *stack);
    if (!stack) return 0;
    item first = {node, {lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}, UINT32_MAX};
    stack[top++] = first;
    while (top) {
        item it = stack[--top];
        if (cv->out->node_count == cv->node_cap) {
            uint32_t ncap = cv->node_cap * 2 + 16;
            rt_node *grown = realloc(cv->out->nodes, ncap * sizeof *grown);
            if (!grown) {
                free(stack);
                return 0;
            }
            cv->out->nodes = grown;
            cv->node_cap = ncap;
        }
        uint32_t idx = cv->out->node_count++;
        rt_node *n = &cv->out->nodes[idx];
        memcpy(n->bmin, it.lo, sizeof it.lo);
        memcpy(n->bmax, it.hi, sizeof it.hi);
        if (it.parent != UINT32_MAX) cv->out->nodes[it.parent].b = idx;
        if (it.node->is_leaf) {
            const em_leaf *l = (const em_leaf *)it.node;
            n->a = cv->next_prim;
            n->b = l->count | RT_NODE_LEAF_FLAG;
            for (uint32_t i = 0; i < l->count; i++)
                cv->out->prim_indices[cv->next_prim++] = l->prims[i];
            continue;
        }
        const em_inner *in = (const em_inner *)it.node;
        n->a = idx + 1;
        if (top + 2 > cap) {
            cap *= 2;
            item *grown = realloc(stack, cap * sizeof *grown);
            if (!grown) {
                free(stack);
                return 0;
            }
            stack = grown;
        }
        item r = {in->child[1],
                  {in->lo[1][0], in->lo[1][1], in->lo[1][2]},
                  {in->hi[1][0], in->hi[1][1], in->hi[1][2]},
                  idx};
        item l = {in->child[0],
                  {in->lo[0][0], in->lo[0][1], in->lo[0][2]},
                  {in->hi[0][0], in->hi[0][1], in->hi[0][2]},
                  UINT32_MAX};
        stack[top++] = r;
        stack[top++] = l;
    }
    free(stack);
    return 1;
}

rt_status rt_embree_build_bvh(rt_embree *em, const rt_aabb *boxes, uint32_t count,
                              const rt_build_options *options, rt_bvh *out, double *ms,
                              rt_error *err) {
    return rt_embree_build_bvh_quality(em, boxes, count, options, RT_EMBREE_MEDIUM, out, ms, err);
}

rt_status rt_embree_build_bvh_quality(rt_embree *em, const rt_aabb *boxes, uint32_t count,
                                      const rt_build_options *options, int quality, rt_bvh *out,
                                      double *ms, rt_error *err) {
    memset(out, 0, sizeof *out);
    *ms = 0.0;
    if (count == 0) return rt_embree_fail(err, RT_ERROR_INVALID_ARGUMENT, "no primitives", NULL);
    struct RTCBuildPrimitive *prims = aligned_alloc(32, sizeof *prims * count);
    if (!prims) return rt_embree_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory", NULL);
    float lo[3] = {boxes[0].bmin[0], boxes[0].bmin[1], boxes[0].bmin[2]};
    float hi[3] = {boxes[0].bmax[0], boxes[0].bmax[1], boxes[0].bmax[2]};
    for (uint32_t i = 0; i < count; i++) {
        const rt_aabb *b = &boxes[i];
        prims[i].lower_x = b->bmin[0];
        prims[i].lower_y = b->bmin[1];
        prims[i].lower_z = b->bmin[2];
        prims[i].upper_x = b->bmax[0];
        prims[i].upper_y = b->bmax[1];
        prims[i].upper_z = b->bmax[2];
        prims[i].geomID = 0;
        prims[i].primID = i;
        for (int k = 0; k < 3; k++) {
            lo[k] = b->bmin[k] < lo[k] ? b->bmin[k] : lo[k];
            hi[k] = b->bmax[k] > hi[k] ? b->bmax[k] : hi[k];
        }
    }
    struct RTCBuildArguments args = rtcDefaultBuildArguments();
    args.byteSize = sizeof args;
    /* LOW: Embree's Morton builder; MEDIUM: its binned SAH builder. */
    args.buildQuality = quality == RT_EMBREE_LOW ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM;
    args.buildFlags = RTC_BUILD_FLAG_NONE;
    args.maxBranchingFactor = 2;
    args.maxDepth = 1024;
    args.sahBlockSize = 1;
    args.minLeafSize = 1;
    args.maxLeafSize = (unsigned)options->leaf_size;
    args.traversalCost = options->costs.traverse;
    args.intersectionCost = options->costs.intersect;
    args.bvh = em->bvh;
    args.primitives = prims;
    args.primitiveCount = count;
    args.primitiveArrayCapacity = count;
    args.createNode = create_node;
    args.setNodeChildren = set_children;
    args.setNodeBounds = set_bounds;
    args.createLeaf = create_leaf;
    double t0 = rt_now_ms();
    const em_node *root = rtcBuildBVH(&args);
    *ms = rt_now_ms() - t0;
    free(prims);
    if (!root) return rt_embree_fail(err, RT_ERROR_BACKEND, "rtcBuildBVH failed", em->device);

    conv cv = {out, boxes, 0, 0};
    out->prim_indices = malloc(sizeof(uint32_t) * count);
    out->prim_count = count;
    if (!out->prim_indices || !add_node(&cv, root, lo, hi)) {
        rt_bvh_free(out);
        return rt_embree_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory", NULL);
    }
    if (cv.next_prim != count) {
        rt_bvh_free(out);
        return rt_embree_fail(err, RT_ERROR_BACKEND, "the tree does not hold every primitive",
                              NULL);
    }
    return RT_OK;
}

rt_status rt_embree_commit_ms(rt_embree *em, const float *positions, uint32_t vertex_count,
                              const uint32_t *indices, uint32_t triangle_count, int quality,
                              double *ms, rt_error *err) {
    *ms = 0.0;
    enum RTCBuildQuality q = quality ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_LOW;
    RTCScene scene = rtcNewScene(em->device);
    if (!scene) return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot create a scene", em->device);
    rtcSetSceneBuildQuality(scene, q);
    RTCGeometry geom = rtcNewGeometry(em->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geom) {
        rtcReleaseScene(scene);
        return rt_embree_fail(err, RT_ERROR_BACKEND, "cannot create a geometry", em->device);
    }
    rtcSetGeometryBuildQuality(geom, q);
    /* Embree's own buffers are padded for its 16-byte loads. */
    float *v = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), vertex_count);
    unsigned *ix = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), triangle_count);
    rt_status st = RT_OK;
    if (!v || !ix) {
        st = rt_embree_fail(err, RT_ERROR_OUT_OF_MEMORY, "cannot allocate buffers", em->device);
    } else {
        memcpy(v, positions, sizeof(float) * 3 * vertex_count);
        memcpy(ix, indices, sizeof(unsigned) * 3 * triangle_count);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene, geom);
        double t0 = rt_now_ms();
        rtcCommitScene(scene);
        *ms = rt_now_ms() - t0;
        if (rtcGetDeviceError(em->device) != RTC_ERROR_NONE)
            st = rt_embree_fail(err, RT_ERROR_BACKEND, "rtcCommitScene failed", em->device);
    }
    rtcReleaseGeometry(geom);
    rtcReleaseScene(scene);
    return st;
}
