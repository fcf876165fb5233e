/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_soft_math.glsl - the GLSL mirror of kernels/rt_soft_math.h: binary32
 * division, square root and difference of products, correctly rounded, from
 * 32-bit integer operations and a float first guess that integer
 * arithmetic checks and corrects (so neither contraction nor the device's
 * denormal mode can change a result: a guess that misses its window sends
 * the operands to the bit-serial loop).
 *
 * A hand-written mirror, line by line (docs/ARCHITECTURE.md says why): each
 * function has the C function's name and steps. test_vulkan_oracle holds it
 * to the C header bit for bit on the special classes and on random operands
 * (rt_vk_soft_test.comp). Differences from C: no pointers (out and inout
 * parameters), bool where C tests an int, findMSB for the leading-zero
 * count, the C constants written by their bits. The bit-serial loops, the
 * guards' path that no operand takes, are not unrolled ([[dont_unroll]]):
 * unrolled, every inlined division made the driver's compile minutes long.
 * Why the common path has no loop at all: llvmpipe and lavapipe give a
 * shader 65535 loop iterations in all (rt_vk_main.comp), and a division of
 * 24 iterations per triangle test spent them. */
#ifndef RT_VK_SOFT_MATH_GLSL
#define RT_VK_SOFT_MATH_GLSL

#extension GL_EXT_control_flow_attributes : require

#include "rt_vk_ticks.glsl" /* RT_VK_TICK in the loops */

#define RT_SM_SIGN  0x80000000u
#define RT_SM_INF   0x7f800000u
#define RT_SM_QNAN  0x7fc00000u
#define RT_SM_QUIET 0x00400000u
#define RT_SM_FRAC  0x007fffffu
#define RT_SM_M24   0x00ffffffu

/* Leading zeros of x != 0. */
uint rt_sm_clz_(uint x) {
    return 31u - uint(findMSB(x));
}

bool rt_sm_is_nan_(uint x) {
    return (x & ~RT_SM_SIGN) > RT_SM_INF;
}

uint rt_sm_daz_(uint x) {
    return (x & RT_SM_INF) != 0u ? x : (x & RT_SM_SIGN);
}

void rt_sm_unpack_(uint x, out uint m, out int e) {
    uint f = x & RT_SM_FRAC, ef = (x >> 23) & 0xffu;
    if (ef != 0u) {
        m = f | 0x00800000u;
        e = int(ef);
    } else {
        uint k = rt_sm_clz_(f) - 8u;
        m = f << k;
        e = 1 - int(k);
    }
}

uint rt_sm_round_pack_(uint sign, int e, uint sig, uint sticky, bool ftz) {
    uint bits;
    if (e >= 255) return sign | RT_SM_INF;
    if (e <= 0) {
        if (ftz) return (e == 0 && sig == 0x01ffffffu) ? (sign | 0x00800000u) : sign;
        uint shift = uint(1 - e);
        if (shift > 25u) {
            sticky |= sig;
            sig = 0u;
        } else {
            sticky |= sig & ((1u << shift) - 1u);
            sig >>= shift;
        }
        bits = sig >> 1;
    } else {
        bits = (uint(e - 1) << 23) + (sig >> 1);
    }
    if ((sig & 1u) != 0u && (sticky != 0u || (bits & 1u) != 0u)) bits += 1u;
    return sign | bits;
}

/* ---- division ---- */

uint rt_sm_div_serial_(uint ma, uint mb, out uint rem) {
    uint r = ma - mb, q = 1u;
    [[dont_unroll]] for (int i = 0; i < 24; i++, RT_VK_TICK) {
        r <<= 1;
        uint t = r - mb;
        uint bit = (t >> 31) ^ 1u;
        q = (q << 1) | bit;
        r = bit != 0u ? t : r;
    }
    rem = r;
    return q;
}

/* The C constants by their bits (24/17 and 8/17 rounded to float), so that
 * no decimal-to-float conversion of the GLSL compiler can differ. */
