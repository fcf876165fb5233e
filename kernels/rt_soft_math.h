/* SPDX-License-Identifier: Apache-2.0 */
/* rt_soft_math.h - IEEE 754 binary32 division, square root and difference of
 * products, correctly rounded (round to nearest, ties to even), from exact
 * 32-bit integer arithmetic and correctly rounded float + - *.
 *
 * Valid C99 and valid OpenCL C (1.2 and later). For devices without fp64
 * and without a correctly rounded divide or sqrt (OpenCL allows 2.5 ulp
 * division and 3 ulp sqrt, Vulkan 2.5 ulp division). What the functions use:
 * 32-bit unsigned add, subtract, multiply (the low 32 bits, wrapping),
 * shifts, bitwise operations, compare; and, in division and sqrt only, float
 * add, subtract and multiply on operands scaled to [1, 4), so that no
 * intermediate is ever subnormal or overflows (the device's denormal mode
 * cannot change it). The float steps only guess the significand; the exact
 * integer remainder then fixes it, and the result is correctly rounded for
 * every input (the guesses' error bounds are checked for every divisor and
 * every sqrt operand by tests/test_core_soft_math.c). No double, no 64-bit
 * integers, no division, no sqrt or fma; FP contraction off (set below for
 * OpenCL; C builds use -ffp-contract=off). docs/PORTABLE_MATH.md has the
 * algorithms and why each result is the correctly rounded one.
 *
 * API (each also as a _bits function on the raw binary32 bit patterns):
 *   rt_soft_div(a, b)                    a / b
 *   rt_soft_sqrt(x)                      sqrt(x)
 *   rt_soft_diff_of_products(a, b, c, d) a*b - c*d, exact, then rounded once
 * and the flush-to-zero variants rt_soft_div_ftz, rt_soft_sqrt_ftz,
 * rt_soft_diff_of_products_ftz: the results of x86 SSE with MXCSR.FTZ and
 * MXCSR.DAZ both set. A subnormal input is read as a zero of its sign; a
 * nonzero result whose magnitude, rounded to 24 bits as if the exponent range
 * were unbounded, is below 2^-126 (x86 detects tininess after rounding) is
 * returned as a zero of its sign. (AArch64's FPCR.FZ detects tininess before
 * rounding: it flushes the results that round up to 2^-126 too.)
 *
 * NaN: any NaN input gives a NaN: the first NaN operand (a, then b, ...) with
 * its quiet bit set; an invalid operation (0/0, inf/inf, sqrt of a negative,
 * inf*0, inf - inf) gives the default NaN 0x7fc00000. Payloads are therefore
 * those of ARM and OpenCL; x86 returns 0xffc00000 for an invalid operation.
 *
 * Zero results: a/b and sqrt follow IEEE 754 (sqrt(-0) = -0). For a*b - c*d
 * the sign of an exact zero is that of (a*b) - (c*d) evaluated with the
 * products exact: both products zero gives -0 only for (-0) - (+0), and two
 * nonzero products that cancel give +0.
 */
#ifndef RT_SOFT_MATH_H
#define RT_SOFT_MATH_H

#include "rt_layout.h"

#ifdef RT_OPENCL
/* The float steps assume each + - * is rounded on its own (OpenCL C lets the
 * compiler fuse a * b + c unless told not to). The kernels set this too. */
