/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_oracle_acne.c - surface offsets (Waechter and Binder 2019) leave
 * no shadow acne: near the origin and 1e5 units away.
 * 1. A lit plane with nothing above it, ambient 0: every pixel that sees the
 *    plane must be lit (a shadowed one is acne).
 * 2. The built-in scenes, as shipped and moved by 1e5: no shadow ray from a
 *    primary hit may hit the triangle it left. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "layout/flat.h"
#include "scene/scene.h"
#include "rt_shade.h"
#include "scene/scene_builtin.h"

static void lit_plane(float offset) {
    rt_scene *s;
    rt_scene_create(&s);
    const float o = offset;
    /* A wavy-free but finely tessellated plane: many shared edges. */
    enum { N = 16 };
    float pos[(N + 1) * (N + 1) * 3];
    uint32_t idx[N * N * 6], k = 0;
    for (int j = 0; j <= N; j++)
        for (int i = 0; i <= N; i++) {
            float *p = pos + 3 * (j * (N + 1) + i);
            p[0] = o + (float)i - N / 2;
            p[1] = o + 0.01f * (float)i; /* slightly tilted */
            p[2] = o + (float)j - N / 2;
        }
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            uint32_t a = (uint32_t)(j * (N + 1) + i), b = a + 1, c = a + N + 1, d = c + 1;
            idx[k++] = a, idx[k++] = c, idx[k++] = b;
            idx[k++] = b, idx[k++] = c, idx[k++] = d;
        }
    uint32_t mesh, mat, obj, light;
    rt_material m = rt_material_default();
    m.ambient = 0.0f;
    rt_material_add(s, &m, &mat);
    rt_mesh_create(s, &mesh);
    rt_mesh_add_triangles(s, mesh, pos, NULL, (N + 1) * (N + 1), idx, N * N * 2);
    rt_object_create(s, mat, &obj);
    rt_object_add_mesh(s, obj, mesh);
    const float lp[3] = {o + 1.0f, o + 20.0f, o - 2.0f}, white[3] = {1, 1, 1};
    rt_light_add(s, lp, white, &light);
    rt_camera cam = {{o, o + 3.0f, o + 9.0f}, {o, o, o}, {0, 1, 0}, 70.0f, 160, 90};
    rt_camera_set(s, &cam);
    rt_render_options opt = rt_render_options_default();
    const char *backends[] = {"cpu", "packet"};
    for (int b = 0; b < 2; b++) {
        rt_renderer *r = test_renderer(backends[b], 2);
        rt_framebuffer fb, depth;
        CHECK(rt_render(r, s, &opt, &fb) == RT_OK);
        opt.aov = RT_AOV_DEPTH;
        CHECK(rt_render(r, s, &opt, &depth) == RT_OK);
        opt.aov = RT_AOV_NONE;
        int seen = 0, dark = 0;
        for (int i = 0; i < fb.width * fb.height; i++) {
            if (!isfinite(depth.pixels[i])) continue;
            seen++;
            if (!(fb.pixels[3 * i] > 0.0f)) dark++;
        }
        CHECK_MSG(seen > fb.width * fb.height / 3, "plane at %g: only %d pixels see it", offset,
                  seen);
        CHECK_MSG(dark == 0, "plane at %g (%s): %d of %d lit pixels are in shadow (acne)", offset,
                  backends[b], dark, seen);
        rt_framebuffer_free(&fb);
        rt_framebuffer_free(&depth);
    }
    rt_scene_destroy(s);
}

/* Shadow rays from primary hits never hit their own triangle. */
static void self_hits(const char *name, float offset) {
    rt_scene *s;
    rt_error err;
    CHECK(rt_scene_builtin(name, &s, &err) == RT_OK);
    if (!s) return;
    if (offset != 0.0f) {
        const float move[16] = {1, 0, 0, offset, 0, 1, 0, offset, 0, 0, 1, offset, 0, 0, 0, 1};
        for (uint32_t o = 0; o < s->object_count; o++) rt_object_transform(s, o, move);
        for (uint32_t l = 0; l < s->light_count; l++)
            for (int k = 0; k < 3; k++) s->lights[l].position[k] += offset;
        rt_camera cam;
        rt_camera_get(s, &cam);
        for (int k = 0; k < 3; k++) cam.position[k] += offset, cam.look_at[k] += offset;
        rt_camera_set(s, &cam);
    }
    rt_camera cam;
    rt_camera_get(s, &cam);
    cam.width = 256;
    cam.height = 144;
    rt_camera_set(s, &cam);
    const rt_flat *flat = test_layout(s, 1);
    if (!flat) {
        rt_scene_destroy(s);
        return;
    }
    rt_scene_view v = rt_flat_view(flat);
    int tested = 0, acne = 0;
    for (int y = 0; y < cam.height; y++)
        for (int x = 0; x < cam.width; x++) {
            rt_ray r;
            rt_hit_d h;
            rt_counters c = {0, 0, 0};
            rt_camera_ray(v.hdr, x, y, &r);
            if (!rt_trace(&v, &r, 0, &h, &c)) continue;
            rt_surface sf;
            rt_surface_at(&v, &r, &h, &sf);
            for (rt_u32 l = 0; l < v.hdr->light_count; l++) {
                float L[3];
                for (int k = 0; k < 3; k++) L[k] = v.lights[l].position[k] - sf.p[k];
                rt_ray sr;
                rt_hit_d sh;
                rt_offset_point(sf.p, sf.ng, rt_dot3(sf.ng, L) >= 0.0f ? 1.0f : -1.0f, sr.org);
                for (int k = 0; k < 3; k++) sr.dir[k] = v.lights[l].position[k] - sr.org[k];
                sr.tmin = 0.0f;
                sr.tmax = RT_SHADOW_TMAX;
                tested++;
                if (rt_trace(&v, &sr, 0, &sh, &c) && sh.inst == h.inst && sh.prim == h.prim) acne++;
            }
        }
    CHECK_MSG(tested > 1000, "%s: too few shadow rays", name);
    CHECK_MSG(acne == 0, "%s moved by %g: %d of %d shadow rays hit their own triangle", name,
              offset, acne, tested);
    rt_scene_destroy(s);
}

int main(void) {
    lit_plane(0.0f);
    lit_plane(1e5f);
    lit_plane(-3e5f);
    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        self_hits(rt_builtin_scene_names[i], 0.0f);
        self_hits(rt_builtin_scene_names[i], 1e5f);
    }
    return TEST_END();
}
