/* packet_trace.c - RT_PK_LANES rays through the two-level BVH together
 * (packet_trace.h), four lanes per NEON vector.
 *
 * Every vector operation below is the scalar oracle's operation on each lane
 * (kernels/rt_shared.h, named at each function), in the same order, so each
 * lane's values are the oracle's bits. Comparisons select with vbslq rather
 * than vminq/vmaxq: that is the oracle's 'a < b ? a : b' with its NaN
 * behaviour, and SIMDe on x86 turns NEON min/max into NaN-checking loops. */
#include "packet_trace.h"

#include <string.h>

#include "simd_neon.h"

enum { L = RT_PK_LANES, G = RT_PK_GROUPS };

/* The packet's rays in one space: the world, or an instance's object space. */
typedef struct pk_geom {
    float32x4_t org[3][G], inv[3][G];
    uint32x4_t neg[3][G]; /* all ones where the lane's inv < 0 */
    float32x4_t lo[G];    /* rt_box_lo(tmin) */
    float32x4_t tmin[G];
    float32x4_t sx[G], sy[G], sz[G];
    int perm[G][3];  /* the watertight axes kx, ky, kz when the group's lanes
                        agree on them, else perm[g][0] = -1 */
    int uniform;     /* all lanes share the sign of inv on every axis ... */
    int neg_axis[3]; /* ... and these are the signs */
    /* The packet's bounds for the interval test (pk_ia_miss): the range of
     * every lane's org and inv per axis and the least rt_box_lo(tmin); only
     * when 'uniform' and every inv is finite (ia). */
    int ia;
    float org_min[3], org_max[3], inv_min[3], inv_max[3], lo_min;
    rt_ray_d ray[L];
    rt_ray_pre pre[L];
} pk_geom;

typedef struct pk_state {
    const rt_scene_view *s;
    _Alignas(16) float t[L];  /* the best hit's t (the ray's tmax at first) */
    _Alignas(16) float hi[L]; /* rt_box_hi(t) */
    rt_hit_d *hit;
    rt_pk_counts *counts;
    _Alignas(16) uint32_t box[L], tri[L]; /* tests per lane */
    uint32_t alive[G];                    /* lanes of each group still tracing */
    uint32_t alive_groups;                /* groups with a lane alive */
    float hi_max;                         /* the greatest of hi */
    int any_hit;
    rt_u32 method;
} pk_state;

