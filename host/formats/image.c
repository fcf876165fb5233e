/* SPDX-License-Identifier: Apache-2.0 */
/* image.c - image.h's calls: PPM/PGM and PFM here in C (image_pnm.c), the
 * other formats of the table (image_formats.def: PNG, JPEG, TIFF, EXR, ...)
 * and reading whatever OpenImageIO reads through the image module, loaded on
 * first use (image_load.c). Comparing and freeing need no module. */
#include "formats/image.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "formats/image_check.h"
#include "base/file_read.h"
#include "formats/image_module.h"
#include "formats/image_pnm.h"

/* The largest PPM or PFM file read: a 32768 x 32768 RGB float image. */
#define RT_MAX_PNM_FILE_BYTES ((uint64_t)12 << 30)

/* The format of path's extension, checked for writing: RT_OK, or
 * RT_ERROR_UNSUPPORTED naming the known ones (the table's list) and, for a
 * format of the image module, why the module cannot be had. */
static rt_status check_format(const char *path, const rt_image_format **format,
                              const rt_image_module **module, rt_error *err) {
    *format = rt_image_format_of(path);
    *module = NULL;
    if (!*format)
        return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                            "unknown image file extension (supported: %s)", rt_image_format_list());
    if ((*format)->module) {
        rt_error why;
        *module = rt_image_module_get(&why);
        if (!*module)
            return rt_error_set(err, why.status, path, 0, 0, "cannot write %s: %s", (*format)->name,
                                why.message);
    }
    return RT_OK;
}

rt_status rt_image_check_output(const char *path, rt_error *err) {
    if (!path || !path[0])
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, NULL, 0, 0, "no output file name");
    const rt_image_format *format;
    const rt_image_module *module;
    rt_status st = check_format(path, &format, &module, err);
    if (st == RT_OK) st = rt_atomic_file_check(path, "image file", err);
    return st;
}

rt_status rt_image_write(const char *path, const rt_image *image, rt_error *err) {
    return rt_image_write_with(path, image, NULL, err);
}

rt_status rt_image_write_with(const char *path, const rt_image *image,
                              const rt_image_write_options *options, rt_error *err) {
    if (!path || !path[0])
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, NULL, 0, 0, "no output file name");
    size_t count = 0;
    rt_status st = rt_image_check(image, "the", path, &count, err);
    if (st != RT_OK) return st;
    const rt_image_format *format;
    const rt_image_module *module;
    st = check_format(path, &format, &module, err);
    if (st != RT_OK) return st;
    int pfm = !module && format->bits == 32;
    if (!module) {
        if (image->channels != 1 && image->channels != 3)
            return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                                "%s holds 1 or 3 channels, not %d (use .png or .exr)",
                                pfm ? "PFM" : "PPM", image->channels);
    }
    /* The whole file is encoded in memory, then written by the one writer
     * of every output (base/atomic_file.h): complete or not at all. */
    unsigned char *bytes = NULL;
    size_t size = 0;
    if (module)
        st = module->encode(path, image, options && options->metadata, &bytes, &size, err);
    else if (!pfm)
        st = rt_pnm_encode(path, image, &bytes, &size, err);
    else
        st = rt_pfm_encode(path, image, &bytes, &size, err);
    if (st == RT_OK) st = rt_atomic_file_write(path, "image file", bytes, size, err);
    free(bytes);
    return st;
}

rt_status rt_image_read(const char *path, rt_image *out, rt_error *err) {
    if (!out)
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, path, 0, 0, "output image is NULL");
    memset(out, 0, sizeof *out);
    if (!path || !path[0])
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, NULL, 0, 0, "no input file name");
    /* The format is told by the first bytes, not the name. */
    FILE *probe = fopen(path, "rb");
    if (!probe)
        return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot open: %s", strerror(errno));
    unsigned char head[2] = {0, 0};
    size_t got = fread(head, 1, 2, probe);
    int read_errno = ferror(probe) ? errno : 0;
    fclose(probe);
    if (read_errno)
        return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot read: %s", strerror(read_errno));
    if (rt_pnm_recognised(head, got)) {
        char *bytes = NULL;
        size_t size = 0;
        rt_status st = rt_read_file(path, "image file", RT_MAX_PNM_FILE_BYTES, &bytes, &size, err);
        if (st == RT_OK) st = rt_pnm_decode(path, (const unsigned char *)bytes, size, out, err);
        free(bytes);
        return st;
    }
    rt_error why;
    const rt_image_module *module = rt_image_module_get(&why);
    if (!module)
        return rt_error_set(err, why.status, path, 0, 0,
                            "not a PPM or PFM file, and other formats need the image module: %s",
                            why.message);
    return module->read(path, out, err);
}

void rt_image_free(rt_image *image) {
    if (!image) return;
    free(image->pixels);
    image->pixels = NULL;
}

/* The difference of two channel values. Equal values (infinities included)
 * differ by 0, two NaNs count as equal, and a NaN against a number differs by
 * infinity, so that a NaN in one image never passes as a match. */
static double channel_difference(float a, float b) {
    if (a == b) return 0.0;
    int a_nan = isnan(a), b_nan = isnan(b);
    if (a_nan && b_nan) return 0.0;
    if (a_nan || b_nan) return INFINITY;
    return fabs((double)a - (double)b);
}

rt_status rt_image_compare(const rt_image *a, const rt_image *b, rt_image_diff *result,
                           rt_image *diff_out, rt_error *err) {
    if (diff_out) memset(diff_out, 0, sizeof *diff_out);
    if (!result) return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "result is NULL");
    size_t count = 0, count_b = 0;
    rt_status st = rt_image_check(a, "first", NULL, &count, err);
    if (st != RT_OK) return st;
    st = rt_image_check(b, "second", NULL, &count_b, err);
    if (st != RT_OK) return st;
    if (a->width != b->width || a->height != b->height || a->channels != b->channels)
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                       "images differ in size: %dx%d with %d channels against %dx%d with %d "
                       "channels",
                       a->width, a->height, a->channels, b->width, b->height, b->channels);
    float *diff = NULL;
    if (diff_out) {
        diff = malloc(count * sizeof(float));
        if (!diff)
            return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "no memory for the difference image");
    }
    const size_t channels = (size_t)a->channels;
    const size_t pixels = count / channels;
    double max_abs = 0.0, sum_squares = 0.0;
    uint64_t differing = 0;
    size_t first = SIZE_MAX;
    for (size_t p = 0; p < pixels; p++) {
        int pixel_differs = 0;
        for (size_t c = 0; c < channels; c++) {
            size_t i = p * channels + c;
            double d = channel_difference(a->pixels[i], b->pixels[i]);
            if (d > 0.0) pixel_differs = 1;
            if (d > max_abs) max_abs = d;
            sum_squares += d * d;
            if (diff) diff[i] = (float)d;
        }
        if (pixel_differs) {
            if (first == SIZE_MAX) first = p;
            differing++;
        }
    }
    double mse = sum_squares / (double)count;
    result->max_abs = max_abs;
    result->rmse = sqrt(mse);
    result->psnr = mse > 0.0 ? -10.0 * log10(mse) : INFINITY;
    result->differing = differing;
    result->pixels = pixels;
    const size_t width = (size_t)a->width;
    result->first_x = first == SIZE_MAX ? -1 : (int)(first % width);
    result->first_y = first == SIZE_MAX ? -1 : (int)(first / width);
    if (diff_out) {
        diff_out->width = a->width;
        diff_out->height = a->height;
        diff_out->channels = a->channels;
        diff_out->pixels = diff;
    }
    return RT_OK;
}
