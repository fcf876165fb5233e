/* rtcl.c - the command-line tool: dispatches to one file per command. */
#include <stdio.h>
#include <string.h>

#include "commands.h"

int main(int argc, char **argv) {
    /* Minimal dispatch of 'bench' for the bvh-fast branch; the lead's
     * dispatcher replaces this. */
    if (argc > 1 && !strcmp(argv[1], "bench")) return cmd_bench(argc - 1, argv + 1);
    puts("rtcl");
    return 0;
}
