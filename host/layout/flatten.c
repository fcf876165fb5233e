/* SPDX-License-Identifier: Apache-2.0 */
/* flatten.c - scene + BVHs -> the device layout (kernels/rt_layout.h). */
#include "layout/flatten.h"

#include "base/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

rt_flat_options rt_flat_options_default(void) {
    rt_flat_options o;
    o.tri_method = RT_TRI_WATERTIGHT;
    o.max_depth = 5;
    o.min_weight = 1.0f / 256.0f;
    return o;
}

/* Depth of a BVH (the root alone is 1), without recursion. */
static uint32_t bvh_depth(const rt_bvh *b) {
    if (!b->node_count) return 0;
    /* Depth-first with a cap, so that even a cyclic tree ends. */
    size_t cap = 4 * (size_t)b->node_count + 4 * (RT_STACK_SIZE + 4);
    uint32_t *stack = malloc(sizeof(uint32_t) * cap);
    if (!stack) return UINT32_MAX;
    uint32_t sp = 0, depth = 0;
    stack[sp++] = 0;
    stack[sp++] = 1;
    while (sp) {
        uint32_t d = stack[--sp], n = stack[--sp];
        if (d > depth) depth = d;
        const rt_node *node = &b->nodes[n];
        if (!(node->b & RT_NODE_LEAF_FLAG) && d <= RT_STACK_SIZE && sp + 4 <= cap) {
            stack[sp++] = node->a;
            stack[sp++] = d + 1;
            stack[sp++] = node->b;
            stack[sp++] = d + 1;
        }
    }
    free(stack);
    return depth;
}

/* Checks a BVH's indices so that no backend can read out of bounds. */
static int bvh_valid(const rt_bvh *b, uint32_t prim_limit, rt_error *err, const char *what) {
    for (uint32_t i = 0; i < b->node_count; i++) {
        const rt_node *n = &b->nodes[i];
        if (n->b & RT_NODE_LEAF_FLAG) {
            uint64_t end = (uint64_t)n->a + (n->b & RT_NODE_COUNT_MASK);
            if (end > b->prim_count) {
                rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                        "%s BVH: leaf %u references entries past the end", what, i);
                return 0;
            }
        } else if (n->a >= b->node_count || n->b >= b->node_count || n->a == i || n->b == i) {
            rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "%s BVH: node %u has bad children", what, i);
            return 0;
        }
    }
    for (uint32_t i = 0; i < b->prim_count; i++)
        if (b->prim_indices[i] >= prim_limit) {
            rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "%s BVH: primitive index out of range", what);
            return 0;
        }
    uint32_t depth = bvh_depth(b);
    if (depth > RT_STACK_SIZE) {
        rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "%s BVH is %u levels deep; traversal supports %d",
                what, depth, RT_STACK_SIZE);
        return 0;
    }
    return 1;
}

/* Checks a kd-tree's indices and depth so that no backend can read out of
 * bounds or overflow its stack (kernels/rt_kd.h). */
static int kd_valid(const rt_kd *kd, uint32_t prim_limit, rt_error *err, const char *what) {
    if (!kd->node_count) return 0;
    for (uint32_t i = 0; i < kd->node_count; i++) {
        const rt_kd_node *n = &kd->nodes[i];
        if ((n->b & 3u) == RT_KD_LEAF) {
            if ((uint64_t)n->a + (n->b >> 2) > kd->prim_count) {
                rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                        "%s kd-tree: leaf %u references entries past the end", what, i);
                return 0;
            }
        } else if (i + 1 >= kd->node_count || (n->b >> 2) <= i + 1 ||
                   (n->b >> 2) >= kd->node_count) {
            /* Depth-first order: children come after their parent, so the
             * walk below ends. */
            rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "%s kd-tree: node %u has bad children", what,
                    i);
            return 0;
        }
    }
    for (uint32_t i = 0; i < kd->prim_count; i++)
        if (kd->prims[i] >= prim_limit) {
            rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "%s kd-tree: triangle index out of range",
                    what);
            return 0;
        }
    /* Depth: the deepest path from the root, by a walk in node order (a
     * child's index is larger than its parent's). */
    uint8_t *depth = calloc(kd->node_count, 1);
    if (!depth) return 0;
    depth[0] = 1;
    int deep = 0;
    for (uint32_t i = 0; i < kd->node_count && !deep; i++) {
        const rt_kd_node *n = &kd->nodes[i];
        if (depth[i] > RT_KD_STACK - 2) deep = 1;
        if ((n->b & 3u) == RT_KD_LEAF) continue;
        depth[i + 1] = (uint8_t)(depth[i] + 1);
        depth[n->b >> 2] = (uint8_t)(depth[i] + 1);
    }
    free(depth);
    if (deep) {
        rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "%s kd-tree is deeper than traversal supports (%d)",
                what, RT_KD_STACK - 2);
        return 0;
    }
    return 1;
}

