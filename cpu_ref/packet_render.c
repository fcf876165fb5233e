/* packet_render.c - the thesis's packet path (Langr 2016, section 3.2.6):
 * 2x2 rays traverse the BVHs together, their box tests four lanes at a time
 * through NEON (host/simd_neon.h), threads over interlaced strips.
 *
 * Bit-identical to the scalar oracle by construction: each lane's box test
 * performs the scalar test's operations in the same order (no FMA), so a lane
 * never culls a node that holds its closest hit; triangle tests are the shared
 * scalar ones per lane; the total hit order makes the closest hit independent
 * of the visiting order; shading after the primary hit is the shared
 * rt_shade_hit. */
#include <stdlib.h>
#include <string.h>

#include "cpu_render.h"
#include "simd_neon.h"

typedef struct packet {
    rt_ray_d ray[4];
    rt_ray_pre pre[4];
    float32x4_t org[3], inv[3];
    uint32x4_t neg[3]; /* all ones where the lane's inv < 0 */
    float32x4_t lo;    /* rt_box_lo(tmin) per lane */
} packet;

static void packet_setup(packet *p) {
    float o[4], iv[4], lo[4];
    uint32_t ng[4];
    for (int k = 0; k < 3; k++) {
        for (int l = 0; l < 4; l++) {
            o[l] = p->ray[l].org[k];
            iv[l] = p->pre[l].inv[k];
            ng[l] = p->pre[l].sign[k] ? 0xffffffffu : 0u;
        }
        p->org[k] = vld1q_f32(o);
        p->inv[k] = vld1q_f32(iv);
        p->neg[k] = vld1q_u32(ng);
    }
    for (int l = 0; l < 4; l++) lo[l] = rt_box_lo(p->ray[l].tmin);
    p->lo = vld1q_f32(lo);
}

static uint32_t lane_bits(uint32x4_t m) {
    return (vgetq_lane_u32(m, 0) & 1u) | (vgetq_lane_u32(m, 1) & 2u) | (vgetq_lane_u32(m, 2) & 4u) |
           (vgetq_lane_u32(m, 3) & 8u);
}

/* rt_box_test on four lanes; returns the lanes of 'active' that hit. */
static uint32_t packet_box(const rt_node *n, const packet *p, float32x4_t hi_t, uint32_t active,
                           float tnear[4]) {
    float32x4_t lo = p->lo, hi = vdupq_n_f32(RT_INF);
    for (int k = 0; k < 3; k++) {
        float32x4_t bmin = vdupq_n_f32(n->bmin[k]), bmax = vdupq_n_f32(n->bmax[k]);
        float32x4_t a = vbslq_f32(p->neg[k], bmax, bmin);
        float32x4_t b = vbslq_f32(p->neg[k], bmin, bmax);
        float32x4_t t0 = vmulq_f32(vsubq_f32(a, p->org[k]), p->inv[k]);
        float32x4_t t1 = vmulq_f32(vsubq_f32(b, p->org[k]), p->inv[k]);
        lo = vbslq_f32(vcgtq_f32(t0, lo), t0, lo);
        hi = vbslq_f32(vcltq_f32(t1, hi), t1, hi);
    }
    float32x4_t scale = vbslq_f32(vcltq_f32(hi, vdupq_n_f32(0.0f)),
                                  vdupq_n_f32(RT_BOX_FAR_SCALE_NEG), vdupq_n_f32(RT_BOX_FAR_SCALE));
    hi = vmulq_f32(hi, scale); /* as rt_box_test: widened for negative t too */
    hi = vbslq_f32(vcltq_f32(hi_t, hi), hi_t, hi);
    vst1q_f32(tnear, lo);
    return lane_bits(vcleq_f32(lo, hi)) & active;
}

typedef struct packet_state {
    const rt_scene_view *s;
    rt_hit_d hit[4];
    rt_counters c[4];
    uint32_t done; /* any-hit lanes that found an occluder */
    int any_hit;
    uint64_t packet_box_tests;
} packet_state;

/* The box range's upper end per lane: rt_box_hi(best t). */
static float32x4_t packet_hi(const packet_state *st) {
    float t[4] = {st->hit[0].t, st->hit[1].t, st->hit[2].t, st->hit[3].t};
    float32x4_t bt = vld1q_f32(t);
    return vaddq_f32(bt, vmulq_f32(vabsq_f32(bt), vdupq_n_f32(RT_BOX_T_MARGIN)));
}

