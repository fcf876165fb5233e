/* rt_vk_render.comp - one frame's tile, one pixel per invocation: the
 * primary ray (rt_camera_ray), its closest hit, then the shaded colour
 * (shadow rays, reflection and refraction through rt_shade_hit's explicit
 * stack, no recursion) or an AOV, as rt_k_shade and rt_cpu_finish_pixel do.
 * Pixels pc.first .. pc.first + pc.count - 1 (row-major); counters[i] gets
 * pixel first + i's ray and test counts. */
#version 450
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

#include "rt_vk_io.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    uint pixel = pc.first + i;
    rt_ray_d r;
    rt_camera_ray(int(pixel % uint(hdr.width)), int(pixel / uint(hdr.width)), r);
    rt_counters c;
    c.box_tests = 0u;
    c.tri_tests = 0u;
    c.rays = 0u;
    rt_hit_d h;
    rt_trace(r, false, h, c);
    uint o = pixel * uint(pc.channels);
    bool hit_any = h.prim != RT_NO_HIT;
    if (pc.aov == AOV_DEPTH) {
        fb[o] = hit_any ? h.t : RT_INF;
    } else if (pc.aov == AOV_PRIMID) {
        fb[o] = hit_any ? float(h.prim) : -1.0;
    } else if (pc.aov == AOV_INSTID) {
        fb[o] = hit_any ? float(h.inst) : -1.0;
    } else if (pc.aov == AOV_NORMAL) {
        fb[o] = 0.0;
        fb[o + 1u] = 0.0;
        fb[o + 2u] = 0.0;
        if (hit_any) {
            rt_surface sf;
            rt_surface_at(r, h, sf);
            for (int k = 0; k < 3; k++) fb[o + uint(k)] = sf.ns[k];
        }
    } else {
        float rgb[3];
        rt_shade_hit(r, h, c, rgb);
        if (pc.aov == AOV_NONE)
            for (int k = 0; k < 3; k++) fb[o + uint(k)] = rgb[k];
        else
            fb[o] = float(pc.aov == AOV_BOX_TESTS ? c.box_tests : c.tri_tests);
    }
    counters[i] = c;
}
