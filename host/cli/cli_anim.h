/* cli_anim.h - what 'rtcl render' and 'rtcl animate' share for dynamic
 * scenes: the --update policy and --time. */
#ifndef RTCL_CLI_ANIM_H
#define RTCL_CLI_ANIM_H

#include "rt.h"

/* Parses an --update value; prints the error and returns 0 when unknown. */
int cli_update_policy(const char *command, const char *text, rt_update_policy *out);

/* Gives every mesh of the scene the policy (a blend mesh follows its
 * object's first keyframe). */
void cli_apply_update(rt_scene *scene, rt_update_policy policy);

/* Writes one JSON object (no newline) with what the last frame's update did:
 * "update": [{"mesh", "name", "action", "ms", "sah"}...], "object_bvh_ms",
 * "layout_ms", "layout_in_place", "layout_bytes". */
void cli_print_update_json(const rt_renderer *renderer, const rt_scene *scene);

#endif /* RTCL_CLI_ANIM_H */
