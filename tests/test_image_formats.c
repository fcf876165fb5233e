/* SPDX-License-Identifier: Apache-2.0 */
/* test_image_formats.c - every format of the library's one table
 * (rt_image_format_at, formats/image_formats.def) is written by its
 * extension and read back (issue 30, item 9): the same size and channels,
 * and the pixels within the format's rounding (half a level at 8 and 16
 * bits, none for float) or, for the lossy ones, within a bound that still
 * catches a wrong channel order or a wrong scale. Upper-case extensions
 * work too; rt_image_format_list holds every extension of the table, and an
 * unknown extension's error gives that list. Where the image module is not
 * built or found its formats say so (RT_ERROR_UNSUPPORTED) and are skipped. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"

enum { W = 23, H = 11 };

/* A smooth image (lossy codecs keep it), different in each channel. */
static void fill(float *px) {
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = px + 3 * (y * W + x);
            p[0] = (float)x / (W - 1);
            p[1] = (float)y / (H - 1);
            p[2] = 0.25f + 0.5f * (float)(x + y) / (W + H - 2);
        }
}

int main(void) {
    char dir[] = "/tmp/rtcl-test-formats-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    float px[W * H * 3];
    fill(px);
    rt_image img = {W, H, 3, px};
    const char *list = rt_image_format_list();
    int module_missing = 0, written = 0;
    for (int i = 0; rt_image_format_at(i); i++) {
        const rt_image_format *f = rt_image_format_at(i);
        CHECK_MSG(strstr(list, f->extension) != NULL, "%s is not in the list '%s'", f->extension,
                  list);
        for (int upper = 0; upper < 2; upper++) {
            char path[256];
            snprintf(path, sizeof path, "%s/image%s", dir, f->extension);
            if (upper)
                for (char *c = strrchr(path, '.'); *c; c++)
                    if (*c >= 'a' && *c <= 'z') *c = (char)(*c - 'a' + 'A');
            CHECK(rt_image_format_of(path) == f);
            rt_error err;
            rt_status st = rt_image_write(path, &img, &err);
            if (st == RT_ERROR_UNSUPPORTED && f->module &&
                (strstr(err.message, "image module") || strstr(err.message, "no PNG or EXR"))) {
                if (!module_missing++)
                    printf("skipped the image module's formats: %s\n", err.message);
                break;
            }
            CHECK_MSG(st == RT_OK, "%s: %s", path, err.message);
            if (st != RT_OK) continue;
            rt_image back;
            st = rt_image_read(path, &back, &err);
            CHECK_MSG(st == RT_OK, "reading %s back: %s", path, err.message);
            if (st != RT_OK) continue;
            written++;
            CHECK_MSG(back.width == W && back.height == H && back.channels == 3,
                      "%s read back as %dx%d with %d channels", path, back.width, back.height,
                      back.channels);
            if (back.width == W && back.height == H && back.channels == 3) {
                double max = 0.0;
                for (int k = 0; k < W * H * 3; k++) {
                    double d = fabs((double)back.pixels[k] - (double)px[k]);
                    if (d > max) max = d;
                }
                /* half a level (and float rounding) for integer formats, none
                 * for float ones; lossy: JPEG and WebP within 6%, HDR's
                 * 8-bit mantissa within 1% of 1 */
                double bound = f->lossy        ? (f->bits == 32 ? 0.01 : 0.06)
                               : f->bits == 8  ? 0.5 / 255.0 + 1e-6
                               : f->bits == 16 ? 0.5 / 65535.0 + 1e-6
                                               : 0.0;
                CHECK_MSG(max <= bound, "%s: read back %g off (at most %g for %d-bit%s)", path, max,
                          bound, f->bits, f->lossy ? ", lossy" : "");
                printf("%-6s %-5s %2d-bit%s: max difference %g\n", f->extension, f->name, f->bits,
                       f->lossy ? " lossy" : "", max);
            }
            rt_image_free(&back);
            unlink(path);
        }
    }
    CHECK(written > 0);
    /* An unknown extension names the same list. */
    char path[256];
    snprintf(path, sizeof path, "%s/image.nosuch", dir);
    rt_error err;
    CHECK(rt_image_format_of(path) == NULL);
    CHECK(rt_image_write(path, &img, &err) == RT_ERROR_UNSUPPORTED);
    CHECK_CONTAINS(err.message, list);
    CHECK(rt_image_check_output(path, &err) == RT_ERROR_UNSUPPORTED);
    CHECK_CONTAINS(err.message, list);
    CHECK(rt_image_format_of("dir.png/image") == NULL); /* a folder's extension is no format */
    rmdir(dir);
    return TEST_END();
}
