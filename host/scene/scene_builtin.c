/* SPDX-License-Identifier: Apache-2.0 */
/* scene_builtin.c - the scenes the project ships, generated in code.
 *
 * "cornell": a Cornell-like room (red and green side walls, open front) with a
 * mirror sphere, a glass sphere and a twisting white column animated by four
 * keyframes, lit by one point light. The default scene.
 * "keyframes": a twisting column with four keyframes and a rigid transform,
 * standing on a floor; it exercises instancing and keyframe selection.
 *
 * Vertex positions are computed in float and written out with %.9g by
 * `rtcl generate`, so the JSON + OBJ copies in scenes/ load to the same bits.
 */
#include "scene/scene_builtin.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "scene/scene.h"

const char *const rt_builtin_scene_names[] = {"cornell", "keyframes", NULL};

const char *rt_builtin_scene_name(int index) {
    enum { COUNT = sizeof rt_builtin_scene_names / sizeof rt_builtin_scene_names[0] - 1 };
    return index >= 0 && index < COUNT ? rt_builtin_scene_names[index] : NULL;
}

/* A growable triangle list that becomes one mesh. */
typedef struct mesh_builder {
    float *pos, *nrm;
    uint32_t *idx;
    uint32_t nv, nt, cap_v, cap_t;
    int with_normals;
    int failed;
} mesh_builder;

static uint32_t mb_vertex(mesh_builder *b, float x, float y, float z, float nx, float ny,
                          float nz) {
    if (b->nv == b->cap_v) {
        uint32_t cap = b->cap_v ? 2 * b->cap_v : 64;
        float *p = realloc(b->pos, 3 * sizeof(float) * cap);
        if (p) b->pos = p;
        float *n = realloc(b->nrm, 3 * sizeof(float) * cap);
        if (n) b->nrm = n;
        if (!p || !n) {
            b->failed = 1;
            return 0;
        }
        b->cap_v = cap;
    }
    float *p = b->pos + 3 * b->nv, *n = b->nrm + 3 * b->nv;
    p[0] = x, p[1] = y, p[2] = z;
    n[0] = nx, n[1] = ny, n[2] = nz;
    return b->nv++;
}

static void mb_tri(mesh_builder *b, uint32_t i, uint32_t j, uint32_t k) {
    if (b->failed) return;
    if (b->nt == b->cap_t) {
        uint32_t cap = b->cap_t ? 2 * b->cap_t : 64;
        uint32_t *p = realloc(b->idx, 3 * sizeof(uint32_t) * cap);
        if (!p) {
            b->failed = 1;
            return;
        }
        b->idx = p;
        b->cap_t = cap;
    }
    uint32_t *t = b->idx + 3 * b->nt++;
    t[0] = i, t[1] = j, t[2] = k;
}

/* A quad a-b-c-d (counter-clockwise seen from the front) as two triangles. */
static void mb_quad(mesh_builder *b, const float a[3], const float bb[3], const float c[3],
                    const float d[3]) {
    uint32_t i0 = mb_vertex(b, a[0], a[1], a[2], 0, 0, 0);
    uint32_t i1 = mb_vertex(b, bb[0], bb[1], bb[2], 0, 0, 0);
    uint32_t i2 = mb_vertex(b, c[0], c[1], c[2], 0, 0, 0);
    uint32_t i3 = mb_vertex(b, d[0], d[1], d[2], 0, 0, 0);
    mb_tri(b, i0, i1, i2);
    mb_tri(b, i0, i2, i3);
}

