/* SPDX-License-Identifier: Apache-2.0 */
/* file_read.h - reading a whole input file (scene, OBJ, MTL, ray file) with
 * its size known up front, and the limits on input sizes (docs/ROBUSTNESS.md,
 * "Limits"). */
#ifndef RT_FILE_READ_H
#define RT_FILE_READ_H

#include <stddef.h>
#include <stdint.h>

#include "rt.h"

/* The largest files read, in bytes. Beyond them the reader refuses the file
 * with RT_ERROR_UNSUPPORTED before reading any of it. */
#define RT_MAX_SCENE_FILE_BYTES ((uint64_t)64 << 20) /* a .json scene: 64 MiB */
#define RT_MAX_OBJ_FILE_BYTES   ((uint64_t)4 << 30)  /* an .obj or .mtl file: 4 GiB */
#define RT_MAX_RAY_FILE_BYTES   ((uint64_t)4 << 30)  /* a ray file of rtcl trace: 4 GiB */
#define RT_MAX_RAY_LINE_BYTES   ((size_t)1 << 20)    /* one line of a ray file: 1 MiB */

/* Opens path for reading as rt_read_file does (only a regular file of at
 * most max_bytes, never blocking on a FIFO; the same errors) and gives its
 * descriptor (to close) and size, for readers that read a file in parts. */
rt_status rt_open_input(const char *path, const char *what, uint64_t max_bytes, int *fd,
                        uint64_t *size, rt_error *err);

/* Reads the file at path into a new NUL-terminated buffer (*text, to free;
 * *len bytes without the terminator). what names the file's kind in
 * messages ("scene file", "OBJ file"). Only regular files are read: the file
 * is opened without blocking (a FIFO never blocks open) and anything else (a
 * directory, a FIFO, a device such as /dev/zero, a socket) is refused with
 * RT_ERROR_IO and its kind; a file of more than max_bytes bytes with
 * RT_ERROR_UNSUPPORTED naming the limit. The buffer is allocated once, from
 * the size fstat gives; a file that changes size while read is an error. */
rt_status rt_read_file(const char *path, const char *what, uint64_t max_bytes, char **text,
                       size_t *len, rt_error *err);

#endif /* RT_FILE_READ_H */
