/* SPDX-License-Identifier: Apache-2.0 */
/* scene.c - the scene model and the rt.h operations that edit it. */
#include "scene/scene.h"

#include <math.h>
#include <stdatomic.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/thread_pool.h"

/* ---- small helpers ---------------------------------------------------- */

rt_status rt_scene_fail(rt_scene *scene, rt_status status, const char *fmt, ...) {
    va_list args;
    va_start(args, fmt);
    rt_error_setv(&scene->error, status, NULL, 0, 0, fmt, args);
    va_end(args);
    return status;
}

/* Grows *array (of elem bytes each) so that it holds at least need elements. */
static int grow(void **array, uint32_t *capacity, uint32_t need, size_t elem) {
    if (need <= *capacity) return 1;
    uint64_t cap = *capacity ? *capacity : 8;
    while (cap < need) cap *= 2;
    if (cap > UINT32_MAX) cap = UINT32_MAX;
    if (cap * elem > SIZE_MAX / 2) return 0;
    void *p = realloc(*array, (size_t)cap * elem);
    if (!p) return 0;
    *array = p;
    *capacity = (uint32_t)cap;
    return 1;
}

void rt_mat4_identity(float m[16]) {
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

void rt_mat4_mul(const float a[16], const float b[16], float out[16]) {
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++) s += a[r * 4 + k] * b[k * 4 + c];
            out[r * 4 + c] = s;
        }
}

int rt_mat4_affine_inverse(const float m[16], float out[16]) {
    /* Inverse of the 3x3 part by cofactors, in double, then the translation. */
    double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9],
           i = m[10];
    double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
    double det = a * A + b * B + c * C;
    if (det == 0.0 || !isfinite(det)) return 0;
    double inv[9] = {A / det, -(b * i - c * h) / det, (b * f - c * e) / det,
                     B / det, (a * i - c * g) / det,  -(a * f - c * d) / det,
                     C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
    for (int r = 0; r < 3; r++) {
        double t = 0.0;
        for (int k = 0; k < 3; k++) {
            out[r * 4 + k] = (float)inv[r * 3 + k];
            t -= inv[r * 3 + k] * m[k * 4 + 3];
        }
        out[r * 4 + 3] = (float)t;
    }
    out[12] = out[13] = out[14] = 0.0f;
    out[15] = 1.0f;
    return 1;
}

int rt_transform_is_identity(const float m[16]) {
    for (int i = 0; i < 16; i++)
        if (m[i] != ((i % 5) == 0 ? 1.0f : 0.0f)) return 0;
    return 1;
}

/* ---- lifetime --------------------------------------------------------- */

rt_material rt_material_default(void) {
    rt_material m = {{1.0f, 1.0f, 1.0f}, 1.0f, 1.0f, 0.0f, 1, 0.0f, 0.0f, 1.0f, {0.0f, 0.0f, 0.0f}};
    return m;
}

rt_status rt_scene_check_finite(rt_scene *scene, uint32_t mesh_id, const float *positions,
                                const float *normals, uint32_t vertex_count) {
    for (uint32_t v = 0; v < vertex_count; v++) {
        if (!rt_scene_finite3(positions + 3 * (size_t)v))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "mesh %u: vertex %u has a NaN or infinite coordinate", mesh_id, v);
        if (normals && !rt_scene_finite3(normals + 3 * (size_t)v))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "mesh %u: normal %u has a NaN or infinite component", mesh_id, v);
    }
    return RT_OK;
}

rt_status rt_scene_create(rt_scene **out) {
    if (!out) return RT_ERROR_INVALID_ARGUMENT;
    rt_scene *s = calloc(1, sizeof *s);
    *out = s;
    if (!s) return RT_ERROR_OUT_OF_MEMORY;
    s->ambient[0] = s->ambient[1] = s->ambient[2] = 0.1f;
    /* A camera at +z looking at the origin until one is set. */
    rt_camera cam = {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 60.0f, 1024, 576};
    s->camera = cam;
    static _Atomic uint64_t next_uid = 1;
    s->uid = atomic_fetch_add(&next_uid, 1);
    return RT_OK;
}

