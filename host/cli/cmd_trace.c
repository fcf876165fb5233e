/* cmd_trace.c - placeholder for 'rtcl trace'. */
#include <stdio.h>

#include "commands.h"

int cmd_trace(int argc, char **argv) {
    (void)argc;
    (void)argv;
    fprintf(stderr, "rtcl trace: not built yet\n");
    return 2;
}
