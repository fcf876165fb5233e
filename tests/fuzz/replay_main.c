/* SPDX-License-Identifier: Apache-2.0 */
/* replay_main.c - runs a fuzz harness on files, for the builds without
 * libFuzzer: each argument is a file or a folder whose files (sorted by name,
 * not recursively) are fed to LLVMFuzzerTestOneInput one by one. A finding
 * aborts, so the ctest fails; the seed corpus and the regression inputs of
 * tests/fuzz/ run this way in every build. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz_util.h"

static int run_file(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        perror(path);
        return 0;
    }
    size_t cap = 1 << 16, n = 0;
    unsigned char *buf = malloc(cap);
    for (;;) {
        if (!buf) abort();
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap) break;
        cap *= 2;
        buf = realloc(buf, cap);
    }
    fclose(f);
    /* An exact-size copy, so that ASan sees reads past the input's end. */
    unsigned char *exact = malloc(n ? n : 1);
    if (!exact) abort();
    memcpy(exact, buf, n);
    free(buf);
    LLVMFuzzerTestOneInput(exact, n);
    free(exact);
    return 1;
}

static int by_name(const void *a, const void *b) {
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int main(int argc, char **argv) {
    int files = 0, bad = 0;
    for (int i = 1; i < argc; i++) {
        struct stat st;
        if (stat(argv[i], &st) != 0) {
            perror(argv[i]);
            bad++;
            continue;
        }
        if (!S_ISDIR(st.st_mode)) {
            files += run_file(argv[i]);
            continue;
        }
        DIR *d = opendir(argv[i]);
        if (!d) {
            perror(argv[i]);
            bad++;
            continue;
        }
        char **names = NULL;
        size_t count = 0;
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (e->d_name[0] == '.') continue;
            names = realloc(names, (count + 1) * sizeof *names);
            if (!names) abort();
            names[count] = malloc(strlen(argv[i]) + strlen(e->d_name) + 2);
            if (!names[count]) abort();
            sprintf(names[count], "%s/%s", argv[i], e->d_name);
            count++;
        }
        closedir(d);
        if (count) qsort(names, count, sizeof *names, by_name);
        for (size_t k = 0; k < count; k++) {
            files += run_file(names[k]);
            free(names[k]);
        }
        free(names);
    }
    printf("%d inputs run, no finding\n", files);
    return bad || files == 0 ? 1 : 0;
}
