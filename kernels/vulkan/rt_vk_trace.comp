/* rt_vk_trace.comp - ray queries (rt_trace_rays): the closest or any hit of
 * rays[0 .. pc.count - 1] into hits[], each ray's tests into counters[]. */
#version 450
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

#include "rt_vk_io.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    rt_ray_d r = rays[i];
    rt_counters c;
    c.box_tests = 0u;
    c.tri_tests = 0u;
    c.rays = 0u;
    rt_hit_d h;
    rt_trace(r, pc.any_hit != 0, h, c);
    hits[i] = h;
    counters[i] = c;
}
