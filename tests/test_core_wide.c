/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_wide.c - the one wide collapse (cpu_ref/wide_bvh.h) in every
 * shape the tracers use (the packet tracer's, the single-ray tracer's at
 * widths 4 and 8), and the instruction-set table (cpu_ref/cpu_isa.h):
 * - every slot's box is its binary node's box, bit for bit; empty slots are
 *   inverted boxes after the real children; no node has more children than
 *   the width, an inner node at least two;
 * - each tree's leaves hold exactly the binary tree's entries, in its
 *   left-to-right order (a leaf of a shape without blocks as an entry range,
 *   a mesh leaf of the single-ray shape as blocks whose lanes are the
 *   layout's triangles, bit for bit, empty lanes repeating the last real
 *   one); every wide node is reached from the roots, once per tree;
 * - after a refit of the binary trees (a deforming mesh, update policy
 *   refit), rt_wide_refit brings both shapes' trees to the new boxes and
 *   vertices (the same checks), and the tracers of every build the CPU runs
 *   give the oracle's hits through them;
 * - shapes other than width 4 or 8, or without a leaf size, are refused;
 * - the table names each build once, finds the widest the CPU runs for NULL
 *   and refuses unknown names.
 * On the built-in scenes, BVH and kd meshes, and the shared scenes when
 * present. Also runs under qemu-aarch64. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "cpu_isa.h"
#include "layout/flat.h"
#include "oracle_util.h"
#include "packet_trace.h"
#include "ray_sets.h"
#include "rt.h"
#include "scene/scene.h"
#include "scene/scene_builtin.h"
#include "single_trace.h"
#include "wide_bvh.h"

static float word_f(const uint32_t *w, size_t i) {
    float f;
    memcpy(&f, &w[i], sizeof f);
    return f;
}

static int same_bits(float a, float b) {
    return memcmp(&a, &b, sizeof a) == 0;
}

/* The binary tree's entries below node x, left to right. */
static void binary_entries(const rt_flat *f, uint32_t x, uint32_t *out, uint32_t *n) {
    const rt_node *nd = &f->nodes[x];
    if (nd->b & RT_NODE_LEAF_FLAG) {
        for (uint32_t i = 0; i < (nd->b & RT_NODE_COUNT_MASK); i++) out[(*n)++] = nd->a + i;
        return;
    }
    binary_entries(f, nd->a, out, n);
    binary_entries(f, nd->b, out, n);
}

/* How many entries the binary tree holds below node x. */
static uint32_t binary_count(const rt_flat *f, uint32_t x) {
    const rt_node *nd = &f->nodes[x];
    if (nd->b & RT_NODE_LEAF_FLAG) return nd->b & RT_NODE_COUNT_MASK;
    return binary_count(f, nd->a) + binary_count(f, nd->b);
}

typedef struct walk {
    const rt_flat *f;
    const rt_wide_bvh *w;
    int top;           /* the object BVH: its leaves are entry ranges always */
    uint32_t *entries; /* the entries found, left to right */
    uint32_t n, cap;   /* how many, and room */
    uint32_t *seen;    /* per wide node: times reached */
    const char *what;
    int bad;
} walk;

/* Checks block j's lanes and appends their entries. */
static void check_block(walk *k, uint32_t j) {
    const int wd = k->w->shape.width;
    const uint32_t *blk = k->w->blocks + (size_t)RT_WIDE_BLOCK_WORDS(wd) * j;
    int last = -1;
    for (int l = 0; l < wd; l++) {
        const uint32_t e = blk[9 * wd + l];
        if (e == RT_WIDE_EMPTY) {
            if (last < 0) k->bad++; /* lane 0 is always real */
            continue;
        }
        if (last != l - 1 || e >= k->f->tri_count || k->n >= k->cap) {
            k->bad++; /* real lanes come first */
            return;
        }
        last = l;
        k->entries[k->n++] = e;
    }
    const uint32_t e_last = blk[9 * wd + last];
    for (int l = 0; l < wd; l++) {
        const uint32_t e = blk[9 * wd + l] == RT_WIDE_EMPTY ? e_last : blk[9 * wd + l];
        const rt_tri *t = &k->f->tris[e];
        for (int c = 0; c < 3; c++) {
            k->bad += !same_bits(word_f(blk, (size_t)c * wd + l), t->v0[c]);
            k->bad += !same_bits(word_f(blk, (size_t)(3 + c) * wd + l), t->v1[c]);
            k->bad += !same_bits(word_f(blk, (size_t)(6 + c) * wd + l), t->v2[c]);
        }
    }
}

