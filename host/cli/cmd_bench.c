/* cmd_bench.c - placeholder for 'rtcl bench'. */
#include <stdio.h>

#include "commands.h"

int cmd_bench(int argc, char **argv) {
    (void)argc;
    (void)argv;
    fprintf(stderr, "rtcl bench: not built yet\n");
    return 2;
}