/* ones[m]: 1 in the lanes whose bit is set in m. */
static const uint32_t ones[16][4] = {{0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {1, 1, 0, 0},
                                     {0, 0, 1, 0}, {1, 0, 1, 0}, {0, 1, 1, 0}, {1, 1, 1, 0},
                                     {0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {1, 1, 0, 1},
                                     {0, 0, 1, 1}, {1, 0, 1, 1}, {0, 1, 1, 1}, {1, 1, 1, 1}};

static inline void count(uint32_t *per_lane, int g, uint32_t m) {
    vst1q_u32(per_lane + 4 * g, vaddq_u32(vld1q_u32(per_lane + 4 * g), vld1q_u32(ones[m])));
}

static inline int lowest_bit(uint32_t m) {
    return __builtin_ctz(m);
}

/* ---- set-up --------------------------------------------------------------- */

/* Per lane rt_ray_prepare, then the vectors; invalid lanes hold a copy of a
 * valid lane's ray, so that every lane computes on real numbers. */
static void pk_geom_setup(pk_geom *p, const rt_ray_d *ray, uint32_t valid) {
    int src = valid ? lowest_bit(valid) : 0;
    for (int l = 0; l < L; l++) {
        p->ray[l] = ray[(valid >> l) & 1u ? l : src];
        rt_ray_prepare(&p->ray[l], &p->pre[l]);
    }
    for (int k = 0; k < 3; k++) p->neg_axis[k] = p->pre[0].sign[k];
    p->uniform = 1;
    for (int g = 0; g < G; g++) {
        const rt_ray_d *r = &p->ray[4 * g];
        const rt_ray_pre *q = &p->pre[4 * g];
        float tmp[4];
        uint32_t neg[4];
        for (int k = 0; k < 3; k++) {
            for (int i = 0; i < 4; i++) tmp[i] = r[i].org[k];
            p->org[k][g] = vld1q_f32(tmp);
            for (int i = 0; i < 4; i++) tmp[i] = q[i].inv[k];
            p->inv[k][g] = vld1q_f32(tmp);
            for (int i = 0; i < 4; i++) {
                neg[i] = q[i].sign[k] ? 0xffffffffu : 0u;
                if (q[i].sign[k] != p->neg_axis[k]) p->uniform = 0;
            }
            p->neg[k][g] = vld1q_u32(neg);
        }
        for (int i = 0; i < 4; i++) tmp[i] = rt_box_lo(r[i].tmin);
        p->lo[g] = vld1q_f32(tmp);
        for (int i = 0; i < 4; i++) tmp[i] = r[i].tmin;
        p->tmin[g] = vld1q_f32(tmp);
        for (int i = 0; i < 4; i++) tmp[i] = q[i].sx;
        p->sx[g] = vld1q_f32(tmp);
        for (int i = 0; i < 4; i++) tmp[i] = q[i].sy;
        p->sy[g] = vld1q_f32(tmp);
        for (int i = 0; i < 4; i++) tmp[i] = q[i].sz;
        p->sz[g] = vld1q_f32(tmp);
        int same = 1;
        for (int i = 1; i < 4; i++)
            same &= q[i].kx == q[0].kx && q[i].ky == q[0].ky && q[i].kz == q[0].kz;
        p->perm[g][0] = same ? q[0].kx : -1;
        p->perm[g][1] = q[0].ky;
        p->perm[g][2] = q[0].kz;
    }
    p->ia = p->uniform;
    p->lo_min = RT_INF;
    for (int k = 0; k < 3; k++) {
        p->org_min[k] = p->inv_min[k] = RT_INF;
        p->org_max[k] = p->inv_max[k] = -RT_INF;
    }
    for (int l = 0; l < L; l++) {
        for (int k = 0; k < 3; k++) {
            float o = p->ray[l].org[k], iv = p->pre[l].inv[k];
            if (!(RT_FABS(iv) < RT_INF) || !(RT_FABS(o) < RT_INF)) p->ia = 0;
            p->org_min[k] = o < p->org_min[k] ? o : p->org_min[k];
            p->org_max[k] = o > p->org_max[k] ? o : p->org_max[k];
            p->inv_min[k] = iv < p->inv_min[k] ? iv : p->inv_min[k];
            p->inv_max[k] = iv > p->inv_max[k] ? iv : p->inv_max[k];
        }
        float lo = rt_box_lo(p->ray[l].tmin);
        if (!(lo == lo)) p->ia = 0;
        p->lo_min = lo < p->lo_min ? lo : p->lo_min;
    }
}

/* The least and the greatest of fl(x * y) over x in [x0, x1], y in [y0, y1]:
 * rounding is monotonic and x * y is bilinear, so both are at corners. */
static inline void corner_products(float x0, float x1, float y0, float y1, float *lo, float *hi) {
    float a = x0 * y0, b = x0 * y1, c = x1 * y0, d = x1 * y1;
    float m0 = a < b ? a : b, m1 = c < d ? c : d;
    float M0 = a > b ? a : b, M1 = c > d ? c : d;
    *lo = m0 < m1 ? m0 : m1;
    *hi = M0 > M1 ? M0 : M1;
}

/* Interval arithmetic over the whole packet (Wald, Boulos and Shirley 2007):
 * 1 when no lane's rt_box_test can pass for node n. Every lane computes
 * t0 = fl(fl(a - org) * inv) with its org and inv inside the packet's
 * ranges, so its t0 is at least the least corner product and its t1 at most
 * the greatest; its entry (the greatest t0, and its rt_box_lo(tmin)) is then
 * at least 'enter' below and its exit (the least t1, scaled as rt_box_test
 * scales it, and its rt_box_hi(t)) at most 'leave'. */
static inline int pk_ia_miss(const rt_node *n, const pk_geom *p, float hi_max) {
    float enter = p->lo_min, leave = RT_INF;
    for (int k = 0; k < 3; k++) {
        float a = p->neg_axis[k] ? n->bmax[k] : n->bmin[k];
        float b = p->neg_axis[k] ? n->bmin[k] : n->bmax[k];
        float t0lo, t0hi, t1lo, t1hi;
        corner_products(a - p->org_max[k], a - p->org_min[k], p->inv_min[k], p->inv_max[k], &t0lo,
                        &t0hi);
        corner_products(b - p->org_max[k], b - p->org_min[k], p->inv_min[k], p->inv_max[k], &t1lo,
                        &t1hi);
        enter = t0lo > enter ? t0lo : enter;
        leave = t1hi < leave ? t1hi : leave;
    }
    leave = leave * (leave < 0.0f ? RT_BOX_FAR_SCALE_NEG : RT_BOX_FAR_SCALE);
    leave = hi_max < leave ? hi_max : leave;
    return enter > leave;
}

/* ---- box test: rt_box_test on the four lanes of group g -------------------- */

static inline uint32_t pk_box(const rt_node *n, const pk_geom *p, const pk_state *st, int g,
                              float32x4_t *tnear) {
    float32x4_t lo = p->lo[g], hi = vdupq_n_f32(RT_INF);
    for (int k = 0; k < 3; k++) {
        float32x4_t a, b;
        if (p->uniform) {
            a = vdupq_n_f32(p->neg_axis[k] ? n->bmax[k] : n->bmin[k]);
            b = vdupq_n_f32(p->neg_axis[k] ? n->bmin[k] : n->bmax[k]);
        } else {
            float32x4_t bmin = vdupq_n_f32(n->bmin[k]), bmax = vdupq_n_f32(n->bmax[k]);
            a = vbslq_f32(p->neg[k][g], bmax, bmin);
            b = vbslq_f32(p->neg[k][g], bmin, bmax);
        }
        float32x4_t t0 = vmulq_f32(vsubq_f32(a, p->org[k][g]), p->inv[k][g]);
        float32x4_t t1 = vmulq_f32(vsubq_f32(b, p->org[k][g]), p->inv[k][g]);
        lo = vbslq_f32(vcgtq_f32(t0, lo), t0, lo);
        hi = vbslq_f32(vcltq_f32(t1, hi), t1, hi);
    }
    float32x4_t scale = vbslq_f32(vcltq_f32(hi, vdupq_n_f32(0.0f)),
                                  vdupq_n_f32(RT_BOX_FAR_SCALE_NEG), vdupq_n_f32(RT_BOX_FAR_SCALE));
    hi = vmulq_f32(hi, scale);
    float32x4_t ht = vld1q_f32(st->hi + 4 * g);
    hi = vbslq_f32(vcltq_f32(ht, hi), ht, hi);
    *tnear = lo;
    return rt_lane_bits(vcleq_f32(lo, hi)) & st->alive[g];
}

/* The first group from 'first' on with a lane that enters node n, or -1;
 * *mask gets that group's entering lanes, *tnear their entry distances. */
static inline int pk_enter(const rt_node *n, const pk_geom *p, pk_state *st, int first,
                           uint32_t *mask, float32x4_t *tnear) {
    int tested = 0;
    for (int g = first; g < G; g++) {
        uint32_t alive = st->alive[g];
        if (!alive) continue;
        /* After one group missed, one interval test may cull the rest. */
        if (tested++ == 1 && p->ia && pk_ia_miss(n, p, st->hi_max)) return -1;
        st->counts->group_box_tests++;
        count(st->box, g, alive);
        uint32_t m = pk_box(n, p, st, g, tnear);
        if (m) {
            *mask = m;
            return g;
        }
    }
    return -1;
}

/* ---- triangles -------------------------------------------------------------- */

/* Records lane l's hit on entry e at t, as rt_leaf_test accepts it. */
static void pk_accept(pk_state *st, int l, rt_u32 e, rt_u32 inst, float t, float u, float v) {
    rt_hit_d *h = &st->hit[l];
    h->t = t;
    h->u = u;
    h->v = v;
    h->prim = st->s->tri_ids[e];
    h->inst = inst;
    h->entry = e;
    if (st->any_hit) {
        st->alive[l >> 2] &= ~(1u << (l & 3));
        if (!st->alive[l >> 2]) st->alive_groups &= ~(1u << (l >> 2));
        return;
    }
    st->t[l] = t;
    st->hi[l] = rt_box_hi(t);
    float m = st->hi[0];
    for (int i = 1; i < L; i++) m = st->hi[i] > m ? st->hi[i] : m;
    st->hi_max = m;
}

/* The lanes of m in group g through the shared scalar test (rt_leaf_test's
 * body): other triangle tests, groups whose lanes disagree on the watertight
 * axes, and lanes that need the watertight test's exact re-check. */
static void pk_tri_lanes(pk_state *st, const pk_geom *p, int g, uint32_t m, rt_u32 e, rt_u32 inst) {
    const rt_tri *tri = &st->s->tris[e];
    for (; m; m &= m - 1) {
        int l = 4 * g + lowest_bit(m);
        float t, u, v;
        if (!rt_tri_test(st->method, tri, &p->ray[l], &p->pre[l], p->ray[l].tmin, st->t[l], &t, &u,
                         &v))
            continue;
        if (st->any_hit || rt_hit_before(t, inst, st->s->tri_ids[e], &st->hit[l]))
            pk_accept(st, l, e, inst, t, u, v);
    }
}

/* rt_tri_watertight on the lanes of m in group g against entry e. */
static void pk_tri(pk_state *st, const pk_geom *p, int g, uint32_t m, rt_u32 e, rt_u32 inst) {
    st->counts->group_tri_tests++;
    count(st->tri, g, m);
    const int kx = p->perm[g][0], ky = p->perm[g][1], kz = p->perm[g][2];
    if (st->method != RT_TRI_WATERTIGHT || kx < 0) {
        pk_tri_lanes(st, p, g, m, e, inst);
        return;
    }
    const rt_tri *tri = &st->s->tris[e];
    const float32x4_t ox = p->org[kx][g], oy = p->org[ky][g], oz = p->org[kz][g];
    const float32x4_t sx = p->sx[g], sy = p->sy[g];
    float32x4_t Az = vsubq_f32(vdupq_n_f32(tri->v0[kz]), oz);
    float32x4_t Bz = vsubq_f32(vdupq_n_f32(tri->v1[kz]), oz);
    float32x4_t Cz = vsubq_f32(vdupq_n_f32(tri->v2[kz]), oz);
    float32x4_t Ax = vsubq_f32(vsubq_f32(vdupq_n_f32(tri->v0[kx]), ox), vmulq_f32(sx, Az));
    float32x4_t Ay = vsubq_f32(vsubq_f32(vdupq_n_f32(tri->v0[ky]), oy), vmulq_f32(sy, Az));
    float32x4_t Bx = vsubq_f32(vsubq_f32(vdupq_n_f32(tri->v1[kx]), ox), vmulq_f32(sx, Bz));
    float32x4_t By = vsubq_f32(vsubq_f32(vdupq_n_f32(tri->v1[ky]), oy), vmulq_f32(sy, Bz));
    float32x4_t Cx = vsubq_f32(vsubq_f32(vdupq_n_f32(tri->v2[kx]), ox), vmulq_f32(sx, Cz));
    float32x4_t Cy = vsubq_f32(vsubq_f32(vdupq_n_f32(tri->v2[ky]), oy), vmulq_f32(sy, Cz));
    float32x4_t U = vsubq_f32(vmulq_f32(Cx, By), vmulq_f32(Cy, Bx));
    float32x4_t V = vsubq_f32(vmulq_f32(Ax, Cy), vmulq_f32(Ay, Cx));
    float32x4_t W = vsubq_f32(vmulq_f32(Bx, Ay), vmulq_f32(By, Ax));
    const float32x4_t zero = vdupq_n_f32(0.0f);
    /* An edge function of exactly zero takes the oracle's exact re-check. */
    uint32x4_t z = vorrq_u32(vorrq_u32(vceqq_f32(U, zero), vceqq_f32(V, zero)), vceqq_f32(W, zero));
    uint32_t zl = rt_lane_bits(z) & m;
    if (zl) {
        pk_tri_lanes(st, p, g, zl, e, inst);
        m &= ~zl;
    }
    uint32x4_t below =
        vorrq_u32(vorrq_u32(vcltq_f32(U, zero), vcltq_f32(V, zero)), vcltq_f32(W, zero));
    uint32x4_t above =
        vorrq_u32(vorrq_u32(vcgtq_f32(U, zero), vcgtq_f32(V, zero)), vcgtq_f32(W, zero));
    float32x4_t det = vaddq_f32(vaddq_f32(U, V), W);
    uint32x4_t out = vorrq_u32(vandq_u32(below, above), vceqq_f32(det, zero));
    uint32_t inside = ~rt_lane_bits(out) & m;
    if (!inside) return;
    /* The oracle's Az = sz * A[kz], its T and its t. */
    const float32x4_t sz = p->sz[g];
    float32x4_t T =
        vaddq_f32(vaddq_f32(vmulq_f32(U, vmulq_f32(sz, Az)), vmulq_f32(V, vmulq_f32(sz, Bz))),
                  vmulq_f32(W, vmulq_f32(sz, Cz)));
    float32x4_t t = rt_div_f32(T, det);
    uint32x4_t in_range =
        vandq_u32(vcgeq_f32(t, p->tmin[g]), vcleq_f32(t, vld1q_f32(st->t + 4 * g)));
    uint32_t hit = rt_lane_bits(in_range) & inside;
    if (!hit) return;
    float tl[4], vl[4], wl[4], dl[4];
    vst1q_f32(tl, t);
    vst1q_f32(vl, V);
    vst1q_f32(wl, W);
    vst1q_f32(dl, det);
    rt_u32 prim = st->s->tri_ids[e];
    for (; hit; hit &= hit - 1) {
        int i = lowest_bit(hit), l = 4 * g + i;
        if (st->any_hit || rt_hit_before(tl[i], inst, prim, &st->hit[l]))
            pk_accept(st, l, e, inst, tl[i], RT_DIV(vl[i], dl[i]), RT_DIV(wl[i], dl[i]));
    }
}

/* A leaf of a mesh BVH: every group from 'first' on whose lanes enter its
 * box tests its triangles (group 'first' entered with first_mask). */
static void pk_leaf(pk_state *st, const pk_geom *p, const rt_node *n, rt_u32 inst, int first,
                    uint32_t first_mask) {
    const rt_u32 begin = n->a, end = n->a + (n->b & RT_NODE_COUNT_MASK);
    for (int g = first; g < G; g++) {
        uint32_t m;
        if (g == first) {
            m = first_mask & st->alive[g];
        } else {
            if (!st->alive[g]) continue;
            float32x4_t tn;
            st->counts->group_box_tests++;
            count(st->box, g, st->alive[g]);
            m = pk_box(n, p, st, g, &tn);
        }
        for (rt_u32 e = begin; e < end && m; e++) {
            pk_tri(st, p, g, m, e, inst);
            m &= st->alive[g];
        }
    }
}

/* ---- traversal -------------------------------------------------------------- */

static void pk_instance(pk_state *st, const pk_geom *world, rt_u32 inst, int first);

/* Is child 1 nearer than child 0 for the packet? Judged by the entry
 * distances of the first lane that enters both (or child 0), as the 2x2
 * packets of Langr 2016 do; the order changes speed, never the hits. */
static inline int second_nearer(int f0, int f1, uint32_t m0, uint32_t m1, float32x4_t t0,
                                float32x4_t t1) {
    if (f0 != f1) return f1 < f0;
    float a[4], b[4];
    vst1q_f32(a, t0);
    vst1q_f32(b, t1);
    int i = lowest_bit((m0 & m1) ? (m0 & m1) : m0);
    return b[i] < a[i];
}

/* One BVH from 'root': a mesh's (inst is its instance) or the object BVH
 * (inst == RT_NO_HIT), whose leaves hand their instances to pk_instance.
 * rt_trace_mesh's and rt_trace's loops, for the packet. */
static void pk_bvh(pk_state *st, const pk_geom *p, rt_u32 root, rt_u32 inst, int first) {
    const rt_node *nodes = st->s->nodes;
    struct {
        rt_u32 node;
        int first;
        uint32_t mask;
    } stack[RT_STACK_SIZE];
    int sp = 0;
    uint32_t mask = 0;
    float32x4_t tn;
    first = pk_enter(&nodes[root], p, st, first, &mask, &tn);
    if (first < 0) return;
    rt_u32 node = root;
    for (;;) {
        const rt_node *n = &nodes[node];
        if (n->b & RT_NODE_LEAF_FLAG) {
            if (inst == RT_NO_HIT) {
                for (rt_u32 e = n->a; e < n->a + (n->b & RT_NODE_COUNT_MASK); e++) {
                    pk_instance(st, p, st->s->inst_ids[e], first);
                    if (!st->alive_groups) return;
                }
            } else {
                pk_leaf(st, p, n, inst, first, mask);
                if (!st->alive_groups) return;
            }
        } else {
            uint32_t m0 = 0, m1 = 0;
            float32x4_t t0, t1;
            int f0 = pk_enter(&nodes[n->a], p, st, first, &m0, &t0);
            int f1 = pk_enter(&nodes[n->b], p, st, first, &m1, &t1);
            if (f0 >= 0 && f1 >= 0) {
                int swap = second_nearer(f0, f1, m0, m1, t0, t1);
                stack[sp].node = swap ? n->a : n->b;
                stack[sp].first = swap ? f0 : f1;
                stack[sp].mask = swap ? m0 : m1;
                sp++;
                node = swap ? n->b : n->a;
                first = swap ? f1 : f0;
                mask = swap ? m1 : m0;
                continue;
            }
            if (f0 >= 0 || f1 >= 0) {
                node = f0 >= 0 ? n->a : n->b;
                first = f0 >= 0 ? f0 : f1;
                mask = f0 >= 0 ? m0 : m1;
                continue;
            }
        }
        if (sp == 0) return;
        --sp;
        node = stack[sp].node;
        first = stack[sp].first;
        mask = stack[sp].mask;
    }
}

/* One instance for the groups from 'first' on: the same rays when it is the
 * identity, else each lane's ray moved into object space as rt_trace_instance
 * moves it. */
static void pk_instance(pk_state *st, const pk_geom *world, rt_u32 inst, int first) {
    const rt_instance *in = &st->s->instances[inst];
    if (in->flags & RT_INST_IDENTITY) {
        pk_bvh(st, world, in->root, inst, first);
        return;
    }
    pk_geom obj;
    rt_ray_d ray[L];
    for (int l = 0; l < L; l++) rt_ray_to_object(in, &world->ray[l], &ray[l]);
    pk_geom_setup(&obj, ray, (1u << L) - 1u);
    pk_bvh(st, &obj, in->root, inst, first);
}

void rt_pk_trace(const rt_scene_view *s, const rt_pk_rays *rays, int any_hit, rt_hit_d *hits,
                 rt_pk_counts *counts) {
    pk_state st;
    st.s = s;
    st.hit = hits;
    st.counts = counts;
    st.any_hit = any_hit;
    st.method = s->hdr->tri_method;
    st.alive_groups = 0;
    for (int l = 0; l < L; l++) {
        st.box[l] = st.tri[l] = 0;
        if ((rays->valid >> l) & 1u) {
            rt_hit_init(&hits[l], &rays->ray[l]);
            counts->c[l].rays++;
        } else { /* a miss, with no ray to take tmax from */
            memset(&hits[l], 0, sizeof hits[l]);
            hits[l].t = RT_INF;
            hits[l].prim = hits[l].inst = hits[l].entry = RT_NO_HIT;
        }
        st.t[l] = hits[l].t;
        st.hi[l] = rt_box_hi(st.t[l]);
    }
    st.hi_max = st.hi[0];
    for (int l = 1; l < L; l++) st.hi_max = st.hi[l] > st.hi_max ? st.hi[l] : st.hi_max;
    for (int g = 0; g < G; g++) {
        st.alive[g] = (rays->valid >> (4 * g)) & 15u;
        if (st.alive[g]) st.alive_groups |= 1u << g;
    }
    if (!rays->valid || s->hdr->instance_count == 0) return;
    pk_geom world;
    pk_geom_setup(&world, rays->ray, rays->valid);
    if (s->hdr->flags & RT_SCENE_SINGLE)
        pk_instance(&st, &world, 0, 0);
    else
        pk_bvh(&st, &world, s->hdr->top_root, RT_NO_HIT, 0);
    for (int l = 0; l < L; l++) {
        counts->c[l].box_tests += st.box[l];
        counts->c[l].tri_tests += st.tri[l];
    }
}