rt_status rt_scene_set_threads(rt_scene *scene, int threads) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (threads < 0) threads = 0;
    if (threads != scene->threads) {
        rt_pool_destroy(scene->pool);
        scene->pool = NULL;
        scene->threads = threads;
    }
    return RT_OK;
}

rt_pool *rt_scene_pool(rt_scene *scene) {
    int n = scene->threads > 0 ? scene->threads : rt_cpu_count();
    if (n <= 1) return NULL;
    if (!scene->pool) scene->pool = rt_pool_create(n);
    return scene->pool;
}

void rt_mesh_data_free_arrays(rt_mesh_data *m) {
    free(m->positions);
    free(m->normals);
    free(m->indices);
    free(m->tri_materials);
    m->positions = m->normals = NULL;
    m->indices = m->tri_materials = NULL;
}

void rt_scene_destroy(rt_scene *scene) {
    if (!scene) return;
    if (scene->animator.destroy) scene->animator.destroy(scene->animator.state);
    rt_pool_destroy(scene->pool);
    for (uint32_t i = 0; i < scene->mesh_count; i++) rt_mesh_data_free_arrays(&scene->meshes[i]);
    for (uint32_t i = 0; i < scene->object_count; i++) {
        free(scene->objects[i].meshes);
        free(scene->objects[i].transform_keys);
    }
    free(scene->camera_path);
    free(scene->notices);
    free(scene->meshes);
    free(scene->materials);
    free(scene->lights);
    free(scene->objects);
    free(scene);
}

void rt_scene_add_notice(rt_scene *scene, const char *text) {
    if (!scene || !text || !text[0]) return;
    size_t have = scene->notices ? strlen(scene->notices) : 0, add = strlen(text);
    char *grown = realloc(scene->notices, have + add + 2);
    if (!grown) return;
    memcpy(grown + have, text, add);
    grown[have + add] = '\n';
    grown[have + add + 1] = '\0';
    scene->notices = grown;
}

const char *rt_scene_notices(const rt_scene *scene) {
    return scene && scene->notices ? scene->notices : "";
}

const char *rt_scene_error(const rt_scene *scene) {
    return scene ? scene->error.message : "";
}

/* ---- meshes ----------------------------------------------------------- */

rt_status rt_mesh_create(rt_scene *scene, uint32_t *mesh_id) {
    if (!scene || !mesh_id) return RT_ERROR_INVALID_ARGUMENT;
    if (!grow((void **)&scene->meshes, &scene->mesh_capacity, scene->mesh_count + 1,
              sizeof(rt_mesh_data)))
        return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory creating a mesh");
    memset(&scene->meshes[scene->mesh_count], 0, sizeof(rt_mesh_data));
    *mesh_id = scene->mesh_count++;
    scene->version++;
    return RT_OK;
}

