/* SPDX-License-Identifier: Apache-2.0 */
/* packet_kd.h - kd-tree meshes (RT_INST_KD) in the packet tracer: a group of
 * RT_VN lanes, one native vector, traverses the tree together. Included once
 * by cpu_ref/packet_trace.c (one copy per instruction-set build), after the
 * leaf test it shares with the BVH path; not a header of its own.
 *
 * Each lane performs rt_kd_trace_mesh (kernels/rt_kd.h) step for step: the
 * same root interval, the same plane distance, margin, side choices and
 * early-termination test, as vector operations in the oracle's order (its
 * 'a < b ? a : b' are rt_vmin_of and rt_vmax_of, NaN included), and the leaf
 * runs the BVH path's vector triangle test and acceptance (pk_leaf_range,
 * pk_tri, pk_hit_accepted). A lane takes part in a cell (its bit in the
 * cell's mask) exactly when its own traversal would visit that cell, and it
 * visits its cells in its own front-to-back order, whatever the other
 * lanes do:
 * - lanes whose ray goes along the split axis (1/dir >= 0, or parallel to
 *   the plane: the oracle then takes the left child first) and lanes that go
 *   against it (1/dir < 0) may share a group. A node then schedules up to
 *   three cells, bottom to top of the stack: the left child for the
 *   backward lanes that go there second, the right child for every lane
 *   that goes there (first for backward lanes, second for forward ones),
 *   and, taken at once, the left child for the forward lanes that go there
 *   first. Each lane sees its own cells in its own order; a subtree may be
 *   walked twice, for two sets of lanes.
 * - on a pop the oracle drops a cell whose entry lies beyond rt_box_hi(best
 *   t); lanes for which the oracle goes straight into the cell (its only or
 *   its first child, never stacked) are exempt ('keep'), as they are there.
 * So each lane's sequence of leaves, triangle tests and hits is the oracle's
 * for the same starting best hit, and its counters are the oracle's too. */

/* Cells a group's stack may hold: at most two pushed per node on the path,
 * and host/layout/flatten.c admits no tree deeper than RT_KD_STACK - 2. */
enum { PK_KD_STACK = 2 * RT_KD_STACK };

typedef struct pk_kd_cell {
    rt_vf tn, tf;        /* each lane's entry and exit t */
    rt_u32 node;         /* index into kd_nodes */
    uint32_t mask, keep; /* its lanes, and those not checked when popped */
} pk_kd_cell;

/* Group g's lanes of m through the kd-tree of the mesh whose bounding
 * rt_node is 'root' (instance inst), the rays p in the mesh's space. */
static void pk_kd_group(pk_state *st, const pk_geom *p, rt_u32 root, rt_u32 inst, int g,
                        uint32_t m) {
    const rt_node *rn = &st->s->nodes[root];
    const rt_kd_node *kd = st->s->kd_nodes;
    const rt_vf inf = rt_vsplat(RT_INF), zero = rt_vsplat(0.0f);
    const rt_vf margin = rt_vsplat(RT_BOX_T_MARGIN);
    /* rt_kd_root_interval over [rt_box_lo(tmin), rt_box_hi(best t)]. */
    st->counts->group_box_tests++;
    count(st, &st->counts->box_tests, st->box, g, m);
    rt_vf tn = p->lo[g], tf = inf;
    for (int k = 0; k < 3; k++) pk_slab_box(rn->bmin[k], rn->bmax[k], p, k, g, &tn, &tf);
    tf = rt_vmin_of(st->hi[g], pk_far(tf));
    m &= rt_vbits(tn <= tf);
    if (!m) return;
    pk_kd_cell stack[PK_KD_STACK];
    int sp = 0;
    rt_u32 node = rn->a;
    for (;;) {
        const rt_kd_node *n = &kd[node];
        const rt_u32 k = n->b & 3u;
        if (k == RT_KD_LEAF) {
            pk_leaf_range(st, p, n->a, n->a + (n->b >> 2), inst, g, m);
            if (!st->alive[g]) return;
        } else {
            st->counts->group_box_tests++;
            count(st, &st->counts->box_tests, st->box, g, m);
            const rt_vf split = rt_vsplat(RT_AS_FLOAT((rt_i32)n->a));
            const rt_u32 left = node + 1u, right = n->b >> 2;
            const rt_vf o = p->org[k][g], inv = p->inv[k][g];
            /* Parallel lanes: the side of the origin, both in the plane. The
             * plane distance below is then unused (it may be 0 * inf). */
            const rt_vi par = ~(rt_vabs(inv) < inf);
            const rt_vf ts = (split - o) * inv;
            const rt_vf mg = rt_vsel(rt_vabs(ts) < inf, rt_vabs(ts) * margin, zero);
            const rt_vf ts_lo = ts - mg, ts_hi = ts + mg;
            const rt_vf first_tf = rt_vsel(par, tf, rt_vmin_of(ts_hi, tf));
            const rt_vf second_tn = rt_vsel(par, tn, rt_vmax_of(ts_lo, tn));
            const rt_vi go_first = rt_vsel_i(par, o <= split, tn <= ts_hi);
            const rt_vi go_second =
                rt_vsel_i(par, o >= split, (ts_lo <= tf) & (second_tn <= st->hi[g]));
            /* Forward lanes take the left child first, backward ones the
             * right. */
            const rt_vi fwd = par | (inv >= zero);
            const uint32_t bf = rt_vbits(go_first) & m, bs = rt_vbits(go_second) & m;
            const uint32_t bfwd = rt_vbits(fwd);
            const uint32_t left_fwd = bf & bfwd;  /* left, first */
            const uint32_t left_bwd = bs & ~bfwd; /* left, second */
            const uint32_t to_right = (bf & ~bfwd) | (bs & bfwd);
            /* Straight into the cell (no pop check): a backward lane's first
             * child, and any lane's only child. */
            const uint32_t only = ~(bf & bs);
            if (left_bwd) {
                assert(sp < PK_KD_STACK);
                stack[sp++] = (pk_kd_cell){second_tn, tf, left, left_bwd, left_bwd & only};
            }
            if (to_right) {
                assert(sp < PK_KD_STACK);
                stack[sp++] = (pk_kd_cell){rt_vsel(fwd, second_tn, tn), rt_vsel(fwd, tf, first_tf),
                                           right, to_right, (bf & ~bfwd) | (to_right & only)};
            }
            if (left_fwd) {
                node = left;
                tf = first_tf;
                m = left_fwd;
                continue;
            }
        }
        /* The next cell with a lane whose best hit may still lie in it. */
        for (;;) {
            if (sp == 0) return;
            const pk_kd_cell *c = &stack[--sp];
            m = c->mask & st->alive[g] & (c->keep | rt_vbits(c->tn <= st->hi[g]));
            if (m) {
                node = c->node;
                tn = c->tn;
                tf = c->tf;
                break;
            }
        }
    }
}

/* A kd-tree mesh for the groups of gm: each group's live lanes in the
 * instance's box, one group at a time. */
static void pk_kd(pk_state *st, const pk_geom *p, rt_u32 root, rt_u32 inst, pk_groups gm) {
    for (pk_groups todo = gm & st->alive_groups; todo; todo &= todo - 1) {
        const int g = rt_lane_first(todo);
        const uint32_t m = st->alive[g] & st->inst_ok[g];
        if (m) pk_kd_group(st, p, root, inst, g, m);
    }
}
