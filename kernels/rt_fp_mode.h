/* SPDX-License-Identifier: Apache-2.0 */
/* rt_fp_mode.h - the calling thread's denormal mode on the CPU (C only).
 *
 * The project's denormal policy (docs/PORTABLE_MATH.md): "preserve" is IEEE
 * gradual underflow; "flush" is flush-to-zero for results and
 * denormals-are-zero for inputs, what most GPUs do. The CPU backends run a
 * flushing comparison by setting the thread's floating-point control
 * register around their work (x86: MXCSR.FTZ and MXCSR.DAZ; AArch64:
 * FPCR.FZ), so every hardware float operation of the oracle flushes; the
 * shared maths' integer-only functions (rt_soft_math.h) ask rt_fp_flushing()
 * which of their variants the thread's mode corresponds to.
 *
 * Where neither register exists the mode cannot be set: rt_fp_can_flush()
 * is 0 and the CPU backends refuse "flush" with a clear error.
 */
#ifndef RT_FP_MODE_H
#define RT_FP_MODE_H

#include <stdint.h>

#if defined(__SSE2__) || defined(_M_X64)
#include <xmmintrin.h>
#define RT_FP_FLUSH_BITS 0x8040u /* MXCSR: FTZ (bit 15) | DAZ (bit 6) */
typedef unsigned rt_fp_saved;
static inline int rt_fp_can_flush(void) {
    return 1;
}
static inline int rt_fp_flushing(void) {
    return (_mm_getcsr() & RT_FP_FLUSH_BITS) == RT_FP_FLUSH_BITS;
}
static inline rt_fp_saved rt_fp_set_flush(int flush) {
    unsigned saved = _mm_getcsr();
    _mm_setcsr(flush ? (saved | RT_FP_FLUSH_BITS) : (saved & ~RT_FP_FLUSH_BITS));
    return saved;
}
static inline void rt_fp_restore(rt_fp_saved saved) {
    _mm_setcsr(saved);
}
#elif defined(__aarch64__)
#define RT_FP_FLUSH_BITS ((uint64_t)1 << 24) /* FPCR.FZ: inputs and results */
typedef uint64_t rt_fp_saved;
static inline uint64_t rt_fp_fpcr_(void) {
    uint64_t v;
    __asm__ volatile("mrs %0, fpcr" : "=r"(v));
    return v;
}
static inline int rt_fp_can_flush(void) {
    return 1;
}
static inline int rt_fp_flushing(void) {
    return (rt_fp_fpcr_() & RT_FP_FLUSH_BITS) != 0;
}
static inline rt_fp_saved rt_fp_set_flush(int flush) {
    uint64_t saved = rt_fp_fpcr_();
    uint64_t v = flush ? (saved | RT_FP_FLUSH_BITS) : (saved & ~RT_FP_FLUSH_BITS);
    __asm__ volatile("msr fpcr, %0" : : "r"(v));
    return saved;
}
static inline void rt_fp_restore(rt_fp_saved saved) {
    __asm__ volatile("msr fpcr, %0" : : "r"(saved));
}
#else
typedef int rt_fp_saved;
static inline int rt_fp_can_flush(void) {
    return 0;
}
static inline int rt_fp_flushing(void) {
    return 0;
}
static inline rt_fp_saved rt_fp_set_flush(int flush) {
    (void)flush;
    return 0;
}
static inline void rt_fp_restore(rt_fp_saved saved) {
    (void)saved;
}
#endif

#endif /* RT_FP_MODE_H */
