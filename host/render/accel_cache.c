/* accel_cache.c - a renderer's BVHs and layout of one scene, kept up to date
 * frame by frame with the least work. */
#include "render/accel_cache.h"

#include <stdlib.h>
#include <string.h>

#include "accel/scene_boxes.h"
#include "accel/tlas.h"
#include "base/clock.h"
#include "base/error.h"
#include "layout/flatten.h"

void rt_accel_cache_clear(rt_accel_cache *c) {
    for (uint32_t i = 0; i < c->mesh_count; i++) {
        rt_bvh_free(&c->bvhs[i]);
        rt_kd_free(&c->kds[i]);
    }
    free(c->bvhs);
    free(c->kds);
    free(c->built_version);
    free(c->built);
    free(c->sah);
    rt_bvh_free(&c->top);
    rt_flat_free(&c->flat);
    /* The generations keep counting, so that a backend never mistakes a new
     * layout for the one it holds. */
    uint32_t layout_generation = c->layout_generation, mesh_generation = c->mesh_generation;
    memset(c, 0, sizeof *c);
    c->layout_generation = layout_generation;
    c->mesh_generation = mesh_generation;
}

/* Grows the per-mesh arrays to the scene's mesh count. */
static int grow(rt_accel_cache *c, uint32_t meshes) {
    if (meshes <= c->mesh_count) return 1;
    rt_bvh *b = realloc(c->bvhs, sizeof(rt_bvh) * meshes);
    if (!b) return 0;
    c->bvhs = b;
    rt_kd *k = realloc(c->kds, sizeof(rt_kd) * meshes);
    if (!k) return 0;
    c->kds = k;
    uint32_t *v = realloc(c->built_version, sizeof(uint32_t) * meshes);
    if (!v) return 0;
    c->built_version = v;
    uint8_t *f = realloc(c->built, meshes);
    if (!f) return 0;
    c->built = f;
    double *h = realloc(c->sah, sizeof(double) * meshes);
    if (!h) return 0;
    c->sah = h;
    for (uint32_t i = c->mesh_count; i < meshes; i++) {
        memset(&c->bvhs[i], 0, sizeof(rt_bvh));
        memset(&c->kds[i], 0, sizeof(rt_kd));
        c->built[i] = 0;
        c->sah[i] = 0.0;
    }
    c->mesh_count = meshes;
    return 1;
}

static rt_status build_mesh(rt_accel_cache *c, const rt_scene *scene, uint32_t m, rt_pool *pool,
                            rt_error *err) {
    const rt_mesh_data *md = &scene->meshes[m];
    if (c->built[m] && c->built_version[m] == md->version) return RT_OK;
    rt_bvh_free(&c->bvhs[m]);
    rt_kd_free(&c->kds[m]);
    c->built[m] = 0;
    if (md->accel == RT_ACCEL_KD || md->accel == RT_ACCEL_KD_BINNED) {
        rt_kd_options ko = rt_kd_options_default();
        ko.builder = md->accel == RT_ACCEL_KD ? RT_KD_EXACT : RT_KD_BINNED;
        rt_error why;
        rt_error_clear(&why);
        rt_status st = rt_kd_build(md->positions, md->vertex_count, md->indices, md->triangle_count,
                                   &ko, pool, &c->kds[m], &why);
        if (st != RT_OK) return rt_fail(err, st, "kd-tree of mesh '%s': %s", md->name, why.message);
        /* The object BVH takes each mesh's box from its BVH's root: a kd
         * mesh gets a BVH of that one node (no entries, never traversed:
         * the layout holds the kd-tree). A tree with no triangle of any
         * area has no box, and the object BVH then leaves the object out,
         * as nothing can hit it. */
        const rt_aabb *bb = &c->kds[m].bounds;
        if (bb->bmin[0] <= bb->bmax[0]) {
            rt_bvh *b = &c->bvhs[m];
            b->nodes = calloc(1, sizeof(rt_node));
            if (!b->nodes) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
            memcpy(b->nodes[0].bmin, bb->bmin, sizeof bb->bmin);
            memcpy(b->nodes[0].bmax, bb->bmax, sizeof bb->bmax);
            b->nodes[0].b = RT_NODE_LEAF_FLAG;
            b->node_count = 1;
        }
    } else if (md->triangle_count) {
        rt_aabb *boxes = malloc(sizeof(rt_aabb) * md->triangle_count);
        if (!boxes) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
        rt_mesh_tri_boxes(md, boxes);
        rt_build_options bo = rt_build_options_default();
        rt_error why;
        rt_error_clear(&why);
        rt_status st = rt_bvh_build(boxes, md->triangle_count, &bo, pool, &c->bvhs[m], &why);
        free(boxes);
        if (st != RT_OK) return rt_fail(err, st, "BVH of mesh '%s': %s", md->name, why.message);
    }
    c->built[m] = 1;
    c->built_version[m] = md->version;
    /* Measured once per build, not per frame: it walks the whole tree. */
    c->sah[m] = c->kds[m].node_count ? rt_kd_measure(&c->kds[m], 1.0f, 2.0f).sah
                : md->triangle_count ? rt_bvh_measure(&c->bvhs[m], 1.0f, 2.0f).sah
                                     : 0.0;
    c->mesh_generation++;
    return RT_OK;
}

static double mean_sah(const rt_accel_cache *c, const rt_scene *scene) {
    double sah = 0.0, weight = 0.0;
    for (uint32_t o = 0; o < scene->object_count; o++) {
        const rt_object_data *ob = &scene->objects[o];
        uint32_t m = ob->meshes[ob->selected];
        double n = (double)scene->meshes[m].triangle_count;
        if (n == 0) continue;
        sah += n * c->sah[m];
        weight += n;
    }
    return weight > 0 ? sah / weight : 0.0;
}

rt_status rt_accel_cache_update(rt_accel_cache *c, const rt_scene *scene, rt_pool *pool,
                                double *build_ms, double *sah_cost, rt_error *err) {
    double t0 = rt_now_ms();
    *build_ms = 0.0;
    if (c->scene_uid != scene->uid) {
        rt_accel_cache_clear(c);
        c->scene_uid = scene->uid;
    }
    if (!grow(c, scene->mesh_count)) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    if (!c->flat_valid || c->flat_scene_version != scene->version) {
        for (uint32_t o = 0; o < scene->object_count; o++) {
            const rt_object_data *ob = &scene->objects[o];
            rt_status st = build_mesh(c, scene, ob->meshes[ob->selected], pool, err);
            if (st != RT_OK) return st;
        }
        /* The object BVH, every frame the scene changed: objects move. */
        rt_bvh_free(&c->top);
        rt_error why;
        rt_error_clear(&why);
        if (scene->object_count) {
            rt_status st = rt_tlas_build(scene, c->bvhs, NULL, pool, &c->top, &why);
            if (st != RT_OK) return rt_fail(err, st, "object BVH: %s", why.message);
        }
        rt_flat_free(&c->flat);
        c->flat_valid = 0;
        rt_status st = rt_flatten_accel(scene, c->bvhs, c->kds, &c->top, NULL, &c->flat, &why);
        if (st != RT_OK) return rt_fail(err, st, "%s", why.message);
        c->flat_valid = 1;
        c->flat_scene_version = scene->version;
        c->layout_generation++;
    }
    *build_ms = rt_now_ms() - t0;
    *sah_cost = mean_sah(c, scene);
    return RT_OK;
}