/* Checks wide node i and the tree below it, appending its entries. */
static void check_node(walk *k, uint32_t i, int entry_node) {
    const rt_wide_bvh *w = k->w;
    const int wd = w->shape.width;
    if (i >= w->node_count) {
        k->bad++;
        return;
    }
    k->seen[i]++;
    const uint32_t *n = w->nodes + (size_t)RT_WIDE_NODE_WORDS(wd) * i;
    int kids = 0, ended = 0;
    for (int c = 0; c < wd; c++) {
        const uint32_t child = n[6 * wd + c], info = n[7 * wd + c];
        const uint32_t src = w->src[(size_t)wd * i + c];
        if (child == RT_WIDE_EMPTY) {
            ended = 1;
            k->bad += info != 0 || src != RT_WIDE_EMPTY;
            for (int a = 0; a < 3; a++)
                k->bad += !(word_f(n, (size_t)a * wd + c) == INFINITY) +
                          !(word_f(n, (size_t)(3 + a) * wd + c) == -INFINITY);
            continue;
        }
        kids++;
        if (ended || src >= k->f->node_count) {
            k->bad++;
            continue;
        }
        const rt_node *b = &k->f->nodes[src];
        for (int a = 0; a < 3; a++)
            k->bad += !same_bits(word_f(n, (size_t)a * wd + c), b->bmin[a]) +
                      !same_bits(word_f(n, (size_t)(3 + a) * wd + c), b->bmax[a]);
        if (!(info & RT_NODE_LEAF_FLAG)) {
            /* An inner child copies an inner binary node. */
            k->bad += info != 0 || (b->b & RT_NODE_LEAF_FLAG) != 0;
            check_node(k, child, 0);
            continue;
        }
        const uint32_t count = info & RT_NODE_COUNT_MASK;
        /* A leaf holds the binary subtree's entries. */
        const uint32_t first = k->n;
        if (k->top || !w->shape.blocks) {
            for (uint32_t e = 0; e < count && k->n < k->cap; e++) k->entries[k->n++] = child + e;
        } else {
            for (uint32_t j = child; j < child + count; j++) {
                if (j >= w->block_count) {
                    k->bad++;
                    break;
                }
                check_block(k, j);
            }
        }
        const uint32_t sub = binary_count(k->f, src);
        if (!(b->b & RT_NODE_LEAF_FLAG)) {
            /* A merged subtree: one run of at most leaf_entries entries. */
            const int merges = !k->top || w->shape.merge_top;
            k->bad += !merges || sub > w->shape.leaf_entries;
        }
        k->bad += k->n - first != sub;
    }
    k->bad += kids > wd || (entry_node ? kids != 1 : kids < 2);
}

