/* SPDX-License-Identifier: Apache-2.0 */
/* obj_internal.h - pieces shared by the OBJ and MTL readers (not public API).
 *
 * Both formats are line based: a statement is a keyword and blank-separated
 * arguments; '#' starts a comment that runs to the end of the line; a
 * backslash right before the line end joins the next line (line
 * continuation). A '\r' counts as a blank, so CRLF files read like LF ones. */
#ifndef RT_OBJ_INTERNAL_H
#define RT_OBJ_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "formats/name_table.h"
#include "formats/obj_load.h"

/* A cursor over a text with its line number and the start of that line, for
 * "file:line:column" messages. */
typedef struct rt_text_cursor {
    const char *p;
    const char *end;
    const char *line_start;
    int64_t line;
} rt_text_cursor;

static inline int rt_text_is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* If p is a backslash that ends its line ("\\\n" or "\\\r\n"), returns the
 * position after that newline, else NULL. */
static inline const char *rt_text_continuation(const char *p, const char *end) {
    if (*p != '\\') return NULL;
    const char *q = p + 1;
    if (q < end && *q == '\r') q++;
    if (q < end && *q == '\n') return q + 1;
    return NULL;
}

/* Skips blanks and line continuations. */
static inline void rt_text_skip_blanks(rt_text_cursor *c) {
    for (;;) {
        while (c->p < c->end && rt_text_is_blank(*c->p)) c->p++;
        if (c->p >= c->end || *c->p != '\\') return;
        const char *after = rt_text_continuation(c->p, c->end);
        if (!after) return;
        c->p = after;
        c->line++;
        c->line_start = after;
    }
}

/* Whether the statement ends here: end of text, newline or comment. */
static inline int rt_text_at_statement_end(const rt_text_cursor *c) {
    return c->p >= c->end || *c->p == '\n' || *c->p == '#';
}

/* Moves to the start of the next line (past continuations). */
static inline void rt_text_next_line(rt_text_cursor *c) {
    if (c->p < c->end && *c->p == '\n') { /* the usual case after a statement */
        c->p++;
        c->line++;
        c->line_start = c->p;
        return;
    }
    for (;;) {
        const char *from = c->p;
        const char *nl = memchr(from, '\n', (size_t)(c->end - from));
        if (!nl) {
            c->p = c->end;
            return;
        }
        const char *before = nl;
        if (before > from && before[-1] == '\r') before--;
        int continued = before > from && before[-1] == '\\';
        c->p = nl + 1;
        c->line++;
        c->line_start = c->p;
        if (!continued) return;
    }
}

/* 1-based column of the cursor, for messages. */
static inline int rt_text_column(const rt_text_cursor *c) {
    ptrdiff_t col = c->p - c->line_start + 1;
    return col > 1000000000 ? 1000000000 : (int)col;
}

static inline int rt_text_line(const rt_text_cursor *c) {
    return c->line > 2000000000 ? 2000000000 : (int)c->line;
}

/* The materials of every MTL file an OBJ file names, each file read once
 * and each name defined once. */
typedef struct rt_mtl_library {
    rt_obj_material *materials; /* by name id */
    uint32_t capacity;
    rt_name_table names;  /* names.count materials */
    uint32_t *defined_in; /* per material: the index in files of its MTL */
    int *defined_at;      /* per material: its newmtl's line */
    struct rt_mtl_file {
        char *path;
        unsigned long long device, inode; /* 0, 0 for text parsed from memory */
    } * files;
    uint32_t file_count, file_capacity;
    /* newmtl statements that name a material defined before (in this or an
     * earlier file): the first definition counts, the later one is skipped
     * (its statements are read and ignored). The first such one, for the
     * notice: */
    uint32_t repeats;
    char first_repeat[640];
} rt_mtl_library;

/* Reads an MTL file into lib: a file read before (the same file by device
 * and inode, whatever the path that names it) is not read again. An
 * unreadable file gives RT_ERROR_IO (the OBJ reader then goes on without
 * it); malformed content gives RT_ERROR_PARSE with file, line and column,
 * and lib keeps the materials of the files read before. */
rt_status rt_mtl_load(rt_mtl_library *lib, const char *path, rt_error *err);

/* The same on text already in memory; name is used in messages. */
rt_status rt_mtl_parse(rt_mtl_library *lib, const char *text, size_t len, const char *name,
                       rt_error *err);

/* A notice about lib's repeated names ("" when none) into out. */
void rt_mtl_notice(const rt_mtl_library *lib, char *out, size_t cap);

/* Frees lib (the materials' names too, unless moved out before). */
void rt_mtl_library_free(rt_mtl_library *lib);

#endif /* RT_OBJ_INTERNAL_H */
