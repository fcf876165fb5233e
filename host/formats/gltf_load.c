/* SPDX-License-Identifier: Apache-2.0 */
/* gltf_load.c - glTF 2.0 scenes into a scene, and their animation at every
 * rt_scene_set_time (gltf_load.h says what is mapped onto what). */
#include "formats/gltf_load.h"

#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/error.h"
#include "base/thread_pool.h"
#include "formats/gltf_module.h"
#include "scene/scene.h"
#include "scene/scene_default_view.h"

int rt_gltf_is_gltf_path(const char *path) {
    size_t n = path ? strlen(path) : 0;
    return (n >= 5 && strcasecmp(path + n - 5, ".gltf") == 0) ||
           (n >= 4 && strcasecmp(path + n - 4, ".glb") == 0);
}

/* ---- the loaded document and its instances ---------------------------------- */

typedef struct gltf_inst {
    uint32_t node, mesh, prim; /* what it shows */
    uint32_t scene_mesh;       /* the scene's mesh holding its vertices */
    uint32_t object;           /* the scene's object showing it */
    int skinned;               /* the node's skin applies */
    /* Not skinned: the mesh holds the node's local vertices (morphed) and
     * the object's transform is the node's world matrix, so that a moving
     * rigid part costs no BVH update. While that matrix is singular (a node
     * scaled to 0) the mesh holds world vertices under the identity. */
    int rigid;
    int local_current; /* the mesh holds the local vertices now */
} gltf_inst;

/* One worker's scratch for evaluating instances: the skin's joint matrices
 * and the vertices of the instance at hand. */
typedef struct gltf_scratch {
    double *joints;  /* 12 per joint (3x4 row-major) */
    float *joints_f; /* the same in float, for the skinning loop */
    uint32_t joint_capacity;
    float *pos, *nrm; /* 3 per vertex of the largest primitive */
} gltf_scratch;

/* What one instance's evaluation in a frame came to (apply_frame). */
typedef struct gltf_job {
    uint32_t inst;
    uint32_t vertices; /* of its primitive: the job's size */
    int local;         /* the instance's vertices in its node's space */
    int outcome;       /* JOB_* */
} gltf_job;

enum { JOB_SAME, JOB_CHANGED, JOB_OUT_OF_MEMORY, JOB_NOT_FINITE };

typedef struct gltf_state {
    const rt_gltf_module *module;
    rt_gltf_doc *doc;
    char path[512];
    gltf_inst *insts;
    uint32_t inst_count;
    uint32_t *order; /* the nodes of the scene, parents first */
    uint32_t order_count;
    int32_t *parent; /* per node, RT_GLTF_NONE for roots */
    double *trs;     /* per node: translation 3, rotation 4, scale 3 (this frame) */
    unsigned char *trs_animated;
    double *world;           /* per node, 16, row-major */
    float *weights;          /* per node, weight_offset[node] .. + weight_len[node] */
    uint32_t *weight_offset; /* per node */
    uint32_t *weight_len;    /* per node: the morph targets of its mesh */
    uint32_t max_vertices;   /* of the largest primitive */
    gltf_scratch *scratch;   /* per worker of the scene's pool (one without) */
    int scratch_count;
    gltf_job *jobs; /* per instance: this frame's evaluations */
    int32_t camera_node;
    uint32_t camera_index;
    uint32_t light_count;
    int32_t *light_nodes; /* per scene light from the file */
    uint32_t *light_ids;
    double *durations; /* per clip */
    uint32_t clip;
    int bake_all; /* every instance in world space (rt_gltf_add_mesh) */
} gltf_state;

static void state_free(void *p) {
    gltf_state *s = p;
    if (!s) return;
    if (s->doc) s->module->free_doc(s->doc);
    free(s->insts);
    free(s->order);
    free(s->parent);
    free(s->trs);
    free(s->trs_animated);
    free(s->world);
    free(s->weights);
    free(s->weight_offset);
    free(s->weight_len);
    for (int w = 0; w < s->scratch_count; w++) {
        free(s->scratch[w].joints);
        free(s->scratch[w].joints_f);
        free(s->scratch[w].pos);
        free(s->scratch[w].nrm);
    }
    free(s->scratch);
    free(s->jobs);
    free(s->light_nodes);
    free(s->light_ids);
    free(s->durations);
    free(s);
}

/* ---- validation --------------------------------------------------------------- */

#define FAIL(...) rt_error_set(err, RT_ERROR_PARSE, path, 0, 0, __VA_ARGS__)

static int in_range(int32_t i, uint32_t n) {
    return i >= 0 && (uint32_t)i < n;
}

static uint32_t mesh_targets(const rt_gltf_mesh *m) {
    uint32_t n = m->weight_count;
    for (uint32_t p = 0; p < m->prim_count; p++)
        if (m->prims[p].target_count > n) n = m->prims[p].target_count;
    return n;
}