float rt_sm_recip_(float fb) {
    float y = uintBitsToFloat(0x3fb4b4b5u) - uintBitsToFloat(0x3ef0f0f1u) * fb;
    float e = 1.0 - fb * y;
    float e2 = e * e;
    y = y + y * e;
    y = y + y * e2;
    e = 1.0 - fb * y;
    y = y + y * e;
    return y;
}

uint rt_sm_fix24_(float q, inout uint bad) {
    uint qb = floatBitsToUint(q), sh = (qb >> 23) - 126u;
    bad |= sh > 2u ? 1u : 0u;
    return ((qb & RT_SM_FRAC) | 0x00800000u) << (sh & 3u);
}

uint rt_sm_div_guess_(uint ma, uint mb, uint dbl, inout uint bad) {
    float fa = uintBitsToFloat(((127u + dbl) << 23) | (ma & RT_SM_FRAC));
    float fb = uintBitsToFloat(0x3f800000u | (mb & RT_SM_FRAC));
    return rt_sm_fix24_(fa * rt_sm_recip_(fb), bad);
}

uint rt_sm_div_sig_(uint ma, uint mb, uint dbl, out uint rem) {
    uint bad = 0u;
    uint q = rt_sm_div_guess_(ma, mb, dbl, bad) - 4u;
    ma <<= dbl;
    uint r = (ma << 24) - q * mb;
    bad |= r >= (mb << 3) ? 1u : 0u;
    [[unroll]] for (int k = 2; k >= 0; k--, RT_VK_TICK) {
        uint t = r - (mb << uint(k));
        uint bit = (t >> 31) ^ 1u;
        q += bit << uint(k);
        r = bit != 0u ? t : r;
    }
    if (bad != 0u) q = rt_sm_div_serial_(ma, mb, r);
    rem = r;
    return q;
}

uint rt_sm_div_bits_(uint a, uint b, bool ftz) {
    if (ftz) {
        a = rt_sm_daz_(a);
        b = rt_sm_daz_(b);
    }
    uint sign = (a ^ b) & RT_SM_SIGN;
    uint aa = a & ~RT_SM_SIGN, ab = b & ~RT_SM_SIGN;
    if (aa > RT_SM_INF) return a | RT_SM_QUIET;
    if (ab > RT_SM_INF) return b | RT_SM_QUIET;
    if (aa == RT_SM_INF) return ab == RT_SM_INF ? RT_SM_QNAN : (sign | RT_SM_INF);
    if (ab == RT_SM_INF) return sign;
    if (ab == 0u) return aa == 0u ? RT_SM_QNAN : (sign | RT_SM_INF);
    if (aa == 0u) return sign;
    uint ma, mb;
    int ea, eb;
    rt_sm_unpack_(aa, ma, ea);
    rt_sm_unpack_(ab, mb, eb);
    uint dbl = ma < mb ? 1u : 0u;
    int e = ea - eb + 127 - int(dbl);
    uint r, q = rt_sm_div_sig_(ma, mb, dbl, r);
    return rt_sm_round_pack_(sign, e, q, r, ftz);
}

/* ---- square root ---- */

uint rt_sm_sqrt_serial_(uint t, out uint rem_out) {
    uint root = 0u, rem = 0u;
    [[dont_unroll]] for (int i = 0; i < 25; i++, RT_VK_TICK) {
        uint pair = 0u;
        if (i < 13) pair = (t >> uint(24 - 2 * i)) & 3u;
        rem = (rem << 2) | pair;
        uint trial = (root << 2) | 1u;
        root <<= 1;
        uint d = rem - trial;
        uint bit = (d >> 31) ^ 1u;
        root |= bit;
        rem = bit != 0u ? d : rem;
    }
    rem_out = rem;
    return root;
}

uint rt_sm_sqrt_guess_(uint m, uint odd, inout uint bad) {
    float fx = uintBitsToFloat(((127u + odd) << 23) | (m & RT_SM_FRAC));
    float hx = 0.5 * fx;
    float y = uintBitsToFloat(0x5f3759dfu - (floatBitsToUint(fx) >> 1));
    y = y * (1.5 - hx * y * y);
    y = y * (1.5 - hx * y * y);
    float s = fx * y;
    s = s + (0.5 * y) * (fx - s * s);
    return rt_sm_fix24_(s, bad);
}

