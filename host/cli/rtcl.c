/* rtcl.c - the command-line tool: dispatches to one file per command. */
#include <stdio.h>
#include <string.h>

int main(int argc, char **argv) {
    (void)argc;
    (void)argv;
    puts("rtcl");
    return 0;
}
