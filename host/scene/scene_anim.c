/* SPDX-License-Identifier: Apache-2.0 */
/* scene_anim.c - dynamic scenes: vertices that move, the update policy a
 * renderer follows for them, and the scene's time (keyframes that switch or
 * blend, keyed object transforms, the camera's path). The scene stays pure
 * data: setting the time only edits meshes, objects and the camera through
 * the same fields the rt.h calls edit, bumping the versions of what changed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

/* Indexed by rt_update_policy; the two building policies are named for
 * their builder (rt_builder_name). */
static const char *const policy_names[] = {"sah", "refit", "lbvh", "auto"};

const char *rt_update_policy_name(rt_update_policy policy) {
    return (unsigned)policy < 4 ? policy_names[policy] : "unknown";
}

int rt_update_policy_parse(const char *name, rt_update_policy *out) {
    if (!name) return 0;
    for (int i = 0; i < 4; i++)
        if (strcmp(name, policy_names[i]) == 0) {
            *out = (rt_update_policy)i;
            return 1;
        }
    /* The names before 0.2. */
    if (strcmp(name, "rebuild") == 0)
        *out = RT_UPDATE_SAH;
    else if (strcmp(name, "fast") == 0)
        *out = RT_UPDATE_LBVH;
    else
        return 0;
    return 1;
}

static int finite3(const float v[3]) {
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

/* *out: a copy of count keys of size bytes each, NULL for none; the
 * scene's error when out of memory. */
static rt_status copy_keys(rt_scene *scene, const void *keys, uint32_t count, size_t size,
                           void **out) {
    *out = NULL;
    if (!count) return RT_OK;
    *out = malloc(size * count);
    if (!*out) return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    memcpy(*out, keys, size * count);
    return RT_OK;
}

/* ---- deforming meshes ------------------------------------------------------ */

rt_status rt_mesh_set_positions(rt_scene *scene, uint32_t mesh_id, const float *positions,
                                const float *normals, uint32_t vertex_count) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (mesh_id >= scene->mesh_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "mesh %u does not exist", mesh_id);
    rt_mesh_data *m = &scene->meshes[mesh_id];
    if (vertex_count != m->vertex_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "mesh %u has %u vertices; %u positions given (the topology stays)",
                             mesh_id, m->vertex_count, vertex_count);
    if (vertex_count && !positions)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "null positions");
    if (normals && !m->normals)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "mesh %u has no normals; none can be set", mesh_id);
    rt_status finite = rt_scene_check_finite(scene, mesh_id, positions, normals, vertex_count);
    if (finite != RT_OK) return finite;
    if (vertex_count) {
        memmove(m->positions, positions, 3 * sizeof(float) * (size_t)vertex_count);
        if (normals) memmove(m->normals, normals, 3 * sizeof(float) * (size_t)vertex_count);
    }
    /* A deforming mesh gets a BVH: kd-trees are for static meshes. */
    m->accel = RT_ACCEL_BVH;
    m->version++;
    scene->version++;
    return RT_OK;
}

rt_status rt_mesh_set_update(rt_scene *scene, uint32_t mesh_id, rt_update_policy policy) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (mesh_id >= scene->mesh_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "mesh %u does not exist", mesh_id);
    if ((unsigned)policy > RT_UPDATE_AUTO)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "unknown update policy %d",
                             (int)policy);
    rt_mesh_data *m = &scene->meshes[mesh_id];
    /* Where the policy changes the mesh's structure (a kd mesh given a
     * deforming policy becomes a BVH, and back), its version tells renderers
     * to rebuild it. */
    const rt_accel before = rt_mesh_data_structure(m);
    m->update_policy = (uint32_t)policy;
    if (rt_mesh_data_structure(m) != before) {
        m->version++;
        scene->version++;
    }
    return RT_OK;
}

/* ---- animation data ------------------------------------------------------------ */

