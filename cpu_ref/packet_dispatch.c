/* packet_dispatch.c - which build of the packet tracer runs.
 *
 * cpu_ref/packet_trace.c is compiled for the baseline of the target
 * ("generic": NEON on ARM, SSE2 on x86-64) and, on x86-64, also with AVX2 and
 * with AVX-512 (CMakeLists.txt); the widest one the CPU supports is taken.
 * All of them give the same bits (tests/test_core_packet.c checks each one
 * the machine can run); they differ in speed only. RTCL_PACKET_ISA=NAME in the
 * environment, or rt_pk_select, picks one by name. */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "packet_trace.h"

typedef void (*pk_trace_fn)(const rt_scene_view *, const rt_pk_wide *, const rt_pk_rays *, int,
                            rt_pk_hits *, rt_pk_counts *);

void rt_pk_trace_generic(const rt_scene_view *s, const rt_pk_wide *w, const rt_pk_rays *rays,
                         int any_hit, rt_pk_hits *hits, rt_pk_counts *counts);
#ifdef RT_PK_X86_VARIANTS
void rt_pk_trace_avx2(const rt_scene_view *s, const rt_pk_wide *w, const rt_pk_rays *rays,
                      int any_hit, rt_pk_hits *hits, rt_pk_counts *counts);
void rt_pk_trace_avx512(const rt_scene_view *s, const rt_pk_wide *w, const rt_pk_rays *rays,
                        int any_hit, rt_pk_hits *hits, rt_pk_counts *counts);
#endif

typedef struct pk_variant {
    const char *name;
    int lanes;
    pk_trace_fn fn;
    int (*supported)(void);
} pk_variant;

static int always(void) {
    return 1;
}
#ifdef RT_PK_X86_VARIANTS
static int has_avx2(void) {
    return __builtin_cpu_supports("avx2");
}
static int has_avx512(void) {
    return __builtin_cpu_supports("avx512f");
}
#endif

/* Widest first. */
static const pk_variant variants[] = {
#ifdef RT_PK_X86_VARIANTS
    {"avx512", 16, rt_pk_trace_avx512, has_avx512},
    {"avx2", 8, rt_pk_trace_avx2, has_avx2},
#endif
    {"generic", 4, rt_pk_trace_generic, always},
};
enum { VARIANTS = sizeof variants / sizeof variants[0] };

static _Atomic(const pk_variant *) chosen;

static const pk_variant *find(const char *name) {
    for (int i = 0; i < VARIANTS; i++)
        if ((!name || strcmp(name, variants[i].name) == 0) && variants[i].supported())
            return &variants[i];
    return NULL;
}

static const pk_variant *current(void) {
    const pk_variant *v = atomic_load_explicit(&chosen, memory_order_acquire);
    if (v) return v;
    const char *env = getenv("RTCL_PACKET_ISA");
    v = env && *env ? find(env) : NULL;
    if (!v) v = find(NULL);
    atomic_store_explicit(&chosen, v, memory_order_release);
    return v;
}

int rt_pk_select(const char *name) {
    const pk_variant *v = find(name);
    if (!v) return 0;
    atomic_store_explicit(&chosen, v, memory_order_release);
    return 1;
}

const char *rt_pk_isa(void) {
    return current()->name;
}

int rt_pk_isa_lanes(void) {
    return current()->lanes;
}

const char *rt_pk_isa_name(int i) {
    return i >= 0 && i < VARIANTS ? variants[i].name : NULL;
}

void rt_pk_trace(const rt_scene_view *s, const rt_pk_wide *w, const rt_pk_rays *rays, int any_hit,
                 rt_pk_hits *hits, rt_pk_counts *counts) {
    current()->fn(s, w, rays, any_hit, hits, counts);
}