rt_status rt_mesh_add_triangles(rt_scene *scene, uint32_t mesh_id, const float *positions,
                                const float *normals, uint32_t vertex_count,
                                const uint32_t *indices, uint32_t triangle_count) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (mesh_id >= scene->mesh_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "mesh %u does not exist", mesh_id);
    if ((vertex_count && !positions) || (triangle_count && !indices))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "null positions or indices");
    rt_mesh_data *m = &scene->meshes[mesh_id];
    /* The limits (docs/ROBUSTNESS.md, "Limits"), checked before anything is
     * read or allocated. */
    if ((uint64_t)m->triangle_count + triangle_count > RT_MAX_MESH_TRIANGLES)
        return rt_scene_fail(scene, RT_ERROR_UNSUPPORTED,
                             "mesh %u: %llu triangles exceed the limit of %llu triangles per mesh",
                             mesh_id, (unsigned long long)m->triangle_count + triangle_count,
                             (unsigned long long)RT_MAX_MESH_TRIANGLES);
    if ((uint64_t)m->vertex_count + vertex_count > RT_MAX_MESH_VERTICES)
        return rt_scene_fail(scene, RT_ERROR_UNSUPPORTED,
                             "mesh %u: %llu vertices exceed the limit of %llu vertices per mesh",
                             mesh_id, (unsigned long long)m->vertex_count + vertex_count,
                             (unsigned long long)RT_MAX_MESH_VERTICES);
    uint64_t total = triangle_count;
    for (uint32_t i = 0; i < scene->mesh_count; i++) total += scene->meshes[i].triangle_count;
    if (total > RT_MAX_SCENE_TRIANGLES)
        return rt_scene_fail(scene, RT_ERROR_UNSUPPORTED,
                             "mesh %u: the scene's meshes would hold %llu triangles, more than "
                             "the limit of %llu",
                             mesh_id, (unsigned long long)total,
                             (unsigned long long)RT_MAX_SCENE_TRIANGLES);
    if (m->vertex_count && ((m->normals != NULL) != (normals != NULL)))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "mesh %u: normals must be given for all vertices or for none",
                             mesh_id);
    rt_status finite = rt_scene_check_finite(scene, mesh_id, positions, normals, vertex_count);
    if (finite != RT_OK) return finite;
    for (uint64_t i = 0; i < 3 * (uint64_t)triangle_count; i++)
        if (indices[i] >= vertex_count)
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "mesh %u: triangle %llu refers to vertex %u of %u", mesh_id,
                                 (unsigned long long)(i / 3), indices[i], vertex_count);
    if ((uint64_t)m->vertex_count + vertex_count > UINT32_MAX / 3 ||
        (uint64_t)m->triangle_count + triangle_count > UINT32_MAX / 3)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "mesh %u: too many triangles",
                             mesh_id);

    if (vertex_count == 0 && triangle_count == 0) return RT_OK; /* nothing to add */
    uint32_t v0 = m->vertex_count, t0 = m->triangle_count;
    uint32_t vcap = m->vertex_capacity, tcap = m->triangle_capacity;
    /* Grow every array first, so that a failure leaves the mesh as it was. */
    if (!grow((void **)&m->positions, &vcap, v0 + vertex_count, 3 * sizeof(float))) goto oom;
    if (normals) {
        uint32_t ncap = m->vertex_capacity;
        if (!grow((void **)&m->normals, &ncap, v0 + vertex_count, 3 * sizeof(float))) goto oom;
        if (ncap != vcap) {
            float *p = realloc(m->normals, (size_t)vcap * 3 * sizeof(float));
            if (!p) goto oom;
            m->normals = p;
        }
    }
    m->vertex_capacity = vcap;
    if (!grow((void **)&m->indices, &tcap, t0 + triangle_count, 3 * sizeof(uint32_t))) goto oom;
    if (m->tri_materials) {
        uint32_t mcap = m->triangle_capacity;
        if (!grow((void **)&m->tri_materials, &mcap, t0 + triangle_count, sizeof(uint32_t)))
            goto oom;
        if (mcap != tcap) {
            uint32_t *p = realloc(m->tri_materials, (size_t)tcap * sizeof(uint32_t));
            if (!p) goto oom;
            m->tri_materials = p;
        }
        for (uint32_t t = 0; t < triangle_count; t++) m->tri_materials[t0 + t] = UINT32_MAX;
    }
    m->triangle_capacity = tcap;

    memcpy(m->positions + 3 * (size_t)v0, positions, 3 * sizeof(float) * (size_t)vertex_count);
    if (normals)
        memcpy(m->normals + 3 * (size_t)v0, normals, 3 * sizeof(float) * (size_t)vertex_count);
    for (uint64_t i = 0; i < 3 * (uint64_t)triangle_count; i++)
        m->indices[3 * (size_t)t0 + i] = indices[i] + v0;
    m->vertex_count += vertex_count;
    m->triangle_count += triangle_count;
    m->version++;
    m->topology_version++;
    scene->version++;
    return RT_OK;
oom:
    return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY,
                         "mesh %u: out of memory adding %u triangles", mesh_id, triangle_count);
}

/* ---- materials and lights ---------------------------------------------- */