static rt_status validate_nodes(const rt_gltf_doc *d, const char *path, int32_t *parent,
                                rt_error *err) {
    for (uint32_t i = 0; i < d->node_count; i++) parent[i] = RT_GLTF_NONE;
    for (uint32_t i = 0; i < d->node_count; i++) {
        const rt_gltf_node *n = &d->nodes[i];
        if (n->mesh != RT_GLTF_NONE && !in_range(n->mesh, d->mesh_count))
            return FAIL("/nodes/%u/mesh: mesh %d does not exist", i, n->mesh);
        if (n->skin != RT_GLTF_NONE && !in_range(n->skin, d->skin_count))
            return FAIL("/nodes/%u/skin: skin %d does not exist", i, n->skin);
        if (n->camera != RT_GLTF_NONE && !in_range(n->camera, d->camera_count))
            return FAIL("/nodes/%u/camera: camera %d does not exist", i, n->camera);
        if (n->light != RT_GLTF_NONE && !in_range(n->light, d->light_count))
            return FAIL("/nodes/%u/extensions/KHR_lights_punctual/light: light %d does not exist",
                        i, n->light);
        for (int k = 0; k < 16; k++)
            if (!isfinite(n->matrix[k])) return FAIL("/nodes/%u/matrix: not finite", i);
        for (int k = 0; k < 3; k++)
            if (!isfinite(n->translation[k]) || !isfinite(n->scale[k]))
                return FAIL("/nodes/%u: translation or scale not finite", i);
        for (int k = 0; k < 4; k++)
            if (!isfinite(n->rotation[k])) return FAIL("/nodes/%u/rotation: not finite", i);
        for (uint32_t c = 0; c < n->child_count; c++) {
            int32_t ch = n->children[c];
            if (!in_range(ch, d->node_count))
                return FAIL("/nodes/%u/children/%u: node %d does not exist", i, c, ch);
            if ((uint32_t)ch == i)
                return FAIL("/nodes/%u/children/%u: the node is its own child", i, c);
            if (parent[ch] != RT_GLTF_NONE)
                return FAIL("/nodes/%u/children/%u: node %d already has parent %d (a node has "
                            "one parent at most)",
                            i, c, ch, parent[ch]);
            parent[ch] = (int32_t)i;
        }
    }
    /* With one parent each, a cycle is a walk up that comes back to itself.
     * Each walk stops at a node an earlier walk cleared, so that a long
     * chain costs linear time: mark[] holds the walk's start + 1 while
     * walking, UINT32_MAX once cleared. */
    uint32_t *mark = calloc(d->node_count ? d->node_count : 1, sizeof(uint32_t));
    if (!mark) return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0, "out of memory");
    for (uint32_t i = 0; i < d->node_count; i++) {
        int32_t p = (int32_t)i;
        while (p != RT_GLTF_NONE && mark[p] != UINT32_MAX) {
            if (mark[p] == i + 1) {
                free(mark);
                return FAIL("/nodes/%d: the node hierarchy has a cycle through this node", p);
            }
            mark[p] = i + 1;
            p = parent[p];
        }
        for (p = (int32_t)i; p != RT_GLTF_NONE && mark[p] != UINT32_MAX; p = parent[p])
            mark[p] = UINT32_MAX;
    }
    free(mark);
    for (uint32_t r = 0; r < d->root_count; r++) {
        if (!in_range(d->roots[r], d->node_count))
            return FAIL("/scenes: node %d does not exist", d->roots[r]);
        if (parent[d->roots[r]] != RT_GLTF_NONE)
            return FAIL("/scenes: node %d is a root of the scene and a child of node %d",
                        d->roots[r], parent[d->roots[r]]);
    }
    for (uint32_t i = 0; i < d->skin_count; i++)
        for (uint32_t j = 0; j < d->skins[i].joint_count; j++)
            if (!in_range(d->skins[i].joints[j], d->node_count))
                return FAIL("/skins/%u/joints/%u: node %d does not exist", i, j,
                            d->skins[i].joints[j]);
    for (uint32_t i = 0; i < d->mesh_count; i++) {
        const rt_gltf_mesh *m = &d->meshes[i];
        for (uint32_t p = 0; p < m->prim_count; p++) {
            const rt_gltf_prim *pr = &m->prims[p];
            if (pr->material != RT_GLTF_NONE && !in_range(pr->material, d->material_count))
                return FAIL("/meshes/%u/primitives/%u/material: material %d does not exist", i, p,
                            pr->material);
            for (uint64_t k = 0; k < 3 * (uint64_t)pr->triangle_count; k++)
                if (pr->indices[k] >= pr->vertex_count)
                    return FAIL("/meshes/%u/primitives/%u/indices: index %u is out of range (the "
                                "primitive has %u vertices)",
                                i, p, pr->indices[k], pr->vertex_count);
        }
    }
    return RT_OK;
}

static rt_status validate_animations(const rt_gltf_doc *d, const char *path, rt_error *err) {
    for (uint32_t a = 0; a < d->animation_count; a++) {
        const rt_gltf_animation *an = &d->animations[a];
        for (uint32_t s = 0; s < an->sampler_count; s++) {
            const rt_gltf_sampler *sa = &an->samplers[s];
            if (!sa->key_count) return FAIL("%s/input: no keyframes", sa->where);
            for (uint32_t k = 0; k < sa->key_count; k++) {
                if (!isfinite(sa->times[k]))
                    return FAIL("%s/input: key time %u is not a finite number", sa->where, k);
                if (k && !(sa->times[k] > sa->times[k - 1]))
                    return FAIL("%s/input: key times are not strictly increasing (key %u: %g "
                                "after %g)",
                                sa->where, k, (double)sa->times[k], (double)sa->times[k - 1]);
            }
            uint64_t vals = (uint64_t)sa->value_count * sa->components;
            for (uint64_t k = 0; k < vals; k++)
                if (!isfinite(sa->values[k]))
                    return FAIL("%s/output: value %llu is not a finite number", sa->where,
                                (unsigned long long)k);
        }
        for (uint32_t c = 0; c < an->channel_count; c++) {
            const rt_gltf_channel *ch = &an->channels[c];
            if (!in_range(ch->sampler, an->sampler_count))
                return FAIL("/animations/%u/channels/%u/sampler: sampler %d does not exist", a, c,
                            ch->sampler);
            if (ch->node != RT_GLTF_NONE && !in_range(ch->node, d->node_count))
                return FAIL("/animations/%u/channels/%u/target/node: node %d does not exist", a, c,
                            ch->node);
            if (ch->node == RT_GLTF_NONE || ch->path < 0) continue;
            const rt_gltf_sampler *sa = &an->samplers[ch->sampler];
            uint64_t per_key = sa->interpolation == RT_GLTF_CUBICSPLINE ? 3 : 1;
            uint64_t elems = (uint64_t)sa->value_count, want;
            uint32_t comps = ch->path == RT_GLTF_PATH_ROTATION  ? 4
                             : ch->path == RT_GLTF_PATH_WEIGHTS ? 1
                                                                : 3;
            if (sa->components != comps)
                return FAIL("%s/output: %u components per value, the %s path needs %u", sa->where,
                            sa->components,
                            ch->path == RT_GLTF_PATH_ROTATION  ? "rotation"
                            : ch->path == RT_GLTF_PATH_WEIGHTS ? "weights"
                                                               : "translation or scale",
                            comps);
            if (ch->path == RT_GLTF_PATH_WEIGHTS) {
                const rt_gltf_node *n = &d->nodes[ch->node];
                uint32_t w = n->mesh >= 0 ? mesh_targets(&d->meshes[n->mesh]) : 0;
                want = (uint64_t)sa->key_count * per_key * w;
            } else {
                want = (uint64_t)sa->key_count * per_key;
            }
            if (elems != want)
                return FAIL("%s/output: %llu values for %u keys, expected %llu (channel %u)",
                            sa->where, (unsigned long long)elems, sa->key_count,
                            (unsigned long long)want, c);
        }
    }
    return RT_OK;
}

/* ---- maths (double) ---------------------------------------------------------- */

static void mat_mul(const double a[16], const double b[16], double out[16]) {
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += a[r * 4 + k] * b[k * 4 + c];
            out[r * 4 + c] = s;
        }
}

static void quat_normalize(double q[4]) {
    double l = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(l > 0.0) || !isfinite(l)) {
        q[0] = q[1] = q[2] = 0.0, q[3] = 1.0;
        return;
    }
    for (int k = 0; k < 4; k++) q[k] /= l;
}

/* Row-major T * R * S. */
static void trs_matrix(const double *t, const double *rq, const double *s, double m[16]) {
    double q[4] = {rq[0], rq[1], rq[2], rq[3]};
    quat_normalize(q);
    double x = q[0], y = q[1], z = q[2], w = q[3];
    double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
                   2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                   2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) m[i * 4 + j] = r[i * 3 + j] * s[j];
        m[i * 4 + 3] = t[i];
    }
    m[12] = m[13] = m[14] = 0.0, m[15] = 1.0;
}

