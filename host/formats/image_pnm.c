/* SPDX-License-Identifier: Apache-2.0 */
/* image_pnm.c - PPM/PGM and PFM encoding and decoding (image_pnm.h). */
#include "formats/image_pnm.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "scene/scene.h" /* RT_MAX_IMAGE_SIDE */

int rt_pnm_recognised(const unsigned char *bytes, size_t size) {
    if (size < 2 || bytes[0] != 'P') return 0;
    return strchr("2356fF", bytes[1]) != NULL && bytes[1] != '\0';
}

/* Clamps to [0,1] and rounds to the nearest of 256 levels. NaN becomes 0 so
 * that a bad pixel shows as black rather than as an arbitrary value. */
static unsigned char to_8bit(float v) {
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 255;
    return (unsigned char)floor((double)v * 255.0 + 0.5);
}

/* A new file buffer: the header (magic 'P' kind, the size, then the scale
 * line, "255" or "-1.0") and room for width * height * channels values of
 * per_value bytes after it, at bytes + *header. NULL on error (err set). */
static unsigned char *start_file(const char *path, const rt_image *image, char kind,
                                 const char *scale, size_t per_value, size_t *header, size_t *total,
                                 rt_error *err) {
    char text[64];
    int n =
        snprintf(text, sizeof text, "P%c\n%d %d\n%s\n", kind, image->width, image->height, scale);
    *header = (size_t)n;
    size_t values = (size_t)image->width * (size_t)image->height * (size_t)image->channels;
    if (values > (SIZE_MAX - *header) / per_value) {
        rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, path, 0, 0, "image too large");
        return NULL;
    }
    *total = *header + values * per_value;
    unsigned char *bytes = malloc(*total);
    if (!bytes) {
        rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0, "no memory for %zu bytes", *total);
        return NULL;
    }
    memcpy(bytes, text, *header);
    return bytes;
}

/* PGM/PPM (8 bits a value, top row first) or, when pfm, PFM (little-endian
 * floats, bottom row first). */
static rt_status encode(const char *path, const rt_image *image, int pfm, unsigned char **out,
                        size_t *size, rt_error *err) {
    size_t n, total;
    char kind = image->channels == 1 ? (pfm ? 'f' : '5') : (pfm ? 'F' : '6');
    unsigned char *bytes =
        start_file(path, image, kind, pfm ? "-1.0" : "255", pfm ? 4 : 1, &n, &total, err);
    if (!bytes) return err ? err->status : RT_ERROR_OUT_OF_MEMORY;
    unsigned char *p = bytes + n;
    size_t row = (size_t)image->width * (size_t)image->channels;
    if (!pfm)
        for (size_t i = 0; i < total - n; i++) p[i] = to_8bit(image->pixels[i]);
    else
        for (int y = image->height - 1; y >= 0; y--) { /* PFM stores the bottom row first */
            const float *src = image->pixels + (size_t)y * row;
            for (size_t i = 0; i < row; i++, p += 4) {
                uint32_t u;
                memcpy(&u, &src[i], 4);
                p[0] = (unsigned char)u; /* little-endian, as the negative scale says */
                p[1] = (unsigned char)(u >> 8);
                p[2] = (unsigned char)(u >> 16);
                p[3] = (unsigned char)(u >> 24);
            }
        }
    *out = bytes;
    *size = total;
    return RT_OK;
}

rt_status rt_pnm_encode(const char *path, const rt_image *image, unsigned char **out, size_t *size,
                        rt_error *err) {
    return encode(path, image, 0, out, size, err);
}

rt_status rt_pfm_encode(const char *path, const rt_image *image, unsigned char **out, size_t *size,
                        rt_error *err) {
    return encode(path, image, 1, out, size, err);
}

/* ---- decoding --------------------------------------------------------- */

typedef struct cursor {
    const unsigned char *p, *end;
} cursor;

static int is_space(unsigned char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/* Skips whitespace and '#' comments (to the end of their line). */
static void skip_space(cursor *c) {
    while (c->p < c->end) {
        if (*c->p == '#') {
            while (c->p < c->end && *c->p != '\n') c->p++;
        } else if (is_space(*c->p)) {
            c->p++;
        } else {
            break;
        }
    }
}

/* A decimal integer in [0, max]; -1 when there is none or it is larger. */
static long read_uint(cursor *c, long max) {
    skip_space(c);
    if (c->p >= c->end || *c->p < '0' || *c->p > '9') return -1;
    long v = 0;
    while (c->p < c->end && *c->p >= '0' && *c->p <= '9') {
        v = v * 10 + (*c->p++ - '0');
        if (v > max) return -1;
    }
    return v;
}

static rt_status parse_fail(const char *path, rt_error *err, const char *what) {
    return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0, "%s", what);
}

static rt_status alloc_pixels(const char *path, long width, long height, int channels,
                              rt_image *out, rt_error *err) {
    size_t count = (size_t)width * (size_t)height * (size_t)channels;
    out->pixels = malloc(count * sizeof(float));
    if (!out->pixels)
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0,
                            "no memory for %ldx%ld pixels with %d channels", width, height,
                            channels);
    out->width = (int)width;
    out->height = (int)height;
    out->channels = channels;
    return RT_OK;
}

