/* SPDX-License-Identifier: Apache-2.0 */
/* test_ray_mask.c - ray masks (rt_object_set_mask, rt_trace_options.ray_masks)
 * and ray ids (rt_trace_options.ray_ids, rt_hit.ray_id), on a scene of twelve
 * objects (boxes, triangle soups, a kd-tree mesh; moved, turned and scaled
 * instances) whose masks are 0x1, 0x2, 0x4, 0x8, 0x10 (twice each),
 * 0xffffffff and 0:
 * (a) on the oracle, every closest hit of 4,096 rays (coherent groups of 64
 *     and random rays) with random masks (0 and 0xffffffff among them)
 *     equals, bit for bit, the hit of the same ray on the scene built
 *     without the objects the ray's mask skips (instance ids mapped), and
 *     every any-hit answer says hit exactly when that reference does;
 * (b) every backend here (cpu, packet with each instruction set this CPU
 *     runs and each packet path, opencl; vulkan with the argument vulkan)
 *     gives the oracle's hits bit for bit (rt_hit as a whole: t, u, v, prim,
 *     inst, hit, normal, mesh, ray_id), closest and any hit (the packet
 *     backend's any-hit answers name no triangle: hit and ray_id there);
 * (c) ray_id is the caller's id, or the ray's index without ids, hit or
 *     miss;
 * (d) a render with one object's mask 0 equals the render of the scene
 *     built without it (image and depth, bits), also when the mask is set
 *     after a first frame on the same renderer.
 * (e) a scene file's object masks ("mask") load and survive rt_scene_save_json.
 * The device backends skip with the reason when there is no device; the
 * program exits 77 when asked for vulkan and none traced. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "cpu_isa.h"
#include "rt.h"

enum { OBJECTS = 12, RAYS = 4096, GROUP = 64, COHERENT = 2048 };

/* Object o's mask: one of five bits for the first ten, then every bit,
 * then none. */
static uint32_t object_mask(int o) {
    if (o < 10) return 1u << (o % 5);
    return o == 10 ? 0xffffffffu : 0u;
}

static uint32_t rng_state = 12345u;
static uint32_t rnd(void) {
    uint32_t x = rng_state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return rng_state = x;
}
static float rndf(float lo, float hi) {
    return lo + (hi - lo) * (float)(rnd() >> 8) * (1.0f / 16777216.0f);
}

/* A unit box about the origin. */
static void add_box(rt_scene *s, uint32_t mesh) {
    float p[24];
    for (int i = 0; i < 8; i++) {
        p[3 * i] = (i & 1) ? 0.5f : -0.5f;
        p[3 * i + 1] = (i & 2) ? 0.5f : -0.5f;
        p[3 * i + 2] = (i & 4) ? 0.5f : -0.5f;
    }
    static const uint32_t idx[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                     2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    CHECK(rt_mesh_add_triangles(s, mesh, p, NULL, 8, idx, 12) == RT_OK);
}

/* tris random triangles in the unit cube about the origin (seeded, so every
 * build of the scene has the same). */
static void add_soup(rt_scene *s, uint32_t mesh, uint32_t seed, int tris) {
    uint32_t keep = rng_state;
    rng_state = seed;
    float *p = malloc(sizeof(float) * 9 * (size_t)tris);
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * (size_t)tris);
    for (int t = 0; t < tris && p && idx; t++) {
        float c[3] = {rndf(-0.4f, 0.4f), rndf(-0.4f, 0.4f), rndf(-0.4f, 0.4f)};
        for (int v = 0; v < 3; v++) {
            for (int k = 0; k < 3; k++) p[9 * t + 3 * v + k] = c[k] + rndf(-0.25f, 0.25f);
            idx[3 * t + v] = (uint32_t)(3 * t + v);
        }
    }
    if (p && idx)
        CHECK(rt_mesh_add_triangles(s, mesh, p, NULL, (uint32_t)(3 * tris), idx, (uint32_t)tris) ==
              RT_OK);
    free(p);
    free(idx);
    rng_state = keep;
}