static void slerp(const double *a, const double *b0, double u, double *out) {
    double b[4] = {b0[0], b0[1], b0[2], b0[3]};
    double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (d < 0.0) {
        d = -d;
        for (int k = 0; k < 4; k++) b[k] = -b[k];
    }
    double wa, wb;
    if (d > 0.9999995) { /* nearly the same: the normalized lerp is exact enough */
        wa = 1.0 - u, wb = u;
    } else {
        double th = acos(d > 1.0 ? 1.0 : d), sn = sin(th);
        wa = sin((1.0 - u) * th) / sn, wb = sin(u * th) / sn;
    }
    for (int k = 0; k < 4; k++) out[k] = wa * a[k] + wb * b[k];
    quat_normalize(out);
}

/* The sampler at time t, n floats per element, into out (n doubles). */
static void sample(const rt_gltf_sampler *s, uint32_t n, int rotation, double t, double *out) {
    uint32_t K = s->key_count;
    int cubic = s->interpolation == RT_GLTF_CUBICSPLINE;
    size_t stride = (size_t)n * (cubic ? 3 : 1), at = cubic ? (size_t)n : 0;
    const float *v = s->values;
    uint32_t i;
    if (K == 1 || t <= s->times[0]) {
        i = 0;
    } else if (t >= s->times[K - 1]) {
        i = K - 1;
    } else {
        uint32_t lo = 0, hi = K - 1; /* times[lo] <= t < times[hi] */
        while (hi - lo > 1) {
            uint32_t mid = lo + (hi - lo) / 2;
            if ((double)s->times[mid] <= t)
                lo = mid;
            else
                hi = mid;
        }
        double t0 = s->times[lo], t1 = s->times[hi], dt = t1 - t0, u = (t - t0) / dt;
        const float *a = v + lo * stride + at, *b = v + hi * stride + at;
        if (s->interpolation == RT_GLTF_STEP) {
            for (uint32_t k = 0; k < n; k++) out[k] = a[k];
        } else if (!cubic) {
            if (rotation) {
                double qa[4] = {a[0], a[1], a[2], a[3]}, qb[4] = {b[0], b[1], b[2], b[3]};
                slerp(qa, qb, u, out);
            } else {
                for (uint32_t k = 0; k < n; k++) out[k] = (1.0 - u) * a[k] + u * b[k];
            }
        } else {
            const float *out_tan = v + lo * stride + 2 * (size_t)n; /* b_lo */
            const float *in_tan = v + hi * stride;                  /* a_hi */
            double u2 = u * u, u3 = u2 * u;
            double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2,
                   h11 = u3 - u2;
            for (uint32_t k = 0; k < n; k++)
                out[k] = h00 * a[k] + h10 * dt * out_tan[k] + h01 * b[k] + h11 * dt * in_tan[k];
            if (rotation) quat_normalize(out);
        }
        return;
    }
    for (uint32_t k = 0; k < n; k++) out[k] = v[i * stride + at + k];
    if (rotation) quat_normalize(out);
}

/* ---- evaluation at a time --------------------------------------------------- */

static void pose_nodes(gltf_state *s, double t) {
    const rt_gltf_doc *d = s->doc;
    for (uint32_t i = 0; i < d->node_count; i++) {
        const rt_gltf_node *n = &d->nodes[i];
        double *p = s->trs + 10 * (size_t)i;
        memcpy(p, n->translation, 3 * sizeof(double));
        memcpy(p + 3, n->rotation, 4 * sizeof(double));
        memcpy(p + 7, n->scale, 3 * sizeof(double));
        s->trs_animated[i] = 0;
        uint32_t wl = s->weight_len[i];
        float *w = s->weights + s->weight_offset[i];
        const rt_gltf_mesh *m = n->mesh >= 0 ? &d->meshes[n->mesh] : NULL;
        for (uint32_t k = 0; k < wl; k++)
            w[k] = k < n->weight_count                              ? n->weights[k]
                   : (!n->weight_count && m && k < m->weight_count) ? m->weights[k]
                                                                    : 0.0f;
    }
    if (s->clip < d->animation_count) {
        const rt_gltf_animation *an = &d->animations[s->clip];
        double tmp[4];
        for (uint32_t c = 0; c < an->channel_count; c++) {
            const rt_gltf_channel *ch = &an->channels[c];
            if (ch->node == RT_GLTF_NONE || ch->path < 0) continue;
            const rt_gltf_sampler *sa = &an->samplers[ch->sampler];
            double *p = s->trs + 10 * (size_t)ch->node;
            switch (ch->path) {
            case RT_GLTF_PATH_TRANSLATION:
                sample(sa, 3, 0, t, p);
                s->trs_animated[ch->node] = 1;
                break;
            case RT_GLTF_PATH_ROTATION:
                sample(sa, 4, 1, t, tmp);
                memcpy(p + 3, tmp, 4 * sizeof(double));
                s->trs_animated[ch->node] = 1;
                break;
            case RT_GLTF_PATH_SCALE:
                sample(sa, 3, 0, t, p + 7);
                s->trs_animated[ch->node] = 1;
                break;
            case RT_GLTF_PATH_WEIGHTS: {
                uint32_t wl = s->weight_len[ch->node];
                if (!wl) break;
                double *buf = malloc(wl * sizeof(double));
                if (!buf) break; /* out of memory: the weights stay the rest pose's */
                sample(sa, wl, 0, t, buf);
                float *w = s->weights + s->weight_offset[ch->node];
                for (uint32_t k = 0; k < wl; k++) w[k] = (float)buf[k];
                free(buf);
                break;
            }
            }
        }
    }
    for (uint32_t o = 0; o < s->order_count; o++) {
        uint32_t i = s->order[o];
        const rt_gltf_node *n = &d->nodes[i];
        double local[16];
        if (n->has_matrix && !s->trs_animated[i]) {
            for (int r = 0; r < 4; r++)
                for (int c = 0; c < 4; c++) local[r * 4 + c] = n->matrix[c * 4 + r];
        } else {
            const double *p = s->trs + 10 * (size_t)i;
            trs_matrix(p, p + 3, p + 7, local);
        }
        double *w = s->world + 16 * (size_t)i;
        if (s->parent[i] == RT_GLTF_NONE)
            memcpy(w, local, sizeof local);
        else
            mat_mul(s->world + 16 * (size_t)s->parent[i], local, w);
    }
}

static void xform_point(const double *m, const double *p, double *out) {
    for (int r = 0; r < 3; r++)
        out[r] = m[r * 4] * p[0] + m[r * 4 + 1] * p[1] + m[r * 4 + 2] * p[2] + m[r * 4 + 3];
}

static void normal_matrix(const double *m, double n[9]) {
    /* cofactors of the 3x3 part: det * inverse transpose */
    double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9],
           i = m[10];
    n[0] = e * i - f * h, n[1] = f * g - d * i, n[2] = d * h - e * g;
    n[3] = c * h - b * i, n[4] = a * i - c * g, n[5] = b * g - a * h;
    n[6] = b * f - c * e, n[7] = c * d - a * f, n[8] = a * e - b * d;
    double det = a * n[0] + b * n[1] + c * n[2];
    if (det < 0.0)
        for (int k = 0; k < 9; k++) n[k] = -n[k];
}

