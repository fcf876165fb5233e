/* SPDX-License-Identifier: Apache-2.0 */
/* packet_render.c - the packet path (Langr 2016, section 3.2.6, with larger
 * packets): tiles of TILE_W x TILE_H pixels, one ray packet per tile
 * (cpu_ref/packet_trace.c), their shadow rays traced as packets too, blocks
 * of tiles taken by the pool's workers in turn.
 *
 * Bit-identical to the scalar oracle: the packet tracer gives each lane the
 * oracle's hit, and shading is the shared code (kernels/rt_shade.h) split
 * where the shadow rays are traced: rt_shade_begin per lane, per light
 * rt_phong_light per lane, one packet of shadow rays, rt_phong_add per
 * unoccluded lane, then rt_shade_end and the secondary rays per lane
 * (rt_shade_children). */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "cpu_render.h"
#include "packet_trace.h"
#include "ray_coherence.h"

/* A tile is one packet. Its lanes run in Morton order, so that every run
 * of 4, 8 or 16 lanes (one vector of the packet tracer) is a compact block
 * of pixels. */
enum { TILE_W = RT_PACKET_TILE_W, TILE_H = RT_PACKET_TILE_H };
_Static_assert(TILE_W *TILE_H == RT_PK_LANES, "a tile is one packet");
_Static_assert(TILE_W == TILE_H || TILE_W == 2 * TILE_H, "a Morton tile");

static void lane_pixel(int x0, int y0, int l, int *x, int *y) {
    int dx = 0, dy = 0;
    for (int b = 0; (1 << (2 * b)) < RT_PK_LANES; b++) {
        dx |= ((l >> (2 * b)) & 1) << b;
        dy |= ((l >> (2 * b + 1)) & 1) << b;
    }
    *x = x0 + dx;
    *y = y0 + dy;
}

static void add_counts(rt_cpu_counts *total, const rt_pk_counts *pc) {
    total->packet_box_tests += pc->group_box_tests;
    total->packet_tri_tests += pc->group_tri_tests;
    total->rays += pc->rays;
    total->box_tests += pc->box_tests;
    total->tri_tests += pc->tri_tests;
}

/* The shading of a tile's hits (the image, or the test-count AOVs, which
 * count the shading rays too): rt_shade_hit's steps with the shadow rays in
 * packets. */
static void shade_tile(const rt_cpu_frame *f, const rt_scene_view *v, const rt_pk_rays *primary,
                       const rt_pk_hits *hits, rt_pk_counts *pc, const int *px, const int *py) {
    rt_hit_d hit[RT_PK_LANES];
    rt_shade_entry e[RT_PK_LANES];
    rt_shade_node nd[RT_PK_LANES];
    rt_pk_mask lit = 0; /* lanes whose node has a Phong term */
    for (int l = 0; l < RT_PK_LANES; l++) {
        if (!((primary->valid >> l) & 1u)) continue;
        rt_pk_get_ray(primary, l, &e[l].ray);
        rt_pk_get_hit(hits, l, &hit[l]);
        e[l].w[0] = e[l].w[1] = e[l].w[2] = 1.0f;
        e[l].depth = 0;
        if (rt_shade_begin(v, &e[l], &hit[l], &nd[l])) lit |= (rt_pk_mask)1 << l;
    }
    for (rt_u32 li = 0; li < v->hdr->light_count && lit; li++) {
        rt_pk_rays shadow;
        memset(&shadow, 0, sizeof shadow); /* lanes without a ray hold zeros */
        rt_pk_hits occluder;
        float Ln[RT_PK_LANES][3], ndl[RT_PK_LANES];
        shadow.valid = 0;
        for (rt_pk_mask m = lit; m; m &= m - 1) {
            int l = __builtin_ctzll(m);
            rt_ray sr;
            if (rt_phong_light(v, &nd[l].sf, li, &sr, Ln[l], &ndl[l])) {
                rt_pk_set_ray(&shadow, l, &sr);
                shadow.valid |= (rt_pk_mask)1 << l;
            }
        }
        if (!shadow.valid) continue;
        rt_pk_trace(f->isa, v, f->wide, &shadow, 1, &occluder, pc);
        for (rt_pk_mask m = shadow.valid; m; m &= m - 1) {
            int l = __builtin_ctzll(m);
            if (occluder.prim[l] == RT_NO_HIT)
                rt_phong_add(v, &nd[l].sf, li, Ln[l], ndl[l], nd[l].dn, nd[l].lit);
        }
    }
    const int w = v->hdr->width;
    for (int l = 0; l < RT_PK_LANES; l++) {
        if (!((primary->valid >> l) & 1u)) continue;
        float term[3], rgb[3] = {0.0f, 0.0f, 0.0f};
        rt_shade_entry child[2];
        int has_term, children;
        rt_shade_end(v, &e[l], &hit[l], &nd[l], term, &has_term, child, &children);
        if (has_term)
            for (int k = 0; k < 3; k++) rgb[k] = rgb[k] + term[k];
        rt_counters sec = {0, 0, 0}; /* the secondary rays' */
        if (f->single)
            rt_single_shade_children(f, v, child, children, &sec, rgb);
        else
            rt_shade_children(v, child, children, &sec, rgb);
        pc->rays += sec.rays;
        pc->box_tests += sec.box_tests;
        pc->tri_tests += sec.tri_tests;
        size_t i = (size_t)py[l] * (size_t)w + (size_t)px[l];
        if (f->aov == RT_AOV_NONE)
            memcpy(f->pixels + 3 * i, rgb, sizeof rgb);
        else
            f->pixels[i] = (float)(f->aov == RT_AOV_BOX_TESTS ? pc->c[l].box_tests + sec.box_tests
                                                              : pc->c[l].tri_tests + sec.tri_tests);
    }
}

