/* SPDX-License-Identifier: Apache-2.0 */
/* cli_number.c - strict number parsing for rtcl's options (cli_number.h). */
#include "cli_number.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int is_digit(char c) {
    return c >= '0' && c <= '9';
}

static int is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/* The length of the number in the grammar at the start of s, 0 when none;
 * *fraction set when it has a point or an exponent (not an integer). */
static size_t scan(const char *s, int *fraction) {
    size_t i = 0, digits = 0;
    *fraction = 0;
    if (s[i] == '+' || s[i] == '-') i++;
    for (; is_digit(s[i]); i++) digits++;
    if (s[i] == '.') {
        *fraction = 1;
        for (i++; is_digit(s[i]); i++) digits++;
    }
    if (!digits) return 0;
    if (s[i] == 'e' || s[i] == 'E') {
        size_t e = i + 1;
        if (s[e] == '+' || s[e] == '-') e++;
        if (!is_digit(s[e])) return 0;
        while (is_digit(s[e])) e++;
        *fraction = 1;
        i = e;
    }
    return i;
}

/* "inf", "infinity", "nan" in any case, with an optional sign. */
static int is_not_finite_word(const char *s) {
    if (*s == '+' || *s == '-') s++;
    static const char *const words[] = {"inf", "infinity", "nan"};
    for (int w = 0; w < 3; w++) {
        size_t n = strlen(words[w]), k = 0;
        while (k < n && s[k] && (s[k] | 0x20) == words[w][k]) k++;
        if (k == n && (s[k] == '\0' || (w == 2 && s[k] == '('))) return 1;
    }
    return 0;
}

cli_number_fault cli_parse_number(const char *text, int integer, double *out) {
    if (!text || !*text) return CLI_NUMBER_EMPTY;
    size_t len = strlen(text);
    if (is_blank(text[0]) || is_blank(text[len - 1])) return CLI_NUMBER_BLANKS;
    if (is_not_finite_word(text)) return CLI_NUMBER_NOT_FINITE;
    int fraction;
    size_t n = scan(text, &fraction);
    if (n != len) return CLI_NUMBER_MALFORMED;
    if (integer) {
        if (fraction) return CLI_NUMBER_NOT_INTEGER;
        errno = 0;
        long long v = strtoll(text, NULL, 10);
        if (errno == ERANGE || v > (1LL << 53) || v < -(1LL << 53)) return CLI_NUMBER_TOO_LARGE;
        *out = (double)v;
        return CLI_NUMBER_OK;
    }
    errno = 0;
    double v = strtod(text, NULL);
    /* ERANGE on overflow (an infinity) is a fault; on underflow strtod
     * gives the correctly rounded subnormal or zero, which is the number. */
    if (!isfinite(v)) return CLI_NUMBER_TOO_LARGE;
    *out = v;
    return CLI_NUMBER_OK;
}

/* What each fault says of the text, by its value. */
static const char *const fault_texts[] = {[CLI_NUMBER_OK] = "is a number",
                                          [CLI_NUMBER_EMPTY] = "is empty",
                                          [CLI_NUMBER_BLANKS] = "has blank space around it",
                                          [CLI_NUMBER_MALFORMED] = "is not a number",
                                          [CLI_NUMBER_NOT_INTEGER] = "is not an integer",
                                          [CLI_NUMBER_NOT_FINITE] = "is not a finite number",
                                          [CLI_NUMBER_TOO_LARGE] = "is too large"};

const char *cli_number_fault_text(cli_number_fault fault) {
    return (unsigned)fault < sizeof fault_texts / sizeof *fault_texts ? fault_texts[fault]
                                                                      : "is not a number";
}
