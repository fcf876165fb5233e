/* SPDX-License-Identifier: Apache-2.0 */
/* bench_print.h - what the benchmark engines and rtcl print with: JSON
 * strings on stdout (the --json outputs, written by hand) and the progress
 * line on stderr. */
#ifndef RT_BENCH_PRINT_H
#define RT_BENCH_PRINT_H

/* Prints s on stdout as a JSON string: quoted, with quotes, backslashes and
 * control characters escaped. */
void json_out_string(const char *s);

/* A progress line on stderr (for a terminal): "scene: what", drawn over the
 * last one. */
void bench_progress_line(const char *scene, const char *what);

#endif /* RT_BENCH_PRINT_H */
