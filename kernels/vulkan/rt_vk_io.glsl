/* rt_vk_io.glsl - what the Vulkan entry shaders share besides the maths: the
 * per-dispatch buffers (bindings 10..13, after the scene view's 0..9), the
 * push constants and the AOV codes of rt.h. host/vulkan/vk_backend.c binds
 * them in this order. */
#ifndef RT_VK_IO_GLSL
#define RT_VK_IO_GLSL

#include "rt_vk_camera.glsl"
#include "rt_vk_shade.glsl"

layout(std430, set = 0, binding = 10) readonly buffer B_rays { rt_ray rays[]; };
layout(std430, set = 0, binding = 11) writeonly buffer B_hits { rt_hit_d hits[]; };
layout(std430, set = 0, binding = 12) writeonly buffer B_counters { rt_counters counters[]; };
layout(std430, set = 0, binding = 13) writeonly buffer B_fb { float fb[]; };
/* Binding 15: items[i] = 1 when item i of the tile may have been cut short
 * by the driver's loop limit (rt_vk_main.comp says how), else 0; from
 * items[pc.list_at] on, the items a re-run dispatch traces (pc.stride > 1). */
layout(std430, set = 0, binding = 15) buffer B_items { uint items[]; };

/* vk_push in host/vulkan/vk_backend.c. */
layout(push_constant) uniform Push {
    uint first;   /* the tile's first pixel */
    uint count;   /* pixels or rays in this dispatch */
    int aov;      /* rt_aov */
    int channels; /* floats per pixel of fb */
    int any_hit;  /* ray queries: 1 any hit, 0 closest */
    int query;    /* 1: ray queries (rays -> hits), 0: a frame's tile */
    uint canary;  /* 2: the iterations of the loop-limit canary */
    uint stride;  /* 1: invocation i is item i; > 1: a re-run (one item per stride) */
    uint ballast; /* 0; a test's iterations spent before tracing */
    uint list_at; /* where the re-run's item list starts in items */
} pc;

#define AOV_NONE      0
#define AOV_DEPTH     1
#define AOV_PRIMID    2
#define AOV_INSTID    3
#define AOV_NORMAL    4
#define AOV_BOX_TESTS 5
#define AOV_TRI_TESTS 6

#endif