static void put_normal(const double *nm, const double *v, float *out) {
    double x = nm[0] * v[0] + nm[1] * v[1] + nm[2] * v[2];
    double y = nm[3] * v[0] + nm[4] * v[1] + nm[5] * v[2];
    double z = nm[6] * v[0] + nm[7] * v[1] + nm[8] * v[2];
    double l = sqrt(x * x + y * y + z * z);
    if (l > 0.0 && isfinite(l))
        x /= l, y /= l, z /= l;
    else
        x = 0.0, y = 0.0, z = 1.0;
    out[0] = (float)x, out[1] = (float)y, out[2] = (float)z;
}

/* Linear-blend skinning in float of an unmorphed primitive: per vertex the
 * weighted sum of its joints' matrices (jf: 12 floats each), applied to
 * the position and (its linear part) to the normal, normalized. */
static void skin_fast(const rt_gltf_prim *pr, const float *jf, float *pos, float *nrm) {
    uint32_t nv = pr->vertex_count, per = 4 * pr->joint_sets;
    for (uint32_t v = 0; v < nv; v++) {
        float m[12] = {0};
        const float *wv = pr->weights + (size_t)v * per;
        const uint32_t *jv = pr->joints + (size_t)v * per;
        for (uint32_t k = 0; k < per; k++) {
            float wt = wv[k];
            if (wt == 0.0f) continue; /* an unused slot's joint may be anything */
            const float *jm = jf + 12 * (size_t)jv[k];
            for (int e = 0; e < 12; e++) m[e] += wt * jm[e];
        }
        const float *p = pr->positions + 3 * (size_t)v;
        float *o = pos + 3 * (size_t)v;
        for (int r = 0; r < 3; r++)
            o[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
        if (nrm) {
            const float *n = pr->normals + 3 * (size_t)v;
            float x = m[0] * n[0] + m[1] * n[1] + m[2] * n[2];
            float y = m[4] * n[0] + m[5] * n[1] + m[6] * n[2];
            float z = m[8] * n[0] + m[9] * n[1] + m[10] * n[2];
            float l = sqrtf(x * x + y * y + z * z);
            float *on = nrm + 3 * (size_t)v;
            if (l > 0.0f && isfinite(l))
                on[0] = x / l, on[1] = y / l, on[2] = z / l;
            else
                on[0] = 0.0f, on[1] = 0.0f, on[2] = 1.0f;
        }
    }
}

/* The instance's vertices at the posed nodes into ws->pos (and ws->nrm when
 * it has normals): skinned, or placed by its node's world matrix, or (local
 * 1, a rigid instance) in the node's space. Returns 0 when out of memory. */
static int eval_inst(const gltf_state *s, gltf_scratch *ws, const gltf_inst *in, int local) {
    const rt_gltf_doc *d = s->doc;
    const rt_gltf_node *node = &d->nodes[in->node];
    const rt_gltf_prim *pr = &d->meshes[in->mesh].prims[in->prim];
    uint32_t nv = pr->vertex_count, nt = pr->target_count;
    const float *w = s->weights + s->weight_offset[in->node];
    uint32_t wl = s->weight_len[in->node];
    const rt_gltf_skin *skin = in->skinned ? &d->skins[node->skin] : NULL;
    if (skin) {
        if (skin->joint_count > ws->joint_capacity) {
            double *j = realloc(ws->joints, 12 * sizeof(double) * skin->joint_count);
            if (!j) return 0;
            ws->joints = j;
            float *jf = realloc(ws->joints_f, 12 * sizeof(float) * skin->joint_count);
            if (!jf) return 0;
            ws->joints_f = jf;
            ws->joint_capacity = skin->joint_count;
        }
        for (uint32_t j = 0; j < skin->joint_count; j++) {
            double ib[16], jm[16];
            const double *c = skin->inverse_bind + 16 * (size_t)j;
            for (int r = 0; r < 4; r++)
                for (int k = 0; k < 4; k++) ib[r * 4 + k] = c[k * 4 + r];
            mat_mul(s->world + 16 * (size_t)skin->joints[j], ib, jm);
            memcpy(ws->joints + 12 * (size_t)j, jm, 12 * sizeof(double));
            for (int e = 0; e < 12; e++) ws->joints_f[12 * (size_t)j + e] = (float)jm[e];
        }
        int morphed = 0;
        for (uint32_t t = 0; t < nt && t < wl; t++) morphed |= w[t] != 0.0f;
        if (!morphed) {
            skin_fast(pr, ws->joints_f, ws->pos, pr->normals ? ws->nrm : NULL);
            return 1;
        }
    }
    static const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const double *place = local ? identity : s->world + 16 * (size_t)in->node;
    double nm[9];
    if (!skin) normal_matrix(place, nm);
    for (uint32_t v = 0; v < nv; v++) {
        double p[3], n[3] = {0, 0, 1};
        for (int k = 0; k < 3; k++) p[k] = pr->positions[3 * (size_t)v + k];
        if (pr->normals)
            for (int k = 0; k < 3; k++) n[k] = pr->normals[3 * (size_t)v + k];
        for (uint32_t t = 0; t < nt && t < wl; t++) {
            if (w[t] == 0.0f) continue;
            const float *dp = pr->target_positions + ((size_t)t * nv + v) * 3;
            for (int k = 0; k < 3; k++) p[k] += (double)w[t] * dp[k];
            if (pr->target_normals) {
                const float *dn = pr->target_normals + ((size_t)t * nv + v) * 3;
                for (int k = 0; k < 3; k++) n[k] += (double)w[t] * dn[k];
            }
        }
        double out[3];
        if (skin) {
            double m[12] = {0};
            uint32_t sets = pr->joint_sets;
            for (uint32_t k = 0; k < 4 * sets; k++) {
                double wt = pr->weights[(size_t)v * 4 * sets + k];
                if (wt == 0.0) continue;
                const double *jm = ws->joints + 12 * (size_t)pr->joints[(size_t)v * 4 * sets + k];
                for (int e = 0; e < 12; e++) m[e] += wt * jm[e];
            }
            xform_point(m, p, out);
            if (pr->normals) {
                /* the blended matrix's linear part, as real-time skinning
                 * does (not its inverse transpose: joints rarely shear) */
                double sn[9] = {m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]};
                put_normal(sn, n, ws->nrm + 3 * (size_t)v);
            }
        } else {
            xform_point(place, p, out);
            if (pr->normals) put_normal(nm, n, ws->nrm + 3 * (size_t)v);
        }
        for (int k = 0; k < 3; k++) ws->pos[3 * (size_t)v + k] = (float)out[k];
    }
    return 1;
}

static int camera_of(const gltf_state *s, rt_camera *cam) {
    const rt_gltf_camera *c = &s->doc->cameras[s->camera_index];
    const double *m = s->world + 16 * (size_t)s->camera_node;
    double o[3] = {0, 0, 0}, f[3] = {0, 0, -1}, pos[3], ahead[3];
    xform_point(m, o, pos);
    xform_point(m, f, ahead);
    for (int k = 0; k < 3; k++) {
        cam->position[k] = (float)pos[k];
        cam->look_at[k] = (float)ahead[k];
        cam->up[k] = (float)m[k * 4 + 1];
    }
    double aspect = c->aspect > 0.0 ? c->aspect : (double)cam->width / cam->height;
    double h = 2.0 * atan(tan(c->yfov * 0.5) * aspect) * 180.0 / 3.14159265358979323846;
    if (!(h > 0.0 && h < 179.0)) return 0;
    cam->hfov_degrees = (float)h;
    return 1;
}

