/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_packet.c - the packet path renders bit-identical images to the
 * scalar oracle on every built-in scene (memcmp of the float framebuffers),
 * for the image (Whitted and direct-only) and the depth, primitive, instance
 * and normal AOVs, with every instruction-set build of the packet tracer the
 * CPU runs; the oracle's image does not depend on the thread count. Also
 * runs under qemu-aarch64, where the packet tracer is NEON.
 *
 * rt_pk_trace itself is held to rt_trace lane by lane for packets that mix
 * valid rays with any ray the API lets through: NaN and infinite origins,
 * directions and range ends, zero directions, empty and inverted ranges,
 * tmax = -inf, in every lane position (check_odd_lanes); on the built-in
 * scenes and on a finely tessellated surface far from the origin hit at tiny
 * t (check_far_surface).
 *
 * All of it runs twice: with BVH meshes and with every mesh a kd-tree
 * (--accel kd: the packets' kd traversal, cpu_ref/packet_kd.h, against the
 * oracle's rt_kd_trace_mesh), and packets of random rays that point every
 * way (check_random_packets) join the odd and the nasty ones. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "cpu_render.h"
#include "oracle_util.h"
#include "rt_fp_mode.h"
#include "packet_trace.h"
#include "layout/flat.h"
#include "scene/scene.h"
#include "rt.h"
#include "scene/scene_builtin.h"

/* The instruction-set build under test, and its packet renderers. */
static const rt_cpu_isa *cur_isa;
static rt_renderer *packet_renderer[2]; /* 3 threads, 2 threads */

/* "cpu" on threads threads, or "packet" of the build under test. */
static rt_renderer *renderer_for(const char *backend, int threads) {
    if (strcmp(backend, "packet") == 0) return packet_renderer[threads == 3 ? 0 : 1];
    return test_renderer(backend, threads);
}

static int render(rt_scene *s, const char *backend, rt_aov aov, int threads, rt_framebuffer *fb,
                  rt_render_stats *st) {
    rt_render_options o = rt_render_options_default();
    o.aov = aov;
    o.stats = st;
    rt_renderer *r = renderer_for(backend, threads);
    rt_status status = rt_render(r, s, &o, fb);
    CHECK_MSG(status == RT_OK, "%s: %s", backend, rt_renderer_error(r));
    return status == RT_OK;
}

static int render_direct(rt_scene *s, const char *backend, rt_framebuffer *fb) {
    rt_render_options o = rt_render_options_default();
    o.direct_only = 1;
    rt_renderer *r = renderer_for(backend, 2);
    rt_status status = rt_render(r, s, &o, fb);
    CHECK_MSG(status == RT_OK, "%s: %s", backend, rt_renderer_error(r));
    return status == RT_OK;
}

static int same(const rt_framebuffer *a, const rt_framebuffer *b) {
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           memcmp(a->pixels, b->pixels,
                  sizeof(float) * (size_t)a->width * a->height * a->channels) == 0;
}

/* Every mesh of s as a kd-tree (accel RT_ACCEL_KD) or as it is. */
static void set_accel(rt_scene *s, rt_accel accel) {
    if (accel != RT_ACCEL_BVH) CHECK(rt_scene_set_static_accel(s, accel) == RT_OK);
}

/* Every image and AOV of every built-in scene, Whitted and direct-only, on
 * the packet path's current instruction-set build, with the meshes' structure
 * accel. */
static void check_scenes(const char *isa, rt_accel accel) {
    const rt_aov aovs[] = {RT_AOV_NONE, RT_AOV_DEPTH, RT_AOV_PRIMID, RT_AOV_INSTID, RT_AOV_NORMAL};
    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        const char *name = rt_builtin_scene_names[i];
        rt_scene *s = test_builtin_scene(
            name, 193, 109); /* odd sizes: packets at the right and bottom edges */
        if (!s) continue;
        set_accel(s, accel);
        for (size_t a = 0; a < sizeof aovs / sizeof aovs[0]; a++) {
            rt_framebuffer c, p;
            rt_render_stats sc, sp;
            if (!render(s, "cpu", aovs[a], 2, &c, &sc)) continue;
            if (render(s, "packet", aovs[a], 3, &p, &sp)) {
                CHECK_MSG(same(&c, &p), "%s: packet (%s, %s) differs from cpu (aov %d)", name, isa,
                          rt_accel_name(accel), (int)aovs[a]);
                if (aovs[a] == RT_AOV_NONE) {
                    CHECK(sp.packets ==
                          (uint64_t)((193 + RT_PACKET_TILE_W - 1) / RT_PACKET_TILE_W) *
                              ((109 + RT_PACKET_TILE_H - 1) / RT_PACKET_TILE_H));
                    CHECK(sp.packet_box_tests > 0 && sp.rays == sc.rays);
                    CHECK(sc.primary_rays == 193u * 109u && sp.primary_rays == sc.primary_rays);
                }
                rt_framebuffer_free(&p);
            }
            if (aovs[a] == RT_AOV_NONE && render(s, "cpu", aovs[a], 1, &p, NULL)) {
                CHECK_MSG(same(&c, &p), "%s: the image depends on the thread count", name);
                rt_framebuffer_free(&p);
            }
            rt_framebuffer_free(&c);
        }
        /* The benchmark set-up: primary plus shadow rays only. */
        rt_framebuffer c, p;
        if (render_direct(s, "cpu", &c)) {
            if (render_direct(s, "packet", &p)) {
                CHECK_MSG(same(&c, &p), "%s: direct-only packet (%s, %s) differs from cpu", name,
                          isa, rt_accel_name(accel));
                rt_framebuffer_free(&p);
            }
            rt_framebuffer_free(&c);
        }
        rt_scene_destroy(s);
    }
}

