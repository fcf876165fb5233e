/* SPDX-License-Identifier: Apache-2.0 */
/* cpu_isa.h - the instruction-set builds of the CPU tracers: one table for
 * the packet tracer (packet_trace.h) and the single-ray tracer
 * (single_trace.h), one place that decides which builds this CPU runs.
 *
 * Both tracers are compiled once per instruction set (CMakeLists.txt): for
 * the target's baseline ("generic": SSE2 on x86-64, NEON on aarch64) and,
 * on x86-64, with AVX2 ("avx2") and with AVX-512F and VL ("avx512"). A build
 * is both tracers of one instruction set, named as --packet-isa names it;
 * all builds give the same bits (tests/test_core_packet.c and
 * test_core_single.c check each one the machine runs) and differ in speed
 * only. The caller picks one by name (rt_renderer_options.packet_isa);
 * nothing here is global state. */
#ifndef RT_CPU_ISA_H
#define RT_CPU_ISA_H

typedef struct rt_cpu_isa rt_cpu_isa;

/* The build named name ("generic", "avx2", "avx512"), or the widest the CPU
 * runs for NULL or ""; NULL when this build or CPU lacks it. */
const rt_cpu_isa *rt_cpu_isa_find(const char *name);

/* The name of this build's i-th instruction set, widest first (whether or
 * not the CPU runs it); NULL past the last. */
const char *rt_cpu_isa_at(int i);

const char *rt_cpu_isa_name(const rt_cpu_isa *isa);
/* The packet tracer's lanes per vector (4, 8 or 16). */
int rt_cpu_isa_lanes(const rt_cpu_isa *isa);
/* The single-ray tracer's node and block width (4 or 8): its trees are
 * rt_sw_shape(rt_cpu_isa_width(isa)). */
int rt_cpu_isa_width(const rt_cpu_isa *isa);

/* For the tracers' per-instruction-set files: RT_ISA names the build being
 * compiled (CMake defines it for each; generic otherwise), and
 * RT_ISA_SYMBOL(x) is x_<isa>, the name of that build's copy of x. */
#ifndef RT_ISA
#define RT_ISA generic
#endif
#define RT_ISA_CAT_(a, b)   a##_##b
#define RT_ISA_CAT(a, b)    RT_ISA_CAT_(a, b)
#define RT_ISA_SYMBOL(name) RT_ISA_CAT(name, RT_ISA)

#endif /* RT_CPU_ISA_H */
