/* SPDX-License-Identifier: Apache-2.0 */
/* cmd_compare.c - 'rtcl compare A B': how far two images are apart.
 *
 * Prints the figures of rt_image_compare and exits 0 when the largest channel
 * difference is within --max-diff (0 by default: identical), 1 when over,
 * 2 on a usage error or when an image cannot be read, compared or written. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_options.h"
#include "commands.h"
#include "frame_image.h"
#include "rt.h"

typedef struct compare_options {
    const char *paths[2];
    const char *diff_path;
    double max_diff;
} compare_options;

static const cli_option compare_table[] = {
    {"--diff", 0, CLI_STRING, "D", offsetof(compare_options, diff_path), .flags = CLI_NONEMPTY,
     .help = "write |A - B| per channel to D, its format by the extension: {formats}; use a "
             "float format (.exr) to see small differences",
     .dynamic_help = cli_image_formats_help, .fallback = "none"},
    {"--max-diff", 0, CLI_FLOAT, "X", offsetof(compare_options, max_diff), 0.0, INFINITY,
     .help = "the largest absolute difference that still passes", .fallback = "0: identical"},
    {NULL}};

static const cli_group compare_groups[] = {{NULL, compare_table, 0}, {NULL}};

const cli_command cmd_compare_spec = {
    "compare",
    "compare two images (exit 1 when they differ too much)",
    "A B",
    "image",
    2,
    2,
    "Compares two images of the same size and channel count, in any format\n"
    "OpenImageIO reads (8-bit files read as values in [0,1]), and prints the\n"
    "largest absolute channel difference, the RMSE over all channels, the PSNR\n"
    "(peak 1), the number of pixels with any channel different, and the first\n"
    "such pixel in row order with its values in A and B. Options may come before\n"
    "or after the images.\n",
    compare_groups,
    "Exit status: 0 when the largest difference is <= X, 1 when it is over, 2 on a\n"
    "usage error or when an image cannot be read, compared (sizes or channel counts\n"
    "differ) or written.\n",
    NULL};

static void print_pixel(const rt_image *image, int x, int y) {
    const float *p = image->pixels + ((size_t)y * image->width + x) * image->channels;
    putchar('(');
    for (int c = 0; c < image->channels; c++) printf("%s%.9g", c ? ", " : "", p[c]);
    putchar(')');
}

static void print_figures(const compare_options *options, const rt_image *a, const rt_image *b,
                          const rt_image_diff *d) {
    printf("A: %s (%dx%d, %d channels)\n", options->paths[0], a->width, a->height, a->channels);
    printf("B: %s\n", options->paths[1]);
    printf("max abs difference: %.9g\n", d->max_abs);
    printf("RMSE:               %.9g\n", d->rmse);
    if (isinf(d->psnr) && d->psnr > 0)
        printf("PSNR:               inf (identical)\n");
    else
        printf("PSNR:               %.3f dB\n", d->psnr);
    printf("differing pixels:   %llu of %llu (%.4g%%)\n", (unsigned long long)d->differing,
           (unsigned long long)d->pixels,
           d->pixels ? 100.0 * (double)d->differing / (double)d->pixels : 0.0);
    if (d->first_x < 0) {
        printf("first difference:   none\n");
        return;
    }
    printf("first difference:   pixel (%d, %d): A = ", d->first_x, d->first_y);
    print_pixel(a, d->first_x, d->first_y);
    printf(", B = ");
    print_pixel(b, d->first_x, d->first_y);
    putchar('\n');
}

int cmd_compare(int argc, char **argv) {
    compare_options options;
    memset(&options, 0, sizeof options);
    int status;
    if (cli_parse(&cmd_compare_spec, &options, argc, argv, &status) < 0) return status;
    options.paths[0] = argv[0];
    options.paths[1] = argv[1];

    rt_image a = {0}, b = {0}, diff = {0};
    rt_error err;
    int exit_status = 2;
    /* The difference image's folder and format are checked before the
     * images are read. */
    if (options.diff_path && rt_image_check_output(options.diff_path, &err) != RT_OK) {
        fprintf(stderr, "rtcl compare: cannot write the difference image: %s\n", err.message);
        goto done;
    }
    if (rt_image_read(options.paths[0], &a, &err) != RT_OK ||
        rt_image_read(options.paths[1], &b, &err) != RT_OK) {
        fprintf(stderr, "rtcl compare: %s\n", err.message);
        goto done;
    }
    rt_image_diff d;
    if (rt_image_compare(&a, &b, &d, options.diff_path ? &diff : NULL, &err) != RT_OK) {
        fprintf(stderr, "rtcl compare: cannot compare %s with %s: %s\n", options.paths[0],
                options.paths[1], err.message);
        goto done;
    }
    print_figures(&options, &a, &b, &d);
    if (options.diff_path) {
        if (rt_image_write(options.diff_path, &diff, &err) != RT_OK) {
            fflush(stdout);
            fprintf(stderr, "rtcl compare: cannot write the difference image: %s\n", err.message);
            goto done;
        }
        printf("difference image:   %s\n", options.diff_path);
    }
    if (d.max_abs <= options.max_diff) {
        printf("result: pass (max abs difference %.9g <= --max-diff %.9g)\n", d.max_abs,
               options.max_diff);
        exit_status = 0;
    } else {
        printf("result: FAIL (max abs difference %.9g > --max-diff %.9g)\n", d.max_abs,
               options.max_diff);
        exit_status = 1;
    }

done:
    rt_image_free(&a);
    rt_image_free(&b);
    rt_image_free(&diff);
    return exit_status;
}
