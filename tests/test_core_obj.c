/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_obj.c - the OBJ/MTL loader: statements, index forms, fan
 * triangulation, normals, materials, every error kind. The shared scenes are in
 * test_core_obj_scenes.c. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/file_read.h"
#include "check.h"
#include "formats/obj_load.h"

static rt_status parse(const char *text, rt_obj_mesh *mesh, rt_error *err) {
    return rt_obj_parse(text, strlen(text), "test.obj", NULL, mesh, err);
}

static int mesh_is_empty(const rt_obj_mesh *m) {
    return !m->positions && !m->normals && !m->indices && !m->tri_materials && !m->materials &&
           m->vertex_count == 0 && m->triangle_count == 0 && m->material_count == 0;
}

static void check_indices(const rt_obj_mesh *m, const uint32_t *expected, uint32_t triangles) {
    CHECK_EQ_INT(m->triangle_count, triangles);
    if (m->triangle_count != triangles) return;
    for (uint32_t i = 0; i < 3 * triangles; i++)
        CHECK_MSG(m->indices[i] == expected[i], "index %u: %u != %u", i, m->indices[i],
                  expected[i]);
}

static void test_positions_and_forms(void) {
    static const char *faces[] = {"f 1 2 3\n", "f 1/1 2/2 3/3\n", "f 1//1 2//1 3//1\n",
                                  "f 1/1/1 2/2/1 3/3/1\n"};
    for (int form = 0; form < 4; form++) {
        char text[512];
        snprintf(text, sizeof text,
                 "v 0 0 0\nv 1 0 0\nv 0 1 0 1.0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n%s",
                 faces[form]);
        rt_obj_mesh m;
        rt_error err;
        CHECK(parse(text, &m, &err) == RT_OK);
        const uint32_t expected[3] = {0, 1, 2};
        check_indices(&m, expected, 1);
        CHECK_EQ_INT(m.vertex_count, 3);
        CHECK(m.positions && m.positions[3] == 1.0f && m.positions[7] == 1.0f);
        CHECK((m.normals != NULL) == (form >= 2));
        if (m.normals) CHECK(m.normals[2] == 1.0f && m.normals[8] == 1.0f);
        CHECK(m.tri_materials == NULL && m.material_count == 0);
        rt_obj_free(&m);
        CHECK(mesh_is_empty(&m));
    }
}

static void test_fan_order_and_negative_indices(void) {
    rt_obj_mesh m;
    rt_error err;
    CHECK(parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0.5 1.5 0\nv 0 1 0\nf 1 2 3 4 5\n"
                "f -5 -4 -3\nf -1 -2 -3 -4\n",
                &m, &err) == RT_OK);
    const uint32_t expected[] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 1, 2, 4, 3, 2, 4, 2, 1};
    check_indices(&m, expected, 6);
    rt_obj_free(&m);

    /* Negative indices count back from the vertices defined so far. */
    CHECK(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nf -3 -2 -1\n", &m, &err) == RT_OK);
    const uint32_t expected2[] = {0, 1, 2, 1, 2, 3};
    check_indices(&m, expected2, 2);
    rt_obj_free(&m);
}

static void test_line_ends_comments_and_ignored_statements(void) {
    rt_obj_mesh m;
    rt_error err;
    const char *text = "# header\r\n"
                       "mtllib none.mtl\r\n"
                       "o thing # named\r\n"
                       "g group\r\n"
                       "s 1\r\n"
                       "  v 0 0 0 # first\r\n"
                       "\tv 1 0 0#glued comment\r\n"
                       "v 0 1 0 0.5 0.2 0.3 1\r\n" /* w and vertex colours are ignored */
                       "vp 0.5\r\n"
                       "l 1 2\r\n"
                       "p 1\r\n"
                       "curv 0 1 1 2\r\n"
                       "usemtl\r\n"
                       "\r\n"
                       "#\r\n"
                       "f 1 2 \\\r\n"
                       "  3 # a face split by a line continuation\r\n"
                       "f 3 2 1";
    CHECK(parse(text, &m, &err) == RT_OK);
    const uint32_t expected[] = {0, 1, 2, 2, 1, 0};
    check_indices(&m, expected, 2);
    CHECK_EQ_INT(m.vertex_count, 3);
    CHECK(m.positions[4] == 0.0f && m.positions[7] == 1.0f && m.positions[8] == 0.0f);
    rt_obj_free(&m);

    CHECK(parse("", &m, &err) == RT_OK);
    CHECK(mesh_is_empty(&m));
    CHECK(rt_obj_parse(NULL, 0, "null.obj", NULL, &m, &err) == RT_OK);
    CHECK(mesh_is_empty(&m));
}