static int d_has_targets(const gltf_state *s, const gltf_inst *in) {
    return s->doc->meshes[in->mesh].prims[in->prim].target_count > 0;
}

/* Scratch for n workers (kept between frames). Returns 0 when out of memory. */
static int reserve_scratch(gltf_state *s, int n) {
    if (n <= s->scratch_count) return 1;
    gltf_scratch *g = realloc(s->scratch, (size_t)n * sizeof *g);
    if (!g) return 0;
    s->scratch = g;
    size_t bytes = 3 * sizeof(float) * (s->max_vertices ? s->max_vertices : 1);
    for (; s->scratch_count < n; s->scratch_count++) {
        gltf_scratch *w = &g[s->scratch_count];
        memset(w, 0, sizeof *w);
        w->pos = malloc(bytes);
        w->nrm = malloc(bytes);
        if (!w->pos || !w->nrm) {
            s->scratch_count++; /* freed with the state */
            return 0;
        }
    }
    return 1;
}

typedef struct frame_work {
    rt_scene *scene;
    gltf_state *state;
    uint32_t count; /* jobs */
    atomic_uint next;
} frame_work;

/* One job: the instance's vertices at this frame into its mesh when they
 * differ. Jobs touch only their own instance's mesh, so workers need no
 * lock; the versions are bumped afterwards, on one thread. */
static void run_job(rt_scene *scene, gltf_state *s, gltf_scratch *ws, gltf_job *job) {
    gltf_inst *in = &s->insts[job->inst];
    if (!eval_inst(s, ws, in, job->local)) {
        job->outcome = JOB_OUT_OF_MEMORY;
        return;
    }
    rt_mesh_data *m = &scene->meshes[in->scene_mesh];
    size_t n = 3 * (size_t)m->vertex_count;
    for (size_t k = 0; k < n; k++)
        if (!isfinite(ws->pos[k])) {
            job->outcome = JOB_NOT_FINITE;
            return;
        }
    in->local_current = job->local;
    int changed = memcmp(m->positions, ws->pos, n * sizeof(float)) != 0;
    if (changed) memcpy(m->positions, ws->pos, n * sizeof(float));
    if (m->normals && memcmp(m->normals, ws->nrm, n * sizeof(float)) != 0) {
        memcpy(m->normals, ws->nrm, n * sizeof(float));
        changed = 1;
    }
    job->outcome = changed ? JOB_CHANGED : JOB_SAME;
}

static void frame_worker(void *ctx, int worker, int worker_count) {
    (void)worker_count;
    frame_work *f = ctx;
    for (;;) {
        uint32_t j = atomic_fetch_add_explicit(&f->next, 1u, memory_order_relaxed);
        if (j >= f->count) return;
        run_job(f->scene, f->state, &f->state->scratch[worker], &f->state->jobs[j]);
    }
}

static int larger_job_first(const void *a, const void *b) {
    const gltf_job *x = a, *y = b;
    return x->vertices != y->vertices ? (x->vertices < y->vertices ? 1 : -1)
                                      : (x->inst > y->inst) - (x->inst < y->inst);
}

/* Writes the frame into the scene's meshes, camera and lights: first, on
 * the caller's thread, the rigid instances' object transforms and which
 * instances need their vertices again; then those instances (posed,
 * skinned, morphed) over the scene's threads, the largest first; then the
 * versions, and the first failure in instance order. */
static rt_status apply_frame(rt_scene *scene, gltf_state *s) {
    uint32_t count = 0;
    for (uint32_t i = 0; i < s->inst_count; i++) {
        gltf_inst *in = &s->insts[i];
        int local = 0;
        /* The caller may have removed objects (rt_object_remove compacts
         * their ids): find the instance's again, or leave it be. */
        if (in->object >= scene->object_count ||
            rt_object_shown_mesh(&scene->objects[in->object]) != in->scene_mesh) {
            uint32_t o = 0;
            while (o < scene->object_count &&
                   rt_object_shown_mesh(&scene->objects[o]) != in->scene_mesh)
                o++;
            if (o == scene->object_count) continue; /* removed */
            in->object = o;
        }
        if (in->rigid) {
            const double *w = s->world + 16 * (size_t)in->node;
            float t[16], inv[16];
            int ok = 1;
            for (int k = 0; k < 16; k++) {
                t[k] = k < 12 ? (float)w[k] : (k == 15 ? 1.0f : 0.0f);
                if (!isfinite(t[k])) ok = 0;
            }
            if (!ok || !rt_mat4_affine_inverse(t, inv))
                rt_mat4_identity(t);
            else
                local = 1;
            rt_object_data *o = &scene->objects[in->object];
            if (memcmp(t, o->transform, sizeof t) != 0) {
                memcpy(o->transform, t, sizeof t);
                scene->version++;
            }
            /* Unmorphed local vertices never change. */
            if (local && in->local_current && !d_has_targets(s, in)) continue;
        }
        uint32_t nv = s->doc->meshes[in->mesh].prims[in->prim].vertex_count;
        s->jobs[count++] = (gltf_job){i, nv, local, JOB_SAME};
    }
    /* The largest instances first, so that no worker starts a big one last. */
    qsort(s->jobs, count, sizeof *s->jobs, larger_job_first);
    rt_pool *pool = count > 1 ? rt_scene_pool(scene) : NULL;
    int workers = pool ? rt_pool_size(pool) : 1;
    if (!reserve_scratch(s, workers))
        return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "%s: out of memory", s->path);
    if (pool) {
        frame_work f = {scene, s, count, 0};
        rt_pool_run(pool, frame_worker, &f);
    } else {
        for (uint32_t j = 0; j < count; j++) run_job(scene, s, &s->scratch[0], &s->jobs[j]);
    }
    const gltf_job *failed = NULL;
    for (uint32_t j = 0; j < count; j++) {
        const gltf_job *job = &s->jobs[j];
        if (job->outcome == JOB_CHANGED) {
            scene->meshes[s->insts[job->inst].scene_mesh].version++;
            scene->version++;
        } else if (job->outcome != JOB_SAME && (!failed || job->inst < failed->inst)) {
            failed = job;
        }
    }
    if (failed && failed->outcome == JOB_OUT_OF_MEMORY)
        return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "%s: out of memory", s->path);
    if (failed)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "%s: node %u: a vertex is not finite at time %g", s->path,
                             s->insts[failed->inst].node, scene->time);
    if (s->camera_node != RT_GLTF_NONE && scene->has_camera) {
        rt_camera cam = scene->camera;
        /* A degenerate pose (a camera node scaled to 0) keeps the last
         * camera: rt_camera_set refuses it and changes nothing. */
        if (camera_of(s, &cam) && memcmp(&cam, &scene->camera, sizeof cam) != 0)
            (void)rt_camera_set(scene, &cam);
    }
    for (uint32_t l = 0; l < s->light_count; l++) {
        if (s->light_ids[l] >= scene->light_count) continue; /* removed by the caller */
        const double *m = s->world + 16 * (size_t)s->light_nodes[l];
        float p[3] = {(float)m[3], (float)m[7], (float)m[11]};
        rt_light_data *ld = &scene->lights[s->light_ids[l]];
        if (memcmp(p, ld->position, sizeof p) != 0) {
            rt_status st = rt_light_set(scene, s->light_ids[l], p, ld->color);
            if (st != RT_OK) return st;
        }
    }
    return RT_OK;
}

