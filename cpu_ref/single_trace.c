/* SPDX-License-Identifier: Apache-2.0 */
/* single_trace.c - one ray at a time through 4- or 8-wide BVHs
 * (single_trace.h), W lanes per vector (simd.h's RT_VN): W = 8 in the AVX2
 * and AVX-512 builds, 4 in the baseline one (SSE2 on x86-64, NEON on
 * aarch64).
 *
 * Every vector operation below is the scalar oracle's operation on each lane
 * (kernels/rt_shared.h, named at each function), in the same order, so each
 * lane's values are the oracle's bits; minimum and maximum are the oracle's
 * 'a < b ? a : b' and 'a > b ? a : b', NaN behaviour included (rt_vmin_of,
 * rt_vmax_of).
 *
 * Compiled once per instruction set (cpu_isa.h: RT_ISA names the build, and
 * the run-time choice is made there). */
#include <assert.h>
#include <string.h>

#include "cpu_isa.h"
#include "single_trace.h"

/* The width of the nodes and blocks: 8 where 8-lane vectors are native (in
 * the AVX-512 build too, where 16-wide nodes would be mostly empty), else
 * 4. simd.h's vectors then have W lanes. */
#if defined(__AVX2__)
#define RT_VN 8
#else
#define RT_VN 4
#endif

#include "simd.h"
#include "watertight_lanes.h"

#if RT_VN == 8 && defined(__AVX2__)
#include <simde/x86/avx2.h>
/* The children's order by a sorting network in one vector (sw_order). */
#define RT_SW_VECTOR_ORDER 1
#else
#define RT_SW_VECTOR_ORDER 0
#endif

#define RT_SW_TRACE RT_ISA_SYMBOL(rt_sw_trace)

enum { W = RT_VN, NODE_WORDS = RT_WIDE_NODE_WORDS(W), BLOCK_WORDS = RT_WIDE_BLOCK_WORDS(W) };

typedef struct sw_ctx {
    const rt_scene_view *s;
    const uint32_t *nodes, *blocks, *inst_root;
    rt_u32 method;
    int any_hit;
    uint64_t box_tests, tri_tests;
    rt_u32 ray_mask; /* the ray being traced's (rt_trace_masked) */
    int prefetch;    /* the tree is larger than a core's L2 (RT_SW_PREFETCH_BYTES) */
} sw_ctx;

/* Trees of more bytes than this (nodes and blocks) have their entered
 * children's lines prefetched; smaller ones stay in a core's L2 cache,
 * where a prefetch is only instructions. Measured (rtcl bench
 * --incoherent, AMD EPYC with 1 MiB of L2 a core): with the prefetch the
 * bunny's and Sponza's 4 MB trees ran 7-14% faster, the Cornell box's
 * 0.3 MB tree the same (docs/OPTIMISATION_LOG.md). */
#define RT_SW_PREFETCH_BYTES (1u << 20)

/* The ray as the box test reads it: org and inv in every lane, the byte
 * offsets of each axis's near and far planes in a node (rt_box_test's a and
 * b: bmax first where inv < 0), and rt_box_lo(tmin). */
typedef struct sw_ray {
    rt_vf org[3], inv[3];
    size_t near[3], far[3];
    rt_vf lo;
} sw_ray;

static inline void sw_ray_setup(const rt_ray *r, const rt_ray_pre *p, sw_ray *rv) {
    for (int k = 0; k < 3; k++) {
        rv->org[k] = rt_vsplat(r->org[k]);
        rv->inv[k] = rt_vsplat(p->inv[k]);
        rv->near[k] = (size_t)(p->sign[k] ? 3 + k : k) * W * 4;
        rv->far[k] = (size_t)(p->sign[k] ? k : 3 + k) * W * 4;
    }
    rv->lo = rt_vsplat(rt_box_lo(r->tmin));
}

