/* Helpers the readers and writers share (io/io.c); not installed. */
#ifndef PNPR_IO_UTIL_H
#define PNPR_IO_UTIL_H

#include <pointnpr/io.h>

#include <stdint.h>

#if defined(__GNUC__)
#define PNPR_IO_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define PNPR_IO_PRINTF(a, b)
#endif

/* Sets err (NULL ok) with a formatted message and the line / byte offset it is about (0 / -1 =
 * none); returns st, so that a reader can write `return pnpr_io_fail(err, ...)`. */
pnpr_status pnpr_io_fail(pnpr_error *err, pnpr_status st, long line, long long offset, const char *fmt, ...)
    PNPR_IO_PRINTF(5, 6);

/* The readers other than PLY's refuse a point filter (pnpr_read_options.keep): returns
 * PNPR_ERR_UNSUPPORTED with a message naming `what` ("read las"), or PNPR_OK without one. */
static inline pnpr_status pnpr_io_no_filter(const pnpr_read_options *opts, pnpr_error *err, const char *what)
{
    if (!opts || !opts->keep) return PNPR_OK;
    return pnpr_io_fail(err, PNPR_ERR_UNSUPPORTED, 0, -1,
                        "%s: a point filter (a tile) reads binary PLY only (convert it: pointnpr convert IN -o OUT.ply)",
                        what);
}

/* A cloud's stream writer (pnpr_write_ply_stream, pnpr_write_pcd_stream). */
typedef pnpr_status (*pnpr_io_stream_writer)(pnpr_write_fn fn, void *user, const pnpr_cloud *cloud,
                                            const pnpr_write_options *opts, pnpr_error *err);
/* Writes the cloud to path through `stream` (output.h: a temporary beside the target, replaced
 * atomically; the input is never the target); `what` names the writer in messages ("write ply"). */
pnpr_status pnpr_io_write_path(const char *path, const pnpr_cloud *cloud, const pnpr_write_options *opts,
                               pnpr_error *err, const char *what, pnpr_io_stream_writer stream);

/* The bytes of the PLY scalar type named by t[0..n) ("uchar", "uint8", "float", ...), 0 for none. */
size_t pnpr_ply_type_size(const char *t, size_t n);

/* a * b and a + b saturating at UINT64_MAX (size checks against the bytes present). */
static inline uint64_t pnpr_mul_sat(uint64_t a, uint64_t b) { return a && b > UINT64_MAX / a ? UINT64_MAX : a * b; }
static inline uint64_t pnpr_add_sat(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }

#endif
