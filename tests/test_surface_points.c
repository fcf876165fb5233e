/* SPDX-License-Identifier: Apache-2.0 */
/* test_surface_points.c - shadow rays start on the right side of the surface
 * (issue 14, item 5): a finely tessellated convex dome (119,072 triangles)
 * lit by one light in front, so that every face looks at the light and
 * nothing can shadow it. Ambient 0 and a blue background: a
 * visible pixel that comes out exactly black had its shadow ray blocked by
 * the sphere itself, an error of the hit point. Counted at 1024x576 on each
 * CPU backend, with the dome at the origin and far from it (coordinates in
 * the thousands and 1e5; vertices there, or around the origin and moved by
 * the object's transform), seen from 5 and from 40 units. Must be 0. (The
 * OpenCL kernels share the maths; test_opencl_oracle holds them to it.)
 *
 * Before the fix the hit point was o + t d, whose rounding grows with the
 * distance travelled, while rt_offset_point moves the point by an amount
 * sized for its own magnitude; now it is the barycentric combination of the
 * vertices in object space, transformed to the world (Waechter and Binder
 * 2019). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rt.h"

/* A dome z = -(x^2 + y^2) over [-0.2, 0.2]^2 around c, n x n vertices
 * (2 (n-1)^2 triangles), seen from distance along +z and lit by one light in
 * front, off the view direction: every face looks at the light, and a convex
 * dome cannot shadow itself. Vertices in double, rounded once. */
static rt_scene *dome_scene(const double c[3], double distance, int n, int moved) {
    /* moved: the vertices around the origin and the object translated to c
     * (the hit point is then transformed to the world). */
    const double o[3] = {0.0, 0.0, 0.0};
    const double *at = moved ? o : c;
    rt_scene *s = NULL;
    CHECK(rt_scene_create(&s) == RT_OK);
    if (!s) return NULL;
    uint32_t verts = (uint32_t)(n * n), tris = (uint32_t)(2 * (n - 1) * (n - 1));
    float *p = malloc(sizeof(float) * 3 * verts);
    uint32_t *ix = malloc(sizeof(uint32_t) * 3 * tris);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double x = -0.2 + 0.4 * j / (n - 1), y = -0.2 + 0.4 * i / (n - 1);
            float *v = p + 3 * (i * n + j);
            v[0] = (float)(at[0] + x);
            v[1] = (float)(at[1] + y);
            v[2] = (float)(at[2] - (x * x + y * y));
        }
    uint32_t t = 0;
    for (int i = 0; i + 1 < n; i++)
        for (int j = 0; j + 1 < n; j++) {
            uint32_t a = (uint32_t)(i * n + j), b = a + 1, d = a + (uint32_t)n + 1,
                     e = a + (uint32_t)n;
            uint32_t q[6] = {a, b, d, a, d, e};
            memcpy(ix + 3 * t, q, sizeof q);
            t += 2;
        }
    uint32_t mesh, mat, obj, light;
    rt_material m = rt_material_default();
    m.ambient = 0.0f;
    m.diffuse = 1.0f;
    CHECK(rt_mesh_create(s, &mesh) == RT_OK);
    CHECK(rt_mesh_add_triangles(s, mesh, p, NULL, verts, ix, tris) == RT_OK);
    CHECK(rt_material_add(s, &m, &mat) == RT_OK);
    CHECK(rt_object_create(s, mat, &obj) == RT_OK);
    CHECK(rt_object_add_mesh(s, obj, mesh) == RT_OK);
    if (moved) {
        float xf[16] = {1, 0, 0, (float)c[0], 0, 1, 0, (float)c[1],
                        0, 0, 1, (float)c[2], 0, 0, 0, 1};
        CHECK(rt_object_transform(s, obj, xf) == RT_OK);
    }
    rt_camera cam;
    rt_camera_get(s, &cam);
    for (int k = 0; k < 3; k++) {
        cam.position[k] = (float)(c[k] + (k == 2 ? distance : 0.0));
        cam.look_at[k] = (float)c[k];
    }
    cam.up[0] = 0.0f, cam.up[1] = 1.0f, cam.up[2] = 0.0f;
    cam.hfov_degrees = (float)(2.0 * atan(0.22 / distance) * 57.29577951308232);
    cam.width = 1024;
    cam.height = 576;
    CHECK_MSG(rt_camera_set(s, &cam) == RT_OK, "%s", rt_scene_error(s));
    const float lp[3] = {(float)(c[0] + 0.4 * distance), (float)(c[1] + 0.3 * distance),
                         (float)(c[2] + distance)};
    const float white[3] = {1.0f, 1.0f, 1.0f}, blue[3] = {0.0f, 0.0f, 1.0f}, none[3] = {0, 0, 0};
    CHECK(rt_light_add(s, lp, white, &light) == RT_OK);
    CHECK(rt_scene_set_background(s, blue) == RT_OK);
    CHECK(rt_scene_set_ambient(s, none) == RT_OK);
    CHECK(rt_scene_commit(s) == RT_OK);
    free(p);
    free(ix);
    return s;
}

static void count_self_shadowed(const char *backend, const double c[3], double distance,
                                int moved) {
    rt_scene *s = dome_scene(c, distance, 245, moved);
    if (!s) return;
    rt_renderer *r = test_renderer(backend, 0);
    rt_framebuffer fb;
    rt_render_options o = rt_render_options_default();
    o.direct_only = 1;
    CHECK_MSG(rt_render(r, s, &o, &fb) == RT_OK, "%s", rt_renderer_error(r));
    long dome = 0, black = 0, first = -1;
    for (long i = 0; i < (long)fb.width * fb.height; i++) {
        const float *px = fb.pixels + 3 * i;
        if (px[0] == 0.0f && px[1] == 0.0f && px[2] == 1.0f) continue; /* background */
        dome++;
        if (px[0] == 0.0f && px[1] == 0.0f && px[2] == 0.0f) {
            black++;
            if (first < 0) first = i;
        }
    }
    printf("%-6s centre (%g, %g, %g)%s, %g away: %ld dome pixels, %ld self-shadowed\n", backend,
           c[0], c[1], c[2], moved ? " by a transform" : "", distance, dome, black);
    CHECK_MSG(dome > 300000, "%s: the dome covers only %ld pixels", backend, dome);
    CHECK_MSG(black == 0, "%s: %ld self-shadowed pixels (first at x %ld, y %ld)", backend, black,
              first % fb.width, first / fb.width);
    rt_framebuffer_free(&fb);
    rt_scene_destroy(s);
}

int main(void) {
    static const double centres[][3] = {{0, 0, 0}, {1000, -2000, 1500}, {1e5, 0, -3e4}};
    static const double distances[] = {5.0, 40.0};
    const char *backends[] = {"cpu", "packet"};
    for (int b = 0; b < 2; b++)
        for (int i = 0; i < 3; i++)
            for (int d = 0; d < 2; d++)
                for (int moved = 0; moved <= (i > 0); moved++)
                    count_self_shadowed(backends[b], centres[i], distances[d], moved);
    return TEST_END();
}
