/* SPDX-License-Identifier: Apache-2.0 */
/* test_gltf_files.c - small glTF files written here, loaded and evaluated:
 * node hierarchies (TRS and matrix), strips and fans, non-indexed
 * primitives, normalized and sparse accessors, every sampler type (STEP,
 * LINEAR, shortest-path slerp, CUBICSPLINE with tangents scaled by the key
 * interval) clamped at both ends, normalized rotation keys, morph targets
 * (node weights over mesh weights, animated weights), skins with two joint
 * sets, clips by name and index, external buffers; and malformed files,
 * each refused with the file's name and the JSON pointer of the fault, never
 * a crash or a hang (a FIFO as a buffer, a directory, a URI leaving the
 * folder, a truncated .glb, out-of-bounds accessors, vertex indices out of
 * range, a cyclic node graph, NaN and non-increasing key times). Skips
 * without the glTF module. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "scene/scene.h"

static char dir[256];

/* ---- writing glTF files ----------------------------------------------------- */

typedef struct gb {
    unsigned char bin[1 << 16];
    size_t n;
    char views[1 << 14], accs[1 << 14];
    int nv, na;
} gb;

static int view(gb *g, const void *data, size_t bytes) {
    while (g->n % 4) g->bin[g->n++] = 0;
    memcpy(g->bin + g->n, data, bytes);
    size_t l = strlen(g->views);
    snprintf(g->views + l, sizeof g->views - l,
             "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}", g->nv ? "," : "", g->n,
             bytes);
    g->n += bytes;
    return g->nv++;
}

static int acc_json(gb *g, const char *json) {
    size_t l = strlen(g->accs);
    snprintf(g->accs + l, sizeof g->accs - l, "%s%s", g->na ? "," : "", json);
    return g->na++;
}

/* An accessor over a new view of data. */
static int acc(gb *g, const void *data, size_t bytes, int ctype, const char *type, int count,
               int normalized) {
    int v = view(g, data, bytes);
    char j[256];
    snprintf(j, sizeof j, "{\"bufferView\":%d,\"componentType\":%d,\"count\":%d,\"type\":\"%s\"%s}",
             v, ctype, count, type, normalized ? ",\"normalized\":true" : "");
    return acc_json(g, j);
}

static int accf(gb *g, const float *f, int count, const char *type) {
    int n = !strcmp(type, "SCALAR") ? 1
            : !strcmp(type, "VEC3") ? 3
            : !strcmp(type, "VEC4") ? 4
                                    : 16;
    return acc(g, f, sizeof(float) * (size_t)(n * count), 5126, type, count, 0);
}

static void b64(const unsigned char *in, size_t n, char *out) {
    static const char t[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t o = 0;
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)in[i] << 16 | (i + 1 < n ? (unsigned)in[i + 1] << 8 : 0) |
                     (i + 2 < n ? in[i + 2] : 0);
        out[o++] = t[v >> 18 & 63];
        out[o++] = t[v >> 12 & 63];
        out[o++] = i + 1 < n ? t[v >> 6 & 63] : '=';
        out[o++] = i + 2 < n ? t[v & 63] : '=';
    }
    out[o] = 0;
}

/* Writes dir/name: the builder's buffer (embedded, or uri when not NULL)
 * and rest (the JSON members after the accessors). Returns the path. */
static const char *write_gltf(const char *name, gb *g, const char *uri, const char *rest) {
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) return path;
    fprintf(f, "{\"asset\":{\"version\":\"2.0\"},\"bufferViews\":[%s],\"accessors\":[%s],",
            g->views, g->accs);
    if (uri) {
        fprintf(f, "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"%s\"}]", g->n, uri);
    } else {
        char *e = malloc(g->n * 2 + 8);
        b64(g->bin, g->n, e);
        fprintf(f,
                "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/"
                "octet-stream;base64,%s\"}]",
                g->n, e);
        free(e);
    }
    fprintf(f, ",%s}", rest);
    fclose(f);
    return path;
}

static void gb_init(gb *g) {
    memset(g, 0, sizeof *g);
}

/* A unit triangle's accessors: positions (0,0,0) (1,0,0) (0,1,0). */
static int tri_positions(gb *g) {
    static const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    return accf(g, p, 3, "VEC3");
}

static rt_scene *load_ok(const char *path) {
    rt_scene *s = NULL;
    rt_error err;
    if (rt_scene_load(path, &s, &err) != RT_OK) {
        CHECK_MSG(0, "%s", err.message);
        return NULL;
    }
    return s;
}

/* Object o's world-space positions (its mesh under its transform), in a
 * buffer of its own (4 at a time). */
static const float *wpos(const rt_scene *s, uint32_t o) {
    static float buf[4][3 * 64];
    static int next;
    float *out = buf[next++ % 4];
    memset(out, 0, sizeof buf[0]);
    if (o >= s->object_count) return out;
    const rt_mesh_data *m = &s->meshes[rt_object_shown_mesh(&s->objects[o])];
    const float *t = s->objects[o].transform;
    for (uint32_t v = 0; v < m->vertex_count && v < 64; v++) {
        const float *q = m->positions + 3 * (size_t)v;
        for (int r = 0; r < 3; r++)
            out[3 * v + r] = (float)((double)t[4 * r] * q[0] + (double)t[4 * r + 1] * q[1] +
                                     (double)t[4 * r + 2] * q[2] + (double)t[4 * r + 3]);
    }
    return out;
}