static void render_tile(const rt_cpu_frame *f, const rt_scene_view *v, int x0, int y0,
                        rt_cpu_counts *total) {
    const rt_scene_header *h = v->hdr;
    rt_pk_rays primary;
    rt_pk_hits hit;
    rt_pk_counts pc;
    int px[RT_PK_LANES], py[RT_PK_LANES];
    memset(&pc, 0, sizeof pc);
    memset(&primary, 0, sizeof primary); /* lanes outside the image hold zeros */
    pc.per_lane = f->aov == RT_AOV_BOX_TESTS || f->aov == RT_AOV_TRI_TESTS;
    /* rt_camera_ray's screen coordinates, once per column and row. */
    float sx[TILE_W], sy[TILE_H];
    for (int i = 0; i < TILE_W; i++) sx[i] = rt_camera_sx(h, x0 + i);
    for (int i = 0; i < TILE_H; i++) sy[i] = rt_camera_sy(h, y0 + i);
    for (int l = 0; l < RT_PK_LANES; l++) {
        lane_pixel(x0, y0, l, &px[l], &py[l]);
        if (px[l] >= h->width || py[l] >= h->height) continue;
        primary.valid |= (rt_pk_mask)1 << l;
        rt_ray r;
        rt_camera_ray_at(h, sx[px[l] - x0], sy[py[l] - y0], &r);
        rt_pk_set_ray(&primary, l, &r);
    }
    rt_pk_trace(f->isa, v, f->wide, &primary, 0, &hit, &pc);
    if (f->aov == RT_AOV_NONE || f->aov == RT_AOV_BOX_TESTS || f->aov == RT_AOV_TRI_TESTS) {
        shade_tile(f, v, &primary, &hit, &pc, px, py);
    } else {
        for (rt_pk_mask m = primary.valid; m; m &= m - 1) {
            int l = __builtin_ctzll(m);
            rt_ray r;
            rt_hit_d hl;
            rt_pk_get_ray(&primary, l, &r);
            rt_pk_get_hit(&hit, l, &hl);
            rt_cpu_finish_pixel(f, v, px[l], py[l], &r, &hl, &pc.c[l]);
        }
    }
    total->packets++;
    total->primary_rays += (uint64_t)__builtin_popcountll(primary.valid);
    add_counts(total, &pc);
}

/* ---- the frame ---------------------------------------------------------------- */

/* Tiles are taken in blocks of BLOCK x BLOCK tiles, in rows of blocks: the
 * tiles traced one after another then lie close together and find their
 * BVH nodes still in cache (a row of tiles would come back to its
 * neighbours below a whole image width later). */
enum { BLOCK = 4 };

typedef struct packet_job {
    const rt_cpu_frame *frame;
    rt_cpu_counts *per_worker;
    atomic_int next_block;
} packet_job;

static void packet_blocks(void *ctx, int worker, int workers) {
    (void)workers;
    packet_job *job = ctx;
    const rt_cpu_frame *f = job->frame;
    rt_scene_view v = rt_flat_view(f->flat);
    const int w = v.hdr->width, h = v.hdr->height;
    const int bw = BLOCK * TILE_W, bh = BLOCK * TILE_H;
    const int across = (w + bw - 1) / bw, blocks = across * ((h + bh - 1) / bh);
    for (;;) {
        int b = atomic_fetch_add_explicit(&job->next_block, 1, memory_order_relaxed);
        if (b >= blocks) break;
        const int bx = (b % across) * bw, by = (b / across) * bh;
        for (int y0 = by; y0 < by + bh && y0 < h; y0 += TILE_H)
            for (int x0 = bx; x0 < bx + bw && x0 < w; x0 += TILE_W)
                render_tile(f, &v, x0, y0, &job->per_worker[worker]);
        if (worker == 0 && f->progress) f->progress(f->progress_user, (double)(b + 1) / blocks);
    }
}

