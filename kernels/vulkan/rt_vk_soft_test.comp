/* rt_vk_soft_test.comp - the soft maths of rt_vk_soft_math.glsl on given
 * operands, for test_vulkan_oracle (not used by frames): case i reads the
 * four bit patterns a, b, c, d at rays-buffer words 4i .. 4i + 3 and writes
 * a / b, sqrt(a) and a*b - c*d at words 3i .. 3i + 2 of the hits buffer
 * (the _ftz variants when SC_DENORM_FLUSH is 1). */
#version 450
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

#include "rt_vk_soft_math.glsl"

layout(constant_id = 4) const uint SC_DENORM_FLUSH = 0u;
layout(std430, set = 0, binding = 10) readonly buffer B_in { uint operands[]; };
layout(std430, set = 0, binding = 11) writeonly buffer B_out { uint results[]; };
layout(push_constant) uniform Push {
    uint first;
    uint count;
    int aov;
    int channels;
    int any_hit;
    int query;
} pc;

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
