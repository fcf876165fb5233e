/* SPDX-License-Identifier: Apache-2.0 */
/* bench_animate.c - the keyframe benchmark (bench_animate.h).
 *
 * What is timed, per frame k >= 1 (frame 0 builds everything and is left
 * out): ours, rt_render whole (the mesh BVH updates by the policy, the
 * object BVH, the layout rewritten in place, the packet backend's wide BVHs,
 * then primary and shadow rays, one light); its "update" is the mesh BVH
 * updates the renderer reports. Embree: its update (rtcCommitGeometry of
 * what changed and rtcCommitScene) plus copying the changed vertices into
 * its buffers plus its frame (embree_trace.c: the same rays and shading,
 * its widest native packets). Setting the scene's time (the blend of two
 * keyframes, the scene's work and not the renderer's) and, for Embree,
 * making the world-space triangles of the frame are not timed.
 *
 * The thesis's method (section 4.1): the build time of each keyframe,
 * averaged over the keyframes; so each row's figures are its per-run means
 * over the frames, min and median over the runs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "engines/bench_animate.h"
#include "engines/bench_print.h"
#include "accel/bvh.h"
#include "base/clock.h"
#include "render/renderer_internal.h"
#include "rt.h"
#include "scene/scene.h"
#ifdef RT_HAVE_EMBREE
#include "accel/bvh_refit.h"
#include "peer/embree_peer.h"
#endif

enum { OURS = 4 };
static const rt_update_policy policies[OURS] = {RT_UPDATE_SAH, RT_UPDATE_REFIT, RT_UPDATE_LBVH,
                                                RT_UPDATE_AUTO};

/* The first object that morphs between keyframes, or -1. */
static int morph_object(const rt_scene *s) {
    for (uint32_t o = 0; o < s->object_count; o++)
        if (s->objects[o].morphing) return (int)o;
    return -1;
}

