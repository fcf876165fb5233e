/* SPDX-License-Identifier: Apache-2.0 */
/* bench_soft_math.c - kernels/rt_soft_math.h against the hardware on many
 * random operands, and its speed.
 *
 *   bench_soft_math [N] [div|sqrt|dop|all]     (N defaults to 10^9)
 *
 * For each function, N random operand sets (half of them uniformly random
 * bit patterns, half from the test generators of tests/soft_math_cases.h:
 * subnormals, quotients near the overflow and underflow thresholds, values
 * near each other, near-cancelling products) are compared bit for bit (any
 * NaN equals any NaN) with the hardware: '/' and sqrtf, and for a*b - c*d the
 * exact reference of test_core_soft_math.c (the products and their TwoSum in
 * double, rounded once). Mismatches must be 0. Then ns per operation, one
 * thread, over a 4096-entry operand buffer repeated: the soft function
 * against the hardware's '/', sqrtf and (float)((double)a*b - (double)c*d)
 * (the fp64 expression the soft one replaces; the compiler may vectorise the
 * hardware loops, as it would in real code). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rt_soft_math.h"
#include "../tests/soft_math_cases.h"

#define BUF 4096

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint32_t bits(float f) {
    return rt_sm_bits_(f);
}
static float flt(uint32_t u) {
    return rt_sm_float_(u);
}

static void operands(uint64_t *seed, long i, int fn, uint32_t q[4]) {
    if (i & 1) {
        for (int j = 0; j < 4; j++) q[j] = sm_rand(seed);
    } else if (fn == 0) {
        sm_div_pair(seed, &q[0], &q[1]);
    } else if (fn == 1) {
        q[0] = sm_operand(seed);
    } else {
        sm_dop_quad(seed, q);
    }
}

static const char *fn_names[3] = {"div", "sqrt", "diff_of_products"};

static long run(int fn, long n) {
    uint64_t seed = 0x0123456789abcdefull ^ (uint64_t)fn;
    long bad = 0;
    double t0 = now();
    for (long i = 0; i < n; i++) {
        uint32_t q[4], want, got;
        operands(&seed, i, fn, q);
        if (fn == 0) {
            want = bits(flt(q[0]) / flt(q[1]));
            got = rt_soft_div_bits(q[0], q[1]);
        } else if (fn == 1) {
            want = bits(sqrtf(flt(q[0])));
            got = rt_soft_sqrt_bits(q[0]);
        } else {
            want = sm_ref_dop(q[0], q[1], q[2], q[3]);
            got = rt_soft_diff_of_products_bits(q[0], q[1], q[2], q[3]);
        }
        if (!sm_same(want, got) && bad++ < 10)
            fprintf(stderr, "%s mismatch: %08x %08x %08x %08x: want %08x got %08x\n", fn_names[fn],
                    (unsigned)q[0], (unsigned)q[1], (unsigned)q[2], (unsigned)q[3], (unsigned)want,
                    (unsigned)got);
    }
    double t_check = now() - t0;

    /* Speed: the same 4096 operand sets, repeated. */
    static float a[BUF], b[BUF], c[BUF], d[BUF];
    static uint32_t out[BUF];
    for (int i = 0; i < BUF; i++) {
        uint32_t q[4];
        operands(&seed, i, fn, q);
        a[i] = flt(q[0]), b[i] = flt(q[1]), c[i] = flt(q[2]), d[i] = flt(q[3]);
    }
    long reps = 20000;
    volatile uint32_t sink = 0;
    double best_soft = 1e30, best_hw = 1e30;
    for (int trial = 0; trial < 3; trial++) {
        t0 = now();
        for (long r = 0; r < reps; r++) {
            if (fn == 0)
                for (int i = 0; i < BUF; i++) out[i] = bits(rt_soft_div(a[i], b[i]));
            else if (fn == 1)
                for (int i = 0; i < BUF; i++) out[i] = bits(rt_soft_sqrt(a[i]));
            else
                for (int i = 0; i < BUF; i++)
                    out[i] = bits(rt_soft_diff_of_products(a[i], b[i], c[i], d[i]));
            sink ^= out[r % BUF];
        }
        double ts = (now() - t0) / ((double)reps * BUF) * 1e9;
        t0 = now();
        for (long r = 0; r < reps; r++) {
            if (fn == 0)
                for (int i = 0; i < BUF; i++) out[i] = bits(a[i] / b[i]);
            else if (fn == 1)
                for (int i = 0; i < BUF; i++) out[i] = bits(sqrtf(a[i]));
            else
                for (int i = 0; i < BUF; i++)
                    out[i] = bits((float)((double)a[i] * b[i] - (double)c[i] * d[i]));
            sink ^= out[r % BUF];
        }
        double th = (now() - t0) / ((double)reps * BUF) * 1e9;
        if (ts < best_soft) best_soft = ts;
        if (th < best_hw) best_hw = th;
    }
    printf("%-17s %ld random operand sets checked, %ld mismatches (%.1f s); "
           "soft %.2f ns/op, hardware %.2f ns/op (best of 3 x %ld x %d)\n",
           fn_names[fn], n, bad, t_check, best_soft, best_hw, reps, BUF);
    return bad;
}

int main(int argc, char **argv) {
    long n = 1000000000L;
    const char *which = "all";
    if (argc > 1) {
        char *end;
        n = strtol(argv[1], &end, 10);
        if (*end || n < 1) {
            fprintf(stderr, "usage: %s [N] [div|sqrt|dop|all]\n", argv[0]);
            return 2;
        }
    }
    if (argc > 2) which = argv[2];
    int any = 0;
    long bad = 0;
    for (int fn = 0; fn < 3; fn++) {
        const char *short_name = fn == 2 ? "dop" : fn_names[fn];
        if (strcmp(which, "all") && strcmp(which, short_name)) continue;
        bad += run(fn, n);
        any = 1;
    }
    if (!any) {
        fprintf(stderr, "unknown function '%s'\n", which);
        return 2;
    }
    return bad ? 1 : 0;
}
