/* SPDX-License-Identifier: Apache-2.0 */
/* scene_save.c - writes a scene as JSON + OBJ (docs/SCENE_FORMAT.md). */
#include "formats/scene_save.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "scene/scene.h"

/* A number that reads back as the same bits: %.9g for a float, %.17g for a
 * double; a negative zero as -0.0 (JSON's -0 is an integer, read as +0). */
static void write_num(FILE *f, double x, int digits) {
    if (x == 0.0 && signbit(x))
        fputs("-0.0", f);
    else
        fprintf(f, "%.*g", digits, x);
}

/* The text before, then v as a JSON array of three numbers. */
static void write_vec3(FILE *f, const char *before, const float v[3]) {
    fputs(before, f);
    fputc('[', f);
    for (int i = 0; i < 3; i++) {
        if (i) fputs(", ", f);
        write_num(f, (double)v[i], 9);
    }
    fputc(']', f);
}

/* Writes one mesh as an OBJ file, whole or not at all. */
static rt_status write_obj(const rt_mesh_data *m, const char *mesh_name, const char *path,
                           rt_error *err) {
    rt_atomic_file out;
    rt_status st = rt_atomic_file_open(&out, path, "OBJ file", err);
    if (st != RT_OK) return st;
    FILE *f = out.stream;
    fprintf(f, "# %s: %u vertices, %u triangles, written by rtcl\n", mesh_name, m->vertex_count,
            m->triangle_count);
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *p = m->positions + 3 * (size_t)v;
        fprintf(f, "v %.9g %.9g %.9g\n", (double)p[0], (double)p[1], (double)p[2]);
    }
    if (m->normals)
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            const float *n = m->normals + 3 * (size_t)v;
            fprintf(f, "vn %.9g %.9g %.9g\n", (double)n[0], (double)n[1], (double)n[2]);
        }
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *i = m->indices + 3 * (size_t)t;
        if (m->normals)
            fprintf(f, "f %u//%u %u//%u %u//%u\n", i[0] + 1, i[0] + 1, i[1] + 1, i[1] + 1, i[2] + 1,
                    i[2] + 1);
        else
            fprintf(f, "f %u %u %u\n", i[0] + 1, i[1] + 1, i[2] + 1);
    }
    return rt_atomic_file_commit(&out, err);
}

/* A mesh name that can be a JSON key and part of a file name as it is. */
static int plain_name(const char *n) {
    if (!n[0] || n[0] == '.') return 0;
    for (const char *c = n; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ||
              *c == '_' || *c == '-' || *c == '.'))
            return 0;
    return 1;
}

static int by_name(const void *a, const void *b) {
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* Whether the meshes' own names can name them in the files: all plain and no
 * two alike. Otherwise (a JSON key with a quote or a slash, two meshes from
 * files of the same name) every mesh is saved as mesh_INDEX: a name written
 * as it was broke the JSON, collided, or pointed outside dir (found by
 * tests/fuzz/fuzz_json). */
static rt_status names_usable(const rt_scene *s, const uint8_t *blend, int *usable) {
    *usable = 1;
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->mesh_count && *usable; i++)
        if (!blend[i]) *usable = plain_name(s->meshes[i].name), n++;
    if (!*usable || n < 2) return RT_OK;
    const char **names = malloc(n * sizeof *names);
    if (!names) return RT_ERROR_OUT_OF_MEMORY;
    n = 0;
    for (uint32_t i = 0; i < s->mesh_count; i++)
        if (!blend[i]) names[n++] = s->meshes[i].name;
    qsort(names, n, sizeof *names, by_name);
    for (uint32_t i = 1; i < n && *usable; i++) *usable = strcmp(names[i - 1], names[i]) != 0;
    free(names);
    return RT_OK;
}

/* Which meshes are blends of morphing objects (made by rt_scene_set_time,
 * not read from the file, and kept emptied after rt_object_remove): they are
 * not saved, the loader makes them again.
 * NULL when out of memory. */
static uint8_t *blend_meshes(const rt_scene *s) {
    uint8_t *blend = calloc(s->mesh_count ? s->mesh_count : 1, 1);
    if (!blend) return NULL;
    for (uint32_t m = 0; m < s->mesh_count; m++) blend[m] = s->meshes[m].blend != 0;
    return blend;
}

/* A key's start: the separator before it, then {"time": T (17 digits). */
static void write_key_time(FILE *f, const char *before, double time) {
    fprintf(f, "%s{\"time\": ", before);
    write_num(f, time, 17);
}

/* The camera: its path (which places the eye and the look-at point at
 * every time) or its position and look-at point; up, fov and size. */
