/* rt_vk_view.glsl - the GLSL mirror of kernels/rt_view.h: the scene view as
 * storage buffers (bindings 0..9 in rt_scene_view's order, the kd nodes at
 * 14, after the per-dispatch buffers 10..13 of rt_vk_io.glsl) and the
 * feature switches as specialization constants (host/vulkan/vk_backend.c
 * sets them from the scene, as OpenCL's -D switches). */
#ifndef RT_VK_VIEW_GLSL
#define RT_VK_VIEW_GLSL

#include "rt_vk_layout.glsl"

layout(constant_id = 0) const uint SC_FLAGS = 0u;         /* RT_STATIC_FLAGS */
layout(constant_id = 1) const uint SC_INST_SET = 0u;      /* RT_STATIC_INST_SET */
layout(constant_id = 2) const uint SC_INST_MASK = 3u;     /* RT_STATIC_INST_MASK */
layout(constant_id = 3) const uint SC_TRI_METHOD = 0u;    /* RT_STATIC_TRI_METHOD */

#define RT_SCENE_FLAGS()  SC_FLAGS
#define RT_INST_FLAGS(f)  (((f) | SC_INST_SET) & SC_INST_MASK)
#define RT_TRI_METHOD()   SC_TRI_METHOD

/* The scene view: bindings 0..9 in rt_scene_view's order. */
layout(std430, set = 0, binding = 0) readonly buffer B_hdr { rt_scene_header hdr; };
layout(std430, set = 0, binding = 1) readonly buffer B_nodes { rt_node nodes[]; };
layout(std430, set = 0, binding = 2) readonly buffer B_tris { rt_tri tris[]; };
layout(std430, set = 0, binding = 3) readonly buffer B_tri_ids { uint tri_ids[]; };
layout(std430, set = 0, binding = 4) readonly buffer B_normals { float tri_normals[]; };
layout(std430, set = 0, binding = 5) readonly buffer B_tri_mats { uint tri_mats[]; };
layout(std430, set = 0, binding = 6) readonly buffer B_inst { rt_instance instances[]; };
layout(std430, set = 0, binding = 7) readonly buffer B_inst_ids { uint inst_ids[]; };
layout(std430, set = 0, binding = 8) readonly buffer B_mats { rt_material_d materials[]; };
layout(std430, set = 0, binding = 9) readonly buffer B_lights { rt_light_d lights[]; };
layout(std430, set = 0, binding = 14) readonly buffer B_kd_nodes { rt_kd_node kd_nodes[]; };

#endif
