/* SPDX-License-Identifier: Apache-2.0 */
/* view_missing.c - 'rtcl view' in a build without SDL2: says what is missing. */
#include <stdio.h>

#include "view.h"

static const char reason[] =
#ifdef RT_VIEW_TURNED_OFF
    "this rtcl was built without the viewer: it was configured with -DRT_VIEW=OFF "
    "(configure with -DRT_VIEW=AUTO or ON, with libsdl2-dev installed)";
#else
    "this rtcl was built without the viewer: SDL2 was not found when it was configured "
    "(install libsdl2-dev, then configure and build again)";
#endif

int view_available(const char **why) {
    *why = reason;
    return 0;
}

int view_run(view_options *options) {
    (void)options;
    cli_error("view", "%s", reason);
    return 2;
}