static void test_normals(void) {
    rt_obj_mesh m;
    rt_error err;
    /* A quad with one shared normal, then a triangle reusing vertex 1 with
     * another normal: (1,n1) is shared, (1,n2) is a new vertex. */
    CHECK(parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 9 9 9\n"
                "vn 0 0 1\nvn 1 0 0\n"
                "f 1//1 2//1 3//1 4//1\n"
                "f 1//2 2//2 3//1\n",
                &m, &err) == RT_OK);
    CHECK_EQ_INT(m.vertex_count, 6); /* 4 + (1,n2) + (2,n2); unused v 5 dropped */
    const uint32_t expected[] = {0, 1, 2, 0, 2, 3, 4, 5, 2};
    check_indices(&m, expected, 3);
    if (m.vertex_count == 6) {
        CHECK(m.positions[12] == 0.0f && m.positions[15] == 1.0f); /* v1, v2 again */
        CHECK(m.normals[12] == 1.0f && m.normals[14] == 0.0f);
        CHECK(m.normals[2] == 1.0f && m.normals[8] == 1.0f);
    }
    rt_obj_free(&m);

    /* One corner without a normal: no normals, positions kept as they are. */
    CHECK(parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 7 7 7\nvn 0 0 1\n"
                "f 1//1 2//1 3//1\nf 1//1 2 3//1\n",
                &m, &err) == RT_OK);
    CHECK(m.normals == NULL);
    CHECK_EQ_INT(m.vertex_count, 4);
    CHECK(m.positions[9] == 7.0f);
    const uint32_t expected2[] = {0, 1, 2, 0, 1, 2};
    check_indices(&m, expected2, 2);
    rt_obj_free(&m);

    /* Normals only in a later face's corners: dropped too. */
    CHECK(parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1 2 3\nf 1//1 2//1 3//1\n", &m, &err) ==
          RT_OK);
    CHECK(m.normals == NULL && m.vertex_count == 3 && m.triangle_count == 2);
    rt_obj_free(&m);
}

