/* render.c - rt_render: picks a backend and runs one frame. */
#include <stdlib.h>
#include <string.h>

#include "scene.h"

rt_render_options rt_render_options_default(void) {
    rt_render_options o;
    memset(&o, 0, sizeof o);
    o.backend = "cpu";
    return o;
}

void rt_framebuffer_free(rt_framebuffer *fb) {
    if (!fb) return;
    free(fb->pixels);
    fb->pixels = NULL;
}

rt_status rt_render(rt_scene *scene, const rt_render_options *options, rt_framebuffer *fb) {
    if (!scene || !fb) return RT_ERROR_INVALID_ARGUMENT;
    (void)options;
    return rt_scene_fail(scene, RT_ERROR_UNSUPPORTED,
                         "no renderer is built yet: the CPU renderer lands with its own issue");
}