rt_status rt_object_set_animation(rt_scene *scene, uint32_t object_id, float keyframe_rate,
                                  int interpolate) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (object_id >= scene->object_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "object %u does not exist",
                             object_id);
    if (!(keyframe_rate > 0.0f) || !isfinite(keyframe_rate))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "object %u: the keyframe rate must be finite and > 0, found %g",
                             object_id, (double)keyframe_rate);
    rt_object_data *o = &scene->objects[object_id];
    o->keyframe_rate = keyframe_rate;
    o->interpolate = interpolate != 0;
    return RT_OK;
}

rt_status rt_object_set_transform_keys(rt_scene *scene, uint32_t object_id,
                                       const rt_transform_key *keys, uint32_t count) {
    if (!scene || (count && !keys)) return RT_ERROR_INVALID_ARGUMENT;
    if (object_id >= scene->object_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "object %u does not exist",
                             object_id);
    for (uint32_t i = 0; i < count; i++) {
        const rt_transform_key *k = &keys[i];
        if (!isfinite(k->time) || (i && !(k->time > keys[i - 1].time)))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "transform key %u: times must be finite and increasing", i);
        if (!finite3(k->translate) || !finite3(k->axis) || !isfinite(k->degrees))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "transform key %u: values must be finite", i);
        if (k->axis[0] == 0.0f && k->axis[1] == 0.0f && k->axis[2] == 0.0f)
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "transform key %u: the rotation axis must not be zero", i);
        if (!(k->scale > 0.0f) || !isfinite(k->scale))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "transform key %u: the scale must be finite and > 0", i);
    }
    void *copy;
    rt_status st = copy_keys(scene, keys, count, sizeof *keys, &copy);
    if (st != RT_OK) return st;
    rt_object_data *o = &scene->objects[object_id];
    free(o->transform_keys);
    o->transform_keys = copy;
    o->transform_key_count = count;
    return RT_OK;
}

rt_status rt_camera_set_path(rt_scene *scene, const rt_camera_key *keys, uint32_t count) {
    if (!scene || (count && !keys)) return RT_ERROR_INVALID_ARGUMENT;
    for (uint32_t i = 0; i < count; i++) {
        const rt_camera_key *k = &keys[i];
        if (!isfinite(k->time) || (i && !(k->time > keys[i - 1].time)))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "camera key %u: times must be finite and increasing", i);
        if (!finite3(k->position) || !finite3(k->look_at))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "camera key %u: position and look_at must be finite", i);
        if (memcmp(k->position, k->look_at, sizeof k->position) == 0)
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "camera key %u: look_at equals the position", i);
    }
    void *copy;
    rt_status st = copy_keys(scene, keys, count, sizeof *keys, &copy);
    if (st != RT_OK) return st;
    free(scene->camera_path);
    scene->camera_path = copy;
    scene->camera_path_count = count;
    return RT_OK;
}

int rt_scene_is_animated(const rt_scene *scene) {
    if (!scene) return 0;
    if (scene->camera_path_count || (scene->animator.set_time && scene->animator.animated))
        return 1;
    for (uint32_t i = 0; i < scene->object_count; i++) {
        const rt_object_data *o = &scene->objects[i];
        if ((o->keyframe_rate > 0.0f && o->mesh_count > 1) || o->transform_key_count) return 1;
    }
    return 0;
}

/* ---- the time ----------------------------------------------------------------- */

/* Where t falls among count increasing key times: segment *i and weight *u in
 * [0, 1]; held at the ends. */
static void key_segment(double t, const double *times, size_t stride, uint32_t count, uint32_t *i,
                        double *u) {
#define KEY_TIME(k) (*(const double *)((const char *)times + (size_t)(k)*stride))
    *i = 0;
    *u = 0.0;
    if (count < 2 || t <= KEY_TIME(0)) return;
    if (t >= KEY_TIME(count - 1)) {
        *i = count - 1;
        return;
    }
    uint32_t lo = 0, hi = count - 1; /* KEY_TIME(lo) <= t < KEY_TIME(hi) */
    while (hi - lo > 1) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (KEY_TIME(mid) <= t)
            lo = mid;
        else
            hi = mid;
    }
    *i = lo;
    *u = (t - KEY_TIME(lo)) / (KEY_TIME(hi) - KEY_TIME(lo));