/* An empty tree: one leaf with no entries and an inverted box. */
static void empty_node(rt_node *n, uint32_t first) {
    for (int k = 0; k < 3; k++) {
        n->bmin[k] = INFINITY;
        n->bmax[k] = -INFINITY;
    }
    n->a = first;
    n->b = RT_NODE_LEAF_FLAG;
}

/* Copies a BVH's nodes to dst with child indices moved by node_base and leaf
 * entries by entry_base. */
static void copy_nodes(const rt_bvh *b, rt_node *dst, uint32_t node_base, uint32_t entry_base) {
    for (uint32_t i = 0; i < b->node_count; i++) {
        rt_node n = b->nodes[i];
        if (n.b & RT_NODE_LEAF_FLAG) {
            n.a += entry_base;
        } else {
            n.a += node_base;
            n.b += node_base;
        }
        dst[i] = n;
    }
}

static void camera_of(const rt_camera *c, rt_scene_header *h) {
    double f[3], r[3], u[3];
    rt_camera_frame_d(c, f, r, u); /* rt_camera_set accepted only finite frames */
    double tx = tan((double)c->hfov_degrees * 3.14159265358979323846 / 360.0);
    double ty = tx * (double)c->height / (double)c->width;
    for (int i = 0; i < 3; i++) {
        h->cam_pos[i] = c->position[i];
        h->cam_forward[i] = (float)f[i];
        h->cam_right[i] = (float)(r[i] * tx);
        h->cam_up[i] = (float)(u[i] * ty);
    }
    h->width = c->width;
    h->height = c->height;
}

/* Stores a triangle; a zero-area one (edge cross product exactly zero) as a
 * point, which every triangle test rejects. */
static void store_tri(const rt_mesh_data *m, uint32_t t, rt_tri *out) {
    const uint32_t *idx = m->indices + 3 * t;
    const float *p0 = m->positions + 3 * idx[0], *p1 = m->positions + 3 * idx[1],
                *p2 = m->positions + 3 * idx[2];
    float e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = p1[k] - p0[k];
        e2[k] = p2[k] - p0[k];
    }
    rt_cross3(e1, e2, n);
    int degenerate = n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f;
    for (int k = 0; k < 3; k++) {
        out->v0[k] = p0[k];
        out->v1[k] = degenerate ? p0[k] : p1[k];
        out->v2[k] = degenerate ? p0[k] : p2[k];
    }
}

static void write_mesh(rt_flat *out, const rt_mesh_data *md, const rt_bvh *b, uint32_t node_base,
                       uint32_t tri_base);
static void write_tris(rt_flat *out, const rt_mesh_data *md, const rt_bvh *b, uint32_t node_base,
                       uint32_t tri_base);
static rt_status write_frame(const rt_scene *scene, const rt_bvh *top, const rt_kd *mesh_kds,
                             int single, uint32_t top_root, const uint32_t *node_base,
                             const uint32_t *tri_base, const uint32_t *tri_span,
                             const rt_flat_options *opt, rt_flat *out, rt_error *err);

rt_status rt_flatten(const rt_scene *scene, const rt_bvh *mesh_bvhs, const rt_bvh *top,
                     const rt_flat_options *options, rt_flat *out, rt_error *err) {
    return rt_flatten_accel(scene, mesh_bvhs, NULL, top, options, out, err);
}

/* Whether mesh m goes into the layout as a kd-tree. */
static const rt_kd *kd_of(const rt_kd *mesh_kds, uint32_t m) {
    return mesh_kds && mesh_kds[m].node_count ? &mesh_kds[m] : NULL;
}

static rt_status flatten(const rt_scene *scene, rt_bvh *mesh_bvhs, const uint8_t *take,
                         const rt_kd *mesh_kds, const rt_bvh *top, const rt_flat_options *options,
                         rt_flat *out, rt_error *err);

