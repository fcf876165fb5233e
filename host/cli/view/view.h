/* SPDX-License-Identifier: Apache-2.0 */
/* view.h - 'rtcl view': the options the command line gives the viewer, and
 * the viewer itself (view_app.c with SDL2, view_missing.c without). */
#ifndef RTCL_VIEW_H
#define RTCL_VIEW_H

#include "cli_util.h"

typedef struct view_options {
    const char *scene_path;
    cli_frame_args frame;       /* --width, --height (and the window's size), --aov, --direct */
    cli_scene_args scene;       /* --accel, --time: scene time at the start */
    cli_renderer_args renderer; /* --backend, --device, --threads, ... */
    int play;                   /* --play: the timeline plays from the start */
    double keyframe_rate;       /* --keyframe-rate: keyframes per second */
    int frames;                 /* --frames: quit after this many (0: never) */
    const char *screenshot;     /* --screenshot: the last frame, at full resolution */
    const char *script;         /* --script: timed input */
    double step_ms;             /* --step: fixed clock per frame; 0: real time */
    int move_divisor;           /* --move-scale: 0 automatic, else the divisor while moving */
    double budget_ms;           /* --budget: the automatic divisor's frame time target */
} view_options;

/* Runs the viewer until the user quits, the script ends it or --frames is
 * reached. Returns the process exit status (0, or 2 after printing why). */
int view_run(view_options *options);

/* 1 when this build has the viewer (SDL2 was found), else 0 with the reason
 * in *why. */
int view_available(const char **why);

#endif /* RTCL_VIEW_H */
