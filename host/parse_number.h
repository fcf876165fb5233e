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

#include <stdint.h>

typedef enum rt_number_result {
    RT_NUMBER_OK = 0,
    RT_NUMBER_MALFORMED,  /* no number here, or an exponent without digits */
    RT_NUMBER_NOT_FINITE, /* "nan", "inf", "infinity" or a value beyond float's range */
    RT_NUMBER_TOO_LARGE   /* an integer beyond +-2^62 */
} rt_number_result;

rt_number_result rt_parse_float(const char *p, const char *end, float *out, const char **next);

/* [+-] digits. */
rt_number_result rt_parse_int64(const char *p, const char *end, int64_t *out, const char **next);

#endif /* RT_PARSE_NUMBER_H */
