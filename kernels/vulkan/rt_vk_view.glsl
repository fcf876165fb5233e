/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_view.glsl - the GLSL mirror of kernels/rt_view.h: the scene view as
 * storage buffers (declared from the view rows of kernels/rt_interface.def,
 * rt_scene_view's order) and the feature switches as specialization
 * constants (host/vulkan/vk_backend.c sets them from the scene, as OpenCL's
 * -D switches). */
#ifndef RT_VK_VIEW_GLSL
#define RT_VK_VIEW_GLSL

#include "rt_vk_interface.glsl" /* the SC_* constants, RT_VK_VIEW_BUFFERS */
#include "rt_vk_layout.glsl"

#define RT_SCENE_FLAGS()  SC_FLAGS
#define RT_INST_FLAGS(f)  (((f) | SC_INST_SET) & SC_INST_MASK)
#define RT_TRI_METHOD()   SC_TRI_METHOD

/* The scene view: the storage buffers of the interface table's view rows. */
RT_VK_VIEW_BUFFERS

#endif
