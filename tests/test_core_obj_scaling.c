/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_obj_scaling.c - OBJ loading stays near-linear where it used to
 * be quadratic: one position used with 100,000 distinct normals (the vertex
 * de-duplication searched a list per position) and 40,000 distinct usemtl
 * names matched against an MTL of 40,000 materials (linear name searches).
 * The loaded mesh is checked value by value. tests/CMakeLists.txt gives this
 * test a TIMEOUT of 20 s: it guards the complexity class (before the fix the
 * input took minutes; now well under a second), not a speed claim. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "formats/obj_load.h"

enum { NORMALS = 100000, NAMES = 40000 };

/* Appends printf output to a growing buffer. */
typedef struct {
    char *p;
    size_t len, cap;
} text_buf;

static void put(text_buf *b, const char *fmt, int a, int c) {
    if (b->cap - b->len < 128) {
        b->cap = b->cap ? 2 * b->cap : 1 << 20;
        b->p = realloc(b->p, b->cap);
        if (!b->p) {
            fprintf(stderr, "out of memory\n");
            exit(1);
        }
    }
    b->len += (size_t)snprintf(b->p + b->len, b->cap - b->len, fmt, a, c);
}

int main(void) {
    /* The MTL: NAMES materials, in reverse order of their names. */
    text_buf mtl = {0};
    for (int m = NAMES - 1; m >= 0; m--) put(&mtl, "newmtl m%d\nKd 0.5 0.%d 0.5\n", m, m % 10);
    const char *mtl_path = test_write_temp("many.mtl", mtl.p);
    free(mtl.p);
    if (!mtl_path) test_skip("cannot write a temporary file");
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", mtl_path);
    *strrchr(dir, '/') = '\0';

    /* The OBJ: three positions, NORMALS normals, triangle k with normal k
     * at all three corners and usemtl m(k % NAMES) before it. */
    text_buf obj = {0};
    put(&obj, "mtllib many.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", 0, 0);
    for (int k = 0; k < NORMALS; k++) put(&obj, "vn %d 1 %d\n", k, k % 7);
    for (int k = 0; k < NORMALS; k++) {
        put(&obj, "usemtl m%d\n", k % NAMES, 0);
        put(&obj, "f 1//%d 2//%d 3//", k + 1, k + 1);
        put(&obj, "%d\n", k + 1, 0);
    }
    rt_obj_mesh m;
    rt_error err;
    rt_status st = rt_obj_parse(obj.p, obj.len, "many.obj", dir, &m, &err);
    free(obj.p);
    CHECK_MSG(st == RT_OK, "%s", err.message);
    if (st != RT_OK) return TEST_END();
    CHECK_EQ_INT(m.triangle_count, NORMALS);
    CHECK_EQ_INT(m.vertex_count, 3 * NORMALS); /* every (position, normal) pair is new */
    CHECK_EQ_INT(m.material_count, NAMES);
    CHECK(m.normals != NULL && m.tri_materials != NULL);
    int bad = 0;
    for (uint32_t k = 0; k < m.triangle_count && m.normals && m.tri_materials; k++) {
        for (int c = 0; c < 3; c++) {
            const uint32_t v = m.indices[3 * k + c];
            /* vertices in order of first use: triangle k's corners are 3k.. */
            bad += v != 3 * k + (uint32_t)c;
            bad += m.positions[3 * v] != (c == 1 ? 1.0f : 0.0f);
            bad += m.positions[3 * v + 1] != (c == 2 ? 1.0f : 0.0f);
            bad += m.normals[3 * v] != (float)k || m.normals[3 * v + 1] != 1.0f ||
                   m.normals[3 * v + 2] != (float)(k % 7);
        }
        /* usemtl m(k % NAMES) is material NAMES - 1 - (k % NAMES) of the MTL. */
        const uint32_t want = NAMES - 1 - k % NAMES;
        bad += m.tri_materials[k] != want;
        if (m.tri_materials[k] < m.material_count) {
            char name[32];
            snprintf(name, sizeof name, "m%u", k % NAMES);
            bad += strcmp(m.materials[m.tri_materials[k]].name, name) != 0;
        }
        if (bad && bad < 2) fprintf(stderr, "triangle %u differs\n", k);
    }
    CHECK_EQ_INT(bad, 0);
    rt_obj_free(&m);
    return TEST_END();
}
