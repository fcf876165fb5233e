/* SPDX-License-Identifier: Apache-2.0 */
/* test_image_pnm.c - PPM/PGM and PFM, the image formats the library reads and
 * writes in plain C, without the image module (so also in builds without
 * OpenImageIO): PFM keeps every float bit (NaN, infinities, -0, subnormals)
 * and stores the bottom row first; both PFM byte orders, ASCII and 16-bit PNM
 * and comments read; malformed and cut-short files are parse errors. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "formats/image.h"

static char dir[512];

static const char *path_of(const char *name) {
    static char paths[4][1024];
    static int slot;
    char *p = paths[slot++ % 4];
    snprintf(p, sizeof paths[0], "%s/%s", dir, name);
    return p;
}

static const char *write_bytes(const char *name, const void *bytes, size_t size) {
    const char *p = path_of(name);
    FILE *f = fopen(p, "wb");
    if (!f) return p;
    fwrite(bytes, 1, size, f);
    fclose(f);
    return p;
}

static void test_pfm_round_trip(int channels) {
    const int w = 3, h = 2, n = w * h * channels;
    float *values = malloc(sizeof(float) * (size_t)n);
    const float specials[] = {NAN, INFINITY, -INFINITY, -0.0f, FLT_TRUE_MIN, FLT_MAX, -1.5f, 0.1f};
    for (int i = 0; i < n; i++) values[i] = specials[i % 8] * (i < 8 ? 1.0f : 0.5f);
    rt_image image = {w, h, channels, values}, back;
    rt_error err;
    const char *p = path_of(channels == 1 ? "grey.pfm" : "rgb.PFM");
    CHECK_MSG(rt_image_write(p, &image, &err) == RT_OK, "%s", err.message);
    CHECK_MSG(rt_image_read(p, &back, &err) == RT_OK, "%s", err.message);
    CHECK(back.width == w && back.height == h && back.channels == channels);
    if (back.pixels && back.width * back.height * back.channels == n)
        CHECK_MSG(memcmp(back.pixels, values, sizeof(float) * (size_t)n) == 0,
                  "%d channels: the floats changed", channels);
    rt_image_free(&back);

    /* The file: header, then the bottom row first, little-endian. */
    FILE *f = fopen(p, "rb");
    unsigned char bytes[256] = {0};
    size_t size = f ? fread(bytes, 1, sizeof bytes, f) : 0;
    if (f) fclose(f);
    char header[32];
    int hn = snprintf(header, sizeof header, "P%c\n%d %d\n-1.0\n", channels == 1 ? 'f' : 'F', w, h);
    CHECK(size == (size_t)hn + 4 * (size_t)n && memcmp(bytes, header, (size_t)hn) == 0);
    uint32_t first;
    memcpy(&first, &values[(h - 1) * w * channels], 4); /* the bottom row's first value */
    CHECK(bytes[hn] == (first & 0xFF) && bytes[hn + 3] == first >> 24);
    free(values);
}

static void test_reading(void) {
    rt_image im;
    rt_error err;
    /* Big-endian PFM (positive scale): 1x1 grey 2.0f = 0x40000000. */
    const unsigned char be[] = {'P', 'f', '\n', '1',  ' ', '1', '\n', '1',
                                '.', '0', '\n', 0x40, 0,   0,   0};
    CHECK_MSG(rt_image_read(write_bytes("be.pfm", be, sizeof be), &im, &err) == RT_OK, "%s",
              err.message);
    CHECK(im.pixels && im.channels == 1 && im.pixels[0] == 2.0f);
    rt_image_free(&im);
    /* ASCII PPM with a comment, maxval 255: level k reads as k / 255.0f. */
    const char p3[] = "P3\n# a comment\n2 1\n255\n0 128 255  7 8 9\n";
    CHECK_MSG(rt_image_read(write_bytes("a.ppm", p3, strlen(p3)), &im, &err) == RT_OK, "%s",
              err.message);
    CHECK(im.pixels && im.width == 2 && im.channels == 3 && im.pixels[1] == 128.0f / 255.0f &&
          im.pixels[2] == 1.0f && im.pixels[5] == 9.0f / 255.0f);
    rt_image_free(&im);
    /* 16-bit binary PGM: big-endian levels over 65535. */
    const unsigned char p5[] = {'P', '5', '\n', '2',  ' ',  '1',  '\n', '6', '5',
                                '5', '3', '5',  '\n', 0x12, 0x34, 0xFF, 0xFF};
    CHECK_MSG(rt_image_read(write_bytes("w.pgm", p5, sizeof p5), &im, &err) == RT_OK, "%s",
              err.message);
    CHECK(im.pixels && im.channels == 1 && im.pixels[0] == 4660.0f / 65535.0f &&
          im.pixels[1] == 1.0f);
    rt_image_free(&im);

    /* Malformed files: each a parse error naming the file, nothing returned. */
    const char *bad[][2] = {
        {"zero.ppm", "P6\n1 1\n0\nabc"},    {"above.ppm", "P3\n1 1\n10\n11 0 0\n"},
        {"cut.ppm", "P6\n4 4\n255\nabc"},   {"ascii_cut.pgm", "P2\n2 2\n255\n1 2 3"},
        {"cut.pfm", "PF\n2 2\n-1.0\nabcd"}, {"scale.pfm", "Pf\n1 1\n0\nabcd"},
        {"size.ppm", "P6\n0 1\n255\n"},     {"huge.ppm", "P6\n99999 1\n255\n"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *p = write_bytes(bad[i][0], bad[i][1], strlen(bad[i][1]));
        CHECK_MSG(rt_image_read(p, &im, &err) == RT_ERROR_PARSE, "%s: %s", bad[i][0], err.message);
        CHECK_CONTAINS(err.message, bad[i][0]);
        CHECK(im.pixels == NULL);
    }
}

static void test_writing_errors(void) {
    float px[8] = {0};
    rt_image rgba = {1, 2, 4, px};
    rt_error err;
    CHECK(rt_image_write(path_of("four.pfm"), &rgba, &err) == RT_ERROR_UNSUPPORTED);
    CHECK_CONTAINS(err.message, "channels");
    rt_image rgb = {1, 2, 3, px};
    CHECK(rt_image_write("/nonexistent_rt_folder/x.pfm", &rgb, &err) == RT_ERROR_IO);
    CHECK_CONTAINS(err.message, "No such file");
    const char *full = path_of("full.pfm");
    if (symlink("/dev/full", full) == 0) {
        CHECK(rt_image_write(full, &rgb, &err) == RT_ERROR_IO);
        CHECK_CONTAINS(err.message, "No space left on device");
        unlink(full);
    }
}

int main(void) {
    snprintf(dir, sizeof dir, "/tmp/rt_test_pnm_%d", (int)getpid());
    char command[600];
    snprintf(command, sizeof command, "mkdir -p '%s'", dir);
    if (system(command) != 0) test_skip("cannot create a temporary folder");
    test_pfm_round_trip(1);
    test_pfm_round_trip(3);
    test_reading();
    test_writing_errors();
    snprintf(command, sizeof command, "rm -rf '%s'", dir);
    if (system(command) != 0) fprintf(stderr, "could not remove %s\n", dir);
    return TEST_END();
}
