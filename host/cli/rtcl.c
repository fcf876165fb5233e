/* SPDX-License-Identifier: Apache-2.0 */
/* rtcl.c - the command-line tool: one function per command (commands.h),
 * 'rtcl help [COMMAND]' and the list of commands. */
#include <stdio.h>
#include <string.h>

#include "cli_signals.h"
#include "commands.h"
#include "rt.h"

static const struct {
    const cli_command *spec;
    int (*run)(int, char **);
} commands[] = {
    {&cmd_render_spec, cmd_render},     {&cmd_trace_spec, cmd_trace},
    {&cmd_info_spec, cmd_info},         {&cmd_compare_spec, cmd_compare},
    {&cmd_devices_spec, cmd_devices},   {&cmd_bench_spec, cmd_bench},
    {&cmd_generate_spec, cmd_generate}, {&cmd_animate_spec, cmd_animate},
    {&cmd_view_spec, cmd_view},
};
#define COMMAND_COUNT (sizeof commands / sizeof commands[0])

static void usage(FILE *out) {
    fprintf(out, "usage: rtcl COMMAND [ARGS...]\n"
                 "       rtcl help [COMMAND | --synopsis]\n"
                 "       rtcl --version\n\ncommands:\n");
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        fprintf(out, "  %-9s %s\n", commands[i].spec->name, commands[i].spec->summary);
    fprintf(out, "\n'rtcl COMMAND --help' or 'rtcl help COMMAND' describes each command, and\n"
                 "'rtcl help --synopsis' lists every command's synopsis. A SCENE is a .json\n"
                 "scene file, a bare .obj file, a glTF 2.0 file (.gltf, .glb), or builtin:NAME\n"
                 "(cornell, keyframes).\n");
}

static int find(const char *name) {
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        if (strcmp(name, commands[i].spec->name) == 0) return (int)i;
    return -1;
}

/* 'rtcl help', 'rtcl help COMMAND', 'rtcl help --synopsis'. */
static int help(int argc, char **argv) {
    if (argc < 3) {
        usage(stdout);
        return 0;
    }
    if (argc > 3) {
        fprintf(stderr, "rtcl help: one command at a time ('%s' and '%s'); see 'rtcl --help'\n",
                argv[2], argv[3]);
        return 2;
    }
    if (!strcmp(argv[2], "--synopsis")) { /* README's list of commands */
        for (size_t i = 0; i < COMMAND_COUNT; i++) {
            printf("%s# %s\n", i ? "\n" : "", commands[i].spec->summary);
            cli_print_synopsis(commands[i].spec, stdout, "");
        }
        return 0;
    }
    int k = find(argv[2]);
    if (k < 0) {
        fprintf(stderr, "rtcl help: unknown command '%s'; see 'rtcl --help'\n", argv[2]);
        return 2;
    }
    cli_print_usage(commands[k].spec, stdout);
    return 0;
}

int main(int argc, char **argv) {
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "version")) {
        printf("rtcl %s\n", rt_version()); /* the library's: rtcl links it statically */
        return 0;
    }
    if (!strcmp(argv[1], "help")) return help(argc, argv);
    int k = find(argv[1]);
    /* An interrupted write leaves no temporary (cli_signals.h). Not for the
     * viewer: SDL turns SIGINT and SIGTERM into a quit event when it finds
     * their default actions, so that the session ends as by Escape. */
    if (k >= 0 && commands[k].run != cmd_view) cli_signals_install();
    if (k >= 0) return commands[k].run(argc - 1, argv + 1);
    fprintf(stderr, "rtcl: unknown command '%s'; see 'rtcl --help'\n", argv[1]);
    return 2;
}
