/* cli_anim.c - the --stats part of the dynamic-scene commands (cli_anim.h). */
#include "cli_anim.h"

#include <stdio.h>

#include "engines/bench_print.h"

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
        rt_mesh_info info;
        json_out_string(rt_mesh_describe(scene, m->mesh, &info) == RT_OK ? info.name : "");
        printf(", \"action\": \"%s\", \"ms\": %.3f, \"sah\": %.4f}", action_name(m->action), m->ms,
               m->sah);
    }
    printf("], \"object_bvh_ms\": %.3f, \"layout_ms\": %.3f, \"layout_in_place\": %s, "
           "\"layout_bytes\": %llu, \"camera_only\": %s",
           u.object_bvh_ms, u.layout_ms, u.layout_in_place ? "true" : "false",
           (unsigned long long)u.layout_bytes, u.camera_only ? "true" : "false");
}
