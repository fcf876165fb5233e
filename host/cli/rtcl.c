/* rtcl.c - the command-line tool: dispatches to one file per command. */
#include <stdio.h>
#include <string.h>

#include "commands.h"

int main(int argc, char **argv) {
    /* Interim: only 'compare' is dispatched until the lead's dispatcher lands. */
    if (argc > 1 && strcmp(argv[1], "compare") == 0) return cmd_compare(argc - 1, argv + 1);
    puts("rtcl");
    return 0;
}