rt_status rt_flatten_accel(const rt_scene *scene, const rt_bvh *mesh_bvhs, const rt_kd *mesh_kds,
                           const rt_bvh *top, const rt_flat_options *options, rt_flat *out,
                           rt_error *err) {
    /* Nothing is taken, so the BVHs are only read. */
    return flatten(scene, (rt_bvh *)mesh_bvhs, NULL, mesh_kds, top, options, out, err);
}

rt_status rt_flatten_take(const rt_scene *scene, rt_bvh *mesh_bvhs, const uint8_t *take,
                          const rt_bvh *top, const rt_flat_options *options, rt_flat *out,
                          rt_error *err) {
    return flatten(scene, mesh_bvhs, take, NULL, top, options, out, err);
}

/* Leaves a taken mesh's BVH as its root node alone (the layout holds the
 * tree); root is that node as the layout has it. */
static void leave_root(rt_bvh *b, const rt_node *root) {
    rt_node *n = malloc(sizeof *n);
    free(b->nodes);
    free(b->prim_indices);
    memset(b, 0, sizeof *b);
    if (!n) return; /* no root: the caller's BVH is empty, and rebuilt */
    *n = *root;
    b->nodes = n;
    b->node_count = 1;
}

static rt_status flatten(const rt_scene *scene, rt_bvh *mesh_bvhs, const uint8_t *take,
                         const rt_kd *mesh_kds, const rt_bvh *top, const rt_flat_options *options,
                         rt_flat *out, rt_error *err) {
    memset(out, 0, sizeof *out);
    rt_flat_options opt = options ? *options : rt_flat_options_default();
    if (opt.tri_method > RT_TRI_BADOUEL || opt.max_depth > RT_MAX_DEPTH) {
        rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "triangle test %u or depth %u out of range",
                opt.tri_method, opt.max_depth);
        return RT_ERROR_INVALID_ARGUMENT;
    }
    uint32_t nmesh = scene->mesh_count, nobj = scene->object_count;
    rt_status failed = RT_ERROR_INVALID_ARGUMENT; /* what fail: returns */

    /* Which meshes are shown, and where each goes. */
    uint32_t *node_base = calloc(nmesh ? nmesh : 1, sizeof(uint32_t));
    uint32_t *tri_base = calloc(nmesh ? nmesh : 1, sizeof(uint32_t));
    uint32_t *tri_span = calloc(nmesh ? nmesh : 1, sizeof(uint32_t));
    uint32_t *kd_base = calloc(nmesh ? nmesh : 1, sizeof(uint32_t));
    uint8_t *used = calloc(nmesh ? nmesh : 1, 1);
    if (!node_base || !tri_base || !tri_span || !kd_base || !used) goto oom;
    for (uint32_t o = 0; o < nobj; o++) {
        const rt_object_data *ob = &scene->objects[o];
        used[rt_object_shown_mesh(ob)] = 1;
    }
    uint64_t nodes = 0, tris = 0, kd_nodes = 0;
    int any_normals = 0, any_mats = 0;
    for (uint32_t m = 0; m < nmesh; m++) {
        if (!used[m]) continue;
        const rt_mesh_data *md = &scene->meshes[m];
        const rt_kd *kd = kd_of(mesh_kds, m);
        if (kd) {
            if (!kd_valid(kd, md->triangle_count, err, md->name)) goto fail;
            node_base[m] = (uint32_t)nodes;
            tri_base[m] = (uint32_t)tris;
            kd_base[m] = (uint32_t)kd_nodes;
            tri_span[m] = kd->prim_count;
            nodes += 1;
            tris += kd->prim_count;
            kd_nodes += kd->node_count;
            any_normals |= md->normals != NULL;
            any_mats |= md->tri_materials != NULL;
            continue;
        }
        const rt_bvh *b = &mesh_bvhs[m];
        if (md->triangle_count && (b->prim_count != md->triangle_count || !b->node_count)) {
            rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "mesh '%s': its BVH holds %u of %u triangles",
                    md->name, b->prim_count, md->triangle_count);
            goto fail;
        }
        if (md->triangle_count && !bvh_valid(b, md->triangle_count, err, md->name)) goto fail;
        node_base[m] = (uint32_t)nodes;
        tri_base[m] = (uint32_t)tris;
        nodes += md->triangle_count ? b->node_count : 1;
        tris += md->triangle_count;
        tri_span[m] = md->triangle_count;
        any_normals |= md->normals != NULL;
        any_mats |= md->tri_materials != NULL;
    }
    int single = nobj == 1 && rt_transform_is_identity(scene->objects[0].transform);
    /* The object BVH may leave out objects whose mesh is empty. */
    if (nobj > 1 || (nobj == 1 && !single)) {
        if (!top || top->prim_count > nobj || (top->prim_count && !top->node_count)) {
            rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                    "the object BVH is missing or holds the wrong objects");
            goto fail;
        }
        if (!bvh_valid(top, nobj, err, "object")) goto fail;
    }
    uint32_t top_root = (uint32_t)nodes;
    if (!single && nobj) nodes += top->node_count ? top->node_count : 1;
    if (nodes >= RT_NODE_COUNT_MASK || tris >= RT_NODE_COUNT_MASK || kd_nodes >= (1u << 30)) {
        rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "scene too large for 31-bit indices");
        goto fail;
    }

    out->node_count = (uint32_t)nodes;
    out->tri_count = (uint32_t)tris;
    /* A taken mesh at the layout's start (a one-mesh scene) gives it its
     * node and entry arrays: at base 0 the layout's nodes are the BVH's as
     * they are, and its triangle ids the BVH's primitive indices. */
    uint32_t first = UINT32_MAX;
    for (uint32_t m = 0; take && m < nmesh && first == UINT32_MAX; m++)
        if (used[m] && take[m] && !kd_of(mesh_kds, m) && scene->meshes[m].triangle_count &&
            node_base[m] == 0 && tri_base[m] == 0)
            first = m;
    if (first != UINT32_MAX) {
        rt_bvh *b = &mesh_bvhs[first];
        rt_node *n = realloc(b->nodes, sizeof(rt_node) * nodes);
        if (!n) goto oom;
        b->nodes = NULL;
        out->nodes = n;
        uint32_t *ids = realloc(b->prim_indices, sizeof(uint32_t) * (tris ? tris : 1));
        if (!ids) goto oom;
        b->prim_indices = NULL;
        out->tri_ids = ids;
    } else {
        out->nodes = malloc(sizeof(rt_node) * (nodes ? nodes : 1));
        out->tri_ids = malloc(sizeof(uint32_t) * (tris ? tris : 1));
    }
    out->tris = malloc(sizeof(rt_tri) * (tris ? tris : 1));
    if (any_normals) out->tri_normals = calloc(9 * (tris ? tris : 1), sizeof(float));
    if (any_mats) out->tri_mats = malloc(sizeof(uint32_t) * (tris ? tris : 1));
    out->instances = calloc(nobj ? nobj : 1, sizeof(rt_instance));
    out->inst_id_count = single || !nobj ? 0 : top->prim_count;
    out->inst_ids = malloc(sizeof(uint32_t) * (out->inst_id_count ? out->inst_id_count : 1));
    out->materials =
        calloc(scene->material_count ? scene->material_count : 1, sizeof(rt_material_d));
    out->lights = calloc(scene->light_count ? scene->light_count : 1, sizeof(rt_light_d));
    out->kd_node_count = (uint32_t)kd_nodes;
    if (kd_nodes) {
        out->kd_nodes = malloc(sizeof(rt_kd_node) * kd_nodes);
        if (!out->kd_nodes) goto oom;
    }
    if (!out->nodes || !out->tris || !out->tri_ids || (any_normals && !out->tri_normals) ||
        (any_mats && !out->tri_mats) || !out->instances || !out->inst_ids || !out->materials ||
        !out->lights)
        goto oom;

    for (uint32_t m = 0; m < nmesh; m++) {
        if (!used[m]) continue;
        const rt_mesh_data *md = &scene->meshes[m];
        const rt_kd *kd = kd_of(mesh_kds, m);
        if (m == first) {
            /* Nodes and ids in place already: the triangles, in id order. */
            rt_bvh in_place = mesh_bvhs[m];
            in_place.nodes = out->nodes;
            in_place.prim_indices = out->tri_ids;
            write_tris(out, md, &in_place, 0, 0);
            leave_root(&mesh_bvhs[m], &out->nodes[0]);
            continue;
        }
        if (!kd) {
            write_mesh(out, md, &mesh_bvhs[m], node_base[m], tri_base[m]);
            if (take && take[m] && md->triangle_count)
                leave_root(&mesh_bvhs[m], &out->nodes[node_base[m]]);
            continue;
        }
        /* The root box, then the tree with absolute indices. */
        rt_node *root = &out->nodes[node_base[m]];
        memcpy(root->bmin, kd->bounds.bmin, sizeof root->bmin);
        memcpy(root->bmax, kd->bounds.bmax, sizeof root->bmax);
        root->a = kd_base[m];
        root->b = RT_NODE_LEAF_FLAG;
        for (uint32_t i = 0; i < kd->node_count; i++) {
            rt_kd_node n = kd->nodes[i];
            if ((n.b & 3u) == RT_KD_LEAF)
                n.a += tri_base[m];
            else
                n.b = (((n.b >> 2) + kd_base[m]) << 2) | (n.b & 3u);
            out->kd_nodes[kd_base[m] + i] = n;
        }
        for (uint32_t j = 0; j < tri_span[m]; j++) {
            uint32_t t = kd->prims[j], e = tri_base[m] + j;
            store_tri(md, t, &out->tris[e]);
            out->tri_ids[e] = t;
            if (md->normals) {
                for (int v = 0; v < 3; v++)
                    memcpy(out->tri_normals + 9 * (size_t)e + 3 * v,
                           md->normals + 3 * (size_t)md->indices[3 * t + v], 3 * sizeof(float));
            }
            if (out->tri_mats)
                out->tri_mats[e] = md->tri_materials ? md->tri_materials[t] : RT_NO_MATERIAL;
        }
    }
    if (write_frame(scene, top, mesh_kds, single, top_root, node_base, tri_base, tri_span, &opt,
                    out, err) != RT_OK)
        goto fail;

    free(node_base);
    free(tri_base);
    free(tri_span);
    free(kd_base);
    free(used);
    return RT_OK;
