/* render.c - rt_render: keeps the scene's BVHs and layout up to date and runs
 * one frame on the chosen backend ("cpu", the scalar oracle, or "packet", the
 * SIMD packet path). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cpu_render.h"
#include "packet_trace.h"
#include "render/render_internal.h"
#include "accel/tlas.h"

struct rt_render_cache {
    uint32_t mesh_count;
    rt_bvh *bvhs;
    uint32_t *built_tris, *built_verts; /* mesh sizes when its BVH was built */
    double *sah;                        /* its SAH cost (for the statistics) */
    uint8_t *built;
    rt_bvh top;
    rt_flat flat;
    int flat_valid;
    uint32_t flat_version;
    uint32_t flat_generation; /* bumped by every flatten */
    rt_pk_wide wide;          /* the packet backend's wide BVHs of flat ... */
    uint32_t wide_generation; /* ... made from this flatten (0: none) */
    rt_pool *pool;
    int pool_threads;
    uint32_t mesh_generation; /* bumped by every mesh BVH (re)build */
    void *backend_state;      /* a device backend's state (uploaded buffers) */
    void (*backend_state_free)(void *state);
};

double rt_now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

rt_render_options rt_render_options_default(void) {
    rt_render_options o;
    memset(&o, 0, sizeof o);
    o.backend = "cpu";
    return o;
}

void rt_framebuffer_free(rt_framebuffer *fb) {
    if (!fb) return;
    free(fb->pixels);
    fb->pixels = NULL;
}

void rt_render_cache_free(struct rt_render_cache *c) {
    if (!c) return;
    for (uint32_t i = 0; i < c->mesh_count; i++) rt_bvh_free(&c->bvhs[i]);
    free(c->bvhs);
    free(c->built_tris);
    free(c->built_verts);
    free(c->sah);
    free(c->built);
    rt_bvh_free(&c->top);
    rt_flat_free(&c->flat);
    rt_pk_wide_free(&c->wide);
    if (c->pool) rt_pool_destroy(c->pool);
    if (c->backend_state_free) c->backend_state_free(c->backend_state);
    free(c);
}

/* Grows the per-mesh arrays to the scene's mesh count. */
static int cache_grow(struct rt_render_cache *c, uint32_t meshes) {
    if (meshes <= c->mesh_count) return 1;
    rt_bvh *b = realloc(c->bvhs, sizeof(rt_bvh) * meshes);
    if (!b) return 0;
    c->bvhs = b;
    uint32_t *t = realloc(c->built_tris, sizeof(uint32_t) * meshes);
    if (!t) return 0;
    c->built_tris = t;
    uint32_t *v = realloc(c->built_verts, sizeof(uint32_t) * meshes);
    if (!v) return 0;
    c->built_verts = v;
    uint8_t *f = realloc(c->built, meshes);
    if (!f) return 0;
    c->built = f;
    double *h = realloc(c->sah, sizeof(double) * meshes);
    if (!h) return 0;
    c->sah = h;
    for (uint32_t i = c->mesh_count; i < meshes; i++) {
        memset(&c->bvhs[i], 0, sizeof(rt_bvh));
        c->built[i] = 0;
    }
    c->mesh_count = meshes;
    return 1;
}

