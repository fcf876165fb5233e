/* SPDX-License-Identifier: Apache-2.0 */
/* ray_file.c - see ray_file.h. */
#include "formats/ray_file.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/file_read.h"
#include "rt_shared.h"

/* The rays read so far. */
typedef struct ray_reader {
    const char *name;
    int want; /* numbers per line: 8, or 11 with normals */
    rt_ray *rays;
    size_t n, cap;
    /* A 4 GiB file of newlines has more lines than an int counts: the count
     * is 64-bit and clamped only for the message. */
    uint64_t lineno;
    rt_error *err;
} ray_reader;

static int line_number(const ray_reader *r) {
    return r->lineno > INT32_MAX ? INT32_MAX : (int)r->lineno;
}

/* Takes one line of line_len bytes at p (without its '\n'); p[line_len] must
 * be readable and strtof must stop there or before (a '\0' or the next
 * line's text: a number strtof reads past the line's end, as it skips
 * newlines as blanks, is not taken). */
static rt_status take_line(ray_reader *r, const char *p, size_t line_len) {
    r->lineno++;
    if (memchr(p, '\0', line_len))
        return rt_error_set(r->err, RT_ERROR_PARSE, r->name, line_number(r), 0,
                            "a NUL byte in the line (a binary file?)");
    const char *const end_of_line = p + line_len;
    while (p < end_of_line && (*p == ' ' || *p == '\t')) p++;
    if (p == end_of_line || *p == '#' || *p == '\r') return RT_OK;
    float v[11];
    int got = 0;
    while (got < r->want + 1) {
        char *end;
        float x = strtof(p, &end);
        if (end == p || end > end_of_line) break;
        if (got < r->want) v[got] = x;
        got++;
        p = end;
    }
    while (p < end_of_line && (*p == ' ' || *p == '\t' || *p == '\r')) p++;
    if (got != r->want || p < end_of_line) {
        const int rest = p < end_of_line ? (int)(end_of_line - p > 41 ? 41 : end_of_line - p) : 0;
        return rt_error_set(r->err, RT_ERROR_PARSE, r->name, line_number(r), 0,
                            "expected %d numbers 'ox oy oz dx dy dz tmin tmax%s'%s%.*s%s", r->want,
                            r->want == 11 ? " nx ny nz" : "", rest ? ", found: " : "",
                            rest > 40 ? 40 : rest, p, rest > 40 ? "..." : "");
    }
    if (r->n == r->cap) {
        size_t cap = r->cap ? 2 * r->cap : 1024;
        rt_ray *grown =
            cap > SIZE_MAX / sizeof *grown ? NULL : realloc(r->rays, cap * sizeof *grown);
        if (!grown)
            return rt_error_set(r->err, RT_ERROR_OUT_OF_MEMORY, r->name, 0, 0,
                                "out of memory for %zu rays", cap);
        r->rays = grown;
        r->cap = cap;
    }
    rt_ray *ray = &r->rays[r->n++];
    memcpy(ray->org, v, sizeof ray->org);
    memcpy(ray->dir, v + 3, sizeof ray->dir);
    ray->tmin = v[6];
    ray->tmax = v[7];
    if (r->want == 11) { /* off the surface, on the side the ray leaves to */
        float d = rt_dot3(v + 8, ray->dir);
        rt_offset_point(v, v + 8, d >= 0.0f ? 1.0f : -1.0f, ray->org);
    }
    return RT_OK;
}

/* The result: the rays on success (NULL when none), nothing on failure. */
static rt_status finish(ray_reader *r, rt_status st, rt_ray **out, size_t *count) {
    if (st != RT_OK || r->n == 0) {
        free(r->rays);
        r->rays = NULL;
        r->n = 0;
    }
    *out = r->rays;
    *count = r->n;
    return st;
}

rt_status rt_rays_parse(const char *text, size_t len, const char *name, int with_normals,
                        rt_ray **out, size_t *count, rt_error *err) {
    ray_reader r = {name, with_normals ? 11 : 8, NULL, 0, 0, 0, err};
    rt_status st = RT_OK;
    /* Line by line; a line ends at '\n' or at the end of the text, which is
     * NUL-terminated, so strtof stops at the text's end. */
    for (size_t at = 0; st == RT_OK && at < len;) {
        const char *p = text + at, *eol = memchr(p, '\n', len - at);
        const size_t line_len = eol ? (size_t)(eol - p) : len - at;
        at += line_len + 1;
        st = take_line(&r, p, line_len);
    }
    return finish(&r, st, out, count);
}