oom:
    failed = rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory flattening the scene");
fail:
    /* A tree given to the layout went with it: that BVH is empty now. */
    for (uint32_t m = 0; take && m < nmesh; m++)
        if (take[m] && !mesh_bvhs[m].nodes) rt_bvh_free(&mesh_bvhs[m]);
    free(node_base);
    free(tri_base);
    free(tri_span);
    free(kd_base);
    free(used);
    rt_flat_free(out);
    return failed;
}

/* Writes a mesh's BVH nodes and triangles at its place in the layout;
 * moved_only: only the nodes and the vertices (and normals), the tree's
 * shape and the triangle order being the same as written before (a refit). */
static void write_tris_as(rt_flat *out, const rt_mesh_data *md, const rt_bvh *b, uint32_t tri_base,
                          int moved_only);

static void write_mesh_as(rt_flat *out, const rt_mesh_data *md, const rt_bvh *b, uint32_t node_base,
                          uint32_t tri_base, int moved_only) {
    if (!md->triangle_count) {
        empty_node(&out->nodes[node_base], tri_base);
        return;
    }
    copy_nodes(b, out->nodes + node_base, node_base, tri_base);
    write_tris_as(out, md, b, tri_base, moved_only);
}

/* The mesh's triangles (and ids, normals, materials) in the order of its
 * BVH's entries, from tri_base on. */
