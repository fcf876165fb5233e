/* SPDX-License-Identifier: Apache-2.0 */
/* frame_image.c - frames and AOVs as image files and display colours. */
#include "frame_image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

const cli_choice cli_aov_choices[] = {{"depth", RT_AOV_DEPTH},
                                      {"primid", RT_AOV_PRIMID},
                                      {"instid", RT_AOV_INSTID},
                                      {"normal", RT_AOV_NORMAL},
                                      {"boxtests", RT_AOV_BOX_TESTS},
                                      {"tritests", RT_AOV_TRI_TESTS},
                                      {NULL, 0}};

int cli_parse_aov(const char *name, rt_aov *out) {
    for (const cli_choice *c = cli_aov_choices; c->name; c++)
        if (strcmp(name, c->name) == 0) {
            *out = (rt_aov)c->value;
            return 1;
        }
    return 0;
}

const char *cli_aov_name(rt_aov aov) {
    for (const cli_choice *c = cli_aov_choices; c->name; c++)
        if (c->value == (int)aov) return c->name;
    return "shaded";
}

int cli_is_float_format(const char *path) {
    const rt_image_format *f = rt_image_format_of(path);
    return f && f->bits == 32;
}

void cli_image_formats_text(char *buf, size_t cap) {
    static const struct {
        int bits;
        const char *what;
    } groups[] = {{8, "8-bit (clamped)"}, {16, "16-bit (clamped)"}, {32, "32-bit float (linear)"}};
    size_t n = 0;
    buf[0] = 0;
    for (size_t g = 0; g < sizeof groups / sizeof groups[0]; g++) {
        int first = 1;
        for (int i = 0; rt_image_format_at(i) && n < cap; i++) {
            const rt_image_format *f = rt_image_format_at(i);
            if (f->bits != groups[g].bits) continue;
            n += (size_t)snprintf(buf + n, cap - n, "%s%s%s%s", first ? (g ? "; " : "") : ", ",
                                  first ? groups[g].what : "", first ? " " : "", f->extension);
            first = 0;
        }
    }
    int lossy = 0;
    for (int i = 0; rt_image_format_at(i) && n < cap; i++)
        if (rt_image_format_at(i)->lossy)
            n += (size_t)snprintf(buf + n, cap - n, "%s%s",
                                  lossy++ ? ", " : " (lossy: ", rt_image_format_at(i)->extension);
    if (lossy && n < cap) snprintf(buf + n, cap - n, ")");
}

/* An id as a colour that tells neighbours apart; black for -1 (a miss). */
static void false_colour(float id, float rgb[3]) {
    if (id < 0.0f) {
        rgb[0] = rgb[1] = rgb[2] = 0.0f;
        return;
    }
    uint32_t h = (uint32_t)id * 2654435761u;
    rgb[0] = 0.25f + 0.75f * (float)((h >> 8) & 255) / 255.0f;
    rgb[1] = 0.25f + 0.75f * (float)((h >> 16) & 255) / 255.0f;
    rgb[2] = 0.25f + 0.75f * (float)((h >> 24) & 255) / 255.0f;
}

float *cli_aov_to_display(const rt_framebuffer *fb, rt_aov aov) {
    size_t n = (size_t)fb->width * fb->height;
    float *rgb = malloc(3 * n * sizeof(float));
    if (!rgb) return NULL;
    float max = 0.0f;
    if (aov == RT_AOV_DEPTH || aov == RT_AOV_BOX_TESTS || aov == RT_AOV_TRI_TESTS)
        for (size_t i = 0; i < n; i++)
            if (isfinite(fb->pixels[i]) && fb->pixels[i] > max) max = fb->pixels[i];
    for (size_t i = 0; i < n; i++) {
        float *o = rgb + 3 * i;
        if (aov == RT_AOV_NORMAL) {
            for (int c = 0; c < 3; c++) o[c] = 0.5f + 0.5f * fb->pixels[3 * i + c];
        } else if (aov == RT_AOV_PRIMID || aov == RT_AOV_INSTID) {
            false_colour(fb->pixels[i], o);
        } else {
            float v = fb->pixels[i];
            float g = isfinite(v) && max > 0.0f ? v / max : (aov == RT_AOV_DEPTH ? 1.0f : 0.0f);
            o[0] = o[1] = o[2] = g;
        }
    }
    return rgb;
}

rt_status cli_frame_check(const char *path, rt_error *err) {
    return rt_image_check_output(path, err);
}

rt_status cli_frame_write(const char *path, const rt_framebuffer *fb, rt_aov aov, int metadata,
                          rt_error *err) {
    rt_image img = {fb->width, fb->height, fb->channels, fb->pixels};
    float *display = NULL;
    if (aov != RT_AOV_NONE && !cli_is_float_format(path)) {
        display = cli_aov_to_display(fb, aov);
        if (!display) {
            memset(err, 0, sizeof *err);
            err->status = RT_ERROR_OUT_OF_MEMORY;
            snprintf(err->message, sizeof err->message, "%s: out of memory", path);
            return err->status;
        }
        img.channels = 3;
        img.pixels = display;
    }
    rt_image_write_options options = {metadata};
    rt_status status = rt_image_write_with(path, &img, &options, err);
    free(display);
    return status;
}

void cli_image_formats_help(const char *help, char *buf, size_t cap) {
    char formats[1024];
    cli_image_formats_text(formats, sizeof formats);
    const char *mark = strstr(help, "{formats}");
    if (mark)
        snprintf(buf, cap, "%.*s%s%s", (int)(mark - help), help, formats, mark + 9);
    else
        snprintf(buf, cap, "%s", help);
}
