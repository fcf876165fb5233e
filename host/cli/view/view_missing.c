/* view_missing.c - 'rtcl view' in a build without SDL2: says what is missing. */
#include <stdio.h>

#include "view.h"

static const char reason[] =
    "this rtcl was built without the viewer: SDL2 was not found when it was configured "
    "(install libsdl2-dev, then configure and build again)";

int view_available(const char **why) {
    *why = reason;
    return 0;
}

int view_run(view_options *options) {
    (void)options;
    cli_error("view", "%s", reason);
    return 2;
}
