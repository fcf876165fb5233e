/* SPDX-License-Identifier: Apache-2.0 */
/* clock.c - the monotonic clock behind rt_now_ms. */
#include "base/clock.h"

#include <time.h>

double rt_now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}