#pragma OPENCL FP_CONTRACT OFF
#define RT_SM_FN
#define RT_SM_BITS(f)  as_uint(f)
#define RT_SM_FLOAT(u) as_float(u)
#define RT_SM_CLZ(x)   clz(x)
#else
#include <string.h>
#define RT_SM_FN       static inline
#define RT_SM_BITS(f)  rt_sm_bits_(f)
#define RT_SM_FLOAT(u) rt_sm_float_(u)
static inline rt_u32 rt_sm_bits_(float f) {
    rt_u32 u;
    memcpy(&u, &f, sizeof u);
    return u;
}
static inline float rt_sm_float_(rt_u32 u) {
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}
/* Leading zeros of x != 0, by halving: for compilers without a builtin. */
static inline rt_u32 rt_sm_clz_(rt_u32 x) {
    rt_u32 n = 0;
    if (!(x & 0xffff0000u)) n += 16, x <<= 16;
    if (!(x & 0xff000000u)) n += 8, x <<= 8;
    if (!(x & 0xf0000000u)) n += 4, x <<= 4;
    if (!(x & 0xc0000000u)) n += 2, x <<= 2;
    if (!(x & 0x80000000u)) n += 1;
    return n;
}
#if (defined(__GNUC__) || defined(__clang__)) && !defined(RT_SM_PORTABLE_CLZ)
#define RT_SM_CLZ(x) ((rt_u32)__builtin_clz(x))
#else
#define RT_SM_CLZ(x) rt_sm_clz_(x)
#endif
#endif

/* Called where a fast path's guard sends an operand to the bit-serial path;
 * the test counts them (there must be none). */
#ifndef RT_SM_GUARD_HOOK
#define RT_SM_GUARD_HOOK() ((void)0)
#endif

#define RT_SM_SIGN  0x80000000u
#define RT_SM_INF   0x7f800000u
#define RT_SM_QNAN  0x7fc00000u /* the default NaN */
#define RT_SM_QUIET 0x00400000u
#define RT_SM_FRAC  0x007fffffu
#define RT_SM_M24   0x00ffffffu

/* x is a NaN (bit pattern). */
RT_SM_FN int rt_sm_is_nan_(rt_u32 x) {
    return (x & ~RT_SM_SIGN) > RT_SM_INF;
}

/* Denormals are zero: a subnormal pattern becomes the zero of its sign. */
RT_SM_FN rt_u32 rt_sm_daz_(rt_u32 x) {
    return (x & RT_SM_INF) ? x : (x & RT_SM_SIGN);
}

/* The significand of a finite nonzero x as an integer in [2^23, 2^24), with
 * x = *m * 2^(*e - 150): *e is the biased exponent, 1 - k for a subnormal
 * shifted left by k. */
RT_SM_FN void rt_sm_unpack_(rt_u32 x, rt_u32 *m, rt_i32 *e) {
    rt_u32 f = x & RT_SM_FRAC, ef = (x >> 23) & 0xffu;
    if (ef) {
        *m = f | 0x00800000u;
        *e = (rt_i32)ef;
    } else {
        rt_u32 k = RT_SM_CLZ(f) - 8u; /* f != 0: bit 23 reached after k shifts */
        *m = f << k;
        *e = 1 - (rt_i32)k;
    }
}

/* Rounds and packs sig * 2^(e - 151) + (a positive amount below one unit of
 * sig if sticky != 0), sig in [2^24, 2^25): e is the biased exponent of the
 * result, sig its 24 significant bits and one guard bit. Round to nearest,
 * ties to even; gradual underflow (ftz = 0) or x86's flush to zero (ftz = 1);
 * overflow gives infinity. */
RT_SM_FN rt_u32 rt_sm_round_pack_(rt_u32 sign, rt_i32 e, rt_u32 sig, rt_u32 sticky, int ftz) {
    rt_u32 bits;
    if (e >= 255) return sign | RT_SM_INF;
    if (e <= 0) {
        if (ftz) {
            /* Tiny after rounding: only sig = 2^25 - 1 (guard set, odd
             * significand) at e = 0 rounds up to 2^-126, which is normal. */
            return (e == 0 && sig == 0x01ffffffu) ? (sign | 0x00800000u) : sign;
        }
        rt_u32 shift = (rt_u32)(1 - e); /* down to the subnormal scale, 2^-149 per unit */
        if (shift > 25u) {
            sticky |= sig;
            sig = 0;
        } else {
            sticky |= sig & ((1u << shift) - 1u);
            sig >>= shift;
        }
        bits = sig >> 1; /* exponent field 0; a carry makes it 2^-126 */
    } else {
        /* The significand's leading bit adds 1 to the field e - 1. */
        bits = ((rt_u32)(e - 1) << 23) + (sig >> 1);
    }
    if ((sig & 1u) && (sticky || (bits & 1u))) bits += 1u; /* carries into the exponent */
    return sign | bits;
}

