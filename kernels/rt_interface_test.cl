/* SPDX-License-Identifier: Apache-2.0 */
/* rt_interface_test.cl - for test_gpu_interface (not part of the backend's
 * program): one work-item goes through the rows of rt_interface_fields.def
 * in order, numbering the words n = 0, 1, ...: the bits of each field the
 * host writes (IN) are copied to items[n], and each field the device writes
 * (OUT) gets the tag RT_PROBE_TAG + n. The host then checks that every word
 * came from, or went to, the offset its C struct has (offsetof). The scene
 * view arrives as the real kernels take it (RT_VIEW_ARGS, arguments
 * RT_ARG_*); the other buffers follow. */
#pragma OPENCL FP_CONTRACT OFF

#include "rt_kernel_args.h"

#define RT_PROBE_TAG 0x40000000u

/* Element 1 of each array, so that the element's size counts too. */
#define RT_PROBE_hdr       (*hdr)
#define RT_PROBE_nodes     nodes[1]
#define RT_PROBE_tris      tris[1]
#define RT_PROBE_instances instances[1]
#define RT_PROBE_materials materials[1]
#define RT_PROBE_lights    lights[1]
#define RT_PROBE_kd_nodes  kd_nodes[1]
#define RT_PROBE_rays      rays[1]
#define RT_PROBE_hits      hits[1]
#define RT_PROBE_counters  counters[1]
#define RT_PROBE_queue     queue[1]
#define RT_PROBE_records   records[1]

#define RT_BITS_F(x) as_uint(x)
#define RT_BITS_U(x) (x)
#define RT_BITS_I(x) (uint)(x)
#define RT_FROM_F(w) as_float(w)
#define RT_FROM_U(w) (w)
#define RT_FROM_I(w) (int)(w)

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
#define RT_VK_ONLY(rows)
#define RT_CL_ONLY(rows) rows

__kernel void rt_k_interface_test(RT_VIEW_ARGS, __global const rt_ray *rays,
                                  __global rt_hit_d *hits, __global rt_counters *counters,
                                  __global const rt_wave_entry *queue,
                                  __global rt_wave_record *records, __global uint *items) {
    if (get_global_id(0) != 0) return;
    uint n = 0;
#include "rt_interface_fields.def"
}
