/* test_core_soft_math.c - kernels/rt_soft_math.h against the hardware and an
 * exact reference, bit for bit (any NaN equals any NaN).
 *
 * rt_soft_div and rt_soft_sqrt against the CPU's '/' and sqrtf (correctly
 * rounded on x86-64 SSE and AArch64): all pairs of the special values
 * (tests/soft_math_cases.h), quotients that are exact midpoints (they exist
 * only for subnormal results) and the operands one ulp beside them, operands
 * whose square roots are within an ulp of a midpoint, and 10^6 random
 * operands of each kind. rt_soft_diff_of_products against an exact
 * reference: in double both products are exact, TwoSum gives their
 * difference exactly as s + err, and s + err is rounded to float by the
 * hardware's conversion with the one case it cannot see (s exactly a float
 * midpoint, err != 0) decided by err's sign. The _ftz variants against the
 * hardware with flush to zero and denormals-are-zero set (MXCSR on x86-64,
 * FPCR.FZ on AArch64 for division and sqrt, where no quotient can fall in
 * the band in which the two architectures' tininess rules differ), and
 * against the reference for the difference of products. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "rt_soft_math.h"
#include "soft_math_cases.h"

#if defined(__SSE2__)
#include <xmmintrin.h>
#define SM_HAVE_FTZ 1
static unsigned sm_csr_saved;
static void ftz_on(void) {
    sm_csr_saved = _mm_getcsr();
    _mm_setcsr(sm_csr_saved | 0x8040u); /* FTZ (bit 15) | DAZ (bit 6) */
}
static void ftz_off(void) {
    _mm_setcsr(sm_csr_saved);
}
#elif defined(__aarch64__)
#define SM_HAVE_FTZ 1
static uint64_t sm_fpcr_saved;
static void ftz_on(void) {
    uint64_t v;
    __asm__ volatile("mrs %0, fpcr" : "=r"(v));
    sm_fpcr_saved = v;
    v |= (uint64_t)1 << 24; /* FZ: inputs and results */
    __asm__ volatile("msr fpcr, %0" : : "r"(v));
}
static void ftz_off(void) {
    __asm__ volatile("msr fpcr, %0" : : "r"(sm_fpcr_saved));
}
#else
#define SM_HAVE_FTZ 0
static void ftz_on(void) {}
static void ftz_off(void) {}
#endif

static uint32_t bits(float f) {
    return rt_sm_bits_(f);
}
static float flt(uint32_t u) {
    return rt_sm_float_(u);
}

/* The hardware, through volatile so that nothing is folded at compile time
 * (and so that the current MXCSR / FPCR applies). */
static uint32_t hw_div(uint32_t a, uint32_t b) {
    volatile float x = flt(a), y = flt(b);
    volatile float q = x / y;
    return bits(q);
}
static uint32_t hw_sqrt(uint32_t a) {
    volatile float x = flt(a);
    volatile float r = sqrtf(x);
    return bits(r);
}

/* ---- the exact reference for a b - c d ---- */

static uint32_t daz(uint32_t x) {
    return (x & 0x7f800000u) ? x : (x & 0x80000000u);
}

/* x86's flush to zero: a result whose 24-bit rounding (unbounded exponent)
 * is below 2^-126 becomes a zero of its sign. */
static uint32_t ref_dop_ftz(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    a = daz(a), b = daz(b), c = daz(c), d = daz(d);
    double p = (double)flt(a) * (double)flt(b), q = (double)flt(c) * (double)flt(d);
    if (!isfinite(p) || !isfinite(q)) return bits((float)(p - q));
    double s, err;
    sm_two_sum(p, -q, &s, &err);
    if (fabs(s) >= 0x1p-125) return bits(sm_round_sum(s, err));
    if (fabs(s) < 0x1p-127) return bits(s < 0.0 || (s == 0.0 && signbit(s)) ? -0.0f : 0.0f);
    float r = sm_round_sum(s * 0x1p100, err * 0x1p100); /* normal: 24-bit rounding */
    if (fabsf(r) < 0x1p-26f) return bits(r < 0.0f ? -0.0f : 0.0f);
    return bits((float)((double)r * 0x1p-100));
}

/* ---- counting ---- */

typedef struct tally {
    const char *name;
    long checked, bad;
} tally;

static void report(tally *t, const char *what, const uint32_t *in, int n_in, uint32_t want,
                   uint32_t got) {
    t->checked++;
    if (sm_same(want, got)) return;
    if (t->bad++ < 8) {
        fprintf(stderr, "%s (%s):", t->name, what);
        for (int i = 0; i < n_in; i++) fprintf(stderr, " %08x", (unsigned)in[i]);
        fprintf(stderr, " -> want %08x got %08x\n", (unsigned)want, (unsigned)got);
    }
}