/* FNV-1a over the framebuffer's bytes: equal images, equal hashes. */
static uint64_t image_hash(const rt_framebuffer *fb) {
    const unsigned char *p = (const unsigned char *)fb->pixels;
    size_t n = sizeof(float) * (size_t)fb->width * (size_t)fb->height * (size_t)fb->channels;
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static void set_policy(rt_scene *s, rt_update_policy p) {
    for (uint32_t m = 0; m < s->mesh_count; m++) rt_mesh_set_update(s, m, p);
}

/* What a row keeps from frame to frame within a run. */
typedef struct row_state {
    rt_renderer *r; /* ours: a fresh renderer per run */
    rt_framebuffer fb;
    rt_render_options o;
    rt_render_stats st;
#ifdef RT_HAVE_EMBREE
    rt_embree_anim *a; /* Embree: its dynamic scene */
    struct embree_trees *trees;
#endif
} row_state;

static int ours_start(const bench_anim_setup *su, bench_anim_row *row, row_state *rs) {
    rt_renderer_options ro = rt_renderer_options_default();
    ro.backend = su->backend ? su->backend : "packet";
    ro.threads = su->threads;
    rt_error e;
    if (rt_renderer_create(&ro, &rs->r, &e) != RT_OK) {
        snprintf(row->error, sizeof row->error, "%.199s", e.message);
        return 0;
    }
    rs->o = rt_render_options_default();
    rs->o.stats = &rs->st;
    rs->o.direct_only = 1;
    rs->o.reuse_framebuffer = 1;
    return 1;
}

static void ours_end(row_state *rs) {
    rt_framebuffer_free(&rs->fb);
    rt_renderer_destroy(rs->r);
    rs->r = NULL;
}

/* Frame k of run run for one of our policies (the scene already at the
 * frame's time; policies are the scene's, so set before each row's frame).
 * ref: rebuild's image hashes per frame (filled by the rebuild row, which
 * renders first, compared by the others; NULL after the first run). */
static int ours_frame(rt_scene *s, bench_anim_result *res, bench_anim_row *row, row_state *rs,
                      rt_update_policy p, int run, int k, uint64_t *ref) {
    set_policy(s, p);
    double t0 = rt_now_ms();
    if (rt_render(rs->r, s, &rs->o, &rs->fb) != RT_OK) {
        snprintf(row->error, sizeof row->error, "%.199s", rt_renderer_error(rs->r));
        return 0;
    }
    double frame = rt_now_ms() - t0;
    rt_update_stats us;
    rt_renderer_update_stats(rs->r, &us);
    double upd = 0.0;
    for (uint32_t i = 0; i < us.mesh_count; i++) upd += us.meshes[i].ms;
    size_t i = bench_anim_index(res, run, k);
    row->update[i] = upd;
    row->frame[i] = frame;
    row->trace[i] = rs->st.render_ms;
    row->sah_f[i] = rs->st.sah_cost;
    row->tests[i] = (double)rs->st.box_tests + 2.0 * (double)rs->st.tri_tests;
    if (ref) {
        uint64_t h = image_hash(&rs->fb);
        if (p == RT_UPDATE_SAH)
            ref[k] = h;
        else if (h != ref[k])
            row->images_match = 0;
    }
    return 1;
}

#ifdef RT_HAVE_EMBREE
/* The frame's layout from the helper renderer (its meshes refitted, so that
 * every mesh keeps its triangle order from frame to frame). */
static int helper_layout(rt_renderer *helper, rt_scene *s, rt_backend_layout *l,
                         bench_anim_row *row) {
    double build_ms, sah;
    if (rt_renderer_layout(helper, s, l, &build_ms, &sah) == RT_OK) return 1;
    snprintf(row->error, sizeof row->error, "%.199s", rt_renderer_error(helper));
    return 0;
}

/* Per scene mesh, the tree an Embree REFIT row keeps refitting. */
typedef struct embree_trees {
    rt_bvh *bvh;
    rt_bvh_refit_info *info;
    double *sah; /* this frame's, NAN: not yet */
    uint32_t n;
} embree_trees;

static void trees_free(embree_trees *t) {
    for (uint32_t m = 0; m < t->n; m++) {
        rt_bvh_free(&t->bvh[m]);
        rt_bvh_refit_info_free(&t->info[m]);
    }
    free(t->bvh);
    free(t->info);
    free(t->sah);
    memset(t, 0, sizeof *t);
}

/* Mesh m's SAH cost in a tree of Embree's builder of this quality, measured
 * as ours (rt_bvh_sah, Ct 1, Ci 2, our leaf size): LOW, rtcBuildBVH's
 * Morton builder, MEDIUM its binned SAH builder, each anew every frame;
 * REFIT, the binned SAH tree of the mesh's first frame refitted since, as
 * Embree's REFIT geometries keep theirs. Embree's own commit trees (4- or
 * 8-wide, its leaves) are not exposed; these are its builders' trees. */
static double mesh_sah(rt_embree *em, const rt_mesh_data *md, int quality, embree_trees *t,
                       uint32_t m) {
    uint32_t n = md->triangle_count;
    if (!n) return 0.0;
    rt_aabb *boxes = malloc(sizeof *boxes * n);
    if (!boxes) return NAN;
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t *ix = md->indices + 3 * (size_t)i;
        for (int k = 0; k < 3; k++) {
            float a = md->positions[3 * ix[0] + k], b = md->positions[3 * ix[1] + k],
                  c = md->positions[3 * ix[2] + k];
            boxes[i].bmin[k] = a < b ? (a < c ? a : c) : (b < c ? b : c);
            boxes[i].bmax[k] = a > b ? (a > c ? a : c) : (b > c ? b : c);
        }
    }
    rt_build_options o = rt_build_options_default();
    rt_error e;
    double ms, sah = NAN;
    rt_bvh *keep = &t->bvh[m];
    if (quality == RT_EMBREE_REFIT && keep->node_count && keep->prim_count == n) {
        rt_bvh_refit(keep, &t->info[m], boxes, NULL);
        sah = rt_bvh_sah_cost(keep, rt_sah_costs_default());
    } else {
        rt_bvh b;
        int q = quality == RT_EMBREE_LOW ? RT_EMBREE_LOW : RT_EMBREE_MEDIUM;
        if (rt_embree_build_bvh_quality(em, boxes, n, &o, q, &b, &ms, &e) == RT_OK) {
            sah = rt_bvh_sah_cost(&b, rt_sah_costs_default());
            if (quality == RT_EMBREE_REFIT) {
                rt_bvh_free(keep);
                rt_bvh_refit_info_free(&t->info[m]);
                *keep = b;
                if (rt_bvh_refit_prepare(keep, &t->info[m]) != RT_OK) {
                    rt_bvh_free(keep);
                    sah = NAN;
                }
            } else {
                rt_bvh_free(&b);
            }
        }
    }
    free(boxes);
    return sah;
}

