/* SPDX-License-Identifier: Apache-2.0 */
/* view_script.c - the --script file reader. */
#include "view_script.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static rt_status script_fail(rt_error *err, const char *path, int line, int column, const char *fmt,
                             ...) {
    memset(err, 0, sizeof *err);
    err->status = RT_ERROR_PARSE;
    err->line = line;
    err->column = column;
    snprintf(err->file, sizeof err->file, "%s", path);
    char reason[512];
    va_list args;
    va_start(args, fmt);
    vsnprintf(reason, sizeof reason, fmt, args);
    va_end(args);
    snprintf(err->message, sizeof err->message, "%s:%d:%d: %s", path, line, column, reason);
    return RT_ERROR_PARSE;
}

/* The next whitespace-separated word of *p: its start (NULL at the end of
 * the line) and length; *p moves past it. */
static const char *word(const char **p, size_t *len) {
    const char *s = *p;
    while (*s == ' ' || *s == '\t' || *s == '\r') s++;
    if (!*s || *s == '\n' || *s == '#') {
        *p = s;
        return NULL;
    }
    const char *e = s;
    while (*e && *e != ' ' && *e != '\t' && *e != '\r' && *e != '\n' && *e != '#') e++;
    *len = (size_t)(e - s);
    *p = e;
    return s;
}

static int word_is(const char *w, size_t n, const char *name) {
    return strlen(name) == n && strncmp(w, name, n) == 0;
}

static int parse_float(const char *w, size_t n, float *out) {
    char buf[64], *end;
    if (n >= sizeof buf) return 0;
    memcpy(buf, w, n);
    buf[n] = 0;
    errno = 0;
    double v = strtod(buf, &end);
    if (errno || *end || end == buf || !isfinite(v) || fabs(v) > 1e6) return 0;
    *out = (float)v;
    return 1;
}

/* Parses one line into ev; returns 1 for an event, 0 for a blank or
 * comment line, -1 after filling err. */
static int parse_line(const char *path, int line_no, const char *line, view_event *ev,
                      rt_error *err) {
    const char *p = line, *w;
    size_t n;
    memset(ev, 0, sizeof *ev);
    ev->line = line_no;
    if (!(w = word(&p, &n))) return 0;
    int col = (int)(w - line) + 1;
    char *end;
    errno = 0;
    long frame = strtol(w, &end, 10);
    if (errno || end != w + n || frame < 0 || frame > 100000000L) {
        script_fail(err, path, line_no, col, "'%.*s' is not a frame number (0..100000000)", (int)n,
                    w);
        return -1;
    }
    ev->frame = frame;
    if (!(w = word(&p, &n))) {
        script_fail(err, path, line_no, (int)(p - line) + 1,
                    "an action must follow the frame (down, up, tap, drag, wheel, "
                    "screenshot, quit)");
        return -1;
    }
    col = (int)(w - line) + 1;
    static const struct {
        const char *word;
        view_event_kind kind;
        int args;
    } actions[] = {{"down", VIEW_EVENT_DOWN, 1},   {"up", VIEW_EVENT_UP, 1},
                   {"tap", VIEW_EVENT_TAP, 1},     {"drag", VIEW_EVENT_DRAG, 2},
                   {"wheel", VIEW_EVENT_WHEEL, 1}, {"screenshot", VIEW_EVENT_SCREENSHOT, 1},
                   {"quit", VIEW_EVENT_QUIT, 0}};
    size_t act = 0;
    while (act < sizeof actions / sizeof *actions && !word_is(w, n, actions[act].word)) act++;
    if (act == sizeof actions / sizeof *actions) {
        script_fail(err, path, line_no, col,
                    "unknown action '%.*s' (down, up, tap, drag, wheel, screenshot, quit)", (int)n,
                    w);
        return -1;
    }
    ev->kind = actions[act].kind;
    const int args = actions[act].args;
    for (int a = 0; a < args; a++) {
        if (!(w = word(&p, &n))) {
            script_fail(err, path, line_no, (int)(p - line) + 1, "this action needs %d %s", args,
                        args == 1 ? "argument" : "arguments");
            return -1;
        }
        col = (int)(w - line) + 1;
        if (ev->kind == VIEW_EVENT_DOWN || ev->kind == VIEW_EVENT_UP ||
            ev->kind == VIEW_EVENT_TAP) {
            char name[32];
            snprintf(name, sizeof name, "%.*s", (int)(n < 31 ? n : 31), w);
            ev->key = n < 31 ? view_key_parse(name) : VIEW_KEY_NONE;
            if (ev->key == VIEW_KEY_NONE) {
                script_fail(err, path, line_no, col,
                            "unknown key '%.*s' (rtcl view --help lists the keys)", (int)n, w);
                return -1;
            }
        } else if (ev->kind == VIEW_EVENT_SCREENSHOT) {
            if (!(ev->path = malloc(n + 1))) {
                script_fail(err, path, line_no, col, "out of memory");
                err->status = RT_ERROR_OUT_OF_MEMORY;
                return -1;
            }
            memcpy(ev->path, w, n);
            ev->path[n] = 0;
            /* The file's folder and format are checked now, before the
             * session's work, not when the frame is due (issue 31). */
            rt_error check;
            if (rt_image_check_output(ev->path, &check) != RT_OK) {
                script_fail(err, path, line_no, col, "screenshot: %s", check.message);
                free(ev->path);
                ev->path = NULL;
                return -1;
            }
        } else if (!parse_float(w, n, a == 0 ? &ev->dx : &ev->dy)) {
            script_fail(err, path, line_no, col, "'%.*s' is not a number in -1e6..1e6", (int)n, w);
            return -1;
        }
    }
    if ((w = word(&p, &n))) {
        script_fail(err, path, line_no, (int)(w - line) + 1, "unexpected '%.*s' after the event",
                    (int)n, w);
        free(ev->path);
        ev->path = NULL;
        return -1;
    }
    return 1;
}

