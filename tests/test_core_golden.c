/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_golden.c - golden images of the built-in scenes, compared
 * exactly: the oracle's float framebuffer (512x288) hashed bit for bit
 * (64-bit FNV-1a over the 32-bit patterns) against tests/golden/NAME.hash.
 * The maths is IEEE basic operations only (no FMA, no fast-math), so the same
 * bits come out on x86 and aarch64 (CI runs this under qemu-aarch64).
 * tests/golden/NAME.png shows the image for people (8-bit, clamped).
 *
 * To regenerate after an intended change of the renderer's output:
 *   RT_GOLDEN_UPDATE=DIR build/tests/test_core_golden
 * writes DIR/NAME.hash and DIR/NAME.ppm; copy the hashes to tests/golden,
 * regenerate the PNGs as test_golden.c says, and say why in the commit. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt.h"
#include "scene/scene_builtin.h"

static uint64_t fnv1a_bits(const float *p, size_t n) {
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < n; i++) {
        uint32_t bits;
        memcpy(&bits, &p[i], 4);
        for (int b = 0; b < 4; b++) {
            h ^= (bits >> (8 * b)) & 0xffu;
            h *= 1099511628211ull;
        }
    }
    return h;
}

static void write_ppm(const char *path, const rt_framebuffer *fb) {
    FILE *f = fopen(path, "wb");
    if (!f) return;
    fprintf(f, "P6\n%d %d\n255\n", fb->width, fb->height);
    for (int i = 0; i < fb->width * fb->height * 3; i++) {
        float v = fb->pixels[i];
        v = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
        fputc((int)(v * 255.0f + 0.5f), f);
    }
    fclose(f);
}

int main(void) {
    const char *update = getenv("RT_GOLDEN_UPDATE");
    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        const char *name = rt_builtin_scene_names[i];
        rt_scene *s = test_builtin_scene(name, 512, 288);
        if (!s) continue;
        rt_framebuffer fb;
        CHECK(rt_render(test_renderer("cpu", 0), s, NULL, &fb) == RT_OK);
        uint64_t h = fnv1a_bits(fb.pixels, (size_t)fb.width * fb.height * fb.channels);
        char path[4096];
        if (update) {
            snprintf(path, sizeof path, "%s/%s.hash", update, name);
            FILE *f = fopen(path, "w");
            CHECK(f != NULL);
            if (f) {
                fprintf(f, "%016llx\n", (unsigned long long)h);
                fclose(f);
            }
            snprintf(path, sizeof path, "%s/%s.ppm", update, name);
            write_ppm(path, &fb);
        } else {
            snprintf(path, sizeof path, "tests/golden/%s.hash", name);
            FILE *f = fopen(test_source_path(path), "r");
            unsigned long long want = 0;
            CHECK_MSG(f && fscanf(f, "%llx", &want) == 1, "cannot read %s", test_source_path(path));
            if (f) fclose(f);
            CHECK_MSG(h == want, "%s: framebuffer hash %016llx, golden %016llx", name,
                      (unsigned long long)h, want);
        }
        rt_framebuffer_free(&fb);
        rt_scene_destroy(s);
    }
    return TEST_END();
}
