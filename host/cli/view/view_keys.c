/* SPDX-License-Identifier: Apache-2.0 */
/* view_keys.c - key names and the key list. */
#include "view_keys.h"

#include <strings.h>

static const char *const names[VIEW_KEY_COUNT] = {
    [VIEW_KEY_NONE] = "",       [VIEW_KEY_W] = "W",           [VIEW_KEY_A] = "A",
    [VIEW_KEY_S] = "S",         [VIEW_KEY_D] = "D",           [VIEW_KEY_R] = "R",
    [VIEW_KEY_F] = "F",         [VIEW_KEY_Q] = "Q",           [VIEW_KEY_E] = "E",
    [VIEW_KEY_UP] = "Up",       [VIEW_KEY_DOWN] = "Down",     [VIEW_KEY_LEFT] = "Left",
    [VIEW_KEY_RIGHT] = "Right", [VIEW_KEY_PAGEUP] = "PageUp", [VIEW_KEY_PAGEDOWN] = "PageDown",
    [VIEW_KEY_SPACE] = "Space", [VIEW_KEY_1] = "1",           [VIEW_KEY_2] = "2",
    [VIEW_KEY_3] = "3",         [VIEW_KEY_4] = "4",           [VIEW_KEY_L] = "L",
    [VIEW_KEY_V] = "V",         [VIEW_KEY_F12] = "F12",       [VIEW_KEY_C] = "C",
    [VIEW_KEY_H] = "H",         [VIEW_KEY_ESCAPE] = "Escape",
};

const char *view_key_name(view_key key) {
    return key > VIEW_KEY_NONE && key < VIEW_KEY_COUNT ? names[key] : "";
}

view_key view_key_parse(const char *name) {
    for (int k = VIEW_KEY_NONE + 1; k < VIEW_KEY_COUNT; k++)
        if (strcasecmp(name, names[k]) == 0) return (view_key)k;
    return VIEW_KEY_NONE;
}

/* The backends of keys 1 to 4, in the order of the keys. */
static const char *const key_backends[] = {"cpu", "packet", "opencl", "vulkan"};
_Static_assert(VIEW_KEY_4 - VIEW_KEY_1 + 1 == sizeof key_backends / sizeof *key_backends,
               "keys 1 to 4 follow each other");

const char *view_key_backend(view_key key) {
    return key >= VIEW_KEY_1 && key <= VIEW_KEY_4 ? key_backends[key - VIEW_KEY_1] : NULL;
}

void view_keys_print(FILE *out, const char *indent) {
    static const char *const lines[] = {
        "W / S         move forward / back",
        "A / D         move left / right",
        "R / F, E / Q  move up / down",
        "arrow keys    turn (also: drag with the left mouse button)",
        "PgUp / PgDn   move faster / slower by 1.5x (also: the mouse wheel)",
        "Space         play / pause the timeline (keyframes cycle while it plays)",
        "1 2 3 4       switch backend live: cpu, packet, opencl, vulkan (where built);",
        "              the BVHs are kept",
        "L             lighting: Whitted (reflection, refraction) / direct only",
        "V             cycle the view: shaded, depth, normal, primitive id, object id,",
        "              box tests, triangle tests (heat maps)",
        "F12           save the next full-resolution frame as rtcl-view-NNNN.png",
        "C             print the camera as a scene file's \"camera\" block (stdout)",
        "H             print this key list (stdout)",
        "Escape        quit",
    };
    for (size_t i = 0; i < sizeof lines / sizeof lines[0]; i++)
        fprintf(out, "%s%s\n", indent, lines[i]);
}
