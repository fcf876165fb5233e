/* mtl_load.c - the few MTL statements a ray tracer uses: newmtl, Kd, Ks, Ns,
 * Ni, d and Tr. Everything else (Ka, Ke, illum, maps, ...) is accepted and
 * ignored. */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/file_read.h"
#include "formats/obj_internal.h"
#include "formats/parse_number.h"

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
    memcpy(rgb, v, sizeof v);
    return RT_OK;
}

static int keyword_is(const char *p, size_t len, const char *word) {
    return len == strlen(word) && memcmp(p, word, len) == 0;
}

rt_status rt_mtl_parse(const char *text, size_t len, const char *name, rt_obj_material **materials,
                       uint32_t *count, rt_error *err) {
    mtl_reader r = {{text ? text : "", (text ? text : "") + len, text ? text : "", 1}, name, err};
    rt_obj_material *list = *materials;
    uint32_t n = *count, cap = n;
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
            if (stop == start) {
                st = rt_error_set(err, RT_ERROR_PARSE, name, line, column,
                                  "newmtl needs a material name");
            } else {
                if (n == cap) {
                    uint32_t new_cap = cap ? cap * 2 : 8;
                    rt_obj_material *grown = realloc(list, (size_t)new_cap * sizeof *list);
                    if (!grown || new_cap < cap) {
                        st = rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, name, line, 0,
                                          "out of memory");
                        goto done;
                    }
                    list = grown;
                    cap = new_cap;
                }
                current = &list[n++];
                *current = default_material();
                size_t name_len = (size_t)(stop - start);
                if (name_len >= sizeof current->name) name_len = sizeof current->name - 1;
                memcpy(current->name, start, name_len);
                current->name[name_len] = '\0';
            }
        } else if (current && keyword_is(keyword, klen, "Kd")) {
            st = read_colour(&r, "Kd", current->kd);
        } else if (current && keyword_is(keyword, klen, "Ks")) {
            st = read_colour(&r, "Ks", current->ks);
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
        if (st != RT_OK) goto done;
        rt_text_next_line(&r.c);
    }
    *materials = list;
    *count = n;
    return RT_OK;
done:
    /* The array may have moved; the count stays, dropping this file's part. */
    *materials = list;
    return st;
}

rt_status rt_mtl_load(const char *path, rt_obj_material **materials, uint32_t *count,
                      rt_error *err) {
    char *text;
    size_t len;
    rt_status st = rt_read_file(path, "MTL file", RT_MAX_OBJ_FILE_BYTES, &text, &len, err);
    if (st != RT_OK) return st;
    st = rt_mtl_parse(text, len, path, materials, count, err);
    free(text);
    return st;
}