static void write_tris_as(rt_flat *out, const rt_mesh_data *md, const rt_bvh *b, uint32_t tri_base,
                          int moved_only) {
    for (uint32_t j = 0; j < b->prim_count; j++) {
        uint32_t t = b->prim_indices[j], e = tri_base + j;
        store_tri(md, t, &out->tris[e]);
        if (!moved_only) out->tri_ids[e] = t;
        if (md->normals) {
            for (int v = 0; v < 3; v++)
                memcpy(out->tri_normals + 9 * (size_t)e + 3 * v,
                       md->normals + 3 * (size_t)md->indices[3 * t + v], 3 * sizeof(float));
        }
        if (out->tri_mats && !moved_only)
            out->tri_mats[e] = md->tri_materials ? md->tri_materials[t] : RT_NO_MATERIAL;
    }
}

static void write_mesh(rt_flat *out, const rt_mesh_data *md, const rt_bvh *b, uint32_t node_base,
                       uint32_t tri_base) {
    write_mesh_as(out, md, b, node_base, tri_base, 0);
}

static void write_tris(rt_flat *out, const rt_mesh_data *md, const rt_bvh *b, uint32_t node_base,
                       uint32_t tri_base) {
    (void)node_base;
    write_tris_as(out, md, b, tri_base, 0);
}

