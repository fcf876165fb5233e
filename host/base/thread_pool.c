/* SPDX-License-Identifier: Apache-2.0 */
/* thread_pool.c - a persistent pool of pthreads (see thread_pool.h).
 *
 * A job is published by bumping a generation counter. Workers first spin a
 * short while on that counter (the builder issues many short jobs back to
 * back, and a condition variable wake-up costs tens of microseconds), then
 * sleep on a condition variable. The caller runs worker 0 itself and waits
 * the same way for the last worker to finish.
 */
#include "base/thread_pool.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <unistd.h>

#include "rt_fp_mode.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define cpu_relax() _mm_pause()
#elif defined(__aarch64__)
#define cpu_relax() __asm__ __volatile__("yield")
#else
#define cpu_relax() ((void)0)
#endif

/* Spin iterations before sleeping: a few tens of microseconds. */
enum { SPIN_LIMIT = 4000 };

typedef struct worker_arg {
    rt_pool *pool;
    int index;
} worker_arg;

struct rt_pool {
    int size;
    int started; /* threads actually created (size - 1 on success) */
    pthread_t *threads;
    worker_arg *args;
    pthread_mutex_t mutex;    /* guards the sleeping side of both waits */
    pthread_cond_t wake;      /* a new job (or stop) was published */
    pthread_cond_t done;      /* the last worker finished */
    pthread_mutex_t run_lock; /* one job at a time, even with several callers */
    rt_pool_fn fn;
    void *ctx;
    atomic_ulong generation;
    atomic_int remaining; /* workers (other than the caller) still in the job */
    atomic_int stop;
};

int rt_cpu_count(void) {
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (int)n;
}

static unsigned long wait_for_job(rt_pool *pool, unsigned long seen) {
    unsigned long g;
    for (int i = 0; i < SPIN_LIMIT; i++) {
        g = atomic_load_explicit(&pool->generation, memory_order_acquire);
        if (g != seen) return g;
        cpu_relax();
    }
    pthread_mutex_lock(&pool->mutex);
    while ((g = atomic_load_explicit(&pool->generation, memory_order_acquire)) == seen)
        pthread_cond_wait(&pool->wake, &pool->mutex);
    pthread_mutex_unlock(&pool->mutex);
    return g;
}

static void *worker_main(void *arg) {
    worker_arg *wa = arg;
    rt_pool *pool = wa->pool;
    unsigned long seen = 0;
    for (;;) {
        seen = wait_for_job(pool, seen);
        if (atomic_load(&pool->stop)) break;
        pool->fn(pool->ctx, wa->index, pool->size);
        if (atomic_fetch_sub_explicit(&pool->remaining, 1, memory_order_acq_rel) == 1) {
            pthread_mutex_lock(&pool->mutex);
            pthread_cond_broadcast(&pool->done);
            pthread_mutex_unlock(&pool->mutex);
        }
    }
    return NULL;
}

static void stop_threads(rt_pool *pool) {
    pthread_mutex_lock(&pool->mutex);
    atomic_store(&pool->stop, 1);
    atomic_fetch_add_explicit(&pool->generation, 1, memory_order_release);
    pthread_cond_broadcast(&pool->wake);
    pthread_mutex_unlock(&pool->mutex);
    for (int i = 0; i < pool->started; i++) pthread_join(pool->threads[i], NULL);
}

rt_pool *rt_pool_create(int threads) {
    if (threads <= 0) threads = rt_cpu_count();
    rt_pool *pool = calloc(1, sizeof *pool);
    if (!pool) return NULL;
    pool->size = threads;
    pool->threads = calloc((size_t)threads, sizeof *pool->threads);
    pool->args = calloc((size_t)threads, sizeof *pool->args);
    if (!pool->threads || !pool->args) {
        free(pool->threads);
        free(pool->args);
        free(pool);
        return NULL;
    }
    pthread_mutex_init(&pool->mutex, NULL);
    pthread_mutex_init(&pool->run_lock, NULL);
    pthread_cond_init(&pool->wake, NULL);
    pthread_cond_init(&pool->done, NULL);
    atomic_init(&pool->generation, 0);
    atomic_init(&pool->remaining, 0);
    atomic_init(&pool->stop, 0);
    for (int i = 1; i < threads; i++) {
        pool->args[i].pool = pool;
        pool->args[i].index = i;
        if (pthread_create(&pool->threads[pool->started], NULL, worker_main, &pool->args[i]) != 0)
            break;
        pool->started++;
    }
    if (pool->started != threads - 1) {
        /* A pool with fewer workers than asked would silently change the
         * meaning of worker_count; refuse instead. */
        stop_threads(pool);
        pool->started = 0;
        rt_pool_destroy(pool);
        return NULL;
    }
    return pool;
}

void rt_pool_destroy(rt_pool *pool) {
    if (!pool) return;
    if (pool->started) stop_threads(pool);
    pthread_mutex_destroy(&pool->mutex);
    pthread_mutex_destroy(&pool->run_lock);
    pthread_cond_destroy(&pool->wake);
    pthread_cond_destroy(&pool->done);
    free(pool->threads);
    free(pool->args);
    free(pool);
}

int rt_pool_size(const rt_pool *pool) {
    return pool ? pool->size : 1;
}

void rt_pool_run(rt_pool *pool, rt_pool_fn fn, void *ctx) {
    if (!pool || pool->size == 1) {
        fn(ctx, 0, 1);
        return;
    }
    pthread_mutex_lock(&pool->run_lock);
    pool->fn = fn;
    pool->ctx = ctx;
    atomic_store_explicit(&pool->remaining, pool->size - 1, memory_order_relaxed);
    pthread_mutex_lock(&pool->mutex);
    atomic_fetch_add_explicit(&pool->generation, 1, memory_order_release);
    pthread_cond_broadcast(&pool->wake);
    pthread_mutex_unlock(&pool->mutex);

    fn(ctx, 0, pool->size);

    int spins = 0;
    while (atomic_load_explicit(&pool->remaining, memory_order_acquire) != 0 &&
           spins++ < SPIN_LIMIT)
        cpu_relax();
    if (atomic_load_explicit(&pool->remaining, memory_order_acquire) != 0) {
        pthread_mutex_lock(&pool->mutex);
        while (atomic_load_explicit(&pool->remaining, memory_order_acquire) != 0)
            pthread_cond_wait(&pool->done, &pool->mutex);
        pthread_mutex_unlock(&pool->mutex);
    }
    pthread_mutex_unlock(&pool->run_lock);
}

typedef struct fp_job {
    rt_pool_fn fn;
    void *ctx;
    int flush;
} fp_job;

static void fp_job_run(void *ctx, int worker, int worker_count) {
    const fp_job *job = ctx;
    rt_fp_saved saved = rt_fp_set_flush(job->flush);
    job->fn(job->ctx, worker, worker_count);
    rt_fp_restore(saved);
}

void rt_pool_run_fp(rt_pool *pool, rt_pool_fn fn, void *ctx, int flush) {
    fp_job job = {fn, ctx, flush};
    rt_pool_run(pool, fp_job_run, &job);
}
