/* SPDX-License-Identifier: Apache-2.0 */
/* bvh.c - rt_bvh_build: options, names and the dispatch to each builder. */
#include "accel/bvh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh_internal.h"
#include "base/error.h"

rt_build_options rt_build_options_default(void) {
    rt_build_options o;
    o.builder = RT_BUILDER_SAH;
    o.threads = 0;
    o.bins = 16;
    o.leaf_size = 10;
    o.costs = rt_sah_costs_default();
    return o;
}

rt_sah_costs rt_sah_costs_default(void) {
    rt_sah_costs c = {1.0f, 2.0f};
    return c;
}

/* One name per rt_builder, by its value. */
static const char *const builder_names[] = {[RT_BUILDER_THESIS_SCALAR] = "thesis-scalar",
                                            [RT_BUILDER_THESIS_NEON] = "thesis-neon",
                                            [RT_BUILDER_THESIS_MT] = "thesis-mt",
                                            [RT_BUILDER_SAH] = "sah",
                                            [RT_BUILDER_LBVH] = "lbvh"};
_Static_assert(sizeof builder_names / sizeof *builder_names == RT_BUILDER_LBVH + 1,
               "a name for every rt_builder");

const char *rt_builder_name(rt_builder builder) {
    return (unsigned)builder < sizeof builder_names / sizeof *builder_names ? builder_names[builder]
                                                                            : "unknown";
}

rt_status rt_bvh_build_tris(const float *positions, const uint32_t *indices, uint32_t count,
                            const rt_build_options *options, rt_pool *pool, rt_bvh *out,
                            rt_error *err) {
    if (!out || (count && (!positions || !indices))) return RT_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    rt_build_options o = options ? *options : rt_build_options_default();
    if (o.builder == RT_BUILDER_SAH) {
        if (o.bins < 2 || o.bins > 256 || o.leaf_size < 1 || o.leaf_size > 1 << 20) {
            rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "bins must be 2..256 and leaf size >= 1");
            return RT_ERROR_INVALID_ARGUMENT;
        }
        return rt_bvh_build_sah_tris(positions, indices, count, &o, pool, 1, out, err);
    }
    rt_aabb *boxes = malloc(sizeof *boxes * (count ? count : 1));
    if (!boxes) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory for the boxes");
    for (uint32_t t = 0; t < count; t++) rt_tri_box(positions, indices + 3 * (size_t)t, &boxes[t]);
    rt_status st = rt_bvh_build(boxes, count, &o, pool, out, err);
    free(boxes);
    return st;
}

rt_status rt_bvh_build(const rt_aabb *boxes, uint32_t count, const rt_build_options *options,
                       rt_pool *pool, rt_bvh *out, rt_error *err) {
    if (!out || (!boxes && count)) return RT_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    rt_build_options o = options ? *options : rt_build_options_default();
    if (o.bins < 2 || o.bins > 256 || o.leaf_size < 1 || o.leaf_size > 1 << 20) {
        rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "bins must be 2..256 and leaf size >= 1");
        return RT_ERROR_INVALID_ARGUMENT;
    }
    if (o.builder == RT_BUILDER_SAH) return rt_bvh_build_sah(boxes, count, &o, pool, 1, out, err);
    if (o.builder == RT_BUILDER_LBVH) return rt_bvh_build_lbvh(boxes, count, &o, pool, out, err);
    return rt_bvh_build_thesis(boxes, count, &o, pool, out, err);
}