/* Writes what changes with every frame: the object BVH, the instances,
 * materials, lights and the header with the camera. */
static rt_status write_frame(const rt_scene *scene, const rt_bvh *top, const rt_kd *mesh_kds,
                             int single, uint32_t top_root, const uint32_t *node_base,
                             const uint32_t *tri_base, const uint32_t *tri_span,
                             const rt_flat_options *opt_in, rt_flat *out, rt_error *err) {
    rt_flat_options opt = *opt_in;
    rt_scene_features feat = rt_scene_features_of(scene);
    uint32_t nobj = scene->object_count;
    int any_normals = out->tri_normals != NULL, any_mats = out->tri_mats != NULL;
    for (uint32_t o = 0; o < nobj; o++) /* no box: an object the object BVH left out */
        for (int k = 0; k < 3; k++) {
            out->instances[o].bmin[k] = RT_INF;
            out->instances[o].bmax[k] = -RT_INF;
        }
    if (!single && nobj && !top->node_count) empty_node(&out->nodes[top_root], 0);
    if (!single && nobj && top->node_count) {
        copy_nodes(top, out->nodes + top_root, top_root, 0);
        memcpy(out->inst_ids, top->prim_indices, sizeof(uint32_t) * top->prim_count);
        /* Each instance's acceptance box (rt_hit_accepted): the box of the
         * leaf holding it, which contains its own box (object_bvh.c widened it)
         * and lies inside every box above it, in this tree and in the wide
         * copies the CPU backends make of it. */
        for (uint32_t i = 0; i < top->node_count; i++) {
            const rt_node *n = &top->nodes[i];
            if (!(n->b & RT_NODE_LEAF_FLAG)) continue;
            for (uint32_t e = n->a; e < n->a + (n->b & RT_NODE_COUNT_MASK); e++) {
                rt_instance *in = &out->instances[top->prim_indices[e]];
                memcpy(in->bmin, n->bmin, sizeof in->bmin);
                memcpy(in->bmax, n->bmax, sizeof in->bmax);
            }
        }
    }

    for (uint32_t o = 0; o < nobj; o++) {
        const rt_object_data *ob = &scene->objects[o];
        rt_instance *in = &out->instances[o];
        uint32_t m = rt_object_shown_mesh(ob);
        float inv[16];
        if (!rt_mat4_affine_inverse(ob->transform, inv))
            return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "object %u: its transform is singular",
                           o);
        memcpy(in->world_to_object, inv, 12 * sizeof(float));
        memcpy(in->object_to_world, ob->transform, 12 * sizeof(float));
        in->root = node_base[m];
        in->material = ob->material;
        in->flags = (rt_transform_is_identity(ob->transform) ? RT_INST_IDENTITY : 0u) |
                    (scene->meshes[m].normals ? RT_INST_NORMALS : 0u) |
                    (kd_of(mesh_kds, m) ? RT_INST_KD : 0u);
        in->mesh = m;
        in->tri_first = tri_base[m];
        in->tri_count = tri_span[m];
        in->mask = ob->mask;
    }
    for (uint32_t i = 0; i < scene->material_count; i++) {
        const rt_material *s = &scene->materials[i];
        rt_material_d *d = &out->materials[i];
        memcpy(d->color, s->color, sizeof d->color);
        d->ambient = s->ambient;
        d->diffuse = s->diffuse;
        d->specular = s->specular;
        d->shininess = s->shininess;
        d->reflectivity = s->reflectivity;
        d->transparency = s->transparency;
        d->ior = s->ior;
        memcpy(d->emission, s->emission, sizeof d->emission);
    }
    for (uint32_t i = 0; i < scene->light_count; i++) {
        memcpy(out->lights[i].position, scene->lights[i].position, 3 * sizeof(float));
        memcpy(out->lights[i].color, scene->lights[i].color, 3 * sizeof(float));
    }

    rt_scene_header *h = &out->hdr;
    h->flags = ((feat.reflection || feat.refraction) ? RT_SCENE_SECONDARY : 0u) |
               (single ? RT_SCENE_SINGLE : 0u) | (any_normals ? RT_SCENE_NORMALS : 0u) |
               (any_mats ? RT_SCENE_TRI_MATS : 0u);
    h->top_root = single ? 0 : top_root;
    h->instance_count = nobj;
    h->light_count = scene->light_count;
    h->material_count = scene->material_count;
    h->tri_method = opt.tri_method;
    h->max_depth = opt.max_depth;
    h->min_weight = opt.min_weight;
    memcpy(h->ambient, scene->ambient, sizeof h->ambient);
    memcpy(h->background, scene->background, sizeof h->background);
    rt_camera cam;
    rt_camera_get(scene, &cam);
    camera_of(&cam, h);
    return RT_OK;
}

