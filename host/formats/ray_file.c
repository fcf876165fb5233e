/* ray_file.c - see ray_file.h. */
#include "formats/ray_file.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/file_read.h"
#include "rt_shared.h"

rt_status rt_rays_parse(const char *text, size_t len, const char *name, int with_normals,
                        rt_ray **out, size_t *count, rt_error *err) {
    *out = NULL;
    *count = 0;
    const int want = with_normals ? 11 : 8;
    size_t n = 0, cap = 1024;
    rt_ray *rays = malloc(cap * sizeof *rays);
    if (!rays) return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, name, 0, 0, "out of memory");
    /* A 4 GiB file of newlines has more lines than an int counts: the count
     * is 64-bit and clamped only for the message. */
    uint64_t lineno = 0;
    rt_status st = RT_OK;
    /* Line by line, of any length; a line ends at '\n' or at the end of the
     * text. The text is NUL-terminated, so strtof stops at the text's end;
     * within the text, a number that strtof reads past the line's end (it
     * skips newlines as blanks) is not taken. */
    for (size_t at = 0; st == RT_OK && at < len;) {
        const char *p = text + at, *eol = memchr(p, '\n', len - at);
        const size_t line_len = eol ? (size_t)(eol - p) : len - at;
        at += line_len + 1;
        lineno++;
        const int line = lineno > INT32_MAX ? INT32_MAX : (int)lineno;
        if (memchr(p, '\0', line_len)) {
            st = rt_error_set(err, RT_ERROR_PARSE, name, line, 0,
                              "a NUL byte in the line (a binary file?)");
            break;
        }
        const char *const end_of_line = p + line_len;
        while (*p == ' ' || *p == '\t') p++;
        if (p == end_of_line || *p == '#' || *p == '\r') continue;
        float v[11];
        int got = 0;
        while (got < want + 1) {
            char *end;
            float x = strtof(p, &end);
            if (end == p || end > end_of_line) break;
            if (got < want) v[got] = x;
            got++;
            p = end;
        }
        while (p < end_of_line && (*p == ' ' || *p == '\t' || *p == '\r')) p++;
        if (got != want || p < end_of_line) {
            const int rest =
                p < end_of_line ? (int)(end_of_line - p > 41 ? 41 : end_of_line - p) : 0;
            st = rt_error_set(err, RT_ERROR_PARSE, name, line, 0,
                              "expected %d numbers 'ox oy oz dx dy dz tmin tmax%s'%s%.*s%s", want,
                              with_normals ? " nx ny nz" : "", rest ? ", found: " : "",
                              rest > 40 ? 40 : rest, p, rest > 40 ? "..." : "");
            break;
        }
        if (n == cap) {
            rt_ray *r = realloc(rays, 2 * cap * sizeof *rays);
            if (!r) {
                st = rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, name, 0, 0, "out of memory");
                break;
            }
            rays = r;
            cap *= 2;
        }
        rt_ray *r = &rays[n++];
        memcpy(r->org, v, sizeof r->org);
        memcpy(r->dir, v + 3, sizeof r->dir);
        r->tmin = v[6];
        r->tmax = v[7];
        if (with_normals) { /* off the surface, on the side the ray leaves to */
            float d = rt_dot3(v + 8, r->dir);
            rt_offset_point(v, v + 8, d >= 0.0f ? 1.0f : -1.0f, r->org);
        }
    }
    if (st != RT_OK || n == 0) {
        free(rays);
        rays = NULL;
    }
    if (st == RT_OK) {
        *out = rays;
        *count = n;
    }
    return st;
}

rt_status rt_rays_load(const char *path, int with_normals, rt_ray **rays, size_t *count,
                       rt_error *err) {
    *rays = NULL;
    *count = 0;
    char *text;
    size_t len;
    rt_status st = rt_read_file(path, "ray file", RT_MAX_RAY_FILE_BYTES, &text, &len, err);
    if (st != RT_OK) return st;
    st = rt_rays_parse(text, len, path, with_normals, rays, count, err);
    free(text);
    return st;
}
