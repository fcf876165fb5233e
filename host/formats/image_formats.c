/* SPDX-License-Identifier: Apache-2.0 */
/* image_formats.c - the table of image formats (image_formats.def) as rt.h
 * gives it: rt_image_format_at, rt_image_format_of, rt_image_format_list. */
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "rt.h"

static const rt_image_format formats[] = {
#define RT_IMAGE_FORMAT(ext, name, bits, coder, lossy) {ext, name, bits, lossy, RT_CODER_##coder},
#define RT_CODER_MODULE                                1
#define RT_CODER_PNM                                   0
#define RT_CODER_PFM                                   0
#include "formats/image_formats.def"
#undef RT_IMAGE_FORMAT
};
#define FORMAT_COUNT ((int)(sizeof formats / sizeof formats[0]))

const rt_image_format *rt_image_format_at(int index) {
    return index >= 0 && index < FORMAT_COUNT ? &formats[index] : NULL;
}

const rt_image_format *rt_image_format_of(const char *path) {
    if (!path) return NULL;
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash + 1 : path, '.');
    if (!dot) return NULL;
    for (int i = 0; i < FORMAT_COUNT; i++)
        if (strcasecmp(dot, formats[i].extension) == 0) return &formats[i];
    return NULL;
}

/* ", " before every extension: the list starts 2 characters in. */
static const char list[] =
#define RT_IMAGE_FORMAT(ext, name, bits, coder, lossy) ", " ext
#include "formats/image_formats.def"
#undef RT_IMAGE_FORMAT
    ;

const char *rt_image_format_list(void) {
    return list + 2;
}
