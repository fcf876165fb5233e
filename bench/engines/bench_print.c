/* SPDX-License-Identifier: Apache-2.0 */
/* bench_print.c - JSON strings and the progress line (bench_print.h). */
#include "engines/bench_print.h"

#include <stdio.h>

void json_out_string(const char *s) {
    putchar('"');
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            printf("\\%c", c);
        else if (c < 0x20)
            printf("\\u%04x", c);
        else
            putchar(c);
    }
    putchar('"');
}

void bench_progress_line(const char *scene, const char *what) {
    fprintf(stderr, "\r\033[K%s: %s", scene, what);
}