static int near3(const float *p, double x, double y, double z, double tol) {
    return fabs(p[0] - x) <= tol && fabs(p[1] - y) <= tol && fabs(p[2] - z) <= tol;
}

#define CHECK_V(p, x, y, z)                                                                        \
    CHECK_MSG(near3((p), (x), (y), (z), 1e-5), "(%g, %g, %g), expected (%g, %g, %g)",              \
              (double)(p)[0], (double)(p)[1], (double)(p)[2], (double)(x), (double)(y),            \
              (double)(z))

/* ---- the tests ------------------------------------------------------------------ */

static void test_hierarchy(void) {
    gb g;
    gb_init(&g);
    int pos = tri_positions(&g);
    char rest[1024];
    /* root: translate (10,0,0); child: rotate 90 deg about z, scale 2;
     * grandchild (matrix): translate (0,0,5). */
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],"
             "\"nodes\":[{\"translation\":[10,0,0],\"children\":[1]},"
             "{\"rotation\":[0,0,0.70710678,0.70710678],\"scale\":[2,2,2],\"children\":[2]},"
             "{\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1],\"mesh\":0}],"
             "\"scenes\":[{\"nodes\":[0]}],\"scene\":0",
             pos);
    rt_scene *s = load_ok(write_gltf("hier.gltf", &g, NULL, rest));
    if (!s) return;
    CHECK_EQ_INT(s->mesh_count, 1);
    CHECK_EQ_INT(s->meshes[0].triangle_count, 1);
    const float *p = wpos(s, 0);
    /* v = R * 2 * (v + (0,0,5)) + (10,0,0): (1,0,0) -> (0,2,10) + (10,0,0) */
    CHECK_V(p + 0, 10, 0, 10);
    CHECK_V(p + 3, 10, 2, 10);
    CHECK_V(p + 6, 8, 0, 10);
    CHECK(!rt_scene_is_animated(s));
    CHECK_EQ_INT(rt_scene_clip_count(s), 0);
    CHECK(s->has_camera);
    CHECK_EQ_INT(s->light_count, 1); /* the default view's */
    rt_scene_destroy(s);
}

static void test_strips_fans(void) {
    gb g;
    gb_init(&g);
    static const float strip[12] = {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0};
    static const float fan[15] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0};
    static const uint8_t fan_idx[5] = {0, 1, 2, 3, 4};
    int ps = accf(&g, strip, 4, "VEC3"), pf = accf(&g, fan, 5, "VEC3");
    int fi = acc(&g, fan_idx, 5, 5121, "SCALAR", 5, 0);
    char rest[1024];
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d},\"mode\":5},"
             "{\"attributes\":{\"POSITION\":%d},\"indices\":%d,\"mode\":6},"
             "{\"attributes\":{\"POSITION\":%d},\"mode\":1}]}],"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]",
             ps, pf, fi, ps);
    rt_scene *s = load_ok(write_gltf("strips.gltf", &g, NULL, rest));
    if (!s) return;
    CHECK_EQ_INT(s->mesh_count, 2); /* the line primitive is left out */
    CHECK_EQ_INT(s->meshes[0].triangle_count, 2);
    CHECK_EQ_INT(s->meshes[1].triangle_count, 3);
    static const uint32_t want_strip[6] = {0, 1, 2, 2, 1, 3},
                          want_fan[9] = {1, 2, 0, 2, 3, 0, 3, 4, 0};
    CHECK(memcmp(s->meshes[0].indices, want_strip, sizeof want_strip) == 0);
    CHECK(memcmp(s->meshes[1].indices, want_fan, sizeof want_fan) == 0);
    CHECK_CONTAINS(rt_scene_notices(s), "1 point or line primitives left out");
    rt_scene_destroy(s);
}