static void write_camera(FILE *f, const rt_scene *s) {
    const rt_camera *c = &s->camera;
    fprintf(f, "{\n  \"camera\": {");
    if (s->camera_path_count) {
        fprintf(f, "\"path\": [");
        for (uint32_t i = 0; i < s->camera_path_count; i++) {
            const rt_camera_key *k = &s->camera_path[i];
            write_key_time(f, i ? ",\n                      " : "", k->time);
            write_vec3(f, ", \"position\": ", k->position);
            write_vec3(f, ", \"look_at\": ", k->look_at);
            fputc('}', f);
        }
        fprintf(f, "],\n             ");
    } else {
        write_vec3(f, "\"position\": ", c->position);
        write_vec3(f, ", \"look_at\": ", c->look_at);
        fprintf(f, ", ");
    }
    write_vec3(f, "\"up\": ", c->up);
    fprintf(f, ",\n             \"fov\": ");
    write_num(f, (double)c->hfov_degrees, 9);
    fprintf(f, ", \"width\": %d, \"height\": %d},\n", c->width, c->height);
}

/* An object's animation and keyed transform (docs/SCENE_FORMAT.md, "Time"). */
static void write_object_time(FILE *f, const rt_object_data *o) {
    if (o->keyframe_rate > 0.0f) {
        fprintf(f, ",\n     \"animation\": {\"keyframe_rate\": ");
        write_num(f, (double)o->keyframe_rate, 9);
        fprintf(f, ", \"interpolate\": %s}", o->interpolate ? "true" : "false");
    }
    if (!o->transform_key_count) return;
    fprintf(f, ",\n     \"transform_keys\": [");
    for (uint32_t i = 0; i < o->transform_key_count; i++) {
        const rt_transform_key *k = &o->transform_keys[i];
        write_key_time(f, i ? ",\n                        " : "", k->time);
        write_vec3(f, ", \"translate\": ", k->translate);
        write_vec3(f, ", \"rotate\": {\"axis\": ", k->axis);
        fprintf(f, ", \"degrees\": ");
        write_num(f, (double)k->degrees, 9);
        fprintf(f, "}, \"scale\": ");
        write_num(f, (double)k->scale, 9);
        fputc('}', f);
    }
    fputc(']', f);
}

/* Mesh i's name in the saved files. */
static const char *saved_name(const rt_scene *s, int usable, uint32_t i, char buf[32]) {
    if (usable) return s->meshes[i].name;
    snprintf(buf, 32, "mesh_%u", i);
    return buf;
}

/* dir/stem.ext into path (cap bytes); 0 when it does not fit. */
static int path_fits(char *path, size_t cap, const char *dir, const char *stem, const char *ext) {
    int n = snprintf(path, cap, "%s/%s%s", dir, stem, ext);
    return n >= 0 && (size_t)n < cap;
}

rt_status rt_scene_save_check(const char *dir, const char *name, rt_error *err) {
    char path[1024];
    if (!dir || !name || !path_fits(path, sizeof path, dir, name, ".json"))
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, dir, 0, 0,
                            "the folder and scene name make a path longer than %zu bytes",
                            sizeof path - 1);
    return rt_atomic_file_check(path, "scene file", err);
}

