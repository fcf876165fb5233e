/* SPDX-License-Identifier: Apache-2.0 */
/* rt_kernel_args.h - what the OpenCL kernel files (rt_single_ray.cl,
 * rt_ray_packet.cl) share besides the maths: the scene-view arguments every
 * tracing kernel takes (in the order of the view rows of rt_interface.def,
 * which host/opencl/cl_backend.c sets as arguments RT_ARG_*;
 * test_opencl_kernel_args holds their names and types to the table) and,
 * through rt_interface.h, the AOV codes. OpenCL C only. */
#ifndef RT_KERNEL_ARGS_H
#define RT_KERNEL_ARGS_H

#include "rt_camera.h"
#include "rt_interface.h"
#include "rt_shade.h"

/* The view arguments every tracing kernel takes, in this order. */
#define RT_VIEW_ARGS                                                                               \
    __global const rt_scene_header *hdr, __global const rt_node *nodes,                            \
        __global const rt_tri *tris, __global const uint *tri_ids,                                 \
        __global const float *tri_normals, __global const uint *tri_mats,                          \
        __global const rt_instance *instances, __global const uint *inst_ids,                      \
        __global const rt_material_d *materials, __global const rt_light_d *lights,                \
        __global const rt_kd_node *kd_nodes

#define RT_VIEW_INIT                                                                               \
    {                                                                                              \
        hdr, nodes, tris, tri_ids, tri_normals, tri_mats, instances, inst_ids, materials, lights,  \
            kd_nodes                                                                               \
    }

/* The completion check (docs/OPENCL.md, "Failures"): each work-item below
 * count ends with RT_K_DONE, one atomic increment of its kernel's counter in
 * done (RT_CL_DONE_<KERNEL>); after a tile the host compares the counters
 * with the items it launched, so a launch the device cut short is an error,
 * never an image with holes.
 * Fault injection for tests: built with -DRT_TEST_SKIP=N (the host adds it
 * when the environment has RTCL_TEST_OPENCL_SKIP=N), work-item i with
 * i % N == N - 1 does not count itself, and the kernels whose results no
 * other kernel reads (rt_k_shade, rt_k_wave_sum, rt_k_packet,
 * rt_k_packet_trace) skip its work too (RT_K_SKIPPED at their start): the
 * holes of a cut launch, without feeding unwritten rays or hits to a later
 * kernel. */
#ifdef RT_TEST_SKIP
#define RT_K_SKIPPED(i) ((i) % (uint)(RT_TEST_SKIP) == (uint)(RT_TEST_SKIP)-1u)
#else
#define RT_K_SKIPPED(i) 0
#endif
#define RT_K_DONE(done, KERNEL, i)                                                                 \
    do {                                                                                           \
        if (!RT_K_SKIPPED(i)) atomic_inc(&(done)[RT_CL_DONE_##KERNEL]);                            \
    } while (0)

#endif /* RT_KERNEL_ARGS_H */