static void test_normalized_sparse(void) {
    gb g;
    gb_init(&g);
    /* i8 normalized positions: -127 -> -1, 127 -> 1, -128 -> -1; u16: 65535 -> 1 */
    static const int8_t p8[12] = {-127, 0, 0, 0, 0, 127, 0, 0, 0, 0, -128, 0}; /* stride 4 */
    static const uint16_t p16[9] = {0, 0, 0, 65535, 0, 0, 0, 32768, 0};
    int v8 = view(&g, p8, sizeof p8);
    char j[512];
    /* byteStride 4 on the view: rewrite the views entry by hand */
    snprintf(j, sizeof j,
             "{\"bufferView\":%d,\"componentType\":5120,\"count\":3,\"type\":\"VEC3\","
             "\"normalized\":true}",
             v8);
    int a8 = acc_json(&g, j);
    int a16 = acc(&g, p16, sizeof p16, 5123, "VEC3", 3, 1);
    /* sparse over a base of 3 vertices: vertex 2 replaced; and a sparse accessor with no view
     * (zeros) */
    static const float base[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint16_t sidx[1] = {2};
    static const float sval[3] = {5, 6, 7};
    int vb = view(&g, base, sizeof base), vi = view(&g, sidx, sizeof sidx),
        vv = view(&g, sval, sizeof sval);
    snprintf(
        j, sizeof j,
        "{\"bufferView\":%d,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"sparse\":{"
        "\"count\":1,"
        "\"indices\":{\"bufferView\":%d,\"componentType\":5123},\"values\":{\"bufferView\":%d}}}",
        vb, vi, vv);
    int as = acc_json(&g, j);
    snprintf(
        j, sizeof j,
        "{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"sparse\":{\"count\":1,"
        "\"indices\":{\"bufferView\":%d,\"componentType\":5123},\"values\":{\"bufferView\":%d}}}",
        vi, vv);
    int az = acc_json(&g, j);
    /* the strided view */
    char *views = g.views;
    char *first = strstr(views, "}");
    if (first) {
        char fixed[1 << 14];
        snprintf(fixed, sizeof fixed, "%.*s,\"byteStride\":4%s", (int)(first - views), views,
                 first);
        snprintf(g.views, sizeof g.views, "%s", fixed);
    }
    char rest[1024];
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}},{\"attributes\":{"
             "\"POSITION\":%d}},"
             "{\"attributes\":{\"POSITION\":%d}},{\"attributes\":{\"POSITION\":%d}}]}],"
             "\"nodes\":[{\"mesh\":0}]",
             a8, a16, as, az);
    rt_scene *s = load_ok(write_gltf("norm.gltf", &g, NULL, rest));
    if (!s) return;
    CHECK_EQ_INT(s->mesh_count, 4);
    if (s->mesh_count == 4) {
        const float *p = wpos(s, 0);
        CHECK_V(p + 0, -1, 0, 0);
        CHECK_V(p + 3, 0, 1, 0);
        CHECK_V(p + 6, 0, 0, -1);
        p = wpos(s, 1);
        CHECK_V(p + 3, 1, 0, 0);
        CHECK_V(p + 6, 0, 32768.0 / 65535.0, 0);
        p = wpos(s, 2);
        CHECK_V(p + 3, 1, 0, 0);
        CHECK_V(p + 6, 5, 6, 7);
        p = wpos(s, 3);
        CHECK_V(p + 0, 0, 0, 0);
        CHECK_V(p + 6, 5, 6, 7);
    }
    rt_scene_destroy(s);
}

/* One triangle on node 0, animated by samplers the caller writes. */
static rt_scene *animated(const char *name, gb *g, int pos, const char *samplers,
                          const char *channels, const char *extra_anim) {
    char rest[4096];
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],"
             "\"animations\":[{\"name\":\"main\",\"samplers\":[%s],\"channels\":[%s]}%s]",
             pos, samplers, channels, extra_anim ? extra_anim : "");
    return load_ok(write_gltf(name, g, NULL, rest));
}

static const float *at_time(rt_scene *s, double t) {
    CHECK(rt_scene_set_time(s, t) == RT_OK);
    return wpos(s, 0);
}

