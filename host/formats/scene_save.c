/* scene_save.c - writes a scene as JSON + OBJ (docs/SCENE_FORMAT.md). */
#include "formats/scene_save.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "scene/scene.h"

static void write_vec3(FILE *f, const float v[3]) {
    fprintf(f, "[%.9g, %.9g, %.9g]", (double)v[0], (double)v[1], (double)v[2]);
}

static rt_status write_obj(const rt_mesh_data *m, const char *path, rt_error *err) {
    FILE *f = fopen(path, "wb");
    if (!f) return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot write: %s", strerror(errno));
    fprintf(f, "# %s: %u vertices, %u triangles, written by rtcl\n", m->name, m->vertex_count,
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

rt_status rt_scene_save_json(const rt_scene *s, const char *dir, const char *name, rt_error *err) {
    char path[1024];
    for (uint32_t i = 0; i < s->mesh_count; i++) {
        if (s->meshes[i].tri_materials)
            return rt_error_set(err, RT_ERROR_UNSUPPORTED, NULL, 0, 0,
                                "mesh %u has per-triangle materials, which JSON cannot express", i);
        snprintf(path, sizeof path, "%s/%s_%s.obj", dir, name, s->meshes[i].name);
        rt_status st = write_obj(&s->meshes[i], path, err);
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
    for (uint32_t i = 0; i < s->mesh_count; i++)
        fprintf(f, "    \"%s\": {\"file\": \"%s_%s.obj\"%s%s%s}%s\n", s->meshes[i].name, name,
                s->meshes[i].name, s->meshes[i].accel ? ", \"accel\": \"" : "",
                s->meshes[i].accel ? rt_accel_name((rt_accel)s->meshes[i].accel) : "",
                s->meshes[i].accel ? "\"" : "", i + 1 < s->mesh_count ? "," : "");
    fprintf(f, "  },\n  \"objects\": [\n");
    for (uint32_t i = 0; i < s->object_count; i++) {
        const rt_object_data *o = &s->objects[i];
        if (o->mesh_count == 1) {
            fprintf(f, "    {\"mesh\": \"%s\"", s->meshes[o->meshes[0]].name);
        } else {
            fprintf(f, "    {\"keyframes\": [");
            for (uint32_t k = 0; k < o->mesh_count; k++)
                fprintf(f, "%s\"%s\"", k ? ", " : "", s->meshes[o->meshes[k]].name);
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
