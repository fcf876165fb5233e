/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_soft_test.comp - the soft maths of rt_vk_soft_math.glsl on given
 * operands, for test_vulkan_oracle (not used by frames): case i reads the
 * four bit patterns a, b, c, d at words 4i .. 4i + 3 of the rays binding and
 * writes a / b, sqrt(a) and a*b - c*d at words 3i .. 3i + 2 of the hits
 * binding (the _ftz variants when SC_DENORM_FLUSH is 1). */
#version 450
#extension GL_GOOGLE_include_directive : require

#include "rt_vk_interface.glsl"
#include "rt_vk_soft_math.glsl"

layout(local_size_x = RT_VK_LOCAL) in;

layout(std430, set = 0, binding = RT_VK_BUF_RAYS) readonly buffer B_in { uint operands[]; };
layout(std430, set = 0, binding = RT_VK_BUF_HITS) writeonly buffer B_out { uint results[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    bool ftz = SC_DENORM_FLUSH != 0u;
    uint a = operands[4u * i], b = operands[4u * i + 1u];
    uint c = operands[4u * i + 2u], d = operands[4u * i + 3u];
    results[3u * i] = rt_sm_div_bits_(a, b, ftz);
    results[3u * i + 1u] = rt_sm_sqrt_bits_(a, ftz);
    results[3u * i + 2u] = rt_sm_dop_bits_(a, b, c, d, ftz);
}