/* RT_OK when each of the n values is a colour component (finite, within
 * 0..RT_MAX_COLOUR), else the scene's error naming what and the value. */
static rt_status check_colour(rt_scene *scene, const char *what, const float *v, int n) {
    for (int i = 0; i < n; i++)
        if (!(v[i] >= 0.0f && v[i] <= RT_MAX_COLOUR))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "%s %g is outside 0..%g (the colour limit)", what, (double)v[i],
                                 (double)RT_MAX_COLOUR);
    return RT_OK;
}

rt_status rt_material_add(rt_scene *scene, const rt_material *mat, uint32_t *material_id) {
    if (!scene || !mat || !material_id) return RT_ERROR_INVALID_ARGUMENT;
    const float coeffs[6] = {mat->ambient,      mat->diffuse,      mat->specular,
                             mat->reflectivity, mat->transparency, mat->ior};
    for (int i = 0; i < 6; i++)
        if (!isfinite(coeffs[i]) || coeffs[i] < 0.0f)
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "material: coefficients must be finite and >= 0");
    rt_status st = check_colour(scene, "material: colour component", mat->color, 3);
    if (st == RT_OK)
        st = check_colour(scene, "material: ambient, diffuse or specular factor", coeffs, 3);
    if (st == RT_OK) st = check_colour(scene, "material: emission component", mat->emission, 3);
    if (st != RT_OK) return st;
    if (mat->shininess < 0 || mat->shininess > 100000)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "material: shininess %d is outside 0..100000", mat->shininess);
    if (mat->ior <= 0.0f)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "material: ior must be > 0");
    if (mat->reflectivity + mat->transparency > 1.0f)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "material: reflectivity + transparency must not exceed 1");
    if (!grow((void **)&scene->materials, &scene->material_capacity, scene->material_count + 1,
              sizeof(rt_material)))
        return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory adding a material");
    scene->materials[scene->material_count] = *mat;
    *material_id = scene->material_count++;
    scene->version++;
    return RT_OK;
}

/* RT_OK when position and color make a light (rt_light_add's rules), else
 * the scene's error naming the value. */
static rt_status check_light(rt_scene *scene, const float position[3], const float color[3]) {
    if (!rt_scene_finite3(position))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "light: position (%g, %g, %g) must be finite", (double)position[0],
                             (double)position[1], (double)position[2]);
    return check_colour(scene, "light: colour component", color, 3);
}

rt_status rt_light_add(rt_scene *scene, const float position[3], const float color[3],
                       uint32_t *light_id) {
    if (!scene || !position || !color || !light_id) return RT_ERROR_INVALID_ARGUMENT;
    rt_status st = check_light(scene, position, color);
    if (st != RT_OK) return st;
    if (!grow((void **)&scene->lights, &scene->light_capacity, scene->light_count + 1,
              sizeof(rt_light_data)))
        return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory adding a light");
    rt_light_data *l = &scene->lights[scene->light_count];
    memcpy(l->position, position, sizeof l->position);
    memcpy(l->color, color, sizeof l->color);
    *light_id = scene->light_count++;
    scene->version++;
    return RT_OK;
}

rt_status rt_light_set(rt_scene *scene, uint32_t light_id, const float position[3],
                       const float color[3]) {
    if (!scene || !position || !color) return RT_ERROR_INVALID_ARGUMENT;
    if (light_id >= scene->light_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "light %u does not exist (%u lights)", light_id, scene->light_count);
    rt_status st = check_light(scene, position, color);
    if (st != RT_OK) return st;
    rt_light_data *l = &scene->lights[light_id];
    memcpy(l->position, position, sizeof l->position);
    memcpy(l->color, color, sizeof l->color);
    scene->version++;
    return RT_OK;
}

rt_status rt_light_get(const rt_scene *scene, uint32_t light_id, float position[3],
                       float color[3]) {
    if (!scene || !position || !color || light_id >= scene->light_count)
        return RT_ERROR_INVALID_ARGUMENT;
    memcpy(position, scene->lights[light_id].position, 3 * sizeof(float));
    memcpy(color, scene->lights[light_id].color, 3 * sizeof(float));
    return RT_OK;
}