static rt_status animator_set_time(rt_scene *scene, void *state, double t) {
    gltf_state *s = state;
    pose_nodes(s, t);
    return apply_frame(scene, s);
}

static uint32_t animator_clip_count(const void *state) {
    return ((const gltf_state *)state)->doc->animation_count;
}

static void animator_clip_info(const void *state, uint32_t i, const char **name, double *duration) {
    const gltf_state *s = state;
    *name = s->doc->animations[i].name;
    *duration = s->durations[i];
}

static rt_status animator_select(rt_scene *scene, void *state, uint32_t i) {
    gltf_state *s = state;
    s->clip = i;
    scene->animator.selected = i;
    return animator_set_time(scene, state, scene->time);
}

/* ---- loading ------------------------------------------------------------------ */

static rt_material material_of(const rt_gltf_material *g) {
    rt_material m = rt_material_default();
    for (int k = 0; k < 3; k++) {
        double c = g->base_color[k];
        m.color[k] = (float)(c < 0.0 ? 0.0 : c > 1.0 ? 1.0 : c);
    }
    double metal = g->metallic < 0.0 ? 0.0 : g->metallic > 1.0 ? 1.0 : g->metallic;
    double rough = g->roughness < 0.0 ? 0.0 : g->roughness > 1.0 ? 1.0 : g->roughness;
    m.ambient = 1.0f;
    m.diffuse = (float)(1.0 - metal);
    m.specular = (float)((1.0 - rough) * (0.04 + 0.96 * metal));
    double r4 = rough * rough * rough * rough;
    double shin = r4 > 0.0 ? 2.0 / r4 - 2.0 : 1024.0;
    m.shininess = shin < 1.0 ? 1 : shin > 1024.0 ? 1024 : (int)lround(shin);
    m.reflectivity = (float)(metal * (1.0 - rough) * (1.0 - rough));
    for (int k = 0; k < 3; k++) {
        double e = g->emissive[k]; /* glTF: linear, in 0..1 */
        m.emission[k] = (float)(e < 0.0 ? 0.0 : e > 1.0 ? 1.0 : e);
    }
    return m;
}

static rt_status oom(const char *path, rt_error *err) {
    return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0, "out of memory");
}

