/* SPDX-License-Identifier: Apache-2.0 */
/* cli_anim.c - the --stats part of the dynamic-scene commands (cli_anim.h). */
#include "cli_anim.h"

#include <stdio.h>

#include "engines/bench_print.h"

/* One name per rt_update_action, in the enum's order (RT_ACTION_NONE = 0). */
static const char *const action_names[] = {"none", "build", "refit", "lbvh", "rebuild"};
_Static_assert(sizeof action_names / sizeof *action_names == RT_ACTION_REBUILD + 1,
               "a name for every rt_update_action");

static const char *action_name(rt_update_action a) {
    return (unsigned)a < sizeof action_names / sizeof *action_names ? action_names[a] : "?";
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
