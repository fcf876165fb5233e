/* cli_util.h - what every rtcl command shares: argument helpers, scene
 * loading (files and builtin:NAME), and the progress bar. */
#ifndef RTCL_CLI_UTIL_H
#define RTCL_CLI_UTIL_H

#include <stddef.h>

#include "rt.h"

/* The value after option argv[*i]; advances *i. Prints a usage error and
 * returns NULL when it is missing. */
const char *cli_value(int argc, char **argv, int *i, const char *command);

/* Parses an integer in [min, max]; prints an error naming the option. */
int cli_int(const char *command, const char *option, const char *text, long min, long max,
            int *out);

/* Parses a finite float; prints an error naming the option. */
int cli_float(const char *command, const char *option, const char *text, double *out);

/* Loads a scene file, or a built-in scene written as builtin:NAME. */
rt_status cli_load_scene(const char *arg, rt_scene **out, rt_error *err);

/* An rt_render_options.progress callback: a bar on stderr when stderr is a
 * terminal, nothing otherwise. user is the label (const char *). */
void cli_progress(void *user, double done);

/* Ends the progress line if one was drawn. */
void cli_progress_done(void);

/* Prints "rtcl COMMAND: " and the message to stderr. */
void cli_error(const char *command, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* The backend name rt_render and rt_trace_rays take: "B" or, with --device,
 * "B:DEVICE" (in buf). Prints an error and returns NULL when a device is given
 * for a backend without devices. */
const char *cli_backend_name(const char *command, const char *backend, const char *device,
                             char *buf, size_t size);
#endif /* RTCL_CLI_UTIL_H */
