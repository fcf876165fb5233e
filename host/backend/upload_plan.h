/* SPDX-License-Identifier: Apache-2.0 */
/* upload_plan.h - what a device backend copies to bring its copy of the
 * flattened layout up to date, one rule for OpenCL and Vulkan: nothing when
 * the device holds this layout and header; the header alone when only it
 * changed (the camera moved, a render option); the changed node and
 * triangle ranges of a layout rewritten in place (refits) plus the
 * per-frame arrays; the per-frame arrays (object BVH, instances, header,
 * materials, lights) when the meshes are the same; else everything. Each
 * backend makes the buffers and executes the copies. */
#ifndef RT_UPLOAD_PLAN_H
#define RT_UPLOAD_PLAN_H

#include <stddef.h>
#include <stdint.h>

#include "backend/backend.h"

/* The layout's arrays, in rt_scene_view's order (bindings 0..9 of both
 * backends), then the kd-tree nodes. */
enum {
    RT_UP_HDR,
    RT_UP_NODES,
    RT_UP_TRIS,
    RT_UP_TRI_IDS,
    RT_UP_NORMALS,
    RT_UP_TRI_MATS,
    RT_UP_INST,
    RT_UP_INST_IDS,
    RT_UP_MATS,
    RT_UP_LIGHTS,
    RT_UP_KD_NODES,
    RT_UP_COUNT
};

/* What the device holds; all zero: nothing. */
typedef struct rt_upload_memo {
    uint32_t *mesh_sig; /* what identifies the mesh part (upload_plan.c) */
    size_t mesh_sig_len;
    int valid;
    uint32_t generation; /* the layout generation */
    rt_scene_header hdr;
} rt_upload_memo;

/* One copy: bytes from src to offset of array's buffer. */
typedef struct rt_upload_copy {
    int array; /* RT_UP_* */
    size_t offset;
    const void *src;
    size_t bytes;
} rt_upload_copy;

typedef struct rt_upload_plan {
    size_t bytes[RT_UP_COUNT]; /* what each buffer must hold */
    int buffers;               /* 1: make every buffer hold bytes[i] before the copies */
    /* private */
    const void *data[RT_UP_COUNT]; /* where each array is */
    int nothing, header_only, partial, mesh_same;
    size_t mesh_node_bytes; /* the object BVH's nodes start here */
    uint32_t *sig;
    size_t sig_len;
} rt_upload_plan;

/* Plans the upload of layout to a device holding memo, whose buffer for
 * array i holds cap[i] bytes now. Then, when plan->buffers, the backend
 * makes buffer i hold plan->bytes[i], noting in remade[i] whether its
 * contents were lost. RT_ERROR_OUT_OF_MEMORY when the plan cannot be
 * allocated. */
rt_status rt_upload_plan_make(const rt_upload_memo *memo, const rt_backend_layout *layout,
                              const size_t cap[RT_UP_COUNT], rt_upload_plan *plan);

/* Calls emit for each copy the plan needs, given which buffers were made
 * anew (ignored unless plan->buffers); stops at the first status other
 * than RT_OK and returns it. */
rt_status rt_upload_plan_run(const rt_upload_plan *plan, const rt_backend_layout *layout,
                             const int remade[RT_UP_COUNT],
                             rt_status (*emit)(void *user, const rt_upload_copy *c), void *user);

/* Records the outcome in memo (ok: the device now holds layout; else
 * nothing) and frees the plan. */
void rt_upload_plan_finish(rt_upload_plan *plan, rt_upload_memo *memo,
                           const rt_backend_layout *layout, int ok);

void rt_upload_memo_free(rt_upload_memo *memo);

#endif /* RT_UPLOAD_PLAN_H */