/* The frame's SAH cost for an Embree row: per shown mesh (mesh_sah), the
 * triangle-weighted mean over the objects, as rt_render_stats.sah_cost. */
static double embree_sah(rt_embree *em, const rt_scene *s, int quality, embree_trees *t) {
    if (t->n < s->mesh_count) {
        rt_bvh *b = realloc(t->bvh, sizeof *b * s->mesh_count);
        if (b) t->bvh = b;
        rt_bvh_refit_info *in = realloc(t->info, sizeof *in * s->mesh_count);
        if (in) t->info = in;
        double *sh = realloc(t->sah, sizeof *sh * s->mesh_count);
        if (sh) t->sah = sh;
        if (!b || !in || !sh) return NAN;
        memset(t->bvh + t->n, 0, sizeof *b * (s->mesh_count - t->n));
        memset(t->info + t->n, 0, sizeof *in * (s->mesh_count - t->n));
        t->n = s->mesh_count;
    }
    for (uint32_t m = 0; m < t->n; m++) t->sah[m] = NAN;
    double sah = 0.0, weight = 0.0;
    for (uint32_t o = 0; o < s->object_count; o++) {
        uint32_t m = rt_object_shown_mesh(&s->objects[o]);
        double n = (double)s->meshes[m].triangle_count;
        if (n == 0) continue;
        if (isnan(t->sah[m])) t->sah[m] = mesh_sah(em, &s->meshes[m], quality, t, m);
        sah += n * t->sah[m];
        weight += n;
    }
    return weight > 0 ? sah / weight : 0.0;
}

/* Frame k of run run for Embree at one quality, from the frame's layout l:
 * frame 0 makes the dynamic scene, every other frame updates and traces it. */
static int embree_frame(rt_scene *s, rt_embree *em, const rt_backend_layout *l, int quality,
                        bench_anim_result *res, bench_anim_row *row, row_state *rs, int run,
                        int k) {
    rt_error e;
    memset(&e, 0, sizeof e);
    if (k == 0) {
        double ms;
        rs->trees = calloc(1, sizeof *rs->trees);
        if (!rs->trees) {
            snprintf(row->error, sizeof row->error, "out of memory");
            return 0;
        }
        if (rt_embree_anim_create(em, l->flat, quality, &rs->a, &ms, &e) != RT_OK) {
            snprintf(row->error, sizeof row->error, "%.199s", e.message);
            return 0;
        }
        embree_sah(em, s, quality, rs->trees); /* the trees REFIT keeps */
        return 1;
    }
    double copy_ms, commit_ms, trace_ms;
    uint64_t rays;
    if (rt_embree_anim_update(rs->a, l->flat, &copy_ms, &commit_ms, &e) != RT_OK) {
        snprintf(row->error, sizeof row->error, "%.199s", e.message);
        return 0;
    }
    rt_embree_render(rt_embree_anim_scene(rs->a), row->lanes, l->pool, NULL, &rays, &trace_ms);
    size_t i = bench_anim_index(res, run, k);
    row->update[i] = commit_ms;
    row->trace[i] = trace_ms;
    row->frame[i] = copy_ms + commit_ms + trace_ms;
    row->sah_f[i] = embree_sah(em, s, quality, rs->trees); /* not timed */
    row->tests[i] = NAN;
    return 1;
}

