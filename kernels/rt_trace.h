/* SPDX-License-Identifier: Apache-2.0 */
/* rt_trace.h - the two-level traversal: the object BVH over the instances,
 * then each reached instance's mesh, by its BVH (rt_bvh.h) or its kd-tree
 * (rt_kd.h), with the ray in the instance's object space. Valid C99 and
 * OpenCL C (rt_math_profile.h); the GLSL mirror is
 * kernels/vulkan/rt_vk_trace.glsl. */
#ifndef RT_KERNELS_TRACE_H
#define RT_KERNELS_TRACE_H

#include "rt_bvh.h"
#include "rt_kd.h"

/* The ray in an instance's object space: o' = M o + m, d' = M d, with M the
 * inverse transform. t keeps its meaning because d' is not normalised. */
RT_FN void rt_ray_to_object(RT_GLOBAL const rt_instance *in, const rt_ray *r, rt_ray *o) {
    RT_GLOBAL const float *m = in->world_to_object;
    for (int i = 0; i < 3; i++) {
        o->org[i] = ((m[4 * i] * r->org[0] + m[4 * i + 1] * r->org[1]) + m[4 * i + 2] * r->org[2]) +
                    m[4 * i + 3];
        o->dir[i] = (m[4 * i] * r->dir[0] + m[4 * i + 1] * r->dir[1]) + m[4 * i + 2] * r->dir[2];
    }
    o->tmin = r->tmin;
    o->tmax = r->tmax;
}

/* Traces one instance: nothing when its mask has no bit of the ray's
 * (ray_mask & in->mask == 0: rt_object_set_mask), else the ray is
 * transformed unless the instance is the identity. */
RT_FN int rt_trace_instance(const rt_scene_view *s, rt_u32 inst, const rt_ray *r,
                            const rt_ray_pre *p, rt_u32 ray_mask, int any_hit, rt_hit_d *best,
                            rt_counters *c) {
    RT_GLOBAL const rt_instance *in = &s->instances[inst];
    if ((ray_mask & in->mask) == 0u) return 0;
    int kd = (RT_INST_FLAGS(in) & RT_INST_KD) != 0;
    float inst_lo = -RT_INF;
    if (!(RT_SCENE_FLAGS(s) & RT_SCENE_SINGLE) && !rt_inst_enter(in, r, p, &inst_lo)) return 0;
    rt_ray o;
    rt_ray_pre op;
    if (RT_INST_FLAGS(in) & RT_INST_IDENTITY) {
        op = *p;
        op.inst_lo = inst_lo;
        return kd ? rt_kd_trace_mesh(s, in->root, inst, r, &op, any_hit, best, c)
                  : rt_trace_mesh(s, in->root, inst, r, &op, any_hit, best, c);
    }
    rt_ray_to_object(in, r, &o);
    rt_ray_prepare(&o, &op);
    op.inst_lo = inst_lo;
    return kd ? rt_kd_trace_mesh(s, in->root, inst, &o, &op, any_hit, best, c)
              : rt_trace_mesh(s, in->root, inst, &o, &op, any_hit, best, c);
}

/* The two-level traversal (Langr 2016, section 3.2.1): the object BVH, then
 * each reached instance's mesh BVH. With one identity instance the object BVH
 * is skipped. An instance whose mask has no bit of the ray's mask is skipped
 * where the traversal reaches it, before its box (rt_trace_instance), so the
 * hit is that of the scene without it.
 * Returns 1 on a hit (for any_hit: some hit in range). */
RT_FN int rt_trace_masked(const rt_scene_view *s, const rt_ray *r, rt_u32 ray_mask, int any_hit,
                          rt_hit_d *best, rt_counters *c) {
    rt_ray_pre p;
    rt_ray_prepare(r, &p);
    rt_hit_init(best, r);
    c->rays++;
    if (s->hdr->instance_count == 0) return 0;
    if (RT_SCENE_FLAGS(s) & RT_SCENE_SINGLE) {
        rt_trace_instance(s, 0, r, &p, ray_mask, any_hit, best, c);
        return best->prim != RT_NO_HIT;
    }
    rt_u32 stack[RT_STACK_SIZE];
    int sp = 0;
    float tn;
    rt_u32 node = s->hdr->top_root;
    c->box_tests++;
    if (!rt_box_test(&s->nodes[node], r, &p, rt_box_lo(r->tmin), rt_box_hi(best->t), &tn)) return 0;
    for (;;) {
        RT_GLOBAL const rt_node *n = &s->nodes[node];
        if (n->b & RT_NODE_LEAF_FLAG) {
            rt_u32 count = n->b & RT_NODE_COUNT_MASK;
            for (rt_u32 e = n->a; e < n->a + count; e++)
                if (rt_trace_instance(s, s->inst_ids[e], r, &p, ray_mask, any_hit, best, c))
                    return 1;
            if (sp == 0) break;
            node = stack[--sp];
            continue;
        }
        if (!rt_descend(s, n, r, &p, best, c, stack, &sp, &node)) break;
    }
    return best->prim != RT_NO_HIT;
}

/* rt_trace_masked with every mask bit: the rays of rendering. */
RT_FN int rt_trace(const rt_scene_view *s, const rt_ray *r, int any_hit, rt_hit_d *best,
                   rt_counters *c) {
    return rt_trace_masked(s, r, 0xffffffffu, any_hit, best, c);
}

#endif /* RT_KERNELS_TRACE_H */