#undef KEY_TIME
}

static void axis_quat(const float axis[3], float degrees, double q[4]) {
    double x = axis[0], y = axis[1], z = axis[2], len = sqrt(x * x + y * y + z * z);
    double h = (double)degrees * (3.14159265358979323846 / 360.0), s = sin(h) / len;
    q[0] = cos(h);
    q[1] = x * s;
    q[2] = y * s;
    q[3] = z * s;
}

/* Spherical interpolation along the shortest arc (q and -q are the same
 * rotation: the one nearer a is taken). */
static void slerp(const double a[4], const double b_in[4], double u, double out[4]) {
    double b[4] = {b_in[0], b_in[1], b_in[2], b_in[3]};
    double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (d < 0.0) {
        for (int k = 0; k < 4; k++) b[k] = -b[k];
        d = -d;
    }
    double wa, wb;
    if (d > 0.9999995) { /* nearly equal: linear, then normalised */
        wa = 1.0 - u;
        wb = u;
    } else {
        double th = acos(d), s = sin(th);
        wa = sin((1.0 - u) * th) / s;
        wb = sin(u * th) / s;
    }
    double n = 0.0;
    for (int k = 0; k < 4; k++) {
        out[k] = wa * a[k] + wb * b[k];
        n += out[k] * out[k];
    }
    n = sqrt(n);
    for (int k = 0; k < 4; k++) out[k] /= n;
}

static void keyed_transform(const rt_object_data *o, double t, float m[16]) {
    const rt_transform_key *k = o->transform_keys;
    uint32_t i;
    double u;
    key_segment(t, &k[0].time, sizeof k[0], o->transform_key_count, &i, &u);
    const rt_transform_key *a = &k[i], *b = &k[i + 1 < o->transform_key_count ? i + 1 : i];
    double qa[4], qb[4], q[4], tr[3];
    axis_quat(a->axis, a->degrees, qa);
    axis_quat(b->axis, b->degrees, qb);
    slerp(qa, qb, u, q);
    double s = (1.0 - u) * a->scale + u * b->scale;
    for (int c = 0; c < 3; c++) tr[c] = (1.0 - u) * a->translate[c] + u * b->translate[c];
    double w = q[0], x = q[1], y = q[2], z = q[3];
    double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                   2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                   2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
    rt_mat4_identity(m);
    for (int row = 0; row < 3; row++) {
        for (int c = 0; c < 3; c++) m[row * 4 + c] = (float)(r[row * 3 + c] * s);
        m[row * 4 + 3] = (float)tr[row];
    }
}

/* Same vertex count, triangles, normals presence and per-triangle materials:
 * two keyframes that can be blended. */
static int same_topology(const rt_mesh_data *a, const rt_mesh_data *b) {
    if (a->vertex_count != b->vertex_count || a->triangle_count != b->triangle_count ||
        (a->normals == NULL) != (b->normals == NULL) ||
        (a->tri_materials == NULL) != (b->tri_materials == NULL))
        return 0;
    size_t tris = a->triangle_count;
    if (tris && memcmp(a->indices, b->indices, 3 * sizeof(uint32_t) * tris) != 0) return 0;
    if (a->tri_materials && tris &&
        memcmp(a->tri_materials, b->tri_materials, sizeof(uint32_t) * tris) != 0)
        return 0;
    return 1;
}

static void *dup(const void *p, size_t bytes) {
    if (!p) return NULL;
    void *q = malloc(bytes ? bytes : 1);
    if (q && bytes) memcpy(q, p, bytes);
    return q;
}

/* Makes the object's blend mesh a copy of src's topology (creating it the
 * first time). The scene's mesh array may move. */