/* ---- division --------------------------------------------------------- */

/* The slow, self-contained path: restoring division, one quotient bit per
 * step. q = floor(ma 2^24 / mb) in [2^24, 2^25) for ma in [mb, 2 mb), and
 * the remainder in *r. Invariant: r < mb < 2^24, so 2r < 2^25 fits. */
RT_SM_FN rt_u32 rt_sm_div_serial_(rt_u32 ma, rt_u32 mb, rt_u32 *rem) {
    rt_u32 r = ma - mb, q = 1u;
    /* The quotient bit is a comparison, not the sign bit of r - mb: clang
     * turns (q << 1) | (~t >> 31) into the funnel-shift intrinsic llvm.fshl,
     * which some OpenCL implementations (Oclgrind) cannot run. Both < 2^25,
     * so the two are the same bit. */
    for (int i = 0; i < 24; i++) {
        r <<= 1;
        rt_u32 bit = r >= mb ? 1u : 0u;
        q = (q << 1) | bit;
        r = bit ? r - mb : r;
    }
    *rem = r;
    return q;
}

/* 1 / fb for fb in [1, 2), with |y fb - 1| <= 1.5 2^-24 (the test checks
 * every fb): the linear minimax start y0 = 24/17 - 8/17 fb (relative error
 * at most 1/17), e = 1 - fb y0 (exact: Sterbenz), y0 (1 + e) (1 + e^2) =
 * (1 - e^4) / fb (Goldschmidt: e^2 is computed beside the chain; error below
 * 1.3e-5), then one Newton step y += y (1 - fb y), which also corrects the
 * rounding errors so far. The chain is 12 operations long (three Newton
 * steps: 14). Every intermediate is 0 or a normal float of magnitude in
 * [2^-50, 2]: no subnormal, no overflow, so a device's denormal flushing
 * cannot change it. */
RT_SM_FN float rt_sm_recip_(float fb) {
    float y = 1.41176471f - 0.470588235f * fb;
    float e = 1.0f - fb * y;
    float e2 = e * e;
    y = y + y * e;
    y = y + y * e2;
    e = 1.0f - fb * y;
    y = y + y * e;
    return y;
}

/* A positive float q in [2^-1, 2^1] as the integer q 2^24, and whether its
 * exponent was outside that range (*bad, then the value is meaningless). */
RT_SM_FN rt_u32 rt_sm_fix24_(float q, rt_u32 *bad) {
    rt_u32 qb = RT_SM_BITS(q), sh = (qb >> 23) - 126u; /* 0, 1 or 2 */
    *bad |= sh > 2u ? 1u : 0u;
    return ((qb & RT_SM_FRAC) | 0x00800000u) << (sh & 3u);
}

/* The quotient's first guess: ma 2^24 / mb (ma doubled if dbl) to within
 * less than 4 units, for ma, mb in [2^23, 2^24) with ma 2^dbl in [mb, 2 mb).
 * The significands as floats fa = ma 2^(dbl - 23) in [1, 4) and fb in
 * [1, 2) (integer bit manipulation, so no subnormal ever reaches the float
 * unit); the quotient fa / fb in [1, 2) as fa * (1 / fb), rounded once. */
RT_SM_FN rt_u32 rt_sm_div_guess_(rt_u32 ma, rt_u32 mb, rt_u32 dbl, rt_u32 *bad) {
    float fa = RT_SM_FLOAT(((127u + dbl) << 23) | (ma & RT_SM_FRAC));
    float fb = RT_SM_FLOAT(0x3f800000u | (mb & RT_SM_FRAC));
    return rt_sm_fix24_(fa * rt_sm_recip_(fb), bad);
}

