/* SPDX-License-Identifier: Apache-2.0 */
/* cli_signals.h - rtcl ended by SIGINT (Ctrl-C), SIGTERM or SIGHUP leaves no
 * temporary behind (issue 31): the handler stops the program writing an
 * output for rtcl (ffmpeg, a video), removes the temporary of every write
 * under way (rt_output_remove_temporaries), so the targets stay as they
 * were, and ends rtcl by the same signal (its exit status is unchanged).
 * SIGKILL cannot be caught: it leaves the temporary (base/atomic_file.h). */
#ifndef RTCL_CLI_SIGNALS_H
#define RTCL_CLI_SIGNALS_H

#include <sys/types.h>

/* Installs the handler for SIGINT, SIGTERM and SIGHUP (each a one-shot:
 * the handler restores the default action before it raises the signal
 * again). Signals that were ignored when rtcl started (nohup) stay ignored. */
void cli_signals_install(void);

/* pid (0: none) is the child that writes an output now: the handler kills
 * it (SIGKILL) and reaps it before the temporaries are removed, so that it
 * cannot create its file again after the removal. The caller sets 0 before
 * it reaps that child itself (a reaped process's id may be reused). */
void cli_signals_child(pid_t pid);

#endif /* RTCL_CLI_SIGNALS_H */