/* Every lane of the packet against rt_trace on the same ray, closest hit and
 * any hit; returns the number of lanes that differ. */
static int compare_packet(const rt_scene_view *v, const rt_wide_bvh *w, const rt_pk_rays *rays,
                          const char *what) {
    int bad = 0;
    for (int any = 0; any < 2; any++) {
        rt_pk_hits ph;
        rt_pk_counts pc;
        memset(&pc, 0, sizeof pc);
        rt_pk_trace(cur_isa, v, w, rays, any, &ph, &pc);
        for (int l = 0; l < RT_PK_LANES; l++) {
            if (!((rays->valid >> l) & 1u)) continue;
            rt_ray r;
            rt_hit_d want, got;
            rt_counters c = {0, 0, 0};
            rt_pk_get_ray(rays, l, &r);
            rt_trace(v, &r, any, &want, &c);
            rt_pk_get_hit(&ph, l, &got);
            int ok = any ? (got.prim == RT_NO_HIT) == (want.prim == RT_NO_HIT)
                         : oracle_same_hit(&got, &want);
            if (!ok && bad++ < 5)
                fprintf(stderr,
                        "%s (%s, %s): lane %d org %g %g %g dir %g %g %g t [%g, %g]: packet t %.9g "
                        "prim %d, cpu t %.9g prim %d\n",
                        what, rt_cpu_isa_name(cur_isa), any ? "any hit" : "closest", l,
                        (double)r.org[0], (double)r.org[1], (double)r.org[2], (double)r.dir[0],
                        (double)r.dir[1], (double)r.dir[2], (double)r.tmin, (double)r.tmax,
                        (double)got.t, (int)got.prim, (double)want.t, (int)want.prim);
        }
    }
    return bad;
}

/* Ray k of the odd kinds: each breaks some packet-wide bound. */
static void odd_ray(int k, const rt_ray *valid, rt_ray *r) {
    const float nan = NAN, inf = INFINITY;
    *r = *valid;
    switch (k % 14) {
    case 0:
        r->tmax = -inf;
        break;
    case 1:
        r->tmax = nan;
        break;
    case 2:
        r->tmin = nan;
        break;
    case 3:
        r->tmin = inf;
        break;
    case 4:
        r->tmin = -inf;
        break;
    case 5:
        r->tmin = 2.0f, r->tmax = 1.0f;
        break; /* inverted */
    case 6:
        r->tmin = r->tmax = 0.5f;
        break; /* empty but for t = 0.5 */
    case 7:
        r->dir[0] = r->dir[1] = r->dir[2] = nan;
        break;
    case 8:
        r->org[1] = nan;
        break;
    case 9:
        r->dir[2] = inf;
        break;
    case 10:
        r->org[0] = -inf;
        break;
    case 11:
        r->dir[0] = r->dir[1] = r->dir[2] = 0.0f;
        break;
    case 12:
        r->dir[0] = 0.0f, r->dir[1] = -0.0f;
        break; /* on the slab planes */
    default:
        r->tmin = -inf, r->tmax = -inf;
        break;
    }
}

