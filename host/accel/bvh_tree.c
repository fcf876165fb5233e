/* SPDX-License-Identifier: Apache-2.0 */
/* bvh_tree.c - a built BVH's lifetime, apart from the builders so that every
 * builder can free a tree without depending on the dispatch in bvh.c. */
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"

void rt_bvh_free(rt_bvh *bvh) {
    if (!bvh) return;
    free(bvh->nodes);
    free(bvh->prim_indices);
    memset(bvh, 0, sizeof *bvh);
}