/* Bytes read from the file at a time. */
#define RAY_FILE_CHUNK ((size_t)1 << 20)

rt_status rt_rays_load(const char *path, int with_normals, rt_ray **rays, size_t *count,
                       rt_error *err) {
    *rays = NULL;
    *count = 0;
    int fd = -1;
    uint64_t size = 0;
    rt_status st = rt_open_input(path, "ray file", RT_MAX_RAY_FILE_BYTES, &fd, &size, err);
    if (st != RT_OK) return st;
    /* The file is read a chunk at a time and parsed line by line, so that
     * memory is the rays and one line, and a binary file (a NUL byte) is
     * refused at its first line, not after the whole file is read. */
    ray_reader r = {path, with_normals ? 11 : 8, NULL, 0, 0, 0, err};
    char *chunk = malloc(RAY_FILE_CHUNK), *line = malloc(RT_MAX_RAY_LINE_BYTES + 1);
    size_t line_len = 0;
    uint64_t total = 0;
    if (!chunk || !line)
        st = rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0, "out of memory");
    while (st == RT_OK) {
        ssize_t got = read(fd, chunk, RAY_FILE_CHUNK);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            st = rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot read the ray file: %s",
                              strerror(errno));
            break;
        }
        total += (uint64_t)got;
        if (total > RT_MAX_RAY_FILE_BYTES) {
            st = rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                              "the ray file grew beyond the limit of %llu bytes while read",
                              (unsigned long long)RT_MAX_RAY_FILE_BYTES);
            break;
        }
        const int last = got == 0;
        for (size_t at = 0; st == RT_OK && (at < (size_t)got || (last && line_len));) {
            const char *p = chunk + at;
            const char *eol = last ? NULL : memchr(p, '\n', (size_t)got - at);
            size_t part = eol ? (size_t)(eol - p) : (size_t)got - at;
            /* A NUL byte fails the line now, before more of it is read. */
            if (memchr(p, '\0', part)) {
                r.lineno++;
                st = rt_error_set(err, RT_ERROR_PARSE, path, line_number(&r), 0,
                                  "a NUL byte in the line (a binary file?)");
                break;
            }
            if (line_len + part > RT_MAX_RAY_LINE_BYTES) {
                r.lineno++;
                st = rt_error_set(err, RT_ERROR_UNSUPPORTED, path, line_number(&r), 0,
                                  "the line is longer than the limit of %zu bytes",
                                  (size_t)RT_MAX_RAY_LINE_BYTES);
                break;
            }
            memcpy(line + line_len, p, part);
            line_len += part;
            at += part;
            if (eol || last) {
                line[line_len] = '\0';
                st = take_line(&r, line, line_len);
                line_len = 0;
                at += eol ? 1 : 0;
            }
        }
        if (last) break;
    }
    close(fd);
    free(chunk);
    free(line);
    return finish(&r, st, rays, count);
}

rt_status rt_hits_write(const char *path, const rt_hit *hits, size_t count, int with_instances,
                        rt_error *err) {
    rt_atomic_file out;
    rt_status st = rt_atomic_file_open(&out, path, "hit file", err);
    if (st != RT_OK) return st;
    FILE *f = out.stream;
    for (size_t i = 0; i < count; i++) {
        const rt_hit *h = &hits[i];
        if (h->hit)
            fprintf(f, "1 %.9g %.9g %.9g %u", (double)h->t, (double)h->u, (double)h->v, h->prim);
        else
            fputs("0 inf 0 0 -1", f);
        if (with_instances) {
            if (h->hit)
                fprintf(f, " %u", h->inst);
            else
                fputs(" -1", f);
        }
        fputc('\n', f);
    }
    return rt_atomic_file_commit(&out, err);
}

rt_status rt_hits_check_output(const char *path, rt_error *err) {
    return rt_atomic_file_check(path, "hit file", err);
}
