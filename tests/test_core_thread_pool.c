/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_thread_pool.c - every worker runs exactly once per job, the
 * caller is worker 0, and the pool survives many jobs. */
#include <stdatomic.h>
#include <string.h>

#include "check.h"
#include "base/thread_pool.h"

typedef struct job {
    atomic_int calls[16];
    atomic_int bad_count;
    int caller_ran;
} job;

static _Thread_local int on_caller;

static void count_calls(void *ctx, int worker, int worker_count) {
    job *j = ctx;
    if (worker < 0 || worker >= 16 || worker_count < 1 || worker_count > 16) {
        atomic_fetch_add(&j->bad_count, 1);
        return;
    }
    atomic_fetch_add(&j->calls[worker], 1);
    if (worker == 0 && on_caller) j->caller_ran = 1;
}

static void run_jobs(int threads, int jobs) {
    rt_pool *pool = rt_pool_create(threads);
    CHECK_MSG(pool != NULL, "pool of %d", threads);
    if (!pool) return;
    CHECK_EQ_INT(rt_pool_size(pool), threads);
    on_caller = 1;
    for (int r = 0; r < jobs; r++) {
        job j;
        memset(&j, 0, sizeof j);
        rt_pool_run(pool, count_calls, &j);
        for (int w = 0; w < 16; w++)
            CHECK_MSG(atomic_load(&j.calls[w]) == (w < threads ? 1 : 0),
                      "%d threads, job %d: worker %d ran %d times", threads, r, w,
                      atomic_load(&j.calls[w]));
        CHECK(atomic_load(&j.bad_count) == 0);
        CHECK_MSG(j.caller_ran, "worker 0 is not the calling thread");
        if (test_failures) break;
    }
    on_caller = 0;
    rt_pool_destroy(pool);
}

int main(void) {
    CHECK(rt_cpu_count() >= 1);
    run_jobs(1, 100);
    run_jobs(2, 5000);
    run_jobs(3, 2000);
    run_jobs(8, 500);
    /* A pool made and dropped many times leaks no threads (the sanitizer
     * build would report leaks). */
    for (int i = 0; i < 50; i++) {
        rt_pool *p = rt_pool_create(4);
        CHECK(p != NULL);
        rt_pool_destroy(p);
    }
    CHECK(rt_pool_size(NULL) == 1);
    return TEST_END();
}
