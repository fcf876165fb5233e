/* SPDX-License-Identifier: Apache-2.0 */
/* cmd_generate.c - 'rtcl generate DIR': the built-in scenes as JSON + OBJ. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_util.h"
#include "commands.h"

static const cli_group generate_groups[] = {{NULL}};

const cli_command cmd_generate_spec = {
    "generate",
    "write the built-in scenes as JSON + OBJ files",
    "DIR",
    "folder",
    1,
    1,
    "Writes every built-in scene (cornell, keyframes) into the folder DIR as\n"
    "NAME.json plus one NAME_MESH.obj per mesh, making DIR (and the folders above\n"
    "it) when it does not exist. Each file is written whole or not at all (a failed\n"
    "write leaves an existing file as it was). The files in scenes/ were made this\n"
    "way; loading them gives the same scene, bit for bit, as builtin:NAME.\n",
    generate_groups,
    NULL,
    NULL};

/* Makes dir and the folders above it where they are missing (mkdir -p);
 * 0 with the reason printed when one cannot be made. */
static int make_folders(const char *dir) {
    char path[4096];
    if (!dir[0]) {
        cli_error("generate", "the folder name is empty");
        return 0;
    }
    if (snprintf(path, sizeof path, "%s", dir) >= (int)sizeof path) {
        cli_error("generate", "%s: the folder name is too long", dir);
        return 0;
    }
    for (char *p = path + 1;; p++) {
        if (*p != '/' && *p != '\0') continue;
        char c = *p;
        *p = '\0';
        struct stat st;
        if (stat(path, &st) != 0) {
            if (errno != ENOENT || (mkdir(path, 0777) != 0 && errno != EEXIST)) {
                cli_error("generate", "%s: cannot make the folder: %s", path, strerror(errno));
                return 0;
            }
        } else if (!S_ISDIR(st.st_mode)) {
            cli_error("generate", "%s: not a folder", path);
            return 0;
        }
        *p = c;
        if (!c) return 1;
        while (p[1] == '/') p++;
        if (!p[1]) return 1;
    }
}

int cmd_generate(int argc, char **argv) {
    int code;
    if (cli_parse(&cmd_generate_spec, NULL, argc, argv, &code) < 0) return code;
    const char *dir = argv[0];
    if (!make_folders(dir)) return 2;
    /* The folder is checked (writable) before any scene is made. */
    rt_error check;
    if (rt_scene_save_check(dir, rt_builtin_scene_name(0), &check) != RT_OK) {
        cli_error("generate", "%s", check.message);
        return 2;
    }
    for (int k = 0; rt_builtin_scene_name(k); k++) {
        const char *name = rt_builtin_scene_name(k);
        rt_scene *scene;
        rt_error err;
        rt_status st = rt_scene_builtin(name, &scene, &err);
        if (st == RT_OK) {
            st = rt_scene_save_json(scene, dir, name, &err);
            rt_scene_destroy(scene);
        }
        if (st != RT_OK) {
            cli_error("generate", "%s", err.message);
            return 2;
        }
        printf("wrote %s/%s.json\n", dir, name);
    }
    return 0;
}
