/* SPDX-License-Identifier: Apache-2.0 */
/* error.h - filling rt_error and the scene's last-error text. */
#ifndef RT_ERROR_H
#define RT_ERROR_H

#include <stdarg.h>
#include <stddef.h>

#include "rt.h"

/* Sets err (if not NULL) to status with a message "file:line:column: reason"
 * (line/column left out when 0; file left out when NULL). Returns status so
 * that callers can write: return rt_error_set(err, ...); */
#if defined(__GNUC__)
__attribute__((format(printf, 6, 7)))
#endif
rt_status
rt_error_set(rt_error *err, rt_status status, const char *file, int line, int column,
             const char *fmt, ...);

rt_status rt_error_setv(rt_error *err, rt_status status, const char *file, int line, int column,
                        const char *fmt, va_list args);

/* rt_error_set with no place: for errors that are not about a file. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
rt_status
rt_fail(rt_error *err, rt_status status, const char *fmt, ...);

/* Copies src into dst (if not NULL) and returns src's status. */
rt_status rt_error_copy(rt_error *dst, const rt_error *src);

/* When st is a failure and err's message does not start with prefix
 * ("opencl: "), puts prefix before the message (the first 1000 characters
 * of it). Returns st, so that a backend can write: return
 * rt_error_prefix(err, st, "vulkan: "); */
rt_status rt_error_prefix(rt_error *err, rt_status st, const char *prefix);

/* Clears err to RT_OK with an empty message. */
void rt_error_clear(rt_error *err);

/* A driver's code and its name, for the tables that name an API's error
 * codes (OpenCL's, Vulkan's). */
typedef struct rt_code_name {
    int code;
    const char *name;
} rt_code_name;

/* The name of code among the count entries of table, or fallback. */
const char *rt_code_name_find(const rt_code_name *table, size_t count, int code,
                              const char *fallback);

#endif /* RT_ERROR_H */