static rt_status morph_reset(rt_scene *scene, uint32_t object, uint32_t src) {
    rt_object_data *o = &scene->objects[object];
    if (o->morph_mesh == UINT32_MAX) {
        uint32_t id;
        rt_status st = rt_mesh_create(scene, &id);
        if (st != RT_OK) return st;
        scene->objects[object].morph_mesh = id;
        scene->meshes[id].blend = 1;
        o = &scene->objects[object];
    }
    const rt_mesh_data *s = &scene->meshes[src];
    rt_mesh_data *m = &scene->meshes[o->morph_mesh];
    size_t v3 = 3 * sizeof(float) * (size_t)s->vertex_count;
    float *pos = dup(s->positions, v3), *nrm = dup(s->normals, v3);
    uint32_t *idx = dup(s->indices, 3 * sizeof(uint32_t) * (size_t)s->triangle_count);
    uint32_t *mats = dup(s->tri_materials, sizeof(uint32_t) * (size_t)s->triangle_count);
    if ((s->positions && !pos) || (s->normals && !nrm) || (s->indices && !idx) ||
        (s->tri_materials && !mats)) {
        free(pos);
        free(nrm);
        free(idx);
        free(mats);
        return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory blending keyframes");
    }
    rt_mesh_data_free_arrays(m);
    m->positions = pos;
    m->normals = nrm;
    m->indices = idx;
    m->tri_materials = mats;
    m->vertex_count = m->vertex_capacity = s->vertex_count;
    m->triangle_count = m->triangle_capacity = s->triangle_count;
    /* Through a copy: GCC at -O1 cannot tell the blend mesh from its source
     * and warns that the two names may overlap (-Wrestrict). */
    char from[sizeof s->name];
    memcpy(from, s->name, sizeof from);
    from[sizeof from - 1] = 0;
    snprintf(m->name, sizeof m->name, "%.100s (blend)", from);
    m->version++;
    m->topology_version++;
    scene->version++;
    return RT_OK;
}

/* Blends keyframes i and j of the object by weight w into its blend mesh. */
static rt_status morph(rt_scene *scene, uint32_t object, uint32_t i, uint32_t j, float w) {
    rt_object_data *o = &scene->objects[object];
    uint32_t a_id = o->meshes[i], b_id = o->meshes[j];
    if (o->morph_mesh == UINT32_MAX ||
        !same_topology(&scene->meshes[o->morph_mesh], &scene->meshes[a_id])) {
        rt_status st = morph_reset(scene, object, a_id);
        if (st != RT_OK) return st;
        o = &scene->objects[object];
    }
    const rt_mesh_data *a = &scene->meshes[a_id], *b = &scene->meshes[b_id];
    rt_mesh_data *m = &scene->meshes[o->morph_mesh];
    m->update_policy = scene->meshes[o->meshes[0]].update_policy;
    size_t n = 3 * (size_t)a->vertex_count;
    int changed = !o->morphing;
    float v = 1.0f - w;
    for (size_t k = 0; k < n; k++) {
        float p = v * a->positions[k] + w * b->positions[k];
        if (p != m->positions[k]) changed = 1;
        m->positions[k] = p;
    }
    if (a->normals)
        for (size_t k = 0; k < n; k++) {
            float p = v * a->normals[k] + w * b->normals[k];
            if (p != m->normals[k]) changed = 1;
            m->normals[k] = p;
        }
    if (changed) {
        m->version++;
        scene->version++;
    }
    if (!o->morphing || o->selected != i) scene->version++;
    o->morphing = 1;
    o->selected = i;
    return RT_OK;
}

static rt_status animate_keyframes(rt_scene *scene, uint32_t object, double t) {
    rt_object_data *o = &scene->objects[object];
    uint32_t n = o->mesh_count;
    double pos = t * (double)o->keyframe_rate, fl = floor(pos);
    double r = fmod(fl, (double)n);
    if (r < 0.0) r += n;
    uint32_t i = (uint32_t)r;
    if (i >= n) i = n - 1;
    uint32_t j = (i + 1) % n;
    float w = (float)(pos - fl);
    if (o->interpolate && n > 1 &&
        same_topology(&scene->meshes[o->meshes[i]], &scene->meshes[o->meshes[j]]))
        return morph(scene, object, i, j, w);
    if (o->morphing || o->selected != i) scene->version++;
    o->morphing = 0;
    o->selected = i;
    return RT_OK;
}