/* rt_box_test on every child of node n against [rv->lo, hi]: bit c set when
 * child c exists and passes; tnear gets each lane's entry distance.
 *
 * The oracle folds the axes in one after the other, lo = (t0 > lo ? t0 :
 * lo) from rt_box_lo(tmin) and hi = (t1 < hi ? t1 : hi) from inf; here each
 * axis is folded into the start value first, then the three are folded
 * together, which shortens the chain of dependent instructions. Either way
 * a NaN t0 or t1 is skipped (each fold keeps the start value, never NaN
 * unless the start value is NaN, which then stays NaN either way) and the
 * result is the greatest (least) of the rest: the same number, up to the
 * sign of a zero, which no comparison below can tell. */
static inline uint32_t node_test(const uint32_t *n, const sw_ray *rv, rt_vf hi, rt_vf *tnear,
                                 uint32_t *real) {
    const char *base = (const char *)n;
    const rt_vf lo0 = rv->lo, inf = rt_vsplat(RT_INF);
    rt_vf lo[3], h[3];
    for (int k = 0; k < 3; k++) {
        const rt_vf a = rt_vload(base + rv->near[k]), b = rt_vload(base + rv->far[k]);
        const rt_vf t0 = (a - rv->org[k]) * rv->inv[k];
        const rt_vf t1 = (b - rv->org[k]) * rv->inv[k];
        lo[k] = rt_vmax_of(t0, lo0);
        h[k] = rt_vmin_of(t1, inf);
    }
    const rt_vf l = rt_vmax_of(lo[0], rt_vmax_of(lo[1], lo[2]));
    const rt_vf hh = rt_vmin_of(h[0], rt_vmin_of(h[1], h[2]));
    /* hi * (hi < 0 ? RT_BOX_FAR_SCALE_NEG : RT_BOX_FAR_SCALE), both
     * products at once and chosen by the sign bit: -0 and a NaN come out
     * the same either way. */
    const rt_vf far =
        rt_vsel_sign(hh, hh * rt_vsplat(RT_BOX_FAR_SCALE_NEG), hh * rt_vsplat(RT_BOX_FAR_SCALE));
    *tnear = l;
    /* A NaN lane passes the oracle's test as it passes this one; an empty
     * slot must still never be entered. */
    *real = rt_vbits(rt_vload_i(n + 6 * W) != rt_vsplat_i(-1));
    /* lo <= (hi < far ? hi : far) as lo <= hi and lo <= far, hi never NaN
     * here (see range_hi): the same for every lo and far, NaN included. */
    return rt_vbits((l <= hi) & (l <= far)) & *real;
}

/* The float at word i of a node or block. */
static inline float fl(const uint32_t *words, int i) {
    float f;
    memcpy(&f, &words[i], sizeof f);
    return f;
}

/* rt_box_hi(t) in every lane, as the box test's upper range end; a NaN
 * (which limits nothing in rt_box_test's 'tmax < hi ? tmax : hi') as +inf,
 * which limits nothing either. */
static inline rt_vf range_hi(float t) {
    const float h = rt_box_hi(t);
    return rt_vsplat(h == h ? h : RT_INF);
}

/* Records a hit as rt_leaf_test accepts it: returns 1 when the ray is an
 * any-hit ray (it is done). */
static inline int take_hit(sw_ctx *x, rt_hit_d *best, float t, float u, float v, rt_u32 e,
                           rt_u32 inst) {
    const rt_u32 prim = x->s->tri_ids[e];
    if (!x->any_hit && !rt_hit_before(t, inst, prim, best)) return 0;
    best->t = t;
    best->u = u;
    best->v = v;
    best->prim = prim;
    best->inst = inst;
    best->entry = e;
    return x->any_hit;
}

/* Entry e through the shared scalar test (rt_leaf_test's body): the
 * triangle tests other than the watertight one, and the watertight test's
 * lanes with an edge function of exactly zero, which need its exact
 * re-check (whatever rt_tri_watertight does there, this follows). */