static void test_samplers(void) {
    static const float times[3] = {1, 2, 4};
    static const float tr[9] = {0, 0, 0, 10, 0, 0, 10, 20, 0};
    /* cubic: in-tangent, value, out-tangent per key */
    static const float cub[27] = {0, 0, 0, 0,  0,  0, 1, 0, 0, /* key 0 */
                                  0, 0, 0, 10, 0,  0, 0, 0, 0, /* key 1 */
                                  0, 0, 0, 10, 20, 0, 0, 0, 0};
    const char *interp[3] = {"STEP", "LINEAR", "CUBICSPLINE"};
    for (int k = 0; k < 3; k++) {
        gb g;
        gb_init(&g);
        int pos = tri_positions(&g);
        int in = accf(&g, times, 3, "SCALAR");
        int out = k == 2 ? accf(&g, cub, 9, "VEC3") : accf(&g, tr, 3, "VEC3");
        char smp[256], ch[256];
        snprintf(smp, sizeof smp, "{\"input\":%d,\"output\":%d,\"interpolation\":\"%s\"}", in, out,
                 interp[k]);
        snprintf(ch, sizeof ch, "{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}}");
        char name[64];
        snprintf(name, sizeof name, "sampler_%s.gltf", interp[k]);
        rt_scene *s = animated(name, &g, pos, smp, ch, NULL);
        if (!s) continue;
        CHECK(rt_scene_is_animated(s));
        CHECK_EQ_INT(rt_scene_clip_count(s), 1);
        const char *cn;
        double dur;
        CHECK(rt_scene_clip_info(s, 0, &cn, &dur) == RT_OK);
        CHECK(!strcmp(cn, "main") && dur == 4.0);
        CHECK_V(at_time(s, -5), 0, 0, 0); /* clamped before the first key */
        CHECK_V(at_time(s, 1), 0, 0, 0);
        CHECK_V(at_time(s, 100), 10, 20, 0); /* and after the last */
        const float *p = at_time(s, 1.5);
        if (k == 0) CHECK_V(p, 0, 0, 0);
        if (k == 1) CHECK_V(p, 5, 0, 0);
        if (k == 2) {
            /* h00 0.5, h10 0.125 (x dt 1 x out-tangent 1), h01 0.5: 0 + 0.125 + 5 */
            CHECK_V(p, 5.125, 0, 0);
        }
        p = at_time(s, 3);
        if (k == 0) CHECK_V(p, 10, 0, 0);
        if (k == 1) CHECK_V(p, 10, 10, 0);
        if (k == 2) CHECK_V(p, 10, 10, 0);
        /* bit for bit the same whatever came before */
        float a[9], b[9];
        memcpy(a, at_time(s, 2.7), sizeof a);
        at_time(s, 0.3);
        memcpy(b, at_time(s, 2.7), sizeof b);
        CHECK(memcmp(a, b, sizeof a) == 0);
        rt_scene_destroy(s);
    }
    /* cubic tangents scaled by the interval: keys 0 and 2 s, out-tangent 1 on x */
    {
        gb g;
        gb_init(&g);
        int pos = tri_positions(&g);
        static const float t2[2] = {0, 2};
        static const float c2[18] = {0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
        int in = accf(&g, t2, 2, "SCALAR"), out = accf(&g, c2, 6, "VEC3");
        char smp[256];
        snprintf(smp, sizeof smp, "{\"input\":%d,\"output\":%d,\"interpolation\":\"CUBICSPLINE\"}",
                 in, out);
        rt_scene *s =
            animated("cubic_dt.gltf", &g, pos, smp,
                     "{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}}", NULL);
        if (s) {
            /* u = 0.5: h10 = 0.125, times dt 2, times 1 */
            CHECK_V(at_time(s, 1.0), 0.25, 0, 0);
            rt_scene_destroy(s);
        }
    }
}

/* Rigid animation moves the object, not the mesh; a node scaled to 0 (a
 * singular matrix) has its world vertices under the identity meanwhile. */
static void test_rigid(void) {
    gb g;
    gb_init(&g);
    int pos = tri_positions(&g);
    static const float times[3] = {0, 1, 2}, sc[9] = {1, 1, 1, 0, 0, 0, 1, 1, 1};
    int in = accf(&g, times, 3, "SCALAR"), out = accf(&g, sc, 3, "VEC3");
    char smp[128];
    snprintf(smp, sizeof smp, "{\"input\":%d,\"output\":%d}", in, out);
    rt_scene *s = animated("rigid.gltf", &g, pos, smp,
                           "{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"scale\"}}", NULL);
    if (!s) return;
    uint32_t v0 = s->meshes[0].version;
    CHECK_V(at_time(s, 0.5) + 3, 0.5, 0, 0);
    CHECK_EQ_INT(s->meshes[0].version, v0); /* the mesh did not change */
    CHECK(s->objects[0].transform[0] == 0.5f);
    CHECK_V(at_time(s, 1.0) + 3, 0, 0, 0); /* singular: world vertices */
    CHECK(rt_transform_is_identity(s->objects[0].transform));
    CHECK(s->meshes[0].version != v0);
    CHECK_V(at_time(s, 1.5) + 3, 0.5, 0, 0); /* and back */
    CHECK(s->meshes[0].positions[3] == 1.0f);
    rt_scene_destroy(s);
}

static void test_rotation(void) {
    /* keys: identity, then -(90 deg about z) written negated: the shortest
     * path goes through 45 deg, not 135 (slerp's sign flip). Normalized
     * short keys too. */
    for (int normalized = 0; normalized < 2; normalized++) {
        gb g;
        gb_init(&g);
        int pos = tri_positions(&g);
        static const float times[2] = {0, 1};
        static const float q[8] = {0, 0, 0, 1, 0, 0, -0.70710678f, -0.70710678f};
        static const int16_t q16[8] = {0, 0, 0, 32767, 0, 0, -23170, -23170};
        int in = accf(&g, times, 2, "SCALAR");
        int out =
            normalized ? acc(&g, q16, sizeof q16, 5122, "VEC4", 2, 1) : accf(&g, q, 2, "VEC4");
        char smp[256];
        snprintf(smp, sizeof smp, "{\"input\":%d,\"output\":%d}", in, out);
        rt_scene *s =
            animated(normalized ? "rot16.gltf" : "rot.gltf", &g, pos, smp,
                     "{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"rotation\"}}", NULL);
        if (!s) continue;
        const float *p = at_time(s, 0.5);
        double tol = normalized ? 1e-4 : 1e-5;
        CHECK_MSG(near3(p + 3, 0.70710678, 0.70710678, 0, tol), "(%g, %g, %g)", (double)p[3],
                  (double)p[4], (double)p[5]);
        p = at_time(s, 1.0);
        CHECK_MSG(near3(p + 3, 0, 1, 0, tol), "(%g, %g, %g)", (double)p[3], (double)p[4],
                  (double)p[5]);
        rt_scene_destroy(s);
    }
}

static void test_morph(void) {
    gb g;
    gb_init(&g);
    int pos = tri_positions(&g);
    static const float d0[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1}, d1[9] = {1, 0, 0, 0, 0, 0, 0, 0, 0};
    int t0 = accf(&g, d0, 3, "VEC3"), t1 = accf(&g, d1, 3, "VEC3");
    static const float times[2] = {0, 1}, w[4] = {0, 0, 1, 1};
    int in = accf(&g, times, 2, "SCALAR"), out = accf(&g, w, 4, "SCALAR");
    char rest[2048];
    /* node 0: mesh weights (0.5, 0) only; node 1: its own weights (1, 2)
     * override; node 2: animated (0,0) -> (1,1) */
    snprintf(
        rest, sizeof rest,
        "\"meshes\":[{\"weights\":[0.5,0],\"primitives\":[{\"attributes\":{\"POSITION\":%d},"
        "\"targets\":[{\"POSITION\":%d},{\"POSITION\":%d}]}]}],"
        "\"nodes\":[{\"mesh\":0},{\"mesh\":0,\"weights\":[1,2]},{\"mesh\":0,\"weights\":[3,3]}],"
        "\"scenes\":[{\"nodes\":[0,1,2]}],"
        "\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d}],"
        "\"channels\":[{\"sampler\":0,\"target\":{\"node\":2,\"path\":\"weights\"}}]}]",
        pos, t0, t1, in, out);
    rt_scene *s = load_ok(write_gltf("morph.gltf", &g, NULL, rest));
    if (!s) return;
    CHECK_EQ_INT(s->mesh_count, 3);
    if (s->mesh_count == 3) {
        CHECK(rt_scene_set_time(s, 0.5) == RT_OK);
        CHECK_V(wpos(s, 0), 0, 0, 0.5);
        CHECK_V(wpos(s, 1), 2, 0, 1);
        CHECK_V(wpos(s, 2), 0.5, 0, 0.5);
        CHECK_V(wpos(s, 2) + 3, 1, 0, 0.5);
    }
    /* An object removed by the caller: the animation goes on with the others. */
    CHECK(rt_object_remove(s, 0) == RT_OK);
    CHECK(rt_scene_set_time(s, 0.25) == RT_OK);
    CHECK_EQ_INT(s->object_count, 2);
    CHECK_V(wpos(s, 1), 0.25, 0, 0.25);
    rt_scene_destroy(s);
}

static void test_skin(void) {
    gb g;
    gb_init(&g);
    static const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    int pos = accf(&g, p, 3, "VEC3");
    /* set 0: joint 0 weight 0.25; set 1: joint 1 weight 0.75 */
    static const uint8_t j0[12] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    static const uint16_t j1[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    static const float w0[12] = {0.25f, 0, 0, 0, 0.25f, 0, 0, 0, 0.25f, 0, 0, 0};
    static const float w1[12] = {0.75f, 0, 0, 0, 0.75f, 0, 0, 0, 0.75f, 0, 0, 0};
    int aj0 = acc(&g, j0, sizeof j0, 5121, "VEC4", 3, 0),
        aj1 = acc(&g, j1, sizeof j1, 5123, "VEC4", 3, 0);
    int aw0 = accf(&g, w0, 3, "VEC4"), aw1 = accf(&g, w1, 3, "VEC4");
    /* inverse bind of joint 1: translate (0,-2,0) undoes its rest place */
    static const float ib[32] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,
                                 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -2, 0, 1};
    int aib = accf(&g, ib, 2, "MAT4");
    static const float times[2] = {0, 1}, tr[6] = {0, 2, 0, 0, 4, 0};
    int in = accf(&g, times, 2, "SCALAR"), out = accf(&g, tr, 2, "VEC3");
    char rest[2048];
    /* node 0 (skinned mesh, translated far: ignored); nodes 1 and 2 joints */
    snprintf(
        rest, sizeof rest,
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d,\"JOINTS_0\":%d,"
        "\"WEIGHTS_0\":%d,\"JOINTS_1\":%d,\"WEIGHTS_1\":%d}}]}],"
        "\"skins\":[{\"joints\":[1,2],\"inverseBindMatrices\":%d}],"
        "\"nodes\":[{\"mesh\":0,\"skin\":0,\"translation\":[100,0,0]},{\"translation\":[1,0,0]},"
        "{\"translation\":[0,2,0]}],\"scenes\":[{\"nodes\":[0,1,2]}],"
        "\"animations\":[{\"name\":\"lift\",\"samplers\":[{\"input\":%d,\"output\":%d}],"
        "\"channels\":[{\"sampler\":0,\"target\":{\"node\":2,\"path\":\"translation\"}}]},"
        "{\"name\":\"still\",\"samplers\":[],\"channels\":[]}]",
        pos, aj0, aw0, aj1, aw1, aib, in, out);
    rt_scene *s = load_ok(write_gltf("skin.gltf", &g, NULL, rest));
    if (!s) return;
    /* t = 1: joint 1 at (0,4,0), its skin matrix translates by (0,2,0);
     * joint 0 translates by (1,0,0). v' = v + 0.25 (1,0,0) + 0.75 (0,2,0) */
    CHECK(rt_scene_set_time(s, 1.0) == RT_OK);
    CHECK_V(wpos(s, 0), 0.25, 1.5, 0);
    CHECK_V(wpos(s, 0) + 3, 1.25, 1.5, 0);
    CHECK(rt_scene_select_clip(s, "still") == RT_OK); /* t = 1 again, clip 1: rest pose */
    CHECK_V(wpos(s, 0), 0.25, 0, 0);
    CHECK(rt_scene_select_clip(s, "0") == RT_OK);
    CHECK_V(wpos(s, 0), 0.25, 1.5, 0);
    CHECK(rt_scene_select_clip(s, "jump") != RT_OK);
    CHECK_CONTAINS(rt_scene_error(s), "lift, still");
    rt_scene_destroy(s);
}

/* A camera (animated with its node), point lights (and a spot light left
 * out), the metallic-roughness mapping, the textures notice. */
static void test_camera_lights_materials(void) {
    gb g;
    gb_init(&g);
    int pos = tri_positions(&g);
    static const float times[2] = {0, 1}, tr[6] = {0, 0, 10, 0, 0, 20};
    int in = accf(&g, times, 2, "SCALAR"), out = accf(&g, tr, 2, "VEC3");
    char rest[3000];
    snprintf(
        rest, sizeof rest,
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d},\"material\":0}]}],"
        "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.25,2,1],"
        "\"metallicFactor\":0.75,\"roughnessFactor\":0.5,\"baseColorTexture\":{\"index\":0}}}],"
        "\"textures\":[{}],"
        "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.5,\"aspectRatio\":2,"
        "\"znear\":0.1}}],"
        "\"extensionsUsed\":[\"KHR_lights_punctual\"],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\",\"color\":[1,0.5,"
        "0.25]},"
        "{\"type\":\"spot\",\"spot\":{}}]}},"
        "\"nodes\":[{\"mesh\":0},{\"camera\":0,\"translation\":[0,0,10]},"
        "{\"translation\":[3,4,5],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
        "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}}],"
        "\"scenes\":[{\"nodes\":[0,1,2,3]}],"
        "\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d}],"
        "\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"translation\"}}]}]",
        pos, in, out);
    rt_scene *s = load_ok(write_gltf("camlight.gltf", &g, NULL, rest));
    if (!s) return;
    rt_camera c;
    rt_camera_get(s, &c);
    CHECK_V(c.position, 0, 0, 10);
    CHECK_V(c.look_at, 0, 0, 9);
    CHECK_V(c.up, 0, 1, 0);
    CHECK_EQ_INT(c.width, 1024);
    CHECK_EQ_INT(c.height, 512);
    double h = 2.0 * atan(tan(0.25) * 2.0) * 180.0 / 3.14159265358979323846;
    CHECK_MSG(fabs(c.hfov_degrees - h) < 1e-4, "hfov %g, expected %g", (double)c.hfov_degrees, h);
    CHECK(rt_scene_set_time(s, 0.5) == RT_OK);
    rt_camera_get(s, &c);
    CHECK_V(c.position, 0, 0, 15);   /* the camera follows its node */
    CHECK_EQ_INT(s->light_count, 1); /* the spot light is left out, no default light */
    if (s->light_count) {
        CHECK_V(s->lights[0].position, 3, 4, 5);
        CHECK_V(s->lights[0].color, 1, 0.5, 0.25);
    }
    CHECK_CONTAINS(rt_scene_notices(s), "textures are ignored");
    CHECK_CONTAINS(rt_scene_notices(s), "spot and directional lights");
    CHECK_EQ_INT(s->material_count, 1);
    if (s->material_count) {
        const rt_material *m = &s->materials[0];
        CHECK_V(m->color, 0.5, 0.25, 1); /* clamped to 1 */
        CHECK(fabs(m->diffuse - 0.25) < 1e-6);
        CHECK(fabs(m->specular - 0.5 * (0.04 + 0.96 * 0.75)) < 1e-6);
        CHECK_EQ_INT(m->shininess, 30); /* 2 / 0.5^4 - 2 */
        CHECK(fabs(m->reflectivity - 0.75 * 0.25) < 1e-6);
    }
    rt_scene_destroy(s);
}