static void count_boxes(packet_state *st, uint32_t mask) {
    st->packet_box_tests++;
    for (int l = 0; l < 4; l++)
        if (mask & (1u << l)) st->c[l].box_tests++;
}

static void packet_instance(packet_state *st, const packet *world, rt_u32 inst, uint32_t active);

/* Traverses one BVH with the lanes in 'active': a mesh's (inst is its
 * instance), or the object BVH (inst == RT_NO_HIT), whose leaves hand each
 * instance to packet_instance. */
static void packet_mesh(packet_state *st, const packet *p, rt_u32 root, rt_u32 inst,
                        uint32_t active) {
    const rt_scene_view *s = st->s;
    rt_u32 stack_node[RT_STACK_SIZE];
    uint32_t stack_mask[RT_STACK_SIZE];
    int sp = 0;
    float tn0[4], tn1[4];
    active &= ~st->done;
    count_boxes(st, active);
    uint32_t mask = packet_box(&s->nodes[root], p, packet_hi(st), active, tn0);
    rt_u32 node = root;
    while (mask) {
        const rt_node *n = &s->nodes[node];
        if (n->b & RT_NODE_LEAF_FLAG) {
            if (inst == RT_NO_HIT) {
                for (rt_u32 e = n->a; e < n->a + (n->b & RT_NODE_COUNT_MASK); e++)
                    packet_instance(st, p, s->inst_ids[e], mask);
            } else {
                for (int l = 0; l < 4; l++) {
                    if (!(mask & (1u << l)) || (st->done & (1u << l))) continue;
                    if (rt_leaf_test(s, n->a, n->b & RT_NODE_COUNT_MASK, inst, &p->ray[l],
                                     &p->pre[l], st->any_hit, &st->hit[l], &st->c[l]))
                        st->done |= 1u << l;
                }
            }
            mask = 0;
        } else {
            float32x4_t hi = packet_hi(st);
            mask &= ~st->done;
            count_boxes(st, mask);
            count_boxes(st, mask);
            uint32_t m0 = packet_box(&s->nodes[n->a], p, hi, mask, tn0);
            uint32_t m1 = packet_box(&s->nodes[n->b], p, hi, mask, tn1);
            if (m0 && m1) {
                /* Nearer child first, judged by the first lane that hits both. */
                uint32_t both = m0 & m1;
                int l = both ? (both & 1 ? 0 : both & 2 ? 1 : both & 4 ? 2 : 3) : -1;
                int right_first = l >= 0 && tn1[l] < tn0[l];
                stack_node[sp] = right_first ? n->a : n->b;
                stack_mask[sp++] = right_first ? m0 : m1;
                node = right_first ? n->b : n->a;
                mask = right_first ? m1 : m0;
                continue;
            }
            node = m0 ? n->a : n->b;
            mask = m0 ? m0 : m1;
            if (mask) continue;
        }
        while (!mask && sp > 0) {
            --sp;
            node = stack_node[sp];
            mask = stack_mask[sp] & ~st->done;
        }
    }
}

/* One instance for the lanes in 'active': the same rays when the instance is
 * the identity, else each lane's ray transformed exactly as rt_trace does. */
static void packet_instance(packet_state *st, const packet *world, rt_u32 inst, uint32_t active) {
    const rt_instance *in = &st->s->instances[inst];
    if (in->flags & RT_INST_IDENTITY) {
        packet_mesh(st, world, in->root, inst, active);
        return;
    }
    packet op;
    for (int l = 0; l < 4; l++) {
        rt_ray_to_object(in, &world->ray[l], &op.ray[l]);
        rt_ray_prepare(&op.ray[l], &op.pre[l]);
    }
    packet_setup(&op);
    packet_mesh(st, &op, in->root, inst, active);
}

/* The two-level traversal for a packet. */
static void packet_trace(packet_state *st, const packet *p, uint32_t active) {
    const rt_scene_view *s = st->s;
    for (int l = 0; l < 4; l++) {
        rt_hit_init(&st->hit[l], &p->ray[l]);
        if (active & (1u << l)) st->c[l].rays++;
    }
    if (s->hdr->instance_count == 0) return;
    if (s->hdr->flags & RT_SCENE_SINGLE) {
        packet_instance(st, p, 0, active);
        return;
    }
    packet_mesh(st, p, s->hdr->top_root, RT_NO_HIT, active);
}

/* ---- rendering ------------------------------------------------------------ */