/* A UV sphere with smooth per-vertex normals. */
static void mb_sphere(mesh_builder *b, const float centre[3], float radius, int rings,
                      int segments) {
    const float pi = 3.14159265358979f;
    uint32_t first = b->nv;
    for (int r = 0; r <= rings; r++) {
        float theta = pi * (float)r / (float)rings;
        for (int s = 0; s <= segments; s++) {
            float phi = 2.0f * pi * (float)s / (float)segments;
            float nx = sinf(theta) * cosf(phi), ny = cosf(theta), nz = sinf(theta) * sinf(phi);
            mb_vertex(b, centre[0] + radius * nx, centre[1] + radius * ny, centre[2] + radius * nz,
                      nx, ny, nz);
        }
    }
    uint32_t row = (uint32_t)segments + 1;
    for (int r = 0; r < rings; r++)
        for (int s = 0; s < segments; s++) {
            uint32_t i00 = first + (uint32_t)r * row + (uint32_t)s, i01 = i00 + 1;
            uint32_t i10 = i00 + row, i11 = i10 + 1;
            if (r != 0) mb_tri(b, i00, i01, i10); /* no zero-area cap triangles */
            if (r != rings - 1) mb_tri(b, i01, i11, i10);
        }
}

/* A square column of 'levels' rings twisted by 'twist' radians over its
 * height, capped at both ends. */
static void mb_twisted_column(mesh_builder *b, float half, float height, int levels, float twist) {
    uint32_t first = b->nv;
    for (int l = 0; l <= levels; l++) {
        float t = (float)l / (float)levels, a = twist * t;
        float ca = cosf(a), sa = sinf(a), y = height * t;
        const float corners[4][2] = {{-half, -half}, {half, -half}, {half, half}, {-half, half}};
        for (int k = 0; k < 4; k++) {
            float x = corners[k][0] * ca - corners[k][1] * sa;
            float z = corners[k][0] * sa + corners[k][1] * ca;
            mb_vertex(b, x, y, z, 0, 0, 0);
        }
    }
    for (int l = 0; l < levels; l++)
        for (int k = 0; k < 4; k++) {
            uint32_t a0 = first + 4 * (uint32_t)l + (uint32_t)k;
            uint32_t a1 = first + 4 * (uint32_t)l + (uint32_t)((k + 1) % 4);
            uint32_t b0 = a0 + 4, b1 = a1 + 4;
            mb_tri(b, a0, b1, a1);
            mb_tri(b, a0, b0, b1);
        }
    uint32_t top = first + 4 * (uint32_t)levels;
    mb_tri(b, first, first + 1, first + 2);
    mb_tri(b, first, first + 2, first + 3);
    mb_tri(b, top, top + 2, top + 1);
    mb_tri(b, top, top + 3, top + 2);
}

static void mb_free(mesh_builder *b) {
    free(b->pos);
    free(b->nrm);
    free(b->idx);
    memset(b, 0, sizeof *b);
}

/* Turns the builder into a mesh of scene and frees it. */
static rt_status mb_commit(mesh_builder *b, rt_scene *scene, const char *name, uint32_t *mesh) {
    rt_status st = b->failed ? RT_ERROR_OUT_OF_MEMORY : rt_mesh_create(scene, mesh);
    if (st == RT_OK)
        st = rt_mesh_add_triangles(scene, *mesh, b->pos, b->with_normals ? b->nrm : NULL, b->nv,
                                   b->idx, b->nt);
    if (st == RT_OK)
        snprintf(scene->meshes[*mesh].name, sizeof scene->meshes[*mesh].name, "%s", name);
    mb_free(b);
    return st;
}

static rt_status add_material(rt_scene *s, float r, float g, float bl, float diffuse,
                              float specular, int shininess, float reflect, float transmit,
                              float ior, uint32_t *id) {
    rt_material m = rt_material_default();
    m.color[0] = r, m.color[1] = g, m.color[2] = bl;
    m.diffuse = diffuse;
    m.specular = specular;
    m.shininess = shininess;
    m.reflectivity = reflect;
    m.transparency = transmit;
    m.ior = ior;
    return rt_material_add(s, &m, id);
}

/* One object showing one mesh. */
static rt_status add_object(rt_scene *s, uint32_t mesh, uint32_t material, uint32_t *object) {
    rt_status st = rt_object_create(s, material, object);
    return st == RT_OK ? rt_object_add_mesh(s, *object, mesh) : st;
}