static int tri_scalar(sw_ctx *x, rt_u32 e, rt_u32 inst, const rt_ray *r, const rt_ray_pre *p,
                      rt_hit_d *best) {
    float t, u, v;
    if (!rt_tri_test(x->method, &x->s->tris[e], r, p, r->tmin, best->t, &t, &u, &v)) return 0;
    if (!rt_hit_accepted(&x->s->tris[e], r, p, t)) return 0;
    return take_hit(x, best, t, u, v, e, inst);
}

/* rt_tri_t_plane's first tier (the plane in float, within its bound) for
 * the lanes of un of a block: each lane's triangle from the block's copies
 * of the vertices, by the oracle's operations in its order (rt_tri_t_apex,
 * rt_tri_t_normal, then the ray's part); the apex picked by selects. Sets
 * those lanes' t and returns the lanes the tier did not settle. */
static uint32_t sw_plane_tier1(const uint32_t *blk, const rt_ray *r, uint32_t un, rt_vf *t) {
    rt_vf v[9]; /* v0, v1, v2, coordinate by coordinate, as the block holds them */
    for (int k = 0; k < 9; k++) v[k] = rt_vload(blk + k * W);
    const rt_vf zero = rt_vsplat(0.0f);
    rt_vf l0 = zero, l1 = zero, l2 = zero;
    for (int i = 0; i < 3; i++) {
        const rt_vf a = v[3 + i] - v[6 + i], b = v[6 + i] - v[i], c = v[i] - v[3 + i];
        l0 = l0 + a * a;
        l1 = l1 + b * b;
        l2 = l2 + c * c;
    }
    const rt_vi k0 = (l0 >= l1) & (l0 >= l2), k1 = ~k0 & (l1 >= l2);
    rt_vf e[3], f[3], a[3];
    for (int i = 0; i < 3; i++) {
        const rt_vf p = rt_vsel(k0, v[i], rt_vsel(k1, v[3 + i], v[6 + i]));
        const rt_vf q = rt_vsel(k0, v[3 + i], rt_vsel(k1, v[6 + i], v[i]));
        const rt_vf s = rt_vsel(k0, v[6 + i], rt_vsel(k1, v[i], v[3 + i]));
        e[i] = q - p;
        f[i] = s - p;
        a[i] = p - rt_vsplat(r->org[i]);
    }
    rt_vf n[3], m[3], d[3];
    for (int i = 0; i < 3; i++) {
        const int j = i == 2 ? 0 : i + 1, k = j == 2 ? 0 : j + 1;
        const rt_vf x = e[j] * f[k], y = e[k] * f[j];
        n[i] = x - y;
        m[i] = rt_vabs(x) + rt_vabs(y);
        d[i] = rt_vsplat(r->dir[i]);
    }
    return rt_vwt_plane1(a, n, m, d, un, t);
}

/* The blocks first .. first + count - 1 of a leaf: rt_tri_watertight on
 * each lane's triangle. Returns 1 when an any-hit ray found a hit. */