/* Packets of coherent valid rays (one origin, directions of one sign per
 * axis: the packet-wide interval test runs) with 1, 2 or many odd lanes at
 * every position, lane 0 included. */
static void check_odd_lanes(const rt_scene_view *v, const rt_wide_bvh *w, const char *name) {
    int bad = 0, packets = 0;
    oracle_rng = 777;
    for (int pkt = 0; pkt < 48 && !bad; pkt++) {
        rt_pk_rays rays;
        rt_ray base;
        rt_camera_ray(v->hdr, (int)(oracle_rnd() * (float)v->hdr->width),
                      (int)(oracle_rnd() * (float)v->hdr->height), &base);
        for (int l = 0; l < RT_PK_LANES; l++) {
            rt_ray r = base;
            for (int k = 0; k < 3; k++) r.dir[k] += 0.01f * (oracle_rnd() - 0.5f);
            if (pkt % 3 == 1) /* secondary-like: different origins */
                for (int k = 0; k < 3; k++) r.org[k] += 0.2f * oracle_rnd();
            rt_pk_set_ray(&rays, l, &r);
        }
        rays.valid = pkt % 4 == 3 ? RT_PK_ALL & ~(rt_pk_mask)0x5 : RT_PK_ALL;
        const int odd = pkt % 5 == 4 ? RT_PK_LANES / 2 : 1 + pkt % 2;
        for (int i = 0; i < odd; i++) {
            int l = (pkt * 7 + i * 13) % RT_PK_LANES;
            if (i == 0) l = (pkt / 2) % 8 * 8 % RT_PK_LANES; /* lane 0 and each vector's first */
            rt_ray r, o;
            rt_pk_get_ray(&rays, l, &r);
            odd_ray(pkt + i, &r, &o);
            rt_pk_set_ray(&rays, l, &o);
            rays.valid |= (rt_pk_mask)1 << l;
        }
        bad += compare_packet(v, w, &rays, name);
        packets++;
    }
    CHECK_MSG(bad == 0, "%s: %d lanes differ from cpu in packets with odd lanes (%s)", name, bad,
              rt_cpu_isa_name(cur_isa));
    CHECK(packets > 0);
}

/* Packets of nasty rays (oracle_vertex_ray: through vertices, tiny and
 * denormal directions, ranges below zero), every triangle test, with
 * denormals kept and flushed: a hit whose t lies outside its triangle's box
 * must be refused by the packets exactly as by the oracle, whose trees and
 * order differ (rt_hit_accepted). */
static void check_vertex_rays(const rt_flat *flat, const rt_wide_bvh *w, const float lo[3],
                              const float hi[3], const char *name) {
    for (int flush = 0; flush < 2; flush++) {
        if (flush && !rt_fp_can_flush()) {
            printf("%s: flush-to-zero not settable on this CPU, flushed rays not tested\n", name);
            break;
        }
        const rt_fp_saved saved = rt_fp_set_flush(flush);
        int bad = 0;
        for (rt_u32 m = 0; m < 4; m++) {
            rt_flat f = *flat;
            f.hdr.tri_method = m;
            rt_scene_view v = rt_flat_view(&f);
            oracle_rng = 4242 + m;
            for (int pkt = 0; pkt < 24; pkt++) {
                rt_pk_rays rays;
                for (int l = 0; l < RT_PK_LANES; l++) {
                    rt_ray r;
                    oracle_vertex_ray(&v, lo, hi, &r);
                    rt_pk_set_ray(&rays, l, &r);
                }
                rays.valid = RT_PK_ALL;
                bad += compare_packet(&v, w, &rays, name);
            }
        }
        rt_fp_restore(saved);
        CHECK_MSG(bad == 0, "%s: %d lanes of vertex rays differ from cpu (%s, %s)", name, bad,
                  rt_cpu_isa_name(cur_isa), flush ? "flush" : "preserve");
    }
}

/* Packets of random rays (oracle_ray): camera rays through random pixels in
 * some packets, rays between random points of the grown bounds in the
 * others (every lane its own origin and direction signs), some with short
 * ranges or tmin > 0. */
