/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_ticks.glsl - each invocation's own count of the loop iterations it
 * has run (rt_vk_resume.glsl says what for): every loop of the shaders
 * adds RT_VK_TICK in its increment, so that one iteration counts one,
 * whether or not the compiler unrolls the loop (a loop the driver unrolls
 * costs the driver's budget nothing: the count only over-states it). The
 * iteration that ends a loop, which the driver counts too, is covered by
 * the constant each checkpoint adds (RT_VK_UNIT). Integer additions only:
 * no float operation depends on it. */
#ifndef RT_VK_TICKS_GLSL
#define RT_VK_TICKS_GLSL

uint rt_vk_ticks = 0u;
#define RT_VK_TICK rt_vk_ticks++

#endif
