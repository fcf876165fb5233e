/* SPDX-License-Identifier: Apache-2.0 */
/* obj_load.h - Wavefront OBJ (and its MTL materials) to one indexed mesh.
 *
 * Faces with n >= 3 vertices are fan-triangulated as (v0,v1,v2),(v0,v2,v3)...,
 * so triangle k of the result is the k-th triangle in file order. vt is
 * ignored; o, g and s are accepted and ignored; usemtl/mtllib give per-triangle
 * materials when the .mtl file can be read.
 */
#ifndef RT_OBJ_LOAD_H
#define RT_OBJ_LOAD_H

#include <stddef.h>
#include <stdint.h>

#include "rt.h"

typedef struct rt_obj_material {
    char *name;  /* whole, as newmtl gives it (trailing blanks dropped) */
    float kd[3]; /* diffuse colour (Kd), default 0.8 */
    float ks[3]; /* specular colour (Ks), default 0 */
    float ke[3]; /* emission (Ke), default 0 */
    float ns;    /* shininess (Ns), default 0 */
    float ni;    /* index of refraction (Ni), default 1 */
    float d;     /* dissolve (d, or 1 - Tr), default 1 */
} rt_obj_material;

typedef struct rt_obj_mesh {
    float *positions; /* 3 per vertex */
    float *normals;   /* 3 per vertex, or NULL when the faces carry no normals */
    uint32_t vertex_count;
    uint32_t *indices; /* 3 per triangle, into the vertices above */
    uint32_t triangle_count;
    /* Per triangle, an index into materials; NULL when the file uses no
     * material. Triangles before the first usemtl, or whose usemtl names a
     * material the .mtl lacks, get UINT32_MAX. */
    uint32_t *tri_materials;
    rt_obj_material *materials;
    uint32_t material_count;
    /* A notice about the input that loading went past (a material name
     * defined twice: the first counts), "" when none; the caller shows it
     * (the library never prints). */
    char notice[768];
} rt_obj_mesh;

/* Reads and parses path. On failure out is left empty and err names the file,
 * the line and the reason. */
rt_status rt_obj_load(const char *path, rt_obj_mesh *out, rt_error *err);

/* Parses text of len bytes; name is used in error messages and base_dir (may
 * be NULL) to resolve mtllib. */
rt_status rt_obj_parse(const char *text, size_t len, const char *name, const char *base_dir,
                       rt_obj_mesh *out, rt_error *err);

void rt_obj_free(rt_obj_mesh *mesh);

#endif /* RT_OBJ_LOAD_H */