static rt_status build_mesh(rt_scene *scene, struct rt_render_cache *c, uint32_t m) {
    const rt_mesh_data *md = &scene->meshes[m];
    /* Meshes only grow (rt_mesh_add_triangles appends), so their sizes tell
     * whether the cached BVH is still the mesh's. */
    if (c->built[m] && c->built_tris[m] == md->triangle_count &&
        c->built_verts[m] == md->vertex_count)
        return RT_OK;
    rt_bvh_free(&c->bvhs[m]);
    c->built[m] = 0;
    if (md->triangle_count) {
        rt_aabb *boxes = malloc(sizeof(rt_aabb) * md->triangle_count);
        if (!boxes) return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory");
        rt_mesh_tri_boxes(md, boxes);
        rt_build_options bo = rt_build_options_default();
        char msg[256] = "";
        rt_status st =
            rt_bvh_build(boxes, md->triangle_count, &bo, c->pool, &c->bvhs[m], msg, sizeof msg);
        free(boxes);
        if (st != RT_OK) return rt_scene_fail(scene, st, "BVH of mesh '%s': %s", md->name, msg);
    }
    c->built[m] = 1;
    /* Measured once per build, not per frame: it walks the whole tree. */
    c->sah[m] = md->triangle_count ? rt_bvh_measure(&c->bvhs[m], 1.0f, 2.0f).sah : 0.0;
    c->mesh_generation++;
    c->built_tris[m] = md->triangle_count;
    c->built_verts[m] = md->vertex_count;
    return RT_OK;
}

rt_status rt_render_prepare(rt_scene *scene, int threads, rt_prepared *out) {
    memset(out, 0, sizeof *out);
    rt_status st = rt_scene_commit(scene);
    if (st != RT_OK) return st;
    if (!scene->render_cache) {
        scene->render_cache = calloc(1, sizeof(struct rt_render_cache));
        if (!scene->render_cache)
            return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    struct rt_render_cache *c = scene->render_cache;
    int want = threads > 0 ? threads : rt_cpu_count();
    if (!c->pool || c->pool_threads != want) {
        if (c->pool) rt_pool_destroy(c->pool);
        c->pool = rt_pool_create(want);
        c->pool_threads = want;
        if (!c->pool) return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "no worker threads");
    }
    out->pool = c->pool;
    if (!cache_grow(c, scene->mesh_count))
        return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory");

    double t0 = rt_now_ms();
    if (!c->flat_valid || c->flat_version != scene->version) {
        for (uint32_t o = 0; o < scene->object_count; o++) {
            const rt_object_data *ob = &scene->objects[o];
            st = build_mesh(scene, c, ob->meshes[ob->selected]);
            if (st != RT_OK) return st;
        }
        /* The object BVH, every frame the scene changed: objects move. */
        rt_bvh_free(&c->top);
        if (scene->object_count) {
            char msg[256] = "";
            st = rt_tlas_build(scene, c->bvhs, NULL, c->pool, &c->top, msg, sizeof msg);
            if (st != RT_OK) return rt_scene_fail(scene, st, "object BVH: %s", msg);
        }
        rt_flat_free(&c->flat);
        c->flat_valid = 0;
        char msg[256] = "";
        st = rt_flatten(scene, c->bvhs, &c->top, NULL, &c->flat, msg, sizeof msg);
        if (st != RT_OK) return rt_scene_fail(scene, st, "%s", msg);
        c->flat_valid = 1;
        c->flat_version = scene->version;
        c->flat_generation++;
    }
    out->build_ms = rt_now_ms() - t0;
    out->flat = &c->flat;
    out->mesh_generation = c->mesh_generation;
    out->flat_version = c->flat_version;
    out->backend_state = &c->backend_state;
    out->backend_state_free = &c->backend_state_free;

    double sah = 0.0, weight = 0.0;
    for (uint32_t o = 0; o < scene->object_count; o++) {
        const rt_object_data *ob = &scene->objects[o];
        uint32_t m = ob->meshes[ob->selected];
        double n = (double)scene->meshes[m].triangle_count;
        if (n == 0) continue;
        sah += n * c->sah[m];
        weight += n;
    }
    out->sah_cost = weight > 0 ? sah / weight : 0.0;
    return RT_OK;
}

const char *rt_backend_split(const char *backend, char *name_out, size_t name_size) {
    const char *colon = strchr(backend, ':');
    size_t n = colon ? (size_t)(colon - backend) : strlen(backend);
    if (n >= name_size) n = name_size - 1;
    memcpy(name_out, backend, n);
    name_out[n] = 0;
    return colon ? colon + 1 : NULL;
}

