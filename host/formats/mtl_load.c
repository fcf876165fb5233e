/* SPDX-License-Identifier: Apache-2.0 */
/* mtl_load.c - the few MTL statements a ray tracer uses: newmtl, Kd, Ks, Ke,
 * Ns, Ni, d and Tr. Everything else (Ka, illum, maps, ...) is accepted and
 * ignored. Each file is read once and each name defined once (the first
 * definition counts; later ones are counted for a notice). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/error.h"
#include "base/file_read.h"
#include "formats/obj_internal.h"
#include "formats/parse_number.h"
#include "scene/scene.h" /* RT_MAX_COLOUR */

static rt_obj_material default_material(void) {
    rt_obj_material m;
    memset(&m, 0, sizeof m);
    m.kd[0] = m.kd[1] = m.kd[2] = 0.8f;
    m.ni = 1.0f;
    m.d = 1.0f;
    return m;
}

typedef struct mtl_reader {
    rt_text_cursor c;
    const char *name;
    rt_error *err;
} mtl_reader;

/* Length of the token at the cursor (up to a blank, newline or comment). */
static size_t token_length(const rt_text_cursor *c) {
    const char *q = c->p;
    while (q < c->end && !rt_text_is_blank(*q) && *q != '\n' && *q != '#') q++;
    return (size_t)(q - c->p);
}

/* Reads one number argument of keyword into *out. */
static rt_status read_number(mtl_reader *r, const char *keyword, float *out) {
    rt_text_skip_blanks(&r->c);
    if (rt_text_at_statement_end(&r->c))
        return rt_error_set(r->err, RT_ERROR_PARSE, r->name, rt_text_line(&r->c),
                            rt_text_column(&r->c), "%s needs a number here", keyword);
    const char *next;
    rt_number_result res = rt_parse_float(r->c.p, r->c.end, out, &next);
    if (res == RT_NUMBER_OK && next < r->c.end && !rt_text_is_blank(*next) && *next != '\n' &&
        *next != '#')
        res = RT_NUMBER_MALFORMED;
    if (res != RT_NUMBER_OK) {
        int len = (int)(token_length(&r->c) > 40 ? 40 : token_length(&r->c));
        return rt_error_set(
            r->err, RT_ERROR_PARSE, r->name, rt_text_line(&r->c), rt_text_column(&r->c),
            "%s: %s \"%.*s\"", keyword,
            res == RT_NUMBER_NOT_FINITE ? "not a finite number" : "malformed number", len, r->c.p);
    }
    r->c.p = next;
    return RT_OK;
}

/* Kd/Ks: "r [g b]"; one value means grey. The "spectral" and "xyz" forms are
 * ignored (the colour keeps its default). */
static rt_status read_colour(mtl_reader *r, const char *keyword, float rgb[3]) {
    rt_text_skip_blanks(&r->c);
    size_t len = token_length(&r->c);
    if ((len == 8 && memcmp(r->c.p, "spectral", 8) == 0) ||
        (len == 3 && memcmp(r->c.p, "xyz", 3) == 0))
        return RT_OK;
    float v[3];
    rt_status st = read_number(r, keyword, &v[0]);
    if (st != RT_OK) return st;
    rt_text_skip_blanks(&r->c);
    if (rt_text_at_statement_end(&r->c)) {
        v[1] = v[2] = v[0];
    } else {
        if ((st = read_number(r, keyword, &v[1])) != RT_OK) return st;
        if ((st = read_number(r, keyword, &v[2])) != RT_OK) return st;
    }
    for (int i = 0; i < 3; i++)
        if (!(v[i] >= 0.0f && v[i] <= RT_MAX_COLOUR))
            return rt_error_set(r->err, RT_ERROR_PARSE, r->name, rt_text_line(&r->c), 0,
                                "%s: %g is outside 0..%g (the colour limit)", keyword, (double)v[i],
                                (double)RT_MAX_COLOUR);
    memcpy(rgb, v, sizeof v);
    return RT_OK;
}

static int keyword_is(const char *p, size_t len, const char *word) {
    return len == strlen(word) && memcmp(p, word, len) == 0;
}

/* Room for one more material in lib. */
static int reserve_material(rt_mtl_library *lib) {
    if (lib->names.count < lib->capacity) return 1;
    uint32_t cap = lib->capacity ? 2 * lib->capacity : 16;
    if (cap < lib->capacity) return 0;
    rt_obj_material *m = realloc(lib->materials, (size_t)cap * sizeof *m);
    if (!m) return 0;
    lib->materials = m;
    uint32_t *in = realloc(lib->defined_in, (size_t)cap * sizeof *in);
    if (!in) return 0;
    lib->defined_in = in;
    int *at = realloc(lib->defined_at, (size_t)cap * sizeof *at);
    if (!at) return 0;
    lib->defined_at = at;
    lib->capacity = cap;
    return 1;
}

/* Adds the file to lib's list; its index in *index. */
static int add_file(rt_mtl_library *lib, const char *path, unsigned long long device,
                    unsigned long long inode, uint32_t *index) {
    if (lib->file_count == lib->file_capacity) {
        uint32_t cap = lib->file_capacity ? 2 * lib->file_capacity : 4;
        struct rt_mtl_file *f = realloc(lib->files, (size_t)cap * sizeof *f);
        if (!f) return 0;
        lib->files = f;
        lib->file_capacity = cap;
    }
    char *copy = strdup(path);
    if (!copy) return 0;
    lib->files[lib->file_count] = (struct rt_mtl_file){copy, device, inode};
    *index = lib->file_count++;
    return 1;
}

