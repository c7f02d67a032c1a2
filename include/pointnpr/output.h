/* pointnpr — output.h: how every output file is written, so that no output ever destroys data
 * (docs/security.md has the rules with their reasons).
 *
 * pnpr_output_open decides by what the name is now:
 *  - a regular file, or a name that does not exist yet: the data go to a temporary file created
 *    exclusively (O_CREAT|O_EXCL, so never through a planted symbolic link) in the same directory,
 *    named ".<name>.<16 random hex digits>.part"; pnpr_output_close renames it over the name when
 *    everything was written, and removes it otherwise, so the old file stays as it was. A file
 *    that is replaced keeps its permission bits;
 *  - a symbolic link to a regular file: the file it points to is replaced that way (the link stays);
 *  - a character device, FIFO or socket, or a link to one: written through, never replaced;
 *  - "-": standard output (never closed);
 *  - a directory or a dangling symbolic link: refused (PNPR_ERR_IO).
 * Write errors are reported with the system's reason (e.g. "No space left on device").
 *
 * Temporaries that exist are listed in a small process-wide table (the one piece of global state
 * in the library, see docs/architecture.md) so that pnpr_output_remove_temporaries, which is
 * async-signal-safe, can delete them when the process is interrupted; a command-line program
 * calls pnpr_output_cleanup_on_signals once at start. */
#ifndef POINTNPR_OUTPUT_H
#define POINTNPR_OUTPUT_H

#include <pointnpr/core.h>

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PNPR_OUTPUT_PATH_MAX 4096

typedef enum pnpr_output_mode {
    PNPR_OUTPUT_REPLACE = 0, /* temporary + rename */
    PNPR_OUTPUT_THROUGH,     /* a special file, written through */
    PNPR_OUTPUT_STDOUT       /* "-" */
} pnpr_output_mode;

typedef struct pnpr_output {
    FILE *f;                 /* write here (or pass pnpr_output_sink + this struct to a stream writer) */
    pnpr_output_mode mode;
    int write_errno;         /* the first failed write's errno (set by pnpr_output_sink), 0 = none */
    int slot;                /* index in the temporaries table, -1 = not listed */
    char path[PNPR_OUTPUT_PATH_MAX];   /* the name as given (messages) */
    char target[PNPR_OUTPUT_PATH_MAX]; /* the file that is replaced (a link's target) */
    char tmp[PNPR_OUTPUT_PATH_MAX];    /* the temporary (REPLACE only) */
} pnpr_output;

/* Opens `path` for writing as described above. On failure o->f is NULL, nothing was created
 * and err names the path and the reason. */
PNPR_NODISCARD pnpr_status pnpr_output_open(pnpr_output *o, const char *path, pnpr_error *err);

/* A sink for the library's stream writers (pnpr_write_ply_stream ...): user = the pnpr_output.
 * Returns 0 when all bytes were written, else 1 (and remembers errno). */
int pnpr_output_sink(void *user, const void *data, size_t size);

/* Finishes the output. writer_status is what the writer returned: PNPR_OK commits (rename, or
 * flush for THROUGH/STDOUT); anything else discards the temporary and returns it unchanged, except
 * that a failed write (PNPR_ERR_IO, or an error on o->f) gets a message with the system's reason.
 * Never leaves a temporary behind. */
PNPR_NODISCARD pnpr_status pnpr_output_close(pnpr_output *o, pnpr_status writer_status, pnpr_error *err);

/* The whole cycle for a writer that prints to a FILE: open, fn(f, ctx) (returns 0 when every
 * write succeeded), close. Errors name the path and the system's reason. */
typedef int (*pnpr_output_fn)(FILE *f, const void *ctx);
PNPR_NODISCARD pnpr_status pnpr_output_write(const char *path, pnpr_output_fn fn, const void *ctx, pnpr_error *err);

/* Checks before any work that `path` can be written and is none of the `input_count` inputs
 * (the same file, also through links or other names): an existing directory, a dangling link,
 * a special file that cannot be opened for writing, a folder that does not exist or cannot be
 * written into (for a temporary), and an input are refused with a message naming the path.
 * "-" is accepted. inputs may hold folder names (never equal to a file). */
PNPR_NODISCARD pnpr_status pnpr_output_check(const char *path, const char *const *inputs, size_t input_count, pnpr_error *err);

/* Deletes every temporary currently open (async-signal-safe: only unlink()). */
void pnpr_output_remove_temporaries(void);

/* Installs handlers for SIGINT, SIGTERM, SIGHUP and SIGQUIT that remove the temporaries and then
 * end the process with the same signal (default action). For programs, not for plugins: a host
 * such as MeshLab keeps its own handlers. Returns 0 on success. */
int pnpr_output_cleanup_on_signals(void);

#ifdef __cplusplus
}
#endif
#endif
