/* SPDX-License-Identifier: Apache-2.0 */
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

/* How often a fast path's guard fired (rt_soft_math.h calls the hook). */
static long sm_guard_taken;
#define RT_SM_GUARD_HOOK() ((void)sm_guard_taken++)

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

/* ---- the fast paths' significand steps, exactly (64-bit reference) ---- */

static tally t_div_sig = {"div significand steps", 0, 0};
static tally t_sqrt_sig = {"sqrt significand steps", 0, 0};
static double worst_div_guess, worst_sqrt_guess; /* in units of the result's last bit */

/* rt_sm_div_sig_ against floor / remainder in 64 bits, and the distance of
 * the float guess from the exact quotient (the proof needs below 4). */
static void check_div_sig(uint32_t ma, uint32_t mb) {
    uint32_t dbl = ma < mb, bad = 0, r;
    uint64_t num = (uint64_t)ma << (24 + dbl);
    uint32_t q = rt_sm_div_sig_(ma, mb, dbl, &r);
    uint32_t in[2] = {ma, mb};
    uint32_t want_q = (uint32_t)(num / mb), want_r = (uint32_t)(num % mb);
    report(&t_div_sig, "quotient", in, 2, want_q, q);
    report(&t_div_sig, "remainder", in, 2, want_r, r);
    double g = (double)rt_sm_div_guess_(ma, mb, dbl, &bad);
    double d = fabs(g - (double)num / (double)mb);
    if (bad) d = 1e9;
    if (d > worst_div_guess) worst_div_guess = d;
}

/* rt_sm_sqrt_sig_ against the exact integer root and remainder. */
static void check_sqrt_sig(uint32_t m, uint32_t odd) {
    uint32_t bad = 0, rem;
    uint64_t big = (uint64_t)m << (25 + odd);
    uint32_t root = rt_sm_sqrt_sig_(m, odd, &rem);
    uint64_t w = (uint64_t)sqrt((double)big); /* within one of the floor */
    while (w * w > big) w--;
    while ((w + 1) * (w + 1) <= big) w++;
    uint32_t in[2] = {m, odd};
    report(&t_sqrt_sig, "root", in, 2, (uint32_t)w, root);
    report(&t_sqrt_sig, "remainder", in, 2, (uint32_t)(big - w * w), rem);
    double g = (double)rt_sm_sqrt_guess_(m, odd, &bad);
    double d = fabs(g - sqrt((double)big));
    if (bad) d = 1e9;
    if (d > worst_sqrt_guess) worst_sqrt_guess = d;
}

/* A float from a significand in [2^23, 2^24) and a biased exponent (1 to
 * 254), or a subnormal when the exponent is 0 or below (the significand
 * shifted right, only where no bit is lost). Returns 0 where not possible. */
static int make_float(uint32_t m, int e, uint32_t *out) {
    if (e >= 255) return 0;
    if (e >= 1) {
        *out = ((uint32_t)e << 23) | (m & 0x007fffffu);
        return 1;
    }
    int sh = 1 - e;
    if (sh > 23 || (m & ((1u << sh) - 1u))) return 0;
    *out = m >> sh;
    return 1;
}

/* The operands whose quotients target the fast path's corners: exact
 * quotients, quotients one part in 2^40 or so beside a midpoint of two
 * floats (a normal result has no exact midpoint), the divisor's significand
 * near 1 and near 2, and results near 2^-126 and 2^127 (and subnormal). */
