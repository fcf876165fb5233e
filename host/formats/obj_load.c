/* SPDX-License-Identifier: Apache-2.0 */
/* obj_load.c - Wavefront OBJ to one indexed triangle mesh.
 *
 * One pass over the text, read in one piece: positions and normals go into
 * growing arrays, faces are fan-triangulated on the fly into triangles of
 * (position index, normal index) corners. At the end, if every corner had a
 * normal, the (position, normal) pairs become the output vertices (each pair
 * once, in order of first use) unless every corner pairs position k with
 * normal k, when the vertices stay in file order; otherwise the positions are
 * the vertices as they are and normals are dropped. See docs/OBJ.md. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/error.h"
#include "base/file_read.h"
#include "formats/obj_internal.h"
#include "formats/parse_number.h"
#include "scene/scene.h" /* the mesh limits */

#define NO_INDEX UINT32_MAX
/* Counts above this are refused so that 3 * count still fits in uint32_t. */
#define MAX_COUNT (UINT32_MAX / 3)

typedef struct obj_parser {
    rt_text_cursor c;
    const char *name;
    const char *base_dir;
    rt_error *err;

    float *positions; /* 3 per v */
    size_t position_count, position_cap;
    float *normals; /* 3 per vn */
    size_t normal_count, normal_cap;
    size_t texcoord_count;

    uint32_t *tri_pos; /* 3 position indices per triangle */
    size_t tri_count, tri_pos_cap;
    uint32_t *tri_nrm; /* 3 normal indices per triangle, while all_normals */
    size_t tri_nrm_cap;
    int all_normals; /* no corner without a normal seen yet */

    uint32_t *tri_mat; /* per triangle a usemtl name id (or NO_INDEX), once usemtl seen */
    size_t tri_mat_cap;
    uint32_t current_mtl;
    rt_name_table usemtl; /* distinct usemtl names, whole */

    rt_mtl_library mtl; /* the materials of the mtllib files */
} obj_parser;

/* ---- small helpers ------------------------------------------------------ */

/* Makes room for need elements of size elem in *data (capacity *cap). */
static inline int reserve(void **data, size_t *cap, size_t need, size_t elem) {
    if (need <= *cap) return 1;
    size_t new_cap = *cap ? *cap : 1024;
    while (new_cap < need) {
        if (new_cap > SIZE_MAX / 2 / elem) return 0;
        new_cap *= 2;
    }
    void *grown = realloc(*data, new_cap * elem);
    if (!grown) return 0;
    *data = grown;
    *cap = new_cap;
    return 1;
}

