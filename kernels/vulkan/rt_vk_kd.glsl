/* SPDX-License-Identifier: Apache-2.0 */
/* rt_vk_kd.glsl - the GLSL mirror of kernels/rt_kd.h: kd-tree traversal of
 * one mesh (instance flag RT_INST_KD) for the Vulkan backend.
 * rt_vk_trace.glsl calls it for kd meshes; a leaf calls rt_leaf_test
 * (rt_vk_hit.glsl) as the C code does: the triangle test and the hit's acceptance are the BVH's
 * own code, so the bits and the closest hit are the oracle's. The same
 * operations in the same order as rt_kd_trace_mesh (every one NoContraction
 * through host/vulkan/spv_precise.c; there is no division here).
 *
 * The kd nodes are storage buffer binding 14 (rt_vk_view.glsl, after the
 * per-dispatch buffers 10..13). Scenes without kd meshes leave RT_INST_KD out of the
 * SC_INST_MASK specialization constant, so the driver drops this code.
 *
 * The stack: (node, entry t, exit t) per cell. The workgroup's shared
 * memory is full (the two BVH stacks take 32 KiB, Vulkan's usual limit), so
 * the kd stack takes the mesh BVH's stack (level 1 of STACK_AT), which a kd
 * mesh does not use, three words per cell: SC_KD_SHARED cells (21, the
 * most that fit; the specialization constant SC_KD_SHARED of
 * kernels/rt_interface.def, which test_vulkan_oracle sets lower to run the
 * other path). A tree deep enough to need more
 * (host/layout/flatten.c admits depth up to RT_KD_STACK - 2) goes on in a
 * private array, which a driver may keep in slow memory but only such deep
 * paths touch. Resumable (rt_vk_resume.glsl): suspended at a node (ST_MESH
 * at = 0) or inside its leaf (at = 1). */
#ifndef RT_VK_KD_GLSL
#define RT_VK_KD_GLSL

#include "rt_vk_bvh.glsl"

#define RT_KD_STACK  64
#define RT_VK_KD_SHARED int(SC_KD_SHARED)

/* rt_kd_root_interval: rt_box_test's slab test, also giving the far end. */
bool rt_kd_root_interval(uint node, rt_ray r, rt_ray_pre p, float lo, float hi, out float tn,
                         out float tf) {
    return rt_box_interval(node, r, p, lo, hi, tn, tf);
}

/* Stack cell k: words 3k .. 3k + 2 of the mesh level's stack while k is
 * below SC_KD_SHARED, else entry k of the private overflow arrays. */
#define KD_PUSH(k, nd, n0, f0)                                         \
    if ((k) < RT_VK_KD_SHARED) {                                       \
        STACK_AT(1, 3 * (k)) = (nd);                                   \
        STACK_AT(1, 3 * (k) + 1) = floatBitsToUint(n0);                \
        STACK_AT(1, 3 * (k) + 2) = floatBitsToUint(f0);                \
    } else {                                                           \
        ov_node[k] = (nd);                                             \
        ov_tn[k] = (n0);                                               \
        ov_tf[k] = (f0);                                               \
    }
#define KD_TN(k)                                                       \
    ((k) < RT_VK_KD_SHARED ? uintBitsToFloat(STACK_AT(1, 3 * (k) + 1)) : ov_tn[k])
#define KD_GET(k, nd, n0, f0)                                          \
    if ((k) < RT_VK_KD_SHARED) {                                       \
        nd = STACK_AT(1, 3 * (k));                                     \
        n0 = uintBitsToFloat(STACK_AT(1, 3 * (k) + 1));                \
        f0 = uintBitsToFloat(STACK_AT(1, 3 * (k) + 2));                \
    } else {                                                           \
        nd = ov_node[k];                                               \
        n0 = ov_tn[k];                                                 \
        f0 = ov_tf[k];                                                 \
    }
#define KD_POP(k) KD_GET(k, node, tn, tf)

/* The traversal's position (ST_MESH: node, stack depth, at, the cell's
 * entry and exit t, then the stack's cells), saved when it suspends and
 * loaded when it resumes (rt_vk_resume.glsl), the t values as bits. */
