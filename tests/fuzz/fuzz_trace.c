/* SPDX-License-Identifier: Apache-2.0 */
/* fuzz_trace.c - libFuzzer harness: fuzzed rays through every CPU backend,
 * each hit compared bit for bit with the scalar oracle (the cpu backend).
 *
 * The scene is fixed: the built-in Cornell box (several objects, one moved
 * by a transform, spheres, keyframes) plus a finely tessellated bumpy
 * surface about 1500 units from the origin, a copy of it under a rotation,
 * and degenerate and coincident triangles. The input is one flags byte (bit
 * 0: any hit; bits 1-2: the triangle test; bit 3: a lane mask; bit 4: the
 * flush-to-zero denormal policy) and then rays of 8 floats each
 * (org, dir, tmin, tmax: any bit pattern: NaN, infinities, denormals,
 * inverted ranges), at most 128.
 *
 * Two levels are checked:
 * - the API: rt_trace_rays on a cpu renderer against packet renderers of
 *   every instruction set the CPU runs (generic, avx2, avx512): the closest
 *   hit's hit, t, u, v, prim and inst in every bit; for any-hit queries,
 *   whether there is a hit. A hit must also lie in [tmin, tmax]. With the
 *   flush policy, cpu and packet both flush (RT_DENORMALS_FLUSH), and the
 *   range check reads denormal range ends as zeros, as the tracers do.
 * - the packet kernel, on the rays as they are (rt_trace_rays turns invalid
 *   rays into misses before a backend sees them; the renderer's own
 *   secondary rays do not pass that filter): packets of 64 lanes, the valid
 *   lanes chosen by the input, through rt_pk_trace of every instruction set
 *   against rt_trace lane by lane. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "layout/flat.h"
#include "oracle_util.h"
#include "packet_trace.h"
#include "render/renderer_internal.h"
#include "scene/scene_builtin.h"

enum { MAX_RAYS = 128, MAX_ISAS = 3 };

static rt_scene *scene;
static rt_renderer *oracle, *oracle_flush;
static rt_renderer *packet[MAX_ISAS], *packet_flush[MAX_ISAS];
static const rt_cpu_isa *isa[MAX_ISAS];
static int isa_count;

static void must(rt_status st, const char *what) {
    if (st != RT_OK) {
        fprintf(stderr, "fuzz_trace set-up: %s failed (%s)\n", what, rt_status_string(st));
        abort();
    }
}

/* One mesh of n x n quads (two triangles each) of cell size h, a bump in y,
 * with its corner at (x0, y0, z0). */
static void add_surface(rt_scene *s, float x0, float y0, float z0, int n, float h, uint32_t *mesh) {
    const uint32_t nv = (uint32_t)((n + 1) * (n + 1)), nt = (uint32_t)(2 * n * n);
    float *p = malloc(sizeof(float) * 3 * nv);
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * nt);
    if (!p || !idx) abort();
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            float *v = p + 3 * (j * (n + 1) + i);
            v[0] = x0 + h * (float)i;
            v[1] = y0 + h * 0.3f * (float)((i * 7 + j * 13) % 5);
            v[2] = z0 + h * (float)j;
        }
    uint32_t t = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)(n + 1),
                     d = c + 1;
            uint32_t *q = idx + 6 * t / 2;
            q[0] = a, q[1] = c, q[2] = b, q[3] = b, q[4] = c, q[5] = d;
            t += 2;
        }
    must(rt_mesh_create(s, mesh), "rt_mesh_create");
    must(rt_mesh_add_triangles(s, *mesh, p, NULL, nv, idx, nt), "surface");
    free(p);
    free(idx);
}