static rt_status build(rt_scene *scene, gltf_state *s, rt_error *err) {
    const char *path = s->path;
    rt_gltf_doc *d = s->doc;
    uint32_t nn = d->node_count;
    s->parent = malloc((nn ? nn : 1) * sizeof(int32_t));
    s->order = malloc((nn ? nn : 1) * sizeof(uint32_t));
    s->trs = malloc((nn ? nn : 1) * 10 * sizeof(double));
    s->trs_animated = calloc(nn ? nn : 1, 1);
    s->world = calloc((nn ? nn : 1) * 16, sizeof(double));
    s->weight_offset = calloc(nn ? nn : 1, sizeof(uint32_t));
    s->weight_len = calloc(nn ? nn : 1, sizeof(uint32_t));
    s->durations = calloc(d->animation_count ? d->animation_count : 1, sizeof(double));
    if (!s->parent || !s->order || !s->trs || !s->trs_animated || !s->world || !s->weight_offset ||
        !s->weight_len || !s->durations)
        return oom(path, err);
    rt_status st = validate_nodes(d, path, s->parent, err);
    if (st == RT_OK) st = validate_animations(d, path, err);
    if (st != RT_OK) return st;
    /* Every node in parents-first order (the scene's roots' trees first, in
     * the file's order, then the rest so that joints and targets outside the
     * scene have a world transform too). */
    uint32_t *stack = malloc((nn ? nn : 1) * sizeof(uint32_t));
    unsigned char *seen = calloc(nn ? nn : 1, 1);
    if (!stack || !seen) {
        free(stack);
        free(seen);
        return oom(path, err);
    }
    uint32_t scene_nodes = 0;
    for (uint32_t pass = 0; pass < 2; pass++) {
        uint32_t starts = pass ? nn : d->root_count;
        for (uint32_t r = 0; r < starts; r++) {
            uint32_t root = pass ? r : (uint32_t)d->roots[r];
            if (seen[root] || (pass && s->parent[root] != RT_GLTF_NONE)) continue;
            uint32_t top = 0;
            stack[top++] = root;
            seen[root] = 1;
            while (top) {
                uint32_t i = stack[--top];
                s->order[s->order_count++] = i;
                const rt_gltf_node *n = &d->nodes[i];
                for (uint32_t c = n->child_count; c-- > 0;) {
                    uint32_t ch = (uint32_t)n->children[c];
                    if (!seen[ch]) {
                        seen[ch] = 1;
                        stack[top++] = ch;
                    }
                }
            }
        }
        if (!pass) scene_nodes = s->order_count;
    }
    free(stack);
    free(seen);
    /* Morph weights per node with a mesh. */
    uint64_t total_w = 0;
    for (uint32_t i = 0; i < nn; i++) {
        const rt_gltf_node *n = &d->nodes[i];
        s->weight_offset[i] = (uint32_t)total_w;
        s->weight_len[i] = n->mesh >= 0 ? mesh_targets(&d->meshes[n->mesh]) : 0;
        total_w += s->weight_len[i];
    }
    s->weights = calloc(total_w ? total_w : 1, sizeof(float));
    if (!s->weights) return oom(path, err);
    /* Instances: the scene's nodes with meshes, in hierarchy order. */
    uint32_t ninst = 0, max_v = 0;
    uint64_t total_v = 0;
    for (uint32_t o = 0; o < scene_nodes; o++) {
        const rt_gltf_node *n = &d->nodes[s->order[o]];
        if (n->mesh >= 0) ninst += d->meshes[n->mesh].prim_count;
    }
    s->insts = calloc(ninst ? ninst : 1, sizeof(gltf_inst));
    if (!s->insts) return oom(path, err);
    for (uint32_t o = 0; o < scene_nodes; o++) {
        uint32_t i = s->order[o];
        const rt_gltf_node *n = &d->nodes[i];
        if (n->mesh < 0) continue;
        const rt_gltf_mesh *m = &d->meshes[n->mesh];
        for (uint32_t p = 0; p < m->prim_count; p++) {
            const rt_gltf_prim *pr = &m->prims[p];
            if (!pr->triangle_count) continue;
            gltf_inst *in = &s->insts[s->inst_count++];
            in->node = i, in->mesh = (uint32_t)n->mesh, in->prim = p;
            in->skinned = n->skin >= 0 && pr->joint_sets > 0;
            in->rigid = !in->skinned && !s->bake_all;
            if (in->skinned) {
                uint32_t jc = d->skins[n->skin].joint_count;
                for (uint64_t k = 0; k < 4ull * pr->joint_sets * pr->vertex_count; k++)
                    if (pr->joints[k] >= jc)
                        return FAIL("/meshes/%d/primitives/%u/attributes/JOINTS_%u: joint %u is "
                                    "out of range (skin %d has %u joints)",
                                    n->mesh, p, (unsigned)((k % (4ull * pr->joint_sets)) / 4),
                                    pr->joints[k], n->skin, jc);
            }
            if (pr->vertex_count > max_v) max_v = pr->vertex_count;
            total_v += pr->vertex_count;
            if (total_v > ((uint64_t)1 << 26))
                return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                                    "/nodes/%u: the scene's instances hold more than 2^26 "
                                    "vertices in all (a limit of this loader)",
                                    i);
        }
    }
    s->max_vertices = max_v;
    s->jobs = malloc((s->inst_count ? s->inst_count : 1) * sizeof(gltf_job));
    if (!s->jobs || !reserve_scratch(s, 1)) return oom(path, err);
    /* Clip durations. */
    for (uint32_t a = 0; a < d->animation_count; a++) {
        const rt_gltf_animation *an = &d->animations[a];
        for (uint32_t c = 0; c < an->channel_count; c++) {
            const rt_gltf_sampler *sa = &an->samplers[an->channels[c].sampler];
            double last = sa->times[sa->key_count - 1];
            if (last > s->durations[a]) s->durations[a] = last;
        }
    }
    /* The camera and the lights: the first camera met; every point light. */
    s->camera_node = RT_GLTF_NONE;
    s->light_nodes = malloc((nn ? nn : 1) * sizeof(int32_t));
    s->light_ids = malloc((nn ? nn : 1) * sizeof(uint32_t));
    if (!s->light_nodes || !s->light_ids) return oom(path, err);
    memset(s->light_ids, 0xff, (nn ? nn : 1) * sizeof(uint32_t));
    int other_lights = 0;
    for (uint32_t o = 0; o < scene_nodes; o++) {
        uint32_t i = s->order[o];
        const rt_gltf_node *n = &d->nodes[i];
        if (n->camera >= 0 && s->camera_node == RT_GLTF_NONE && d->cameras[n->camera].perspective) {
            s->camera_node = (int32_t)i;
            s->camera_index = (uint32_t)n->camera;
        }
        if (n->light >= 0) {
            if (d->lights[n->light].type == RT_GLTF_LIGHT_POINT)
                s->light_nodes[s->light_count++] = (int32_t)i;
            else
                other_lights = 1;
        }
    }
    /* The frame at time 0 of clip 0, then the scene. */
    s->clip = 0;
    pose_nodes(s, 0.0);
    uint32_t *mat_ids = malloc((d->material_count + 1) * sizeof(uint32_t));
    if (!mat_ids) return oom(path, err);
    for (uint32_t k = 0; k <= d->material_count; k++) mat_ids[k] = UINT32_MAX;
    int textured = 0;
    for (uint32_t k = 0; k < s->inst_count && st == RT_OK; k++) {
        gltf_inst *in = &s->insts[k];
        const rt_gltf_prim *pr = &d->meshes[in->mesh].prims[in->prim];
        uint32_t slot = pr->material >= 0 ? (uint32_t)pr->material : d->material_count;
        if (mat_ids[slot] == UINT32_MAX) {
            rt_material m =
                slot < d->material_count ? material_of(&d->materials[slot]) : rt_material_default();
            if (slot < d->material_count && d->materials[slot].textured) textured = 1;
            st = rt_material_add(scene, &m, &mat_ids[slot]);
            if (st != RT_OK) break;
        }
        if (!eval_inst(s, &s->scratch[0], in, 0)) {
            st = oom(path, err);
            break;
        }
        uint32_t mesh, obj;
        st = rt_mesh_create(scene, &mesh);
        if (st == RT_OK)
            st = rt_mesh_add_triangles(scene, mesh, s->scratch[0].pos,
                                       pr->normals ? s->scratch[0].nrm : NULL, pr->vertex_count,
                                       pr->indices, pr->triangle_count);
        if (st == RT_OK) st = rt_object_create(scene, mat_ids[slot], &obj);
        if (st == RT_OK) st = rt_object_add_mesh(scene, obj, mesh);
        if (st != RT_OK) {
            free(mat_ids);
            return rt_error_set(err, st, path, 0, 0, "/nodes/%u (mesh %u, primitive %u): %s",
                                in->node, in->mesh, in->prim, scene->error.message);
        }
        in->scene_mesh = mesh;
        in->object = obj;
        const char *mn = d->meshes[in->mesh].name;
        snprintf(scene->meshes[mesh].name, sizeof scene->meshes[mesh].name, "%.60s:%.40s/%u",
                 strrchr(path, '/') ? strrchr(path, '/') + 1 : path, mn[0] ? mn : "mesh", in->prim);
    }
    free(mat_ids);
    if (st != RT_OK) return st;
    /* Rigid instances into their nodes' space under object transforms. */
    st = apply_frame(scene, s);
    if (st != RT_OK) return rt_error_set(err, st, path, 0, 0, "%s", scene->error.message);
    for (uint32_t l = 0; l < s->light_count; l++) {
        const rt_gltf_light *gl = &d->lights[d->nodes[s->light_nodes[l]].light];
        const double *m = s->world + 16 * (size_t)s->light_nodes[l];
        float p[3] = {(float)m[3], (float)m[7], (float)m[11]}, c[3];
        for (int k = 0; k < 3; k++) {
            double v = gl->color[k];
            c[k] = (float)(v < 0.0 || !isfinite(v) ? 0.0 : v > 1e6 ? 1e6 : v);
        }
        st = rt_light_add(scene, p, c, &s->light_ids[l]);
        if (st != RT_OK)
            return rt_error_set(err, st, path, 0, 0, "/nodes/%d: %s", s->light_nodes[l],
                                scene->error.message);
    }
    rt_camera cam;
    memset(&cam, 0, sizeof cam);
    cam.width = 1024;
    cam.height = 576;
    if (s->camera_node != RT_GLTF_NONE) {
        double a = d->cameras[s->camera_index].aspect;
        if (a > 0.0 && isfinite(a)) {
            double h = 1024.0 / a;
            cam.height = h < 1.0 ? 1 : h > 32768.0 ? 32768 : (int)lround(h);
        }
        if (!camera_of(s, &cam) || rt_camera_set(scene, &cam) != RT_OK) {
            rt_scene_add_notice(scene, "glTF camera unusable (field of view or orientation): "
                                       "using the default view");
            s->camera_node = RT_GLTF_NONE;
        }
    }
    if (s->camera_node == RT_GLTF_NONE) {
        int keep = scene->no_default_light;
        if (s->light_count) scene->no_default_light = 1;
        st = rt_scene_apply_default_view(scene, 0, 0);
        scene->no_default_light = keep;
        if (st != RT_OK) return rt_error_set(err, st, path, 0, 0, "%s", scene->error.message);
    } else if (!s->light_count && !scene->no_default_light) {
        /* the default lights and ambient, keeping the file's camera */
        rt_camera keep = scene->camera;
        scene->no_default_light = 1;
        st = rt_scene_apply_default_view(scene, keep.width, keep.height);
        scene->no_default_light = 0;
        if (st == RT_OK) st = rt_camera_set(scene, &keep);
        if (st == RT_OK) st = rt_scene_add_default_lights(scene);
        if (st != RT_OK) return rt_error_set(err, st, path, 0, 0, "%s", scene->error.message);
    }
    char note[700];
    if (textured || d->texture_count) {
        snprintf(note, sizeof note,
                 "%s: textures are ignored (%u in the file): materials use their factors only",
                 path, d->texture_count);
        rt_scene_add_notice(scene, note);
    }
    uint32_t skipped = 0;
    for (uint32_t k = 0; k < d->mesh_count; k++) skipped += d->meshes[k].skipped_prims;
    if (skipped) {
        snprintf(note, sizeof note, "%s: %u point or line primitives left out", path, skipped);
        rt_scene_add_notice(scene, note);
    }
    if (other_lights) {
        snprintf(note, sizeof note, "%s: spot and directional lights are left out", path);
        rt_scene_add_notice(scene, note);
    }
    return RT_OK;
}

