/* bvh_fast.c - placeholder until the fast builder lands. */
#include <stdio.h>

#include "bvh_internal.h"

rt_status rt_bvh_build_fast(const rt_aabb *boxes, uint32_t count, const rt_build_options *options,
                            rt_pool *pool, int use_neon, rt_bvh *out, char *msg, size_t msg_size) {
    if (msg) snprintf(msg, msg_size, "the fast builder is not built yet");
    return RT_ERROR_UNSUPPORTED;
}