static tally t_div = {"div", 0, 0}, t_div_ftz = {"div_ftz", 0, 0};
static tally t_sqrt = {"sqrt", 0, 0}, t_sqrt_ftz = {"sqrt_ftz", 0, 0};
static tally t_dop = {"diff_of_products", 0, 0}, t_dop_ftz = {"diff_of_products_ftz", 0, 0};
static tally t_dop_hw = {"diff_of_products_ftz vs x86 double", 0, 0};

static void check_div(const char *what, uint32_t a, uint32_t b) {
    uint32_t in[2] = {a, b};
    report(&t_div, what, in, 2, hw_div(a, b), rt_soft_div_bits(a, b));
    if (SM_HAVE_FTZ) {
        ftz_on();
        uint32_t h = hw_div(a, b);
        ftz_off();
        report(&t_div_ftz, what, in, 2, h, rt_soft_div_ftz_bits(a, b));
    }
}

static void check_sqrt(const char *what, uint32_t a) {
    report(&t_sqrt, what, &a, 1, hw_sqrt(a), rt_soft_sqrt_bits(a));
    if (SM_HAVE_FTZ) {
        ftz_on();
        uint32_t h = hw_sqrt(a);
        ftz_off();
        report(&t_sqrt_ftz, what, &a, 1, h, rt_soft_sqrt_ftz_bits(a));
    }
}

static void check_dop(const char *what, const uint32_t q[4]) {
    report(&t_dop, what, q, 4, sm_ref_dop(q[0], q[1], q[2], q[3]),
           rt_soft_diff_of_products_bits(q[0], q[1], q[2], q[3]));
    uint32_t soft_ftz = rt_soft_diff_of_products_ftz_bits(q[0], q[1], q[2], q[3]);
    report(&t_dop_ftz, what, q, 4, ref_dop_ftz(q[0], q[1], q[2], q[3]), soft_ftz);
#if defined(__SSE2__)
    /* Where the double difference is exact, x86 itself (DAZ on the float to
     * double conversions, FTZ on the double to float one) is a reference. */
    volatile double p = (double)flt(q[0]) * flt(q[1]), r = (double)flt(q[2]) * flt(q[3]);
    double s, err;
    sm_two_sum(p, -r, &s, &err);
    if (err == 0.0 || !isfinite(s)) {
        ftz_on();
        volatile float fa = flt(q[0]), fb = flt(q[1]), fc = flt(q[2]), fd = flt(q[3]);
        volatile float h = (float)((double)fa * (double)fb - (double)fc * (double)fd);
        ftz_off();
        report(&t_dop_hw, what, q, 4, bits(h), soft_ftz);
    }
#endif
}