/* Q = floor(ma 2^(24 + dbl) / mb) in [2^24, 2^25) and the remainder in *rem,
 * for ma, mb in [2^23, 2^24) with ma 2^dbl in [mb, 2 mb): the guess, the
 * exact remainder, then restoring steps (docs/PORTABLE_MATH.md). */
RT_SM_FN rt_u32 rt_sm_div_sig_(rt_u32 ma, rt_u32 mb, rt_u32 dbl, rt_u32 *rem) {
    rt_u32 bad = 0u;
    rt_u32 q = rt_sm_div_guess_(ma, mb, dbl, &bad) - 4u;
    ma <<= dbl;
    /* Q lies in [q, q + 8) (the guess G is within 4 units: Q in [G - 4,
     * G + 3]): then R' = ma 2^24 - q mb is in [0, 8 mb), below 2^27, and the
     * 32-bit wrapped products give it exactly. Three restoring steps of 4,
     * 2 and 1 times mb bring it into [0, mb). */
    rt_u32 r = (ma << 24) - q * mb;
    bad |= r >= (mb << 3) ? 1u : 0u;
    for (int k = 2; k >= 0; k--) {
        rt_u32 t = r - (mb << k);
        rt_u32 bit = (t >> 31) ^ 1u; /* r >= mb 2^k (r, t below 2^27) */
        q += bit << k;
        r = bit ? t : r;
    }
    /* Never taken (the bound is proven); a guard, not a path to rely on. */
    if (bad) {
        RT_SM_GUARD_HOOK();
        q = rt_sm_div_serial_(ma, mb, &r);
    }
    *rem = r;
    return q;
}

RT_SM_FN rt_u32 rt_sm_div_bits_(rt_u32 a, rt_u32 b, int ftz) {
    if (ftz) {
        a = rt_sm_daz_(a);
        b = rt_sm_daz_(b);
    }
    rt_u32 sign = (a ^ b) & RT_SM_SIGN;
    rt_u32 aa = a & ~RT_SM_SIGN, ab = b & ~RT_SM_SIGN;
    if (aa > RT_SM_INF) return a | RT_SM_QUIET;
    if (ab > RT_SM_INF) return b | RT_SM_QUIET;
    if (aa == RT_SM_INF) return ab == RT_SM_INF ? RT_SM_QNAN : (sign | RT_SM_INF);
    if (ab == RT_SM_INF) return sign;
    if (ab == 0u) return aa == 0u ? RT_SM_QNAN : (sign | RT_SM_INF);
    if (aa == 0u) return sign;

    rt_u32 ma, mb;
    rt_i32 ea, eb;
    rt_sm_unpack_(aa, &ma, &ea);
    rt_sm_unpack_(ab, &mb, &eb);
    /* a / b = (ma / mb) 2^(ea - eb); with ma in [mb, 2 mb) the quotient's
     * biased exponent is ea - eb + 127. */
    rt_u32 dbl = ma < mb ? 1u : 0u;
    rt_i32 e = ea - eb + 127 - (rt_i32)dbl;
    rt_u32 r, q = rt_sm_div_sig_(ma, mb, dbl, &r);
    return rt_sm_round_pack_(sign, e, q, r, ftz);
}

/* ---- square root ------------------------------------------------------- */

/* The slow, self-contained path: digit by digit, root = floor(sqrt(t 2^24))
 * for t in [2^24, 2^26), and the remainder in *rem. */
RT_SM_FN rt_u32 rt_sm_sqrt_serial_(rt_u32 t, rt_u32 *rem_out) {
    rt_u32 root = 0u, rem = 0u;
    /* 13 bit pairs of t, then 12 zero pairs. After each step root =
     * floor(sqrt(leading pairs)) and rem = leading pairs - root^2 <= 2 root,
     * below 2^26. */
    for (int i = 0; i < 25; i++) {
        rt_u32 pair = i < 13 ? (t >> (24 - 2 * i)) & 3u : 0u;
        rem = (rem << 2) | pair;
        rt_u32 trial = (root << 2) | 1u;
        root <<= 1;
        /* A comparison, not the sign bit of rem - trial (rem < 2^28, trial <
         * 2^27, so the same bit): see rt_sm_div_serial_ (no llvm.fshl). */
        rt_u32 bit = rem >= trial ? 1u : 0u;
        root |= bit;
        rem = bit ? rem - trial : rem;
    }
    *rem_out = rem;
    return root;
}