static void test_materials(void) {
    const char *mtl_path = test_write_temp("materials.mtl", "# test materials\r\n"
                                                            "newmtl red\r\n"
                                                            "  Kd 0.8 0.1 0.05 # comment\r\n"
                                                            "  Ks 0.5 0.5 0.5\r\n"
                                                            "  Ns 32\r\n"
                                                            "  Ni 1.5\r\n"
                                                            "  illum 2\r\n"
                                                            "  map_Kd red.png\r\n"
                                                            "newmtl glass pane\n"
                                                            "Kd 0.25\n"
                                                            "Tr 0.75\n"
                                                            "newmtl opaque\n"
                                                            "d 0.5\n");
    CHECK(mtl_path != NULL);
    const char *obj_path = test_write_temp("with_materials.obj", "mtllib materials.mtl\n"
                                                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                                 "f 1 2 3\n"
                                                                 "usemtl glass pane\n"
                                                                 "f 1 2 3\n"
                                                                 "usemtl red\n"
                                                                 "f 1 2 3\n"
                                                                 "usemtl missing\n"
                                                                 "f 1 2 3\n"
                                                                 "usemtl red\n"
                                                                 "f 1 2 3 1\n");
    rt_obj_mesh m;
    rt_error err;
    CHECK(rt_obj_load(obj_path, &m, &err) == RT_OK);
    CHECK_EQ_INT(m.material_count, 3);
    CHECK_EQ_INT(m.triangle_count, 6);
    if (m.material_count == 3 && m.tri_materials) {
        const rt_obj_material *red = &m.materials[0], *glass = &m.materials[1];
        const rt_obj_material *opaque = &m.materials[2];
        CHECK(strcmp(red->name, "red") == 0);
        CHECK(red->kd[0] == 0.8f && red->kd[1] == 0.1f && red->kd[2] == 0.05f);
        CHECK(red->ks[0] == 0.5f && red->ns == 32.0f && red->ni == 1.5f && red->d == 1.0f);
        CHECK(strcmp(glass->name, "glass pane") == 0);
        CHECK(glass->kd[0] == 0.25f && glass->kd[1] == 0.25f && glass->kd[2] == 0.25f);
        CHECK(glass->d == 0.25f && glass->ks[0] == 0.0f && glass->ni == 1.0f);
        CHECK(opaque->d == 0.5f && opaque->kd[1] == 0.8f); /* default Kd */
        const uint32_t expected[] = {UINT32_MAX, 1, 0, UINT32_MAX, 0, 0};
        for (int t = 0; t < 6; t++)
            CHECK_MSG(m.tri_materials[t] == expected[t], "triangle %d: %u", t, m.tri_materials[t]);
    }
    rt_obj_free(&m);

    /* A missing .mtl is not an error: the mesh comes without materials. */
    obj_path = test_write_temp(
        "missing_mtl.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
    CHECK(rt_obj_load(obj_path, &m, &err) == RT_OK);
    CHECK(m.triangle_count == 1 && m.material_count == 0 && !m.materials && !m.tri_materials);
    rt_obj_free(&m);

    /* A malformed .mtl is: the message names the .mtl, its line and column. */
    test_write_temp("bad.mtl", "newmtl a\nKd 0.5 0.5 0.5\nNs 1.2.3\n");
    obj_path = test_write_temp("bad_mtl.obj", "mtllib bad.mtl\nv 0 0 0\n");
    CHECK(rt_obj_load(obj_path, &m, &err) == RT_ERROR_PARSE);
    CHECK(mesh_is_empty(&m));
    CHECK_CONTAINS(err.message, "bad.mtl:3:4: Ns: malformed number \"1.2.3\"");
}

/* Issue 31: an mtllib named again (by another path too) is read once; a
 * material name defined again keeps its first definition, with one notice
 * naming both places; names are whole (two that differ after 127 bytes are
 * two materials); an out-of-range colour is refused with file:line. */
static void test_repeated_materials(void) {
    /* 1000 materials, named 2000 times over: a file of 2000 mtllib lines
     * used to read the file 2000 times and keep 2 million materials. */
    size_t cap = 64 * 1024, n = 0;
    char *text = malloc(cap);
    for (int i = 0; i < 1000 && text; i++)
        n += (size_t)snprintf(text + n, cap - n, "newmtl m%d\nKd 0.%d 0.5 0.5\n", i, i % 10);
    CHECK(text && test_write_temp("big.mtl", text) != NULL);
    free(text);
    cap = 2000 * 24 + 64;
    text = malloc(cap);
    n = 0;
    for (int i = 0; i < 2000 && text; i++)
        n += (size_t)snprintf(text + n, cap - n, "mtllib %s\n", i % 2 ? "big.mtl" : "./big.mtl");
    if (text) snprintf(text + n, cap - n, "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m999\nf 1 2 3\n");
    const char *obj_path = text ? test_write_temp("many_mtllib.obj", text) : NULL;
    free(text);
    rt_obj_mesh m;
    rt_error err;
    CHECK(obj_path && rt_obj_load(obj_path, &m, &err) == RT_OK);
    CHECK_EQ_INT(m.material_count, 1000);
    CHECK(m.tri_materials && m.tri_materials[0] == 999);
    CHECK(m.notice[0] == '\0');
    rt_obj_free(&m);

    /* A name defined twice (in one file and across files): the first counts. */
    char long_a[300], long_b[300];
    memset(long_a, 'x', 200);
    memcpy(long_b, long_a, 200);
    strcpy(long_a + 200, "_red");
    strcpy(long_b + 200, "_blue");
    char mtl[2048];
    snprintf(mtl, sizeof mtl,
             "newmtl red\nKd 1 0 0\nnewmtl %s\nKd 1 0 0\nnewmtl %s\nKd 0 0 1\n"
             "newmtl red\nKd 0 1 0\n",
             long_a, long_b);
    test_write_temp("first.mtl", mtl);
    test_write_temp("second.mtl", "newmtl red\nKd 0 0 1\nnewmtl green\nKd 0 1 0\n");
    char obj[2048];
    snprintf(obj, sizeof obj,
             "mtllib first.mtl second.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n"
             "usemtl %s\nf 1 2 3\nusemtl %s\nf 1 2 3\nusemtl green\nf 1 2 3\n",
             long_a, long_b);
    obj_path = test_write_temp("twice.obj", obj);
    CHECK(rt_obj_load(obj_path, &m, &err) == RT_OK);
    CHECK_EQ_INT(m.material_count, 4);
    if (m.material_count == 4 && m.tri_materials) {
        const uint32_t want[4] = {0, 1, 2, 3};
        for (int t = 0; t < 4; t++) CHECK_EQ_INT(m.tri_materials[t], want[t]);
        CHECK(m.materials[0].kd[0] == 1.0f && m.materials[0].kd[1] == 0.0f);
        CHECK(strcmp(m.materials[1].name, long_a) == 0 && m.materials[1].kd[2] == 0.0f);
        CHECK(strcmp(m.materials[2].name, long_b) == 0 && m.materials[2].kd[2] == 1.0f);
        CHECK(strcmp(m.materials[3].name, "green") == 0);
    }
    CHECK_CONTAINS(m.notice, "first.mtl:7: material 'red' was defined before, at ");
    CHECK_CONTAINS(m.notice, "first.mtl:1, and 1 more material names are defined again; the "
                             "first definition of each is used");
    rt_obj_free(&m);

    /* Colours beyond the limit (or negative) are refused where they are. */
    test_write_temp("huge.mtl", "newmtl a\nKd 0.5 0.5 0.5\nnewmtl b\nKd 1 1e38 1\n");
    obj_path = test_write_temp("huge_mtl.obj", "mtllib huge.mtl\nv 0 0 0\n");
    CHECK(rt_obj_load(obj_path, &m, &err) == RT_ERROR_PARSE);
    CHECK_CONTAINS(err.message, "huge.mtl:4: Kd: 1e+38 is outside 0..1e+06 (the colour limit)");
    test_write_temp("negative.mtl", "newmtl a\nKs -0.5\n");
    obj_path = test_write_temp("negative_mtl.obj", "mtllib negative.mtl\nv 0 0 0\n");
    CHECK(rt_obj_load(obj_path, &m, &err) == RT_ERROR_PARSE);
    CHECK_CONTAINS(err.message, "negative.mtl:2: Ks: -0.5 is outside 0..1e+06");
}

/* Parses text, expects a parse error at line:column with reason in it. */
static void expect_error(const char *text, int line, int column, const char *reason) {
    rt_obj_mesh m;
    rt_error err;
    rt_status st = parse(text, &m, &err);
    CHECK_MSG(st == RT_ERROR_PARSE, "no parse error for: %s", text);
    CHECK(mesh_is_empty(&m));
    CHECK_MSG(err.line == line, "line %d, expected %d: %s", err.line, line, err.message);
    if (column)
        CHECK_MSG(err.column == column, "column %d, expected %d: %s", err.column, column,
                  err.message);
    CHECK_CONTAINS(err.message, reason);
    CHECK_CONTAINS(err.message, "test.obj:");
}

static void test_errors(void) {
    /* issue 31: an index followed by more than a '/' is malformed, not the
     * number it starts with ("vertex index 0 is invalid" for 0x5). */
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0x5\n", 4, 7,
                 "malformed vertex reference \"0x5\"");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2e0 3\n", 4, 5,
                 "malformed vertex reference \"2e0\"");
    expect_error("v 0 0 0\nv 1.2.3 0 0\n", 2, 3, "malformed number \"1.2.3\"");
    expect_error("v 0 0 0\nv 0 abc 0\n", 2, 5, "malformed number \"abc\"");
    expect_error("v 1e 0 0\n", 1, 3, "malformed number \"1e\"");
    expect_error("v 0 0 0x1p3\n", 1, 7, "malformed number \"0x1p3\"");
    expect_error("vn 0 0 1,5\n", 1, 8, "malformed number \"1,5\"");
    expect_error("v 0 0 0\nv 1 2\n", 2, 6, "vertex has 2 coordinates, needs 3");
    expect_error("v\n", 1, 2, "vertex has 0 coordinates, needs 3");
    expect_error("vn 1 0\n", 1, 7, "normal has 2 components, needs 3");
    expect_error("v 0 0 nan\n", 1, 7, "\"nan\" is not a finite number");
    expect_error("v 0 -inf 0\n", 1, 5, "\"-inf\" is not a finite number");
    expect_error("v 1e39 0 0\n", 1, 3, "\"1e39\" is not a finite number");
    expect_error("vn 0 0 1e400\n", 1, 8, "not a finite number");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 3\n", 4, 5, "vertex index 0 is invalid");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 4, 7,
                 "vertex index 4 is out of range (3 vertices so far)");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 2 3\n", 4, 3,
                 "vertex index -4 is out of range (3 vertices so far)");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n", 4, 7,
                 "vertex index 99999999999999999999999 is out of range");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n", 5, 11,
                 "normal index 2 is out of range (1 normals so far)");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n", 4, 5,
                 "texture coordinate index 1 is out of range (0 texture coordinates so far)");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//0 2//1 3//1\n", 5, 6,
                 "normal index 0 is invalid");
    expect_error("v 0 0 0\nv 1 0 0\nf 1 2\n", 3, 1, "face has 2 vertices, needs at least 3");
    expect_error("v 0 0 0\nf\n", 2, 1, "face has 0 vertices, needs at least 3");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n", 4, 3,
                 "malformed vertex reference \"1/\"");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3//\n", 4, 7, "malformed vertex reference");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1 2/1/1/1 3\n", 6, 5,
                 "malformed vertex reference");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", 4, 7, "malformed vertex reference \"x\"");
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3.0\n", 4, 7, "malformed vertex reference");
    /* Line numbers count CRLF lines and joined lines. */
    expect_error("v 0 0 0\r\nv 0 \\\n0 0\r\nv 1 2 x\r\n", 4, 7, "malformed number \"x\"");
    /* Errors after many good statements: nothing is half-returned. */
    expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\nf 1 2 5\n", 6, 7, "out of range");
}

