/* SPDX-License-Identifier: Apache-2.0 */
/* count.c - rt_count_intersections: the triangles each ray crosses, on the
 * renderer's layout and workers (cpu_ref/crossings.h), whatever its backend. */
#include <stdlib.h>

#include "base/error.h"
#include "crossings.h"
#include "render/render_frame.h"

rt_status rt_count_intersections(rt_renderer *r, rt_scene *scene, const rt_ray *rays, size_t count,
                                 uint32_t *counts) {
    if (!r) return RT_ERROR_INVALID_ARGUMENT;
    rt_status st =
        rt_frame_query_begin(r, "rt_count_intersections", scene, rays, count, counts, "counts");
    if (st != RT_OK) return st;
    rt_frame_state fs;
    st = rt_frame_layout(r, scene, RT_TRI_TEST_WATERTIGHT, 0, &fs);
    if (st != RT_OK) return st;
    const rt_ray *in;
    rt_ray *copy;
    st = rt_frame_rays(r, rays, count, &in, &copy);
    if (st != RT_OK) return st;
    st = rt_count_crossings(fs.layout.pool, r->denormals == RT_DENORMALS_FLUSH, &fs.flat, in, count,
                            counts, &r->error);
    free(copy);
    return st;
}