static int leaf_test(sw_ctx *x, rt_u32 first, rt_u32 count, rt_u32 inst, const rt_ray *r,
                     const rt_ray_pre *p, rt_hit_d *best) {
    if (x->method != RT_TRI_WATERTIGHT) {
        for (rt_u32 j = first; j < first + count; j++) {
            const uint32_t *ent = x->blocks + (size_t)BLOCK_WORDS * j + 9 * W;
            for (int l = 0; l < W && ent[l] != RT_WIDE_EMPTY; l++) {
                x->tri_tests++;
                if (tri_scalar(x, ent[l], inst, r, p, best)) return 1;
            }
        }
        return 0;
    }
    const int kx = p->kx, ky = p->ky, kz = p->kz;
    const rt_vf ox = rt_vsplat(r->org[kx]), oy = rt_vsplat(r->org[ky]), oz = rt_vsplat(r->org[kz]);
    const rt_vf sx = rt_vsplat(p->sx), sy = rt_vsplat(p->sy), sz = rt_vsplat(p->sz);
    const rt_vf tmin = rt_vsplat(r->tmin);
    for (rt_u32 j = first; j < first + count; j++) {
        const uint32_t *blk = x->blocks + (size_t)BLOCK_WORDS * j;
        /* The oracle's A[i] = v0[i] - org[i] (and B, C) at kx, ky, kz. */
        const rt_vf A[3] = {rt_vload(blk + kx * W) - ox, rt_vload(blk + ky * W) - oy,
                            rt_vload(blk + kz * W) - oz};
        const rt_vf B[3] = {rt_vload(blk + (3 + kx) * W) - ox, rt_vload(blk + (3 + ky) * W) - oy,
                            rt_vload(blk + (3 + kz) * W) - oz};
        const rt_vf C[3] = {rt_vload(blk + (6 + kx) * W) - ox, rt_vload(blk + (6 + ky) * W) - oy,
                            rt_vload(blk + (6 + kz) * W) - oz};
        rt_vwt wt;
        const uint32_t z = rt_vwt_edges(A, B, C, sx, sy, &wt);
        const uint32_t *ent = blk + 9 * W;
        uint32_t valid = rt_vbits(rt_vload_i(ent) != rt_vsplat_i(-1));
        x->tri_tests += rt_lane_run(valid);
        if (z & valid) {
            for (uint32_t m = z & valid; m; m &= m - 1)
                if (tri_scalar(x, ent[rt_lane_first(m)], inst, r, p, best)) return 1;
            valid &= ~z;
        }
        uint32_t inside = rt_vwt_inside(&wt, valid);
        if (!inside) continue;
        rt_vf t = rt_vwt_t(&wt, sz);
        const rt_vf V = wt.V, Wf = wt.W, det = wt.det;
        /* A t that the oracle takes from the plane (rt_tri_t.h): the shared
         * scalar function for those lanes (rare). */
        uint32_t before;
        uint32_t un = rt_vwt_unsure(&wt, A, B, C, sx, sy, sz, tmin, inside, &before);
        inside &= ~before;
        if (un) un = sw_plane_tier1(blk, r, un, &t);
        for (; un; un &= un - 1) {
            const int l = rt_lane_first(un);
            t[l] = rt_tri_t_plane(&x->s->tris[ent[l]], r, t[l]);
        }
        uint32_t hit = rt_vbits((t >= tmin) & (t <= rt_vsplat(best->t))) & inside;
        for (; hit; hit &= hit - 1) {
            const int l = rt_lane_first(hit);
            /* rt_hit_accepted, from the block's copies of the vertices
             * (the layout's triangle is not in cache). */
            float mn[3], mx[3];
            for (int k = 0; k < 3; k++) {
                const float a = fl(blk, k * W + l), b = fl(blk, (3 + k) * W + l);
                const float c = fl(blk, (6 + k) * W + l);
                mn[k] = rt_min3(a, b, c);
                mx[k] = rt_max3(a, b, c);
            }
            if (!rt_hit_accepted_box(mn, mx, r, p, t[l])) continue;
            /* u = V / det and v = W / det, divided as the oracle divides. */
            if (take_hit(x, best, t[l], V[l] / det[l], Wf[l] / det[l], ent[l], inst)) return 1;
        }
    }
    return 0;
}

/* Starts loading child s's node, or the first block of its leaf, without
 * a branch: the address is picked by a select, and the lines of a block
 * (the larger of the two) are fetched either way. In the object BVH a
 * leaf's child is an instance range: its "node" is some node of the array,
 * which costs a useless fetch, no fault. */
static inline void prefetch(const sw_ctx *x, const uint32_t *child, const uint32_t *info, int s,
                            int top) {
    const uintptr_t node = (uintptr_t)(x->nodes + (size_t)NODE_WORDS * child[s]);
    const uintptr_t block = (uintptr_t)(x->blocks + (size_t)BLOCK_WORDS * child[s]);
    const char *p = (const char *)(!top && (info[s] & RT_NODE_LEAF_FLAG) ? block : node);
    for (int off = 0; off < 4 * BLOCK_WORDS; off += 64) __builtin_prefetch(p + off);
}

/* A child as the traversal carries it: one 64-bit word, its info above its
 * ref. */
