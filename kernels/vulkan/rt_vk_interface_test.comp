/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_interface_test.comp - for test_gpu_interface (not used by frames):
 * one invocation goes through the rows of kernels/rt_interface_fields.def
 * in order, numbering the words n = 0, 1, ...: the bits of each field the
 * host writes (IN) are copied to items[n], and each field the device writes
 * (OUT) gets the tag RT_PROBE_TAG + n. The host then checks that every word
 * came from, or went to, the offset its C struct has (offsetof), in the
 * buffers and push constants declared exactly as the main shader declares
 * them (rt_vk_io.glsl and the generated rt_vk_interface.glsl). */
#version 450
#extension GL_GOOGLE_include_directive : require

#include "rt_vk_io.glsl"

layout(local_size_x = RT_VK_LOCAL) in;

#define RT_PROBE_TAG 0x40000000u

/* Where each buffer's struct is read or written: element 1 of an array, so
 * that the element's size counts too. */
#define RT_PROBE_hdr       hdr
#define RT_PROBE_nodes     nodes[1]
#define RT_PROBE_tris      tris[1]
#define RT_PROBE_instances instances[1]
#define RT_PROBE_materials materials[1]
#define RT_PROBE_lights    lights[1]
#define RT_PROBE_kd_nodes  kd_nodes[1]
#define RT_PROBE_rays      rays[1]
#define RT_PROBE_hits      hits[1]
#define RT_PROBE_counters  counters[1]
#define RT_PROBE_pc        pc

#define RT_BITS_F(x) floatBitsToUint(x)
#define RT_BITS_U(x) (x)
#define RT_BITS_I(x) uint(x)
#define RT_FROM_F(w) uintBitsToFloat(w)
#define RT_FROM_U(w) (w)
#define RT_FROM_I(w) int(w)

#define RT_PROBE_IN(x, kind)                                                                       \
    items[n] = RT_BITS_##kind(x);                                                                  \
    n++;
#define RT_PROBE_OUT(x, kind)                                                                      \
    x = RT_FROM_##kind(RT_PROBE_TAG + n);                                                          \
    n++;
#define RT_FIELD(dir, buf, type, field, kind) RT_PROBE_##dir(RT_PROBE_##buf.field, kind)
#define RT_FIELDS(dir, buf, type, field, count, kind)                                              \
    for (int k = 0; k < count; k++) {                                                              \
        RT_PROBE_##dir(RT_PROBE_##buf.field[k], kind)                                              \
    }
#define RT_VK_ONLY(rows) rows
#define RT_CL_ONLY(rows)

void main() {
    if (gl_GlobalInvocationID.x != 0u) return;
    uint n = 0u;
#include "rt_interface_fields.def"
}