static rt_status fail(obj_parser *o, rt_status status, int column, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static rt_status fail(obj_parser *o, rt_status status, int column, const char *fmt, ...) {
    va_list args;
    va_start(args, fmt);
    rt_error_setv(o->err, status, o->name, rt_text_line(&o->c), column, fmt, args);
    va_end(args);
    return status;
}

static rt_status out_of_memory(obj_parser *o) {
    return fail(o, RT_ERROR_OUT_OF_MEMORY, 0, "out of memory");
}

/* Whether a number or index may end at p: a blank, the end of the
 * statement, or a line continuation. */
static int ends_token(const rt_text_cursor *c, const char *p) {
    if (p >= c->end) return 1;
    char ch = *p;
    return rt_text_is_blank(ch) || ch == '\n' || ch == '#' ||
           (ch == '\\' && rt_text_continuation(p, c->end));
}

/* Length of the token at the cursor, capped for messages. */
static int token_length(const rt_text_cursor *c) {
    const char *q = c->p;
    while (q < c->end && !rt_text_is_blank(*q) && *q != '\n' && *q != '#' && q - c->p < 40) q++;
    return (int)(q - c->p);
}

/* ---- statements --------------------------------------------------------- */

/* Reads the count numbers of a v or vn statement into out; any further
 * numbers (v's optional w, vertex colours) must be numbers and are ignored. */
static inline rt_status read_floats(obj_parser *o, const char *what, const char *part, int count,
                                    float *out) {
    for (int i = 0;; i++) {
        rt_text_skip_blanks(&o->c);
        if (rt_text_at_statement_end(&o->c)) {
            if (i >= count) return RT_OK;
            return fail(o, RT_ERROR_PARSE, rt_text_column(&o->c), "%s has %d %s, needs %d", what, i,
                        part, count);
        }
        float value;
        const char *next;
        rt_number_result res = rt_parse_float(o->c.p, o->c.end, &value, &next);
        if (res == RT_NUMBER_OK && !ends_token(&o->c, next)) res = RT_NUMBER_MALFORMED;
        if (res == RT_NUMBER_NOT_FINITE)
            return fail(o, RT_ERROR_PARSE, rt_text_column(&o->c),
                        "%s coordinate \"%.*s\" is not a finite number (NaN, Inf or beyond "
                        "float's range)",
                        what, token_length(&o->c), o->c.p);
        if (res != RT_NUMBER_OK)
            return fail(o, RT_ERROR_PARSE, rt_text_column(&o->c), "malformed number \"%.*s\"",
                        token_length(&o->c), o->c.p);
        if (i < count) out[i] = value;
        o->c.p = next;
    }
}

static rt_status parse_vertex(obj_parser *o) {
    if (o->position_count >= MAX_COUNT)
        return fail(o, RT_ERROR_PARSE, 1, "more than %u vertices", (unsigned)MAX_COUNT);
    if (!reserve((void **)&o->positions, &o->position_cap, 3 * (o->position_count + 1),
                 sizeof(float)))
        return out_of_memory(o);
    rt_status st = read_floats(o, "vertex", "coordinates", 3, o->positions + 3 * o->position_count);
    if (st == RT_OK) o->position_count++;
    return st;
}

static rt_status parse_normal(obj_parser *o) {
    if (o->normal_count >= MAX_COUNT)
        return fail(o, RT_ERROR_PARSE, 1, "more than %u normals", (unsigned)MAX_COUNT);
    if (!reserve((void **)&o->normals, &o->normal_cap, 3 * (o->normal_count + 1), sizeof(float)))
        return out_of_memory(o);
    rt_status st = read_floats(o, "normal", "components", 3, o->normals + 3 * o->normal_count);
    if (st == RT_OK) o->normal_count++;
    return st;
}

/* Reads one index at the cursor and turns it into a 0-based index below
 * count (negative indices count back from the newest element). */
static inline rt_status read_index(obj_parser *o, const char *kind, const char *plural,
                                   size_t count, const char *corner_start, uint32_t *out) {
    /* Fast path for the usual positive index of at most 9 digits that is in
     * range: no sign, no 64-bit parse, no column bookkeeping. Anything else
     * (signs, zero, long or out-of-range numbers, malformed text) takes the
     * general path below, which also produces the errors. */
    const char *s = o->c.p;
    if (s < o->c.end && rt_is_digit(*s)) {
        const char *limit = o->c.end - s > 9 ? s + 9 : o->c.end;
        uint32_t v = 0;
        while (s < limit && rt_is_digit(*s)) v = v * 10u + (uint32_t)(*s++ - '0');
        if (v != 0 && v <= count && !(s < o->c.end && rt_is_digit(*s))) {
            o->c.p = s;
            *out = v - 1;
            return RT_OK;
        }
    }
    int64_t value;
    const char *next;
    const char *start = o->c.p;
    rt_number_result res = rt_parse_int64(start, o->c.end, &value, &next);
    /* The number must end the index: "0x5" or "1e3" is no index 0 or 1. */
    if (res != RT_NUMBER_MALFORMED && next < o->c.end && *next != '/' && !ends_token(&o->c, next))
        res = RT_NUMBER_MALFORMED;
    if (res == RT_NUMBER_MALFORMED) {
        o->c.p = corner_start;
        return fail(o, RT_ERROR_PARSE, rt_text_column(&o->c), "malformed vertex reference \"%.*s\"",
                    token_length(&o->c), corner_start);
    }
    int column = (int)(start - o->c.line_start + 1);
    if (res == RT_NUMBER_TOO_LARGE)
        return fail(o, RT_ERROR_PARSE, column, "%s index %.*s is out of range (%zu %s so far)",
                    kind, (int)(next - start > 40 ? 40 : next - start), start, count, plural);
    if (value == 0)
        return fail(o, RT_ERROR_PARSE, column,
                    "%s index 0 is invalid (indices start at 1; negative ones count back)", kind);
    int64_t index = value > 0 ? value - 1 : (int64_t)count + value;
    if (index < 0 || (uint64_t)index >= count)
        return fail(o, RT_ERROR_PARSE, column, "%s index %lld is out of range (%zu %s so far)",
                    kind, (long long)value, count, plural);
    o->c.p = next;
    *out = (uint32_t)index;
    return RT_OK;
}

/* One face corner: v, v/vt, v//vn or v/vt/vn. *nrm is NO_INDEX without vn. */
static inline rt_status read_corner(obj_parser *o, uint32_t *pos, uint32_t *nrm) {
    const char *corner_start = o->c.p;
    rt_status st = read_index(o, "vertex", "vertices", o->position_count, corner_start, pos);
    if (st != RT_OK) return st;
    *nrm = NO_INDEX;
    if (o->c.p < o->c.end && *o->c.p == '/') {
        o->c.p++;
        if (o->c.p < o->c.end && *o->c.p != '/') {
            uint32_t vt;
            st = read_index(o, "texture coordinate", "texture coordinates", o->texcoord_count,
                            corner_start, &vt);
            if (st != RT_OK) return st;
        }
        if (o->c.p < o->c.end && *o->c.p == '/') {
            o->c.p++;
            st = read_index(o, "normal", "normals", o->normal_count, corner_start, nrm);
            if (st != RT_OK) return st;
        } else if (o->c.p[-1] == '/') {
            o->c.p = corner_start; /* "1/" */
            return fail(o, RT_ERROR_PARSE, rt_text_column(&o->c),
                        "malformed vertex reference \"%.*s\"", token_length(&o->c), corner_start);
        }
    }
    if (!ends_token(&o->c, o->c.p)) {
        o->c.p = corner_start;
        return fail(o, RT_ERROR_PARSE, rt_text_column(&o->c), "malformed vertex reference \"%.*s\"",
                    token_length(&o->c), corner_start);
    }
    return RT_OK;
}

static inline rt_status emit_triangle(obj_parser *o, const uint32_t pos[3], const uint32_t nrm[3]) {
    if (o->tri_count >= MAX_COUNT)
        return fail(o, RT_ERROR_PARSE, 1, "more than %u triangles", (unsigned)MAX_COUNT);
    size_t t = o->tri_count;
    if (!reserve((void **)&o->tri_pos, &o->tri_pos_cap, 3 * (t + 1), sizeof(uint32_t)))
        return out_of_memory(o);
    memcpy(o->tri_pos + 3 * t, pos, 3 * sizeof(uint32_t));
    if (o->all_normals) {
        if (!reserve((void **)&o->tri_nrm, &o->tri_nrm_cap, 3 * (t + 1), sizeof(uint32_t)))
            return out_of_memory(o);
        memcpy(o->tri_nrm + 3 * t, nrm, 3 * sizeof(uint32_t));
    }
    if (o->tri_mat) {
        if (!reserve((void **)&o->tri_mat, &o->tri_mat_cap, t + 1, sizeof(uint32_t)))
            return out_of_memory(o);
        o->tri_mat[t] = o->current_mtl;
    }
    o->tri_count++;
    return RT_OK;
}

/* f v1 v2 v3 ...: fan (v0,v1,v2), (v0,v2,v3), ... */
static rt_status parse_face(obj_parser *o, int face_column) {
    uint32_t pos[3], nrm[3];
    int corners = 0;
    for (;;) {
        rt_text_skip_blanks(&o->c);
        if (rt_text_at_statement_end(&o->c)) break;
        uint32_t p = 0, n = NO_INDEX;
        rt_status st = read_corner(o, &p, &n);
        if (st != RT_OK) return st;
        if (n == NO_INDEX && o->all_normals) {
            /* One corner without a normal: the mesh gets no normals. */
            o->all_normals = 0;
            free(o->tri_nrm);
            o->tri_nrm = NULL;
            o->tri_nrm_cap = 0;
        }
        if (corners < 3) {
            pos[corners] = p;
            nrm[corners] = n;
        } else {
            pos[1] = pos[2];
            nrm[1] = nrm[2];
            pos[2] = p;
            nrm[2] = n;
        }
        corners++;
        if (corners >= 3 && (st = emit_triangle(o, pos, nrm)) != RT_OK) return st;
    }
    if (corners < 3)
        return fail(o, RT_ERROR_PARSE, face_column, "face has %d vertices, needs at least 3",
                    corners);
    return RT_OK;
}

/* The rest of the statement, without the comment and trailing blanks. */
/* ---- hash tables of ids -------------------------------------------------- */

/* Open addressing with linear probing over a power-of-two number of slots,
 * each an id or NO_INDEX; the caller compares keys through the ids. Kept at
 * most half full, so a lookup probes O(1) slots on average: loading stays
 * near-linear however many distinct normals share a position or however
 * many usemtl names a file has. */
static uint32_t *id_table_new(size_t min_entries, size_t *slot_count) {
    size_t n = 16;
    while (n < 2 * min_entries) n *= 2;
    uint32_t *t = malloc(n * sizeof *t);
    if (!t) return NULL;
    for (size_t i = 0; i < n; i++) t[i] = NO_INDEX;
    *slot_count = n;
    return t;
}

/* A 64-bit finaliser (splitmix64) for a pair of indices. */
static uint64_t hash_pair(uint32_t a, uint32_t b) {
    uint64_t x = ((uint64_t)a << 32 | b) + 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

static void rest_of_statement(obj_parser *o, const char **start, size_t *len) {
    rt_text_skip_blanks(&o->c);
    const char *s = o->c.p, *q = s;
    while (q < o->c.end && *q != '\n' && *q != '#') q++;
    while (q > s && rt_text_is_blank(q[-1])) q--;
    *start = s;
    *len = (size_t)(q - s);
}

static rt_status parse_usemtl(obj_parser *o) {
    const char *name;
    size_t len;
    rest_of_statement(o, &name, &len);
    int added;
    uint32_t id = rt_name_add(&o->usemtl, name, len, &added);
    if (id == RT_NO_NAME) return out_of_memory(o);
    o->current_mtl = id;
    if (!o->tri_mat) {
        /* First usemtl: the triangles so far have no material. */
        if (!reserve((void **)&o->tri_mat, &o->tri_mat_cap, o->tri_count + 1, sizeof(uint32_t)))
            return out_of_memory(o);
        for (size_t t = 0; t < o->tri_count; t++) o->tri_mat[t] = NO_INDEX;
    }
    return RT_OK;
}

/* mtllib a.mtl [b.mtl ...], relative to base_dir. A file that cannot be read
 * is skipped; a malformed one is an error. */
static rt_status parse_mtllib(obj_parser *o) {
    for (;;) {
        rt_text_skip_blanks(&o->c);
        if (rt_text_at_statement_end(&o->c)) return RT_OK;
        const char *s = o->c.p;
        while (o->c.p < o->c.end && !rt_text_is_blank(*o->c.p) && *o->c.p != '\n' && *o->c.p != '#')
            o->c.p++;
        if (!o->base_dir) continue; /* parsing text with no folder: materials are not read */
        size_t len = (size_t)(o->c.p - s);
        size_t dir_len = strlen(o->base_dir);
        char *path = malloc(dir_len + len + 2);
        if (!path) return out_of_memory(o);
        if (s[0] == '/') {
            memcpy(path, s, len);
            path[len] = '\0';
        } else {
            memcpy(path, o->base_dir, dir_len);
            path[dir_len] = '/';
            memcpy(path + dir_len + 1, s, len);
            path[dir_len + 1 + len] = '\0';
        }
        rt_error mtl_err;
        rt_status st = rt_mtl_load(&o->mtl, path, &mtl_err);
        free(path);
        if (st == RT_ERROR_IO) continue;
        if (st != RT_OK) {
            if (o->err) *o->err = mtl_err;
            return st;
        }
    }
}

/* Dispatches one statement; the cursor is on its first non-blank byte. */
static rt_status parse_statement(obj_parser *o) {
    const char *p = o->c.p, *end = o->c.end;
    size_t avail = (size_t)(end - p);
    int column = rt_text_column(&o->c);
#define ENDS_KEYWORD(i) ((i) >= avail || rt_text_is_blank(p[i]) || p[i] == '\n' || p[i] == '#')
    if (p[0] == 'v') {
        if (ENDS_KEYWORD(1)) {
            o->c.p += 1;
            return parse_vertex(o);
        }
        if (p[1] == 'n' && ENDS_KEYWORD(2)) {
            o->c.p += 2;
            return parse_normal(o);
        }
        if (p[1] == 't' && ENDS_KEYWORD(2)) {
            o->texcoord_count++; /* texture coordinates are counted, not read */
            return RT_OK;
        }
    } else if (p[0] == 'f' && ENDS_KEYWORD(1)) {
        o->c.p += 1;
        return parse_face(o, column);
    } else if (avail >= 6 && memcmp(p, "usemtl", 6) == 0 && ENDS_KEYWORD(6)) {
        o->c.p += 6;
        return parse_usemtl(o);
    } else if (avail >= 6 && memcmp(p, "mtllib", 6) == 0 && ENDS_KEYWORD(6)) {
        o->c.p += 6;
        return parse_mtllib(o);
    }
#undef ENDS_KEYWORD
    return RT_OK; /* o, g, s, l, p, vp, ... and unknown statements are ignored */
}

/* ---- the result ---------------------------------------------------------- */

/* Each distinct (position, normal) pair of the corners becomes one vertex, in
 * order of first use. A hash table of (position, normal) pairs finds repeats
 * (a position used with many normals stays linear). */
static rt_status build_vertices_with_normals(obj_parser *o, rt_obj_mesh *out) {
    size_t corners = 3 * o->tri_count;
    size_t slot_count = 0;
    uint32_t *slots = id_table_new(corners, &slot_count); /* (position, normal) -> vertex */
    uint32_t *normal_of = malloc(corners * sizeof *normal_of);
    uint32_t *position_of = malloc(corners * sizeof *position_of);
    /* The output indices overwrite tri_pos in place: corner k is read
     * before it is written. */
    uint32_t *indices = o->tri_pos;
    float *positions = NULL, *normals = NULL;
    uint32_t count = 0;
    rt_status st = RT_OK;
    if (!slots || !normal_of || !position_of) goto oom;
    for (size_t k = 0; k < corners; k++) {
        const uint32_t p = o->tri_pos[k], n = o->tri_nrm[k];
        const size_t mask = slot_count - 1;
        size_t i = (size_t)hash_pair(p, n) & mask;
        uint32_t v;
        while ((v = slots[i]) != NO_INDEX && !(position_of[v] == p && normal_of[v] == n))
            i = (i + 1) & mask;
        if (v == NO_INDEX) {
            v = slots[i] = count++;
            normal_of[v] = n;
            position_of[v] = p;
        }
        indices[k] = v;
    }
    positions = malloc((size_t)count * 3 * sizeof(float));
    normals = malloc((size_t)count * 3 * sizeof(float));
    if (!positions || !normals) goto oom;
    for (uint32_t v = 0; v < count; v++) {
        memcpy(positions + 3 * (size_t)v, o->positions + 3 * (size_t)position_of[v],
               3 * sizeof(float));
        memcpy(normals + 3 * (size_t)v, o->normals + 3 * (size_t)normal_of[v], 3 * sizeof(float));
    }
    out->positions = positions;
    out->normals = normals;
    out->vertex_count = count;
    out->indices = indices;
    o->tri_pos = NULL;
    positions = normals = NULL;
    goto done;
oom:
    st = out_of_memory(o);
done:
    free(slots);
    free(normal_of);
    free(position_of);
    free(positions);
    free(normals);
    return st;
}

/* tri_materials from the usemtl name ids and the materials read: a name
 * is matched whole (the MTL reader defines each name once). */
static rt_status build_materials(obj_parser *o, rt_obj_mesh *out) {
    if (!o->tri_mat || o->mtl.names.count == 0) return RT_OK;
    uint32_t *material_of_name = malloc(((size_t)o->usemtl.count + 1) * sizeof(uint32_t));
    if (!material_of_name) return out_of_memory(o);
    for (uint32_t id = 0; id < o->usemtl.count; id++) {
        uint32_t m = rt_name_find(&o->mtl.names, o->usemtl.names[id], o->usemtl.sizes[id]);
        material_of_name[id] = m == RT_NO_NAME ? NO_INDEX : m;
    }
    for (size_t t = 0; t < o->tri_count; t++)
        o->tri_mat[t] = o->tri_mat[t] == NO_INDEX ? NO_INDEX : material_of_name[o->tri_mat[t]];
    free(material_of_name);
    out->tri_materials = o->tri_mat;
    o->tri_mat = NULL;
    return RT_OK;
}

/* True when every corner's normal index equals its position index and there
 * are as many normals as positions (files written per vertex, like Sponza or
 * rtcl generate): then the vertices stay as they are, in file order. */
static int normals_match_positions(const obj_parser *o) {
    if (o->normal_count != o->position_count) return 0;
    for (size_t k = 0; k < 3 * o->tri_count; k++)
        if (o->tri_nrm[k] != o->tri_pos[k]) return 0;
    return 1;
}

static rt_status build_mesh(obj_parser *o, rt_obj_mesh *out) {
    rt_status st;
    int keep_vertices = o->all_normals && o->tri_count > 0 && normals_match_positions(o);
    if (keep_vertices) {
        out->normals = o->normals;
        o->normals = NULL;
    }
    if (o->all_normals && o->tri_count > 0 && !keep_vertices) {
        st = build_vertices_with_normals(o, out);
        if (st != RT_OK) return st;
    } else {
        /* Positions as they are (unused ones included), with the normals
         * kept above or none. The
         * arrays give back their unused capacity (realloc to less cannot
         * fail in a way that loses data: on NULL the old block stays). */
        float *fit_positions =
            o->position_count ? realloc(o->positions, 3 * o->position_count * sizeof(float)) : NULL;
        if (fit_positions) o->positions = fit_positions;
        uint32_t *fit_indices =
            o->tri_count ? realloc(o->tri_pos, 3 * o->tri_count * sizeof(uint32_t)) : NULL;
        if (fit_indices) o->tri_pos = fit_indices;
        out->positions = o->positions;
        out->vertex_count = (uint32_t)o->position_count;
        out->indices = o->tri_pos;
        o->positions = NULL;
        o->tri_pos = NULL;
    }
    out->triangle_count = (uint32_t)o->tri_count;
    st = build_materials(o, out);
    if (st != RT_OK) return st;
    if (o->mtl.names.count) {
        /* The materials and their names move to the mesh. */
        out->materials = o->mtl.materials;
        out->material_count = o->mtl.names.count;
        for (uint32_t i = 0; i < out->material_count; i++) o->mtl.names.names[i] = NULL;
        o->mtl.materials = NULL;
    }
    rt_mtl_notice(&o->mtl, out->notice, sizeof out->notice);
    return RT_OK;
}

static void free_parser(obj_parser *o) {
    free(o->positions);
    free(o->normals);
    free(o->tri_pos);
    free(o->tri_nrm);
    free(o->tri_mat);
    rt_name_table_free(&o->usemtl);
    if (o->mtl.materials)
        for (uint32_t i = 0; i < o->mtl.names.count; i++) o->mtl.materials[i].name = NULL;
    rt_mtl_library_free(&o->mtl);
}

/* ---- counts before memory ---------------------------------------------- */

/* The statements' counts, read without parsing numbers: v lines, vn lines
 * and the triangles of the f lines (corners - 2 each), by the parser's own
 * rules for blanks, comments and continuations. A malformed file counts as
 * what it would be up to its first error; the counts only bound what the
 * parse may allocate. */
static void count_statements(const char *text, size_t len, uint64_t *vertices, uint64_t *normals,
                             uint64_t *triangles) {
    rt_text_cursor c = {text, text + len, text, 1};
    *vertices = *normals = *triangles = 0;
    while (c.p < c.end) {
        rt_text_skip_blanks(&c);
        const char *p = c.p;
        size_t avail = (size_t)(c.end - p);
#define ENDS_AT(i) ((i) >= avail || rt_text_is_blank(p[i]) || p[i] == '\n' || p[i] == '#')
        if (avail && p[0] == 'v' && ENDS_AT(1)) {
            ++*vertices;
        } else if (avail > 1 && p[0] == 'v' && p[1] == 'n' && ENDS_AT(2)) {
            ++*normals;
        } else if (avail && p[0] == 'f' && ENDS_AT(1)) {
            uint64_t corners = 0;
            c.p++;
            for (;;) {
                rt_text_skip_blanks(&c);
                if (rt_text_at_statement_end(&c)) break;
                corners++;
                while (c.p < c.end && !rt_text_is_blank(*c.p) && *c.p != '\n' && *c.p != '#' &&
                       !rt_text_continuation(c.p, c.end))
                    c.p++;
            }
            if (corners >= 3) *triangles += corners - 2;
        }
#undef ENDS_AT
        rt_text_next_line(&c);
    }
}

/* The mesh limits checked from the counts, before the parse allocates for
 * them. Only a file large enough to hold more than a limit is counted: a
 * triangle takes at least 2 bytes of text (" 1" in a fan), a vertex 8. */
static rt_status check_counts(const char *text, size_t len, const char *name, rt_error *err) {
    if (len / 2 <= RT_MAX_MESH_TRIANGLES && len / 8 <= RT_MAX_MESH_VERTICES) return RT_OK;
    uint64_t vertices, normals, triangles;
    count_statements(text, len, &vertices, &normals, &triangles);
    if (triangles > RT_MAX_MESH_TRIANGLES)
        return rt_error_set(err, RT_ERROR_UNSUPPORTED, name, 0, 0,
                            "the file's faces make %llu triangles, more than the limit of %llu "
                            "triangles per mesh",
                            (unsigned long long)triangles,
                            (unsigned long long)RT_MAX_MESH_TRIANGLES);
    if (vertices > RT_MAX_MESH_VERTICES || normals > RT_MAX_MESH_VERTICES)
        return rt_error_set(err, RT_ERROR_UNSUPPORTED, name, 0, 0,
                            "the file has %llu vertices and %llu normals, more than the limit "
                            "of %llu vertices per mesh",
                            (unsigned long long)vertices, (unsigned long long)normals,
                            (unsigned long long)RT_MAX_MESH_VERTICES);
    return RT_OK;
}

/* ---- public API ------------------------------------------------------------ */

rt_status rt_obj_parse(const char *text, size_t len, const char *name, const char *base_dir,
                       rt_obj_mesh *out, rt_error *err) {
    memset(out, 0, sizeof *out);
    rt_error_clear(err);
    if (!text) {
        text = "";
        len = 0;
    }
    rt_status st = check_counts(text, len, name ? name : "<obj>", err);
    if (st != RT_OK) return st;
    obj_parser o;
    memset(&o, 0, sizeof o);
    o.c.p = o.c.line_start = text;
    o.c.end = text + len;
    o.c.line = 1;
    o.name = name ? name : "<obj>";
    o.base_dir = base_dir;
    o.err = err;
    o.all_normals = 1;
    o.current_mtl = NO_INDEX;

    while (o.c.p < o.c.end) {
        rt_text_skip_blanks(&o.c);
        if (!rt_text_at_statement_end(&o.c)) {
            st = parse_statement(&o);
            if (st != RT_OK) break;
        }
        rt_text_next_line(&o.c);
    }
    if (st == RT_OK) st = build_mesh(&o, out);
    free_parser(&o);
    if (st != RT_OK) rt_obj_free(out);
    return st;
}

rt_status rt_obj_load(const char *path, rt_obj_mesh *out, rt_error *err) {
    memset(out, 0, sizeof *out);
    char *text;
    size_t len;
    rt_status st = rt_read_file(path, "OBJ file", RT_MAX_OBJ_FILE_BYTES, &text, &len, err);
    if (st != RT_OK) return st;
    /* mtllib names are relative to the OBJ's folder. */
    const char *slash = strrchr(path, '/');
    char *dir = slash ? malloc((size_t)(slash - path) + 2) : NULL;
    if (slash && !dir) {
        free(text);
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0, "out of memory");
    }
    if (dir) {
        size_t dir_len = slash == path ? 1 : (size_t)(slash - path);
        memcpy(dir, path, dir_len);
        dir[dir_len] = '\0';
    }
    st = rt_obj_parse(text, len, path, dir ? dir : ".", out, err);
    free(dir);
    free(text);
    return st;
}

void rt_obj_free(rt_obj_mesh *mesh) {
    if (!mesh) return;
    free(mesh->positions);
    free(mesh->normals);
    free(mesh->indices);
    free(mesh->tri_materials);
    for (uint32_t i = 0; mesh->materials && i < mesh->material_count; i++)
        free(mesh->materials[i].name);
    free(mesh->materials);
    memset(mesh, 0, sizeof *mesh);
}
