/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_obj_numbers.c - the loaders' number parsing: floats bit-identical
 * to strtof, the accepted grammar, and integers. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "formats/parse_number.h"

static uint32_t bits_of(float f) {
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* Checks that text parses as a whole to exactly what strtof gives, or is
 * reported as not finite where strtof overflows. */
static int check_like_strtof(const char *text) {
    size_t len = strlen(text);
    char *end_ref;
    float ref = strtof(text, &end_ref);
    float got = 12345.0f;
    const char *next = NULL;
    rt_number_result res = rt_parse_float(text, text + len, &got, &next);
    if (!isfinite(ref)) {
        CHECK_MSG(res == RT_NUMBER_NOT_FINITE, "\"%s\": expected not finite, got %d", text,
                  (int)res);
        return res == RT_NUMBER_NOT_FINITE;
    }
    int ok = res == RT_NUMBER_OK && bits_of(got) == bits_of(ref) && next == text + len &&
             end_ref == text + len;
    CHECK_MSG(ok, "\"%s\": got %.9g (0x%08x, result %d), strtof %.9g (0x%08x)", text, got,
              bits_of(got), (int)res, ref, bits_of(ref));
    return ok;
}

static void test_edge_cases(void) {
    const char *cases[] = {
        "0",
        "-0",
        "+0",
        "0.0",
        "-0.0",
        ".5",
        "5.",
        "-.5",
        "1",
        "-1",
        "0.1",
        "0.2",
        "0.3",
        "16777216",
        "16777217",
        "16777218",
        "16777219",
        "33554431",
        "33554433",
        "0.000000001",
        "1e10",
        "1e11",
        "1e-10",
        "1e-11",
        "1E5",
        "1e+5",
        "1e-06",
        "2.5e-3",
        "3.4028235e38",
        "3.40282346e38",
        "3.4028235677973366e38",
        "1.17549435e-38",
        "1.4e-45",
        "1e-45",
        "7e-46",
        "7.1e-46",
        "1e-50",
        "0e999",
        "0.000e-999",
        "123456789012345678901234567890",
        "0.1000000000000000000000000001",
        "1.00000005960464477539062",
        "1.000000059604644775390625",
        "1.0000000596046447753906251",
        "0.0503644",
        "-0.0503375",
        "10.92724",
        "-1.631212",
        "0.100000000",
        "100000000000",
        "99999999999999999999",
        "1234567.125",
        "8388608.5",
        "8388609.5",
        "0.30000001192092896",
        "4.7019774e-38",
        "000000000000000000000000001.5",
        "1.5000000000000000000000000",
        "9.999999e9",
        "123.456e-7",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) check_like_strtof(cases[i]);
}

/* A tiny deterministic generator, so that failures repeat. */
static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static uint32_t rng(void) {
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (uint32_t)(rng_state >> 16);
}

static void test_random_strings(void) {
    int failures = 0;
    for (int n = 0; n < 300000 && failures < 10; n++) {
        char text[96];
        size_t k = 0;
        if (rng() % 3 == 0) text[k++] = (rng() & 1) ? '-' : '+';
        int digits = 1 + (int)(rng() % (n % 4 == 0 ? 30 : 10));
        int point = (int)(rng() % (unsigned)(digits + 2)) - 1; /* -1: no point */
        for (int d = 0; d < digits; d++) {
            if (d == point) text[k++] = '.';
            text[k++] = (char)('0' + rng() % 10);
        }
        if (point == digits) text[k++] = '.';
        if (rng() % 3 == 0) {
            text[k++] = (rng() & 1) ? 'e' : 'E';
            int e = (int)(rng() % 90) - 50;
            k += (size_t)snprintf(text + k, sizeof text - k, (rng() & 1) ? "%d" : "%+d", e);
        }
        text[k] = '\0';
        if (!check_like_strtof(text)) failures++;
    }
    /* Random float bit patterns printed with 6 to 9 significant digits. */
    for (int n = 0; n < 200000 && failures < 10; n++) {
        uint32_t u = rng() ^ (rng() << 16);
        float f;
        memcpy(&f, &u, sizeof f);
        if (!isfinite(f)) continue;
        char text[64];
        snprintf(text, sizeof text, (n & 1) ? "%.*g" : "%.*f", 6 + n % 4, (double)f);
        if (strlen(text) < 60 && !check_like_strtof(text)) failures++;
    }
    CHECK_EQ_INT(failures, 0);
}

static void expect_float_result(const char *text, rt_number_result expected, size_t consumed) {
    float v;
    const char *next = NULL;
    rt_number_result res = rt_parse_float(text, text + strlen(text), &v, &next);
    CHECK_MSG(res == expected, "\"%s\": result %d, expected %d", text, (int)res, (int)expected);
    if (expected == RT_NUMBER_OK)
        CHECK_MSG(next == text + consumed, "\"%s\": consumed %d, expected %d", text,
                  (int)(next - text), (int)consumed);
}

static void test_grammar(void) {
    expect_float_result("abc", RT_NUMBER_MALFORMED, 0);
    expect_float_result("", RT_NUMBER_MALFORMED, 0);
    expect_float_result("-", RT_NUMBER_MALFORMED, 0);
    expect_float_result(".", RT_NUMBER_MALFORMED, 0);
    expect_float_result("1e", RT_NUMBER_MALFORMED, 0);
    expect_float_result("1e+", RT_NUMBER_MALFORMED, 0);
    expect_float_result("nan", RT_NUMBER_NOT_FINITE, 0);
    expect_float_result("-NaN", RT_NUMBER_NOT_FINITE, 0);
    expect_float_result("inf", RT_NUMBER_NOT_FINITE, 0);
    expect_float_result("-Infinity", RT_NUMBER_NOT_FINITE, 0);
    expect_float_result("1e39", RT_NUMBER_NOT_FINITE, 0);
    expect_float_result("-1e39", RT_NUMBER_NOT_FINITE, 0);
    expect_float_result("1e999999999999", RT_NUMBER_NOT_FINITE, 0);
    /* The number stops where the grammar does; the caller judges the rest. */
    expect_float_result("1.2.3", RT_NUMBER_OK, 3);
    expect_float_result("0x1p3", RT_NUMBER_OK, 1);
    expect_float_result("1.5/2", RT_NUMBER_OK, 3);
    expect_float_result("2e3x", RT_NUMBER_OK, 3);
    /* Not NUL-terminated: the parser must stop at end. */
    const char digits[] = "123456";
    float v;
    const char *next;
    CHECK(rt_parse_float(digits, digits + 3, &v, &next) == RT_NUMBER_OK && v == 123.0f);
    CHECK(next == digits + 3);
}

static void test_integers(void) {
    int64_t v = 0;
    const char *next;
    const char *t = "42 ";
    CHECK(rt_parse_int64(t, t + 3, &v, &next) == RT_NUMBER_OK && v == 42 && next == t + 2);
    t = "-7/";
    CHECK(rt_parse_int64(t, t + 3, &v, &next) == RT_NUMBER_OK && v == -7 && next == t + 2);
    t = "+3";
    CHECK(rt_parse_int64(t, t + 2, &v, &next) == RT_NUMBER_OK && v == 3);
    t = "x";
    CHECK(rt_parse_int64(t, t + 1, &v, &next) == RT_NUMBER_MALFORMED);
    t = "-";
    CHECK(rt_parse_int64(t, t + 1, &v, &next) == RT_NUMBER_MALFORMED);
    t = "123456789012345678"; /* 18 digits: the fast path */
    CHECK(rt_parse_int64(t, t + strlen(t), &v, &next) == RT_NUMBER_OK && v == 123456789012345678ll);
    t = "1234567890123456789"; /* 19 digits: the full parser */
    CHECK(rt_parse_int64(t, t + strlen(t), &v, &next) == RT_NUMBER_OK &&
          v == 1234567890123456789ll);
    t = "99999999999999999999999";
    CHECK(rt_parse_int64(t, t + strlen(t), &v, &next) == RT_NUMBER_TOO_LARGE);
    CHECK(next == t + strlen(t));
}

int main(void) {
    test_edge_cases();
    test_random_strings();
    test_grammar();
    test_integers();
    return TEST_END();
}
