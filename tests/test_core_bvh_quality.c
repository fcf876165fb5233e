/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_bvh_quality.c - rt_bvh_measure on hand-made trees whose figures
 * are worked out by hand, and on built trees. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "bvh_validate.h"
#include "check.h"

/* The library's error of the last call a check prints. */
static rt_error lib_err;

static rt_node box_node(float x0, float y0, float z0, float x1, float y1, float z1, uint32_t a,
                        uint32_t b) {
    rt_node n = {{x0, y0, z0}, {x1, y1, z1}, a, b};
    return n;
}

#define NEAR(a, b) (fabs((a) - (b)) <= 1e-9 * (fabs(b) + 1.0))

static void test_hand_computed(void) {
    /* Root [0,2]x[0,1]x[0,1]: area 2(2 + 1 + 2) = 10. Two leaves [0,1]^3
     * and [1,2]x[0,1]^2: area 6 each, with 3 and 2 primitives.
     * SAH = Ct * 10/10 + Ci * 3 * 6/10 + Ci * 2 * 6/10 = 1 + 3.6 + 2.4 = 7. */
    rt_node nodes[3] = {box_node(0, 0, 0, 2, 1, 1, 1, 2),
                        box_node(0, 0, 0, 1, 1, 1, 0, 3 | RT_NODE_LEAF_FLAG),
                        box_node(1, 0, 0, 2, 1, 1, 3, 2 | RT_NODE_LEAF_FLAG)};
    uint32_t idx[5] = {0, 1, 2, 3, 4};
    rt_bvh bvh = {nodes, 3, idx, 5};
    rt_bvh_quality q = rt_bvh_measure(&bvh, rt_sah_costs_default());
    CHECK_MSG(NEAR(q.sah, 7.0), "sah %.12g", q.sah);
    CHECK_EQ_INT(q.nodes, 3);
    CHECK_EQ_INT(q.leaves, 2);
    CHECK_EQ_INT(q.depth, 2);
    CHECK_EQ_INT(q.bytes, 3 * 32 + 5 * 4);
    /* Other costs scale the two sums apart: Ct 3, Ci 0.5: 3 + 0.9 + 0.6. */
    q = rt_bvh_measure(&bvh, (rt_sah_costs){3.0f, 0.5f});
    CHECK_MSG(NEAR(q.sah, 4.5), "sah %.12g", q.sah);

    /* Depth 3 with children stored before parents (any builder's order):
     * root 0 -> (3, 1); node 3 -> (2, 4). Root [0,4]x[0,1]x[0,1]: area 18.
     * Node 3 [0,2]x..: 10; leaves 2 [0,1]: 6 (1 prim), 4 [1,2]: 6 (1 prim);
     * leaf 1 [2,4]: 10 (2 prims).
     * SAH = 1 + 10/18 + 2*6/18 + 2*6/18 + 2*2*10/18 = 1 + (10 + 24 + 40)/18. */
    rt_node deep[5] = {
        box_node(0, 0, 0, 4, 1, 1, 3, 1), box_node(2, 0, 0, 4, 1, 1, 2, 2 | RT_NODE_LEAF_FLAG),
        box_node(0, 0, 0, 1, 1, 1, 0, 1 | RT_NODE_LEAF_FLAG), box_node(0, 0, 0, 2, 1, 1, 2, 4),
        box_node(1, 0, 0, 2, 1, 1, 1, 1 | RT_NODE_LEAF_FLAG)};
    rt_bvh d = {deep, 5, idx, 4};
    q = rt_bvh_measure(&d, rt_sah_costs_default());
    CHECK_MSG(NEAR(q.sah, 1.0 + 74.0 / 18.0), "sah %.12g", q.sah);
    CHECK_EQ_INT(q.depth, 3);
    CHECK_EQ_INT(q.leaves, 3);
    CHECK_EQ_INT(q.bytes, 5 * 32 + 4 * 4);

    /* A leaf root counts Ci * count. */
    rt_node leaf = box_node(0, 0, 0, 1, 2, 3, 0, 5 | RT_NODE_LEAF_FLAG);
    rt_bvh l = {&leaf, 1, idx, 5};
    q = rt_bvh_measure(&l, rt_sah_costs_default());
    CHECK_MSG(NEAR(q.sah, 10.0), "sah %.12g", q.sah);
    CHECK_EQ_INT(q.depth, 1);

    /* Zero-area root (everything on one line): every ratio is 1. */
    rt_node flat[3] = {box_node(0, 0, 0, 2, 0, 0, 1, 2),
                       box_node(0, 0, 0, 1, 0, 0, 0, 1 | RT_NODE_LEAF_FLAG),
                       box_node(1, 0, 0, 2, 0, 0, 1, 1 | RT_NODE_LEAF_FLAG)};
    rt_bvh fl = {flat, 3, idx, 2};
    q = rt_bvh_measure(&fl, rt_sah_costs_default());
    CHECK_MSG(NEAR(q.sah, 5.0), "sah %.12g", q.sah);

    /* The empty tree. */
    rt_bvh empty = {NULL, 0, NULL, 0};
    q = rt_bvh_measure(&empty, rt_sah_costs_default());
    CHECK(q.sah == 0.0 && q.nodes == 0 && q.leaves == 0 && q.depth == 0 && q.bytes == 0);
}

static void test_built_trees(void) {
    /* One box: a leaf root, SAH = Ci. */
    rt_aabb one = {{0, 0, 0}, {1, 1, 1}};
    rt_build_options o = rt_build_options_default();
    o.builder = RT_BUILDER_THESIS_SCALAR;
    rt_bvh t;
    char msg[256];
    CHECK(rt_bvh_build(&one, 1, &o, NULL, &t, &lib_err) == RT_OK);
    rt_bvh_quality q = rt_bvh_measure(&t, rt_sah_costs_default());
    CHECK(NEAR(q.sah, 2.0) && q.nodes == 1 && q.leaves == 1 && q.depth == 1);
    rt_bvh_free(&t);

    /* Two far clusters of 20 unit boxes: the tree must beat one big leaf
     * (SAH 2 * 40 = 80) by far, and the figures must agree with the tree. */
    rt_aabb boxes[40];
    uint32_t seed = 5;
    for (int i = 0; i < 40; i++) {
        float base = i < 20 ? 0.0f : 1000.0f;
        for (int k = 0; k < 3; k++) {
            boxes[i].bmin[k] = base + bvh_test_uniform(&seed, 0.0f, 10.0f);
            boxes[i].bmax[k] = boxes[i].bmin[k] + 1.0f;
        }
    }
    CHECK(rt_bvh_build(boxes, 40, &o, NULL, &t, &lib_err) == RT_OK);
    CHECK(bvh_validate(&t, boxes, 40, 10, 0, msg, sizeof msg));
    q = rt_bvh_measure(&t, rt_sah_costs_default());
    CHECK_MSG(q.sah < 10.0, "sah %g", q.sah);
    CHECK_EQ_INT(q.nodes, t.node_count);
    CHECK_EQ_INT(q.leaves, (t.node_count + 1) / 2);
    CHECK(q.depth >= 3 && q.depth <= 6);
    CHECK_EQ_INT(q.bytes, t.node_count * sizeof(rt_node) + 40 * sizeof(uint32_t));
    rt_bvh_free(&t);
}

int main(void) {
    test_hand_computed();
    test_built_trees();
    return TEST_END();
}
