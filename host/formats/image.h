/* image.h - images: write PNG, EXR, PPM/PGM and PFM by extension, read any
 * format OpenImageIO reads, compare two images. PPM/PGM and PFM are plain C
 * (image_pnm.c); PNG, EXR and the other formats go through the image module
 * librtcl_image.so (OpenImageIO), loaded on first use (image_module.h): where
 * the build or the install lacks it, those calls fail with
 * RT_ERROR_UNSUPPORTED saying so. */
#ifndef RT_IMAGE_H
#define RT_IMAGE_H

#include <stdint.h>

#include "rt.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The largest image read (rt_image_read), checked from its header before
 * any pixel memory is allocated: at most RT_MAX_IMAGE_READ_PIXELS pixels
 * (32768 x 32768, the largest frame rtcl renders) and
 * RT_MAX_IMAGE_READ_CHANNELS channels; beyond them RT_ERROR_UNSUPPORTED. */
#define RT_MAX_IMAGE_READ_PIXELS   ((uint64_t)1 << 30)
#define RT_MAX_IMAGE_READ_CHANNELS 16

typedef struct rt_image {
    int width;
    int height;
    int channels;
    float *pixels; /* row-major, top row first, channels interleaved */
} rt_image;

/* Writes pixels by the file's extension: .png and .ppm (or .pgm) store 8
 * bits per channel (values clamped to [0,1], rounded to nearest), .exr and
 * .pfm store 32-bit floats. err names the file on failure. The extension is
 * case-insensitive; any other is RT_ERROR_UNSUPPORTED, as is a .ppm or .pfm
 * with other than 1 (written as grey, P5 or Pf) or 3 channels. NaN is stored
 * as 0 in 8-bit files. An alpha channel is stored as given, never
 * premultiplied. A file that cannot be created or written in full is
 * RT_ERROR_IO with the system's reason. The file is written whole or not
 * at all (base/atomic_file.h): on any failure an existing file at path is
 * left as it was. No time stamp or other varying field is written, so equal
 * pixels give equal files. */
rt_status rt_image_write(const char *path, const rt_image *image, rt_error *err);

typedef struct rt_image_write_options {
    /* 1: PNG and EXR files record when they were written (EXR capDate, PNG
     * "Creation Time") and the software ("rtcl"), so two writes of one
     * image differ; PPM and PFM have no place for either. 0 (the default):
     * neither is written. */
    int metadata;
} rt_image_write_options;

/* rt_image_write with options (NULL: the defaults). */
rt_status rt_image_write_with(const char *path, const rt_image *image,
                              const rt_image_write_options *options, rt_error *err);

/* Whether rt_image_write could write path, checked before the work that
 * makes the image: a known extension, the image module for PNG and EXR,
 * and a folder that exists and is writable (rt_atomic_file_check). RT_OK or
 * rt_image_write's error for that fault. Nothing is created. */
rt_status rt_image_check_output(const char *path, rt_error *err);

/* Reads an image as floats in [0,1] for 8-bit files; the format is told by
 * the file's first bytes (PPM/PGM and PFM here, anything else through the
 * image module). The caller frees with
 * rt_image_free. 8- and 16-bit levels k read as exactly k / 255.0f and
 * k / 65535.0f, so an 8-bit file written from such values reads back
 * bit-identical. Subimage 0 only, all its channels. A file that cannot be
 * opened is RT_ERROR_IO; one that is not an image or is damaged or cut short
 * is RT_ERROR_PARSE (RT_ERROR_UNSUPPORTED for deep images and for images
 * beyond the limits above, refused from the header before the pixels are
 * allocated or read). On failure *out is zeroed. */
rt_status rt_image_read(const char *path, rt_image *out, rt_error *err);

void rt_image_free(rt_image *image);

typedef struct rt_image_diff {
    double max_abs;     /* largest absolute channel difference */
    double rmse;        /* over all channels */
    double psnr;        /* dB, against a peak of 1; INFINITY when identical */
    uint64_t differing; /* pixels with any channel different */
    uint64_t pixels;
    int first_x, first_y; /* first differing pixel in row order, -1 if none */
} rt_image_diff;

/* Compares a and b (same size and channel count, else RT_ERROR_INVALID_ARGUMENT).
 * If diff_out is not NULL it receives |a - b| per channel (caller frees with
 * rt_image_free; zeroed on failure). Equal values, infinities included,
 * differ by 0; NaN against NaN counts as equal, NaN against a number as an
 * infinite difference, so a NaN in one image never passes as a match. */
rt_status rt_image_compare(const rt_image *a, const rt_image *b, rt_image_diff *result,
                           rt_image *diff_out, rt_error *err);

#ifdef __cplusplus
}
#endif
#endif /* RT_IMAGE_H */
