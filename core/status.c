/* Status strings, error details, progress reporting, thread count. */
#include <pointnpr/core.h>
#include "internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const char *pnpr_status_string(pnpr_status status)
{
    switch (status) {
    case PNPR_OK: return "ok";
    case PNPR_ERR_INVALID_ARGUMENT: return "invalid argument";
    case PNPR_ERR_OUT_OF_MEMORY: return "out of memory";
    case PNPR_ERR_IO: return "input/output error";
    case PNPR_ERR_FORMAT: return "corrupt or unsupported file content";
    case PNPR_ERR_TRUNCATED: return "file is truncated";
    case PNPR_ERR_UNSUPPORTED: return "unsupported";
    case PNPR_ERR_EMPTY: return "no (valid) points";
    case PNPR_ERR_CANCELLED: return "cancelled";
    case PNPR_ERR_NOT_FOUND: return "not found";
    case PNPR_ERR_NUMERIC: return "non-finite number";
    case PNPR_STATUS_COUNT_: break;
    }
    return "unknown status";
}

pnpr_status pnpr_error_set(pnpr_error *err, pnpr_status status, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
        err->offset = -1;
        err->line = 0;
    }
    return status;
}

int pnpr_progress_report(const pnpr_progress *progress, const char *stage, double fraction)
{
    if (!progress || !progress->fn)
        return 0;
    if (!(fraction >= 0.0)) fraction = 0.0;
    if (fraction > 1.0) fraction = 1.0;
    return progress->fn(progress->user, stage ? stage : "", fraction) != 0;
}

int pnpr_default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    if (n < 1) return 1;
    if (n > 256) return 256;
    return (int)n;
}

void pnpr_free(void *p)
{
    free(p);
}

void pnpr_error_prefix_path(pnpr_error *err, const char *path)
{
    if (!err || !path) return;
    char msg[sizeof err->message];
    size_t np = strlen(path), nm = strnlen(err->message, sizeof err->message - 1);
    if (np > sizeof msg - 3) np = sizeof msg - 3;
    memcpy(msg, path, np);
    memcpy(msg + np, ": ", 2);
    if (nm > sizeof msg - 1 - (np + 2)) nm = sizeof msg - 1 - (np + 2);
    memcpy(msg + np + 2, err->message, nm);
    msg[np + 2 + nm] = '\0';
    memcpy(err->message, msg, sizeof msg);
}
