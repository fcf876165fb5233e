/* SPDX-License-Identifier: Apache-2.0 */
/* test_image.c - image.h: writing PNG/EXR/PPM, reading back, 8-bit rounding,
 * comparison figures and the errors for bad sizes, names and paths. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "formats/image.h"

static char temp_dir[512];

/* A path in this process's temporary folder (static buffer per slot). */
static const char *temp_path(const char *name) {
    static char paths[8][1024];
    static int slot;
    char *path = paths[slot++ % 8];
    snprintf(path, sizeof paths[0], "%s/%s", temp_dir, name);
    return path;
}

/* 8-bit level a value was stored as (reads give level / 255). */
static int level_of(float v) {
    return (int)lroundf(v * 255.0f);
}

static bool read_file(const char *path, unsigned char *bytes, size_t capacity, size_t *size) {
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    *size = fread(bytes, 1, capacity, f);
    fclose(f);
    return *size > 0 && *size < capacity;
}

static bool write_file(const char *path, const unsigned char *bytes, size_t size) {
    FILE *f = fopen(path, "wb");
    if (!f) return false;
    bool ok = fwrite(bytes, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

static rt_image make_image(int width, int height, int channels) {
    rt_image image = {width, height, channels, NULL};
    image.pixels = calloc((size_t)width * height * channels, sizeof(float));
    return image;
}

/* An RGB gradient whose values are exact 8-bit levels. */
static rt_image make_levels_image(int width, int height) {
    rt_image image = make_image(width, height, 3);
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            for (int c = 0; c < 3; c++)
                image.pixels[(y * width + x) * 3 + c] =
                    (float)((x * 37 + y * 11 + c * 90) % 256) / 255.0f;
    return image;
}

static void test_8bit_round_trip(const char *name) {
    rt_image image = make_levels_image(13, 7);
    rt_error err;
    const char *path = temp_path(name);
    CHECK_EQ_INT(rt_image_write(path, &image, &err), RT_OK);
    rt_image back;
    CHECK_EQ_INT(rt_image_read(path, &back, &err), RT_OK);
    CHECK_EQ_INT(back.width, 13);
    CHECK_EQ_INT(back.height, 7);
    CHECK_EQ_INT(back.channels, 3);
    if (back.pixels && back.width == 13 && back.height == 7 && back.channels == 3) {
        int mismatches = 0;
        for (int i = 0; i < 13 * 7 * 3; i++)
            if (back.pixels[i] != image.pixels[i]) /* k / 255.0f reads back exactly */
                mismatches++;
        CHECK_MSG(mismatches == 0, "%s: %d values changed", name, mismatches);
    }
    rt_image_free(&back);
    rt_image_free(&image);
}

/* Clamping and round-to-nearest, checked on the bytes of a PPM file as well
 * as through reading the PNG back. */
static void test_8bit_rounding(void) {
    const float values[] = {-0.5f,
                            0.0f,
                            0.2f,
                            10.4f / 255.0f,
                            10.6f / 255.0f,
                            254.49f / 255.0f,
                            254.51f / 255.0f,
                            1.0f,
                            1.7f,
                            NAN,
                            INFINITY,
                            0.5f};
    const int expected[] = {0, 0, 51, 10, 11, 254, 255, 255, 255, 0, 255, 128};
    rt_image image = make_image(4, 1, 3);
    memcpy(image.pixels, values, sizeof values);
    rt_error err;

    const char *ppm = temp_path("rounding.ppm");
    CHECK_EQ_INT(rt_image_write(ppm, &image, &err), RT_OK);
    FILE *f = fopen(ppm, "rb");
    CHECK(f != NULL);
    if (f) {
        int width = 0, height = 0, maxval = 0;
        char magic[3] = {0};
        int fields = fscanf(f, "%2s %d %d %d", magic, &width, &height, &maxval);
        fgetc(f); /* the single whitespace before the pixel bytes */
        CHECK_EQ_INT(fields, 4);
        CHECK_MSG(strcmp(magic, "P6") == 0, "magic %s", magic);
        CHECK_EQ_INT(width, 4);
        CHECK_EQ_INT(height, 1);
        CHECK_EQ_INT(maxval, 255);
        unsigned char bytes[12] = {0};
        CHECK_EQ_INT(fread(bytes, 1, 12, f), 12);
        for (int i = 0; i < 12; i++)
            CHECK_MSG(bytes[i] == expected[i], "value %d: byte %d, expected %d", i, bytes[i],
                      expected[i]);
        fclose(f);
    }

    const char *png = temp_path("rounding.png");
    CHECK_EQ_INT(rt_image_write(png, &image, &err), RT_OK);
    rt_image back;
    CHECK_EQ_INT(rt_image_read(png, &back, &err), RT_OK);
    if (back.pixels && back.width * back.height * back.channels == 12)
        for (int i = 0; i < 12; i++)
            CHECK_MSG(level_of(back.pixels[i]) == expected[i],
                      "png value %d: level %d, expected %d", i, level_of(back.pixels[i]),
                      expected[i]);
    rt_image_free(&back);
    rt_image_free(&image);
}

/* EXR keeps 32-bit floats exactly, values outside [0,1] included. */
static void test_exr_round_trip(void) {
    rt_image image = make_image(5, 3, 3);
    for (int i = 0; i < 5 * 3 * 3; i++) image.pixels[i] = (float)(i - 20) * 0.123456789f;
    image.pixels[7] = 1e-30f;
    image.pixels[8] = 12345.678f;
    rt_error err;
    const char *path = temp_path("floats.EXR"); /* the extension is case-insensitive */
    CHECK_EQ_INT(rt_image_write(path, &image, &err), RT_OK);
    rt_image back;
    CHECK_EQ_INT(rt_image_read(path, &back, &err), RT_OK);
    CHECK_EQ_INT(back.width, 5);
    CHECK_EQ_INT(back.height, 3);
    CHECK_EQ_INT(back.channels, 3);
    if (back.pixels && back.width * back.height * back.channels == 45)
        CHECK(memcmp(back.pixels, image.pixels, 45 * sizeof(float)) == 0);
    rt_image_free(&back);
    rt_image_free(&image);
}

/* One channel (a depth AOV) and four channels (alpha is not premultiplied). */
static void test_channel_counts(void) {
    rt_error err;
    rt_image grey = make_image(3, 2, 1);
    for (int i = 0; i < 6; i++) grey.pixels[i] = (float)(i * 40) / 255.0f;
    const char *names[] = {"grey.png", "grey.ppm", "grey.exr"};
    for (int n = 0; n < 3; n++) {
        const char *path = temp_path(names[n]);
        CHECK_MSG(rt_image_write(path, &grey, &err) == RT_OK, "%s", err.message);
        rt_image back;
        CHECK_MSG(rt_image_read(path, &back, &err) == RT_OK, "%s", err.message);
        CHECK_EQ_INT(back.channels, 1);
        if (back.pixels && back.width * back.height * back.channels == 6)
            for (int i = 0; i < 6; i++)
                CHECK_MSG(level_of(back.pixels[i]) == i * 40, "%s value %d", names[n], i);
        rt_image_free(&back);
    }
    rt_image_free(&grey);

    rt_image rgba = make_image(2, 2, 4);
    for (int p = 0; p < 4; p++) {
        rgba.pixels[p * 4 + 0] = 200.0f / 255.0f;
        rgba.pixels[p * 4 + 1] = 100.0f / 255.0f;
        rgba.pixels[p * 4 + 2] = 50.0f / 255.0f;
        rgba.pixels[p * 4 + 3] = (float)(p * 60) / 255.0f; /* alpha 0 included */
    }
    const char *path = temp_path("rgba.png");
    CHECK_EQ_INT(rt_image_write(path, &rgba, &err), RT_OK);
    rt_image back;
    CHECK_EQ_INT(rt_image_read(path, &back, &err), RT_OK);
    CHECK_EQ_INT(back.channels, 4);
    if (back.pixels && back.width * back.height * back.channels == 16)
        for (int i = 0; i < 16; i++)
            CHECK_MSG(level_of(back.pixels[i]) == level_of(rgba.pixels[i]),
                      "rgba value %d: level %d, expected %d", i, level_of(back.pixels[i]),
                      level_of(rgba.pixels[i]));
    rt_image_free(&back);

    /* PPM has no alpha channel: refused, not silently dropped. */
    const char *ppm = temp_path("rgba.ppm");
    CHECK_EQ_INT(rt_image_write(ppm, &rgba, &err), RT_ERROR_UNSUPPORTED);
    CHECK_CONTAINS(err.message, "rgba.ppm");
    CHECK_CONTAINS(err.message, "channels");
    CHECK(access(ppm, F_OK) != 0);
    rt_image_free(&rgba);
}

static void test_compare_figures(void) {
    /* 2x2 RGB; b differs at (1,0) by 0.5 in green and at (0,1) by 0.25 in
     * blue and -0.25 in red. */
    rt_image a = make_image(2, 2, 3), b = make_image(2, 2, 3);
    for (int i = 0; i < 12; i++) a.pixels[i] = b.pixels[i] = 0.25f + 0.05f * (float)i;
    b.pixels[1 * 3 + 1] += 0.5f;
    b.pixels[2 * 3 + 2] += 0.25f;
    b.pixels[2 * 3 + 0] -= 0.25f;
    rt_error err;
    rt_image_diff d;
    rt_image diff;
    CHECK_EQ_INT(rt_image_compare(&a, &b, &d, &diff, &err), RT_OK);
    double e1 = fabs((double)b.pixels[4] - a.pixels[4]);
    double e2 = fabs((double)b.pixels[8] - a.pixels[8]);
    double e3 = fabs((double)b.pixels[6] - a.pixels[6]);
    double mse = (e1 * e1 + e2 * e2 + e3 * e3) / 12.0;
    CHECK_MSG(d.max_abs == e1, "max_abs %.9g", d.max_abs);
    CHECK_MSG(fabs(d.max_abs - 0.5) < 1e-6, "max_abs %.9g", d.max_abs);
    CHECK_MSG(fabs(d.rmse - sqrt(mse)) < 1e-12, "rmse %.9g, expected %.9g", d.rmse, sqrt(mse));
    CHECK_MSG(fabs(d.psnr - (-10.0 * log10(mse))) < 1e-9, "psnr %.9g", d.psnr);
    CHECK_MSG(fabs(d.psnr - 15.0514998) < 1e-6, "psnr %.9g", d.psnr); /* mse = 0.375 / 12 */
    CHECK_EQ_INT(d.differing, 2);
    CHECK_EQ_INT(d.pixels, 4);
    CHECK_EQ_INT(d.first_x, 1);
    CHECK_EQ_INT(d.first_y, 0);
    CHECK_EQ_INT(diff.width, 2);
    CHECK_EQ_INT(diff.height, 2);
    CHECK_EQ_INT(diff.channels, 3);
    if (diff.pixels) {
        for (int i = 0; i < 12; i++) {
            float expected = (float)fabs((double)a.pixels[i] - b.pixels[i]);
            CHECK_MSG(diff.pixels[i] == expected, "diff value %d: %g, expected %g", i,
                      diff.pixels[i], expected);
        }
        /* The difference image writes like any other. */
        CHECK_EQ_INT(rt_image_write(temp_path("diff.exr"), &diff, &err), RT_OK);
    }
    rt_image_free(&diff);

    /* The first differing pixel is the first in row order. */
    b.pixels[0 * 3 + 2] += 0.001f;
    CHECK_EQ_INT(rt_image_compare(&a, &b, &d, NULL, &err), RT_OK);
    CHECK_EQ_INT(d.first_x, 0);
    CHECK_EQ_INT(d.first_y, 0);
    CHECK_EQ_INT(d.differing, 3);

    /* Identical images. */
    CHECK_EQ_INT(rt_image_compare(&a, &a, &d, NULL, &err), RT_OK);
    CHECK(d.max_abs == 0.0);
    CHECK(d.rmse == 0.0);
    CHECK(isinf(d.psnr) && d.psnr > 0);
    CHECK_EQ_INT(d.differing, 0);
    CHECK_EQ_INT(d.first_x, -1);
    CHECK_EQ_INT(d.first_y, -1);

    /* A NaN in one image only never passes as equal; NaN in both does. */
    memcpy(b.pixels, a.pixels, 12 * sizeof(float));
    b.pixels[11] = NAN;
    CHECK_EQ_INT(rt_image_compare(&a, &b, &d, NULL, &err), RT_OK);
    CHECK(isinf(d.max_abs));
    CHECK_EQ_INT(d.differing, 1);
    CHECK_EQ_INT(d.first_x, 1);
    CHECK_EQ_INT(d.first_y, 1);
    a.pixels[11] = NAN;
    CHECK_EQ_INT(rt_image_compare(&a, &b, &d, NULL, &err), RT_OK);
    CHECK(d.max_abs == 0.0);
    CHECK_EQ_INT(d.differing, 0);

    /* Sizes or channel counts that do not match. */
    rt_image small = make_image(2, 1, 3);
    rt_image grey = make_image(2, 2, 1);
    diff.pixels = (float *)&diff; /* must be reset on failure */
    CHECK_EQ_INT(rt_image_compare(&a, &small, &d, &diff, &err), RT_ERROR_INVALID_ARGUMENT);
    CHECK(diff.pixels == NULL);
    CHECK_CONTAINS(err.message, "differ in size");
    CHECK_CONTAINS(err.message, "2x2");
    CHECK_CONTAINS(err.message, "2x1");
    CHECK_EQ_INT(rt_image_compare(&a, &grey, &d, NULL, &err), RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(err.message, "1 channels");
    CHECK_EQ_INT(rt_image_compare(&a, NULL, &d, NULL, &err), RT_ERROR_INVALID_ARGUMENT);
    rt_image_free(&small);
    rt_image_free(&grey);
    rt_image_free(&a);
    rt_image_free(&b);
}

static void test_write_errors(void) {
    rt_image image = make_levels_image(2, 2);
    rt_error err;

    const char *bad = temp_path("picture.bmpx");
    CHECK_EQ_INT(rt_image_write(bad, &image, &err), RT_ERROR_UNSUPPORTED);
    CHECK_CONTAINS(err.message, "picture.bmpx");
    CHECK_CONTAINS(err.message, ".png");
    CHECK_CONTAINS(err.message, ".exr");
    CHECK_CONTAINS(err.message, ".ppm");
    CHECK(access(bad, F_OK) != 0);
    CHECK_EQ_INT(rt_image_write(temp_path("no_extension"), &image, &err), RT_ERROR_UNSUPPORTED);
    /* A dot in a folder name is not an extension. */
    CHECK_EQ_INT(rt_image_write("/tmp/some.png/image", &image, &err), RT_ERROR_UNSUPPORTED);

    const char *unwritable = "/nonexistent_rt_folder/out.png";
    CHECK_EQ_INT(rt_image_write(unwritable, &image, &err), RT_ERROR_IO);
    CHECK_CONTAINS(err.message, unwritable);
    CHECK_CONTAINS(err.message, "No such file");
    CHECK_EQ_INT(rt_image_write("/nonexistent_rt_folder/out.exr", &image, &err), RT_ERROR_IO);
    CHECK_CONTAINS(err.message, "out.exr");

    /* A full disk: /dev/full fails every write with ENOSPC. Every format
     * reports it (OIIO's PNG writer used to drop it: "wrote", exit 0). */
    const char *full_names[] = {"full.png", "full.ppm", "full.exr"};
    for (int i = 0; i < 3; i++) {
        const char *full = temp_path(full_names[i]);
        unlink(full);
        if (symlink("/dev/full", full) != 0) {
            CHECK_MSG(0, "cannot link %s to /dev/full", full);
            continue;
        }
        CHECK_EQ_INT(rt_image_write(full, &image, &err), RT_ERROR_IO);
        CHECK_CONTAINS(err.message, full_names[i]);
        CHECK_CONTAINS(err.message, "No space left on device");
        unlink(full);
    }

    rt_image empty = {0, 4, 3, NULL};
    CHECK_EQ_INT(rt_image_write(temp_path("empty.png"), &empty, &err), RT_ERROR_INVALID_ARGUMENT);
    CHECK_CONTAINS(err.message, "empty.png");
    CHECK_EQ_INT(rt_image_write(NULL, &image, &err), RT_ERROR_INVALID_ARGUMENT);
    rt_image_free(&image);
}

static void test_read_errors(void) {
    rt_image image;
    rt_error err;
    const char *missing = temp_path("missing.png");
    CHECK_EQ_INT(rt_image_read(missing, &image, &err), RT_ERROR_IO);
    CHECK_CONTAINS(err.message, missing);
    CHECK_CONTAINS(err.message, "No such file");
    CHECK(image.pixels == NULL);

    /* Not an image at all, and a PNG cut short. */
    const char *garbage = test_write_temp("garbage.png", "this is not a picture\n");
    CHECK_EQ_INT(rt_image_read(garbage, &image, &err), RT_ERROR_PARSE);
    CHECK_CONTAINS(err.message, "garbage.png");
    CHECK(image.pixels == NULL);

    /* Files cut short and a PNG with one byte changed. */
    const char *names[] = {"whole.png", "whole.exr", "whole.ppm"};
    for (int k = 0; k < 3; k++) {
        rt_image levels = make_levels_image(64, 64);
        const char *whole = temp_path(names[k]);
        CHECK_EQ_INT(rt_image_write(whole, &levels, &err), RT_OK);
        rt_image_free(&levels);
        static unsigned char bytes[1 << 16];
        size_t n = 0;
        if (!read_file(whole, bytes, sizeof bytes, &n)) continue;

        char cut_name[64];
        snprintf(cut_name, sizeof cut_name, "cut_%s", names[k]);
        const char *cut = temp_path(cut_name);
        CHECK(write_file(cut, bytes, n / 2));
        CHECK_MSG(rt_image_read(cut, &image, &err) == RT_ERROR_PARSE, "%s: %s", cut_name,
                  err.message);
        CHECK_CONTAINS(err.message, cut_name);
        CHECK(image.pixels == NULL);

        if (k == 0) {
            const char *damaged = temp_path("damaged.png");
            bytes[n / 2] ^= 0x10;
            CHECK(write_file(damaged, bytes, n));
            CHECK_EQ_INT(rt_image_read(damaged, &image, &err), RT_ERROR_PARSE);
            CHECK_CONTAINS(err.message, "damaged.png");
            CHECK_CONTAINS(err.message, "CRC");
        }
    }

    CHECK_EQ_INT(rt_image_read(temp_dir, &image, &err) != RT_OK, 1); /* a folder */
    CHECK_EQ_INT(rt_image_read(NULL, &image, &err), RT_ERROR_INVALID_ARGUMENT);
}

int main(void) {
    /* test_write_temp makes the per-process folder; the other files go next to it. */
    const char *marker = test_write_temp("marker", "");
    if (!marker) test_skip("cannot create a temporary folder");
    snprintf(temp_dir, sizeof temp_dir, "%s", marker);
    *strrchr(temp_dir, '/') = '\0';

    /* The library never prints: everything it says to stderr during the
     * tests is caught in a file and must be empty at the end. */
    fflush(stderr);
    int saved_stderr = dup(2);
    const char *captured = temp_path("stderr.txt");
    FILE *capture = fopen(captured, "w+");
    if (!capture || saved_stderr < 0) test_skip("cannot capture stderr");
    dup2(fileno(capture), 2);

    test_8bit_round_trip("levels.png");
    test_8bit_round_trip("levels.ppm");
    test_8bit_rounding();
    test_exr_round_trip();
    test_channel_counts();
    test_compare_figures();
    test_write_errors();
    test_read_errors();

    fflush(stderr);
    dup2(saved_stderr, 2);
    close(saved_stderr);
    fseek(capture, 0, SEEK_END);
    long printed = ftell(capture);
    if (printed > 0) { /* show it, so that the failure is easy to trace */
        char text[2048] = {0};
        fseek(capture, 0, SEEK_SET);
        fread(text, 1, sizeof text - 1, capture);
        fprintf(stderr, "printed during the tests:\n%s\n", text);
    }
    fclose(capture);
    CHECK_MSG(printed == 0, "the tests wrote %ld bytes to stderr", printed);

    char command[1024];
    snprintf(command, sizeof command, "rm -rf '%s'", temp_dir);
    if (system(command) != 0) fprintf(stderr, "could not remove %s\n", temp_dir);
    return TEST_END();
}