/* The scene: the objects o with keep(o) (all: keep NULL), each with its
 * mask when masks is set. The meshes are always the same three (a box, a
 * soup, a soup with a kd-tree), so mesh ids agree between builds; *ids gets
 * each object's id in the original scene. */
static rt_scene *build(uint32_t ray_mask, int filter, int skip, int masks, uint32_t ids[OBJECTS],
                       uint32_t *count) {
    rt_scene *s = NULL;
    if (rt_scene_create(&s) != RT_OK) return NULL;
    rt_material mats[3] = {rt_material_default(), rt_material_default(), rt_material_default()};
    mats[0].color[0] = 0.9f, mats[0].color[1] = 0.5f, mats[0].color[2] = 0.3f;
    mats[0].ambient = 0.2f, mats[0].diffuse = 0.8f, mats[0].specular = 0.3f;
    mats[0].shininess = 16;
    mats[1].reflectivity = 0.6f, mats[1].diffuse = 0.4f, mats[1].ambient = 0.1f;
    mats[2].transparency = 0.7f, mats[2].ior = 1.3f, mats[2].diffuse = 0.2f;
    uint32_t mat[3], mesh[3];
    for (int i = 0; i < 3; i++) CHECK(rt_material_add(s, &mats[i], &mat[i]) == RT_OK);
    for (int i = 0; i < 3; i++) CHECK(rt_mesh_create(s, &mesh[i]) == RT_OK);
    add_box(s, mesh[0]);
    add_soup(s, mesh[1], 777u, 60);
    add_soup(s, mesh[2], 4242u, 80);
    CHECK(rt_mesh_set_accel(s, mesh[2], RT_ACCEL_KD) == RT_OK);
    *count = 0;
    for (int o = 0; o < OBJECTS; o++) {
        if (o == skip) continue;
        if (filter && !(ray_mask & object_mask(o))) continue;
        uint32_t id;
        CHECK(rt_object_create(s, mat[o % 3], &id) == RT_OK);
        CHECK(rt_object_add_mesh(s, id, mesh[o % 3]) == RT_OK);
        if (o != 0) { /* object 0 keeps the identity */
            const float x = (float)(o % 4) * 1.3f - 1.95f, y = (float)(o / 4) * 1.2f - 1.2f;
            const float z = (o & 1) ? 0.4f : -0.3f, c = 0.8f, sn = 0.6f, sc = (o & 2) ? 0.8f : 1.1f;
            float m[16] = {sc, 0, 0, x, 0, sc, 0, y, 0, 0, sc, z, 0, 0, 0, 1};
            if (o % 3 == 1) { /* turned about y */
                m[0] = c * sc, m[2] = sn * sc, m[8] = -sn * sc, m[10] = c * sc;
            }
            CHECK(rt_object_transform(s, id, m) == RT_OK);
        }
        if (masks) CHECK(rt_object_set_mask(s, id, object_mask(o)) == RT_OK);
        ids[(*count)++] = (uint32_t)o;
    }
    const float light[3] = {2.0f, 4.0f, 6.0f}, white[3] = {1.0f, 1.0f, 1.0f};
    uint32_t lid;
    CHECK(rt_light_add(s, light, white, &lid) == RT_OK);
    rt_camera cam = {{0.3f, 0.5f, 7.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 50.0f, 64, 48};
    CHECK(rt_camera_set(s, &cam) == RT_OK);
    CHECK(rt_scene_commit(s) == RT_OK);
    return s;
}

static rt_ray rays[RAYS];
static uint32_t ray_masks[RAYS], ray_ids[RAYS];

static void make_rays(void) {
    for (int i = 0; i < RAYS; i++) {
        rt_ray *r = &rays[i];
        if (i < COHERENT) {
            /* Groups of 64 from one origin in close directions: packets. */
            const int g = i / GROUP;
            uint32_t keep = rng_state;
            rng_state = 99u + (uint32_t)g;
            float o[3] = {rndf(-3, 3), rndf(-2, 2), rndf(5, 8)};
            float to[3] = {rndf(-1.5f, 1.5f), rndf(-1.2f, 1.2f), 0.0f};
            rng_state = keep;
            for (int k = 0; k < 3; k++) {
                r->org[k] = o[k];
                r->dir[k] = to[k] - o[k] + rndf(-0.3f, 0.3f);
            }
        } else {
            for (int k = 0; k < 3; k++) {
                r->org[k] = rndf(-3.5f, 3.5f);
                float to = rndf(-2.0f, 2.0f);
                r->dir[k] = (rnd() & 7) ? to - r->org[k] : rndf(-1, 1);
            }
        }
        r->tmin = 0.0f;
        r->tmax = (rnd() & 15) ? INFINITY : rndf(1.0f, 6.0f);
        const uint32_t pick = rnd() % 10;
        if (pick == 0)
            ray_masks[i] = 0u;
        else if (pick == 1)
            ray_masks[i] = 0xffffffffu;
        else
            ray_masks[i] = (rnd() & 31u) | ((rnd() & 1u) ? rnd() & ~31u : 0u);
        ray_ids[i] = rnd();
    }
}

static int same_hit(const rt_hit *a, const rt_hit *b) {
    return memcmp(a, b, sizeof *a) == 0;
}

static void print_hit(const char *who, const rt_hit *h) {
    fprintf(stderr,
            "  %s: hit %d t %.9g u %.9g v %.9g prim %u inst %u normal %.9g %.9g %.9g mesh %u id "
            "%u\n",
            who, h->hit, (double)h->t, (double)h->u, (double)h->v, h->prim, h->inst,
            (double)h->normal[0], (double)h->normal[1], (double)h->normal[2], h->mesh, h->ray_id);
}

/* Closest and any hits of the cpu backend with masks and ids: on the
 * scene of twelve objects, and on the scene of one (RT_SCENE_SINGLE). */
static rt_hit oracle_many[2][RAYS], oracle_single[2][RAYS];
static rt_hit (*oracle)[RAYS] = oracle_many;

static rt_status trace(rt_renderer *r, rt_scene *s, int any, const uint32_t *masks,
                       const uint32_t *ids, rt_trace_path path, rt_hit *out,
                       rt_trace_stats *stats) {
    rt_trace_options q;
    memset(&q, 0, sizeof q);
    q.any_hit = any;
    q.ray_masks = masks;
    q.ray_ids = ids;
    q.packet_path = path;
    q.stats = stats;
    return rt_trace_rays(r, s, rays, RAYS, out, &q);
}

/* (a): the oracle against the scenes without the skipped objects. */
static void check_reference(rt_renderer *cpu, rt_scene *masked) {
    for (int any = 0; any <= 1; any++)
        CHECK(trace(cpu, masked, any, ray_masks, ray_ids, RT_TRACE_PATH_AUTO, oracle[any], NULL) ==
              RT_OK);
    /* The rays by the objects their mask keeps: bits 0..4, and "some bit"
     * for object 10. */
    rt_hit *ref = malloc(sizeof(rt_hit) * RAYS);
    int done[64] = {0}, hits = 0, masked_out = 0, differ = 0;
    static rt_hit unmasked[RAYS];
    CHECK(trace(cpu, masked, 0, NULL, NULL, RT_TRACE_PATH_AUTO, unmasked, NULL) == RT_OK);
    for (int i = 0; i < RAYS && ref; i++) {
        const uint32_t m = ray_masks[i];
        const int key = (int)(m & 31u) | (m ? 32 : 0);
        if (done[key]) continue;
        done[key] = 1;
        uint32_t ids[OBJECTS], n;
        rt_scene *s = build(m, 1, -1, 0, ids, &n);
        if (!s) continue;
        rt_renderer *fresh = test_renderer("cpu", 0);
        for (int any = 0; any <= 1 && fresh; any++) {
            CHECK(trace(fresh, s, any, NULL, NULL, RT_TRACE_PATH_AUTO, ref, NULL) == RT_OK);
            for (int j = 0; j < RAYS; j++) {
                const uint32_t mj = ray_masks[j];
                if (((int)(mj & 31u) | (mj ? 32 : 0)) != key) continue;
                rt_hit want = ref[j];
                if (want.hit) want.inst = ids[want.inst];
                want.ray_id = ray_ids[j];
                const rt_hit *got = &oracle[any][j];
                int ok =
                    any ? got->hit == want.hit && got->ray_id == want.ray_id : same_hit(got, &want);
                if (!ok && differ++ < 3) {
                    fprintf(stderr, "ray %d mask %#x (%s):\n", j, mj, any ? "any hit" : "closest");
                    print_hit("masked", got);
                    print_hit("reference", &want);
                }
                if (!any) {
                    hits += got->hit;
                    masked_out += unmasked[j].hit && !got->hit;
                    if (got->hit) CHECK(ray_masks[j] & object_mask((int)got->inst));
                }
            }
        }
        rt_scene_destroy(s);
    }
    free(ref);
    CHECK_MSG(differ == 0, "%d oracle answers differ from the scenes without the skipped objects",
              differ);
    CHECK_MSG(hits > RAYS / 4 && masked_out > RAYS / 20,
              "a weak test: %d of %d rays hit, %d hits lost to masks", hits, RAYS, masked_out);
    printf("oracle: %d of %d rays hit with masks, %d hits masked away\n", hits, RAYS, masked_out);

    /* NULL masks: every ray 0xffffffff (object 11, mask 0, is never hit). */
    static rt_hit all[RAYS];
    static uint32_t ones[RAYS];
    for (int i = 0; i < RAYS; i++) ones[i] = 0xffffffffu;
    CHECK(trace(cpu, masked, 0, ones, NULL, RT_TRACE_PATH_AUTO, all, NULL) == RT_OK);
    CHECK(memcmp(all, unmasked, sizeof all) == 0);
    int on_11 = 0;
    for (int i = 0; i < RAYS; i++) on_11 += unmasked[i].hit && unmasked[i].inst == 11;
    CHECK_EQ_INT(on_11, 0);
}

/* One box with the identity transform and mask 0x1: the layout's single
 * instance, which the traversals enter without the object BVH. */
static rt_scene *build_single(void) {
    rt_scene *s = NULL;
    if (rt_scene_create(&s) != RT_OK) return NULL;
    rt_material m = rt_material_default();
    uint32_t mat, mesh, obj, lid;
    CHECK(rt_material_add(s, &m, &mat) == RT_OK);
    CHECK(rt_mesh_create(s, &mesh) == RT_OK);
    add_box(s, mesh);
    CHECK(rt_object_create(s, mat, &obj) == RT_OK);
    CHECK(rt_object_add_mesh(s, obj, mesh) == RT_OK);
    CHECK(rt_object_set_mask(s, obj, 0x1u) == RT_OK);
    const float light[3] = {2.0f, 4.0f, 6.0f}, white[3] = {1.0f, 1.0f, 1.0f};
    CHECK(rt_light_add(s, light, white, &lid) == RT_OK);
    CHECK(rt_scene_commit(s) == RT_OK);
    return s;
}

/* (a) on the single-instance scene: a ray whose mask lacks bit 0 misses,
 * the others hit as without masks. */
static void check_single_reference(rt_renderer *cpu, rt_scene *s) {
    for (int any = 0; any <= 1; any++)
        CHECK(trace(cpu, s, any, ray_masks, ray_ids, RT_TRACE_PATH_AUTO, oracle_single[any],
                    NULL) == RT_OK);
    static rt_hit plain[2][RAYS];
    int differ = 0, hits = 0, lost = 0;
    for (int any = 0; any <= 1; any++) {
        CHECK(trace(cpu, s, any, NULL, ray_ids, RT_TRACE_PATH_AUTO, plain[any], NULL) == RT_OK);
        for (int i = 0; i < RAYS; i++) {
            rt_hit want = plain[any][i];
            if (!(ray_masks[i] & 1u)) {
                lost += !any && want.hit;
                want =
                    (rt_hit){INFINITY,           0.0f,       0.0f,      UINT32_MAX, UINT32_MAX, 0,
                             {0.0f, 0.0f, 0.0f}, UINT32_MAX, ray_ids[i]};
            }
            hits += !any && want.hit;
            differ += !same_hit(&oracle_single[any][i], &want);
        }
    }
    CHECK_MSG(differ == 0, "single instance: %d oracle answers are not the unmasked or a miss",
              differ);
    CHECK_MSG(hits > RAYS / 50 && lost > RAYS / 50,
              "single instance: a weak test (%d hits, %d lost)", hits, lost);
}

static int device_traced;

/* (b), (c): one renderer against the oracle. */
static void check_backend(const char *label, rt_renderer *r, rt_scene *s, const char *backend,
                          rt_trace_path path) {
    static rt_hit got[RAYS];
    for (int any = 0; any <= 1; any++) {
        rt_trace_stats st;
        rt_status status = trace(r, s, any, ray_masks, ray_ids, path, got, &st);
        if (status != RT_OK && strcmp(backend, "cpu") && strcmp(backend, "packet")) {
            printf("%s not tested: %s\n", label, rt_renderer_error(r));
            return;
        }
        CHECK_MSG(status == RT_OK, "%s: %s", label, rt_renderer_error(r));
        if (status != RT_OK) return;
        CHECK_MSG(!strcmp(st.backend, backend), "%s traced on %s", label, st.backend);
        const int names = !(any && !strcmp(backend, "packet"));
        int differ = 0;
        for (int i = 0; i < RAYS; i++) {
            const rt_hit *want = &oracle[any][i];
            int ok = names ? same_hit(&got[i], want)
                           : got[i].hit == want->hit && got[i].ray_id == want->ray_id;
            if (!ok && differ++ < 3) {
                fprintf(stderr, "%s ray %d mask %#x (%s):\n", label, i, ray_masks[i],
                        any ? "any hit" : "closest");
                print_hit(label, &got[i]);
                print_hit("oracle", want);
            }
        }
        CHECK_MSG(differ == 0, "%s %s: %d of %d hits differ from the oracle's", label,
                  any ? "any hit" : "closest", differ, RAYS);
        device_traced += strcmp(backend, "cpu") && strcmp(backend, "packet");
    }
    /* (c) without ids: the index, hit or miss; the hits otherwise the same. */
    {
        rt_status status = trace(r, s, 0, ray_masks, NULL, path, got, NULL);
        CHECK_MSG(status == RT_OK, "%s: %s", label, rt_renderer_error(r));
        int bad = 0;
        for (int i = 0; i < RAYS && status == RT_OK; i++) {
            rt_hit want = oracle[0][i];
            want.ray_id = (uint32_t)i;
            bad += !same_hit(&got[i], &want);
        }
        CHECK_MSG(bad == 0, "%s: %d hits without ids are not the oracle's with the index", label,
                  bad);
    }
    if (!test_failures) printf("%s: the oracle's hits, closest and any\n", label);
}

/* (d): object `hide` with mask 0 renders as the scene without it. */
static void check_render(const char *label, rt_renderer *r, const char *backend) {
    enum { HIDE = 5 };
    const int failures = test_failures;
    uint32_t ids[OBJECTS], n;
    rt_scene *with = build(0, 0, -1, 0, ids, &n);
    rt_scene *without = build(0, 0, HIDE, 0, ids, &n);
    if (!with || !without) goto done;
    for (int aov = 0; aov <= 1; aov++) {
        rt_render_options o = rt_render_options_default();
        o.aov = aov ? RT_AOV_DEPTH : RT_AOV_NONE;
        rt_render_stats st;
        o.stats = &st;
        rt_framebuffer a, b, c;
        memset(&a, 0, sizeof a), memset(&b, 0, sizeof b), memset(&c, 0, sizeof c);
        CHECK(rt_object_set_mask(with, HIDE, 0xffffffffu) == RT_OK);
        rt_status status = rt_render(r, with, &o, &a); /* a first frame with the object */
        if (status != RT_OK && strcmp(backend, "cpu") && strcmp(backend, "packet")) {
            printf("%s render not tested: %s\n", label, rt_renderer_error(r));
            goto done;
        }
        CHECK_MSG(status == RT_OK, "%s: %s", label, rt_renderer_error(r));
        if (status == RT_OK && !strcmp(backend, "opencl") && !st.exact) {
            printf("%s device '%s' does not promise exact results: render not compared\n", label,
                   st.device);
            rt_framebuffer_free(&a);
            goto done;
        }
        CHECK(rt_object_set_mask(with, HIDE, 0u) == RT_OK);
        CHECK(rt_render(r, with, &o, &b) == RT_OK);
        CHECK(rt_render(r, without, &o, &c) == RT_OK);
        CHECK_MSG(!test_same_fb(&a, &c), "%s: object %d is not in the picture: a weak test", label,
                  HIDE);
        CHECK_MSG(test_same_fb(&b, &c),
                  "%s %s: mask 0 does not render as the scene without the object", label,
                  aov ? "depth" : "image");
        rt_framebuffer_free(&a);
        rt_framebuffer_free(&b);
        rt_framebuffer_free(&c);
    }
    if (test_failures == failures)
        printf("%s: an object of mask 0 renders as the scene without it\n", label);
done:
    rt_scene_destroy(with);
    rt_scene_destroy(without);
}

static void check_api(void) {
    uint32_t ids[OBJECTS], n;
    rt_scene *s = build(0, 0, -1, 0, ids, &n);
    if (!s) return;
    rt_object_info info;
    CHECK(rt_object_describe(s, 3, &info) == RT_OK);
    CHECK(info.mask == 0xffffffffu);
    CHECK(rt_object_set_mask(s, 3, 0x10u) == RT_OK);
    CHECK(rt_object_describe(s, 3, &info) == RT_OK);
    CHECK(info.mask == 0x10u);
    CHECK(rt_object_set_mask(s, OBJECTS, 1u) == RT_ERROR_INVALID_ARGUMENT);
    CHECK(rt_object_set_mask(NULL, 0, 1u) == RT_ERROR_INVALID_ARGUMENT);
    /* Removing an object moves the masks with the objects. */
    CHECK(rt_object_remove(s, 2) == RT_OK);
    CHECK(rt_object_describe(s, 2, &info) == RT_OK);
    CHECK(info.mask == 0x10u);
    rt_scene_destroy(s);
}

/* The object masks of a scene file ("mask"): loaded, and kept by
 * rt_scene_save_json (a saved scene traces as the one it was saved from). */
static void check_json(void) {
    static const char json[] =
        "{\"meshes\": {\"t\": {\"positions\": [0,0,0, 1,0,0, 0,1,0], \"triangles\": [0,1,2]}},\n"
        " \"objects\": [{\"mesh\": \"t\", \"mask\": 0}, {\"mesh\": \"t\", \"mask\": 4294967295},\n"
        "             {\"mesh\": \"t\", \"mask\": 5}, {\"mesh\": \"t\"}]}\n";
    static const uint32_t want[4] = {0u, 0xffffffffu, 5u, 0xffffffffu};
    const char *path = test_write_temp("masks.json", json);
    rt_scene *a = NULL, *b = NULL;
    rt_error err;
    CHECK_MSG(rt_scene_load(path, &a, &err) == RT_OK, "%s", err.message);
    if (!a) return;
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", path);
    *strrchr(dir, '/') = '\0';
    CHECK_MSG(rt_scene_save_json(a, dir, "masks_saved", &err) == RT_OK, "%s", err.message);
    char saved[4200];
    snprintf(saved, sizeof saved, "%s/masks_saved.json", dir);
    CHECK_MSG(rt_scene_load(saved, &b, &err) == RT_OK, "%s: %s", saved, err.message);
    for (uint32_t i = 0; i < 4; i++) {
        rt_object_info ia, ib;
        CHECK(rt_object_describe(a, i, &ia) == RT_OK);
        CHECK_MSG(ia.mask == want[i], "object %u: mask %#x loaded, %#x in the file", i, ia.mask,
                  want[i]);
        if (b && rt_object_describe(b, i, &ib) == RT_OK)
            CHECK_MSG(ib.mask == want[i], "object %u: mask %#x after saving, %#x before", i,
                      ib.mask, want[i]);
    }
    rt_scene_destroy(a);
    rt_scene_destroy(b);
}

static rt_renderer *make(const char *backend, const char *isa, rt_error *err) {
    rt_renderer_options ro = rt_renderer_options_default();
    ro.backend = backend;
    ro.packet_isa = isa;
    return test_renderer_with(&ro, err);
}

/* check_backend on both scenes. */
static void check_scenes(const char *label, rt_renderer *r, rt_scene *many, rt_scene *single,
                         const char *backend, rt_trace_path path) {
    char one[96];
    snprintf(one, sizeof one, "%s, single instance", label);
    oracle = oracle_many;
    check_backend(label, r, many, backend, path);
    oracle = oracle_single;
    check_backend(one, r, single, backend, path);
    oracle = oracle_many;
}

static void device(const char *backend, rt_scene *s, rt_scene *single) {
    rt_error err;
    rt_renderer *r = make(backend, NULL, &err);
    if (!r) {
        printf("%s not tested: %s\n", backend, err.message);
        return;
    }
    check_scenes(backend, r, s, single, backend, RT_TRACE_PATH_AUTO);
    check_render(backend, r, backend);
}

int main(int argc, char **argv) {
    const int only_vulkan = argc > 1 && !strcmp(argv[1], "vulkan");
    make_rays();
    uint32_t ids[OBJECTS], n;
    rt_scene *s = build(0, 0, -1, 1, ids, &n);
    rt_scene *single = build_single();
    rt_renderer *cpu = test_renderer("cpu", 0);
    if (!s || !single || !cpu) return TEST_END();
    check_reference(cpu, s);
    check_single_reference(cpu, single);
    if (only_vulkan) {
        device("vulkan", s, single);
        rt_scene_destroy(s);
        rt_scene_destroy(single);
        if (!device_traced) test_skip("no Vulkan device traced the rays (said above)");
        return TEST_END();
    }
    check_api();
    check_json();
    check_scenes("cpu", cpu, s, single, "cpu", RT_TRACE_PATH_AUTO);
    check_render("cpu", cpu, "cpu");
    static const rt_trace_path paths[] = {RT_TRACE_PATH_AUTO, RT_TRACE_PATH_PACKETS,
                                          RT_TRACE_PATH_SINGLE};
    static const char *const path_names[] = {"auto", "packets", "single"};
    for (int k = 0; rt_cpu_isa_at(k); k++) {
        const char *isa = rt_cpu_isa_at(k);
        if (!rt_cpu_isa_find(isa)) {
            printf("packet build %s: not run, this CPU lacks it\n", isa);
            continue;
        }
        rt_error err;
        rt_renderer *r = make("packet", isa, &err);
        CHECK_MSG(r != NULL, "packet %s: %s", isa, err.message);
        if (!r) continue;
        for (int p = 0; p < 3; p++) {
            char label[64];
            snprintf(label, sizeof label, "packet %s, %s", isa, path_names[p]);
            check_scenes(label, r, s, single, "packet", paths[p]);
        }
        char label[64];
        snprintf(label, sizeof label, "packet %s", isa);
        check_render(label, r, "packet");
    }
    device("opencl", s, single);
    rt_scene_destroy(s);
    rt_scene_destroy(single);
    return TEST_END();
}
