/* SPDX-License-Identifier: Apache-2.0 */
/* accel_cache.c - a renderer's BVHs and layout of one scene, kept up to date
 * frame by frame with the least work. */
#include "render/accel_cache.h"

#include <stdlib.h>
#include <string.h>

#include "accel/scene_boxes.h"
#include "accel/object_bvh.h"
#include "base/clock.h"
#include "base/error.h"

void rt_accel_cache_clear(rt_accel_cache *c) {
    for (uint32_t i = 0; i < c->mesh_count; i++) {
        rt_bvh_free(&c->bvhs[i]);
        rt_kd_free(&c->kds[i]);
        rt_bvh_refit_info_free(&c->refit[i]);
    }
    free(c->bvhs);
    free(c->kds);
    free(c->built_version);
    free(c->built_topology);
    free(c->built);
    free(c->dirty);
    free(c->parked);
    free(c->sah);
    free(c->sah_rebuilt);
    free(c->refit);
    free(c->updates);
    free(c->boxes);
    free(c->dirty_nodes);
    free(c->dirty_tris);
    rt_bvh_free(&c->top);
    rt_flat_free(&c->flat);
    rt_flat_shape_free(&c->shape);
    /* The generations keep counting, so that a backend never mistakes a new
     * layout for the one it holds. */
    uint32_t layout_generation = c->layout_generation, mesh_generation = c->mesh_generation;
    memset(c, 0, sizeof *c);
    c->layout_generation = layout_generation;
    c->mesh_generation = mesh_generation;
}

#define GROW(field, n)                                                                             \
    do {                                                                                           \
        void *p_ = realloc(c->field, sizeof *c->field * (n));                                      \
        if (!p_) return 0;                                                                         \
        c->field = p_;                                                                             \
    } while (0)

/* Grows the per-mesh arrays to the scene's mesh count. */
static int grow(rt_accel_cache *c, uint32_t meshes) {
    if (meshes <= c->mesh_count) return 1;
    GROW(bvhs, meshes);
    GROW(kds, meshes);
    GROW(built_version, meshes);
    GROW(built_topology, meshes);
    GROW(built, meshes);
    GROW(dirty, meshes);
    GROW(parked, meshes);
    GROW(sah, meshes);
    GROW(sah_rebuilt, meshes);
    GROW(refit, meshes);
    GROW(updates, meshes);
    GROW(dirty_nodes, meshes + 1);
    GROW(dirty_tris, meshes);
    for (uint32_t i = c->mesh_count; i < meshes; i++) {
        memset(&c->bvhs[i], 0, sizeof(rt_bvh));
        memset(&c->kds[i], 0, sizeof(rt_kd));
        memset(&c->refit[i], 0, sizeof(rt_bvh_refit_info));
        c->built[i] = 0;
        c->parked[i] = 0;
        c->dirty[i] = RT_DIRTY_ALL;
        c->sah[i] = c->sah_rebuilt[i] = 0.0;
    }
    c->mesh_count = meshes;
    return 1;
}

static rt_status tri_boxes(rt_accel_cache *c, const rt_mesh_data *md, rt_error *err) {
    if (md->triangle_count > c->boxes_cap) {
        rt_aabb *b = realloc(c->boxes, sizeof(rt_aabb) * md->triangle_count);
        if (!b) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
        c->boxes = b;
        c->boxes_cap = md->triangle_count;
    }
    rt_mesh_tri_boxes(md, c->boxes);
    return RT_OK;
}

/* A fresh build of mesh m's BVH with builder. */
static rt_status build(rt_accel_cache *c, const rt_mesh_data *md, uint32_t m, rt_builder builder,
                       rt_pool *pool, rt_error *err) {
    rt_bvh_free(&c->bvhs[m]);
    c->parked[m] = 0;
    rt_bvh_refit_info_free(&c->refit[m]);
    rt_build_options bo = rt_build_options_default();
    bo.builder = builder;
    rt_error why;
    rt_error_clear(&why);
    rt_status st;
    if (builder == RT_BUILDER_SAH) {
        /* Straight from the triangles: no box array at the build's peak. */
        st = rt_bvh_build_tris(md->positions, md->indices, md->triangle_count, &bo, pool,
                               &c->bvhs[m], &why);
    } else {
        st = tri_boxes(c, md, err);
        if (st != RT_OK) return st;
        st = rt_bvh_build(c->boxes, md->triangle_count, &bo, pool, &c->bvhs[m], &why);
    }
    if (st != RT_OK) return rt_fail(err, st, "BVH of mesh '%s': %s", md->name, why.message);
    return RT_OK;
}

