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

/* The lines of a text in memory (core/text_file.c): copies the line that starts at *pos, without
 * its '\n' (a NUL byte ends its content), into buf (cap bytes, NUL-terminated) and moves *pos
 * past it. 1: a line; 0: the end of the text; -1: a line of cap - 1 characters or more. */
int pnpr_text_line(const char *text, size_t size, size_t *pos, char *buf, size_t cap);

/* Joins the `count` names (those whose bit i is set in `skip` left out, i < 32) with `sep` into
 * buf (cap > 0 bytes, NUL-terminated, truncated to fit). Returns buf. The lists of names in
 * messages and usage texts (styles, brush presets). */
const char *pnpr_join_names(char *buf, size_t cap, const char *sep, const char *const *names, size_t count,
                            uint32_t skip);

/* qsort comparator of floats, ascending (core/median.c). */
int pnpr_cmp_float(const void *a, const void *b);
/* qsort comparator of uint32_t (indices, labels), ascending (core/median.c). */
int pnpr_cmp_u32(const void *a, const void *b);
/* The same for uint64_t (packed keys: value << 32 | index). */
int pnpr_cmp_u64(const void *a, const void *b);
/* The k-th smallest of v[0..n) (k < n): v is reordered so that v[k] holds it, no larger value
 * before it and no smaller after it (the rest unsorted); expected O(n). */
float pnpr_select_float(float *v, size_t n, size_t k);
double pnpr_select_double(double *v, size_t n, size_t k);
/* The median of v[0..n), n > 0: v[n / 2] of the sorted order (v is reordered, pnpr_select_float). */
float pnpr_median_float(float *v, size_t n);

/* Permutes n elements of `size` bytes (at most 24) through `scratch` (n * size bytes). forward: the element
 * at position p moves to perm[p]; else the element at perm[p] moves to p (core/cloud.c). */
void pnpr_permute(void *data, size_t size, size_t n, const uint32_t *perm, int forward, char *scratch);

/* Monotonic clock in seconds. */
double pnpr_now(void);

#endif
