/* cli_anim.c - the --update and --stats parts of the dynamic-scene commands. */
#include "cli_anim.h"
#include "json_out.h"

#include <stdio.h>

#include "cli_util.h"
#include "scene/scene.h"

int cli_update_policy(const char *command, const char *text, rt_update_policy *out) {
    if (rt_update_policy_parse(text, out)) return 1;
    cli_error(
        command,
        "--update: unknown policy '%s' (sah, refit, lbvh, auto; or rebuild = sah, fast = lbvh)",
        text);
    return 0;
}

void cli_apply_update(rt_scene *scene, rt_update_policy policy) {
    for (uint32_t m = 0; m < scene->mesh_count; m++) rt_mesh_set_update(scene, m, policy);
}

static const char *action_name(rt_update_action a) {
    switch (a) {
    case RT_ACTION_NONE:
        return "none";
    case RT_ACTION_BUILD:
        return "build";
    case RT_ACTION_REFIT:
        return "refit";
    case RT_ACTION_LBVH:
        return "lbvh";
    case RT_ACTION_REBUILD:
        return "rebuild";
    }
    return "?";
}

void cli_print_update_json(const rt_renderer *renderer, const rt_scene *scene) {
    rt_update_stats u;
    rt_renderer_update_stats(renderer, &u);
    printf("\"update\": [");
    for (uint32_t i = 0; i < u.mesh_count; i++) {
        const rt_mesh_update *m = &u.meshes[i];
        printf("%s{\"mesh\": %u, \"name\": ", i ? ", " : "", m->mesh);
        json_out_string(m->mesh < scene->mesh_count ? scene->meshes[m->mesh].name : "");
        printf(", \"action\": \"%s\", \"ms\": %.3f, \"sah\": %.4f}", action_name(m->action), m->ms,
               m->sah);
    }
    printf("], \"object_bvh_ms\": %.3f, \"layout_ms\": %.3f, \"layout_in_place\": %s, "
           "\"layout_bytes\": %llu, \"camera_only\": %s",
           u.object_bvh_ms, u.layout_ms, u.layout_in_place ? "true" : "false",
           (unsigned long long)u.layout_bytes, u.camera_only ? "true" : "false");
}