static void embree_end(row_state *rs) {
    if (rs->trees) trees_free(rs->trees);
    free(rs->trees);
    rs->trees = NULL;
    rt_embree_anim_destroy(rs->a);
    rs->a = NULL;
}
#endif

/* The row's figures from its samples. */
static void summarize(bench_anim_result *res, bench_anim_row *row) {
    if (row->error[0]) return;
    double *u = malloc(sizeof(double) * (size_t)res->runs * 3);
    if (!u) {
        snprintf(row->error, sizeof row->error, "out of memory");
        return;
    }
    double *f = u + res->runs, *t = f + res->runs, sah = 0.0;
    for (int run = 0; run < res->runs; run++) {
        u[run] = f[run] = t[run] = 0.0;
        for (int k = 1; k <= res->frames; k++) {
            size_t i = bench_anim_index(res, run, k);
            u[run] += row->update[i] / res->frames;
            f[run] += row->frame[i] / res->frames;
            t[run] += row->trace[i] / res->frames;
            sah += row->sah_f[i] / ((double)res->frames * res->runs);
        }
    }
    bench_min_median(u, res->runs, &row->update_ms_min, &row->update_ms_median);
    bench_min_median(f, res->runs, &row->frame_ms_min, &row->frame_ms_median);
    bench_min_median(t, res->runs, &row->trace_ms_min, &row->trace_ms_median);
    row->sah = sah;
    free(u);
}

static int row_init(bench_anim_row *row, const char *engine, const char *policy, size_t n) {
    memset(row, 0, sizeof *row);
    snprintf(row->engine, sizeof row->engine, "%s", engine);
    snprintf(row->policy, sizeof row->policy, "%s", policy);
    row->images_match = -1;
    row->update = calloc(n, sizeof(double));
    row->frame = calloc(n, sizeof(double));
    row->trace = calloc(n, sizeof(double));
    row->sah_f = calloc(n, sizeof(double));
    row->tests = calloc(n, sizeof(double));
    return row->update && row->frame && row->trace && row->sah_f && row->tests;
}

void bench_anim_free(bench_anim_result *res) {
    for (int i = 0; i < res->n_rows; i++) {
        bench_anim_row *r = &res->rows[i];
        free(r->update);
        free(r->frame);
        free(r->trace);
        free(r->sah_f);
        free(r->tests);
    }
    res->n_rows = 0;
}

