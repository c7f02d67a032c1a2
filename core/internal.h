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

/* Writing a file so that a failure never leaves half a file: pnpr_file_begin opens path + ".tmp"
 * (tmp must hold the name, cap bytes); pnpr_file_commit closes it and renames it onto path, or
 * removes it when write_failed or any write/close error happened. Errors name the path. */
#include <stdio.h>
pnpr_status pnpr_file_begin(const char *path, char *tmp, size_t cap, FILE **r_f, pnpr_error *err);
pnpr_status pnpr_file_commit(FILE *f, const char *tmp, const char *path, int write_failed, pnpr_error *err);

/* Prefixes err->message with "path: " (truncating the message's end if needed). NULL err ok. */
void pnpr_error_prefix_path(pnpr_error *err, const char *path);

/* Monotonic clock in seconds. */
double pnpr_now(void);

#endif
