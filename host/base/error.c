/* SPDX-License-Identifier: Apache-2.0 */
/* error.c - error values with their place of origin. */
#include "base/error.h"

#include <stdio.h>
#include <string.h>

/* One name per rt_status, in the enum's order (RT_OK = 0 upwards). */
static const char *const status_names[] = {"ok",           "invalid argument", "i/o error",
                                           "parse error",  "out of memory",    "unsupported",
                                           "backend error"};
_Static_assert(sizeof status_names / sizeof *status_names == RT_ERROR_BACKEND + 1,
               "a name for every rt_status");

const char *rt_status_string(rt_status status) {
    return (unsigned)status < sizeof status_names / sizeof *status_names ? status_names[status]
                                                                         : "unknown status";
}

const char *rt_code_name_find(const rt_code_name *table, size_t count, int code,
                              const char *fallback) {
    for (size_t i = 0; i < count; i++)
        if (table[i].code == code) return table[i].name;
    return fallback;
}

void rt_error_clear(rt_error *err) {
    if (!err) return;
    memset(err, 0, sizeof *err);
}

rt_status rt_error_setv(rt_error *err, rt_status status, const char *file, int line, int column,
                        const char *fmt, va_list args) {
    if (!err) return status;
    char reason[768];
    vsnprintf(reason, sizeof reason, fmt, args);
    err->status = status;
    err->line = line;
    err->column = column;
    snprintf(err->file, sizeof err->file, "%s", file ? file : "");
    if (file && line > 0 && column > 0)
        snprintf(err->message, sizeof err->message, "%s:%d:%d: %s", file, line, column, reason);
    else if (file && line > 0)
        snprintf(err->message, sizeof err->message, "%s:%d: %s", file, line, reason);
    else if (file)
        snprintf(err->message, sizeof err->message, "%s: %s", file, reason);
    else
        snprintf(err->message, sizeof err->message, "%s", reason);
    return status;
}

rt_status rt_error_set(rt_error *err, rt_status status, const char *file, int line, int column,
                       const char *fmt, ...) {
    va_list args;
    va_start(args, fmt);
    rt_error_setv(err, status, file, line, column, fmt, args);
    va_end(args);
    return status;
}

rt_status rt_fail(rt_error *err, rt_status status, const char *fmt, ...) {
    va_list args;
    va_start(args, fmt);
    rt_error_setv(err, status, NULL, 0, 0, fmt, args);
    va_end(args);
    return status;
}

rt_status rt_error_prefix(rt_error *err, rt_status st, const char *prefix) {
    if (st != RT_OK && err && strncmp(err->message, prefix, strlen(prefix)) != 0) {
        char reason[sizeof err->message];
        memcpy(reason, err->message, sizeof reason);
        snprintf(err->message, sizeof err->message, "%s%.1000s", prefix, reason);
    }
    return st;
}

rt_status rt_error_copy(rt_error *dst, const rt_error *src) {
    if (dst && dst != src) *dst = *src;
    return src->status;
}