typedef struct packet_job {
    const rt_cpu_frame *frame;
    rt_cpu_counts *per_worker;
} packet_job;

static void packet_strips(void *ctx, int worker, int workers) {
    packet_job *job = ctx;
    const rt_cpu_frame *f = job->frame;
    rt_scene_view v = rt_flat_view(f->flat);
    const int w = v.hdr->width, h = v.hdr->height, strips = (h + 1) / 2;
    rt_cpu_counts *total = &job->per_worker[worker];
    packet_state st;
    memset(&st, 0, sizeof st);
    st.s = &v;
    for (int strip = worker; strip < strips; strip += workers) {
        int y0 = 2 * strip;
        for (int x0 = 0; x0 < w; x0 += 2) {
            packet p;
            uint32_t active = 0;
            for (int l = 0; l < 4; l++) {
                int x = x0 + (l & 1), y = y0 + (l >> 1);
                if (x < w && y < h) active |= 1u << l;
                rt_camera_ray(v.hdr, x < w ? x : x0, y < h ? y : y0, &p.ray[l]);
                rt_ray_prepare(&p.ray[l], &p.pre[l]);
            }
            packet_setup(&p);
            memset(st.c, 0, sizeof st.c);
            st.done = 0;
            st.packet_box_tests = 0;
            packet_trace(&st, &p, active);
            total->packets++;
            total->packet_box_tests += st.packet_box_tests;
            for (int l = 0; l < 4; l++) {
                if (!(active & (1u << l))) continue;
                int x = x0 + (l & 1), y = y0 + (l >> 1);
                rt_cpu_finish_pixel(f, &v, x, y, &p.ray[l], &st.hit[l], &st.c[l]);
                if (f->aov == RT_AOV_BOX_TESTS)
                    f->pixels[(size_t)y * w + x] = (float)st.c[l].box_tests;
                if (f->aov == RT_AOV_TRI_TESTS)
                    f->pixels[(size_t)y * w + x] = (float)st.c[l].tri_tests;
                total->rays += st.c[l].rays;
                total->box_tests += st.c[l].box_tests;
                total->tri_tests += st.c[l].tri_tests;
                total->primary_rays++;
            }
        }
        if (worker == 0 && f->progress) f->progress(f->progress_user, (double)(strip + 1) / strips);
    }
}

void rt_packet_render(const rt_cpu_frame *frame, rt_pool *pool, rt_cpu_counts *counts) {
    int workers = pool ? rt_pool_size(pool) : 1;
    packet_job job = {frame, calloc((size_t)workers, sizeof(rt_cpu_counts))};
    memset(counts, 0, sizeof *counts);
    if (!job.per_worker) return;
    if (pool)
        rt_pool_run(pool, packet_strips, &job);
    else
        packet_strips(&job, 0, 1);
    for (int i = 0; i < workers; i++) {
        counts->rays += job.per_worker[i].rays;
        counts->primary_rays += job.per_worker[i].primary_rays;
        counts->box_tests += job.per_worker[i].box_tests;
        counts->tri_tests += job.per_worker[i].tri_tests;
        counts->packets += job.per_worker[i].packets;
        counts->packet_box_tests += job.per_worker[i].packet_box_tests;
    }
    free(job.per_worker);
}

void rt_packet_trace_rays(const rt_flat *flat, const rt_ray_d *rays, size_t n, rt_hit_d *hits,
                          int any_hit, rt_counters *c) {
    rt_scene_view v = rt_flat_view(flat);
    packet_state st;
    memset(&st, 0, sizeof st);
    st.s = &v;
    st.any_hit = any_hit;
    for (size_t i = 0; i < n; i += 4) {
        packet p;
        uint32_t active = 0;
        for (int l = 0; l < 4; l++) {
            size_t j = i + (size_t)l < n ? i + (size_t)l : i;
            if (i + (size_t)l < n) active |= 1u << l;
            p.ray[l] = rays[j];
            rt_ray_prepare(&p.ray[l], &p.pre[l]);
        }
        packet_setup(&p);
        memset(st.c, 0, sizeof st.c);
        st.done = 0;
        packet_trace(&st, &p, active);
        for (int l = 0; l < 4 && i + (size_t)l < n; l++) {
            hits[i + (size_t)l] = st.hit[l];
            c->rays += st.c[l].rays;
            c->box_tests += st.c[l].box_tests;
            c->tri_tests += st.c[l].tri_tests;
        }
    }
}
