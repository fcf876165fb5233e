/* SPDX-License-Identifier: Apache-2.0 */
/* cli_signals.c - see cli_signals.h. The handler uses async-signal-safe
 * calls only: kill, waitpid, unlink (in rt_output_remove_temporaries) and
 * raise. */
#define _POSIX_C_SOURCE 200809L
#include "cli_signals.h"

#include <errno.h>
#include <signal.h>
#include <string.h>
#include <sys/wait.h>

#include "rt.h"

static volatile sig_atomic_t child_pid;

static void on_signal(int sig) {
    int saved = errno;
    pid_t pid = (pid_t)child_pid;
    if (pid > 0) {
        kill(pid, SIGKILL);
        while (waitpid(pid, NULL, 0) < 0 && errno == EINTR) {
        }
    }
    rt_output_remove_temporaries();
    errno = saved;
    /* SA_RESETHAND made the action the default one: delivered once this
     * handler returns (the signal is blocked until then), it ends rtcl. */
    raise(sig);
}

void cli_signals_install(void) {
    static const int signals[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t i = 0; i < sizeof signals / sizeof signals[0]; i++) {
        struct sigaction old;
        if (sigaction(signals[i], NULL, &old) != 0 || old.sa_handler == SIG_IGN) continue;
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sigfillset(&sa.sa_mask);
        sa.sa_flags = SA_RESETHAND;
        sigaction(signals[i], &sa, NULL);
    }
}

void cli_signals_child(pid_t pid) {
    child_pid = (sig_atomic_t)pid;
}