/* Which backend runs: "cpu", "packet", or a device backend. "auto" takes
 * OpenCL when this build has it and a device exists, else the CPU with a
 * notice in the statistics (the caller decides whether to show it). */
typedef struct backend_choice {
    int packet;
    const rt_backend_ops *device_ops;
    const char *device; /* after "opencl:" */
    const char *notice;
} backend_choice;

static rt_status choose_backend(rt_scene *scene, const char *backend, const char *what,
                                backend_choice *out) {
    static char notice[320];
    char name[32];
    memset(out, 0, sizeof *out);
    out->device = rt_backend_split(backend, name, sizeof name);
    const rt_backend_ops *cl = RT_OPENCL_OPS;
    if (strcmp(name, "cpu") == 0 && !out->device) return RT_OK;
    if (strcmp(name, "packet") == 0 && !out->device) {
        out->packet = 1;
        return RT_OK;
    }
    if (strcmp(name, "opencl") == 0) {
        if (!cl)
            return rt_scene_fail(scene, RT_ERROR_UNSUPPORTED,
                                 "this build has no OpenCL backend (configure with "
                                 "-DRT_OPENCL=ON and the OpenCL ICD loader installed)");
        out->device_ops = cl;
        return RT_OK;
    }
    if (strcmp(name, "auto") == 0) {
        char why[256] = "this build has no OpenCL backend";
        if (cl && cl->available(why, sizeof why)) {
            out->device_ops = cl;
            return RT_OK;
        }
        snprintf(notice, sizeof notice, "OpenCL not available (%s): using the CPU", why);
        out->notice = notice;
        return RT_OK;
    }
    return rt_scene_fail(scene, RT_ERROR_UNSUPPORTED,
                         "unknown or unavailable backend '%s' (%s: cpu, packet, auto%s)", backend,
                         what, cl ? ", opencl[:DEVICE]" : "");
}

rt_status rt_render_wide(rt_scene *scene, rt_prepared *prep, const rt_pk_wide **out) {
    struct rt_render_cache *c = scene->render_cache;
    if (c->wide_generation != c->flat_generation) {
        double t0 = rt_now_ms();
        rt_pk_wide_free(&c->wide);
        c->wide_generation = 0;
        if (rt_pk_wide_build(&c->flat, &c->wide) != RT_OK)
            return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory (packet BVH)");
        c->wide_generation = c->flat_generation;
        prep->build_ms += rt_now_ms() - t0;
    }
    *out = &c->wide;
    return RT_OK;
}

/* The public enum mirrors the layout's RT_TRI_* numbers. */
_Static_assert(RT_TRI_TEST_WATERTIGHT == RT_TRI_WATERTIGHT && RT_TRI_TEST_MOLLER == RT_TRI_MOLLER &&
                   RT_TRI_TEST_PLUECKER == RT_TRI_PLUECKER && RT_TRI_TEST_BADOUEL == RT_TRI_BADOUEL,
               "rt_triangle_test and RT_TRI_* differ");

rt_status rt_flat_with_tri_test(rt_scene *scene, const rt_flat *flat, rt_triangle_test test,
                                rt_flat *out) {
    if ((int)test < RT_TRI_TEST_WATERTIGHT || (int)test > RT_TRI_TEST_BADOUEL)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "unknown triangle test %d",
                             (int)test);
    *out = *flat;
    out->hdr.tri_method = (uint32_t)test;
    return RT_OK;
}