#define TRY(expr)                                                                                  \
    do {                                                                                           \
        rt_status st_ = (expr);                                                                    \
        if (st_ != RT_OK) return st_;                                                              \
    } while (0)

/* The mesh in b as a new object of its own with material. */
static rt_status commit_object(mesh_builder *b, rt_scene *s, const char *name, uint32_t material) {
    uint32_t mesh, obj;
    TRY(mb_commit(b, s, name, &mesh));
    return add_object(s, mesh, material, &obj);
}

/* The animated object of both scenes: four keyframes, twisted columns
 * "column_K" (mb_twisted_column with twist K * twist_step), showing
 * keyframe selected, placed by the rigid transform; then a commit. */
static rt_status add_column_object(mesh_builder *b, rt_scene *s, uint32_t material, float half,
                                   float height, int levels, float twist_step, uint32_t selected,
                                   const float transform[16]) {
    uint32_t obj;
    TRY(rt_object_create(s, material, &obj));
    for (int k = 0; k < 4; k++) {
        char name[32];
        uint32_t mesh;
        snprintf(name, sizeof name, "column_%d", k);
        mb_twisted_column(b, half, height, levels, twist_step * (float)k);
        TRY(mb_commit(b, s, name, &mesh));
        TRY(rt_object_add_mesh(s, obj, mesh));
    }
    TRY(rt_object_select_mesh(s, obj, selected));
    TRY(rt_object_transform(s, obj, transform));
    return rt_scene_commit(s);
}

/* What every built-in scene ends with: one white light at light, ambient
 * 0.1, the background and the camera. */
static rt_status finish_scene(rt_scene *s, const float light[3], const float background[3],
                              const rt_camera *cam) {
    const float white_light[3] = {1.0f, 1.0f, 1.0f}, ambient[3] = {0.1f, 0.1f, 0.1f};
    uint32_t id;
    TRY(rt_light_add(s, light, white_light, &id));
    TRY(rt_scene_set_ambient(s, ambient));
    TRY(rt_scene_set_background(s, background));
    return rt_camera_set(s, cam);
}

static rt_status build_cornell(rt_scene *s) {
    const float W = 1.6f, H = 1.8f, D = 1.0f; /* half width, height, half depth */
    uint32_t white, red, green, mirror, glass;
    TRY(add_material(s, 0.8f, 0.8f, 0.8f, 0.9f, 0.0f, 1, 0.0f, 0.0f, 1.0f, &white));
    TRY(add_material(s, 0.75f, 0.15f, 0.15f, 0.9f, 0.0f, 1, 0.0f, 0.0f, 1.0f, &red));
    TRY(add_material(s, 0.15f, 0.75f, 0.15f, 0.9f, 0.0f, 1, 0.0f, 0.0f, 1.0f, &green));
    TRY(add_material(s, 0.9f, 0.9f, 0.9f, 0.1f, 0.6f, 64, 0.8f, 0.0f, 1.0f, &mirror));
    TRY(add_material(s, 1.0f, 1.0f, 1.0f, 0.05f, 0.6f, 64, 0.05f, 0.9f, 1.5f, &glass));

    mesh_builder b = {0};
    /* Floor, ceiling and back wall, seen from inside. */
    const float f0[3] = {-W, 0, D}, f1[3] = {W, 0, D}, f2[3] = {W, 0, -D}, f3[3] = {-W, 0, -D};
    const float c0[3] = {-W, H, -D}, c1[3] = {W, H, -D}, c2[3] = {W, H, D}, c3[3] = {-W, H, D};
    mb_quad(&b, f0, f1, f2, f3);
    mb_quad(&b, c0, c1, c2, c3);
    mb_quad(&b, f3, f2, c1, c0);
    TRY(commit_object(&b, s, "room", white));

    const float l0[3] = {-W, 0, D}, l1[3] = {-W, 0, -D}, l2[3] = {-W, H, -D}, l3[3] = {-W, H, D};
    mb_quad(&b, l0, l1, l2, l3);
    TRY(commit_object(&b, s, "left_wall", red));

    const float r0[3] = {W, 0, -D}, r1[3] = {W, 0, D}, r2[3] = {W, H, D}, r3[3] = {W, H, -D};
    mb_quad(&b, r0, r1, r2, r3);
    TRY(commit_object(&b, s, "right_wall", green));

    /* The animated object: a twisting white column with four keyframes,
     * moved to the back of the room by a rigid transform. */
    const float to_back[16] = {1, 0, 0, 0.05f, 0, 1, 0, 0, 0, 0, 1, -0.6f, 0, 0, 0, 1};
    TRY(add_column_object(&b, s, white, 0.22f, 0.9f, 12, 0.4f, 1, to_back));

    b.with_normals = 1;
    const float ms[3] = {-0.8f, 0.4f, -0.2f};
    mb_sphere(&b, ms, 0.4f, 24, 48);
    TRY(commit_object(&b, s, "mirror_sphere", mirror));

    b.with_normals = 1;
    const float gs[3] = {0.7f, 0.35f, 0.25f};
    mb_sphere(&b, gs, 0.35f, 24, 48);
    TRY(commit_object(&b, s, "glass_sphere", glass));

    const float light[3] = {0.0f, 1.6f, 0.2f}, black[3] = {0.0f, 0.0f, 0.0f};
    rt_camera cam = {{0.0f, 0.9f, 3.0f}, {0.0f, 0.9f, 0.0f}, {0.0f, 1.0f, 0.0f}, 60.0f, 1024, 576};
    return finish_scene(s, light, black, &cam);
}

