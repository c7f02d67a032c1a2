/* Internal helpers shared by the library's .c files (not installed). */
#ifndef PNPR_INTERNAL_H
#define PNPR_INTERNAL_H

#include <pointnpr/core.h>

/* Runs fn(ctx, begin, end) over [0, n) in chunks of `chunk` items on `threads` threads
 * (0 = all cores; the calling thread works too). Progress is reported from the calling thread
 * as `stage` with the fraction of items done; a cancel request stops handing out chunks and
 * returns PNPR_ERR_CANCELLED. fn must be safe to run concurrently on disjoint ranges. */
typedef void (*pnpr_range_fn)(void *ctx, size_t begin, size_t end);
pnpr_status pnpr_parallel_for(size_t n, size_t chunk, int threads, pnpr_range_fn fn, void *ctx,
                              const pnpr_progress *progress, const char *stage);

/* Prefixes err->message with "path: " (truncating the message's end if needed). NULL err ok. */
void pnpr_error_prefix_path(pnpr_error *err, const char *path);

/* Monotonic clock in seconds. */
double pnpr_now(void);

#endif
