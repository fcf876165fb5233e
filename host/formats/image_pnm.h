/* SPDX-License-Identifier: Apache-2.0 */
/* image_pnm.h - PPM/PGM and PFM in plain C: the formats the library reads
 * and writes without its image module (image_module.h), so that a build
 * without OpenImageIO still writes images, and they need no module at run
 * time. */
#ifndef RT_IMAGE_PNM_H
#define RT_IMAGE_PNM_H

#include <stddef.h>

#include "formats/image.h"

/* Whether bytes (the start of a file, size of them) are a PNM file this
 * reader takes (P2, P3, P5, P6) or a PFM file (Pf, PF). */
int rt_pnm_recognised(const unsigned char *bytes, size_t size);

/* Encodes image as binary PPM (3 channels, P6) or PGM (1 channel, P5), 8
 * bits: values clamped to [0,1] and rounded to the nearest of 256 levels,
 * NaN as 0. *out (to free) receives the file's bytes. The channel count is
 * checked by the caller. */
rt_status rt_pnm_encode(const char *path, const rt_image *image, unsigned char **out, size_t *size,
                        rt_error *err);

/* Encodes image as PFM: 32-bit little-endian floats, rows bottom to top as
 * the format has them, "PF" for 3 channels, "Pf" for 1. Values are stored
 * exactly (NaN and infinities included). */
rt_status rt_pfm_encode(const char *path, const rt_image *image, unsigned char **out, size_t *size,
                        rt_error *err);

/* Decodes a PNM (P2, P3, P5, P6; maxval 1..65535, levels k read as
 * k / maxval correctly rounded, so 8-bit k is exactly k / 255.0f) or PFM file
 * (either byte order; the scale's magnitude is ignored, as most writers set
 * it to 1) of size bytes. A malformed or cut-short file is RT_ERROR_PARSE with
 * path and the reason. */
rt_status rt_pnm_decode(const char *path, const unsigned char *bytes, size_t size, rt_image *out,
                        rt_error *err);

#endif /* RT_IMAGE_PNM_H */
