/* SPDX-License-Identifier: Apache-2.0 */
/* view_script.h - timed input for 'rtcl view --script FILE', so that a
 * session replays exactly without a person at the keyboard.
 *
 * The format: one event a line, "FRAME ACTION [ARGS]"; '#' starts a comment
 * and blank lines are ignored. FRAME is the 0-based number of the frame
 * before which the event happens; frames must not decrease. Actions:
 *   down KEY        KEY is pressed and stays held (movement keys move while held)
 *   up KEY          KEY is released
 *   tap KEY         KEY is pressed and released (the one-shot keys: Space, 1-4,
 *                   L, V, F12, C, H, Escape, PageUp, PageDown)
 *   drag DX DY      a drag with the left mouse button by DX, DY pixels (turns)
 *   wheel N         N notches of the mouse wheel (positive: faster)
 *   screenshot FILE save the first full-resolution frame from this frame on
 *                   (format by extension: .png, .ppm, .exr)
 *   quit            end the session
 * KEY is a name from view_keys.h (W, Up, PageDown, Space, 1, F12, ...). A
 * scripted session runs on a fixed clock (rtcl view --step), so the camera
 * and the timeline advance the same on every run. */
#ifndef RTCL_VIEW_SCRIPT_H
#define RTCL_VIEW_SCRIPT_H

#include <stddef.h>

#include "rt.h"
#include "view_keys.h"

typedef enum view_event_kind {
    VIEW_EVENT_DOWN,
    VIEW_EVENT_UP,
    VIEW_EVENT_TAP,
    VIEW_EVENT_DRAG,
    VIEW_EVENT_WHEEL,
    VIEW_EVENT_SCREENSHOT,
    VIEW_EVENT_QUIT
} view_event_kind;

typedef struct view_event {
    long frame;
    view_event_kind kind;
    view_key key; /* down, up, tap */
    float dx, dy; /* drag (dx also wheel notches) */
    char *path;   /* screenshot */
    int line;     /* in the script file, for messages */
} view_event;

typedef struct view_script {
    view_event *events;
    size_t count;
    size_t next; /* the first event not yet replayed */
} view_script;

/* Reads a script file. On failure *out is empty and err holds
 * "file:line:column: reason". */
rt_status view_script_load(const char *path, view_script *out, rt_error *err);

/* The next event due before frame 'frame', or NULL when none is; each is
 * returned once. */
const view_event *view_script_next(view_script *script, long frame);

void view_script_free(view_script *script);

#endif /* RTCL_VIEW_SCRIPT_H */
