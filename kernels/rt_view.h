/* SPDX-License-Identifier: Apache-2.0 */
/* rt_view.h - the scene as a backend sees it: rt_scene_view, the arrays of
 * the flattened layout (rt_layout.h), and the feature switches that read the
 * scene's flags at run time or take them as compile-time constants. Valid
 * C99 and OpenCL C (rt_math_profile.h); in OpenCL each array is a kernel
 * argument (rt_kernel_args.h), in GLSL a storage buffer
 * (kernels/vulkan/rt_vk_view.glsl, where the switches are specialization
 * constants). */
#ifndef RT_KERNELS_VIEW_H
#define RT_KERNELS_VIEW_H

#include "rt_math_profile.h"

/* Feature switches. By default the header and instance flags are read at run
 * time. An OpenCL kernel specialised to a scene is compiled with
 * -DRT_STATIC_FLAGS=<header flags> (and RT_STATIC_INST_SET / _MASK, and
 * RT_STATIC_TRI_METHOD), so unused paths (secondary rays, instance transforms,
 * normal interpolation) fold away. The values are those of the scene being
 * rendered, so the result is the same either way. */
#ifdef RT_STATIC_FLAGS
#define RT_SCENE_FLAGS(s) (RT_STATIC_FLAGS)
#define RT_INST_FLAGS(in) ((((in)->flags) | (RT_STATIC_INST_SET)) & (RT_STATIC_INST_MASK))
#else
#define RT_SCENE_FLAGS(s) ((s)->hdr->flags)
#define RT_INST_FLAGS(in) ((in)->flags)
#endif
#ifdef RT_STATIC_TRI_METHOD
#define RT_TRI_METHOD(s) (RT_STATIC_TRI_METHOD)
#else
#define RT_TRI_METHOD(s) ((s)->hdr->tri_method)
#endif

/* Everything a backend reads. In OpenCL each pointer is a kernel argument. */
typedef struct rt_scene_view {
    RT_GLOBAL const rt_scene_header *hdr;
    RT_GLOBAL const rt_node *nodes;
    RT_GLOBAL const rt_tri *tris;
    RT_GLOBAL const rt_u32 *tri_ids;
    RT_GLOBAL const float *tri_normals;
    RT_GLOBAL const rt_u32 *tri_mats;
    RT_GLOBAL const rt_instance *instances;
    RT_GLOBAL const rt_u32 *inst_ids;
    RT_GLOBAL const rt_material_d *materials;
    RT_GLOBAL const rt_light_d *lights;
    RT_GLOBAL const rt_kd_node *kd_nodes; /* kd-tree meshes (rt_kd.h) */
} rt_scene_view;

#endif /* RT_KERNELS_VIEW_H */