static rt_status build_keyframes(rt_scene *s) {
    uint32_t floor_mat, column_mat;
    TRY(add_material(s, 0.7f, 0.7f, 0.75f, 0.9f, 0.0f, 1, 0.2f, 0.0f, 1.0f, &floor_mat));
    TRY(add_material(s, 0.9f, 0.6f, 0.2f, 0.8f, 0.4f, 16, 0.0f, 0.0f, 1.0f, &column_mat));
    mesh_builder b = {0};
    const float f0[3] = {-3, 0, 3}, f1[3] = {3, 0, 3}, f2[3] = {3, 0, -3}, f3[3] = {-3, 0, -3};
    mb_quad(&b, f0, f1, f2, f3);
    TRY(commit_object(&b, s, "floor", floor_mat));

    /* A quarter turn about y, then a step to the right: a rigid transform. */
    const float m[16] = {0, 0, 1, 0.5f, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 0, 1};
    TRY(add_column_object(&b, s, column_mat, 0.35f, 2.0f, 16, 0.6f, 2, m));

    const float light[3] = {2.0f, 4.0f, 3.0f}, sky[3] = {0.2f, 0.3f, 0.45f};
    rt_camera cam = {{0.0f, 2.0f, 6.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 60.0f, 1024, 576};
    return finish_scene(s, light, sky, &cam);
}

rt_status rt_scene_builtin(const char *name, rt_scene **out, rt_error *err) {
    rt_error_clear(err);
    if (!out) return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, NULL, 0, 0, "no output scene");
    *out = NULL;
    rt_status (*build)(rt_scene *) = NULL;
    if (name && strcmp(name, "cornell") == 0) build = build_cornell;
    if (name && strcmp(name, "keyframes") == 0) build = build_keyframes;
    if (!build)
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, NULL, 0, 0,
                            "no built-in scene named '%s' (try: cornell, keyframes)",
                            name ? name : "(null)");
    rt_scene *s;
    if (rt_scene_create(&s) != RT_OK)
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, NULL, 0, 0, "out of memory");
    rt_status st = build(s);
    if (st != RT_OK) {
        rt_error_set(err, st, NULL, 0, 0, "built-in scene '%s': %s", name, rt_scene_error(s));
        rt_scene_destroy(s);
        return st;
    }
    snprintf(s->source, sizeof s->source, "builtin:%s", name);
    *out = s;
    return RT_OK;
}