static void set_up(void) {
    rt_error err;
    must(rt_scene_builtin("cornell", &scene, &err), "the Cornell box");
    uint32_t mat, mesh, obj;
    rt_material m = rt_material_default();
    must(rt_material_add(scene, &m, &mat), "rt_material_add");

    /* Far from the origin, cells of 0.01: hits at tiny t far out. */
    add_surface(scene, 1500.0f, 1498.5f, -1500.0f, 24, 0.01f, &mesh);
    must(rt_object_create(scene, mat, &obj), "rt_object_create");
    must(rt_object_add_mesh(scene, obj, mesh), "rt_object_add_mesh");
    /* The same surface turned about y by 90 degrees and moved. */
    must(rt_object_create(scene, mat, &obj), "rt_object_create");
    must(rt_object_add_mesh(scene, obj, mesh), "rt_object_add_mesh");
    const float turn[16] = {0, 0, 1, 3.0f, 0, 1, 0, -1500.0f, -1, 0, 0, 1.0f, 0, 0, 0, 1};
    must(rt_object_transform(scene, obj, turn), "rt_object_transform");

    /* Degenerate triangles (a repeated vertex, three collinear points, a
     * point), two identical ones and a permuted copy, near the box. */
    const float p[] = {0,    0.5f, 0.5f, 1,    0.5f, 0.5f, 0,    1.5f, 0.5f, 2,   0.5f,
                       0.5f, 0.3f, 0.9f, 0.1f, 0.3f, 0.9f, 0.1f, 0.3f, 0.9f, 0.1f};
    const uint32_t t[] = {0, 0, 2, 0, 1, 3, 4, 5, 6, 0, 1, 2, 0, 1, 2, 1, 2, 0};
    must(rt_mesh_create(scene, &mesh), "rt_mesh_create");
    must(rt_mesh_add_triangles(scene, mesh, p, NULL, 7, t, 6), "degenerate triangles");
    must(rt_object_create(scene, mat, &obj), "rt_object_create");
    must(rt_object_add_mesh(scene, obj, mesh), "rt_object_add_mesh");
    must(rt_scene_commit(scene), "rt_scene_commit");

    rt_renderer_options o = rt_renderer_options_default();
    o.threads = 1;
    must(rt_renderer_create(&o, &oracle, &err), "the cpu renderer");
    o.denormals = RT_DENORMALS_FLUSH;
    must(rt_renderer_create(&o, &oracle_flush, &err), "the flushing cpu renderer");
    for (int i = 0; rt_cpu_isa_at(i) && isa_count < MAX_ISAS; i++) {
        const rt_cpu_isa *v = rt_cpu_isa_find(rt_cpu_isa_at(i));
        if (!v) continue; /* this CPU lacks it */
        o.backend = "packet";
        o.packet_isa = rt_cpu_isa_at(i);
        o.denormals = RT_DENORMALS_PRESERVE;
        must(rt_renderer_create(&o, &packet[isa_count], &err), "a packet renderer");
        o.denormals = RT_DENORMALS_FLUSH;
        must(rt_renderer_create(&o, &packet_flush[isa_count], &err), "a flushing packet renderer");
        isa[isa_count++] = v;
    }
}

static void report(const char *what, const char *isa_name, int i, const rt_ray *r) {
    fprintf(stderr, "%s (%s), ray %d: org %a %a %a dir %a %a %a t [%a, %a]\n", what, isa_name, i,
            (double)r->org[0], (double)r->org[1], (double)r->org[2], (double)r->dir[0],
            (double)r->dir[1], (double)r->dir[2], (double)r->tmin, (double)r->tmax);
}

static int same_bits(float a, float b) {
    return memcmp(&a, &b, sizeof a) == 0;
}

/* The API level: rt_trace_rays, cpu against packet. */
/* x as the flush-to-zero policy reads it: a denormal is a zero of its sign. */
static float as_flushed(float x, int flush) {
    return flush && fabsf(x) < FLT_MIN ? copysignf(0.0f, x) : x;
}

static void check_api(const rt_ray *rays, int n, const rt_trace_options *opt, int flush) {
    rt_hit want[MAX_RAYS], got[MAX_RAYS];
    must(rt_trace_rays(flush ? oracle_flush : oracle, scene, rays, (size_t)n, want, opt),
         "rt_trace_rays (cpu)");
    for (int i = 0; i < n; i++)
        if (want[i].hit && !(want[i].t >= as_flushed(rays[i].tmin, flush) &&
                             want[i].t <= as_flushed(rays[i].tmax, flush))) {
            report("the cpu backend's hit is outside [tmin, tmax]", "cpu", i, &rays[i]);
            fprintf(stderr, "t %a\n", (double)want[i].t);
            abort();
        }
    for (int k = 0; k < isa_count; k++) {
        must(rt_trace_rays(flush ? packet_flush[k] : packet[k], scene, rays, (size_t)n, got, opt),
             "rt_trace_rays (packet)");
        for (int i = 0; i < n; i++) {
            const rt_hit *a = &want[i], *b = &got[i];
            int ok = a->hit == b->hit;
            if (ok && !opt->any_hit)
                ok = same_bits(a->t, b->t) && same_bits(a->u, b->u) && same_bits(a->v, b->v) &&
                     a->prim == b->prim && a->inst == b->inst;
            if (!ok) {
                report("rt_trace_rays: packet differs from cpu", rt_cpu_isa_name(isa[k]), i,
                       &rays[i]);
                fprintf(stderr, "cpu: hit %d t %a u %a v %a prim %u inst %u\n", a->hit,
                        (double)a->t, (double)a->u, (double)a->v, a->prim, a->inst);
                fprintf(stderr, "packet: hit %d t %a u %a v %a prim %u inst %u\n", b->hit,
                        (double)b->t, (double)b->u, (double)b->v, b->prim, b->inst);
                abort();
            }
        }
    }
}

