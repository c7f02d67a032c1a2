/* A minimal parallel-for over index ranges (pthreads, dynamic chunking with an atomic counter). */
#include "internal.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <time.h>

double pnpr_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct job {
    size_t n, chunk;
    pnpr_range_fn fn;
    void *ctx;
    atomic_size_t next;   /* next chunk start */
    atomic_size_t done;   /* items finished */
    atomic_int stop;
} job;

/* Takes and runs one chunk; returns 0 when there is no work left. */
static int run_one(job *j)
{
    if (atomic_load_explicit(&j->stop, memory_order_relaxed)) return 0;
    size_t b = atomic_fetch_add(&j->next, j->chunk);
    if (b >= j->n) return 0;
    size_t e = j->n - b < j->chunk ? j->n : b + j->chunk;
    j->fn(j->ctx, b, e);
    atomic_fetch_add(&j->done, e - b);
    return 1;
}

static void *worker(void *arg)
{
    job *j = arg;
    while (run_one(j)) {}
    return NULL;
}

pnpr_status pnpr_parallel_for(size_t n, size_t chunk, int threads, pnpr_range_fn fn, void *ctx,
                              const pnpr_progress *progress, const char *stage)
{
    if (!fn) return PNPR_ERR_INVALID_ARGUMENT;
    if (n == 0) return PNPR_OK;
    if (chunk == 0) chunk = 1024;
    if (threads <= 0) threads = pnpr_default_threads();
    if (threads > PNPR_THREADS_MAX) threads = PNPR_THREADS_MAX;
    size_t chunks = (n + chunk - 1) / chunk;
    if ((size_t)threads > chunks) threads = (int)chunks;

    job j;
    j.n = n; j.chunk = chunk; j.fn = fn; j.ctx = ctx;
    atomic_init(&j.next, 0);
    atomic_init(&j.done, 0);
    atomic_init(&j.stop, 0);

    pthread_t *tid = NULL;
    int started = 0;
    if (threads > 1) {
        tid = malloc((size_t)(threads - 1) * sizeof *tid);
        if (tid)
            for (; started < threads - 1; started++)
                if (pthread_create(&tid[started], NULL, worker, &j) != 0) break;
    }
    /* The calling thread works too, and reports progress between its chunks. */
    int cancelled = 0;
    if (pnpr_progress_report(progress, stage, 0.0)) { atomic_store(&j.stop, 1); cancelled = 1; }
    while (!cancelled && run_one(&j)) {
        double f = (double)atomic_load(&j.done) / (double)n;
        if (pnpr_progress_report(progress, stage, f)) { atomic_store(&j.stop, 1); cancelled = 1; }
    }
    for (int t = 0; t < started; t++) pthread_join(tid[t], NULL);
    free(tid);
    if (cancelled) return PNPR_ERR_CANCELLED;
    if (pnpr_progress_report(progress, stage, 1.0)) return PNPR_ERR_CANCELLED;
    return PNPR_OK;
}