static rt_status refit(rt_accel_cache *c, const rt_mesh_data *md, uint32_t m, rt_pool *pool,
                       rt_error *err) {
    if (!c->refit[m].parents && rt_bvh_refit_prepare(&c->bvhs[m], &c->refit[m]) != RT_OK)
        return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    rt_bvh_refit_tris(&c->bvhs[m], &c->refit[m], md->positions, md->indices, pool);
    return RT_OK;
}

/* Whether mesh m gets a kd-tree (the scene's one rule). */
static int mesh_is_kd(const rt_mesh_data *md) {
    return rt_mesh_data_structure(md) != RT_ACCEL_BVH;
}

/* Builds mesh m's kd-tree whole, and a BVH of its one root box for the
 * object BVH. */
static rt_status build_kd(rt_accel_cache *c, const rt_mesh_data *md, uint32_t m, rt_pool *pool,
                          rt_error *err) {
    rt_bvh_free(&c->bvhs[m]);
    c->parked[m] = 0;
    rt_bvh_refit_info_free(&c->refit[m]);
    rt_kd_options ko = rt_kd_options_default();
    ko.builder = md->accel == RT_ACCEL_KD ? RT_KD_EXACT : RT_KD_BINNED;
    rt_error why;
    rt_error_clear(&why);
    rt_status st = rt_kd_build(md->positions, md->vertex_count, md->indices, md->triangle_count,
                               &ko, pool, &c->kds[m], &why);
    if (st != RT_OK) return rt_fail(err, st, "kd-tree of mesh '%s': %s", md->name, why.message);
    /* The object BVH takes each mesh's box from its BVH's root: a kd mesh
     * gets a BVH of that one node (no entries, never traversed: the layout
     * holds the kd-tree). A tree with no triangle of any area has no box,
     * and the object BVH then leaves the object out, as nothing can hit it. */
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
    return RT_OK;
}

/* Brings mesh m's BVH up to date by its policy; records what it did. */
static rt_status update_mesh(rt_accel_cache *c, const rt_scene *scene, uint32_t m, rt_pool *pool,
                             rt_error *err) {
    const rt_mesh_data *md = &scene->meshes[m];
    if (c->built[m] && c->built_version[m] == md->version) return RT_OK;
    double t0 = rt_now_ms();
    int had = c->built[m];
    c->built[m] = 0;
    rt_update_action action = RT_ACTION_BUILD;
    double sah = 0.0;
    /* A kd mesh is static (rebuilt whole); what was one loses its tree. */
    int had_kd = c->kds[m].node_count != 0;
    rt_kd_free(&c->kds[m]);
    if (mesh_is_kd(md)) {
        rt_status st = build_kd(c, md, m, pool, err);
        if (st != RT_OK) return st;
    } else if (md->triangle_count) {
        rt_status st = RT_OK;
        rt_update_policy policy = (rt_update_policy)md->update_policy;
        int can_refit = had && !had_kd && c->built_topology[m] == md->topology_version &&
                        c->bvhs[m].prim_count == md->triangle_count && c->bvhs[m].node_count;
        if ((policy == RT_UPDATE_REFIT || policy == RT_UPDATE_AUTO) && can_refit) {
            st = refit(c, md, m, pool, err);
            action = RT_ACTION_REFIT;
            if (st == RT_OK && policy == RT_UPDATE_AUTO) {
                /* Refit while the tree stays within the bound of its last
                 * rebuild's cost; past it, rebuild. */
                sah = rt_bvh_sah_cost(&c->bvhs[m], rt_sah_costs_default());
                if (sah > RT_UPDATE_AUTO_BOUND * c->sah_rebuilt[m]) {
                    st = build(c, md, m, RT_BUILDER_SAH, pool, err);
                    action = RT_ACTION_REBUILD;
                }
            }
        } else if (policy == RT_UPDATE_LBVH) {
            st = build(c, md, m, RT_BUILDER_LBVH, pool, err);
            action = RT_ACTION_LBVH;
        } else {
            st = build(c, md, m, RT_BUILDER_SAH, pool, err);
        }
        if (st != RT_OK) return st;
    } else {
        rt_bvh_free(&c->bvhs[m]);
        c->parked[m] = 0;
        rt_bvh_refit_info_free(&c->refit[m]);
    }
    double ms = rt_now_ms() - t0;
    /* Measured outside the update's time (but for "auto", which needs it):
     * one pass over the nodes. */
    if (c->kds[m].node_count)
        sah = rt_kd_measure(&c->kds[m], rt_sah_costs_default()).sah;
    else if (action != RT_ACTION_REFIT || !sah)
        sah = rt_bvh_sah_cost(&c->bvhs[m], rt_sah_costs_default());
    if (action == RT_ACTION_BUILD || action == RT_ACTION_REBUILD || action == RT_ACTION_LBVH)
        c->sah_rebuilt[m] = sah;
    c->sah[m] = sah;
    c->built[m] = 1;
    c->built_version[m] = md->version;
    c->built_topology[m] = md->topology_version;
    if (action != RT_ACTION_REFIT)
        c->dirty[m] = RT_DIRTY_ALL;
    else if (c->dirty[m] != RT_DIRTY_ALL)
        c->dirty[m] = RT_DIRTY_MOVED;
    c->mesh_generation++;
    rt_mesh_update *u = &c->updates[c->update_count++];
    u->mesh = m;
    u->action = action;
    u->ms = ms;
    u->sah = sah;
    return RT_OK;
}

