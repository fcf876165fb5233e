/* SPDX-License-Identifier: Apache-2.0 */
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

/* rt_image, rt_image_write (with rt_image_write_with and
 * rt_image_check_output), rt_image_read, rt_image_free, rt_image_diff and
 * rt_image_compare are public: declared in rt.h. */

/* The largest image read (rt_image_read), checked from its header before
 * any pixel memory is allocated: at most RT_MAX_IMAGE_READ_PIXELS pixels
 * (32768 x 32768, the largest frame rtcl renders) and
 * RT_MAX_IMAGE_READ_CHANNELS channels; beyond them RT_ERROR_UNSUPPORTED. */
#define RT_MAX_IMAGE_READ_PIXELS   ((uint64_t)1 << 30)
#define RT_MAX_IMAGE_READ_CHANNELS 16

#ifdef __cplusplus
}
#endif
#endif /* RT_IMAGE_H */
