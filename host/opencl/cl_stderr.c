/* SPDX-License-Identifier: Apache-2.0 */
/* cl_stderr.c - descriptor 2 into a temporary file around device builds. */
#include "opencl/cl_stderr.h"

#include <pthread.h>
#include <stdlib.h>
#include <unistd.h>

#define RT_CL_STDERR_MAX (64 * 1024)

/* Two renderers building at once in two threads would otherwise each save
 * the other's temporary file as "the real stderr". */
static pthread_mutex_t capture_lock = PTHREAD_MUTEX_INITIALIZER;

void rt_cl_stderr_begin(rt_cl_stderr *c) {
    pthread_mutex_lock(&capture_lock);
    c->saved = -1;
    c->file = tmpfile();
    if (!c->file) return;
    fflush(stderr);
    c->saved = dup(2);
    if (c->saved < 0 || dup2(fileno(c->file), 2) < 0) {
        if (c->saved >= 0) close(c->saved);
        c->saved = -1;
        fclose(c->file);
        c->file = NULL;
    }
}

char *rt_cl_stderr_end(rt_cl_stderr *c) {
    char *text = NULL;
    if (c->saved >= 0) {
        fflush(stderr);
        dup2(c->saved, 2);
        close(c->saved);
        c->saved = -1;
        /* The writes went through the descriptor, past the FILE's buffer. */
        long size = fseek(c->file, 0, SEEK_END) == 0 ? ftell(c->file) : 0;
        if (size < 0) size = 0;
        if (size > RT_CL_STDERR_MAX) size = RT_CL_STDERR_MAX;
        text = malloc((size_t)size + 1);
        if (text) {
            rewind(c->file);
            size_t got = fread(text, 1, (size_t)size, c->file);
            text[got] = '\0';
        }
    }
    if (c->file) fclose(c->file);
    c->file = NULL;
    pthread_mutex_unlock(&capture_lock);
    return text;
}