static inline uint64_t sw_child(uint32_t ref, uint32_t info) {
    return (uint64_t)info << 32 | ref;
}

/* A stack of children to visit: each one's ref and info words (a node's
 * child and info lanes) and its entry distance. It holds the entered
 * siblings of the path's nodes, at most W - 1 per level; the wide tree is
 * no deeper than the binary one plus its entry node (which has one child),
 * and host/layout/flatten.c rejects binary trees deeper than RT_STACK_SIZE.
 * W more slots take sw_order's whole-vector stores. */
enum { SW_STACK = (W - 1) * RT_STACK_SIZE + 1 + W };
typedef struct sw_stack {
    uint32_t ref[SW_STACK], info[SW_STACK];
    float t[SW_STACK];
} sw_stack;

#if RT_SW_VECTOR_ORDER

/* One compare-exchange step of a sorting network: each lane against its
 * partner (p, the keys permuted), the larger kept where the lane's bit of
 * take_max is set. */
#define RT_SW_EXCHANGE(v, p, take_max)                                                             \
    simde_mm256_blend_epi32(simde_mm256_min_epu32(v, p), simde_mm256_max_epu32(v, p), take_max)

/* The eight keys of v in ascending order: Batcher's bitonic network, six
 * steps; lane i meets lane i ^ j (j = 1, 2, 4) by a shuffle within 128-bit
 * halves or a swap of the halves, and keeps the larger where i is the
 * upper of the pair in an ascending run or the lower in a descending one. */
static inline simde__m256i sw_sort8(simde__m256i v) {
    v = RT_SW_EXCHANGE(v, simde_mm256_shuffle_epi32(v, 0xb1), 0x66); /* runs of 2 */
    v = RT_SW_EXCHANGE(v, simde_mm256_shuffle_epi32(v, 0x4e), 0x3c); /* runs of 4 */
    v = RT_SW_EXCHANGE(v, simde_mm256_shuffle_epi32(v, 0xb1), 0x5a);
    v = RT_SW_EXCHANGE(v, simde_mm256_permute4x64_epi64(v, 0x4e), 0xf0); /* all 8 */
    v = RT_SW_EXCHANGE(v, simde_mm256_shuffle_epi32(v, 0x4e), 0xcc);
    v = RT_SW_EXCHANGE(v, simde_mm256_shuffle_epi32(v, 0xb1), 0xaa);
    return v;
}

/* The k >= 2 entered children m of a node (child and info its lanes, tn
 * their entry distances) in visiting order, without a branch: the first is
 * returned (info above ref), the other k - 1 pushed so that the second is
 * popped next. Closest hit: nearest first. Any hit: leaves first, then
 * inner nodes farthest first (see traverse). The order decides only how
 * soon a hit shrinks the range, never which children are visited.
 *
 * Each child is a key: its distance's bits with the sign and the three
 * lowest bits cleared (a non-negative float's bits order as the float;
 * the order of a negative or NaN distance only costs time), its slot in
 * those three bits, and ~0 for the slots not entered, above every entered
 * key, so that the k entered ones come first. */
