/* bvh_thesis.c - placeholder until the thesis builder lands. */
#include <stdio.h>

#include "bvh_internal.h"

rt_status rt_bvh_build_thesis(const rt_aabb *boxes, uint32_t count, const rt_build_options *options,
                              rt_pool *pool, rt_bvh *out, char *msg, size_t msg_size) {
    if (msg) snprintf(msg, msg_size, "the thesis builder is not built yet");
    return RT_ERROR_UNSUPPORTED;
}
