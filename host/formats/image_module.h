/* SPDX-License-Identifier: Apache-2.0 */
/* image_module.h - the interface between the library and its image module
 * (librtcl_image.so, host/image_oiio/), which reads and writes the formats
 * that need OpenImageIO (PNG, EXR and whatever else OIIO reads).
 *
 * The module is loaded with dlopen on the first such read or write, so that
 * programs that never touch those formats (rtcl --help, info, trace,
 * devices) do not map OpenImageIO and its ~250 libraries at start-up. The
 * module exports one symbol, RT_IMAGE_MODULE_SYMBOL, returning this table;
 * it calls nothing in the library (it has its own copy of the error
 * formatting), so it works beside the static and the shared library alike. */
#ifndef RT_IMAGE_MODULE_H
#define RT_IMAGE_MODULE_H

#include <stddef.h>

#include "formats/image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever the table or the structs it passes change; the loader
 * refuses a module of another version (a stale install) by name. */
#define RT_IMAGE_MODULE_ABI 2

#define RT_IMAGE_MODULE_FILE   "librtcl_image.so"
#define RT_IMAGE_MODULE_SYMBOL "rtcl_image_module"

typedef struct rt_image_module {
    int abi;             /* RT_IMAGE_MODULE_ABI of the module's build */
    size_t image_size;   /* sizeof(rt_image) there */
    size_t error_size;   /* sizeof(rt_error) there */
    const char *library; /* what it encodes with, "OpenImageIO 2.4.7" */
    /* Encodes image in the format of path's extension (PNG or EXR) into a
     * new buffer (*bytes, to free() by the caller; *size bytes); nothing is
     * written: the library writes the file (base/atomic_file.h). metadata:
     * rt_image_write_options.metadata. rt_image_write's errors otherwise. */
    rt_status (*encode)(const char *path, const rt_image *image, int metadata,
                        unsigned char **bytes, size_t *size, rt_error *err);
    /* rt_image_read's contract (image.h); it takes any image OIIO reads. */
    rt_status (*read)(const char *path, rt_image *out, rt_error *err);
} rt_image_module;

typedef const rt_image_module *(*rt_image_module_entry)(void);

/* The module on first use, NULL when it cannot be had; then err (if not
 * NULL) says why, naming the places looked in and what to install. Thread-
 * safe; the module stays loaded. Defined in formats/image_load.c. */
const rt_image_module *rt_image_module_get(rt_error *err);

#ifdef __cplusplus
}
#endif
#endif /* RT_IMAGE_MODULE_H */