int bench_animate(const char *path, const bench_anim_setup *su, bench_anim_result *res, char *err,
                  size_t err_size) {
    memset(res, 0, sizeof *res);
    rt_scene *s = NULL;
    rt_error e;
    if (su->progress) su->progress(path, "loading");
    if (rt_scene_open(path, &s, &e) != RT_OK) {
        snprintf(err, err_size, "%s", e.message);
        return 0;
    }
    rt_scene_set_threads(s, su->threads);
    int mo = morph_object(s);
    uint32_t clips = rt_scene_clip_count(s);
    if (su->animation && rt_scene_select_clip(s, su->animation) != RT_OK) {
        snprintf(err, err_size, "%s: %s", path, rt_scene_error(s));
        rt_scene_destroy(s);
        return 0;
    }
    if (mo < 0 && !(clips && rt_scene_is_animated(s))) {
        snprintf(err, err_size,
                 "%s: no object morphs between keyframes (--animate needs an object with "
                 "\"animation\": {\"keyframe_rate\": R, \"interpolate\": true} over keyframes of "
                 "one topology)",
                 path);
        rt_scene_destroy(s);
        return 0;
    }
    rt_camera cam;
    rt_camera_get(s, &cam);
    cam.width = su->width;
    cam.height = su->height;
    if (rt_camera_set(s, &cam) != RT_OK) {
        snprintf(err, err_size, "%s", rt_scene_error(s));
        rt_scene_destroy(s);
        return 0;
    }
    for (uint32_t o = 0; o < s->object_count; o++)
        res->triangles += s->meshes[rt_object_shown_mesh(&s->objects[o])].triangle_count;
    res->runs = su->runs;
    if (mo >= 0) {
        const rt_object_data *od = &s->objects[mo];
        res->keyframes = od->mesh_count;
        res->morph_triangles = s->meshes[od->morph_mesh].triangle_count;
        res->frames = su->frames > 0 ? su->frames : (int)od->mesh_count;
        res->fps = su->fps > 0.0 ? su->fps : (double)od->keyframe_rate;
    } else {
        /* A glTF clip: skinned meshes deform (world space, identity
         * transform), rigid parts move as objects. */
        for (uint32_t o = 0; o < s->object_count; o++)
            if (rt_transform_is_identity(s->objects[o].transform))
                res->morph_triangles +=
                    s->meshes[rt_object_shown_mesh(&s->objects[o])].triangle_count;
        res->frames = su->frames > 0 ? su->frames : 10;
        res->fps = su->fps > 0.0 ? su->fps : 5.0;
    }
    size_t n = (size_t)res->runs * (size_t)(res->frames + 1);
    uint64_t *ref = calloc((size_t)res->frames + 1, sizeof *ref);
    double *scene_ms = calloc((size_t)res->runs + 1, sizeof *scene_ms);
    int ok = ref != NULL && scene_ms != NULL;
    for (int p = 0; p < OURS && ok; p++) {
        ok = row_init(&res->rows[res->n_rows++], "rtcl", rt_update_policy_name(policies[p]), n);
        if (p) res->rows[p].images_match = 1;
    }
    int n_ours = res->n_rows;
#ifdef RT_HAVE_EMBREE
    static const char *const qualities[3] = {"refit", "low", "medium"};
    rt_embree *em = NULL;
    rt_renderer *helper = NULL;
    if (!su->embree) {
        snprintf(res->embree_note, sizeof res->embree_note, "left out (--no-embree)");
    } else if (ok) {
        rt_error ee;
        memset(&ee, 0, sizeof ee);
        rt_renderer_options ro = rt_renderer_options_default();
        ro.threads = su->threads;
        if (rt_embree_create(su->threads, &em, &ee) != RT_OK) {
            snprintf(res->embree_note, sizeof res->embree_note, "%.199s", ee.message);
        } else if (rt_renderer_create(&ro, &helper, &ee) != RT_OK) {
            snprintf(res->embree_note, sizeof res->embree_note, "%.199s", ee.message);
        } else {
            int lanes = 1;
            for (int w = 4; w <= 16; w *= 2)
                if (rt_embree_native_lanes(em, w)) lanes = w;
            for (int q = 0; q < 3 && ok; q++) {
                ok = row_init(&res->rows[res->n_rows++], "embree", qualities[q], n);
                res->rows[res->n_rows - 1].lanes = lanes;
            }
        }
    }
#else
    snprintf(
        res->embree_note, sizeof res->embree_note,
        "this build has no Embree (configured with RT_EMBREE=OFF, or libembree-dev was not found)");
#endif
    if (!ok) snprintf(err, err_size, "out of memory");
    /* Run by run, frame by frame, every row's frame k before any row's frame
     * k + 1, so that the machine's noise falls on every row alike; each row
     * keeps its renderer (or Embree scene) through the run. */
    row_state rs[BENCH_ANIM_MAX_ROWS];
    memset(rs, 0, sizeof rs);
    for (int run = 0; run < res->runs && ok; run++) {
        for (int r = 0; r < n_ours; r++)
            if (!res->rows[r].error[0]) ours_start(su, &res->rows[r], &rs[r]);
        for (int k = 0; k <= res->frames; k++) {
            if (su->progress) {
                char what[80];
                snprintf(what, sizeof what, "run %d of %d, frame %d of %d", run + 1, res->runs, k,
                         res->frames);
                su->progress(path, what);
            }
            double ts = rt_now_ms();
            rt_scene_set_time(s, k / res->fps); /* the scene's work, apart from the rows' */
            if (k > 0 && scene_ms) scene_ms[run] += (rt_now_ms() - ts) / res->frames;
            for (int r = 0; r < n_ours; r++)
                if (!res->rows[r].error[0] && rs[r].r &&
                    !ours_frame(s, res, &res->rows[r], &rs[r], policies[r], run, k,
                                run == 0 ? ref : NULL))
                    ours_end(&rs[r]);
#ifdef RT_HAVE_EMBREE
            if (res->n_rows > n_ours) {
                /* The frame's layout, once for the Embree rows (not timed). */
                rt_backend_layout l;
                set_policy(s, RT_UPDATE_REFIT);
                if (!helper_layout(helper, s, &l, &res->rows[n_ours])) {
                    char why[sizeof res->rows[0].error];
                    memcpy(why, res->rows[n_ours].error, sizeof why);
                    for (int r = n_ours + 1; r < res->n_rows; r++)
                        memcpy(res->rows[r].error, why, sizeof why);
                } else {
                    for (int r = n_ours; r < res->n_rows; r++)
                        if (!res->rows[r].error[0])
                            embree_frame(s, em, &l, r - n_ours, res, &res->rows[r], &rs[r], run, k);
                }
            }
#endif
        }
        for (int r = 0; r < res->n_rows; r++) {
            if (r < n_ours) ours_end(&rs[r]);
#ifdef RT_HAVE_EMBREE
            else
                embree_end(&rs[r]);
#endif
        }
    }
    /* Without rebuild's images there is nothing to compare with. */
    for (int r = 1; r < n_ours && res->rows[0].error[0]; r++) res->rows[r].images_match = -1;
    for (int r = 0; r < res->n_rows && ok; r++) summarize(res, &res->rows[r]);
#ifdef RT_HAVE_EMBREE
    rt_renderer_destroy(helper);
    rt_embree_destroy(em);
#endif
    res->scene_ms_min = res->scene_ms_median = NAN;
    if (ok && res->runs > 0)
        bench_min_median(scene_ms, res->runs, &res->scene_ms_min, &res->scene_ms_median);
    free(ref);
    free(scene_ms);
    rt_scene_destroy(s);
    if (!ok) bench_anim_free(res);
    return ok;
}