rt_status view_script_load(const char *path, view_script *out, rt_error *err) {
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "r");
    if (!f) {
        memset(err, 0, sizeof *err);
        err->status = RT_ERROR_IO;
        snprintf(err->file, sizeof err->file, "%s", path);
        snprintf(err->message, sizeof err->message, "%s: cannot open: %s", path, strerror(errno));
        return RT_ERROR_IO;
    }
    char line[4096];
    int line_no = 0;
    size_t capacity = 0;
    rt_status status = RT_OK;
    while (fgets(line, sizeof line, f)) {
        line_no++;
        size_t len = strlen(line);
        if (len == sizeof line - 1 && line[len - 1] != '\n' && !feof(f)) {
            status = script_fail(err, path, line_no, 1, "line longer than %d characters",
                                 (int)sizeof line - 2);
            break;
        }
        view_event ev;
        int r = parse_line(path, line_no, line, &ev, err);
        if (r < 0) {
            status = err->status;
            break;
        }
        if (r == 0) continue;
        if (out->count && ev.frame < out->events[out->count - 1].frame) {
            free(ev.path);
            status = script_fail(err, path, line_no, 1,
                                 "frame %ld comes after frame %ld: frames must not decrease",
                                 ev.frame, out->events[out->count - 1].frame);
            break;
        }
        if (out->count == capacity) {
            size_t cap = capacity ? 2 * capacity : 16;
            view_event *grown = realloc(out->events, cap * sizeof *grown);
            if (!grown) {
                free(ev.path);
                status = script_fail(err, path, line_no, 1, "out of memory");
                err->status = status = RT_ERROR_OUT_OF_MEMORY;
                break;
            }
            out->events = grown;
            capacity = cap;
        }
        out->events[out->count++] = ev;
    }
    if (status == RT_OK && ferror(f)) {
        memset(err, 0, sizeof *err);
        err->status = status = RT_ERROR_IO;
        snprintf(err->message, sizeof err->message, "%s: read error", path);
    }
    fclose(f);
    if (status != RT_OK) view_script_free(out);
    return status;
}

const view_event *view_script_next(view_script *script, long frame) {
    if (script->next < script->count && script->events[script->next].frame <= frame)
        return &script->events[script->next++];
    return NULL;
}

void view_script_free(view_script *script) {
    for (size_t i = 0; i < script->count; i++) free(script->events[i].path);
    free(script->events);
    memset(script, 0, sizeof *script);
}