/* An emissive material: its emission, and, with no KHR_lights_punctual
 * light, the point light the loader makes of it instead of the default
 * light (docs/SCENE_FORMAT.md, "Emission"). */
static void test_emissive_material(void) {
    gb g;
    gb_init(&g);
    int pos = tri_positions(&g);
    char rest[600];
    snprintf(
        rest, sizeof rest,
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d},\"material\":0}]}],"
        "\"materials\":[{\"emissiveFactor\":[1,0.5,2]}],"
        "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.5,\"znear\":0.1}}],"
        "\"nodes\":[{\"mesh\":0},{\"camera\":0,\"translation\":[0,0,10]}],"
        "\"scenes\":[{\"nodes\":[0,1]}]",
        pos);
    rt_scene *s = load_ok(write_gltf("emissive.gltf", &g, NULL, rest));
    if (!s) return;
    CHECK_EQ_INT(s->material_count, 1);
    if (s->material_count) CHECK_V(s->materials[0].emission, 1, 0.5, 1); /* clamped to 1 */
    CHECK_EQ_INT(s->light_count, 1); /* the emitter's, not the default light */
    if (s->light_count) CHECK_V(s->lights[0].color, 1, 0.5, 1);
    rt_scene_destroy(s);
}

static void test_external_and_glb(void) {
    gb g;
    gb_init(&g);
    int pos = tri_positions(&g);
    char path[512];
    snprintf(path, sizeof path, "%s/tri.bin", dir);
    FILE *f = fopen(path, "wb");
    fwrite(g.bin, 1, g.n, f);
    fclose(f);
    char rest[256];
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],\"nodes\":[{"
             "\"mesh\":0}]",
             pos);
    rt_scene *s = load_ok(write_gltf("ext.gltf", &g, "tri.bin", rest));
    if (s) {
        CHECK_EQ_INT(s->meshes[0].vertex_count, 3);
        rt_scene_destroy(s);
    }
}