/* The square root's first guess: sqrt(t 2^24) for t = m 2^(1 + odd), m in
 * [2^23, 2^24), to within 1.7 units (tests check all 2^24 inputs). fx = t
 * 2^-24 in [1, 4) as a float; y ~ 1 / sqrt(fx) from the integer estimate
 * and two Newton steps y *= 1.5 - (fx / 2) y y; s = fx y, then one Newton
 * step on s: s += (y / 2) (fx - s s). Every intermediate is a normal float
 * of magnitude in [2^-30, 4]. */
RT_SM_FN rt_u32 rt_sm_sqrt_guess_(rt_u32 m, rt_u32 odd, rt_u32 *bad) {
    float fx = RT_SM_FLOAT(((127u + odd) << 23) | (m & RT_SM_FRAC));
    float hx = 0.5f * fx;
    float y = RT_SM_FLOAT(0x5f3759dfu - (RT_SM_BITS(fx) >> 1));
    y = y * (1.5f - hx * y * y);
    y = y * (1.5f - hx * y * y);
    float s = fx * y;
    s = s + (0.5f * y) * (fx - s * s);
    return rt_sm_fix24_(s, bad);
}

/* root = floor(sqrt(t 2^24)) in [2^24, 2^25) for t = m 2^(1 + odd), m in
 * [2^23, 2^24), and the remainder t 2^24 - root^2 in *rem_out: the guess,
 * the exact remainder, then restoring steps (docs/PORTABLE_MATH.md). */
RT_SM_FN rt_u32 rt_sm_sqrt_sig_(rt_u32 m, rt_u32 odd, rt_u32 *rem_out) {
    rt_u32 t = m << (1u + odd);
    rt_u32 bad = 0u;
    rt_u32 root = rt_sm_sqrt_guess_(m, odd, &bad) - 2u;
    /* The guess G is within 1.7 units of sqrt(M), so the root is in [G - 2,
     * G + 1], in [r0, r0 + 4) for r0 = G - 2: then M - r0^2 is in [0, 8 r0 +
     * 16), below 2^29, and the 32-bit wrapped products give it exactly (M =
     * t 2^24). Steps of 2 and 1: (r + j)^2 - r^2 = 2 j r + j^2. */
    rt_u32 rem = (t << 24) - root * root;
    bad |= rem >= (root << 3) + 16u ? 1u : 0u;
    for (int k = 1; k >= 0; k--) {
        rt_u32 d = rem - ((root << (k + 1u)) + (1u << (2u * k)));
        rt_u32 bit = (d >> 31) ^ 1u; /* rem, d below 2^29 */
        root += bit << k;
        rem = bit ? d : rem;
    }
    /* Never taken (every fx is checked); a guard, not a path to rely on. */
    if (bad) {
        RT_SM_GUARD_HOOK();
        root = rt_sm_sqrt_serial_(t, &rem);
    }
    *rem_out = rem;
    return root;
}