rt_status rt_render(rt_scene *scene, const rt_render_options *options, rt_framebuffer *fb) {
    if (!scene || !fb) return RT_ERROR_INVALID_ARGUMENT;
    rt_render_options opt = options ? *options : rt_render_options_default();
    const char *backend = opt.backend ? opt.backend : "cpu";
    backend_choice choice;
    rt_status st = choose_backend(scene, backend, "this build renders with", &choice);
    if (st != RT_OK) return st;
    int packet = choice.packet;
    if (opt.aov < RT_AOV_NONE || opt.aov > RT_AOV_TRI_TESTS)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "unknown AOV %d", (int)opt.aov);
    rt_prepared prep;
    st = rt_render_prepare(scene, opt.threads, &prep);
    if (st != RT_OK) return st;

    rt_flat flat;
    st = rt_flat_with_tri_test(scene, prep.flat, opt.tri_test, &flat);
    if (st != RT_OK) return st;
    if (opt.direct_only) flat.hdr.flags &= ~(uint32_t)RT_SCENE_SECONDARY;
    const rt_scene_header *h = &flat.hdr;
    int channels = (opt.aov == RT_AOV_NONE || opt.aov == RT_AOV_NORMAL) ? 3 : 1;
    int reuse = opt.reuse_framebuffer && fb->pixels && fb->width == h->width &&
                fb->height == h->height && fb->channels == channels;
    if (!reuse) {
        if (opt.reuse_framebuffer) rt_framebuffer_free(fb);
        memset(fb, 0, sizeof *fb);
        fb->pixels = calloc((size_t)h->width * (size_t)h->height * (size_t)channels, sizeof(float));
        if (!fb->pixels) return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    fb->width = h->width;
    fb->height = h->height;
    fb->channels = channels;

    if (choice.device_ops) {
        rt_render_stats local;
        rt_render_stats *s = opt.stats ? opt.stats : &local;
        memset(s, 0, sizeof *s);
        rt_prepared with_test = prep; /* the device compiles the triangle test in */
        with_test.flat = &flat;
        st = choice.device_ops->render(scene, &with_test, choice.device, &opt, fb, s);
        if (st != RT_OK) {
            rt_framebuffer_free(fb);
            return st;
        }
        s->sah_cost = prep.sah_cost;
        s->build_ms = prep.build_ms;
        s->backend = choice.device_ops->name;
        return RT_OK;
    }

    const rt_pk_wide *wide = NULL;
    if (packet && (st = rt_render_wide(scene, &prep, &wide)) != RT_OK) {
        rt_framebuffer_free(fb);
        return st;
    }
    rt_cpu_frame frame = {&flat,    wide,         opt.aov,          fb->pixels,
                          channels, opt.progress, opt.progress_user};
    rt_cpu_counts counts;
    double t0 = rt_now_ms();
    if (packet)
        rt_packet_render(&frame, prep.pool, &counts);
    else
        rt_cpu_render(&frame, prep.pool, &counts);
    double ms = rt_now_ms() - t0;
    if (opt.stats) {
        rt_render_stats *s = opt.stats;
        memset(s, 0, sizeof *s);
        s->sah_cost = prep.sah_cost;
        s->build_ms = prep.build_ms;
        s->render_ms = ms;
        s->rays = counts.rays;
        s->primary_rays = counts.primary_rays;
        s->box_tests = counts.box_tests;
        s->tri_tests = counts.tri_tests;
        s->packets = counts.packets;
        s->packet_box_tests = counts.packet_box_tests;
        s->packet_tri_tests = counts.packet_tri_tests;
        if (packet) {
            s->packet_rays = RT_PK_LANES;
            s->packet_isa = rt_pk_isa();
            s->packet_vector = rt_pk_isa_lanes();
        }
        s->backend = packet ? "packet" : "cpu";
        s->threads = rt_pool_size(prep.pool);
        s->notice = choice.notice;
    }
    return RT_OK;
}

/* rt_trace_rays's backend choice (host/trace.c). */
rt_status rt_trace_backend(rt_scene *scene, const char *backend, int *packet,
                           const rt_backend_ops **device_ops, const char **device) {
    backend_choice choice;
    rt_status st = choose_backend(scene, backend, "ray queries run on", &choice);
    if (st != RT_OK) return st;
    *packet = choice.packet;
    *device_ops = choice.device_ops;
    *device = choice.device;
    return RT_OK;
}
