/* SPDX-License-Identifier: Apache-2.0 */
/* parse_number.h - fast decimal number parsing for the text loaders.
 *
 * The parsers read from [p, end) and need no terminating NUL. They stop at
 * the first byte that cannot continue the number and report it in *next; the
 * caller decides whether that byte may follow a number (a blank, a '/', ...).
 *
 * Floats are bit-identical to strtof on the same text: short mantissas with
 * small exponents are computed exactly (one correctly rounded float operation
 * on exact operands), everything else goes to strtof. Accepted grammar:
 * [+-] digits [. digits] [(e|E) [+-] digits], at least one mantissa digit;
 * no hex floats, no "inf"/"nan" (they are reported as not finite). */
#ifndef RT_PARSE_NUMBER_H
#define RT_PARSE_NUMBER_H

#include <float.h>
#include <stdint.h>

typedef enum rt_number_result {
    RT_NUMBER_OK = 0,
    RT_NUMBER_MALFORMED,  /* no number here, or an exponent without digits */
    RT_NUMBER_NOT_FINITE, /* "nan", "inf", "infinity" or a value beyond float's range */
    RT_NUMBER_TOO_LARGE   /* an integer beyond +-2^62 */
} rt_number_result;

/* The complete parsers; the inline versions below call them for anything
 * off their fast path. */
rt_number_result rt_parse_float_full(const char *p, const char *end, float *out, const char **next);
rt_number_result rt_parse_int64_full(const char *p, const char *end, int64_t *out,
                                     const char **next);

static inline int rt_is_digit(char c) {
    return (unsigned)(c - '0') < 10u;
}

/* The common case of model files, inlined into the loaders' loops: a sign,
 * at most 19 digits with an optional point, an optional exponent, and a
 * value that is exact as computed (see parse_number.c). */
static inline rt_number_result rt_parse_float(const char *p, const char *end, float *out,
                                              const char **next) {
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
    static const float powers[11] = {1e0f, 1e1f, 1e2f, 1e3f, 1e4f, 1e5f,
                                     1e6f, 1e7f, 1e8f, 1e9f, 1e10f};
    const char *s = p;
    int negative = 0;
    if (s < end && (*s == '-' || *s == '+')) negative = *s++ == '-';
    const char *digits_start = s;
    uint64_t m = 0;
    while (s < end && rt_is_digit(*s)) m = m * 10 + (uint64_t)(*s++ - '0');
    int digits = (int)(s - digits_start), fraction = 0;
    if (s < end && *s == '.') {
        const char *fraction_start = ++s;
        while (s < end && rt_is_digit(*s)) m = m * 10 + (uint64_t)(*s++ - '0');
        fraction = (int)(s - fraction_start);
        digits += fraction;
    }
    int exponent = 0;
    if (s < end && (*s == 'e' || *s == 'E')) {
        const char *e = s + 1;
        int exp_negative = 0;
        if (e < end && (*e == '-' || *e == '+')) exp_negative = *e++ == '-';
        if (e + 1 < end && rt_is_digit(e[0]) && rt_is_digit(e[1]) &&
            !(e + 2 < end && rt_is_digit(e[2]))) {
            exponent = (e[0] - '0') * 10 + (e[1] - '0');
            s = e + 2;
        } else if (e < end && rt_is_digit(e[0]) && !(e + 1 < end && rt_is_digit(e[1]))) {
            exponent = e[0] - '0';
            s = e + 1;
        } else {
            digits = 0; /* let the full parser handle it */
        }
        if (exp_negative) exponent = -exponent;
    }
    exponent -= fraction;
    if (digits > 0 && digits <= 19 && m <= (1u << 24) && exponent >= -10 && exponent <= 10) {
        float value = (float)m;
        value = exponent < 0 ? value / powers[-exponent] : value * powers[exponent];
        *out = negative ? -value : value;
        *next = s;
        return RT_NUMBER_OK;
    }
#endif
    return rt_parse_float_full(p, end, out, next);
}

/* [+-] digits. */
static inline rt_number_result rt_parse_int64(const char *p, const char *end, int64_t *out,
                                              const char **next) {
    const char *s = p;
    int negative = 0;
    if (s < end && (*s == '-' || *s == '+')) negative = *s++ == '-';
    const char *digits_start = s;
    int64_t value = 0;
    /* At most 18 digits here (no overflow); longer go to the full parser. */
    const char *limit = end - s > 18 ? s + 18 : end;
    while (s < limit && rt_is_digit(*s)) value = value * 10 + (*s++ - '0');
    if (s == digits_start || (s < end && rt_is_digit(*s)))
        return rt_parse_int64_full(p, end, out, next);
    *out = negative ? -value : value;
    *next = s;
    return RT_NUMBER_OK;
}

#endif /* RT_PARSE_NUMBER_H */