RT_SM_FN rt_u32 rt_sm_sqrt_bits_(rt_u32 x, int ftz) {
    if (ftz) x = rt_sm_daz_(x);
    if (rt_sm_is_nan_(x)) return x | RT_SM_QUIET;
    if ((x & ~RT_SM_SIGN) == 0u) return x; /* sqrt(+-0) = +-0 */
    if (x & RT_SM_SIGN) return RT_SM_QNAN;
    if (x == RT_SM_INF) return x;

    rt_u32 m;
    rt_i32 e;
    rt_sm_unpack_(x, &m, &e);
    /* x = m 2^(E - 23), E = e - 127 unbiased. Shift m left by k = 25 (E
     * even) or 26 (E odd): M = m 2^k in [2^48, 2^50) and E - 23 - k is even,
     * so sqrt(x) = sqrt(M) 2^((E - 23 - k) / 2) with sqrt(M) in [2^24, 2^25).
     * M = t 2^24 with t = m 2^(k - 24) below 2^26. */
    rt_u32 odd = (rt_u32)(e + 1) & 1u; /* E = e - 127 is odd when e is even */
    rt_u32 rem, root = rt_sm_sqrt_sig_(m, odd, &rem);
    /* Result exponent floor(E / 2), biased: floor((e - 127) / 2) + 127 =
     * floor((e + 149) / 2) - 11, with e + 149 > 0 (e >= -22). */
    rt_i32 er = (rt_i32)((rt_u32)(e + 149) >> 1) - 11;
    return rt_sm_round_pack_(0u, er, root, rem, ftz);
}

/* ---- difference of products --------------------------------------------- */

/* The exact product of two finite nonzero values as a 48-bit significand in
 * two 24-bit limbs, hi in [2^23, 2^24): a b = (hi 2^24 + lo) 2^(*e). */
RT_SM_FN void rt_sm_mul_exact_(rt_u32 a, rt_u32 b, rt_u32 *hi, rt_u32 *lo, rt_i32 *e) {
    rt_u32 ma, mb;
    rt_i32 ea, eb;
    rt_sm_unpack_(a, &ma, &ea);
    rt_sm_unpack_(b, &mb, &eb);
    /* 12-bit halves: every partial product is below 2^24. */
    rt_u32 ah = ma >> 12, al = ma & 0xfffu, bh = mb >> 12, bl = mb & 0xfffu;
    rt_u32 mid = ah * bl + al * bh; /* < 2^25 */
    rt_u32 l = al * bl + ((mid & 0xfffu) << 12);
    rt_u32 h = ah * bh + (mid >> 12) + (l >> 24);
    l &= RT_SM_M24;
    rt_i32 ex = ea + eb - 300;
    if (h < 0x00800000u) { /* product in [2^46, 2^47): normalise */
        h = (h << 1) | (l >> 23);
        l = (l << 1) & RT_SM_M24;
        ex -= 1;
    }
    *hi = h;
    *lo = l;
    *e = ex;
}

/* 0: finite, 1: infinite, 2: NaN (inf * 0 included), for the product a b. */
RT_SM_FN int rt_sm_prod_class_(rt_u32 a, rt_u32 b) {
    rt_u32 aa = a & ~RT_SM_SIGN, ab = b & ~RT_SM_SIGN;
    if (aa > RT_SM_INF || ab > RT_SM_INF) return 2;
    if (aa == RT_SM_INF || ab == RT_SM_INF) return (aa == 0u || ab == 0u) ? 2 : 1;
    return 0;
}