uint rt_sm_sqrt_sig_(uint m, uint odd, out uint rem_out) {
    uint t = m << (1u + odd);
    uint bad = 0u;
    uint root = rt_sm_sqrt_guess_(m, odd, bad) - 2u;
    uint rem = (t << 24) - root * root;
    bad |= rem >= (root << 3) + 16u ? 1u : 0u;
    [[unroll]] for (int k = 1; k >= 0; k--, RT_VK_TICK) {
        uint d = rem - ((root << uint(k + 1)) + (1u << uint(2 * k)));
        uint bit = (d >> 31) ^ 1u;
        root += bit << uint(k);
        rem = bit != 0u ? d : rem;
    }
    if (bad != 0u) root = rt_sm_sqrt_serial_(t, rem);
    rem_out = rem;
    return root;
}

uint rt_sm_sqrt_bits_(uint x, bool ftz) {
    if (ftz) x = rt_sm_daz_(x);
    if (rt_sm_is_nan_(x)) return x | RT_SM_QUIET;
    if ((x & ~RT_SM_SIGN) == 0u) return x;
    if ((x & RT_SM_SIGN) != 0u) return RT_SM_QNAN;
    if (x == RT_SM_INF) return x;
    uint m;
    int e;
    rt_sm_unpack_(x, m, e);
    uint odd = uint(e + 1) & 1u;
    uint rem, root = rt_sm_sqrt_sig_(m, odd, rem);
    int er = int(uint(e + 149) >> 1) - 11;
    return rt_sm_round_pack_(0u, er, root, rem, ftz);
}

/* ---- difference of products ---- */

void rt_sm_mul_exact_(uint a, uint b, out uint hi, out uint lo, out int e) {
    uint ma, mb;
    int ea, eb;
    rt_sm_unpack_(a, ma, ea);
    rt_sm_unpack_(b, mb, eb);
    uint ah = ma >> 12, al = ma & 0xfffu, bh = mb >> 12, bl = mb & 0xfffu;
    uint mid = ah * bl + al * bh;
    uint l = al * bl + ((mid & 0xfffu) << 12);
    uint h = ah * bh + (mid >> 12) + (l >> 24);
    l &= RT_SM_M24;
    int ex = ea + eb - 300;
    if (h < 0x00800000u) {
        h = (h << 1) | (l >> 23);
        l = (l << 1) & RT_SM_M24;
        ex -= 1;
    }
    hi = h;
    lo = l;
    e = ex;
}

int rt_sm_prod_class_(uint a, uint b) {
    uint aa = a & ~RT_SM_SIGN, ab = b & ~RT_SM_SIGN;
    if (aa > RT_SM_INF || ab > RT_SM_INF) return 2;
    if (aa == RT_SM_INF || ab == RT_SM_INF) return (aa == 0u || ab == 0u) ? 2 : 1;
    return 0;
}

