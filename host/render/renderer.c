/* SPDX-License-Identifier: Apache-2.0 */
/* renderer.c - rt_renderer: the caller-owned context that keeps a scene's
 * BVHs and layout, the worker threads and the backends' state between
 * frames (Langr 2016's RayTracerContext). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "render/backend_registry.h"
#include "render/renderer_internal.h"

rt_renderer_options rt_renderer_options_default(void) {
    rt_renderer_options o;
    memset(&o, 0, sizeof o);
    o.backend = "cpu";
    return o;
}

const char *rt_renderer_error(const rt_renderer *r) {
    return r ? r->error.message : "";
}

const rt_backend_slot *rt_renderer_slot(const rt_renderer *r) {
    return &r->slots[r->current];
}

const char *rt_renderer_backend(const rt_renderer *r) {
    return r ? r->slots[r->current].ops->name : "";
}

const char *rt_renderer_build_log(const rt_renderer *r) {
    if (!r || r->slot_count == 0) return "";
    const rt_backend_slot *slot = &r->slots[r->current];
    return slot->ops->build_log ? slot->ops->build_log(slot->state) : "";
}

/* The slot for a backend spec: the one made before for it, or a new one.
 * On failure the renderer is unchanged. */
static rt_status find_slot(rt_renderer *r, const rt_backend_ops *ops, const char *spec,
                           const char *device, int *slot, rt_error *err) {
    for (int i = 0; i < r->slot_count; i++)
        if (r->slots[i].ops == ops && strcmp(r->slots[i].spec, spec) == 0) {
            *slot = i;
            return RT_OK;
        }
    if (r->slot_count == RT_RENDERER_SLOTS)
        return rt_fail(err, RT_ERROR_UNSUPPORTED,
                       "a renderer keeps at most %d backends; make another renderer",
                       RT_RENDERER_SLOTS);
    rt_backend_config config;
    memset(&config, 0, sizeof config);
    config.device = device;
    config.device_options = r->device_options[0] ? r->device_options : NULL;
    config.packet_isa = r->packet_isa[0] ? r->packet_isa : NULL;
    config.opencl = r->opencl;
    config.device_math = r->device_math;
    config.flush_denormals = r->denormals == RT_DENORMALS_FLUSH;
    config.on_compile = r->on_compile;
    config.on_compile_user = r->on_compile_user;
    void *state = NULL;
    rt_status st = ops->create(&config, &state, err);
    if (st != RT_OK) return st;
    rt_backend_slot *s = &r->slots[r->slot_count];
    snprintf(s->spec, sizeof s->spec, "%s", spec);
    s->ops = ops;
    s->state = state;
    *slot = r->slot_count++;
    return RT_OK;
}

static rt_status set_backend(rt_renderer *r, const char *spec, rt_error *err) {
    if (!spec) spec = "cpu";
    char name[32];
    const char *colon = strchr(spec, ':');
    size_t n = colon ? (size_t)(colon - spec) : strlen(spec);
    if (n >= sizeof name) return rt_fail(err, RT_ERROR_UNSUPPORTED, "unknown backend '%s'", spec);
    memcpy(name, spec, n);
    name[n] = 0;
    const char *device = colon ? colon + 1 : NULL;
    if (strlen(spec) >= sizeof r->slots[0].spec)
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "backend name too long: '%.40s...'", spec);

    const rt_backend_ops *ops;
    char notice[sizeof r->notice] = "";
    char chosen[sizeof r->slots[0].spec];
    snprintf(chosen, sizeof chosen, "%s", spec);
    if (strcmp(name, "auto") == 0) {
        /* The first device backend with a device, on the device asked for;
         * else the CPU. It shares the slot of the backend it chose. */
        rt_error why;
        rt_error_clear(&why);
        ops = rt_backend_auto(&why);
        if (!ops) {
            snprintf(notice, sizeof notice, "%.480s: using the CPU", why.message);
            ops = rt_backend_find("cpu", err);
            device = NULL;
        }
        if (device)
            snprintf(chosen, sizeof chosen, "%s:%s", ops->name, device);
        else
            snprintf(chosen, sizeof chosen, "%s", ops->name);
    } else {
        ops = rt_backend_find(name, err);
        if (!ops) return RT_ERROR_UNSUPPORTED;
        if (device && !rt_backend_takes_device(ops))
            return rt_fail(err, RT_ERROR_UNSUPPORTED,
                           "backend '%s' runs on the CPU and takes no device ('%s')", name, spec);
    }
    int slot = 0;
    rt_status st = find_slot(r, ops, chosen, device, &slot, err);
    if (st != RT_OK) return st;
    r->current = slot;
    memcpy(r->notice, notice, sizeof notice);
    return RT_OK;
}