RT_SM_FN rt_u32 rt_sm_dop_bits_(rt_u32 a, rt_u32 b, rt_u32 c, rt_u32 d, int ftz) {
    if (ftz) {
        a = rt_sm_daz_(a);
        b = rt_sm_daz_(b);
        c = rt_sm_daz_(c);
        d = rt_sm_daz_(d);
    }
    /* The signs of the two terms of (a b) + (-(c d)). */
    rt_u32 s1 = (a ^ b) & RT_SM_SIGN, s2 = ((c ^ d) & RT_SM_SIGN) ^ RT_SM_SIGN;
    int k1 = rt_sm_prod_class_(a, b), k2 = rt_sm_prod_class_(c, d);
    if (k1 | k2) {
        if (rt_sm_is_nan_(a)) return a | RT_SM_QUIET;
        if (rt_sm_is_nan_(b)) return b | RT_SM_QUIET;
        if (rt_sm_is_nan_(c)) return c | RT_SM_QUIET;
        if (rt_sm_is_nan_(d)) return d | RT_SM_QUIET;
        if (k1 == 2 || k2 == 2 || (k1 == 1 && k2 == 1 && s1 != s2)) return RT_SM_QNAN;
        return (k1 == 1 ? s1 : s2) | RT_SM_INF;
    }
    int z1 = (a & ~RT_SM_SIGN) == 0u || (b & ~RT_SM_SIGN) == 0u;
    int z2 = (c & ~RT_SM_SIGN) == 0u || (d & ~RT_SM_SIGN) == 0u;
    if (z1 && z2) return s1 & s2; /* -0 + -0 = -0, any other sum of zeros +0 */

    /* X: the term of larger magnitude, Y the other (zero when its product is). */
    rt_u32 xh = 0u, xl = 0u, yh = 0u, yl = 0u, sx, sy;
    rt_i32 ex = 0, ey = 0;
    if (z1) {
        rt_sm_mul_exact_(c, d, &xh, &xl, &ex);
        sx = s2;
        sy = s2;
        ey = ex;
    } else if (z2) {
        rt_sm_mul_exact_(a, b, &xh, &xl, &ex);
        sx = s1;
        sy = s1;
        ey = ex;
    } else {
        rt_u32 h1, l1, h2, l2;
        rt_i32 e1, e2;
        rt_sm_mul_exact_(a, b, &h1, &l1, &e1);
        rt_sm_mul_exact_(c, d, &h2, &l2, &e2);
        /* Both significands have their leading bit at 47: the exponent
         * orders the magnitudes, the limbs break a tie. */
        int first = e1 > e2 || (e1 == e2 && (h1 > h2 || (h1 == h2 && l1 >= l2)));
        xh = first ? h1 : h2;
        xl = first ? l1 : l2;
        ex = first ? e1 : e2;
        sx = first ? s1 : s2;
        yh = first ? h2 : h1;
        yl = first ? l2 : l1;
        ey = first ? e2 : e1;
        sy = first ? s2 : s1;
    }
    /* Fixed point window of three 24-bit limbs, unit 2^(ex - 24): X is
     * (xh, xl, 0); Y is shifted right by ex - ey >= 0, and the bits it loses
     * are ORed into its lowest bit (sticky). Bits are lost only for a shift
     * above 24, when |X - Y| > |X| / 2: the result's rounding position is
     * then above bit 44 and a sticky bit 0 cannot move it across a rounding
     * boundary (docs/PORTABLE_MATH.md). */
    rt_u32 y2 = yh, y1 = yl, y0 = 0u, st = 0u;
    rt_u32 sh = (rt_u32)(ex - ey);
    if (sh >= 72u) {
        st = y2 | y1;
        y2 = y1 = 0u;
    } else {
        if (sh >= 48u) {
            st = y1;
            y0 = y2;
            y1 = y2 = 0u;
            sh -= 48u;
        } else if (sh >= 24u) {
            y0 = y1;
            y1 = y2;
            y2 = 0u;
            sh -= 24u;
        }
        if (sh) {
            rt_u32 up = 24u - sh;
            st |= y0 & ((1u << sh) - 1u);
            y0 = (y0 >> sh) | ((y1 << up) & RT_SM_M24);
            y1 = (y1 >> sh) | ((y2 << up) & RT_SM_M24);
            y2 >>= sh;
        }
    }
    y0 |= st ? 1u : 0u;

    rt_u32 r0, r1, r2, t;
    if (sx == sy) {
        t = y0; /* x0 = 0 */
        r0 = t & RT_SM_M24;
        t = xl + y1 + (t >> 24);
        r1 = t & RT_SM_M24;
        r2 = xh + y2 + (t >> 24); /* below 2^25 */
    } else {
        t = 0u - y0;
        r0 = t & RT_SM_M24;
        t = xl - y1 - (t >> 31);
        r1 = t & RT_SM_M24;
        r2 = xh - y2 - (t >> 31); /* |X| >= |Y|: no borrow out */
    }
    /* Leading bit p of the window (0 .. 72), the 25 bits from it down, and
     * whether anything below them is nonzero. */
    rt_u32 sig, sticky;
    rt_i32 p;
    if (r2) {
        rt_u32 n = 32u - RT_SM_CLZ(r2), k = 25u - n; /* n in 1 .. 25 */
        p = 47 + (rt_i32)n;
        sig = (r2 << k) | (r1 >> (24u - k));
        sticky = (r1 & ((1u << (24u - k)) - 1u)) | r0;
    } else if (r1) {
        rt_u32 n = 32u - RT_SM_CLZ(r1), k = 25u - n;
        p = 23 + (rt_i32)n;
        sig = (r1 << k) | (r0 >> (24u - k));
        sticky = r0 & ((1u << (24u - k)) - 1u);
    } else if (r0) {
        rt_u32 n = 32u - RT_SM_CLZ(r0);
        p = (rt_i32)n - 1;
        sig = r0 << (25u - n);
        sticky = 0u;
    } else {
        return 0u; /* exact cancellation: +0 */
    }
    /* value = window 2^(ex - 24) = sig 2^(p - 24 + ex - 24): biased
     * exponent p + ex + 103. */
    return rt_sm_round_pack_(sx, p + ex + 103, sig, sticky, ftz);
}

