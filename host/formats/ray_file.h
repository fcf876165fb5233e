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

/* Reads the ray file at path (a regular file of at most
 * RT_MAX_RAY_FILE_BYTES, base/file_read.h) and parses it as above, reading
 * it a chunk at a time: memory is the rays and one line (of at most
 * RT_MAX_RAY_LINE_BYTES, else RT_ERROR_UNSUPPORTED with file:line), and a
 * NUL byte fails the file at its line before the rest is read. */
rt_status rt_rays_load(const char *path, int with_normals, rt_ray **rays, size_t *count,
                       rt_error *err);

/* Writes the hit file of `rtcl trace --out`: per ray one line "1 t u v prim"
 * (t, u, v with %.9g, so they read back as the same floats) or "0 inf 0 0 -1"
 * for a miss, followed by " inst" (" -1" for a miss) when with_instances.
 * Whole or not at all (base/atomic_file.h); err names the file. */
rt_status rt_hits_write(const char *path, const rt_hit *hits, size_t count, int with_instances,
                        rt_error *err);

/* Whether rt_hits_write could write path (its folder exists and is
 * writable; rt_atomic_file_check), checked before the rays are traced. */
rt_status rt_hits_check_output(const char *path, rt_error *err);

#endif /* RT_RAY_FILE_H */