/* ---- rewriting a layout in place ------------------------------------------------ */

void rt_flatten_camera(const rt_scene *scene, rt_flat *flat) {
    rt_camera cam;
    rt_camera_get(scene, &cam);
    camera_of(&cam, &flat->hdr);
}

void rt_flat_shape_free(rt_flat_shape *shape) {
    free(shape->shown);
    free(shape->node_base);
    free(shape->tri_base);
    free(shape->node_count);
    free(shape->tri_count);
    memset(shape, 0, sizeof *shape);
}

rt_status rt_flat_shape_of(const rt_scene *scene, const rt_bvh *mesh_bvhs, const rt_bvh *top,
                           rt_flat_shape *shape) {
    memset(shape, 0, sizeof *shape);
    uint32_t nmesh = scene->mesh_count, nobj = scene->object_count;
    shape->shown = malloc(sizeof(uint32_t) * (nobj ? nobj : 1));
    shape->node_base = malloc(sizeof(uint32_t) * (nmesh ? nmesh : 1));
    shape->tri_base = malloc(sizeof(uint32_t) * (nmesh ? nmesh : 1));
    shape->node_count = malloc(sizeof(uint32_t) * (nmesh ? nmesh : 1));
    shape->tri_count = malloc(sizeof(uint32_t) * (nmesh ? nmesh : 1));
    if (!shape->shown || !shape->node_base || !shape->tri_base || !shape->node_count ||
        !shape->tri_count) {
        rt_flat_shape_free(shape);
        return RT_ERROR_OUT_OF_MEMORY;
    }
    shape->object_count = nobj;
    shape->mesh_count = nmesh;
    for (uint32_t m = 0; m < nmesh; m++) shape->node_base[m] = UINT32_MAX;
    /* The same walk as rt_flatten: meshes in id order, the object BVH last. */
    uint8_t *used = calloc(nmesh ? nmesh : 1, 1);
    if (!used) {
        rt_flat_shape_free(shape);
        return RT_ERROR_OUT_OF_MEMORY;
    }
    for (uint32_t o = 0; o < nobj; o++)
        used[shape->shown[o] = rt_object_shown_mesh(&scene->objects[o])] = 1;
    uint32_t nodes = 0, tris = 0;
    for (uint32_t m = 0; m < nmesh; m++) {
        const rt_mesh_data *md = &scene->meshes[m];
        shape->node_count[m] = md->triangle_count ? mesh_bvhs[m].node_count : 1;
        shape->tri_count[m] = md->triangle_count;
        if (!used[m]) continue;
        shape->node_base[m] = nodes;
        shape->tri_base[m] = tris;
        nodes += shape->node_count[m];
        tris += md->triangle_count;
    }
    free(used);
    shape->single = nobj == 1 && rt_transform_is_identity(scene->objects[0].transform);
    shape->top_root = nodes;
    shape->top_nodes = top ? top->node_count : 0;
    shape->top_prims = top ? top->prim_count : 0;
    shape->material_count = scene->material_count;
    shape->light_count = scene->light_count;
    return RT_OK;
}

static uint64_t mesh_bytes(const rt_flat *f, uint32_t nodes, uint32_t tris) {
    uint64_t per_tri = sizeof(rt_tri) + sizeof(uint32_t) +
                       (f->tri_normals ? 9 * sizeof(float) : 0) +
                       (f->tri_mats ? sizeof(uint32_t) : 0);
    return (uint64_t)nodes * sizeof(rt_node) + (uint64_t)tris * per_tri;
}

