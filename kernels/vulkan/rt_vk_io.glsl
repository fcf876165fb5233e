/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_io.glsl - what the Vulkan entry shaders share besides the maths (the
 * twin of kernels/rt_kernel_args.h): the per-dispatch buffers, declared from
 * the table (kernels/rt_interface.def, RT_VK_IO_BUFFERS of the generated
 * rt_vk_interface.glsl, which also holds the push constants pc and the AOV
 * codes). host/vulkan/vk_backend.c binds them by the same table.
 *
 * items (binding RT_VK_BUF_ITEMS): items[i] = 1 when item i of the tile may
 * have been cut short by the driver's loop limit (rt_vk_main.comp says how),
 * else 0; from items[pc.list_at] on, the items a re-run dispatch traces
 * (pc.stride > 1). */
#ifndef RT_VK_IO_GLSL
#define RT_VK_IO_GLSL

#include "rt_vk_camera.glsl"
#include "rt_vk_shade.glsl"

RT_VK_IO_BUFFERS

#endif
