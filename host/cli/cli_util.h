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

/* Loads a scene file, or a built-in scene written as builtin:NAME; prints
 * the loader's notices (rt_scene_notices) on stderr, "rtcl: notice: ..."
 * each. */
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

/* The options every command that renders or traces takes: the renderer's
 * (rt_renderer_options). */
typedef struct cli_renderer_args {
    rt_renderer_options opt;
    const char *backend; /* --backend [cpu] */
    const char *device;  /* --device, or NULL */
    int accel_set;       /* --accel given: */
    rt_accel accel;      /* the structure of every static mesh */
    int verbose;         /* --verbose: the device compiler's messages on stderr */
    char spec[256];      /* backend[:device], made by cli_renderer_create */
} cli_renderer_args;

/* The help lines of those options. */
extern const char cli_renderer_usage[];

void cli_renderer_args_init(cli_renderer_args *a);

/* If argv[*i] is one of the renderer options, takes it (and its value) and
 * returns 1; 0 when it is not one; -1 after printing an error. */
int cli_renderer_arg(int argc, char **argv, int *i, const char *command, cli_renderer_args *a);

/* --device-math auto|native|portable and --denormals preserve|flush at
 * argv[*i]: 1 when taken (the value stored, *i past it), 0 when argv[*i] is
 * neither option, -1 after printing the error for a bad or missing value. */
int cli_maths_arg(int argc, char **argv, int *i, const char *command, rt_device_math *math,
                  rt_denormals *denormals);

/* Creates the renderer the options ask for; prints the error and returns
 * NULL when it cannot. */
rt_renderer *cli_renderer_create(const char *command, cli_renderer_args *a);

/* Applies --accel (if given) to the scene's static meshes; prints the error
 * and returns 0 on failure. */
int cli_apply_accel(const char *command, const cli_renderer_args *a, rt_scene *scene);
/* Prints the renderer's last kernel build messages (rt_renderer_build_log)
 * on stderr, "rtcl COMMAND: opencl build log:" and the lines, if there are
 * any. For --verbose; a failed build's error carries them already. */
void cli_print_build_log(const char *command, const rt_renderer *renderer);

#endif /* RTCL_CLI_UTIL_H */