/* ---- malformed files ------------------------------------------------------------- */

static void expect_fail(const char *path, const char *needle) {
    rt_scene *s = NULL;
    rt_error err;
    rt_status st = rt_scene_load(path, &s, &err);
    CHECK_MSG(st != RT_OK, "%s loaded", path);
    CHECK(s == NULL);
    if (st == RT_OK) {
        rt_scene_destroy(s);
        return;
    }
    const char *slash = strrchr(path, '/');
    printf("refused: %s\n", err.message);
    CHECK_CONTAINS(err.message, slash ? slash + 1 : path);
    if (needle) CHECK_CONTAINS(err.message, needle);
}

static void write_glb(const char *name, const char *json, const unsigned char *bin, size_t nbin,
                      size_t cut) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    size_t nj = (strlen(json) + 3) / 4 * 4, nb = (nbin + 3) / 4 * 4;
    size_t total = 12 + 8 + nj + (nbin ? 8 + nb : 0);
    unsigned char *b = calloc(1, total);
    uint32_t h[3] = {0x46546C67u, 2, (uint32_t)total};
    memcpy(b, h, 12);
    uint32_t c[2] = {(uint32_t)nj, 0x4E4F534Au};
    memcpy(b + 12, c, 8);
    memset(b + 20, ' ', nj);
    memcpy(b + 20, json, strlen(json));
    if (nbin) {
        uint32_t c2[2] = {(uint32_t)nb, 0x004E4942u};
        memcpy(b + 20 + nj, c2, 8);
        memcpy(b + 28 + nj, bin, nbin);
    }
    FILE *f = fopen(path, "wb");
    fwrite(b, 1, cut ? cut : total, f);
    fclose(f);
    free(b);
}

