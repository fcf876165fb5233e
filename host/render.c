/* render.c - rt_render: keeps the scene's BVHs and layout up to date and runs
 * one frame on the chosen backend ("cpu", the scalar oracle, or "packet", the
 * 2x2 NEON path). */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cpu_render.h"
#include "render_internal.h"
#include "tlas.h"

struct rt_render_cache {
    uint32_t mesh_count;
    rt_bvh *bvhs;
    uint32_t *built_tris, *built_verts; /* mesh sizes when its BVH was built */
    uint8_t *built;
    rt_bvh top;
    rt_flat flat;
    int flat_valid;
    uint32_t flat_version;
    rt_pool *pool;
    int pool_threads;
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
    free(c->built);
    rt_bvh_free(&c->top);
    rt_flat_free(&c->flat);
    if (c->pool) rt_pool_destroy(c->pool);
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
    }
    out->build_ms = rt_now_ms() - t0;
    out->flat = &c->flat;

    double sah = 0.0, weight = 0.0;
    for (uint32_t o = 0; o < scene->object_count; o++) {
        const rt_object_data *ob = &scene->objects[o];
        uint32_t m = ob->meshes[ob->selected];
        double n = (double)scene->meshes[m].triangle_count;
        if (n == 0) continue;
        sah += n * rt_bvh_measure(&c->bvhs[m], 1.0f, 2.0f).sah;
        weight += n;
    }
    out->sah_cost = weight > 0 ? sah / weight : 0.0;
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
    int packet = strcmp(backend, "packet") == 0;
    if (!packet && strcmp(backend, "cpu") != 0)
        return rt_scene_fail(scene, RT_ERROR_UNSUPPORTED,
                             "unknown or unavailable backend '%s' (this build renders with: cpu, "
                             "packet)",
                             backend);
    if (opt.aov < RT_AOV_NONE || opt.aov > RT_AOV_TRI_TESTS)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "unknown AOV %d", (int)opt.aov);
    rt_prepared prep;
    rt_status st = rt_render_prepare(scene, opt.threads, &prep);
    if (st != RT_OK) return st;

    rt_flat flat;
    st = rt_flat_with_tri_test(scene, prep.flat, opt.tri_test, &flat);
    if (st != RT_OK) return st;
    const rt_scene_header *h = &flat.hdr;
    int channels = (opt.aov == RT_AOV_NONE || opt.aov == RT_AOV_NORMAL) ? 3 : 1;
    memset(fb, 0, sizeof *fb);
    fb->pixels = calloc((size_t)h->width * (size_t)h->height * (size_t)channels, sizeof(float));
    if (!fb->pixels) return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    fb->width = h->width;
    fb->height = h->height;
    fb->channels = channels;

    rt_cpu_frame frame = {&flat, opt.aov, fb->pixels, channels, opt.progress, opt.progress_user};
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
        s->backend = packet ? "packet" : "cpu";
        s->threads = rt_pool_size(prep.pool);
    }
    return RT_OK;
}