static inline uint64_t sw_order(uint32_t m, rt_vf tn, const uint32_t *child, const uint32_t *info,
                                int any_hit, sw_stack *st, int *sp) {
    const simde__m256i slot = simde_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const simde__m256i body = simde_mm256_set1_epi32(0x7ffffff8);
    const simde__m256i bits =
        simde_mm256_and_si256((simde__m256i)tn, simde_mm256_set1_epi32(0x7fffffff));
    simde__m256i key;
    if (any_hit) {
        const simde__m256i far_first =
            simde_mm256_sub_epi32(simde_mm256_set1_epi32(0x7fffffff), bits);
        const simde__m256i leaf =
            simde_mm256_srai_epi32(simde_mm256_loadu_si256((const void *)info), 31);
        key = simde_mm256_andnot_si256(leaf, simde_mm256_and_si256(far_first, body));
    } else {
        key = simde_mm256_and_si256(bits, body);
    }
    key = simde_mm256_or_si256(key, slot);
    key = simde_mm256_or_si256(key, ~(simde__m256i)rt_vmask(m));
    const simde__m256i sorted = sw_sort8(key);
    /* Push the sorted keys k-1 .. 1 (farthest first): lane j of the pushed
     * vector takes sorted lane (k - 1 - j) & 7; lanes from k - 1 on are
     * written too, above the stack's top, and overwritten later. */
    const int k = (int)rt_lane_count(m);
    const simde__m256i seven = simde_mm256_set1_epi32(7);
    const simde__m256i back =
        simde_mm256_and_si256(simde_mm256_sub_epi32(simde_mm256_set1_epi32(k - 1), slot), seven);
    const simde__m256i lanes =
        simde_mm256_and_si256(simde_mm256_permutevar8x32_epi32(sorted, back), seven);
    const simde__m256i refs = simde_mm256_loadu_si256((const void *)child);
    const simde__m256i infos = simde_mm256_loadu_si256((const void *)info);
    simde_mm256_storeu_si256((void *)(st->ref + *sp),
                             simde_mm256_permutevar8x32_epi32(refs, lanes));
    simde_mm256_storeu_si256((void *)(st->info + *sp),
                             simde_mm256_permutevar8x32_epi32(infos, lanes));
    simde_mm256_storeu_si256((void *)(st->t + *sp),
                             simde_mm256_permutevar8x32_epi32((simde__m256i)tn, lanes));
    *sp += k - 1;
    const int first = simde_mm256_cvtsi256_si32(sorted) & 7;
    return sw_child(child[first], info[first]);
}
#endif

static int trace_instance(sw_ctx *x, rt_u32 inst, const rt_ray *r, const rt_ray_pre *p,
                          rt_hit_d *best);

/* rt_trace_mesh (top == 0: the tree of instance inst) and rt_trace's object
 * BVH loop (top == 1), from entry node 'entry', children nearest first (for
 * any-hit rays leaves first, then farthest first). A child pushed on the
 * stack is dropped when popped if its entry distance lies beyond the
 * range's upper end by then: its box test would now fail. Returns 1 when
 * an any-hit ray found a hit. */