rt_status rt_scene_set_time(rt_scene *scene, double seconds) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (!isfinite(seconds))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "the time must be finite");
    scene->time = seconds;
    for (uint32_t i = 0; i < scene->object_count; i++) {
        rt_object_data *o = &scene->objects[i];
        if (o->keyframe_rate > 0.0f && o->mesh_count) {
            rt_status st = animate_keyframes(scene, i, seconds);
            if (st != RT_OK) return st;
            o = &scene->objects[i];
        }
        if (o->transform_key_count) {
            float m[16];
            keyed_transform(o, seconds, m);
            if (memcmp(m, o->transform, sizeof m) != 0) {
                memcpy(o->transform, m, sizeof m);
                scene->version++;
            }
        }
    }
    if (scene->camera_path_count) {
        const rt_camera_key *k = scene->camera_path;
        uint32_t i;
        double u;
        key_segment(seconds, &k[0].time, sizeof k[0], scene->camera_path_count, &i, &u);
        const rt_camera_key *a = &k[i], *b = &k[i + 1 < scene->camera_path_count ? i + 1 : i];
        rt_camera c = scene->camera;
        for (int d = 0; d < 3; d++) {
            c.position[d] = (float)((1.0 - u) * a->position[d] + u * b->position[d]);
            c.look_at[d] = (float)((1.0 - u) * a->look_at[d] + u * b->look_at[d]);
        }
        if (memcmp(&c, &scene->camera, sizeof c) != 0) {
            rt_status st = rt_camera_set(scene, &c);
            if (st != RT_OK) return st;
        }
    }
    if (scene->animator.set_time)
        return scene->animator.set_time(scene, scene->animator.state, seconds);
    return RT_OK;
}

/* ---- a loader's clips (rt_scene_animator) ------------------------------------ */

uint32_t rt_scene_clip_count(const rt_scene *scene) {
    if (!scene || !scene->animator.clip_count) return 0;
    return scene->animator.clip_count(scene->animator.state);
}

rt_status rt_scene_clip_info(const rt_scene *scene, uint32_t index, const char **name,
                             double *duration) {
    if (!scene || index >= rt_scene_clip_count(scene)) return RT_ERROR_INVALID_ARGUMENT;
    const char *n = "";
    double d = 0.0;
    scene->animator.clip_info(scene->animator.state, index, &n, &d);
    if (name) *name = n;
    if (duration) *duration = d;
    return RT_OK;
}

uint32_t rt_scene_selected_clip(const rt_scene *scene) {
    return scene && rt_scene_clip_count(scene) ? scene->animator.selected : 0;
}

rt_status rt_scene_select_clip(rt_scene *scene, const char *clip) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (!clip) return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "no clip named");
    uint32_t n = rt_scene_clip_count(scene);
    if (!n)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "the scene has no animation clips (--animation is for glTF files)");
    for (uint32_t i = 0; i < n; i++) {
        const char *name = "";
        rt_scene_clip_info(scene, i, &name, NULL);
        if (strcmp(name, clip) == 0)
            return scene->animator.select_clip(scene, scene->animator.state, i);
    }
    char *end;
    unsigned long k = strtoul(clip, &end, 10);
    if (clip[0] >= '0' && clip[0] <= '9' && !*end && k < n)
        return scene->animator.select_clip(scene, scene->animator.state, (uint32_t)k);
    char names[400] = "";
    size_t used = 0;
    for (uint32_t i = 0; i < n && used + 2 < sizeof names; i++) {
        const char *name = "";
        rt_scene_clip_info(scene, i, &name, NULL);
        int w = snprintf(names + used, sizeof names - used, "%s%s", i ? ", " : "", name);
        if (w < 0) break;
        used += (size_t)w;
    }
    if (used >= sizeof names) used = sizeof names - 1;
    return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                         "no animation clip '%.100s': the scene has %u (0..%u: %s)", clip, n, n - 1,
                         names);
}
