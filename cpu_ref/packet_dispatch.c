/* packet_dispatch.c - which build of the packet tracer runs.
 *
 * cpu_ref/packet_trace.c is compiled for the baseline of the target
 * ("generic": NEON on ARM, SSE2 on x86-64) and, on x86-64, also with AVX2 and
 * with AVX-512 (CMakeLists.txt); the widest one the CPU supports is taken.
 * All of them give the same bits (tests/test_core_packet.c checks each one
 * the machine can run); they differ in speed only. The caller picks one by
 * name (rt_renderer_options.packet_isa); nothing here is global state. */
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

struct rt_pk_variant {
    const char *name;
    int lanes;
    pk_trace_fn fn;
    int (*supported)(void);
};

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
static const rt_pk_variant variants[] = {
#ifdef RT_PK_X86_VARIANTS
    {"avx512", 16, rt_pk_trace_avx512, has_avx512},
    {"avx2", 8, rt_pk_trace_avx2, has_avx2},
#endif
    {"generic", 4, rt_pk_trace_generic, always},
};
enum { VARIANTS = sizeof variants / sizeof variants[0] };

const rt_pk_variant *rt_pk_variant_find(const char *name) {
    int widest = !name || !*name;
    for (int i = 0; i < VARIANTS; i++)
        if ((widest || strcmp(name, variants[i].name) == 0) && variants[i].supported())
            return &variants[i];
    return NULL;
}

const char *rt_pk_variant_name(const rt_pk_variant *v) {
    return v->name;
}

int rt_pk_variant_lanes(const rt_pk_variant *v) {
    return v->lanes;
}

const char *rt_pk_isa_name(int i) {
    return i >= 0 && i < VARIANTS ? variants[i].name : NULL;
}

void rt_pk_trace(const rt_pk_variant *isa, const rt_scene_view *s, const rt_pk_wide *w,
                 const rt_pk_rays *rays, int any_hit, rt_pk_hits *hits, rt_pk_counts *counts) {
    isa->fn(s, w, rays, any_hit, hits, counts);
}