/* ---- output ------------------------------------------------------------------ */

static void json_number(const char *key, double v) {
    if (isfinite(v))
        printf(", \"%s\": %.4f", key, v);
    else
        printf(", \"%s\": null", key);
}

/* Per frame 1 .. frames: the median over the runs of samples v. */
static void json_series(const char *key, const bench_anim_result *res, const double *v,
                        double *scratch) {
    printf("%s\"%s\": [", key[0] == 'u' ? "" : ", ", key);
    for (int k = 1; k <= res->frames; k++) {
        for (int run = 0; run < res->runs; run++) scratch[run] = v[bench_anim_index(res, run, k)];
        double mn, med;
        bench_min_median(scratch, res->runs, &mn, &med);
        if (isfinite(med))
            printf("%s%.4f", k > 1 ? ", " : "", med);
        else
            printf("%snull", k > 1 ? ", " : "");
    }
    putchar(']');
}

void bench_anim_print_json(const char *path, const bench_anim_result *res, int series) {
    printf(", \"triangles\": %u, \"morph_triangles\": %u, \"keyframes\": %u, \"frames\": %d, "
           "\"fps\": %.4f, \"runs\": %d",
           res->triangles, res->morph_triangles, res->keyframes, res->frames, res->fps, res->runs);
    json_number("scene_ms_min", res->scene_ms_min);
    json_number("scene_ms_median", res->scene_ms_median);
    if (res->embree_note[0]) {
        printf(", \"embree_missing\": ");
        json_out_string(res->embree_note);
    }
    printf(", \"dynamic\": [");
    double *scratch = malloc(sizeof(double) * (size_t)(res->runs ? res->runs : 1));
    for (int i = 0; i < res->n_rows; i++) {
        const bench_anim_row *r = &res->rows[i];
        printf("%s{\"scene\": ", i ? ", " : "");
        json_out_string(path);
        printf(", \"engine\": \"%s\", \"policy\": \"%s\"", r->engine, r->policy);
        if (r->lanes) printf(", \"lanes\": %d", r->lanes);
        if (r->error[0]) {
            printf(", \"error\": ");
            json_out_string(r->error);
            putchar('}');
            continue;
        }
        json_number("update_ms_min", r->update_ms_min);
        json_number("update_ms_median", r->update_ms_median);
        json_number("frame_ms_min", r->frame_ms_min);
        json_number("frame_ms_median", r->frame_ms_median);
        json_number("trace_ms_min", r->trace_ms_min);
        json_number("trace_ms_median", r->trace_ms_median);
        json_number("sah", r->sah);
        if (!strcmp(r->engine, "embree"))
            printf(", \"sah_note\": \"rtcBuildBVH's binary trees of this quality (REFIT: its "
                   "MEDIUM tree of the first frame, refitted), leaf size %d, measured as ours; "
                   "Embree's commit trees are not exposed\"",
                   rt_build_options_default().leaf_size);
        if (r->images_match >= 0)
            printf(", \"images_match_rebuild\": %s", r->images_match ? "true" : "false");
        if (series && scratch) {
            printf(", \"series\": {");
            json_series("update_ms", res, r->update, scratch);
            json_series("trace_ms", res, r->trace, scratch);
            json_series("frame_ms", res, r->frame, scratch);
            json_series("sah", res, r->sah_f, scratch);
            json_series("tests", res, r->tests, scratch);
            putchar('}');
        }
        putchar('}');
    }
    free(scratch);
    putchar(']');
}