static void test_malformed(void) {
    char path[512], rest[2048];
    gb g;
    /* a .glb, whole then truncated inside its BIN chunk */
    gb_init(&g);
    static const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const char *json =
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":36}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"accessors\":[{\"bufferView\":0,"
        "\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],\"meshes\":[{\"primitives\":"
        "[{\"attributes\":{\"POSITION\":0}}]}],\"nodes\":[{\"mesh\":0}]}";
    write_glb("ok.glb", json, (const unsigned char *)p, sizeof p, 0);
    snprintf(path, sizeof path, "%s/ok.glb", dir);
    rt_scene *s = load_ok(path);
    if (s) rt_scene_destroy(s);
    write_glb("cut.glb", json, (const unsigned char *)p, sizeof p,
              12 + 8 + (strlen(json) + 3) / 4 * 4 + 8 + 10);
    snprintf(path, sizeof path, "%s/cut.glb", dir);
    expect_fail(path, "truncated");
    write_glb("cut2.glb", json, (const unsigned char *)p, sizeof p, 30);
    snprintf(path, sizeof path, "%s/cut2.glb", dir);
    expect_fail(path, NULL);

    /* an accessor reading past its view */
    gb_init(&g);
    int pos = tri_positions(&g);
    snprintf(g.accs, sizeof g.accs,
             "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"}");
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],\"nodes\":[{"
             "\"mesh\":0}]",
             pos);
    expect_fail(write_gltf("oob.gltf", &g, NULL, rest), "/accessors/0");
    /* a view past its buffer */
    gb_init(&g);
    pos = tri_positions(&g);
    snprintf(g.views, sizeof g.views, "{\"buffer\":0,\"byteOffset\":8,\"byteLength\":36}");
    expect_fail(write_gltf("oobview.gltf", &g, NULL, rest), "/bufferViews/0");
    /* an index out of range */
    gb_init(&g);
    pos = tri_positions(&g);
    static const uint16_t idx[3] = {0, 1, 7};
    int ia = acc(&g, idx, sizeof idx, 5123, "SCALAR", 3, 0);
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d},\"indices\":%d}]}],"
             "\"nodes\":[{\"mesh\":0}]",
             pos, ia);
    expect_fail(write_gltf("index.gltf", &g, NULL, rest), "/meshes/0/primitives/0/indices");
    /* buffer URIs: outside the folder, a directory, a FIFO, missing */
    gb_init(&g);
    pos = tri_positions(&g);
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],\"nodes\":[{"
             "\"mesh\":0}]",
             pos);
    snprintf(path, sizeof path, "%s/sub", dir);
    mkdir(path, 0700);
    snprintf(path, sizeof path, "%s/outside.bin", dir);
    FILE *f = fopen(path, "wb");
    fwrite(g.bin, 1, g.n, f);
    fclose(f);
    /* the file in sub/ points at ../outside.bin */
    {
        char name[64];
        snprintf(name, sizeof name, "sub/up.gltf");
        expect_fail(write_gltf(name, &g, "../outside.bin", rest), "leaves");
    }
    snprintf(path, sizeof path, "%s/adir.bin", dir);
    mkdir(path, 0700);
    expect_fail(write_gltf("dir.gltf", &g, "adir.bin", rest), NULL);
    snprintf(path, sizeof path, "%s/fifo.bin", dir);
    if (mkfifo(path, 0600) == 0) expect_fail(write_gltf("fifo.gltf", &g, "fifo.bin", rest), NULL);
    expect_fail(write_gltf("missing.gltf", &g, "nothere.bin", rest), NULL);
    /* a FIFO as the scene file itself */
    snprintf(path, sizeof path, "%s/pipe.gltf", dir);
    if (mkfifo(path, 0600) == 0) expect_fail(path, "not a regular file");
    /* cyclic nodes; two parents */
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],"
             "\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"children\":[2]},{\"children\":[1]}]",
             pos);
    expect_fail(write_gltf("cycle.gltf", &g, NULL, rest), "/nodes/");
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],"
             "\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"children\":[0]}]",
             pos);
    expect_fail(write_gltf("cycle2.gltf", &g, NULL, rest), "cycle");
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],"
             "\"nodes\":[{\"mesh\":0,\"children\":[0]}]",
             pos);
    expect_fail(write_gltf("self.gltf", &g, NULL, rest), "own child");
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],"
             "\"nodes\":[{\"mesh\":0,\"children\":[5]}]",
             pos);
    expect_fail(write_gltf("child.gltf", &g, NULL, rest), "/nodes/0/children/0");
    /* NaN and non-increasing key times; a NaN key value */
    static const float nan_t[2] = {0, NAN}, dec_t[3] = {0, 1, 1},
                       vals[9] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    static const float nan_v[6] = {0, 0, 0, NAN, 0, 0}, ok_t[2] = {0, 1};
    for (int k = 0; k < 3; k++) {
        gb_init(&g);
        pos = tri_positions(&g);
        int in = k == 0   ? accf(&g, nan_t, 2, "SCALAR")
                 : k == 1 ? accf(&g, dec_t, 3, "SCALAR")
                          : accf(&g, ok_t, 2, "SCALAR");
        int out = k == 2 ? accf(&g, nan_v, 2, "VEC3") : accf(&g, vals, k == 1 ? 3 : 2, "VEC3");
        snprintf(
            rest, sizeof rest,
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],"
            "\"nodes\":[{\"mesh\":0}],\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d}],"
            "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}}]}]",
            pos, in, out);
        const char *names[3] = {"nan_t.gltf", "dec_t.gltf", "nan_v.gltf"};
        const char *needle[3] = {"/animations/0/samplers/0/input", "strictly increasing",
                                 "/animations/0/samplers/0/output"};
        expect_fail(write_gltf(names[k], &g, NULL, rest), needle[k]);
    }
    /* an output of the wrong size; a sampler that does not exist; a joint out of range */
    gb_init(&g);
    pos = tri_positions(&g);
    int in = accf(&g, ok_t, 2, "SCALAR"), out = accf(&g, vals, 3, "VEC3");
    snprintf(
        rest, sizeof rest,
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],"
        "\"nodes\":[{\"mesh\":0}],\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d}],"
        "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}},"
        "{\"sampler\":3,\"target\":{\"node\":0,\"path\":\"scale\"}}]}]",
        pos, in, out);
    expect_fail(write_gltf("outsize.gltf", &g, NULL, rest), "/animations/0/samplers/0/output");
    gb_init(&g);
    pos = tri_positions(&g);
    static const uint8_t jj[12] = {0, 0, 0, 0, 9, 0, 0, 0, 0, 0, 0, 0};
    static const float ww[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    int aj = acc(&g, jj, sizeof jj, 5121, "VEC4", 3, 0), aw = accf(&g, ww, 3, "VEC4");
    snprintf(rest, sizeof rest,
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d,\"JOINTS_0\":%d,"
             "\"WEIGHTS_0\":%d}}]}],"
             "\"skins\":[{\"joints\":[1]}],\"nodes\":[{\"mesh\":0,\"skin\":0},{}]",
             pos, aj, aw);
    expect_fail(write_gltf("joint.gltf", &g, NULL, rest), "JOINTS_0");
    /* a required extension that would change the geometry */
    gb_init(&g);
    pos = tri_positions(&g);
    snprintf(rest, sizeof rest,
             "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
             "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],"
             "\"nodes\":[{\"mesh\":0}]",
             pos);
    expect_fail(write_gltf("draco.gltf", &g, NULL, rest), "/extensionsRequired/0");
    /* not JSON at all */
    snprintf(path, sizeof path, "%s/garbage.gltf", dir);
    f = fopen(path, "w");
    fputs("{\"asset\": [", f);
    fclose(f);
    expect_fail(path, NULL);
}

int main(void) {
    snprintf(dir, sizeof dir, "/tmp/rt_gltf_XXXXXX");
    if (!mkdtemp(dir)) {
        printf("skipped: no temporary folder\n");
        return 77;
    }
    /* Is the module here? */
    {
        gb g;
        gb_init(&g);
        int pos = tri_positions(&g);
        char rest[256];
        snprintf(rest, sizeof rest,
                 "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d}}]}],\"nodes\":[{"
                 "\"mesh\":0}]",
                 pos);
        rt_scene *s = NULL;
        rt_error err;
        if (rt_scene_load(write_gltf("probe.gltf", &g, NULL, rest), &s, &err) != RT_OK &&
            err.status == RT_ERROR_UNSUPPORTED) {
            printf("skipped: %s\n", err.message);
            return 77;
        }
        rt_scene_destroy(s);
    }
    test_hierarchy();
    test_strips_fans();
    test_normalized_sparse();
    test_samplers();
    test_rotation();
    test_rigid();
    test_morph();
    test_skin();
    test_camera_lights_materials();
    test_emissive_material();
    test_external_and_glb();
    test_malformed();
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    return TEST_END();
}