#define KD_SAVE(atv)                                                   \
    {                                                                  \
        uint w = ST_MESH;                                              \
        st_put(w, node);                                               \
        st_put(w, uint(sp));                                           \
        st_put(w, (atv));                                              \
        st_putf(w, tn);                                                \
        st_putf(w, tf);                                                \
        for (int k = 0; k < sp; k++, RT_VK_TICK) {                     \
            uint cn;                                                   \
            float c0, c1;                                              \
            KD_GET(k, cn, c0, c1)                                      \
            st_put(w, cn);                                             \
            st_putf(w, c0);                                            \
            st_putf(w, c1);                                            \
        }                                                              \
    }
#define KD_LOAD()                                                      \
    {                                                                  \
        uint w = ST_MESH;                                              \
        node = st_get(w);                                              \
        sp = int(st_get(w));                                           \
        at = st_get(w);                                                \
        tn = st_getf(w);                                               \
        tf = st_getf(w);                                               \
        for (int k = 0; k < sp; k++, RT_VK_TICK) {                     \
            uint cn = st_get(w);                                       \
            float c0 = st_getf(w);                                     \
            float c1 = st_getf(w);                                     \
            KD_PUSH(k, cn, c0, c1)                                     \
        }                                                              \
    }

/* rt_kd_trace_mesh: the kd-tree of the mesh whose bounding rt_node is root,
 * with a ray already in the mesh's space; best.t is the upper end of the
 * range; true when any_hit found an occluder. */
bool rt_kd_trace_mesh(uint root, uint inst, rt_ray r, rt_ray_pre p, bool any_hit,
                      inout rt_hit_d best, inout rt_counters c) {
    float tn, tf;
    uint ov_node[RT_KD_STACK];
    float ov_tn[RT_KD_STACK], ov_tf[RT_KD_STACK];
    int sp = 0;
    uint node, at = 0u;
    if (rt_vk_resuming) {
        KD_LOAD()
        if (at == 0u) rt_vk_resuming = false;
    } else {
        c.box_tests++;
        if (!rt_kd_root_interval(root, r, p, rt_box_lo(r.tmin), rt_box_hi(best.t), tn, tf))
            return false;
        node = nodes[root].a;
    }
    for (;; RT_VK_TICK) {
        if (rt_vk_checkpoint()) {
            at = 0u;
            break;
        }
        uint na = kd_nodes[node].a, nb = kd_nodes[node].b;
        uint k = nb & 3u;
        bool pop = false;
        if (k == RT_KD_LEAF) {
            if (rt_leaf_test(na, nb >> 2, inst, r, p, any_hit, best, c)) return true;
            if (rt_vk_suspended) {
                at = 1u;
                break;
            }
            pop = true;
        } else {
            c.box_tests++;
            float split = uintBitsToFloat(na);
            uint left = node + 1u, right = nb >> 2;
            float o = rt_pick3(r.org, int(k)), inv = rt_pick3(p.inv, int(k));
            uint first, second;
            float first_tf, second_tn;
            bool go_first, go_second;
            if (!(RT_FABS(inv) < RT_INF)) {
                /* Parallel to the plane: the side of the origin, both when
                 * the ray lies in the plane. */
                first = left;
                second = right;
                first_tf = tf;
                second_tn = tn;
                go_first = o <= split;
                go_second = o >= split;
            } else {
                float ts = (split - o) * inv; /* finite or +-inf, never NaN */
                float m = RT_FABS(ts) < RT_INF ? RT_FABS(ts) * RT_BOX_T_MARGIN : 0.0;
                float ts_lo = ts - m, ts_hi = ts + m;
                bool left_first = inv >= 0.0;
                first = left_first ? left : right;
                second = left_first ? right : left;
                first_tf = ts_hi < tf ? ts_hi : tf;
                second_tn = ts_lo > tn ? ts_lo : tn;
                go_first = tn <= ts_hi;
                go_second = ts_lo <= tf && second_tn <= rt_box_hi(best.t);
            }
            if (go_first && go_second) {
                KD_PUSH(sp, second, second_tn, tf)
                sp++;
                node = first;
                tf = first_tf;
            } else if (go_first) {
                node = first;
                tf = first_tf;
            } else if (go_second) {
                node = second;
                tn = second_tn;
            } else {
                pop = true;
            }
        }
        if (pop) {
            /* The next cell that may still hold a hit at or before best. */
            for (;; RT_VK_TICK) {
                if (sp == 0) return false;
                --sp;
                if (KD_TN(sp) <= rt_box_hi(best.t)) break;
            }
            KD_POP(sp)
        }
    }
    /* Suspended (the one way out of the loop). */
    KD_SAVE(at)
    return false;
}

#endif