/* Whether the scene's meshes are rebuilt frame after frame by the LBVH
 * (policy lbvh), which reuses the triangle boxes' scratch (the SAH
 * builder reads the triangles themselves). */
static int keeps_boxes(const rt_scene *scene) {
    for (uint32_t m = 0; m < scene->mesh_count; m++)
        if (scene->meshes[m].update_policy == RT_UPDATE_LBVH) return 1;
    return 0;
}

/* Parks the static meshes the layout holds (accel_cache.h): their BVHs
 * keep the root node, the layout the tree. A mesh with another update
 * policy keeps its tree, which the next frame refits or replaces. */
/* Whether mesh m's tree may live in the layout alone (accel_cache.h):
 * a static BVH mesh the layout shows, with the tree the shape says. */
static int parkable(const rt_accel_cache *c, const rt_scene *scene, uint32_t m) {
    const rt_bvh *b = &c->bvhs[m];
    const rt_mesh_data *md = &scene->meshes[m];
    return !c->parked[m] && m < c->shape.mesh_count && c->shape.node_base[m] != UINT32_MAX &&
           md->triangle_count && !c->kds[m].node_count && md->update_policy == RT_UPDATE_SAH &&
           b->node_count >= 2 && b->node_count == c->shape.node_count[m] &&
           b->prim_count == c->shape.tri_count[m];
}

static void park(rt_accel_cache *c, const rt_scene *scene) {
    for (uint32_t m = 0; m < scene->mesh_count && m < c->shape.mesh_count; m++) {
        rt_bvh *b = &c->bvhs[m];
        if (!parkable(c, scene, m)) continue;
        rt_node *root = realloc(b->nodes, sizeof *root);
        if (root) b->nodes = root;
        free(b->prim_indices);
        b->prim_indices = NULL;
        b->node_count = 1;
        b->prim_count = 0;
        rt_bvh_refit_info_free(&c->refit[m]);
        c->parked[m] = 1;
    }
}

