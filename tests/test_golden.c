/* SPDX-License-Identifier: Apache-2.0 */
/* test_golden.c - the oracle's images of the built-in scenes (512x288)
 * written as 8-bit PNG match tests/golden/NAME.png exactly. The exact check
 * of the float bits is test_core_golden (hashes, also under qemu); this one
 * keeps the PNGs people look at honest. Regenerate with
 *   rtcl render builtin:NAME --width 512 --height 288 -o tests/golden/NAME.png */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "formats/image.h"
#include "rt.h"
#include "scene/scene_builtin.h"

int main(void) {
    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        const char *name = rt_builtin_scene_names[i];
        rt_scene *s = test_builtin_scene(name, 512, 288);
        rt_error err;
        if (!s) continue;
        rt_framebuffer fb;
        CHECK(rt_render(test_renderer("cpu", 0), s, NULL, &fb) == RT_OK);
        char rel[256];
        snprintf(rel, sizeof rel, "%s.png", name);
        rt_image img = {fb.width, fb.height, fb.channels, fb.pixels};
        const char *tmp = test_write_temp(rel, "");
        CHECK(tmp && rt_image_write(tmp, &img, &err) == RT_OK);
        rt_image now, golden;
        memset(&now, 0, sizeof now);
        memset(&golden, 0, sizeof golden);
        CHECK_MSG(rt_image_read(tmp, &now, &err) == RT_OK, "%s", err.message);
        snprintf(rel, sizeof rel, "tests/golden/%s.png", name);
        CHECK_MSG(rt_image_read(test_source_path(rel), &golden, &err) == RT_OK, "%s", err.message);
        CHECK_MSG(now.width == golden.width && now.height == golden.height &&
                      now.channels == golden.channels && now.pixels && golden.pixels &&
                      memcmp(now.pixels, golden.pixels,
                             sizeof(float) * (size_t)now.width * now.height * now.channels) == 0,
                  "%s: the rendered PNG differs from tests/golden/%s.png", name, name);
        rt_image_free(&now);
        rt_image_free(&golden);
        rt_framebuffer_free(&fb);
        rt_scene_destroy(s);
    }
    return TEST_END();
}
