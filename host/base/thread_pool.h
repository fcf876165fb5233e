/* SPDX-License-Identifier: Apache-2.0 */
/* thread_pool.h - a persistent pool of pthreads.
 *
 * Threads are created once and sleep between jobs, so a build or a frame costs
 * no thread creation. One job runs at a time; the calling thread takes part as
 * worker 0.
 */
#ifndef RT_THREAD_POOL_H
#define RT_THREAD_POOL_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rt_pool rt_pool;

/* Runs on every worker: worker is 0..worker_count-1. */
typedef void (*rt_pool_fn)(void *ctx, int worker, int worker_count);

/* threads <= 0: one per online core. Returns NULL when out of memory or when
 * no thread could be created. */
rt_pool *rt_pool_create(int threads);
void rt_pool_destroy(rt_pool *pool);
int rt_pool_size(const rt_pool *pool);

/* Calls fn(ctx, w, n) once for each worker w and returns when all are done. */
void rt_pool_run(rt_pool *pool, rt_pool_fn fn, void *ctx);

/* As rt_pool_run, with each worker's denormal mode set for the job (flush 1:
 * flush-to-zero and denormals-are-zero; 0: IEEE gradual underflow, whatever
 * the thread had) and restored afterwards; see kernels/rt_fp_mode.h. The
 * CPU backends trace so, and nothing else runs in that mode. */
void rt_pool_run_fp(rt_pool *pool, rt_pool_fn fn, void *ctx, int flush);

/* Number of online cores. */
int rt_cpu_count(void);

#ifdef __cplusplus
}
#endif
#endif /* RT_THREAD_POOL_H */