rt_status rt_accel_cache_unpark(rt_accel_cache *c) {
    for (uint32_t m = 0; m < c->mesh_count; m++) {
        if (!c->parked[m]) continue;
        uint32_t node_base = c->shape.node_base[m], tri_base = c->shape.tri_base[m];
        uint32_t nodes = c->shape.node_count[m], tris = c->shape.tri_count[m];
        rt_node *n = malloc(sizeof *n * nodes);
        uint32_t *prims = malloc(sizeof *prims * tris);
        if (!n || !prims) {
            free(n);
            free(prims);
            return RT_ERROR_OUT_OF_MEMORY;
        }
        /* The inverse of the layout's copy (flatten.c): indices less the
         * bases, boxes as they are. */
        for (uint32_t i = 0; i < nodes; i++) {
            n[i] = c->flat.nodes[node_base + i];
            if (n[i].b & RT_NODE_LEAF_FLAG) {
                n[i].a -= tri_base;
            } else {
                n[i].a -= node_base;
                n[i].b -= node_base;
            }
        }
        memcpy(prims, c->flat.tri_ids + tri_base, sizeof *prims * tris);
        rt_bvh *b = &c->bvhs[m];
        free(b->nodes);
        b->nodes = n;
        b->node_count = nodes;
        b->prim_indices = prims;
        b->prim_count = tris;
        c->parked[m] = 0;
    }
    return RT_OK;
}