/* The kernel level: raw rays in 64-lane packets, rt_pk_trace against
 * rt_trace. valid_bits picks the lanes (a lane without a ray is never
 * valid). */
static void check_kernel(const rt_ray *rays, int n, int any_hit, rt_triangle_test test,
                         uint64_t valid_bits) {
    rt_backend_layout layout;
    double build_ms, sah;
    must(rt_renderer_layout(oracle, scene, &layout, &build_ms, &sah), "rt_renderer_layout");
    static rt_wide_bvh wide;
    static int have_wide;
    if (!have_wide) { /* the scene never changes, nor does its layout */
        must(rt_wide_build(layout.flat, rt_pk_shape(), &wide), "rt_wide_build");
        have_wide = 1;
    }
    rt_scene_view v = rt_flat_view(layout.flat);
    rt_scene_header hdr = *v.hdr;
    hdr.tri_method = (rt_u32)test;
    v.hdr = &hdr;
    for (int base = 0; base < n; base += RT_PK_LANES) {
        rt_pk_rays pr;
        memset(&pr, 0, sizeof pr);
        const int lanes = n - base < RT_PK_LANES ? n - base : RT_PK_LANES;
        for (int l = 0; l < lanes; l++) {
            rt_ray r;
            memcpy(r.org, rays[base + l].org, sizeof r.org);
            memcpy(r.dir, rays[base + l].dir, sizeof r.dir);
            r.tmin = rays[base + l].tmin;
            r.tmax = rays[base + l].tmax;
            rt_pk_set_ray(&pr, l, &r);
        }
        pr.valid = (lanes == RT_PK_LANES ? RT_PK_ALL : (((rt_pk_mask)1 << lanes) - 1)) &
                   (valid_bits ? valid_bits : RT_PK_ALL);
        rt_hit_d want[RT_PK_LANES];
        for (int l = 0; l < lanes; l++) {
            rt_ray r;
            rt_counters c = {0, 0, 0};
            rt_pk_get_ray(&pr, l, &r);
            if ((pr.valid >> l) & 1u) rt_trace(&v, &r, any_hit, &want[l], &c);
        }
        for (int k = 0; k < isa_count; k++) {
            rt_pk_hits ph;
            rt_pk_counts pc;
            memset(&pc, 0, sizeof pc);
            rt_pk_trace(isa[k], &v, &wide, &pr, any_hit, &ph, &pc);
            for (int l = 0; l < lanes; l++) {
                if (!((pr.valid >> l) & 1u)) continue;
                rt_hit_d got;
                rt_pk_get_hit(&ph, l, &got);
                const rt_hit_d *w = &want[l];
                int ok = any_hit ? (got.prim == RT_NO_HIT) == (w->prim == RT_NO_HIT)
                                 : oracle_same_hit(&got, w);
                if (!ok) {
                    report("rt_pk_trace differs from rt_trace", rt_cpu_isa_name(isa[k]), base + l,
                           &rays[base + l]);
                    fprintf(stderr, "rt_trace: t %a u %a v %a prim %u inst %u\n", (double)w->t,
                            (double)w->u, (double)w->v, w->prim, w->inst);
                    fprintf(stderr, "rt_pk_trace: t %a u %a v %a prim %u inst %u\n", (double)got.t,
                            (double)got.u, (double)got.v, got.prim, got.inst);
                    abort();
                }
            }
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (!scene) set_up();
    if (size < 1 + 8 * sizeof(float)) return 0;
    const uint8_t flags = data[0];
    rt_trace_options opt;
    memset(&opt, 0, sizeof opt);
    opt.any_hit = flags & 1;
    opt.tri_test = (rt_triangle_test)((flags >> 1) & 3);
    int n = (int)((size - 1) / (8 * sizeof(float)));
    if (n > MAX_RAYS) n = MAX_RAYS;
    rt_ray rays[MAX_RAYS];
    memcpy(rays, data + 1, (size_t)n * sizeof *rays);
    /* Valid lanes: all, or (flags bit 3) every lane but those of bit k of the
     * low bits of the first ray's tmin, so that masks vary too. */
    uint64_t valid = 0;
    if (flags & 8) {
        uint32_t bits;
        memcpy(&bits, &rays[0].tmin, sizeof bits);
        valid = ~(uint64_t)(bits * 0x9E3779B97F4A7C15ull) | 1u;
    }
    check_api(rays, n, &opt, (flags >> 4) & 1);
    check_kernel(rays, n, opt.any_hit, opt.tri_test, valid);
    return 0;
}