rt_status rt_packet_render(const rt_cpu_frame *frame, rt_pool *pool, rt_cpu_counts *counts) {
    int workers = pool ? rt_pool_size(pool) : 1;
    packet_job job;
    job.frame = frame;
    job.per_worker = calloc((size_t)workers, sizeof(rt_cpu_counts));
    atomic_init(&job.next_block, 0);
    memset(counts, 0, sizeof *counts);
    if (!job.per_worker) return RT_ERROR_OUT_OF_MEMORY;
    rt_pool_run_fp(pool, packet_blocks, &job, frame->flush_denormals);
    for (int i = 0; i < workers; i++) {
        counts->rays += job.per_worker[i].rays;
        counts->primary_rays += job.per_worker[i].primary_rays;
        counts->box_tests += job.per_worker[i].box_tests;
        counts->tri_tests += job.per_worker[i].tri_tests;
        counts->packets += job.per_worker[i].packets;
        counts->packet_box_tests += job.per_worker[i].packet_box_tests;
        counts->packet_tri_tests += job.per_worker[i].packet_tri_tests;
    }
    free(job.per_worker);
    return RT_OK;
}

/* The origin span under which a group of rays counts as coherent: a
 * fiftieth of the scene's largest extent. */
static float coherent_org_span(const rt_flat *flat) {
    if (!flat->hdr.instance_count || !flat->node_count) return 0.0f;
    const uint32_t root =
        (flat->hdr.flags & RT_SCENE_SINGLE) ? flat->instances[0].root : flat->hdr.top_root;
    const rt_node *n = &flat->nodes[root];
    float e = 0.0f;
    for (int k = 0; k < 3; k++) {
        const float d = n->bmax[k] - n->bmin[k];
        e = d > e ? d : e;
    }
    return 0.02f * e;
}

void rt_packet_trace_rays(const rt_cpu_frame *tr, const rt_ray *rays, const uint32_t *masks,
                          size_t n, rt_hit_d *hits, int any_hit, rt_trace_path path, rt_counters *c,
                          uint64_t *packet_rays) {
    rt_scene_view v = rt_flat_view(tr->flat);
    const float span = coherent_org_span(tr->flat);
    for (size_t i = 0; i < n; i += RT_PK_LANES) {
        size_t count = n - i < RT_PK_LANES ? n - i : RT_PK_LANES;
        const int single =
            tr->single && path != RT_TRACE_PATH_PACKETS &&
            (path == RT_TRACE_PATH_SINGLE || !rt_rays_coherent(rays + i, count, span));
        if (single) {
            rt_sw_trace_masked(tr->isa, &v, tr->single, rays + i, masks ? masks + i : NULL, count,
                               any_hit, hits + i, c);
            continue;
        }
        rt_pk_rays p;
        rt_pk_hits h;
        rt_pk_counts pc;
        memset(&pc, 0, sizeof pc);
        memset(&p, 0, sizeof p);
        p.valid = RT_PK_ALL >> (RT_PK_LANES - count);
        for (size_t l = 0; l < count; l++) rt_pk_set_ray(&p, (int)l, &rays[i + l]);
        /* The lanes' masks, a whole packet of them (lanes past count: 0). */
        uint32_t lane_masks[RT_PK_LANES];
        if (masks) {
            memset(lane_masks, 0, sizeof lane_masks);
            memcpy(lane_masks, masks + i, sizeof(uint32_t) * count);
        }
        rt_pk_trace_masked(tr->isa, &v, tr->wide, &p, masks ? lane_masks : NULL, any_hit, &h, &pc);
        for (size_t l = 0; l < count; l++) rt_pk_get_hit(&h, (int)l, &hits[i + l]);
        c->rays += (rt_u32)pc.rays;
        c->box_tests += (rt_u32)pc.box_tests;
        c->tri_tests += (rt_u32)pc.tri_tests;
        *packet_rays += count;
    }
}

void rt_single_shade_children(const rt_cpu_frame *f, const rt_scene_view *v,
                              const rt_shade_entry *child, int children, rt_counters *c,
                              float *rgb) {
    rt_shade_entry stack[RT_SHADE_STACK];
    int sp = 0;
    for (int i = 0; i < children; i++) stack[sp++] = child[i];
    while (sp > 0) {
        const rt_shade_entry e = stack[--sp];
        rt_hit_d h;
        rt_sw_trace(f->isa, v, f->single, &e.ray, 1, 0, &h, c);
        /* rt_shade_step, its shadow rays through the single-ray tracer. */
        rt_shade_node nd;
        if (rt_shade_begin(v, &e, &h, &nd)) {
            for (rt_u32 li = 0; li < v->hdr->light_count; li++) {
                rt_ray sr;
                rt_hit_d sh;
                float Ln[3], ndl;
                if (!rt_phong_light(v, &nd.sf, li, &sr, Ln, &ndl)) continue;
                rt_sw_trace(f->isa, v, f->single, &sr, 1, 1, &sh, c);
                if (sh.prim != RT_NO_HIT) continue;
                rt_phong_add(v, &nd.sf, li, Ln, ndl, nd.dn, nd.lit);
            }
        }
        float term[3];
        rt_shade_entry next[2];
        int has_term, n;
        rt_shade_end(v, &e, &h, &nd, term, &has_term, next, &n);
        if (has_term)
            for (int k = 0; k < 3; k++) rgb[k] = rgb[k] + term[k];
        for (int i = 0; i < n; i++)
            if (sp < RT_SHADE_STACK) stack[sp++] = next[i];
    }
}