static rt_status set_color(rt_scene *scene, float dst[3], const float color[3], const char *what) {
    if (!scene || !color) return RT_ERROR_INVALID_ARGUMENT;
    char name[64];
    snprintf(name, sizeof name, "%s component", what);
    rt_status st = check_colour(scene, name, color, 3);
    if (st != RT_OK) return st;
    memcpy(dst, color, 3 * sizeof(float));
    scene->version++;
    return RT_OK;
}

rt_status rt_scene_set_ambient(rt_scene *scene, const float color[3]) {
    return set_color(scene, scene ? scene->ambient : NULL, color, "ambient light");
}

rt_status rt_scene_set_background(rt_scene *scene, const float color[3]) {
    return set_color(scene, scene ? scene->background : NULL, color, "background colour");
}

rt_status rt_scene_set_exposure(rt_scene *scene, float ev) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    rt_error_clear(&scene->error);
    if (!(ev >= -64.0f && ev <= 64.0f))
        return rt_fail(&scene->error, RT_ERROR_INVALID_ARGUMENT,
                       "exposure %g is not a number of stops in -64..64", (double)ev);
    scene->exposure = ev; /* read at rt_render: no version bump, nothing to rebuild */
    return RT_OK;
}

float rt_scene_exposure(const rt_scene *scene) {
    return scene ? scene->exposure : 0.0f;
}

/* ---- objects ------------------------------------------------------------ */

/* Object id, or NULL: no scene, or (the scene's error) no such object. */
static rt_object_data *object_at(rt_scene *scene, uint32_t id) {
    if (!scene) return NULL;
    if (id >= scene->object_count) {
        rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "object %u does not exist", id);
        return NULL;
    }
    return &scene->objects[id];
}

rt_status rt_object_create(rt_scene *scene, uint32_t material_id, uint32_t *object_id) {
    if (!scene || !object_id) return RT_ERROR_INVALID_ARGUMENT;
    if (material_id >= scene->material_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "material %u does not exist",
                             material_id);
    if (!grow((void **)&scene->objects, &scene->object_capacity, scene->object_count + 1,
              sizeof(rt_object_data)))
        return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory creating an object");
    rt_object_data *o = &scene->objects[scene->object_count];
    memset(o, 0, sizeof *o);
    o->material = material_id;
    o->mask = 0xffffffffu;
    o->morph_mesh = UINT32_MAX;
    rt_mat4_identity(o->transform);
    rt_mat4_identity(o->pending);
    *object_id = scene->object_count++;
    scene->version++;
    return RT_OK;
}

rt_status rt_object_add_mesh(rt_scene *scene, uint32_t object_id, uint32_t mesh_id) {
    rt_object_data *o = object_at(scene, object_id);
    if (!o) return RT_ERROR_INVALID_ARGUMENT;
    if (mesh_id >= scene->mesh_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "mesh %u does not exist", mesh_id);
    if (!grow((void **)&o->meshes, &o->mesh_capacity, o->mesh_count + 1, sizeof(uint32_t)))
        return rt_scene_fail(scene, RT_ERROR_OUT_OF_MEMORY, "out of memory adding a keyframe");
    o->meshes[o->mesh_count++] = mesh_id;
    scene->version++;
    return RT_OK;
}

rt_status rt_object_select_mesh(rt_scene *scene, uint32_t object_id, uint32_t keyframe) {
    rt_object_data *o = object_at(scene, object_id);
    if (!o) return RT_ERROR_INVALID_ARGUMENT;
    if (keyframe >= o->mesh_count)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "object %u has %u keyframes; %u does not exist", object_id,
                             o->mesh_count, keyframe);
    o->selected = keyframe;
    scene->version++;
    return RT_OK;
}

