/* cmd_generate.c - 'rtcl generate DIR': the built-in scenes as JSON + OBJ. */
#include <stdio.h>
#include <string.h>

#include "cli_util.h"
#include "commands.h"
#include "scene/scene_builtin.h"
#include "formats/scene_save.h"

static const char usage[] =
    "usage: rtcl generate DIR\n"
    "\n"
    "Writes every built-in scene (cornell, keyframes) into the existing folder DIR\n"
    "as NAME.json plus one NAME_MESH.obj per mesh, each file written whole or not at\n"
    "all (a failed write leaves an existing file as it was). The files in scenes/ were made\n"
    "this way; loading them gives the same scene, bit for bit, as builtin:NAME.\n";

int cmd_generate(int argc, char **argv) {
    const char *dir = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            fputs(usage, stdout);
            return 0;
        }
        if (argv[i][0] == '-' || dir) {
            cli_error("generate", "unexpected argument '%s'\n%s", argv[i], usage);
            return 2;
        }
        dir = argv[i];
    }
    if (!dir) {
        fputs(usage, stderr);
        return 2;
    }
    /* The folder is checked before any scene is made. */
    rt_error check;
    if (rt_scene_save_check(dir, rt_builtin_scene_names[0], &check) != RT_OK) {
        cli_error("generate", "%s", check.message);
        return 2;
    }
    for (int k = 0; rt_builtin_scene_names[k]; k++) {
        rt_scene *scene;
        rt_error err;
        rt_status st = rt_scene_builtin(rt_builtin_scene_names[k], &scene, &err);
        if (st == RT_OK) {
            st = rt_scene_save_json(scene, dir, rt_builtin_scene_names[k], &err);
            rt_scene_destroy(scene);
        }
        if (st != RT_OK) {
            cli_error("generate", "%s", err.message);
            return 2;
        }
        printf("wrote %s/%s.json\n", dir, rt_builtin_scene_names[k]);
    }
    return 0;
}
