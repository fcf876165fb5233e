/* SPDX-License-Identifier: Apache-2.0 */
/* ray_file.h - the ray files of `rtcl trace --rays` (one ray per text line),
 * read into rt_ray arrays. The format is the one `rtcl trace --help` gives. */
#ifndef RT_RAY_FILE_H
#define RT_RAY_FILE_H

#include <stddef.h>

#include "rt.h"

/* Parses the ray file text of len bytes; text[len] must be '\0' (as
 * rt_read_file leaves it). One ray per line: "ox oy oz dx dy dz tmin tmax",
 * plus "nx ny nz" when with_normals (the origin is then a surface point with
 * that normal and is moved off the surface with rt_offset_point, to the side
 * the direction points to). Blank lines and lines starting with '#' are
 * skipped; lines may be of any length. On success *rays (to free, NULL when
 * there are none) holds *count rays; on failure *rays is NULL, *count 0, and
 * err says "name:line: reason" (a NUL byte in a line, a line without exactly
 * the numbers expected). */
rt_status rt_rays_parse(const char *text, size_t len, const char *name, int with_normals,
                        rt_ray **rays, size_t *count, rt_error *err);

/* rt_rays_load (public, rt.h) reads the ray file at path (a regular file of
 * at most RT_MAX_RAY_FILE_BYTES, base/file_read.h) a chunk at a time (lines
 * of at most RT_MAX_RAY_LINE_BYTES) and parses it as above. */

/* rt_hits_write and rt_hits_check_output (the hit files of `rtcl trace
 * --out`) are public too: rt.h. */

#endif /* RT_RAY_FILE_H */