void bench_anim_print_text(const char *path, const bench_anim_result *res) {
    printf("%s: %u triangles morphing (of %u), %u keyframes; %d frames at %g fps after the first "
           "build, %d runs, rows interleaved frame by frame (per-run mean over the frames, min and "
           "median over the "
           "runs)\n",
           path, res->morph_triangles, res->triangles, res->keyframes, res->frames, res->fps,
           res->runs);
    printf("  the scene's own work per frame (rt_scene_set_time: blending, or a glTF clip's "
           "posing, skinning and morphing): min %.3f ms, median %.3f ms\n",
           res->scene_ms_min, res->scene_ms_median);
    printf("  %-7s %-8s %10s %10s %10s %10s %10s %10s %8s %s\n", "engine", "policy", "update min",
           "median", "trace min", "median", "frame min", "median", "SAH", "images");
    for (int i = 0; i < res->n_rows; i++) {
        const bench_anim_row *r = &res->rows[i];
        printf("  %-7s %-8s ", r->engine, r->policy);
        if (r->error[0]) {
            printf("failed: %s\n", r->error);
            continue;
        }
        printf("%10.2f %10.2f %10.2f %10.2f %10.2f %10.2f ", r->update_ms_min, r->update_ms_median,
               r->trace_ms_min, r->trace_ms_median, r->frame_ms_min, r->frame_ms_median);
        if (isfinite(r->sah))
            printf("%8.2f ", r->sah);
        else
            printf("%8s ", "-");
        printf("%s\n", r->images_match < 0 ? "-" : r->images_match ? "= sah" : "DIFFER from sah");
    }
    if (res->embree_note[0]) printf("  embree: no rows: %s\n", res->embree_note);
}

int bench_anim_run(const char *const *scenes, int n_scenes, const bench_anim_setup *setup, int json,
                   int series, const char *who) {
    const bench_anim_setup su = *setup;
    int failed = 0;
    for (int i = 0; i < n_scenes; i++) {
        bench_anim_result res;
        char why[400] = "";
        int ok = bench_animate(scenes[i], &su, &res, why, sizeof why);
        if (su.progress) fprintf(stderr, "\r\033[K");
        if (!ok) {
            fprintf(stderr, "%s: %s\n", who, why);
            failed = 1;
            continue;
        }
        if (json) {
            printf("{\"scene\": ");
            json_out_string(scenes[i]);
            printf(", \"threads\": %d, \"width\": %d, \"height\": %d", su.threads, su.width,
                   su.height);
            bench_anim_print_json(scenes[i], &res, series);
            printf("}\n");
        } else {
            bench_anim_print_text(scenes[i], &res);
        }
        fflush(stdout);
        bench_anim_free(&res);
    }
    return failed ? 2 : 0;
}
