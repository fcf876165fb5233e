/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_io.glsl - what the Vulkan entry shaders share besides the maths (the
 * twin of kernels/rt_kernel_args.h): the per-dispatch buffers, declared from
 * the table (kernels/rt_interface.def, RT_VK_IO_BUFFERS of the generated
 * rt_vk_interface.glsl, which also holds the push constants pc and the AOV
 * codes). host/vulkan/vk_backend.c binds them by the same table.
 *
 * items (binding RT_VK_BUF_ITEMS): items[i] = 1 when item i of the tile may
 * have been cut short by the driver's loop limit (rt_vk_main.comp says how),
 * 2 when it suspended to go on in a further dispatch, else 0; from items[pc.list_at] on, the items
 * a re-run dispatch traces (pc.stride > 1), as pairs (item, state slot).
 *
 * state (binding RT_VK_BUF_STATE): RT_VK_STATE_WORDS words per slot, the
 * saved state of an item that suspended (items[i] = 2; rt_vk_resume.glsl). */
#ifndef RT_VK_IO_GLSL
#define RT_VK_IO_GLSL

#include "rt_vk_camera.glsl"
#include "rt_vk_shade.glsl" /* and the buffers, declared in rt_vk_resume.glsl */

#endif
