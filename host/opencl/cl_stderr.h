/* SPDX-License-Identifier: Apache-2.0 */
/* cl_stderr.h - keeping what a device compiler prints on the process's
 * stderr off the user's terminal.
 *
 * PoCL's compiler (clang inside the driver) writes its build messages to the
 * program's build log, but the summary line ("N warnings generated.") to file
 * descriptor 2 itself; other drivers may print too. The library never prints,
 * so while an OpenCL program is built (and warmed up) descriptor 2 points at
 * a temporary file, and what landed there joins the build log
 * (rt_renderer_build_log), shown by rtcl with --verbose or on failure. */
#ifndef RT_CL_STDERR_H
#define RT_CL_STDERR_H

#include <stdio.h>

typedef struct rt_cl_stderr {
    int saved;  /* the real descriptor 2, or -1 when nothing was redirected */
    FILE *file; /* where descriptor 2 points meanwhile */
} rt_cl_stderr;

/* Points descriptor 2 at a temporary file until rt_cl_stderr_end. One
 * capture at a time in the process (a lock is held in between): whatever any
 * thread writes to descriptor 2 meanwhile is captured too. When no temporary
 * file can be made nothing is redirected and the build prints as before. */
void rt_cl_stderr_begin(rt_cl_stderr *capture);

/* Puts descriptor 2 back and returns what was written meanwhile, as a new
 * NUL-terminated string to free (at most 64 KiB; "" when nothing), or NULL
 * when nothing was captured or no memory. */
char *rt_cl_stderr_end(rt_cl_stderr *capture);

#endif /* RT_CL_STDERR_H */
