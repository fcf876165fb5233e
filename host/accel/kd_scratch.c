/* kd_scratch.c - a build worker's scratch list (kd_internal.h); its own file
 * so that the split finders, which use it, and the recursion, which uses the
 * finders, do not call each other. */
#include "accel/kd_internal.h"

#include <stdlib.h>

int kd_scratch_list(kd_scratch *w, uint32_t n) {
    if (n <= w->list_cap) return 1;
    uint32_t *l = realloc(w->list, sizeof(uint32_t) * (n + 1));
    if (!l) return 0;
    w->list = l;
    w->list_cap = n;
    return 1;
}