static inline __attribute__((always_inline)) int traverse(sw_ctx *x, rt_u32 entry, rt_u32 inst,
                                                          const rt_ray *r, const rt_ray_pre *p,
                                                          rt_hit_d *best, const int top) {
    sw_ray rv;
    sw_ray_setup(r, p, &rv);
    sw_stack st;
    int sp = 0;
    rt_vf hi = range_hi(best->t);
    /* The entry node only tests the root's box: skipping a box test lets
     * a ray test more, never fewer, so the traversal starts at the root. */
    const uint32_t *en = x->nodes + (size_t)NODE_WORDS * entry;
    uint64_t cur = sw_child(en[6 * W], en[7 * W]);
    uint64_t boxes = 0;
    int found = 0;
#define RT_SW_REF(s) sw_child(child[s], info[s])
#define RT_SW_PUSH(s)                                                                              \
    do {                                                                                           \
        st.ref[sp] = child[s];                                                                     \
        st.info[sp] = info[s];                                                                     \
        st.t[sp++] = d[s];                                                                         \
    } while (0)
    for (;;) {
        const rt_u32 ref = (rt_u32)cur, cinfo = (rt_u32)(cur >> 32);
        if (cinfo & RT_NODE_LEAF_FLAG) {
            const rt_u32 count = cinfo & RT_NODE_COUNT_MASK;
            if (top) {
                for (rt_u32 e = ref; e < ref + count && !found; e++)
                    found = trace_instance(x, x->s->inst_ids[e], r, p, best);
            } else {
                found = leaf_test(x, ref, count, inst, r, p, best);
            }
            if (found) break;
            hi = range_hi(best->t);
        } else {
            const uint32_t *n = x->nodes + (size_t)NODE_WORDS * ref;
            rt_vf tn;
            uint32_t real, m = node_test(n, &rv, hi, &tn, &real);
            boxes += rt_lane_run(real);
            if (m) {
                const uint32_t *child = n + 6 * W, *info = n + 7 * W;
                /* In a tree larger than a core's L2, every entered child's
                 * lines are fetched now, while the nearest is traversed
                 * (the others are probably next). */
                if (x->prefetch)
                    for (uint32_t f = m; f; f &= f - 1)
                        prefetch(x, child, info, rt_lane_first(f), top);
                const int s0 = rt_lane_first(m);
                if (!(m & (m - 1))) { /* one child: on with it */
                    cur = RT_SW_REF(s0);
                    continue;
                }
#if RT_SW_VECTOR_ORDER
                /* Three or more (any hit: two or more) by the network. */
                const uint32_t m1 = m & (m - 1);
                if (x->any_hit || (m1 & (m1 - 1))) {
                    assert(sp + W <= SW_STACK);
                    cur = sw_order(m, tn, child, info, x->any_hit, &st, &sp);
                    continue;
                }
#endif
                float d[W];
                memcpy(d, &tn, sizeof d);
                if (x->any_hit) {
                    /* Any order gives the same answer; measured fastest:
                     * leaves first (one may end the ray at once), then
                     * inner nodes, each farthest entry first (a ray that
                     * leaves a surface enters the boxes around its origin
                     * first, which it mostly does not hit; the far boxes
                     * hold what occludes it: about a third fewer box tests
                     * than slot order and half of nearest first on the
                     * shared scenes' diffuse bounces). */
                    const uint32_t leaves = m & rt_vbits(rt_vload_i(info) < rt_vsplat_i(0));
                    const uint32_t inner = m & ~leaves;
                    int order[W], k = 0;
                    for (uint32_t q = leaves; q; q &= q - 1) order[k++] = rt_lane_first(q);
                    const int k0 = k;
                    for (uint32_t q = inner; q; q &= q - 1) {
                        const int c = rt_lane_first(q);
                        int i = k++;
                        while (i > k0 && d[order[i - 1]] < d[c]) {
                            order[i] = order[i - 1];
                            i--;
                        }
                        order[i] = c;
                    }
                    for (int i = k - 1; i > 0; i--) RT_SW_PUSH(order[i]);
                    cur = RT_SW_REF(order[0]);
                    continue;
                }
                m &= m - 1;
                const int s1 = rt_lane_first(m);
                m &= m - 1;
                if (!m) { /* two: the nearer first */
                    const int near = !(d[s1] < d[s0]) ? s0 : s1;
                    RT_SW_PUSH(near == s0 ? s1 : s0);
                    cur = RT_SW_REF(near);
                    continue;
                }
                /* Nearest first: sort the entered children by entry
                 * distance, push all but the nearest, farthest first. */
                int order[W], h = 2;
                order[0] = d[s1] < d[s0] ? s1 : s0;
                order[1] = order[0] == s0 ? s1 : s0;
                for (; m; m &= m - 1) {
                    const int s = rt_lane_first(m);
                    int i = h++;
                    while (i > 0 && d[order[i - 1]] > d[s]) {
                        order[i] = order[i - 1];
                        i--;
                    }
                    order[i] = s;
                }
                assert(sp + h - 1 <= SW_STACK - W);
                for (int i = h - 1; i > 0; i--) RT_SW_PUSH(order[i]);
                cur = RT_SW_REF(order[0]);
                continue;
            }
        }
        /* The next pushed child whose box test could still pass (a NaN hi
         * drops nothing, as in rt_box_test). */
        while (sp > 0 && st.t[sp - 1] > hi[0]) sp--;
        if (sp == 0) break;
        sp--;
        cur = sw_child(st.ref[sp], st.info[sp]);
    }
#undef RT_SW_REF
#undef RT_SW_PUSH
    x->box_tests += boxes;
    return found;
}

/* rt_trace_instance: the ray moved into the instance's space unless it is
 * the identity. */
