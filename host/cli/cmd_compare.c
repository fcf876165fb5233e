/* cmd_compare.c - 'rtcl compare A B': how far two images are apart.
 *
 * Prints the figures of rt_image_compare and exits 0 when the largest channel
 * difference is within --max-diff (0 by default: identical), 1 when over,
 * 2 on a usage error or when an image cannot be read, compared or written. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "formats/image.h"

static const char usage_text[] =
    "usage: rtcl compare A B [--diff D] [--max-diff X]\n"
    "\n"
    "Compares two images of the same size and channel count, in any format\n"
    "OpenImageIO reads (8-bit files read as values in [0,1]), and prints the\n"
    "largest absolute channel difference, the RMSE over all channels, the PSNR\n"
    "(peak 1), the number of pixels with any channel different, and the first\n"
    "such pixel in row order with its values in A and B.\n"
    "\n"
    "options (in any order, before or after the images):\n"
    "  --diff D       write |A - B| per channel to D (.png, .ppm or .exr; PNG and\n"
    "                 PPM keep 8 bits, so use .exr to see small differences)\n"
    "  --max-diff X   largest absolute difference that still passes (default 0)\n"
    "  --help         show this text\n"
    "\n"
    "exit status: 0 when the largest difference is <= X, 1 when it is over,\n"
    "2 on a usage error or when an image cannot be read, compared (sizes or\n"
    "channel counts differ) or written.\n";

typedef struct compare_options {
    const char *paths[2];
    int path_count;
    const char *diff_path;
    double max_diff;
} compare_options;

static int usage_error(const char *fmt, const char *detail) {
    fprintf(stderr, "rtcl compare: ");
    fprintf(stderr, fmt, detail);
    fprintf(stderr, "\nusage: rtcl compare A B [--diff D] [--max-diff X] (see --help)\n");
    return 2;
}

/* The value of an option given as "--name VALUE" or "--name=VALUE"; NULL if
 * arg is not this option. *index moves past a separate value. */
static const char *option_value(const char *name, int argc, char **argv, int *index, int *missing) {
    const char *arg = argv[*index];
    size_t length = strlen(name);
    if (strncmp(arg, name, length) != 0) return NULL;
    if (arg[length] == '=') return arg + length + 1;
    if (arg[length] != '\0') return NULL;
    if (*index + 1 >= argc) {
        *missing = 1;
        return NULL;
    }
    *index += 1;
    return argv[*index];
}

/* Returns -1 when parsed, else the exit status (0 after --help). */
static int parse_options(int argc, char **argv, compare_options *options) {
    memset(options, 0, sizeof *options);
    int only_paths = 0;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        int missing = 0;
        const char *value;
        if (only_paths || arg[0] != '-' || arg[1] == '\0') {
            if (options->path_count == 2) return usage_error("one image too many: %s", arg);
            options->paths[options->path_count++] = arg;
        } else if (strcmp(arg, "--") == 0) {
            only_paths = 1;
        } else if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            fputs(usage_text, stdout);
            return 0;
        } else if ((value = option_value("--diff", argc, argv, &i, &missing)) || missing) {
            if (missing || !value[0]) return usage_error("%s needs a file name", "--diff");
            options->diff_path = value;
        } else if ((value = option_value("--max-diff", argc, argv, &i, &missing)) || missing) {
            if (missing) return usage_error("%s needs a number", "--max-diff");
            char *end = NULL;
            errno = 0;
            double x = strtod(value, &end);
            if (end == value || *end != '\0' || errno == ERANGE || !isfinite(x) || x < 0.0)
                return usage_error("--max-diff needs a number >= 0, not '%s'", value);
            options->max_diff = x;
        } else {
            return usage_error("unknown option %s", arg);
        }
    }
    if (options->path_count < 2) return usage_error("%s", "needs two images, A and B");
    return -1;
}

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
    int status = parse_options(argc, argv, &options);
    if (status >= 0) return status;

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