static void check_random_packets(const rt_scene_view *v, const rt_wide_bvh *w, const float lo[3],
                                 const float hi[3], const char *name) {
    int bad = 0;
    oracle_rng = 9001;
    for (int pkt = 0; pkt < 32; pkt++) {
        rt_pk_rays rays;
        for (int l = 0; l < RT_PK_LANES; l++) {
            rt_ray r;
            oracle_ray(v->hdr, lo, hi, pkt % 4 == 0 ? 2 * l : pkt % 4 == 1 ? l : 2 * l + 1, &r);
            rt_pk_set_ray(&rays, l, &r);
        }
        rays.valid = pkt % 3 == 2 ? RT_PK_ALL & ~(rt_pk_mask)0x90 : RT_PK_ALL;
        bad += compare_packet(v, w, &rays, name);
    }
    CHECK_MSG(bad == 0, "%s: %d lanes of random rays differ from cpu (%s)", name, bad,
              rt_cpu_isa_name(cur_isa));
}

/* Instances of the layout with a kd-tree mesh. */
static int kd_instances(const rt_scene_view *v) {
    int n = 0;
    for (rt_u32 i = 0; i < v->hdr->instance_count; i++)
        n += (v->instances[i].flags & RT_INST_KD) != 0;
    return n;
}

static void check_odd_lanes_scene(rt_scene *s, const char *name, rt_accel accel) {
    set_accel(s, accel);
    const rt_flat *flat = test_layout(s, 1);
    if (!flat) return;
    rt_wide_bvh w;
    CHECK(rt_wide_build(flat, rt_pk_shape(), &w) == RT_OK);
    rt_scene_view v = rt_flat_view(flat);
    /* The kd pass must trace kd meshes (and the BVH pass none). */
    CHECK_MSG((kd_instances(&v) > 0) == (accel != RT_ACCEL_BVH), "%s: %d kd instances with %s",
              name, kd_instances(&v), rt_accel_name(accel));
    check_odd_lanes(&v, &w, name);
    float lo[3], hi[3];
    rt_scene_bounds(s, lo, hi);
    check_random_packets(&v, &w, lo, hi, name);
    check_vertex_rays(flat, &w, lo, hi, name);
    rt_wide_free(&w);
}

/* A finely tessellated bumpy surface about 1500 units from the origin, and
 * packets of bounce-like rays that leave it from nearby points at tiny t
 * (the next triangle a fraction of a cell away). */
static void check_far_surface(rt_accel accel) {
    enum { CELLS = 96 };
    const float cell = 0.25f; /* test_far_terrain's */
    float *pos;
    rt_scene *s = test_far_terrain(CELLS, &pos);
    if (!s) return;
    oracle_rng = 4242;
    set_accel(s, accel);
    const rt_flat *flat = test_layout(s, 1);
    if (!flat) {
        rt_scene_destroy(s);
        free(pos);
        return;
    }
    rt_wide_bvh w;
    CHECK(rt_wide_build(flat, rt_pk_shape(), &w) == RT_OK);
    rt_scene_view v = rt_flat_view(flat);
    CHECK((kd_instances(&v) > 0) == (accel != RT_ACCEL_BVH));
    int bad = 0, tiny = 0;
    for (int pkt = 0; pkt < 400; pkt++) {
        rt_pk_rays rays;
        /* A point of a random cell, and a shared direction nearly along the
         * surface (one sign per axis for the whole packet), downwards. */
        const int ci = 2 + (int)(oracle_rnd() * (CELLS - 4)),
                  cj = 2 + (int)(oracle_rnd() * (CELLS - 4));
        float d0[3] = {oracle_rnd() - 0.5f, -0.02f - 0.3f * oracle_rnd(), oracle_rnd() - 0.5f};
        for (int l = 0; l < RT_PK_LANES; l++) {
            const float fu = oracle_rnd(), fv = oracle_rnd();
            const float *p00 = pos + 3 * (cj * (CELLS + 1) + ci);
            const float *p11 = pos + 3 * ((cj + 1) * (CELLS + 1) + ci + 1);
            rt_ray r;
            for (int k = 0; k < 3; k++) {
                r.org[k] = p00[k] + (fu > fv ? fu : fv) * 0.5f * (p11[k] - p00[k]);
                r.dir[k] = d0[k] * (1.0f + 0.02f * (oracle_rnd() - 0.5f));
            }
            r.org[0] = p00[0] + fu * cell, r.org[2] = p00[2] + fv * cell;
            r.org[1] += 0.002f + 0.01f * oracle_rnd(); /* just above: t is tiny */
            r.tmin = 0.0f;
            r.tmax = pkt % 7 == 6 && l == 0 ? -INFINITY : INFINITY;
            rt_pk_set_ray(&rays, l, &r);
        }
        rays.valid = RT_PK_ALL;
        bad += compare_packet(&v, &w, &rays, "far surface");
        rt_pk_hits ph;
        rt_pk_counts pc;
        memset(&pc, 0, sizeof pc);
        rt_pk_trace(cur_isa, &v, &w, &rays, 0, &ph, &pc);
        for (int l = 0; l < RT_PK_LANES; l++) tiny += ph.prim[l] != RT_NO_HIT && ph.t[l] < 0.1f;
    }
    CHECK_MSG(bad == 0, "far surface: %d lanes differ from cpu (%s)", bad,
              rt_cpu_isa_name(cur_isa));
    CHECK_MSG(tiny > 1000, "far surface: only %d hits at t < 0.1", tiny);
    check_odd_lanes(&v, &w, "far surface");
    rt_wide_free(&w);
    rt_scene_destroy(s);
    free(pos);
}

