/* SPDX-License-Identifier: Apache-2.0 */
/* json_bulk.c - see json_bulk.h. */
#include "formats/json_bulk.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

static int is_digit(char c) {
    return c >= '0' && c <= '9';
}

/* The end of the JSON number at text[p] by jansson's grammar (-?(0|[1-9]
 * digits)(.digits)?([eE][+-]?digits)?), or 0 when there is none; *integer
 * when it has no fraction or exponent. */
static size_t number_end(const char *text, size_t len, size_t p, int *integer) {
    size_t i = p;
    if (i < len && text[i] == '-') i++;
    if (i >= len || !is_digit(text[i])) return 0;
    if (text[i] == '0') {
        i++;
        if (i < len && is_digit(text[i])) return 0; /* a leading zero */
    } else {
        while (i < len && is_digit(text[i])) i++;
    }
    *integer = 1;
    if (i < len && text[i] == '.') {
        *integer = 0;
        i++;
        if (i >= len || !is_digit(text[i])) return 0;
        while (i < len && is_digit(text[i])) i++;
    }
    if (i < len && (text[i] == 'e' || text[i] == 'E')) {
        *integer = 0;
        i++;
        if (i < len && (text[i] == '+' || text[i] == '-')) i++;
        if (i >= len || !is_digit(text[i])) return 0;
        while (i < len && is_digit(text[i])) i++;
    }
    return i;
}

/* The number text[p..q) as jansson reads it: an integer with strtoll (0
 * when out of long long's range, which jansson refuses), a real with strtod
 * (0 when it overflows, which jansson refuses). */
static int number_value(const char *text, size_t p, size_t q, int integer, long long *ivalue,
                        double *rvalue) {
    char small[64];
    size_t n = q - p;
    char *buf = n < sizeof small ? small : malloc(n + 1);
    if (!buf) return 0;
    memcpy(buf, text + p, n);
    buf[n] = '\0';
    int ok = 1;
    errno = 0;
    if (integer) {
        *ivalue = strtoll(buf, NULL, 10);
        ok = errno != ERANGE;
    } else {
        *rvalue = strtod(buf, NULL);
        ok = !(errno == ERANGE && isinf(*rvalue));
    }
    if (buf != small) free(buf);
    return ok;
}

/* Whether the number's value could be beyond jansson's ranges (then it is
 * converted to find out): long integers, long reals, any exponent. */
static int may_overflow(const char *text, size_t p, size_t q, int integer) {
    if (q - p > 18) return 1;
    if (integer) return 0;
    for (size_t i = p; i < q; i++)
        if (text[i] == 'e' || text[i] == 'E') return 1;
    return 0;
}

/* The array at text[p] == '[' if it holds only numbers jansson accepts:
 * 1 with its end (one past ']') and count, else 0. */
static int number_array(const char *text, size_t len, size_t p, size_t *end, size_t *count) {
    size_t i = p + 1, n = 0;
    while (i < len && is_space(text[i])) i++;
    if (i < len && text[i] == ']') return 0; /* empty: jansson's */
    for (;;) {
        int integer;
        size_t q = number_end(text, len, i, &integer);
        if (!q) return 0;
        if (may_overflow(text, i, q, integer)) {
            long long iv;
            double rv;
            if (!number_value(text, i, q, integer, &iv, &rv)) return 0;
        }
        n++;
        i = q;
        while (i < len && is_space(text[i])) i++;
        if (i < len && text[i] == ']') break;
        if (i >= len || text[i] != ',') return 0;
        i++;
        while (i < len && is_space(text[i])) i++;
    }
    *end = i + 1;
    *count = n;
    return 1;
}