static void div_corners(uint64_t *seed) {
    for (long i = 0; i < 300000; i++) {
        uint32_t ma, mb = (sm_rand(seed) & 0x00ffffffu) | 0x00800000u;
        uint32_t kind = sm_rand(seed) % 5u;
        if (kind == 0) { /* exact: ma = K mb' with mb' = mb >> j */
            int kb = 1 + (int)(sm_rand(seed) % 23u);
            uint32_t K = (sm_rand(seed) & ((1u << kb) - 1u)) | 1u, B = mb >> kb;
            if (!B) B = 1;
            uint32_t p = K * B; /* below 2^24 */
            uint32_t s1 = RT_SM_CLZ(p) - 8u, s2 = RT_SM_CLZ(B) - 8u;
            ma = p << s1, mb = B << s2;
        } else if (kind <= 2) { /* beside the midpoint M (25 bits, odd) */
            uint32_t M = (sm_rand(seed) & 0x00ffffffu) | 0x01000001u;
            uint32_t k = 24u + (kind == 2); /* quotient in [1, 2) or [1/2, 1) */
            uint64_t prod = (uint64_t)M * mb;
            ma = (uint32_t)(prod >> k) + (sm_rand(seed) & 1u);
            if (ma < 0x00800000u || ma > 0x00ffffffu) continue;
        } else if (kind == 3) { /* mb near 1 or near 2 */
            uint32_t off = sm_rand(seed) % 64u;
            mb = sm_rand(seed) & 1u ? 0x00800000u + off : 0x00ffffffu - off;
            ma = (sm_rand(seed) & 0x00ffffffu) | 0x00800000u;
            if (sm_rand(seed) & 1u) ma = sm_rand(seed) & 1u ? 0x00800000u + off : 0x00ffffffu - off;
        } else {
            ma = (sm_rand(seed) & 0x00ffffffu) | 0x00800000u;
        }
        check_div_sig(ma, mb);
        /* The exponents: a result near 2^-126 (normal or subnormal), near
         * 2^127, or anywhere; subnormal operands where they can be exact. */
        int er = (int)(sm_rand(seed) % 8u) - 3; /* result biased exponent -3 .. 4 */
        uint32_t where = sm_rand(seed) % 3u;
        if (where == 1) er += 250;
        if (where == 2) er = 1 + (int)(sm_rand(seed) % 254u);
        int eb = 1 + (int)(sm_rand(seed) % 254u);
        if (sm_rand(seed) % 8u == 0) eb = -(int)(sm_rand(seed) % 20u);
        int ea = er + eb - 127 + (ma < mb); /* ma < mb lowers the exponent by 1 */
        uint32_t a, b;
        if (!make_float(ma, ea, &a) || !make_float(mb, eb, &b)) continue;
        uint32_t sg = sm_rand(seed) & 0x80000000u;
        check_div("corner", a ^ sg, b);
        check_div("corner", a, b ^ sg);
    }
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

    /* The fast paths, as a proof by exhaustion where it can be one. sqrt's
     * significand steps depend on m and the exponent's parity only: all
     * 2^24 of them, exactly. Division's guess uses 1 / fb for each of the
     * 2^23 divisors: |fb y - 1| <= 1.5 2^-24 for every one is the premise of
     * the bound docs/PORTABLE_MATH.md proves (guess within 4 units). */
    for (uint32_t odd = 0; odd < 2; odd++) {
        for (uint32_t m = 0x00800000u; m <= 0x00ffffffu; m++) check_sqrt_sig(m, odd);
    }
    double worst_recip = 0.0;
    for (uint32_t mb = 0x00800000u; mb <= 0x00ffffffu; mb++) {
        float fb = flt(0x3f800000u | (mb & 0x007fffffu));
        double d = fabs((double)fb * (double)rt_sm_recip_(fb) - 1.0); /* exact product */
        if (d > worst_recip) worst_recip = d;
    }
    printf("1/fb for all 2^23 fb: |fb y - 1| <= %.4g 2^-24; sqrt guess within %.4f units\n",
           worst_recip * 0x1p24, worst_sqrt_guess);
    CHECK_MSG(worst_recip <= 1.5 * 0x1p-24, "1/fb off by %.4g 2^-24", worst_recip * 0x1p24);
    CHECK_MSG(worst_sqrt_guess < 2.0, "sqrt guess off by %.4f units", worst_sqrt_guess);
    div_corners(&seed);
    for (long i = 0; i < 2000000; i++) { /* random significands */
        uint32_t ma = (sm_rand(&seed) & 0x00ffffffu) | 0x00800000u;
        check_div_sig(ma, (sm_rand(&seed) & 0x00ffffffu) | 0x00800000u);
    }
    printf("division guess within %.4f units (bound 4)\n", worst_div_guess);
    CHECK_MSG(worst_div_guess < 4.0, "division guess off by %.4f units", worst_div_guess);
    /* The guard paths (never taken by the above) still compute the same. */
    long serial_bad = 0;
    for (long i = 0; i < 100000; i++) {
        uint32_t ma = (sm_rand(&seed) & 0x00ffffffu) | 0x00800000u;
        uint32_t mb = (sm_rand(&seed) & 0x00ffffffu) | 0x00800000u, r1, r2, dbl = ma < mb;
        uint32_t q1 = rt_sm_div_serial_(ma << dbl, mb, &r1), q2 = rt_sm_div_sig_(ma, mb, dbl, &r2);
        serial_bad += q1 != q2 || r1 != r2;
        uint32_t t = ma << (1u + (i & 1));
        q1 = rt_sm_sqrt_serial_(t, &r1), q2 = rt_sm_sqrt_sig_(ma, (uint32_t)(i & 1), &r2);
        serial_bad += q1 != q2 || r1 != r2;
    }
    CHECK_MSG(serial_bad == 0, "the bit-serial guard paths differ %ld times", serial_bad);

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

    printf("fast-path guards taken (all of the above): %ld\n", sm_guard_taken);
    CHECK_MSG(sm_guard_taken == 0, "the fast paths' guards fired %ld times", sm_guard_taken);
    tally *all[] = {&t_div,     &t_div_ftz, &t_sqrt,    &t_sqrt_ftz, &t_dop,
                    &t_dop_ftz, &t_dop_hw,  &t_div_sig, &t_sqrt_sig};
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