uint64_t rt_flat_bytes(const rt_flat *f) {
    return mesh_bytes(f, f->node_count, f->tri_count) + sizeof f->hdr +
           (uint64_t)f->hdr.instance_count * sizeof(rt_instance) +
           (uint64_t)f->inst_id_count * sizeof(uint32_t) +
           (uint64_t)f->hdr.material_count * sizeof(rt_material_d) +
           (uint64_t)f->hdr.light_count * sizeof(rt_light_d) +
           (uint64_t)f->kd_node_count * sizeof(rt_kd_node);
}

rt_status rt_flatten_update(const rt_scene *scene, const rt_bvh *mesh_bvhs, const rt_bvh *top,
                            const uint8_t *dirty, rt_flat_shape *shape, rt_flat *flat,
                            uint64_t *bytes) {
    uint32_t nmesh = scene->mesh_count, nobj = scene->object_count;
    *bytes = 0;
    /* kd-tree meshes are static and their nodes live apart: such a layout
     * is always made anew. */
    if (flat->kd_node_count) return RT_ERROR_UNSUPPORTED;
    if (nmesh != shape->mesh_count || nobj != shape->object_count ||
        scene->material_count != shape->material_count || scene->light_count != shape->light_count)
        return RT_ERROR_UNSUPPORTED;
    for (uint32_t o = 0; o < nobj; o++)
        if (rt_object_shown_mesh(&scene->objects[o]) != shape->shown[o])
            return RT_ERROR_UNSUPPORTED;
    int single = nobj == 1 && rt_transform_is_identity(scene->objects[0].transform);
    if (single != shape->single || (top ? top->node_count : 0) != shape->top_nodes ||
        (top ? top->prim_count : 0) != shape->top_prims)
        return RT_ERROR_UNSUPPORTED;
    rt_scene_features feat = rt_scene_features_of(scene);
    if ((feat.normals != 0) != (flat->tri_normals != NULL) ||
        (feat.tri_materials != 0) != (flat->tri_mats != NULL))
        return RT_ERROR_UNSUPPORTED;
    for (uint32_t m = 0; m < nmesh; m++) {
        if (shape->node_base[m] == UINT32_MAX || !dirty[m]) continue;
        const rt_mesh_data *md = &scene->meshes[m];
        uint32_t nodes = md->triangle_count ? mesh_bvhs[m].node_count : 1;
        if (nodes != shape->node_count[m] || md->triangle_count != shape->tri_count[m])
            return RT_ERROR_UNSUPPORTED;
        /* A refitted tree keeps the shape validated when it was written. */
        if (md->triangle_count && dirty[m] != RT_DIRTY_MOVED &&
            (mesh_bvhs[m].prim_count != md->triangle_count ||
             !bvh_valid(&mesh_bvhs[m], md->triangle_count, NULL, md->name)))
            return RT_ERROR_UNSUPPORTED;
    }
    if (!single && nobj && top && !bvh_valid(top, nobj, NULL, "object"))
        return RT_ERROR_UNSUPPORTED;
    /* The shape holds: rewrite the changed meshes and the frame's part. */
    for (uint32_t m = 0; m < nmesh; m++) {
        if (shape->node_base[m] == UINT32_MAX || !dirty[m]) continue;
        int moved = dirty[m] == RT_DIRTY_MOVED;
        write_mesh_as(flat, &scene->meshes[m], &mesh_bvhs[m], shape->node_base[m],
                      shape->tri_base[m], moved);
        *bytes += moved ? (uint64_t)shape->node_count[m] * sizeof(rt_node) +
                              (uint64_t)shape->tri_count[m] *
                                  (sizeof(rt_tri) + (flat->tri_normals ? 9 * sizeof(float) : 0))
                        : mesh_bytes(flat, shape->node_count[m], shape->tri_count[m]);
    }
    rt_flat_options opt = rt_flat_options_default();
    opt.tri_method = flat->hdr.tri_method;
    opt.max_depth = flat->hdr.max_depth;
    opt.min_weight = flat->hdr.min_weight;
    rt_error why;
    if (write_frame(scene, top, NULL, single, shape->top_root, shape->node_base, shape->tri_base,
                    shape->tri_count, &opt, flat, &why) != RT_OK)
        return RT_ERROR_UNSUPPORTED;
    *bytes += rt_flat_bytes(flat) - mesh_bytes(flat, shape->top_root, flat->tri_count);
    return RT_OK;
}