int main(void) {
    /* Each instruction-set build of the packet tracer this CPU runs. */
    int tested = 0;
    for (int k = 0; rt_cpu_isa_at(k); k++) {
        if (!rt_cpu_isa_find(rt_cpu_isa_at(k))) {
            printf("packet build %s: not run, this CPU lacks it\n", rt_cpu_isa_at(k));
            continue;
        }
        rt_renderer_options ro = rt_renderer_options_default();
        ro.backend = "packet";
        ro.packet_isa = rt_cpu_isa_at(k);
        cur_isa = rt_cpu_isa_find(ro.packet_isa);
        rt_error err;
        for (int t = 0; t < 2; t++) {
            ro.threads = t == 0 ? 3 : 2;
            packet_renderer[t] = test_renderer_with(&ro, &err);
            CHECK_MSG(packet_renderer[t] != NULL, "packet %s: %s", ro.packet_isa, err.message);
        }
        if (!packet_renderer[0] || !packet_renderer[1]) continue;
        const rt_accel accels[] = {RT_ACCEL_BVH, RT_ACCEL_KD};
        for (int a = 0; a < 2; a++) {
            printf("packet build %s, %s meshes\n", rt_cpu_isa_at(k), rt_accel_name(accels[a]));
            check_scenes(rt_cpu_isa_at(k), accels[a]);
            for (int i = 0; rt_builtin_scene_names[i]; i++) {
                rt_scene *s = test_builtin_scene(rt_builtin_scene_names[i], 64, 48);
                if (!s) continue;
                check_odd_lanes_scene(s, rt_builtin_scene_names[i], accels[a]);
                rt_scene_destroy(s);
            }
            check_far_surface(accels[a]);
        }
        tested++;
    }
    CHECK(tested > 0);
    /* An unknown backend or instruction set is refused with a clear message,
     * and so is a device for a CPU backend. */
    rt_renderer_options o = rt_renderer_options_default();
    rt_renderer *r = NULL;
    rt_error err;
    o.backend = "warp";
    CHECK(rt_renderer_create(&o, &r, &err) == RT_ERROR_UNSUPPORTED && r == NULL);
    CHECK_CONTAINS(err.message, "backend 'warp'");
    o.backend = "packet";
    o.packet_isa = "mmx";
    CHECK(rt_renderer_create(&o, &r, &err) == RT_ERROR_UNSUPPORTED && r == NULL);
    CHECK_CONTAINS(err.message, "'mmx'");
    o.backend = "cpu:1";
    o.packet_isa = NULL;
    CHECK(rt_renderer_create(&o, &r, &err) == RT_ERROR_UNSUPPORTED && r == NULL);
    CHECK_CONTAINS(err.message, "takes no device");
    /* A failed switch keeps the backend. */
    o.backend = "packet";
    CHECK(rt_renderer_create(&o, &r, &err) == RT_OK);
    CHECK(rt_renderer_set_backend(r, "warp") == RT_ERROR_UNSUPPORTED);
    CHECK_CONTAINS(rt_renderer_error(r), "backend 'warp'");
    CHECK(strcmp(rt_renderer_backend(r), "packet") == 0);
    rt_renderer_destroy(r);
    return TEST_END();
}
