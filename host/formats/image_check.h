/* SPDX-License-Identifier: Apache-2.0 */
/* image_check.h - the checks of an image's size that the library and the
 * image module (host/image_oiio/) both make, compiled into each (the module
 * calls nothing in the library). */
#ifndef RT_FORMATS_IMAGE_CHECK_H
#define RT_FORMATS_IMAGE_CHECK_H

#include <stddef.h>

#include "formats/image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* width * height * channels in *out: 1, or 0 when a dimension is negative or
 * the float values would not fit in memory (SIZE_MAX bytes). */
int rt_image_value_count(int width, int height, int channels, size_t *out);

/* Checks that image is usable (not NULL, every dimension > 0, a size that
 * fits in memory, pixels set) and puts its float count in *count. what
 * names it in the message ("the", "first"); path, if not NULL, is the file
 * the error is about. RT_OK or RT_ERROR_INVALID_ARGUMENT. */
rt_status rt_image_check(const rt_image *image, const char *what, const char *path, size_t *count,
                         rt_error *err);

#ifdef __cplusplus
}
#endif
#endif /* RT_FORMATS_IMAGE_CHECK_H */