static void test_file_errors(void) {
    rt_obj_mesh m;
    rt_error err;
    CHECK(rt_obj_load("/nonexistent/folder/none.obj", &m, &err) == RT_ERROR_IO);
    CHECK(mesh_is_empty(&m));
    CHECK_CONTAINS(err.message, "/nonexistent/folder/none.obj: cannot open the OBJ file: ");
    CHECK_CONTAINS(err.message, "No such file or directory");

    CHECK(rt_obj_load("/tmp", &m, &err) == RT_ERROR_IO);
    CHECK(mesh_is_empty(&m));
    CHECK_CONTAINS(err.message, "/tmp: cannot read the OBJ file: it is a directory");

    /* The reader's size limit is a parameter: exactly at it is read, one
     * byte over is refused before reading (RT_ERROR_UNSUPPORTED). */
    const char *hundred = test_write_temp(
        "hundred.txt", "0123456789012345678901234567890123456789012345678901234567890123456789"
                       "01234567890123456789012345678\n");
    char *text = NULL;
    size_t len = 0;
    CHECK(rt_read_file(hundred, "test file", 100, &text, &len, &err) == RT_OK);
    CHECK(text && len == 100 && text[99] == '\n' && text[100] == '\0');
    free(text);
    CHECK(rt_read_file(hundred, "test file", 99, &text, &len, &err) == RT_ERROR_UNSUPPORTED);
    CHECK(text == NULL);
    CHECK_CONTAINS(err.message,
                   "hundred.txt: the test file is 100 bytes, more than the limit of 99");

    const char *path = test_write_temp("bad_face.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
    CHECK(rt_obj_load(path, &m, &err) == RT_ERROR_PARSE);
    CHECK_CONTAINS(err.message, "bad_face.obj:3:1: face has 2 vertices");
    CHECK_EQ_INT(err.line, 3);
}

/* Random byte mutations of a small file: every result is either a parse
 * error with an empty mesh, or a mesh whose indices are all in range. */
static void test_mutations_never_crash(void) {
    const char *base = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                       "usemtl a\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf -1 -2 -3\nf 1//1 3//1 4//1\n";
    const char alphabet[] = "0123456789 /-+.eE#\n\r\\vfnt\tx";
    size_t len = strlen(base);
    char text[256];
    uint32_t state = 12345;
    int bad = 0;
    for (int n = 0; n < 20000; n++) {
        memcpy(text, base, len + 1);
        for (int k = 0; k < 1 + n % 4; k++) {
            state = state * 1664525u + 1013904223u;
            size_t at = (state >> 8) % len;
            state = state * 1664525u + 1013904223u;
            text[at] = alphabet[(state >> 8) % (sizeof alphabet - 1)];
        }
        rt_obj_mesh m;
        rt_error err;
        size_t cut = n % 7 == 0 ? (size_t)(state >> 4) % len : len; /* sometimes truncated */
        /* An exact-size copy, so that the sanitizer sees any read past the end. */
        char *exact = malloc(cut ? cut : 1);
        if (!exact) continue;
        memcpy(exact, text, cut);
        rt_status st = rt_obj_parse(exact, cut, "fuzz.obj", NULL, &m, &err);
        free(exact);
        if (st == RT_OK) {
            for (uint32_t i = 0; i < 3 * m.triangle_count; i++)
                if (m.indices[i] >= m.vertex_count) bad++;
        } else if (st != RT_ERROR_PARSE || !mesh_is_empty(&m) || err.line < 1) {
            bad++;
        }
        rt_obj_free(&m);
    }
    CHECK_EQ_INT(bad, 0);
}

int main(void) {
    test_positions_and_forms();
    test_fan_order_and_negative_indices();
    test_line_ends_comments_and_ignored_statements();
    test_normals();
    test_materials();
    test_repeated_materials();
    test_errors();
    test_file_errors();
    test_mutations_never_crash();
    return TEST_END();
}
