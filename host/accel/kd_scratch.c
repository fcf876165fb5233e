/* SPDX-License-Identifier: Apache-2.0 */
/* kd_scratch.c - a build worker's scratch list and the leaves' sort (kd_internal.h); its own file
 * so that the split finders, which use it, and the recursion, which uses the
 * finders, do not call each other. */
#include "accel/kd_internal.h"

#include <stdlib.h>

int rt_kd_scratch_list(kd_scratch *w, uint32_t n) {
    if (n <= w->list_cap) return 1;
    uint32_t *l = realloc(w->list, sizeof(uint32_t) * (n + 1));
    if (!l) return 0;
    w->list = l;
    w->list_cap = n;
    return 1;
}

int rt_kd_scratch_buf(kd_scratch *w, size_t bytes) {
    if (bytes <= w->buf_cap) return 1;
    size_t cap = w->buf_cap ? w->buf_cap : 4096;
    while (cap < bytes) cap *= 2;
    void *b = realloc(w->buf, cap);
    if (!b) return 0;
    w->buf = b;
    w->buf_cap = cap;
    return 1;
}

void rt_kd_scratch_free(kd_scratch *w) {
    free(w->flags);
    free(w->list);
    free(w->buf);
    w->flags = NULL;
    w->list = NULL;
    w->buf = NULL;
    w->list_cap = 0;
    w->buf_cap = 0;
}

static int u32_cmp(const void *pa, const void *pb) {
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return a < b ? -1 : a > b;
}

void rt_kd_sort_u32(uint32_t *v, uint32_t n) {
    if (n > 32) {
        qsort(v, n, sizeof(uint32_t), u32_cmp);
        return;
    }
    for (uint32_t i = 1; i < n; i++) {
        uint32_t x = v[i], j = i;
        while (j > 0 && v[j - 1] > x) {
            v[j] = v[j - 1];
            j--;
        }
        v[j] = x;
    }
}