/* Past the string at text[p] == '"' (escapes skipped, not decoded). */
static size_t string_end(const char *text, size_t len, size_t p) {
    size_t i = p + 1;
    while (i < len && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
    return i < len ? i + 1 : len;
}

static int is_bulk_key(const char *key, size_t n) {
    return (n == 9 && memcmp(key, "positions", 9) == 0) ||
           (n == 7 && memcmp(key, "normals", 7) == 0) ||
           (n == 9 && memcmp(key, "triangles", 9) == 0);
}

static int add(rt_json_bulk_table *t, size_t start, size_t end, size_t count) {
    if (t->count == t->capacity) {
        size_t cap = t->capacity ? 2 * t->capacity : 16;
        rt_json_bulk *a = realloc(t->arrays, cap * sizeof *a);
        if (!a) return 0;
        t->arrays = a;
        t->capacity = cap;
    }
    t->arrays[t->count++] = (rt_json_bulk){start, end, count, 0};
    return 1;
}

int rt_json_bulk_scan(const char *text, size_t len, rt_json_bulk_table *table) {
    memset(table, 0, sizeof *table);
    /* Strings are skipped whole, so that brackets and quotes in them do not
     * count; a string followed by ':' is a key. Anything malformed is left
     * to jansson, which reports it before it reaches any later array. */
    for (size_t i = 0; i < len;) {
        if (text[i] != '"') {
            i++;
            continue;
        }
        size_t key = i + 1, after = string_end(text, len, i);
        size_t key_len = after > key ? after - key - 1 : 0;
        i = after;
        size_t j = i;
        while (j < len && is_space(text[j])) j++;
        if (j >= len || text[j] != ':' || !is_bulk_key(text + key, key_len)) continue;
        j++;
        while (j < len && is_space(text[j])) j++;
        size_t end, count;
        if (j < len && text[j] == '[' && number_array(text, len, j, &end, &count) &&
            end - j >= RT_JSON_BULK_MIN_BYTES) {
            if (!add(table, j, end, count)) {
                rt_json_bulk_free(table);
                return 0;
            }
            i = end;
        }
    }
    return 1;
}

rt_json_bulk *rt_json_bulk_at(rt_json_bulk_table *table, size_t offset) {
    size_t lo = 0, hi = table->count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (table->arrays[mid].start < offset)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < table->count && table->arrays[lo].start == offset ? &table->arrays[lo] : NULL;
}

void rt_json_bulk_free(rt_json_bulk_table *table) {
    free(table->arrays);
    memset(table, 0, sizeof *table);
}

size_t rt_json_bulk_read(void *buffer, size_t size, void *data) {
    rt_json_bulk_reader *r = data;
    char *out = buffer;
    size_t n = 0;
    while (n < size && r->pos < r->len) {
        const rt_json_bulk *b = r->next < r->table->count ? &r->table->arrays[r->next] : NULL;
        if (b && r->pos >= b->end) {
            r->next++;
            continue;
        }
        if (!b || r->pos < b->start) {
            size_t stop = b ? b->start : r->len, k = stop - r->pos;
            if (k > size - n) k = size - n;
            memcpy(out + n, r->text + r->pos, k);
            n += k;
            r->pos += k;
            continue;
        }
        /* Inside an array: its placeholder, then blanks to its end. */
        char placeholder[48];
        int m = snprintf(placeholder, sizeof placeholder, "[{\"\":%zu}]", b->start);
        size_t from = r->pos - b->start;
        while (n < size && r->pos < b->end) {
            out[n++] = from < (size_t)m ? placeholder[from] : ' ';
            from++;
            r->pos++;
        }
    }
    return n;
}

int rt_json_bulk_next(const char *text, size_t end, size_t *pos, size_t *at, int *integer,
                      long long *ivalue, double *rvalue) {
    size_t i = *pos;
    while (i < end && (is_space(text[i]) || text[i] == '[' || text[i] == ',')) i++;
    if (i >= end || text[i] == ']') return 0;
    size_t q = number_end(text, end, i, integer);
    if (!q) return 0; /* the scan accepted the array: cannot happen */
    *at = i;
    if (!number_value(text, i, q, *integer, ivalue, rvalue)) return 0;
    *pos = q;
    return 1;
}
