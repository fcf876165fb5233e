/* SPDX-License-Identifier: Apache-2.0 */
/* view_keys.h - the viewer's keys, independent of SDL: their names (for
 * --script files) and what each does (for --help and the H key). The SDL
 * layer (view_app.c) maps its key codes to these. */
#ifndef RTCL_VIEW_KEYS_H
#define RTCL_VIEW_KEYS_H

#include <stdio.h>

typedef enum view_key {
    VIEW_KEY_NONE = 0,
    VIEW_KEY_W,
    VIEW_KEY_A,
    VIEW_KEY_S,
    VIEW_KEY_D,
    VIEW_KEY_R,
    VIEW_KEY_F,
    VIEW_KEY_Q,
    VIEW_KEY_E,
    VIEW_KEY_UP,
    VIEW_KEY_DOWN,
    VIEW_KEY_LEFT,
    VIEW_KEY_RIGHT,
    VIEW_KEY_PAGEUP,
    VIEW_KEY_PAGEDOWN,
    VIEW_KEY_SPACE,
    VIEW_KEY_1,
    VIEW_KEY_2,
    VIEW_KEY_3,
    VIEW_KEY_4,
    VIEW_KEY_L,
    VIEW_KEY_V,
    VIEW_KEY_F12,
    VIEW_KEY_C,
    VIEW_KEY_H,
    VIEW_KEY_ESCAPE,
    VIEW_KEY_COUNT
} view_key;

/* The key's name in scripts ("W", "Up", "PageDown", "Space", "1", "F12",
 * "Escape"); "" for VIEW_KEY_NONE. */
const char *view_key_name(view_key key);

/* The key named name (case-insensitive), VIEW_KEY_NONE when none is. */
view_key view_key_parse(const char *name);

/* The backend the number key selects ("cpu", "packet", "opencl", "vulkan"),
 * or NULL when key is not a number key. */
const char *view_key_backend(view_key key);

/* Writes the key list, one key (or pair) a line, each line prefixed with
 * indent. */
void view_keys_print(FILE *out, const char *indent);

#endif /* RTCL_VIEW_KEYS_H */