rt_status rt_scene_save_json(const rt_scene *s, const char *dir, const char *name, rt_error *err) {
    char path[1024], mesh_name[32], other_name[32];
    int usable;
    uint8_t *blend = blend_meshes(s);
    if (!blend || names_usable(s, blend, &usable) != RT_OK) {
        free(blend);
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, NULL, 0, 0, "out of memory");
    }
    /* Everything that can refuse the scene is checked before any file is
     * written, so a refused scene leaves no files behind. */
    rt_status st = RT_OK;
    for (uint32_t i = 0; i < s->mesh_count && st == RT_OK; i++)
        if (!blend[i] && s->meshes[i].tri_materials)
            st = rt_error_set(err, RT_ERROR_UNSUPPORTED, NULL, 0, 0,
                              "mesh %u has per-triangle materials, which JSON cannot express", i);
    if (st == RT_OK && !path_fits(path, sizeof path, dir, name, ".json"))
        st = rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, dir, 0, 0,
                          "the folder and scene name make a path longer than %zu bytes",
                          sizeof path - 1);
    if (st == RT_OK) st = rt_atomic_file_check(path, "scene file", err);
    for (uint32_t i = 0; i < s->mesh_count && st == RT_OK; i++) {
        if (blend[i]) continue;
        const char *mesh = saved_name(s, usable, i, mesh_name);
        char obj_name[600];
        snprintf(obj_name, sizeof obj_name, "%s_%s", name, mesh);
        if (!path_fits(path, sizeof path, dir, obj_name, ".obj"))
            st = rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, dir, 0, 0,
                              "the folder and mesh name make a path longer than %zu bytes",
                              sizeof path - 1);
        else
            st = write_obj(&s->meshes[i], mesh, path, err);
    }
    if (st != RT_OK) {
        free(blend);
        return st;
    }
    path_fits(path, sizeof path, dir, name, ".json");
    rt_atomic_file out;
    st = rt_atomic_file_open(&out, path, "scene file", err);
    if (st != RT_OK) {
        free(blend);
        return st;
    }
    FILE *f = out.stream;
    write_camera(f, s);
    write_vec3(f, "  \"background\": ", s->background);
    write_vec3(f, ",\n  \"ambient\": ", s->ambient);
    if (s->exposure != 0.0f) fprintf(f, ",\n  \"exposure\": %.9g", (double)s->exposure);
    fprintf(f, ",\n  \"materials\": {\n");
    for (uint32_t i = 0; i < s->material_count; i++) {
        const rt_material *m = &s->materials[i];
        fprintf(f, "    \"m%u\": {\"color\": ", i);
        write_vec3(f, "", m->color);
        fprintf(f,
                ", \"ambient\": %.9g, \"diffuse\": %.9g, \"specular\": %.9g, \"shininess\": %d,\n"
                "          \"reflectivity\": %.9g, \"transparency\": %.9g, \"ior\": %.9g",
                (double)m->ambient, (double)m->diffuse, (double)m->specular, m->shininess,
                (double)m->reflectivity, (double)m->transparency, (double)m->ior);
        if (m->emission[0] != 0.0f || m->emission[1] != 0.0f || m->emission[2] != 0.0f)
            write_vec3(f, ", \"emission\": ", m->emission);
        fprintf(f, "}%s\n", i + 1 < s->material_count ? "," : "");
    }
    fprintf(f, "  },\n  \"lights\": [\n");
    for (uint32_t i = 0; i < s->light_count; i++) {
        write_vec3(f, "    {\"position\": ", s->lights[i].position);
        write_vec3(f, ", \"color\": ", s->lights[i].color);
        fprintf(f, "}%s\n", i + 1 < s->light_count ? "," : "");
    }
    fprintf(f, "  ],\n  \"meshes\": {");
    int first = 1;
    for (uint32_t i = 0; i < s->mesh_count; i++) {
        if (blend[i]) continue;
        const rt_mesh_data *md = &s->meshes[i];
        const char *mesh = saved_name(s, usable, i, mesh_name);
        fprintf(f, "%s\n    \"%s\": {\"file\": \"%s_%s.obj\"", first ? "" : ",", mesh, name, mesh);
        if (md->accel) fprintf(f, ", \"accel\": \"%s\"", rt_accel_name((rt_accel)md->accel));
        if (md->update_policy != RT_UPDATE_SAH)
            fprintf(f, ", \"update\": \"%s\"",
                    rt_update_policy_name((rt_update_policy)md->update_policy));
        fputc('}', f);
        first = 0;
    }
    fprintf(f, "\n  },\n  \"objects\": [\n");
    for (uint32_t i = 0; i < s->object_count; i++) {
        const rt_object_data *o = &s->objects[i];
        int animated = o->keyframe_rate > 0.0f;
        if (o->mesh_count == 1 && !animated) {
            fprintf(f, "    {\"mesh\": \"%s\"", saved_name(s, usable, o->meshes[0], mesh_name));
        } else {
            fprintf(f, "    {\"keyframes\": [");
            for (uint32_t k = 0; k < o->mesh_count; k++)
                fprintf(f, "%s\"%s\"", k ? ", " : "",
                        saved_name(s, usable, o->meshes[k], other_name));
            /* An animation chooses the keyframe from the time ("frame" and
             * "animation" exclude each other). */
            if (animated)
                fputc(']', f);
            else
                fprintf(f, "], \"frame\": %u", o->selected);
        }
        fprintf(f, ", \"material\": \"m%u\"", o->material);
        if (o->mask != 0xffffffffu) fprintf(f, ", \"mask\": %u", o->mask);
        float id[16];
        rt_mat4_identity(id);
        /* Keyed transforms place the object at every time ("transform" and
         * "transform_keys" exclude each other). */
        if (!o->transform_key_count && memcmp(id, o->transform, sizeof id) != 0) {
            fprintf(f, ",\n     \"transform\": {\"matrix\": [");
            for (int k = 0; k < 16; k++) {
                write_num(f, (double)o->transform[k], 9);
                if (k < 15) fputs(", ", f);
            }
            fprintf(f, "]}");
        }
        write_object_time(f, o);
        fprintf(f, "}%s\n", i + 1 < s->object_count ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
    free(blend);
    return rt_atomic_file_commit(&out, err);
}
