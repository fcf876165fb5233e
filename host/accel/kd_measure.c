/* SPDX-License-Identifier: Apache-2.0 */
/* kd_measure.c - a kd-tree's SAH cost and size, walked without recursion. */
#include "accel/kd.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double area(const rt_aabb *b) {
    double dx = (double)b->bmax[0] - (double)b->bmin[0];
    double dy = (double)b->bmax[1] - (double)b->bmin[1];
    double dz = (double)b->bmax[2] - (double)b->bmin[2];
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

rt_kd_quality rt_kd_measure(const rt_kd *kd, rt_sah_costs costs) {
    rt_kd_quality q;
    memset(&q, 0, sizeof q);
    if (!kd->node_count) return q;
    q.nodes = kd->node_count;
    q.refs = kd->prim_count;
    q.bytes = sizeof(rt_kd_node) * kd->node_count + sizeof(uint32_t) * kd->prim_count;
    double root = area(&kd->bounds);
    typedef struct item {
        uint32_t node, depth;
        rt_aabb cell;
    } item;
    item stack[RT_KD_MAX_DEPTH + 4];
    int sp = 0;
    stack[sp++] = (item){0, 1, kd->bounds};
    while (sp) {
        item it = stack[--sp];
        if (it.depth > q.depth) q.depth = it.depth;
        const rt_kd_node *n = &kd->nodes[it.node];
        double p = root > 0.0 ? area(&it.cell) / root : 1.0;
        if ((n->b & 3u) == RT_KD_LEAF) {
            uint32_t cnt = n->b >> 2;
            q.leaves++;
            if (!cnt) q.empty++;
            q.sah += (double)costs.intersect * p * (double)cnt;
            continue;
        }
        q.sah += (double)costs.traverse * p;
        if (sp + 2 > RT_KD_MAX_DEPTH + 4) continue; /* deeper than any built tree */
        int k = (int)(n->b & 3u);
        float split;
        memcpy(&split, &n->a, sizeof split);
        item l = {it.node + 1, it.depth + 1, it.cell}, r = {n->b >> 2, it.depth + 1, it.cell};
        l.cell.bmax[k] = split;
        r.cell.bmin[k] = split;
        stack[sp++] = r;
        stack[sp++] = l;
    }
    /* Distinct triangles: a bit per triangle index. */
    uint32_t top = 0;
    for (uint32_t i = 0; i < kd->prim_count; i++)
        if (kd->prims[i] > top) top = kd->prims[i];
    uint8_t *seen = calloc((size_t)top / 8 + 1, 1);
    if (seen && kd->prim_count) {
        uint32_t distinct = 0;
        for (uint32_t i = 0; i < kd->prim_count; i++) {
            uint32_t t = kd->prims[i];
            if (!(seen[t / 8] & (1u << (t % 8)))) distinct++;
            seen[t / 8] |= (uint8_t)(1u << (t % 8));
        }
        q.refs_per_tri = (double)kd->prim_count / (double)distinct;
    }
    free(seen);
    return q;
}
