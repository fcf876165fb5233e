/* scene_save.c - writes a scene as JSON + OBJ (docs/SCENE_FORMAT.md). */
#include "formats/scene_save.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "scene/scene.h"

static void write_vec3(FILE *f, const float v[3]) {
    fprintf(f, "[%.9g, %.9g, %.9g]", (double)v[0], (double)v[1], (double)v[2]);
}

static rt_status write_obj(const rt_mesh_data *m, const char *mesh_name, const char *path,
                           rt_error *err) {
    FILE *f = fopen(path, "wb");
    if (!f) return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot write: %s", strerror(errno));
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
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "write failed: %s", strerror(errno));
    return RT_OK;
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
static rt_status names_usable(const rt_scene *s, int *usable) {
    *usable = 1;
    for (uint32_t i = 0; i < s->mesh_count && *usable; i++) *usable = plain_name(s->meshes[i].name);
    if (!*usable || s->mesh_count < 2) return RT_OK;
    const char **names = malloc(s->mesh_count * sizeof *names);
    if (!names) return RT_ERROR_OUT_OF_MEMORY;
    for (uint32_t i = 0; i < s->mesh_count; i++) names[i] = s->meshes[i].name;
    qsort(names, s->mesh_count, sizeof *names, by_name);
    for (uint32_t i = 1; i < s->mesh_count && *usable; i++)
        *usable = strcmp(names[i - 1], names[i]) != 0;
    free(names);
    return RT_OK;
}

/* Mesh i's name in the saved files. */
static const char *saved_name(const rt_scene *s, int usable, uint32_t i, char buf[32]) {
    if (usable) return s->meshes[i].name;
    snprintf(buf, 32, "mesh_%u", i);
    return buf;
}

rt_status rt_scene_save_json(const rt_scene *s, const char *dir, const char *name, rt_error *err) {
    char path[1024], mesh_name[32], other_name[32];
    int usable;
    if (names_usable(s, &usable) != RT_OK)
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, NULL, 0, 0, "out of memory");
    for (uint32_t i = 0; i < s->mesh_count; i++) {
        if (s->meshes[i].tri_materials)
            return rt_error_set(err, RT_ERROR_UNSUPPORTED, NULL, 0, 0,
                                "mesh %u has per-triangle materials, which JSON cannot express", i);
        const char *mesh = saved_name(s, usable, i, mesh_name);
        snprintf(path, sizeof path, "%s/%s_%s.obj", dir, name, mesh);
        rt_status st = write_obj(&s->meshes[i], mesh, path, err);
        if (st != RT_OK) return st;
    }
    snprintf(path, sizeof path, "%s/%s.json", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot write: %s", strerror(errno));
    const rt_camera *c = &s->camera;
    fprintf(f, "{\n  \"camera\": {\"position\": ");
    write_vec3(f, c->position);
    fprintf(f, ", \"look_at\": ");
    write_vec3(f, c->look_at);
    fprintf(f, ", \"up\": ");
    write_vec3(f, c->up);
    fprintf(f, ",\n             \"fov\": %.9g, \"width\": %d, \"height\": %d},\n",
            (double)c->hfov_degrees, c->width, c->height);
    fprintf(f, "  \"background\": ");
    write_vec3(f, s->background);
    fprintf(f, ",\n  \"ambient\": ");
    write_vec3(f, s->ambient);
    fprintf(f, ",\n  \"materials\": {\n");
    for (uint32_t i = 0; i < s->material_count; i++) {
        const rt_material *m = &s->materials[i];
        fprintf(f, "    \"m%u\": {\"color\": ", i);
        write_vec3(f, m->color);
        fprintf(f,
                ", \"ambient\": %.9g, \"diffuse\": %.9g, \"specular\": %.9g, \"shininess\": %d,\n"
                "          \"reflectivity\": %.9g, \"transparency\": %.9g, \"ior\": %.9g}%s\n",
                (double)m->ambient, (double)m->diffuse, (double)m->specular, m->shininess,
                (double)m->reflectivity, (double)m->transparency, (double)m->ior,
                i + 1 < s->material_count ? "," : "");
    }
    fprintf(f, "  },\n  \"lights\": [\n");
    for (uint32_t i = 0; i < s->light_count; i++) {
        fprintf(f, "    {\"position\": ");
        write_vec3(f, s->lights[i].position);
        fprintf(f, ", \"color\": ");
        write_vec3(f, s->lights[i].color);
        fprintf(f, "}%s\n", i + 1 < s->light_count ? "," : "");
    }
    fprintf(f, "  ],\n  \"meshes\": {\n");
    for (uint32_t i = 0; i < s->mesh_count; i++) {
        const char *mesh = saved_name(s, usable, i, mesh_name);
        uint32_t accel = s->meshes[i].accel;
        fprintf(f, "    \"%s\": {\"file\": \"%s_%s.obj\"%s%s%s}%s\n", mesh, name, mesh,
                accel ? ", \"accel\": \"" : "", accel ? rt_accel_name((rt_accel)accel) : "",
                accel ? "\"" : "", i + 1 < s->mesh_count ? "," : "");
    }
    fprintf(f, "  },\n  \"objects\": [\n");
    for (uint32_t i = 0; i < s->object_count; i++) {
        const rt_object_data *o = &s->objects[i];
        if (o->mesh_count == 1) {
            fprintf(f, "    {\"mesh\": \"%s\"", saved_name(s, usable, o->meshes[0], mesh_name));
        } else {
            fprintf(f, "    {\"keyframes\": [");
            for (uint32_t k = 0; k < o->mesh_count; k++)
                fprintf(f, "%s\"%s\"", k ? ", " : "",
                        saved_name(s, usable, o->meshes[k], other_name));
            fprintf(f, "], \"frame\": %u", o->selected);
        }
        fprintf(f, ", \"material\": \"m%u\"", o->material);
        float id[16];
        rt_mat4_identity(id);
        if (memcmp(id, o->transform, sizeof id) != 0) {
            fprintf(f, ",\n     \"transform\": {\"matrix\": [");
            for (int k = 0; k < 16; k++)
                fprintf(f, "%.9g%s", (double)o->transform[k], k < 15 ? ", " : "");
            fprintf(f, "]}");
        }
        fprintf(f, "}%s\n", i + 1 < s->object_count ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "write failed: %s", strerror(errno));
    return RT_OK;
}