static rt_status decode_pfm(const char *path, cursor *c, int channels, rt_image *out,
                            rt_error *err) {
    long width = read_uint(c, RT_MAX_IMAGE_SIDE), height = read_uint(c, RT_MAX_IMAGE_SIDE);
    if (width <= 0 || height <= 0)
        return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0,
                            "bad PFM size (width and height 1..%d)", RT_MAX_IMAGE_SIDE);
    skip_space(c);
    char scale_text[64];
    size_t n = 0;
    while (c->p < c->end && !is_space(*c->p) && n + 1 < sizeof scale_text)
        scale_text[n++] = (char)*c->p++;
    scale_text[n] = '\0';
    char *stop;
    double scale = strtod(scale_text, &stop);
    if (n == 0 || *stop || scale == 0.0 || !isfinite(scale))
        return parse_fail(path, err, "bad PFM scale (a non-zero number)");
    if (c->p >= c->end || !is_space(*c->p)) return parse_fail(path, err, "PFM header cut short");
    c->p++; /* one whitespace character before the floats */
    size_t row = (size_t)width * (size_t)channels;
    if ((size_t)(c->end - c->p) < row * (size_t)height * 4)
        return parse_fail(path, err, "PFM file cut short: fewer floats than its size says");
    rt_status st = alloc_pixels(path, width, height, channels, out, err);
    if (st != RT_OK) return st;
    int little = scale < 0.0;
    for (long y = height - 1; y >= 0; y--) {
        float *dst = out->pixels + (size_t)y * row;
        for (size_t i = 0; i < row; i++, c->p += 4) {
            const unsigned char *b = c->p;
            uint32_t u = little ? (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                                      (uint32_t)b[3] << 24
                                : (uint32_t)b[3] | (uint32_t)b[2] << 8 | (uint32_t)b[1] << 16 |
                                      (uint32_t)b[0] << 24;
            memcpy(&dst[i], &u, 4);
        }
    }
    return RT_OK;
}

static rt_status decode_pnm(const char *path, cursor *c, char kind, rt_image *out, rt_error *err) {
    int channels = (kind == '3' || kind == '6') ? 3 : 1;
    int binary = kind == '5' || kind == '6';
    long width = read_uint(c, RT_MAX_IMAGE_SIDE), height = read_uint(c, RT_MAX_IMAGE_SIDE);
    if (width <= 0 || height <= 0)
        return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0,
                            "bad PNM size (width and height 1..%d)", RT_MAX_IMAGE_SIDE);
    long maxval = read_uint(c, 65535);
    if (maxval <= 0) return parse_fail(path, err, "bad PNM maximum value (1..65535)");
    size_t count = (size_t)width * (size_t)height * (size_t)channels;
    if (!binary && count > 0 && (size_t)(c->end - c->p) < 2 * count - 1)
        /* Each level takes a digit and a separator: the file is checked to
         * be long enough before the pixels are allocated. */
        return parse_fail(path, err, "PNM file cut short: fewer pixels than its size says");
    if (binary) {
        if (c->p >= c->end || !is_space(*c->p))
            return parse_fail(path, err, "PNM header cut short");
        c->p++; /* one whitespace character before the binary levels */
        size_t per = maxval > 255 ? 2 : 1;
        if ((size_t)(c->end - c->p) < count * per)
            return parse_fail(path, err, "PNM file cut short: fewer pixels than its size says");
    }
    rt_status st = alloc_pixels(path, width, height, channels, out, err);
    if (st != RT_OK) return st;
    const float top = (float)maxval;
    for (size_t i = 0; i < count; i++) {
        long k;
        if (!binary) {
            k = read_uint(c, 65535);
            if (k < 0) {
                free(out->pixels);
                memset(out, 0, sizeof *out);
                return parse_fail(path, err,
                                  c->p >= c->end ? "PNM file cut short: fewer pixels than its "
                                                   "size says"
                                                 : "bad PNM pixel value");
            }
        } else if (maxval > 255) { /* 16-bit levels are big-endian */
            k = (long)c->p[0] << 8 | c->p[1];
            c->p += 2;
        } else {
            k = *c->p++;
        }
        if (k > maxval) {
            free(out->pixels);
            memset(out, 0, sizeof *out);
            return parse_fail(path, err, "PNM pixel value above the file's maximum");
        }
        out->pixels[i] = (float)k / top; /* correctly rounded: 8-bit k reads as k / 255.0f */
    }
    return RT_OK;
}

rt_status rt_pnm_decode(const char *path, const unsigned char *bytes, size_t size, rt_image *out,
                        rt_error *err) {
    memset(out, 0, sizeof *out);
    if (!rt_pnm_recognised(bytes, size)) return parse_fail(path, err, "not a PNM or PFM file");
    cursor c = {bytes + 2, bytes + size};
    char kind = (char)bytes[1];
    if (c.p >= c.end || !is_space(*c.p)) return parse_fail(path, err, "not a PNM or PFM file");
    if (kind == 'F' || kind == 'f') return decode_pfm(path, &c, kind == 'F' ? 3 : 1, out, err);
    return decode_pnm(path, &c, kind, out, err);
}
