/* cli_util.c - shared helpers of the rtcl commands. */
#include "cli_util.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene/scene_builtin.h"

void cli_error(const char *command, const char *fmt, ...) {
    va_list args;
    va_start(args, fmt);
    fprintf(stderr, "rtcl %s: ", command);
    vfprintf(stderr, fmt, args);
    fputc('\n', stderr);
    va_end(args);
}

const char *cli_value(int argc, char **argv, int *i, const char *command) {
    if (*i + 1 >= argc) {
        cli_error(command, "option %s needs a value (see rtcl %s --help)", argv[*i], command);
        return NULL;
    }
    return argv[++*i];
}

int cli_int(const char *command, const char *option, const char *text, long min, long max,
            int *out) {
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (errno || end == text || *end || v < min || v > max) {
        cli_error(command, "%s: '%s' is not an integer in %ld..%ld", option, text, min, max);
        return 0;
    }
    *out = (int)v;
    return 1;
}

int cli_float(const char *command, const char *option, const char *text, double *out) {
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (errno || end == text || *end || !isfinite(v)) {
        cli_error(command, "%s: '%s' is not a finite number", option, text);
        return 0;
    }
    *out = v;
    return 1;
}

rt_status cli_load_scene(const char *arg, rt_scene **out, rt_error *err) {
    if (strncmp(arg, "builtin:", 8) == 0) return rt_scene_builtin(arg + 8, out, err);
    return rt_scene_load(arg, out, err);
}

static int progress_drawn;

void cli_progress(void *user, double done) {
    static int last_percent = -1;
    if (!isatty(STDERR_FILENO)) return;
    int percent = (int)(done * 100.0 + 0.5);
    if (percent == last_percent && done < 1.0) return;
    last_percent = percent;
    const int width = 30;
    int filled = (int)(done * width + 0.5);
    char bar[64];
    for (int k = 0; k < width; k++) bar[k] = k < filled ? '#' : '.';
    bar[width] = 0;
    fprintf(stderr, "\r%s [%s] %3d%%", user ? (const char *)user : "", bar, percent);
    fflush(stderr);
    progress_drawn = 1;
}

void cli_progress_done(void) {
    if (progress_drawn) fputc('\n', stderr);
    progress_drawn = 0;
}

const char *cli_backend_name(const char *command, const char *backend, const char *device,
                             char *buf, size_t size) {
    if (!device) return backend;
    if (strcmp(backend, "opencl") != 0 && strcmp(backend, "auto") != 0) {
        cli_error(command, "--device applies to --backend opencl or auto, not '%s'", backend);
        return NULL;
    }
    snprintf(buf, size, "%s:%s", backend, device);
    return buf;
}
