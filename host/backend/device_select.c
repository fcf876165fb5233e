/* SPDX-License-Identifier: Apache-2.0 */
/* device_select.c - see device_select.h. */
#include "backend/device_select.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"

static int contains_nocase(const char *hay, const char *needle) {
    size_t n = strlen(needle);
    for (; *hay; hay++) {
        size_t i = 0;
        while (i < n && hay[i] &&
               tolower((unsigned char)hay[i]) == tolower((unsigned char)needle[i]))
            i++;
        if (i == n) return 1;
    }
    return n == 0;
}

/* Entry i's field at offset. */
static const void *field(const void *devs, rt_device_fields f, int i, size_t offset) {
    return (const char *)devs + f.stride * (size_t)i + offset;
}

int rt_device_select(const char *api, const void *devs, int count, rt_device_fields fields,
                     const char *sel, rt_error *err) {
    if (!sel || !*sel) {
        for (int i = 0; i < count; i++)
            if (*(const int *)field(devs, fields, i, fields.exact)) return i;
        return count > 0 ? 0 : -1;
    }
    char *end;
    long idx = strtol(sel, &end, 10);
    if (end != sel && *end == 0) {
        if (idx >= 0 && idx < count) return (int)idx;
        rt_fail(err, RT_ERROR_INVALID_ARGUMENT,
                "no %s device %ld (there %s %d: 0..%d, see 'rtcl devices')", api, idx,
                count == 1 ? "is" : "are", count, count - 1);
        return -1;
    }
    for (int i = 0; i < count; i++)
        if (contains_nocase(field(devs, fields, i, fields.name), sel)) return i;
    rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "no %s device named like '%s' (see 'rtcl devices')",
            api, sel);
    return -1;
}