rt_status rt_object_transform(rt_scene *scene, uint32_t object_id, const float matrix[16]) {
    if (!scene || !matrix) return RT_ERROR_INVALID_ARGUMENT;
    rt_object_data *o = object_at(scene, object_id);
    if (!o) return RT_ERROR_INVALID_ARGUMENT;
    for (int i = 0; i < 16; i++)
        if (!isfinite(matrix[i]))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "object %u: transform element %d is not finite", object_id, i);
    if (matrix[12] != 0.0f || matrix[13] != 0.0f || matrix[14] != 0.0f || matrix[15] != 1.0f)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "object %u: the last row of a transform must be 0 0 0 1", object_id);
    float inv[16];
    if (!rt_mat4_affine_inverse(matrix, inv))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "object %u: the transform is singular", object_id);
    float composed[16];
    rt_mat4_mul(matrix, o->pending, composed);
    memcpy(o->pending, composed, sizeof composed);
    o->has_pending = 1;
    return RT_OK;
}

rt_status rt_object_set_mask(rt_scene *scene, uint32_t object_id, uint32_t mask) {
    rt_object_data *o = object_at(scene, object_id);
    if (!o) return RT_ERROR_INVALID_ARGUMENT;
    if (o->mask == mask) return RT_OK;
    o->mask = mask;
    scene->version++; /* the layout's instances change: every backend uploads them again */
    return RT_OK;
}

rt_status rt_scene_commit(rt_scene *scene) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    for (uint32_t i = 0; i < scene->object_count; i++) {
        rt_object_data *o = &scene->objects[i];
        if (!o->has_pending) continue;
        float composed[16];
        rt_mat4_mul(o->pending, o->transform, composed);
        memcpy(o->transform, composed, sizeof composed);
        rt_mat4_identity(o->pending);
        o->has_pending = 0;
        scene->version++;
    }
    return RT_OK;
}

/* ---- camera --------------------------------------------------------------- */

static void cross3(const float a[3], const float b[3], float out[3]) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static int normalize3(float v[3]) {
    float len = sqrtf(rt_scene_dot3(v, v));
    if (!(len > 0.0f) || !isfinite(len)) return 0;
    v[0] /= len, v[1] /= len, v[2] /= len;
    return 1;
}

int rt_camera_frame_d(const rt_camera *c, double f[3], double r[3], double u[3]) {
    const double up[3] = {c->up[0], c->up[1], c->up[2]};
    for (int i = 0; i < 3; i++) f[i] = (double)c->look_at[i] - (double)c->position[i];
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int i = 0; i < 3; i++) f[i] /= fl;
    r[0] = f[1] * up[2] - f[2] * up[1];
    r[1] = f[2] * up[0] - f[0] * up[2];
    r[2] = f[0] * up[1] - f[1] * up[0];
    double rl = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    double ul = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
    /* |f x up| = |up| sin(angle): exactly zero for an up (anti)parallel to
     * f in double even where the float check above passed. */
    if (!(fl > 0.0) || !isfinite(fl) || !(rl > RT_CAMERA_MIN_SINE * ul) || !isfinite(rl)) return 0;
    for (int i = 0; i < 3; i++) r[i] /= rl;
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    for (int i = 0; i < 3; i++)
        if (!isfinite(f[i]) || !isfinite(r[i]) || !isfinite(u[i])) return 0;
    return 1;
}

