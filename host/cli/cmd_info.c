/* cmd_info.c - placeholder for 'rtcl info'. */
#include <stdio.h>

#include "commands.h"

int cmd_info(int argc, char **argv) {
    (void)argc;
    (void)argv;
    fprintf(stderr, "rtcl info: not built yet\n");
    return 2;
}
