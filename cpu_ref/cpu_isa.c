/* SPDX-License-Identifier: Apache-2.0 */
/* cpu_isa.c - the table of the CPU tracers' instruction-set builds
 * (cpu_isa.h), and the one test of what this CPU runs. */
#include "cpu_isa.h"

#include <string.h>

#include "packet_trace.h"
#include "single_trace.h"

/* The builds compiled into the library, widest first (CMakeLists.txt
 * compiles the per-instruction-set files once for each and defines
 * RT_ISA_X86_BUILDS on x86-64). */
#if defined(RT_ISA_X86_BUILDS)
#define RT_ISA_BUILDS(X) X(avx512) X(avx2) X(generic)
#else
#define RT_ISA_BUILDS(X) X(generic)
#endif

#define RT_ISA_DECLARE(isa)                                                                        \
    extern const rt_pk_tracer rt_pk_tracer_##isa;                                                  \
    extern const rt_sw_tracer rt_sw_tracer_##isa;
RT_ISA_BUILDS(RT_ISA_DECLARE)

/* Whether this CPU runs a build: the one place that asks. On x86-64 GCC's
 * and Clang's __builtin_cpu_supports reads cpuid, and for AVX and AVX-512
 * also whether the operating system saves those registers (XCR0). The
 * baseline runs on every CPU of its target: SSE2 is part of x86-64, and
 * Advanced SIMD (NEON) of AArch64 (getauxval's HWCAP_ASIMD, always set), so
 * "generic" needs no test. */
static int runs_generic(void) {
    return 1;
}
#if defined(RT_ISA_X86_BUILDS)
/* Both builds also use POPCNT and BMI1 (CMakeLists.txt), which every CPU
 * with AVX2 has; asked all the same. */
static int runs_avx2(void) {
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt") &&
           __builtin_cpu_supports("bmi");
}
static int runs_avx512(void) {
    return runs_avx2() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
}
#endif

struct rt_cpu_isa {
    const char *name;
    const rt_pk_tracer *packet;
    const rt_sw_tracer *single;
    int (*runs)(void);
};

#define RT_ISA_ENTRY(isa) {#isa, &rt_pk_tracer_##isa, &rt_sw_tracer_##isa, runs_##isa},
static const rt_cpu_isa isas[] = {RT_ISA_BUILDS(RT_ISA_ENTRY)};
enum { ISAS = sizeof isas / sizeof isas[0] };

const rt_cpu_isa *rt_cpu_isa_find(const char *name) {
    const int widest = !name || !*name;
    for (int i = 0; i < ISAS; i++)
        if ((widest || strcmp(name, isas[i].name) == 0) && isas[i].runs()) return &isas[i];
    return NULL;
}

const char *rt_cpu_isa_at(int i) {
    return i >= 0 && i < ISAS ? isas[i].name : NULL;
}

const char *rt_cpu_isa_name(const rt_cpu_isa *isa) {
    return isa->name;
}

int rt_cpu_isa_lanes(const rt_cpu_isa *isa) {
    return isa->packet->lanes;
}

int rt_cpu_isa_width(const rt_cpu_isa *isa) {
    return isa->single->width;
}

void rt_pk_trace(const rt_cpu_isa *isa, const rt_scene_view *s, const rt_wide_bvh *w,
                 const rt_pk_rays *rays, int any_hit, rt_pk_hits *hits, rt_pk_counts *counts) {
    isa->packet->trace(s, w, rays, NULL, any_hit, hits, counts);
}

void rt_pk_trace_masked(const rt_cpu_isa *isa, const rt_scene_view *s, const rt_wide_bvh *w,
                        const rt_pk_rays *rays, const uint32_t *masks, int any_hit,
                        rt_pk_hits *hits, rt_pk_counts *counts) {
    isa->packet->trace(s, w, rays, masks, any_hit, hits, counts);
}

void rt_sw_trace(const rt_cpu_isa *isa, const rt_scene_view *s, const rt_wide_bvh *b,
                 const rt_ray *rays, size_t n, int any_hit, rt_hit_d *hits, rt_counters *c) {
    isa->single->trace(s, b, rays, NULL, n, any_hit, hits, c);
}

void rt_sw_trace_masked(const rt_cpu_isa *isa, const rt_scene_view *s, const rt_wide_bvh *b,
                        const rt_ray *rays, const uint32_t *masks, size_t n, int any_hit,
                        rt_hit_d *hits, rt_counters *c) {
    isa->single->trace(s, b, rays, masks, n, any_hit, hits, c);
}