rt_status rt_renderer_create(const rt_renderer_options *options, rt_renderer **out, rt_error *err) {
    if (!out) return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "rt_renderer_create: out is NULL");
    *out = NULL;
    rt_renderer_options o = options ? *options : rt_renderer_options_default();
    if (o.device_options && strlen(o.device_options) > 255)
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "device options longer than 255 characters");
    if (o.packet_isa && strlen(o.packet_isa) >= 32)
        return rt_fail(err, RT_ERROR_UNSUPPORTED, "unknown packet instruction set '%.40s'",
                       o.packet_isa);
    if ((unsigned)o.device_math > RT_DEVICE_MATH_PORTABLE)
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "unknown device maths profile %d",
                       (int)o.device_math);
    if ((unsigned)o.denormals > RT_DENORMALS_FLUSH)
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "unknown denormal policy %d",
                       (int)o.denormals);
    rt_renderer *r = calloc(1, sizeof *r);
    if (!r) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    r->threads = o.threads;
    snprintf(r->device_options, sizeof r->device_options, "%s",
             o.device_options ? o.device_options : "");
    snprintf(r->packet_isa, sizeof r->packet_isa, "%s", o.packet_isa ? o.packet_isa : "");
    r->opencl = o.opencl;
    r->device_math = o.device_math;
    r->denormals = o.denormals;
    r->on_compile = o.on_compile;
    r->on_compile_user = o.on_compile_user;
    r->pool = rt_pool_create(o.threads);
    if (!r->pool) {
        free(r);
        return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "no worker threads");
    }
    rt_status st = set_backend(r, o.backend, err);
    if (st != RT_OK) {
        rt_renderer_destroy(r);
        return st;
    }
    *out = r;
    return RT_OK;
}

void rt_renderer_destroy(rt_renderer *r) {
    if (!r) return;
    for (int i = 0; i < r->slot_count; i++) r->slots[i].ops->destroy(r->slots[i].state);
    rt_accel_cache_clear(&r->accel);
    if (r->pool) rt_pool_destroy(r->pool);
    free(r);
}

rt_status rt_renderer_set_backend(rt_renderer *r, const char *backend) {
    if (!r) return RT_ERROR_INVALID_ARGUMENT;
    rt_error_clear(&r->error);
    return set_backend(r, backend, &r->error);
}

rt_status rt_renderer_layout(rt_renderer *r, rt_scene *scene, rt_backend_layout *out,
                             double *build_ms, double *sah_cost) {
    memset(out, 0, sizeof *out);
    rt_status st = rt_scene_commit(scene);
    if (st != RT_OK) return rt_error_copy(&r->error, &scene->error);
    st = rt_accel_cache_update(&r->accel, scene, r->pool, build_ms, sah_cost, &r->error);
    if (st != RT_OK) return st;
    out->flat = &r->accel.flat;
    out->pool = r->pool;
    out->layout_generation = r->accel.layout_generation;
    out->mesh_generation = r->accel.mesh_generation;
    out->base_generation = r->accel.base_generation;
    out->dirty_nodes = r->accel.dirty_nodes;
    out->dirty_node_ranges = r->accel.dirty_node_ranges;
    out->dirty_tris = r->accel.dirty_tris;
    out->dirty_tri_ranges = r->accel.dirty_tri_ranges;
    out->shapes_kept = r->accel.shapes_kept;
    return RT_OK;
}

rt_status rt_renderer_update_stats(const rt_renderer *r, rt_update_stats *out) {
    if (!r || !out) return RT_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    out->meshes = r->accel.updates;
    out->mesh_count = r->accel.update_count;
    out->object_bvh_ms = r->accel.object_bvh_ms;
    out->layout_ms = r->accel.layout_ms;
    out->layout_in_place = r->accel.layout_in_place;
    out->layout_bytes = r->accel.layout_bytes;
    out->camera_only = r->accel.camera_only;
    return RT_OK;
}

rt_status rt_renderer_memory(const rt_renderer *r, const rt_scene *scene, rt_memory_stats *out) {
    if (!r || !out) return RT_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    for (uint32_t m = 0; scene && m < scene->mesh_count; m++) {
        const rt_mesh_data *md = &scene->meshes[m];
        out->scene += (uint64_t)md->vertex_count * 3 * sizeof(float) * (md->normals ? 2 : 1) +
                      (uint64_t)md->triangle_count *
                          (3 * sizeof(uint32_t) + (md->tri_materials ? sizeof(uint32_t) : 0));
    }
    if (scene && r->accel.scene_uid == scene->uid) rt_accel_cache_memory(&r->accel, out);
    const rt_backend_slot *slot = rt_renderer_slot(r);
    if (slot->ops && slot->ops->memory && slot->state)
        slot->ops->memory(slot->state, &out->backend, &out->device);
    return RT_OK;
}