static double mean_sah(const rt_accel_cache *c, const rt_scene *scene) {
    double sah = 0.0, weight = 0.0;
    for (uint32_t o = 0; o < scene->object_count; o++) {
        uint32_t m = rt_object_shown_mesh(&scene->objects[o]);
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
    c->update_count = 0;
    c->object_bvh_ms = c->layout_ms = 0.0;
    c->layout_bytes = 0;
    c->layout_in_place = 0;
    c->camera_only = 0;
    if (c->flat_valid && c->flat_scene_version == scene->version &&
        c->flat_camera_version != scene->camera_version) {
        /* Only the camera moved: the BVHs and every array of the layout
         * hold; the header takes the new camera. */
        double t1 = rt_now_ms();
        rt_flatten_camera(scene, &c->flat);
        c->flat_camera_version = scene->camera_version;
        c->layout_ms = rt_now_ms() - t1;
        c->layout_bytes = sizeof c->flat.hdr;
        c->layout_in_place = 1;
        c->camera_only = 1;
    } else if (!c->flat_valid || c->flat_scene_version != scene->version) {
        /* Each mesh once, though several objects show it. */
        for (uint32_t o = 0; o < scene->object_count; o++) {
            rt_status st =
                update_mesh(c, scene, rt_object_shown_mesh(&scene->objects[o]), pool, err);
            if (st != RT_OK) return st;
        }
        /* The triangle boxes are scratch of the builds: kept only for
         * scenes that rebuild cheaply frame after frame. */
        if (!keeps_boxes(scene)) {
            free(c->boxes);
            c->boxes = NULL;
            c->boxes_cap = 0;
        }
        /* The object BVH, every frame the scene changed: objects move. */
        double t1 = rt_now_ms();
        rt_bvh_free(&c->top);
        rt_error why;
        rt_error_clear(&why);
        if (scene->object_count) {
            rt_status st = rt_object_bvh_build(scene, c->bvhs, NULL, pool, &c->top, &why);
            if (st != RT_OK) return rt_fail(err, st, "object BVH: %s", why.message);
        }
        double t2 = rt_now_ms();
        c->object_bvh_ms = t2 - t1;
        rt_status st = RT_OK;
        /* A layout with kd meshes is made anew (rt_flatten_update refuses one
         * too): kd nodes live apart and kd meshes are never refitted. */
        int has_kd = 0;
        for (uint32_t m = 0; m < scene->mesh_count; m++) has_kd |= c->kds[m].node_count != 0;
        if (c->flat_valid && !has_kd &&
            rt_flatten_update(scene, c->bvhs, &c->top, c->dirty, &c->shape, &c->flat,
                              &c->layout_bytes) == RT_OK) {
            c->layout_in_place = 1;
            /* What changed, for backends holding the previous generation. */
            c->base_generation = c->layout_generation;
            c->dirty_node_ranges = c->dirty_tri_ranges = 0;
            c->shapes_kept = 1;
            for (uint32_t m = 0; m < scene->mesh_count; m++) {
                if (!c->dirty[m] || c->shape.node_base[m] == UINT32_MAX) continue;
                if (c->dirty[m] == RT_DIRTY_ALL) c->shapes_kept = 0;
                rt_flat_range n = {c->shape.node_base[m], c->shape.node_count[m], 0};
                rt_flat_range t = {c->shape.tri_base[m], c->shape.tri_count[m],
                                   c->dirty[m] == RT_DIRTY_MOVED};
                c->dirty_nodes[c->dirty_node_ranges++] = n;
                if (t.count) c->dirty_tris[c->dirty_tri_ranges++] = t;
            }
            rt_flat_range top = {c->shape.top_root, c->flat.node_count - c->shape.top_root, 0};
            if (top.count) c->dirty_nodes[c->dirty_node_ranges++] = top;
        } else {
            c->base_generation = 0;
            c->shapes_kept = 0;
            c->dirty_node_ranges = c->dirty_tri_ranges = 0;
            /* The parked trees come back out of the old layout first. */
            if (rt_accel_cache_unpark(c) != RT_OK)
                return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
            rt_flat_free(&c->flat);
            rt_flat_shape_free(&c->shape);
            c->flat_valid = 0;
            if (has_kd) {
                st = rt_flatten_accel(scene, c->bvhs, c->kds, &c->top, NULL, &c->flat, &why);
                if (st != RT_OK) return rt_fail(err, st, "%s", why.message);
            } else {
                /* The shape first: the static meshes' trees go into the
                 * layout (rt_flatten_take), each held once. */
                st = rt_flat_shape_of(scene, c->bvhs, &c->top, &c->shape);
                if (st != RT_OK) return rt_fail(err, st, "out of memory");
                uint8_t *take = calloc(scene->mesh_count ? scene->mesh_count : 1, 1);
                if (!take) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
                for (uint32_t m = 0; m < scene->mesh_count; m++) take[m] = parkable(c, scene, m);
                st = rt_flatten_take(scene, c->bvhs, take, &c->top, NULL, &c->flat, &why);
                for (uint32_t m = 0; m < scene->mesh_count; m++) {
                    if (!take[m]) continue;
                    if (st == RT_OK) {
                        c->parked[m] = 1;
                        rt_bvh_refit_info_free(&c->refit[m]);
                    } else {
                        /* Its tree went with the failed layout: built anew next time. */
                        rt_bvh_free(&c->bvhs[m]);
                        c->built[m] = 0;
                    }
                }
                free(take);
                if (st != RT_OK) {
                    rt_flat_shape_free(&c->shape);
                    return rt_fail(err, st, "%s", why.message);
                }
            }
            c->layout_bytes = rt_flat_bytes(&c->flat);
        }
        if (c->mesh_count) memset(c->dirty, 0, c->mesh_count); /* dirty is NULL without meshes */
        if (!has_kd) park(c, scene); /* the meshes rebuilt and rewritten in place */
        c->layout_ms = rt_now_ms() - t2;
        c->flat_valid = 1;
        c->flat_scene_version = scene->version;
        c->flat_camera_version = scene->camera_version;
        c->layout_generation++;
    }
    *build_ms = rt_now_ms() - t0;
    *sah_cost = mean_sah(c, scene);
    return RT_OK;
}

static uint64_t bvh_bytes(const rt_bvh *b) {
    return (uint64_t)b->node_count * sizeof(rt_node) + (uint64_t)b->prim_count * sizeof(uint32_t);
}

void rt_accel_cache_memory(const rt_accel_cache *c, rt_memory_stats *out) {
    for (uint32_t m = 0; m < c->mesh_count; m++) {
        out->mesh_bvhs += bvh_bytes(&c->bvhs[m]) +
                          (uint64_t)c->kds[m].node_count * sizeof(rt_kd_node) +
                          (uint64_t)c->kds[m].prim_count * sizeof(uint32_t);
        const rt_bvh_refit_info *r = &c->refit[m];
        if (r->parents)
            out->kept += (uint64_t)r->node_count * (sizeof(uint32_t) + sizeof(uint32_t)) +
                         (uint64_t)r->leaf_count * sizeof(uint32_t);
    }
    out->object_bvh += bvh_bytes(&c->top);
    out->kept += (uint64_t)c->boxes_cap * sizeof(rt_aabb);
    if (c->flat_valid) {
        out->layout += rt_flat_bytes(&c->flat);
        out->triangles += c->flat.tri_count;
    }
}
