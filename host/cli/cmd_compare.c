/* cmd_compare.c - placeholder for 'rtcl compare'. */
#include <stdio.h>

#include "commands.h"

int cmd_compare(int argc, char **argv) {
    (void)argc;
    (void)argv;
    fprintf(stderr, "rtcl compare: not built yet\n");
    return 2;
}
