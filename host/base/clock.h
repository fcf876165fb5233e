/* SPDX-License-Identifier: Apache-2.0 */
/* clock.h - the one monotonic clock that timings in the library, rtcl and
 * the benchmark programs read (base/clock.c). */
#ifndef RT_CLOCK_H
#define RT_CLOCK_H

/* Milliseconds on a monotonic clock. */
double rt_now_ms(void);

#endif /* RT_CLOCK_H */
