/* SPDX-License-Identifier: Apache-2.0 */
/* cli_util.h - what the rtcl commands share: the option groups of scenes,
 * renderers and kernels (tables for cli_options.h) with what applies them,
 * messages, the progress bar and the clock. rtcl is a program on rt.h
 * alone (tests/arch/check_includes.py holds it to that). */
#ifndef RTCL_CLI_UTIL_H
#define RTCL_CLI_UTIL_H

#include <stddef.h>
#include <stdio.h>

#include "cli_options.h"
#include "rt.h"

/* Prints "rtcl COMMAND: " and the message to stderr. */
void cli_error(const char *command, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* "true" or "false": v as a JSON value (the --json outputs). */
const char *cli_json_bool(int v);

/* Milliseconds on a monotonic clock (differences only). */
double cli_now_ms(void);

/* An rt_render_options.progress callback: a bar on stderr when stderr is a
 * terminal, nothing otherwise. user is the label (const char *). */
void cli_progress(void *user, double done);

/* Ends the progress line if one was drawn. */
void cli_progress_done(void);

/* ---- scene options: how SCENE is opened ---------------------------------- */

typedef struct cli_scene_args {
    int accel;   /* --accel: an rt_accel for every static mesh, or -1: each mesh's own */
    double time; /* --time: seconds, NAN when not given */
    int update;  /* --update: an rt_update_policy for every mesh, or -1: each mesh's own */
    const char *animation; /* --animation: a clip's name or index (glTF), or NULL */
} cli_scene_args;

/* The scene groups, each a table into cli_scene_args (title
 * CLI_SCENE_TITLE): --accel and --animation; --time; --update. */
extern const cli_option cli_scene_options[];
extern const cli_option cli_time_options[];
extern const cli_option cli_update_options[];
#define CLI_SCENE_TITLE "Scene options"

void cli_scene_args_init(cli_scene_args *a);

/* Opens source (a file or builtin:NAME, rt_scene_open), prints the
 * loader's notices (rt_scene_notices) on stderr, "rtcl COMMAND: notice:
 * ..." each, gives the scene threads for its own per-frame work
 * (rt_scene_set_threads: the renderer's --threads), and applies the scene
 * options given: --accel, --animation, then --time, then --update. Prints
 * the error and returns NULL when that fails. */
rt_scene *cli_scene_open(const char *command, const char *source, const cli_scene_args *a,
                         int threads);

/* ---- image options: what a frame is --------------------------------------- */

typedef struct cli_frame_args {
    int width, height; /* --width, --height: 0 for the scene camera's */
    int direct;        /* --direct: primary and shadow rays only */
    int aov;           /* --aov (cli_aov_options): an rt_aov */
    int spp;           /* --spp (cli_sample_options): samples per pixel, 0: one */
    double exposure;   /* --exposure: stops, NAN for the scene's */
} cli_frame_args;

/* --width, --height, --direct. */
extern const cli_option cli_frame_options[];
/* --aov (the same struct). */
extern const cli_option cli_aov_options[];
/* --spp and --exposure (the same struct): render and animate. */
extern const cli_option cli_sample_options[];
#define CLI_FRAME_TITLE "Image options"

void cli_frame_args_init(cli_frame_args *a);

/* Sets the camera's size from --width and --height; prints the error and
 * returns 0 when the scene refuses it. */
int cli_apply_frame_size(const char *command, rt_scene *scene, const cli_frame_args *a);

/* ---- renderer options --------------------------------------------------- */

typedef struct cli_renderer_args {
    const char *backend;    /* --backend [cpu] */
    const char *device;     /* --device, or NULL */
    int threads;            /* --threads [0: one per core] */
    const char *packet_isa; /* --packet-isa, or NULL */
    int verbose;            /* --verbose: the device compiler's messages on stderr */
    /* Kernel options (cli_kernel_options). */
    const char *cl_options; /* --cl-options, or NULL */
    int device_math;        /* --device-math: rt_device_math */
    int denormals;          /* --denormals: rt_denormals */
    /* Test options (cli_test_options). */
    int cl_one_ray, cl_no_wavefront, cl_packet_lanes, cl_wave_cap;
    char spec[256]; /* backend[:device], made by cli_renderer_create */
} cli_renderer_args;

/* --backend, --device, --threads, --packet-isa, --verbose. --backend is
 * row 0, so that a command whose default backend is another (rtcl view:
 * auto) lists cli_backend_auto_options, then cli_renderer_options + 1. */
extern const cli_option cli_renderer_options[];
/* --backend alone, the default auto (the command sets
 * cli_renderer_args.backend to "auto" after cli_renderer_args_init). */
extern const cli_option cli_backend_auto_options[];
#define CLI_RENDERER_TITLE "Renderer options"
/* --cl-options, --device-math, --denormals: how device kernels are built. */
extern const cli_option cli_kernel_options[];
#define CLI_KERNEL_TITLE "Kernel options (device backends)"
/* --cl-one-ray, --cl-packet-lanes, --cl-no-wavefront, --cl-wave-cap. */
extern const cli_option cli_test_options[];
#define CLI_TEST_TITLE "For tests and comparisons (every choice gives the same bits)"

/* The choices of --accel (the library's names, cli_option.choice_name),
 * --device-math and --denormals, for commands with rows of their own. */
const char *cli_accel_name(int value);
extern const cli_choice cli_device_math_choices[];
extern const cli_choice cli_denormals_choices[];

void cli_renderer_args_init(cli_renderer_args *a);

/* Creates the renderer the options ask for; prints the error and returns
 * NULL when it cannot (a --device for a backend that takes none, as the
 * backend registry says, among others). */
rt_renderer *cli_renderer_create(const char *command, cli_renderer_args *a);

/* 1 when the backend named by spec (NAME or NAME:DEVICE) takes a device,
 * by the backend registry (rt_backend_describe). */
int cli_backend_takes_device(const char *spec);

/* The renderer's notice when there is one (auto found no device: "rtcl
 * COMMAND: notice: ...: using the CPU"), else with --verbose the line
 * "rtcl COMMAND: backend: NAME (DEVICE)" with the device that ran
 * (rt_render_stats or rt_trace_stats); else nothing: the backend auto chose
 * is named by the command's own result line (render's "wrote", the --stats
 * and --json output), not by a line of its own. On stderr; stdout is left
 * alone (--json). */
void cli_print_backend_choice(const char *command, const cli_renderer_args *a, const char *backend,
                              const char *device, const char *notice);

/* "backend NAME, DEVICE" (or "backend NAME" without a device) into buf, for
 * a result line; returns buf. */
const char *cli_backend_text(const char *backend, const char *device, char *buf, size_t cap);

/* ---- the renderer and the scene of a command ------------------------------ */

/* Sets each group given (any may be NULL) to its defaults, as its _init. */
void cli_args_init(cli_frame_args *frame, cli_scene_args *scene, cli_renderer_args *renderer);

/* What a command that renders or traces holds. */
typedef struct cli_session {
    rt_renderer *renderer;
    rt_scene *scene;
} cli_session;

/* The step render and animate share: makes the renderer (cli_renderer_create),
 * then opens source (cli_scene_open) and, with frame non-NULL, sizes its
 * camera (cli_apply_frame_size), in that order. Prints the first error and
 * returns 0 with nothing held. */
int cli_session_open(cli_session *out, const char *command, const char *source,
                     cli_renderer_args *renderer, const cli_scene_args *scene,
                     const cli_frame_args *frame);

/* Destroys what out holds (either may be NULL) and sets both to NULL. */
void cli_session_close(cli_session *out);

/* Prints the renderer's last kernel build messages (rt_renderer_build_log)
 * on stderr, "rtcl COMMAND: BACKEND build log:" and the lines, if there are
 * any. For --verbose; a failed build's error carries them already. */
void cli_print_build_log(const char *command, const rt_renderer *renderer);

#endif /* RTCL_CLI_UTIL_H */
