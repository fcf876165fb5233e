/* rtcl.c - the command-line tool: one function per command (commands.h). */
#include <stdio.h>
#include <string.h>

#include "commands.h"

static const struct {
    const char *name;
    int (*run)(int, char **);
    const char *summary;
} commands[] = {
    {"render", cmd_render, "render a scene to an image (PNG, EXR, PPM) or an AOV"},
    {"trace", cmd_trace, "trace rays from a text file and write their hits"},
    {"info", cmd_info, "print what a scene holds and which features it uses"},
    {"compare", cmd_compare, "compare two images (exit 1 when they differ too much)"},
    {"devices", cmd_devices, "list OpenCL platforms and devices, and which are bit-exact"},
    {"bench", cmd_bench, "measure BVH builds (and renders) on scenes, beside Embree"},
    {"generate", cmd_generate, "write the built-in scenes as JSON + OBJ files"},
    {"animate", cmd_animate, "render the frames of an animated scene to images"},
    {"view", cmd_view, "fly through a scene in a window, switch backends live (SDL2)"},
};
#define COMMAND_COUNT (sizeof commands / sizeof commands[0])

static void usage(FILE *out) {
    fprintf(out, "usage: rtcl COMMAND [ARGS...]\n\ncommands:\n");
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        fprintf(out, "  %-9s %s\n", commands[i].name, commands[i].summary);
    fprintf(out, "\n'rtcl COMMAND --help' describes each command. A SCENE is a .json scene file,\n"
                 "a bare .obj file, or builtin:NAME (cornell, keyframes).\n");
}

int main(int argc, char **argv) {
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
        strcmp(argv[1], "help") == 0) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        if (strcmp(argv[1], commands[i].name) == 0) return commands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "rtcl: unknown command '%s'\n\n", argv[1]);
    usage(stderr);
    return 2;
}