static rt_status load_gltf(rt_scene *scene, const char *path, int bake_all, rt_error *err) {
    const rt_gltf_module *module = rt_gltf_module_get(err);
    if (!module) {
        char why[sizeof err->message];
        snprintf(why, sizeof why, "%s", err ? err->message : "no glTF module");
        return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0, "cannot read glTF: %s", why);
    }
    gltf_state *s = calloc(1, sizeof *s);
    if (!s) return oom(path, err);
    s->module = module;
    s->bake_all = bake_all;
    snprintf(s->path, sizeof s->path, "%s", path);
    rt_status st = module->read(path, &s->doc, err);
    if (st == RT_OK) st = build(scene, s, err);
    if (st != RT_OK) {
        state_free(s);
        return st;
    }
    int animated = 0;
    for (uint32_t a = 0; a < s->doc->animation_count && !animated; a++)
        for (uint32_t c = 0; c < s->doc->animations[a].channel_count; c++)
            if (s->doc->animations[a].channels[c].node >= 0 &&
                s->doc->animations[a].channels[c].path >= 0)
                animated = 1;
    if (!s->doc->animation_count) {
        state_free(s); /* a still scene: nothing to keep */
        return RT_OK;
    }
    scene->animator.state = s;
    scene->animator.set_time = animator_set_time;
    scene->animator.destroy = state_free;
    scene->animator.clip_count = animator_clip_count;
    scene->animator.clip_info = animator_clip_info;
    scene->animator.select_clip = animator_select;
    scene->animator.selected = 0;
    scene->animator.animated = animated;
    return RT_OK;
}

rt_status rt_scene_load_gltf(rt_scene *scene, const char *path, rt_error *err) {
    return load_gltf(scene, path, 0, err);
}

/* ---- one mesh for a JSON scene ---------------------------------------------- */

rt_status rt_gltf_add_mesh(rt_scene *scene, const char *path, uint32_t *mesh_id, rt_error *err) {
    rt_scene *g;
    if (rt_scene_create(&g) != RT_OK) return oom(path, err);
    g->no_default_light = 1;
    rt_status st = load_gltf(g, path, 1, err);
    if (st == RT_OK && rt_scene_triangle_count(g) == 0)
        st = rt_error_set(err, RT_ERROR_PARSE, path, 0, 0, "the file has no triangles");
    if (st != RT_OK) {
        rt_scene_destroy(g);
        return st;
    }
    /* The objects' meshes, one after another, each triangle keeping its
     * object's material (the glTF materials become the scene's). */
    uint32_t *map = malloc((g->material_count ? g->material_count : 1) * sizeof(uint32_t));
    uint64_t tris = 0, verts = 0;
    int normals = 1;
    for (uint32_t o = 0; o < g->object_count; o++) {
        const rt_mesh_data *m = &g->meshes[rt_object_shown_mesh(&g->objects[o])];
        tris += m->triangle_count;
        verts += m->vertex_count;
        if (!m->normals) normals = 0;
    }
    float *pos = malloc(3 * sizeof(float) * (verts ? verts : 1));
    float *nrm = normals ? malloc(3 * sizeof(float) * (verts ? verts : 1)) : NULL;
    uint32_t *idx = malloc(3 * sizeof(uint32_t) * (tris ? tris : 1));
    uint32_t *tm = malloc(sizeof(uint32_t) * (tris ? tris : 1));
    if (!map || !pos || (normals && !nrm) || !idx || !tm || verts > UINT32_MAX / 3 ||
        tris > UINT32_MAX / 3) {
        st = oom(path, err);
        goto done;
    }
    for (uint32_t k = 0; k < g->material_count && st == RT_OK; k++)
        st = rt_material_add(scene, &g->materials[k], &map[k]);
    if (st != RT_OK) {
        st = rt_error_set(err, st, path, 0, 0, "%s", scene->error.message);
        goto done;
    }
    uint64_t v0 = 0, t0 = 0;
    for (uint32_t o = 0; o < g->object_count; o++) {
        const rt_mesh_data *m = &g->meshes[rt_object_shown_mesh(&g->objects[o])];
        memcpy(pos + 3 * v0, m->positions, 3 * sizeof(float) * m->vertex_count);
        if (nrm) memcpy(nrm + 3 * v0, m->normals, 3 * sizeof(float) * m->vertex_count);
        for (uint64_t t = 0; t < m->triangle_count; t++) {
            for (int c = 0; c < 3; c++)
                idx[3 * (t0 + t) + c] = (uint32_t)(v0 + m->indices[3 * t + c]);
            tm[t0 + t] = map[g->objects[o].material];
        }
        v0 += m->vertex_count;
        t0 += m->triangle_count;
    }
    st = rt_mesh_create(scene, mesh_id);
    if (st == RT_OK)
        st = rt_mesh_add_triangles(scene, *mesh_id, pos, nrm, (uint32_t)verts, idx, (uint32_t)tris);
    if (st != RT_OK) {
        st = rt_error_set(err, st, path, 0, 0, "%s", scene->error.message);
        goto done;
    }
    scene->meshes[*mesh_id].tri_materials = tm;
    tm = NULL;
    snprintf(scene->meshes[*mesh_id].name, sizeof scene->meshes[*mesh_id].name, "%.120s",
             strrchr(path, '/') ? strrchr(path, '/') + 1 : path);
done:
    free(map);
    free(pos);
    free(nrm);
    free(idx);
    free(tm);
    rt_scene_destroy(g);
    return st;
}
