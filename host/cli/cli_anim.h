/* SPDX-License-Identifier: Apache-2.0 */
/* cli_anim.h - what the dynamic-scene commands print: the last frame's
 * update (rtcl animate --stats). */
#ifndef RTCL_CLI_ANIM_H
#define RTCL_CLI_ANIM_H

#include "rt.h"

/* Writes one JSON object's members (no braces, no newline) with what the
 * last frame's update did: "update": [{"mesh", "name", "action", "ms",
 * "sah"}...], "object_bvh_ms", "layout_ms", "layout_in_place",
 * "layout_bytes", "camera_only". */
void cli_print_update_json(const rt_renderer *renderer, const rt_scene *scene);

#endif /* RTCL_CLI_ANIM_H */
