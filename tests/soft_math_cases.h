/* SPDX-License-Identifier: Apache-2.0 */
/* soft_math_cases.h - operands for the tests of kernels/rt_soft_math.h: the
 * special values (every class of binary32 and the boundaries between them)
 * and random generators (bit patterns, values near each other, results near
 * the overflow and underflow thresholds, near-cancelling products).
 * And the references they are compared with. Header-only;
 * test_core_soft_math.c, test_soft_math_opencl.c and bench/bench_soft_math.c
 * share it. */
#ifndef RT_SOFT_MATH_CASES_H
#define RT_SOFT_MATH_CASES_H

#include <math.h>
#include <stdint.h>

#include "rt_soft_math.h"

/* xorshift64*: reproducible, good enough for operands. */
static inline uint32_t sm_rand(uint64_t *s) {
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (uint32_t)((*s * 2685821657736338717ull) >> 32);
}

/* The special values, both signs: fills out[] (at least 256 entries) and
 * returns the count. */
static inline int sm_specials(uint32_t *out) {
    static const uint32_t base[] = {
        0x00000000u,                                                     /* 0 */
        0x00000001u,                                                     /* smallest subnormal */
        0x00000002u, 0x00000003u, 0x00000555u, 0x00400000u,              /* 2^-127 */
        0x00400001u, 0x003fffffu, 0x00555555u, 0x007ffffeu, 0x007fffffu, /* largest subnormal */
        0x00800000u,                                                     /* smallest normal */
        0x00800001u, 0x00ffffffu, 0x01000000u, 0x01000001u, 0x0c000000u, /* 2^-103 */
        0x1f800000u,                                                     /* 2^-64 */
        0x33800000u,                                                     /* 2^-24 */
        0x34000000u,                                                     /* 2^-23 */
        0x3e800000u, 0x3eaaaaabu,                                        /* 1/3 */
        0x3dcccccdu,                                                     /* 0.1 */
        0x3f000000u, 0x3f7ffffeu, 0x3f7fffffu,                           /* 1 - 2^-24 */
        0x3f800000u,                                                     /* 1 */
        0x3f800001u, 0x3f800002u, 0x3fb504f3u,                           /* sqrt(2) */
        0x3fc00000u, 0x3fffffffu, 0x40000000u,                           /* 2 */
        0x40000001u, 0x40400000u,                                        /* 3 */
        0x40490fdbu,                                                     /* pi */
        0x40a00000u, 0x40e00000u, 0x41200000u, 0x4b000000u, 0x4b7fffffu, /* 2^24 - 1 */
        0x4b800000u, 0x4b800001u, 0x5f800000u,                           /* 2^64 */
        0x7e800000u,                                                     /* 2^126 */
        0x7effffffu, 0x7f000000u,                                        /* 2^127 */
        0x7f000001u, 0x7f7ffffeu, 0x7f7fffffu,                           /* largest normal */
        0x7f800000u,                                                     /* inf */
        0x7f800001u,                                                     /* signalling NaN */
        0x7fc00000u,                                                     /* quiet NaN */
        0x7fffffffu, 0x12345678u, 0x2b7c9a31u, 0x5d0f2e47u, 0x61e3c1a5u,
        0x0f0f0f0fu, 0x1b4e81b5u, 0x6f7fffffu, 0x10800000u, 0x6e800000u};
    int n = 0;
    for (unsigned i = 0; i < sizeof base / sizeof base[0]; i++) {
        out[n++] = base[i];
        out[n++] = base[i] | 0x80000000u;
    }
    /* Powers of two across the whole range, subnormal ones included. */
    for (int e = 0; e < 255; e += 9) out[n++] = (uint32_t)e << 23;
    for (int k = 0; k < 23; k += 5) out[n++] = 1u << k;
    return n;
}

/* A random operand: a bit pattern (1/4), a subnormal (1/8), near 1 (1/8), or
 * any finite value with a random exponent (the rest). */
static inline uint32_t sm_operand(uint64_t *s) {
    uint32_t r = sm_rand(s), kind = r & 7u, x = sm_rand(s);
    if (kind < 2) return x;
    if (kind == 2) return x & 0x807fffffu;
    if (kind == 3) return (x & 0x800fffffu) | (x & 1u ? 0x3f800000u : 0x3f000000u);
    return (x & 0x807fffffu) | ((r >> 8) % 255u) << 23;
}

/* x moved by a few ulps (the bit pattern, so it may cross a power of two). */
static inline uint32_t sm_nudge(uint64_t *s, uint32_t x) {
    uint32_t d = sm_rand(s) % 9u;
    uint32_t m = x & 0x7fffffffu;
    m = (uint32_t)((int32_t)m + (int32_t)d - 4);
    if (m >= 0x7f800000u) m = x & 0x7fffffffu;
    return (x & 0x80000000u) | m;
}