/* Every tree of w against the layout f. */
static void check_trees(const rt_flat *f, const rt_wide_bvh *w, const char *what) {
    walk k = {f,    w, 0, NULL, 0, 0, calloc(w->node_count ? w->node_count : 1, sizeof(uint32_t)),
              what, 0};
    k.cap = f->tri_count + f->hdr.instance_count + 1;
    k.entries = malloc(sizeof(uint32_t) * k.cap);
    uint32_t *want = malloc(sizeof(uint32_t) * k.cap);
    uint32_t *root_done = calloc(f->node_count ? f->node_count : 1, sizeof(uint32_t));
    if (!k.seen || !k.entries || !want || !root_done) {
        CHECK(0);
        return;
    }
    const uint32_t insts = f->hdr.instance_count;
    int trees = 0;
    for (uint32_t i = 0; i <= insts; i++) {
        const int top = i == insts;
        if (top && (!insts || (f->hdr.flags & RT_SCENE_SINGLE))) {
            k.bad += w->top != RT_WIDE_EMPTY;
            break;
        }
        const uint32_t root = top ? f->hdr.top_root : f->instances[i].root;
        const uint32_t entry = top ? w->top : w->inst_root[i];
        if (!top && root_done[root]) {
            /* Instances of one mesh share its tree. */
            k.bad += root_done[root] != entry + 1;
            continue;
        }
        if (!top) root_done[root] = entry + 1;
        k.top = top;
        k.n = 0;
        check_node(&k, entry, 1);
        k.bad += w->src[(size_t)w->shape.width * entry] != root;
        uint32_t nw = 0;
        binary_entries(f, root, want, &nw);
        k.bad += nw != k.n || memcmp(want, k.entries, sizeof(uint32_t) * nw) != 0;
        trees++;
    }
    for (uint32_t i = 0; i < w->node_count; i++) k.bad += k.seen[i] != 1;
    CHECK_MSG(k.bad == 0, "%s: %d faults in the wide trees (%d trees, %u nodes, %u blocks)", what,
              k.bad, trees, w->node_count, w->block_count);
    free(k.seen);
    free(k.entries);
    free(want);
    free(root_done);
}

/* The shapes the tracers use. */
static int shapes(rt_wide_shape out[3]) {
    out[0] = rt_pk_shape();
    out[1] = rt_sw_shape(4);
    out[2] = rt_sw_shape(8);
    return 3;
}

static void check_layout(const rt_flat *f, const char *name) {
    rt_wide_shape sh[3];
    const int n = shapes(sh);
    for (int i = 0; i < n; i++) {
        char what[160];
        snprintf(what, sizeof what, "%s, %s shape width %d", name,
                 sh[i].blocks ? "single" : "packet", sh[i].width);
        rt_wide_bvh w;
        if (rt_wide_build(f, sh[i], &w) != RT_OK) {
            CHECK_MSG(0, "%s: rt_wide_build failed", what);
            continue;
        }
        check_trees(f, &w, what);
        printf("%s: %u nodes, %u blocks checked\n", what, w.node_count, w.block_count);
        /* A refit against the same layout changes nothing. */
        rt_wide_bvh again;
        CHECK(rt_wide_build(f, sh[i], &again) == RT_OK);
        CHECK(rt_wide_refit(f, &again) == RT_OK);
        CHECK_MSG(again.node_count == w.node_count && again.block_count == w.block_count &&
                      memcmp(again.nodes, w.nodes,
                             4 * (size_t)w.node_count * RT_WIDE_NODE_WORDS(w.shape.width)) == 0 &&
                      (!w.block_count ||
                       memcmp(again.blocks, w.blocks,
                              4 * (size_t)w.block_count * RT_WIDE_BLOCK_WORDS(w.shape.width)) == 0),
                  "%s: a refit on the same layout changed the trees", what);
        rt_wide_free(&again);
        rt_wide_free(&w);
    }
}