/* Parses one file's text; file is its index in lib->files. */
static rt_status parse_text(rt_mtl_library *lib, uint32_t file, const char *text, size_t len,
                            const char *name, rt_error *err) {
    mtl_reader r = {{text ? text : "", (text ? text : "") + len, text ? text : "", 1}, name, err};
    rt_obj_material *current = NULL;
    rt_status st = RT_OK;
    while (r.c.p < r.c.end) {
        rt_text_skip_blanks(&r.c);
        if (rt_text_at_statement_end(&r.c)) {
            rt_text_next_line(&r.c);
            continue;
        }
        size_t klen = token_length(&r.c);
        const char *keyword = r.c.p;
        int line = rt_text_line(&r.c), column = rt_text_column(&r.c);
        r.c.p += klen;
        if (keyword_is(keyword, klen, "newmtl")) {
            rt_text_skip_blanks(&r.c);
            const char *start = r.c.p;
            while (r.c.p < r.c.end && *r.c.p != '\n' && *r.c.p != '#') r.c.p++;
            const char *stop = r.c.p;
            while (stop > start && rt_text_is_blank(stop[-1])) stop--;
            if (stop == start)
                return rt_error_set(err, RT_ERROR_PARSE, name, line, column,
                                    "newmtl needs a material name");
            if (!reserve_material(lib))
                return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, name, line, 0, "out of memory");
            int added;
            uint32_t id = rt_name_add(&lib->names, start, (size_t)(stop - start), &added);
            if (id == RT_NO_NAME)
                return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, name, line, 0, "out of memory");
            if (added) {
                current = &lib->materials[id];
                *current = default_material();
                current->name = lib->names.names[id];
                lib->defined_in[id] = file;
                lib->defined_at[id] = line;
            } else {
                /* Defined before: the first definition counts. */
                current = NULL;
                if (lib->repeats++ == 0) {
                    int shown = (int)(stop - start > 80 ? 80 : stop - start);
                    snprintf(lib->first_repeat, sizeof lib->first_repeat,
                             "%.200s:%d: material '%.*s%s' was defined before, at %.200s:%d", name,
                             line, shown, start, stop - start > 80 ? "..." : "",
                             lib->files[lib->defined_in[id]].path, lib->defined_at[id]);
                }
            }
        } else if (current && keyword_is(keyword, klen, "Kd")) {
            st = read_colour(&r, "Kd", current->kd);
        } else if (current && keyword_is(keyword, klen, "Ks")) {
            st = read_colour(&r, "Ks", current->ks);
        } else if (current && keyword_is(keyword, klen, "Ke")) {
            st = read_colour(&r, "Ke", current->ke);
        } else if (current && keyword_is(keyword, klen, "Ns")) {
            st = read_number(&r, "Ns", &current->ns);
        } else if (current && keyword_is(keyword, klen, "Ni")) {
            st = read_number(&r, "Ni", &current->ni);
        } else if (current && keyword_is(keyword, klen, "d")) {
            /* "d -halo f" is an old variant; its factor is read as d. */
            rt_text_skip_blanks(&r.c);
            if (token_length(&r.c) == 5 && memcmp(r.c.p, "-halo", 5) == 0) r.c.p += 5;
            st = read_number(&r, "d", &current->d);
        } else if (current && keyword_is(keyword, klen, "Tr")) {
            float tr;
            st = read_number(&r, "Tr", &tr);
            if (st == RT_OK) current->d = 1.0f - tr;
        }
        if (st != RT_OK) return st;
        rt_text_next_line(&r.c);
    }
    return RT_OK;
}

rt_status rt_mtl_parse(rt_mtl_library *lib, const char *text, size_t len, const char *name,
                       rt_error *err) {
    uint32_t file;
    if (!add_file(lib, name, 0, 0, &file))
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, name, 0, 0, "out of memory");
    return parse_text(lib, file, text, len, name, err);
}

rt_status rt_mtl_load(rt_mtl_library *lib, const char *path, rt_error *err) {
    /* The same file again (a repeated mtllib line, or another path to it)
     * adds nothing: it is not read twice. */
    struct stat info;
    if (stat(path, &info) == 0)
        for (uint32_t i = 0; i < lib->file_count; i++)
            if ((lib->files[i].device || lib->files[i].inode) &&
                lib->files[i].device == (unsigned long long)info.st_dev &&
                lib->files[i].inode == (unsigned long long)info.st_ino)
                return RT_OK;
    char *text;
    size_t len;
    rt_status st = rt_read_file(path, "MTL file", RT_MAX_OBJ_FILE_BYTES, &text, &len, err);
    if (st != RT_OK) return st;
    uint32_t file;
    if (!add_file(lib, path, (unsigned long long)info.st_dev, (unsigned long long)info.st_ino,
                  &file))
        st = rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0, "out of memory");
    else
        st = parse_text(lib, file, text, len, path, err);
    free(text);
    return st;
}

void rt_mtl_notice(const rt_mtl_library *lib, char *out, size_t cap) {
    if (!lib->repeats) {
        out[0] = '\0';
        return;
    }
    if (lib->repeats == 1)
        snprintf(out, cap, "%s; the first definition is used", lib->first_repeat);
    else
        snprintf(out, cap,
                 "%s, and %u more material names are defined again; the first "
                 "definition of each is used",
                 lib->first_repeat, lib->repeats - 1);
}

void rt_mtl_library_free(rt_mtl_library *lib) {
    rt_name_table_free(&lib->names);
    free(lib->materials);
    free(lib->defined_in);
    free(lib->defined_at);
    for (uint32_t i = 0; i < lib->file_count; i++) free(lib->files[i].path);
    free(lib->files);
    memset(lib, 0, sizeof *lib);
}
