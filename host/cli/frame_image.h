/* SPDX-License-Identifier: Apache-2.0 */
/* frame_image.h - a rendered frame (or AOV) as an image file or as display
 * colours, the same way for 'rtcl render' and 'rtcl view', so that a viewer
 * screenshot and a render of the same camera are the same file. */
#ifndef RTCL_FRAME_IMAGE_H
#define RTCL_FRAME_IMAGE_H

#include "cli_options.h"
#include "rt.h"

/* The AOV names (depth, primid, instid, normal, boxtests, tritests) and
 * their rt_aov values, for --aov. */
extern const cli_choice cli_aov_choices[];

/* Parses an AOV name (depth, primid, instid, normal, boxtests, tritests);
 * returns 1 and sets *out when known, 0 otherwise. */
int cli_parse_aov(const char *name, rt_aov *out);

/* The name of an AOV ("shaded" for RT_AOV_NONE). */
const char *cli_aov_name(rt_aov aov);

/* 1 when path names a float image format (.exr, .pfm, ...: 32 bits in the
 * library's table), which stores AOVs raw. */
int cli_is_float_format(const char *path);

/* The formats written by extension, for a help text: the library's table
 * (rt_image_format_at) grouped by bits, the lossy ones marked, into buf. */
void cli_image_formats_text(char *buf, size_t cap);

/* An option's dynamic_help (cli_options.h): help with "{formats}" replaced by
 * cli_image_formats_text. */
void cli_image_formats_help(const char *help, char *buf, size_t cap);

/* Makes an AOV displayable: a new 3-channel image (caller frees with free()),
 * depth and counters scaled to [0,1] by their maximum, ids in false colour,
 * normals as 0.5 + 0.5 n. NULL when out of memory. */
float *cli_aov_to_display(const rt_framebuffer *fb, rt_aov aov);

/* Writes fb to path by its extension: the shaded image as it is; an AOV raw
 * in .exr, else through cli_aov_to_display. metadata: the time of writing
 * and the software in PNG and EXR files (rt_image_write_options). Whole or
 * not at all; err names the file on failure. */
rt_status cli_frame_write(const char *path, const rt_framebuffer *fb, rt_aov aov, int metadata,
                          rt_error *err);

/* Whether cli_frame_write could write path (format and folder), checked
 * before the frame is rendered: RT_OK or the fault in err. */
rt_status cli_frame_check(const char *path, rt_error *err);

#endif /* RTCL_FRAME_IMAGE_H */