/* The oracle's hits against both tracers of every build the CPU runs. */
static int trace_all_builds(const rt_flat *f, const rt_wide_bvh *pk, const rt_wide_bvh *sw4,
                            const rt_wide_bvh *sw8, const rt_ray *rays, int n) {
    int bad = 0;
    rt_scene_view v = rt_flat_view(f);
    for (int k = 0; rt_cpu_isa_at(k); k++) {
        const rt_cpu_isa *isa = rt_cpu_isa_find(rt_cpu_isa_at(k));
        if (!isa) continue;
        const rt_wide_bvh *sw = rt_cpu_isa_width(isa) == 4 ? sw4 : sw8;
        for (int any = 0; any < 2; any++)
            for (int first = 0; first < n; first += RT_PK_LANES) {
                rt_pk_rays pr;
                memset(&pr, 0, sizeof pr);
                rt_hit_d single[RT_PK_LANES];
                const int m = n - first < RT_PK_LANES ? n - first : RT_PK_LANES;
                for (int l = 0; l < m; l++) {
                    rt_pk_set_ray(&pr, l, &rays[first + l]);
                    pr.valid |= (rt_pk_mask)1 << l;
                }
                rt_pk_hits ph;
                rt_pk_counts pc;
                memset(&pc, 0, sizeof pc);
                rt_pk_trace(isa, &v, pk, &pr, any, &ph, &pc);
                rt_counters c = {0, 0, 0};
                rt_sw_trace(isa, &v, sw, rays + first, (size_t)m, any, single, &c);
                for (int l = 0; l < m; l++) {
                    rt_hit_d want, got;
                    rt_trace(&v, &rays[first + l], any, &want, &c);
                    rt_pk_get_hit(&ph, l, &got);
                    if (any) {
                        bad += (got.prim == RT_NO_HIT) != (want.prim == RT_NO_HIT);
                        bad += (single[l].prim == RT_NO_HIT) != (want.prim == RT_NO_HIT);
                    } else {
                        bad += !oracle_same_hit(&got, &want) + !oracle_same_hit(&single[l], &want);
                    }
                }
            }
    }
    return bad;
}

/* A deforming mesh refitted: the wide trees of the first frame, refitted,
 * against the second frame's layout. */
static void check_refit(void) {
    rt_scene *s = test_builtin_scene("keyframes", 32, 32);
    if (!s) return;
    /* Every mesh refits; the first one deforms. */
    for (uint32_t m = 0; m < s->mesh_count; m++)
        CHECK(rt_mesh_set_update(s, m, RT_UPDATE_REFIT) == RT_OK);
    const rt_flat *f0 = test_layout(s, 2);
    if (!f0) return;
    const uint32_t nodes0 = f0->node_count, insts = f0->hdr.instance_count;
    rt_wide_bvh pk, sw4, sw8;
    CHECK(rt_wide_build(f0, rt_pk_shape(), &pk) == RT_OK);
    CHECK(rt_wide_build(f0, rt_sw_shape(4), &sw4) == RT_OK);
    CHECK(rt_wide_build(f0, rt_sw_shape(8), &sw8) == RT_OK);
    const rt_mesh_data *md = &s->meshes[0];
    const uint32_t nv = md->vertex_count;
    float *pos = malloc(sizeof(float) * 3 * nv);
    if (!pos) {
        CHECK(0);
        return;
    }
    for (uint32_t i = 0; i < nv; i++) {
        const float *p = &md->positions[3 * i];
        pos[3 * i] = p[0] * 1.25f + 0.1f * sinf(3.0f * p[1]);
        pos[3 * i + 1] = p[1] * 0.8f + 0.05f;
        pos[3 * i + 2] = p[2] + 0.1f * cosf(2.0f * p[0]);
    }
    CHECK(rt_mesh_set_positions(s, 0, pos, NULL, nv) == RT_OK);
    free(pos);
    const rt_flat *f1 = test_layout(s, 2);
    if (!f1) return;
    /* A refit keeps the binary trees' shapes (the precondition of
     * rt_wide_refit). */
    CHECK(f1->node_count == nodes0 && f1->hdr.instance_count == insts);
    CHECK(rt_wide_refit(f1, &pk) == RT_OK);
    CHECK(rt_wide_refit(f1, &sw4) == RT_OK);
    CHECK(rt_wide_refit(f1, &sw8) == RT_OK);
    check_trees(f1, &pk, "keyframes refitted, packet shape");
    check_trees(f1, &sw4, "keyframes refitted, single shape width 4");
    check_trees(f1, &sw8, "keyframes refitted, single shape width 8");
    enum { N = 3000 };
    rt_ray *rays = malloc(sizeof(rt_ray) * N);
    if (rays) {
        rt_rays_random(f1, 17, N / 2, rays);
        rt_rays_diffuse(f1, 18, N - N / 2, rays + N / 2);
        const int bad = trace_all_builds(f1, &pk, &sw4, &sw8, rays, N);
        CHECK_MSG(bad == 0, "keyframes refitted: %d hits differ from the oracle", bad);
        printf("keyframes refitted: %d rays through refitted trees, %d differ\n", N, bad);
    }
    free(rays);
    rt_wide_free(&pk);
    rt_wide_free(&sw4);
    rt_wide_free(&sw8);
    rt_scene_destroy(s);
}