static int trace_instance(sw_ctx *x, rt_u32 inst, const rt_ray *r, const rt_ray_pre *p,
                          rt_hit_d *best) {
    const rt_instance *in = &x->s->instances[inst];
    /* rt_trace_masked's mask test, where the traversal reaches an instance
     * (its object BVH leaf, or the single instance). */
    if (!(x->ray_mask & in->mask)) return 0;
    if (RT_INST_FLAGS(in) & RT_INST_KD) {
        /* A kd-tree mesh: no wide traversal for it, so the ray goes through
         * the oracle's (rt_trace_instance, kernels/rt_kd.h) from its best hit
         * so far; what it finds is the oracle's by construction. */
        rt_counters c = {0, 0, 0};
        const int done = rt_trace_instance(x->s, inst, r, p, x->ray_mask, x->any_hit, best, &c);
        x->box_tests += c.box_tests;
        x->tri_tests += c.tri_tests;
        return done;
    }
    const rt_u32 entry = x->inst_root[inst];
    /* A mesh whose root is a leaf (a wall, a box) is that leaf's blocks:
     * no traversal to set up (skipping the root's box test only lets the
     * ray test more). */
    const uint32_t *en = x->nodes + (size_t)NODE_WORDS * entry;
    const rt_u32 root_info = en[7 * W];
    /* rt_trace_instance's instance box, for rt_hit_accepted. */
    float inst_lo = -RT_INF;
    if (!(RT_SCENE_FLAGS(x->s) & RT_SCENE_SINGLE) && !rt_inst_enter(in, r, p, &inst_lo)) return 0;
    rt_ray o;
    rt_ray_pre op;
    r = rt_cpu_instance_ray(in, r, p, inst_lo, &o, &op);
    p = &op;
    if (root_info & RT_NODE_LEAF_FLAG)
        return leaf_test(x, en[6 * W], root_info & RT_NODE_COUNT_MASK, inst, r, p, best);
    return traverse(x, entry, inst, r, p, best, 0);
}

/* rt_trace. */
static void trace_one(sw_ctx *x, const rt_wide_bvh *b, const rt_ray *r, rt_hit_d *best) {
    rt_ray_pre p;
    rt_ray_prepare(r, &p);
    rt_hit_init(best, r);
    if (x->s->hdr->instance_count == 0) return;
    if (RT_SCENE_FLAGS(x->s) & RT_SCENE_SINGLE) {
        trace_instance(x, 0, r, &p, best);
        return;
    }
    traverse(x, b->top, RT_NO_HIT, r, &p, best, 1);
}

/* This build's entry point (rt_sw_tracer.trace). */
void RT_SW_TRACE(const rt_scene_view *s, const rt_wide_bvh *b, const rt_ray *rays,
                 const uint32_t *masks, size_t n, int any_hit, rt_hit_d *hits, rt_counters *c);
void RT_SW_TRACE(const rt_scene_view *s, const rt_wide_bvh *b, const rt_ray *rays,
                 const uint32_t *masks, size_t n, int any_hit, rt_hit_d *hits, rt_counters *c) {
    assert(b->shape.width == W && b->shape.blocks);
    sw_ctx x = {s,       b->nodes, b->blocks, b->inst_root, s->hdr->tri_method,
                any_hit, 0,        0,         0xffffffffu,  0};
    x.prefetch = ((uint64_t)b->node_count * NODE_WORDS + (uint64_t)b->block_count * BLOCK_WORDS) *
                     sizeof(uint32_t) >
                 RT_SW_PREFETCH_BYTES;
    for (size_t i = 0; i < n; i++) {
        if (masks) x.ray_mask = masks[i];
        trace_one(&x, b, &rays[i], &hits[i]);
    }
    c->rays += (rt_u32)n;
    c->box_tests += (rt_u32)x.box_tests;
    c->tri_tests += (rt_u32)x.tri_tests;
}

extern const rt_sw_tracer RT_ISA_SYMBOL(rt_sw_tracer);
const rt_sw_tracer RT_ISA_SYMBOL(rt_sw_tracer) = {W, RT_SW_TRACE};
