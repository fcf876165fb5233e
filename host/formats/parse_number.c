/* SPDX-License-Identifier: Apache-2.0 */
/* parse_number.c - decimal integers and floats without strtof where exact.
 *
 * Why the float fast path is exact: a mantissa m <= 2^24 and 10^k for
 * k <= 10 (= 2^k * 5^k with 5^10 < 2^24) are both exact floats, and IEEE
 * multiplication and division round the exact result once, to nearest-even,
 * which is what strtof does for the decimal m * 10^e. This needs float
 * arithmetic to be evaluated in float (FLT_EVAL_METHOD 0); otherwise every
 * number goes to strtof. */
#include "formats/parse_number.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
#define FAST_FLOAT_EXACT 1
#else
#define FAST_FLOAT_EXACT 0
#endif

static const float exact_powers_of_ten[11] = {1e0f, 1e1f, 1e2f, 1e3f, 1e4f, 1e5f,
                                              1e6f, 1e7f, 1e8f, 1e9f, 1e10f};

static int lower(char c) {
    return (c >= 'A' && c <= 'Z') ? c + ('a' - 'A') : c;
}

/* Whether [p, end) starts with word, ignoring case. */
static int starts_with_word(const char *p, const char *end, const char *word) {
    size_t n = strlen(word);
    if ((size_t)(end - p) < n) return 0;
    for (size_t i = 0; i < n; i++)
        if (lower(p[i]) != word[i]) return 0;
    return 1;
}

/* strtof on a NUL-terminated copy of [p, q), which the caller has checked to
 * be a number in our grammar, so strtof reads exactly those bytes. */
static rt_number_result float_by_strtof(const char *p, const char *q, float *out) {
    char small[64];
    size_t n = (size_t)(q - p);
    char *buf = n < sizeof small ? small : malloc(n + 1);
    if (!buf) return RT_NUMBER_MALFORMED; /* cannot happen for sane input */
    memcpy(buf, p, n);
    buf[n] = '\0';
    float value = strtof(buf, NULL);
    if (buf != small) free(buf);
    if (!isfinite(value)) return RT_NUMBER_NOT_FINITE;
    *out = value;
    return RT_NUMBER_OK;
}

/* Past an optional '+' or '-' at s; *negative: it was '-'. */
static inline const char *skip_sign(const char *s, const char *end, int *negative) {
    *negative = s < end && *s == '-';
    return s < end && (*s == '+' || *s == '-') ? s + 1 : s;
}

rt_number_result rt_parse_float_full(const char *p, const char *end, float *out,
                                     const char **next) {
    int negative;
    const char *s = skip_sign(p, end, &negative);

    /* Mantissa: up to 19 significant digits fit in m; more go to strtof. */
    uint64_t m = 0;
    int significant = 0;
    int64_t exponent = 0;
    int digits = 0;
    for (; s < end && rt_is_digit(*s); s++, digits++) {
        if (m || *s != '0') {
            if (significant < 19)
                m = m * 10 + (uint64_t)(*s - '0');
            else
                exponent++;
            significant++;
        }
    }
    if (s < end && *s == '.') {
        s++;
        for (; s < end && rt_is_digit(*s); s++, digits++) {
            if (m || *s != '0') {
                if (significant < 19) {
                    m = m * 10 + (uint64_t)(*s - '0');
                    exponent--;
                }
                significant++;
            } else {
                exponent--;
            }
        }
    }
    if (digits == 0) {
        *next = p;
        const char *word = (p < end && (*p == '+' || *p == '-')) ? p + 1 : p;
        if (starts_with_word(word, end, "nan") || starts_with_word(word, end, "inf"))
            return RT_NUMBER_NOT_FINITE;
        return RT_NUMBER_MALFORMED;
    }
    if (s < end && (*s == 'e' || *s == 'E')) {
        int exp_negative;
        const char *e = skip_sign(s + 1, end, &exp_negative);
        if (e >= end || !rt_is_digit(*e)) {
            *next = e;
            return RT_NUMBER_MALFORMED;
        }
        int64_t written = 0;
        for (; e < end && rt_is_digit(*e); e++)
            if (written < 1000000) written = written * 10 + (*e - '0');
        exponent += exp_negative ? -written : written;
        s = e;
    }
    *next = s;

    if (m == 0) {
        *out = negative ? -0.0f : 0.0f;
        return RT_NUMBER_OK;
    }
    /* Trailing zeros of a long mantissa move into the exponent. */
    while (m > (1u << 24) && m % 10 == 0 && significant <= 19) {
        m /= 10;
        exponent++;
    }
    if (FAST_FLOAT_EXACT && significant <= 19 && m <= (1u << 24) && exponent >= -10 &&
        exponent <= 10) {
        float value = (float)m;
        if (exponent < 0)
            value = value / exact_powers_of_ten[-exponent];
        else
            value = value * exact_powers_of_ten[exponent];
        *out = negative ? -value : value;
        return RT_NUMBER_OK;
    }
    return float_by_strtof(p, s, out);
}

rt_number_result rt_parse_int64_full(const char *p, const char *end, int64_t *out,
                                     const char **next) {
    int negative;
    const char *s = skip_sign(p, end, &negative);
    if (s >= end || !rt_is_digit(*s)) {
        *next = p;
        return RT_NUMBER_MALFORMED;
    }
    const int64_t limit = (int64_t)1 << 62;
    int64_t value = 0;
    int too_large = 0;
    for (; s < end && rt_is_digit(*s); s++) {
        if (value > limit / 10)
            too_large = 1; /* keep reading the digits */
        else
            value = value * 10 + (*s - '0');
        if (value > limit) too_large = 1;
    }
    *next = s;
    if (too_large) return RT_NUMBER_TOO_LARGE;
    *out = negative ? -value : value;
    return RT_NUMBER_OK;
}
