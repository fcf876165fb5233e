/* rt_kernel_args.h - what the OpenCL kernel files (rt_single_ray.cl, rt_ray_packet.cl)
 * share besides the maths: the scene-view arguments every tracing kernel
 * takes (in this order: host/cl_backend.c sets them as arguments 0..10) and
 * the AOV codes of rt.h. OpenCL C only. */
#ifndef RT_KERNEL_ARGS_H
#define RT_KERNEL_ARGS_H

#include "rt_camera.h"
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

/* AOV codes (rt_aov in rt.h). */
#define AOV_NONE      0
#define AOV_DEPTH     1
#define AOV_PRIMID    2
#define AOV_INSTID    3
#define AOV_NORMAL    4
#define AOV_BOX_TESTS 5
#define AOV_TRI_TESTS 6

#endif /* RT_KERNEL_ARGS_H */