rt_status rt_camera_set(rt_scene *scene, const rt_camera *cam) {
    if (!scene || !cam) return RT_ERROR_INVALID_ARGUMENT;
    if (!rt_scene_finite3(cam->position) || !rt_scene_finite3(cam->look_at) ||
        !rt_scene_finite3(cam->up))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "camera: vectors must be finite");
    float fwd[3] = {cam->look_at[0] - cam->position[0], cam->look_at[1] - cam->position[1],
                    cam->look_at[2] - cam->position[2]};
    /* The float check stands for every camera whose view vector's length
     * fits a float; one whose squared length overflows (a camera 1e38 from
     * its look-at point) is told apart in double, where it cannot
     * overflow: only an exact zero means the two points are equal. */
    if (!normalize3(fwd)) {
        double d[3], len2 = 0.0;
        for (int k = 0; k < 3; k++) {
            d[k] = (double)cam->look_at[k] - (double)cam->position[k];
            len2 += d[k] * d[k];
        }
        if (!(len2 > 0.0))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "camera: the look-at point equals the position (%g, %g, %g)",
                                 (double)cam->position[0], (double)cam->position[1],
                                 (double)cam->position[2]);
        /* Not zero: too long for a float (the double frame below decides)
         * or too short (its square underflows to zero). */
        if (rt_scene_finite3(fwd) && !(rt_scene_dot3(fwd, fwd) > 0.0f))
            return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                                 "camera: the view direction from (%g, %g, %g) to (%g, %g, %g) is "
                                 "too short for a float",
                                 (double)cam->position[0], (double)cam->position[1],
                                 (double)cam->position[2], (double)cam->look_at[0],
                                 (double)cam->look_at[1], (double)cam->look_at[2]);
    }
    double f[3], r[3], u[3];
    if (!rt_camera_frame_d(cam, f, r, u))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "camera: up is zero or (nearly) parallel to the view direction");
    if (!(cam->hfov_degrees > 0.0f && cam->hfov_degrees < 180.0f))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "camera: field of view %g is outside (0, 180) degrees",
                             (double)cam->hfov_degrees);
    if (cam->width < 1 || cam->height < 1 || cam->width > RT_MAX_IMAGE_SIDE ||
        cam->height > RT_MAX_IMAGE_SIDE)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "camera: resolution %dx%d is outside 1..%d (the image size limit)",
                             cam->width, cam->height, RT_MAX_IMAGE_SIDE);
    /* The largest framebuffer (4 float channels) must fit in size_t: true
     * on 64-bit machines (16 GiB), checked for 32-bit ones. */
    if ((uint64_t)cam->width * (uint64_t)cam->height * 4u * sizeof(float) > (uint64_t)SIZE_MAX)
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT,
                             "camera: a %dx%d image does not fit in this machine's memory space",
                             cam->width, cam->height);
    scene->camera = *cam;
    scene->has_camera = 1;
    /* The camera's own version: a camera move rewrites only the layout's
     * header (render/accel_cache.c), no BVH. */
    scene->camera_version++;
    return RT_OK;
}

rt_status rt_camera_get(const rt_scene *scene, rt_camera *camera) {
    if (!scene || !camera) return RT_ERROR_INVALID_ARGUMENT;
    *camera = scene->camera;
    return RT_OK;
}

/* The camera's orthonormal frame: forward, right, up. */
static void camera_frame(const rt_camera *c, float fwd[3], float right[3], float up[3]) {
    for (int i = 0; i < 3; i++) fwd[i] = c->look_at[i] - c->position[i];
    normalize3(fwd);
    cross3(fwd, c->up, right);
    normalize3(right);
    cross3(right, fwd, up);
}

rt_status rt_camera_move(rt_scene *scene, float right, float up, float forward) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (!isfinite(right) || !isfinite(up) || !isfinite(forward))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "camera move must be finite");
    float f[3], r[3], u[3];
    camera_frame(&scene->camera, f, r, u);
    rt_camera c = scene->camera;
    for (int i = 0; i < 3; i++) {
        float d = right * r[i] + up * u[i] + forward * f[i];
        c.position[i] += d;
        c.look_at[i] += d;
    }
    return rt_camera_set(scene, &c);
}