uint rt_sm_dop_bits_(uint a, uint b, uint c, uint d, bool ftz) {
    if (ftz) {
        a = rt_sm_daz_(a);
        b = rt_sm_daz_(b);
        c = rt_sm_daz_(c);
        d = rt_sm_daz_(d);
    }
    uint s1 = (a ^ b) & RT_SM_SIGN, s2 = ((c ^ d) & RT_SM_SIGN) ^ RT_SM_SIGN;
    int k1 = rt_sm_prod_class_(a, b), k2 = rt_sm_prod_class_(c, d);
    if ((k1 | k2) != 0) {
        if (rt_sm_is_nan_(a)) return a | RT_SM_QUIET;
        if (rt_sm_is_nan_(b)) return b | RT_SM_QUIET;
        if (rt_sm_is_nan_(c)) return c | RT_SM_QUIET;
        if (rt_sm_is_nan_(d)) return d | RT_SM_QUIET;
        if (k1 == 2 || k2 == 2 || (k1 == 1 && k2 == 1 && s1 != s2)) return RT_SM_QNAN;
        return (k1 == 1 ? s1 : s2) | RT_SM_INF;
    }
    bool z1 = (a & ~RT_SM_SIGN) == 0u || (b & ~RT_SM_SIGN) == 0u;
    bool z2 = (c & ~RT_SM_SIGN) == 0u || (d & ~RT_SM_SIGN) == 0u;
    if (z1 && z2) return s1 & s2;
    uint xh = 0u, xl = 0u, yh = 0u, yl = 0u, sx, sy;
    int ex = 0, ey = 0;
    if (z1) {
        rt_sm_mul_exact_(c, d, xh, xl, ex);
        sx = s2;
        sy = s2;
        ey = ex;
    } else if (z2) {
        rt_sm_mul_exact_(a, b, xh, xl, ex);
        sx = s1;
        sy = s1;
        ey = ex;
    } else {
        uint h1, l1, h2, l2;
        int e1, e2;
        rt_sm_mul_exact_(a, b, h1, l1, e1);
        rt_sm_mul_exact_(c, d, h2, l2, e2);
        bool first = e1 > e2 || (e1 == e2 && (h1 > h2 || (h1 == h2 && l1 >= l2)));
        xh = first ? h1 : h2;
        xl = first ? l1 : l2;
        ex = first ? e1 : e2;
        sx = first ? s1 : s2;
        yh = first ? h2 : h1;
        yl = first ? l2 : l1;
        ey = first ? e2 : e1;
        sy = first ? s2 : s1;
    }
    uint y2 = yh, y1 = yl, y0 = 0u, st = 0u;
    uint sh = uint(ex - ey);
    if (sh >= 72u) {
        st = y2 | y1;
        y2 = 0u;
        y1 = 0u;
    } else {
        if (sh >= 48u) {
            st = y1;
            y0 = y2;
            y1 = 0u;
            y2 = 0u;
            sh -= 48u;
        } else if (sh >= 24u) {
            y0 = y1;
            y1 = y2;
            y2 = 0u;
            sh -= 24u;
        }
        if (sh != 0u) {
            uint up = 24u - sh;
            st |= y0 & ((1u << sh) - 1u);
            y0 = (y0 >> sh) | ((y1 << up) & RT_SM_M24);
            y1 = (y1 >> sh) | ((y2 << up) & RT_SM_M24);
            y2 >>= sh;
        }
    }
    y0 |= st != 0u ? 1u : 0u;
    uint r0, r1, r2, t;
    if (sx == sy) {
        t = y0;
        r0 = t & RT_SM_M24;
        t = xl + y1 + (t >> 24);
        r1 = t & RT_SM_M24;
        r2 = xh + y2 + (t >> 24);
    } else {
        t = 0u - y0;
        r0 = t & RT_SM_M24;
        t = xl - y1 - (t >> 31);
        r1 = t & RT_SM_M24;
        r2 = xh - y2 - (t >> 31);
    }
    uint sig, sticky;
    int p;
    if (r2 != 0u) {
        uint n = 32u - rt_sm_clz_(r2), k = 25u - n;
        p = 47 + int(n);
        sig = (r2 << k) | (r1 >> (24u - k));
        sticky = (r1 & ((1u << (24u - k)) - 1u)) | r0;
    } else if (r1 != 0u) {
        uint n = 32u - rt_sm_clz_(r1), k = 25u - n;
        p = 23 + int(n);
        sig = (r1 << k) | (r0 >> (24u - k));
        sticky = r0 & ((1u << (24u - k)) - 1u);
    } else if (r0 != 0u) {
        uint n = 32u - rt_sm_clz_(r0);
        p = int(n) - 1;
        sig = r0 << (25u - n);
        sticky = 0u;
    } else {
        return 0u;
    }
    return rt_sm_round_pack_(sx, p + ex + 103, sig, sticky, ftz);
}

#endif