int main(void) {
    uint32_t sp[512];
    int ns = sm_specials(sp);
    uint64_t seed = 0x9e3779b97f4a7c15ull;
    const long n_random = 1000000;

    /* The portable clz (for compilers without __builtin_clz). */
    int clz_bad = 0;
    for (int i = 0; i < 32; i++) {
        for (uint32_t low = 0; low < 4; low++) {
            uint32_t x = (1u << i) | ((low * 0x55555555u) & ((1u << i) - 1u));
            clz_bad += rt_sm_clz_(x) != (uint32_t)(31 - i);
        }
    }
    CHECK_MSG(clz_bad == 0, "rt_sm_clz_ wrong for %d values", clz_bad);

    /* Every pair of specials; sqrt of every special. */
    for (int i = 0; i < ns; i++) {
        check_sqrt("special", sp[i]);
        for (int j = 0; j < ns; j++) check_div("special pair", sp[i], sp[j]);
    }
    /* Quadruples of specials: all of a sample of 24 (both signs of 12: 0,
     * subnormals, 2^-126, 1 - 2^-24, 1, 1 + 2^-23, 2^24 - 1, the largest
     * normal, inf, NaN), and random quadruples of all of them. */
    static const int pick[12] = {0, 1, 10, 11, 25, 26, 27, 40, 49, 50, 52, 55};
    for (int i = 0; i < 24 * 24 * 24 * 24; i++) {
        int k = i;
        uint32_t q[4];
        for (int j = 0; j < 4; j++, k /= 24) q[j] = sp[pick[(k % 24) % 12] * 2 + (k % 24) / 12];
        check_dop("special quad", q);
    }
    for (long i = 0; i < 200000; i++) {
        uint32_t q[4];
        for (int j = 0; j < 4; j++) q[j] = sp[sm_rand(&seed) % (uint32_t)ns];
        check_dop("random special quad", q);
    }

    /* Division with an exact midpoint result: K 2^-150, K odd, from
     * a = K B 2^x, b = B 2^(x + 150) with K B < 2^24; then a moved an ulp. */
    for (long i = 0; i < 200000; i++) {
        int kbits = 1 + (int)(sm_rand(&seed) % 23u);
        uint32_t K = (sm_rand(&seed) & ((1u << kbits) - 1u)) | 1u;
        uint32_t B = sm_rand(&seed) & ((1u << (24 - kbits)) - 1u);
        if (!B) B = 1;
        int x = -149 + (int)(sm_rand(&seed) % 100u);
        int shift = (int)(sm_rand(&seed) % 4u); /* 2^-150 .. 2^-153 midpoints */
        uint32_t a = bits(ldexpf((float)(K * B), x));
        uint32_t b = bits(ldexpf((float)B, x + 150 + shift));
        if ((b & 0x7f800000u) == 0x7f800000u || bits(flt(a)) != a) continue;
        uint32_t sg = sm_rand(&seed) & 0x80000000u;
        check_div("midpoint", a ^ sg, b);
        check_div("beside midpoint", (a + 1u) ^ sg, b);
        if (a & 0x7fffffffu) check_div("beside midpoint", (a - 1u) ^ sg, b);
    }
    /* Square roots near midpoints: x nearest to M^2 for a midpoint M (25
     * significant bits, odd), and its neighbours; and exact squares. */
    for (long i = 0; i < 200000; i++) {
        uint32_t M = (sm_rand(&seed) & 0x00ffffffu) | 0x01000001u;
        int e = -100 + (int)(sm_rand(&seed) % 150u);
        double m = ldexp((double)M, e - 24);
        double sq = m * m; /* exact: 50 bits */
        uint32_t x = bits((float)sq);
        if (!(x & 0x7f800000u) || (x & 0x7f800000u) == 0x7f800000u) continue;
        for (int d = -2; d <= 2; d++) check_sqrt("near midpoint^2", x + (uint32_t)d);
        uint32_t h = (sm_rand(&seed) & 0xfffu) | 0x1000u; /* 13 bits: exact square */
        check_sqrt("square", bits(ldexpf((float)(h * h), e)));
    }
    /* Products of 25 significant bits (midpoints) minus 0 or a tiny term. */
    for (long i = 0; i < 200000; i++) {
        uint32_t B = (sm_rand(&seed) % 0x555555u + 0x555556u) | 1u; /* 3 B: 25 bits, odd */
        int e = -100 + (int)(sm_rand(&seed) % 150u);
        uint32_t q[4] = {bits(ldexpf(3.0f, e)), bits((float)B), 0, 0};
        uint32_t kind = sm_rand(&seed) % 3u;
        if (kind == 1) q[2] = bits(ldexpf(1.0f, e - 30)), q[3] = bits(1.0f);
        if (kind == 2) q[2] = bits(ldexpf(-1.0f, e - 60)), q[3] = bits(ldexpf(1.0f, -40));
        check_dop("midpoint product", q);
    }

    /* Random operands. */
    for (long i = 0; i < n_random; i++) {
        uint32_t a, b;
        if (i & 1) {
            a = sm_rand(&seed), b = sm_rand(&seed);
        } else {
            sm_div_pair(&seed, &a, &b);
        }
        check_div("random", a, b);
        check_sqrt("random", i & 1 ? sm_rand(&seed) : sm_operand(&seed));
        uint32_t q[4];
        if (i & 1) {
            for (int j = 0; j < 4; j++) q[j] = sm_rand(&seed);
        } else {
            sm_dop_quad(&seed, q);
        }
        check_dop("random", q);
    }

    tally *all[] = {&t_div, &t_div_ftz, &t_sqrt, &t_sqrt_ftz, &t_dop, &t_dop_ftz, &t_dop_hw};
    for (unsigned i = 0; i < sizeof all / sizeof all[0]; i++) {
        printf("%-36s %9ld checked, %ld mismatches\n", all[i]->name, all[i]->checked, all[i]->bad);
        CHECK_MSG(all[i]->bad == 0, "%s: %ld mismatches", all[i]->name, all[i]->bad);
    }
    if (!SM_HAVE_FTZ)
        printf("div_ftz, sqrt_ftz: not checked against hardware (no x86 SSE or AArch64 here)\n");
#if !defined(__SSE2__)
    printf("diff_of_products_ftz vs x86 double: not checked (not x86)\n");
#endif
    CHECK(t_div.checked > 1000000 && t_sqrt.checked > 1000000 && t_dop.checked > 1000000);
    return TEST_END();
}