rt_status rt_camera_rotate(rt_scene *scene, float yaw_degrees, float pitch_degrees) {
    if (!scene) return RT_ERROR_INVALID_ARGUMENT;
    if (!isfinite(yaw_degrees) || !isfinite(pitch_degrees))
        return rt_scene_fail(scene, RT_ERROR_INVALID_ARGUMENT, "camera rotation must be finite");
    const float deg = 3.14159265358979f / 180.0f;
    float f[3], r[3], u[3];
    camera_frame(&scene->camera, f, r, u);
    rt_camera c = scene->camera;
    float dist = 0.0f;
    for (int i = 0; i < 3; i++) dist += (c.look_at[i] - c.position[i]) * f[i];
    float cy = cosf(yaw_degrees * deg), sy = sinf(yaw_degrees * deg);
    float cp = cosf(pitch_degrees * deg), sp = sinf(pitch_degrees * deg);
    /* Yaw turns forward towards -right (a positive yaw looks left), then
     * pitch turns it towards up. */
    float f1[3], r1[3];
    for (int i = 0; i < 3; i++) {
        f1[i] = cy * f[i] - sy * r[i];
        r1[i] = cy * r[i] + sy * f[i];
    }
    float f2[3];
    for (int i = 0; i < 3; i++) f2[i] = cp * f1[i] + sp * u[i];
    normalize3(f2);
    (void)r1;
    for (int i = 0; i < 3; i++) c.look_at[i] = c.position[i] + dist * f2[i];
    return rt_camera_set(scene, &c);
}

/* ---- queries ---------------------------------------------------------------- */

uint64_t rt_scene_triangle_count(const rt_scene *scene) {
    uint64_t n = 0;
    for (uint32_t i = 0; i < scene->object_count; i++) {
        const rt_object_data *o = &scene->objects[i];
        if (o->mesh_count) n += scene->meshes[rt_object_shown_mesh(o)].triangle_count;
    }
    return n;
}

static int is_identity(const float m[16]);

static void transform_point(const float m[16], const float p[3], float out[3]) {
    for (int r = 0; r < 3; r++)
        out[r] = m[r * 4 + 0] * p[0] + m[r * 4 + 1] * p[1] + m[r * 4 + 2] * p[2] + m[r * 4 + 3];
}

int rt_scene_bounds(const rt_scene *scene, float bmin[3], float bmax[3]) {
    int any = 0;
    for (int k = 0; k < 3; k++) bmin[k] = INFINITY, bmax[k] = -INFINITY;
    for (uint32_t i = 0; i < scene->object_count; i++) {
        const rt_object_data *o = &scene->objects[i];
        if (!o->mesh_count) continue;
        const rt_mesh_data *m = &scene->meshes[rt_object_shown_mesh(o)];
        /* Only vertices that triangles use count: unused ones would move the
         * default camera away from the model. With the identity (most objects,
         * every bare OBJ) transform_point's sums are x + (+-0) ... + 0: x itself,
         * and +0 for either zero; x + 0.0f is that same float (positions are
         * finite), without the twelve products per vertex. */
        const int identity = is_identity(o->transform);
        for (uint64_t t = 0; t < 3 * (uint64_t)m->triangle_count; t++) {
            float p[3];
            const float *v = m->positions + 3 * (size_t)m->indices[t];
            if (identity)
                for (int k = 0; k < 3; k++) p[k] = v[k] + 0.0f;
            else
                transform_point(o->transform, v, p);
            for (int k = 0; k < 3; k++) {
                if (p[k] < bmin[k]) bmin[k] = p[k];
                if (p[k] > bmax[k]) bmax[k] = p[k];
            }
            any = 1;
        }
    }
    return any;
}

static int is_identity(const float m[16]) {
    float id[16];
    rt_mat4_identity(id);
    return memcmp(m, id, sizeof id) == 0;
}

rt_scene_features rt_scene_features_of(const rt_scene *scene) {
    rt_scene_features f;
    memset(&f, 0, sizeof f);
    for (uint32_t i = 0; i < scene->material_count; i++) {
        if (scene->materials[i].reflectivity > 0.0f) f.reflection = 1;
        if (scene->materials[i].transparency > 0.0f) f.refraction = 1;
    }
    f.instancing = scene->object_count > 1;
    for (uint32_t i = 0; i < scene->object_count; i++) {
        const rt_object_data *o = &scene->objects[i];
        if (!is_identity(o->transform) || o->has_pending) f.instancing = 1;
        if (o->mesh_count > 1) f.keyframes = 1;
    }
    for (uint32_t i = 0; i < scene->mesh_count; i++) {
        if (scene->meshes[i].normals) f.normals = 1;
        if (scene->meshes[i].tri_materials) f.tri_materials = 1;
    }
    return f;
}
