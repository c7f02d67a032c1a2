/* Files written through a temporary name and renamed when complete (see core/internal.h). */
#include "internal.h"

#include <errno.h>
#include <string.h>

pnpr_status pnpr_file_begin(const char *path, char *tmp, size_t cap, FILE **r_f, pnpr_error *err)
{
    *r_f = NULL;
    if (!path || !path[0]) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "no output path");
    if ((size_t)snprintf(tmp, cap, "%s.tmp", path) >= cap)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: path too long", path);
    *r_f = fopen(tmp, "wb");
    if (!*r_f) return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, strerror(errno));
    return PNPR_OK;
}

pnpr_status pnpr_file_commit(FILE *f, const char *tmp, const char *path, int write_failed, pnpr_error *err)
{
    int bad = write_failed || ferror(f);
    if (fclose(f) != 0) bad = 1;
    if (!bad && rename(tmp, path) == 0) return PNPR_OK;
    int e = errno;
    remove(tmp);
    return pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot write (%s)", path, strerror(e ? e : EIO));
}
