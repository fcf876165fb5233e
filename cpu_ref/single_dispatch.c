/* single_dispatch.c - which build of the single-ray tracer runs.
 *
 * cpu_ref/single_trace.c is compiled like the packet tracer
 * (cpu_ref/packet_dispatch.c): for the target's baseline ("generic": NEON
 * on ARM, SSE2 on x86-64; width 4) and, on x86-64, with AVX2 and with
 * AVX-512 (width 8). All give the same bits (tests/test_core_single.c checks
 * each one the machine runs); the caller picks one by name. */
#include <string.h>

#include "single_trace.h"

typedef void (*sw_trace_fn)(const rt_scene_view *, const rt_sw_bvh *, const rt_ray *, size_t, int,
                            rt_hit_d *, rt_counters *);

#define RT_SW_DECLARE(isa)                                                                         \
    void rt_sw_trace_##isa(const rt_scene_view *s, const rt_sw_bvh *b, const rt_ray *rays,         \
                           size_t n, int any_hit, rt_hit_d *hits, rt_counters *c);                 \
    int rt_sw_width_##isa(void);
RT_SW_DECLARE(generic)
#ifdef RT_PK_X86_VARIANTS
RT_SW_DECLARE(avx2)
RT_SW_DECLARE(avx512)
#endif

struct rt_sw_variant {
    const char *name;
    sw_trace_fn fn;
    int (*width)(void);
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
static const rt_sw_variant variants[] = {
#ifdef RT_PK_X86_VARIANTS
    {"avx512", rt_sw_trace_avx512, rt_sw_width_avx512, has_avx512},
    {"avx2", rt_sw_trace_avx2, rt_sw_width_avx2, has_avx2},
#endif
    {"generic", rt_sw_trace_generic, rt_sw_width_generic, always},
};
enum { VARIANTS = sizeof variants / sizeof variants[0] };

const rt_sw_variant *rt_sw_variant_find(const char *name) {
    int widest = !name || !*name;
    for (int i = 0; i < VARIANTS; i++)
        if ((widest || strcmp(name, variants[i].name) == 0) && variants[i].supported())
            return &variants[i];
    return NULL;
}

const char *rt_sw_variant_name(const rt_sw_variant *v) {
    return v->name;
}

int rt_sw_variant_width(const rt_sw_variant *v) {
    return v->width();
}

void rt_sw_trace(const rt_sw_variant *v, const rt_scene_view *s, const rt_sw_bvh *b,
                 const rt_ray *rays, size_t n, int any_hit, rt_hit_d *hits, rt_counters *c) {
    v->fn(s, b, rays, n, any_hit, hits, c);
}