/* ---- the API ------------------------------------------------------------ */

RT_SM_FN rt_u32 rt_soft_div_bits(rt_u32 a, rt_u32 b) {
    return rt_sm_div_bits_(a, b, 0);
}
RT_SM_FN rt_u32 rt_soft_div_ftz_bits(rt_u32 a, rt_u32 b) {
    return rt_sm_div_bits_(a, b, 1);
}
RT_SM_FN rt_u32 rt_soft_sqrt_bits(rt_u32 x) {
    return rt_sm_sqrt_bits_(x, 0);
}
RT_SM_FN rt_u32 rt_soft_sqrt_ftz_bits(rt_u32 x) {
    return rt_sm_sqrt_bits_(x, 1);
}
RT_SM_FN rt_u32 rt_soft_diff_of_products_bits(rt_u32 a, rt_u32 b, rt_u32 c, rt_u32 d) {
    return rt_sm_dop_bits_(a, b, c, d, 0);
}
RT_SM_FN rt_u32 rt_soft_diff_of_products_ftz_bits(rt_u32 a, rt_u32 b, rt_u32 c, rt_u32 d) {
    return rt_sm_dop_bits_(a, b, c, d, 1);
}

RT_SM_FN float rt_soft_div(float a, float b) {
    return RT_SM_FLOAT(rt_sm_div_bits_(RT_SM_BITS(a), RT_SM_BITS(b), 0));
}
RT_SM_FN float rt_soft_div_ftz(float a, float b) {
    return RT_SM_FLOAT(rt_sm_div_bits_(RT_SM_BITS(a), RT_SM_BITS(b), 1));
}
RT_SM_FN float rt_soft_sqrt(float x) {
    return RT_SM_FLOAT(rt_sm_sqrt_bits_(RT_SM_BITS(x), 0));
}
RT_SM_FN float rt_soft_sqrt_ftz(float x) {
    return RT_SM_FLOAT(rt_sm_sqrt_bits_(RT_SM_BITS(x), 1));
}
RT_SM_FN float rt_soft_diff_of_products(float a, float b, float c, float d) {
    return RT_SM_FLOAT(
        rt_sm_dop_bits_(RT_SM_BITS(a), RT_SM_BITS(b), RT_SM_BITS(c), RT_SM_BITS(d), 0));
}
RT_SM_FN float rt_soft_diff_of_products_ftz(float a, float b, float c, float d) {
    return RT_SM_FLOAT(
        rt_sm_dop_bits_(RT_SM_BITS(a), RT_SM_BITS(b), RT_SM_BITS(c), RT_SM_BITS(d), 1));
}

#endif /* RT_SOFT_MATH_H */