static void check_table(void) {
    int builds = 0;
    for (int k = 0; rt_cpu_isa_at(k); k++) {
        for (int j = 0; j < k; j++) CHECK(strcmp(rt_cpu_isa_at(j), rt_cpu_isa_at(k)) != 0);
        const rt_cpu_isa *isa = rt_cpu_isa_find(rt_cpu_isa_at(k));
        if (!isa) {
            printf("build %s: not run by this CPU\n", rt_cpu_isa_at(k));
            continue;
        }
        builds++;
        const int lanes = rt_cpu_isa_lanes(isa), width = rt_cpu_isa_width(isa);
        printf("build %s: packet lanes %d, single-ray width %d\n", rt_cpu_isa_name(isa), lanes,
               width);
        CHECK(strcmp(rt_cpu_isa_name(isa), rt_cpu_isa_at(k)) == 0);
        CHECK(lanes == 4 || lanes == 8 || lanes == 16);
        CHECK(width == 4 || width == 8);
        /* NULL and "" take the widest the CPU runs: the first that runs. */
        if (builds == 1) CHECK(rt_cpu_isa_find(NULL) == isa && rt_cpu_isa_find("") == isa);
    }
    CHECK(builds > 0 && rt_cpu_isa_find("generic") != NULL);
    CHECK(rt_cpu_isa_find("sse9") == NULL && rt_cpu_isa_at(-1) == NULL);
}

int main(void) {
    check_table();
    for (int i = 0; rt_builtin_scene_names[i]; i++) {
        const char *name = rt_builtin_scene_names[i];
        for (int kd = 0; kd < 2; kd++) {
            rt_scene *s = test_builtin_scene(name, 32, 32);
            if (!s) continue;
            if (kd) CHECK(rt_scene_set_static_accel(s, RT_ACCEL_KD) == RT_OK);
            const rt_flat *f = test_layout(s, 2);
            char what[64];
            snprintf(what, sizeof what, "%s%s", name, kd ? " (kd)" : "");
            if (f) check_layout(f, what);
            if (f && !kd) {
                rt_wide_bvh none;
                rt_wide_shape bad = rt_sw_shape(4);
                bad.leaf_entries = 0;
                CHECK(rt_wide_build(f, rt_sw_shape(5), &none) == RT_ERROR_INVALID_ARGUMENT);
                CHECK(rt_wide_build(f, bad, &none) == RT_ERROR_INVALID_ARGUMENT);
                /* Other widths of the same collapse (the packet tracer's
                 * RT_PK_WIDTH may be 8) hold the same invariants. */
                rt_wide_shape wide8 = rt_pk_shape();
                wide8.width = 8;
                CHECK(rt_wide_build(f, wide8, &none) == RT_OK);
                check_trees(f, &none, "packet shape at width 8");
                rt_wide_free(&none);
            }
            rt_scene_destroy(s);
        }
    }
    check_refit();
    const char *shared[] = {"stanford_bunny/stanford-bunny.obj", "sponza_dabrovic/sponza.obj"};
    for (size_t i = 0; i < sizeof shared / sizeof shared[0]; i++) {
        const char *path = test_shared_scene(shared[i]);
        if (!path) {
            printf("%s: shared scenes not present, not checked\n", shared[i]);
            continue;
        }
        rt_scene *s = NULL;
        rt_error err;
        if (rt_scene_load(path, &s, &err) != RT_OK) {
            /* The core build has OBJ; a failure here is a real one. */
            CHECK_MSG(0, "%s: %s", path, err.message);
            continue;
        }
        const rt_flat *f = test_layout(s, 2);
        if (f) check_layout(f, shared[i]);
        rt_scene_destroy(s);
    }
    return TEST_END();
}
