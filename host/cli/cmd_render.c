/* cmd_render.c - placeholder for 'rtcl render'. */
#include <stdio.h>

#include "commands.h"

int cmd_render(int argc, char **argv) {
    (void)argc;
    (void)argv;
    fprintf(stderr, "rtcl render: not built yet\n");
    return 2;
}