/* A pair whose quotient is near the over- or underflow threshold, or within
 * a few ulps of each other (quotient near 1). */
static inline void sm_div_pair(uint64_t *s, uint32_t *a, uint32_t *b) {
    uint32_t r = sm_rand(s), kind = r % 4u;
    uint32_t ea = 1u + (sm_rand(s) % 254u);
    *a = (sm_rand(s) & 0x807fffffu) | ea << 23;
    if (kind == 0) {
        *b = sm_nudge(s, *a) ^ (r & 0x80000000u);
    } else if (kind == 1) { /* a / b near 2^-126 .. 2^-150 */
        int eb = (int)ea + 126 + (int)(sm_rand(s) % 27u);
        if (eb > 254) eb = 254;
        *b = (sm_rand(s) & 0x807fffffu) | (uint32_t)eb << 23;
    } else if (kind == 2) { /* a / b near 2^128 */
        int eb = (int)ea - 127 - (int)(sm_rand(s) % 3u) + 1;
        if (eb < 0) eb = 0;
        *b = (sm_rand(s) & 0x807fffffu) | (uint32_t)eb << 23;
    } else {
        *b = sm_operand(s);
    }
}

/* Four operands whose products nearly cancel (c d within a few ulps of a b,
 * by nudging a pair of the operands), or with products near the over- or
 * underflow thresholds, or random. */
static inline void sm_dop_quad(uint64_t *s, uint32_t q[4]) {
    uint32_t r = sm_rand(s), kind = r % 5u;
    for (int i = 0; i < 4; i++) q[i] = sm_operand(s);
    if (kind <= 1) { /* c = a, d = b, each nudged: a b - c d cancels */
        int swap = (int)(r >> 8) & 1;
        q[2] = sm_nudge(s, q[swap ? 1 : 0]);
        q[3] = sm_nudge(s, q[swap ? 0 : 1]);
    } else if (kind == 2) { /* products near 2^-126 .. 2^-150 or 2^128 */
        int big = (int)(r >> 8) & 1;
        for (int i = 0; i < 4; i++) {
            uint32_t e = big ? 127u + 62u + sm_rand(s) % 3u : 127u - 63u - sm_rand(s) % 13u;
            q[i] = (q[i] & 0x807fffffu) | e << 23;
        }
    } else if (kind == 3) { /* one exponent far away: the sticky path */
        uint32_t e1 = 1u + sm_rand(s) % 254u, e2 = 1u + sm_rand(s) % 254u;
        q[0] = (q[0] & 0x807fffffu) | e1 << 23;
        q[1] = (q[1] & 0x807fffffu) | e2 << 23;
    }
}

/* ---- the references the tests and bench_soft_math compare with ---------- */

/* Bit for bit, but any NaN equals any NaN (payloads are not promised). */
static inline int sm_same(uint32_t x, uint32_t y) {
    return x == y || (rt_sm_is_nan_(x) && rt_sm_is_nan_(y));
}

/* The float nearest s + err (ties to even), where s = fl(s + err) in double. */
static inline float sm_round_sum(double s, double err) {
    float f = (float)s;
    if (err == 0.0 || (double)f == s || isinf(s)) return f;
    float lo, hi;
    if ((double)f < s) {
        lo = f;
        hi = nextafterf(f, INFINITY);
    } else {
        hi = f;
        lo = nextafterf(f, -INFINITY);
    }
    double dlo = isinf(lo) ? -0x1p128 : (double)lo, dhi = isinf(hi) ? 0x1p128 : (double)hi;
    double mid = 0.5 * (dlo + dhi); /* exact: 25 bits */
    if (s != mid) return f;         /* s + err is on s's side of the midpoint */
    return err > 0.0 ? hi : lo;
}

/* s + err = p + q exactly (Knuth's TwoSum, doubles). */
static inline void sm_two_sum(double p, double q, double *s, double *err) {
    *s = p + q;
    double bb = *s - p;
    *err = (p - (*s - bb)) + (q - bb);
}

/* The exact a b - c d rounded once: float products are exact in double, their
 * difference is exact as s + err. */
static inline uint32_t sm_ref_dop(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    double p = (double)rt_sm_float_(a) * (double)rt_sm_float_(b),
           q = (double)rt_sm_float_(c) * (double)rt_sm_float_(d);
    if (!isfinite(p) || !isfinite(q)) return rt_sm_bits_((float)(p - q));
    double s, err;
    sm_two_sum(p, -q, &s, &err);
    return rt_sm_bits_(sm_round_sum(s, err));
}

#endif /* RT_SOFT_MATH_CASES_H */
