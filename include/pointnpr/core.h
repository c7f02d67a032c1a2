/* pointnpr — non-photorealistic rendering of point clouds.
 * core.h: version, status codes, error details, progress/cancel callback.
 *
 * Rules every module follows:
 *  - every fallible call returns pnpr_status and never aborts or exits;
 *  - options structs are valid when zero-initialised (zero = documented default);
 *  - no global mutable state: everything lives in caller-provided objects. */
#ifndef POINTNPR_CORE_H
#define POINTNPR_CORE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PNPR_VERSION_MAJOR 0
#define PNPR_VERSION_MINOR 1
#define PNPR_VERSION_PATCH 0
#define PNPR_VERSION_STRING "0.1.0"

/* Functions that return a pnpr_status are marked so that a caller who drops the status gets a
 * warning (an error under -Werror): every status is either handled or explicitly discarded. */
#if defined(__GNUC__) || defined(__clang__)
#define PNPR_NODISCARD __attribute__((warn_unused_result))
#else
#define PNPR_NODISCARD
#endif

typedef enum pnpr_status {
    PNPR_OK = 0,
    PNPR_ERR_INVALID_ARGUMENT, /* NULL pointer, negative/zero size where not allowed, bad option */
    PNPR_ERR_OUT_OF_MEMORY,
    PNPR_ERR_IO,               /* cannot open/read/write a file */
    PNPR_ERR_FORMAT,           /* corrupt or unsupported file content (details in pnpr_error) */
    PNPR_ERR_TRUNCATED,        /* file ends before the data its header announces */
    PNPR_ERR_UNSUPPORTED,      /* valid input that this build cannot handle */
    PNPR_ERR_EMPTY,            /* the operation needs at least one (valid) point */
    PNPR_ERR_CANCELLED,        /* the progress callback asked to stop */
    PNPR_ERR_NOT_FOUND,        /* a named property/element does not exist */
    PNPR_ERR_NUMERIC,          /* NaN/Inf where a finite number is required */
    PNPR_STATUS_COUNT_
} pnpr_status;

/* Static English text for a status; never NULL (unknown values give "unknown status"). */
const char *pnpr_status_string(pnpr_status status);

/* Optional detail for a failed call: filled by functions that take it (may be NULL).
 * message: one line, e.g. "x.ply: line 12: expected 3 vertex values, found 2".
 * offset: byte offset in the input where the problem was found, or -1. line: 1-based, or 0. */
typedef struct pnpr_error {
    char message[512];
    long long offset;
    long line;
} pnpr_error;

/* Fills err (if not NULL) with a printf-style message; returns status unchanged so that
 * callers can write `return pnpr_error_set(err, PNPR_ERR_FORMAT, ...)`. */
pnpr_status pnpr_error_set(pnpr_error *err, pnpr_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Loads a whole text file (for the memory parsers, e.g. pnpr_style_map_parse): *r_text holds
 * *r_size bytes and a terminating NUL, owned by the caller (free). A file larger than max_size
 * bytes is refused (PNPR_ERR_UNSUPPORTED); PNPR_ERR_IO "PATH: reason" when it cannot be read. */
PNPR_NODISCARD pnpr_status pnpr_text_file_load(const char *path, size_t max_size, char **r_text, size_t *r_size, pnpr_error *err);

/* Progress/cancel callback. `fraction` in [0,1] for the named stage. Return non-zero to cancel:
 * the running call then stops as soon as it can and returns PNPR_ERR_CANCELLED.
 * May be called from the calling thread only (never from worker threads). */
typedef int (*pnpr_progress_fn)(void *user, const char *stage, double fraction);

typedef struct pnpr_progress {
    pnpr_progress_fn fn; /* NULL = no reporting, never cancelled */
    void *user;
} pnpr_progress;

/* Returns non-zero when the caller asked to cancel. Safe with progress == NULL. */
int pnpr_progress_report(const pnpr_progress *progress, const char *stage, double fraction);

/* Releases memory the library handed over to the caller (e.g. pnpr_kdtree_detach). NULL ok. */
void pnpr_free(void *p);

/* Number of worker threads to use when an option says 0 (= all cores). At least 1. */
int pnpr_default_threads(void);

/* Every `threads` option is clamped to this many (and to the number of work chunks): a larger
 * value starts no more threads. */
#define PNPR_THREADS_MAX 1024

#ifdef __cplusplus
}
#endif
#endif
