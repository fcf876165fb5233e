/* SPDX-License-Identifier: Apache-2.0 */
/* image_check.c - image_check.h. */
#include "formats/image_check.h"

#include <stdint.h>

#include "base/error.h"

int rt_image_value_count(int width, int height, int channels, size_t *out) {
    if (width < 0 || height < 0 || channels < 0) return 0;
    size_t n = (size_t)width;
    if (height && n > SIZE_MAX / sizeof(float) / (size_t)height) return 0;
    n *= (size_t)height;
    if (channels && n > SIZE_MAX / sizeof(float) / (size_t)channels) return 0;
    *out = n * (size_t)channels;
    return 1;
}

rt_status rt_image_check(const rt_image *image, const char *what, const char *path, size_t *count,
                         rt_error *err) {
    if (!image)
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, path, 0, 0, "%s image is NULL", what);
    if (image->width <= 0 || image->height <= 0 || image->channels <= 0)
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, path, 0, 0,
                            "%s image has size %dx%d with %d channels (all must be > 0)", what,
                            image->width, image->height, image->channels);
    if (!rt_image_value_count(image->width, image->height, image->channels, count))
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, path, 0, 0,
                            "%s image size %dx%dx%d overflows", what, image->width, image->height,
                            image->channels);
    if (!image->pixels)
        return rt_error_set(err, RT_ERROR_INVALID_ARGUMENT, path, 0, 0, "%s image has no pixels",
                            what);
    return RT_OK;
}
