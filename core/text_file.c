/* Text files for the memory parsers: loading a file whole, and its lines (core.h, internal.h). */
#include "internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int pnpr_text_line(const char *text, size_t size, size_t *pos, char *buf, size_t cap)
{
    if (*pos >= size) return 0;
    const char *start = text + *pos, *nl = memchr(start, '\n', size - *pos);
    size_t len = nl ? (size_t)(nl - start) : size - *pos;
    *pos += len + (nl != NULL);
    if (len >= cap - 1) return -1;
    memcpy(buf, start, len);
    buf[len] = '\0';
    return 1;
}

static pnpr_status load_fail(FILE *f, char *data, const char *path, pnpr_error *err)
{
    pnpr_status st = pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, strerror(errno));
    free(data);
    if (f) fclose(f);
    return st;
}

pnpr_status pnpr_text_file_load(const char *path, size_t max_size, char **r_text, size_t *r_size, pnpr_error *err)
{
    if (!path || !r_text || !r_size) return PNPR_ERR_INVALID_ARGUMENT;
    *r_text = NULL;
    *r_size = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return load_fail(NULL, NULL, path, err);
    size_t size = 0, cap = 4096;
    char *data = malloc(cap + 1);
    if (!data) { fclose(f); return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory", path); }
    for (size_t got; (got = fread(data + size, 1, cap - size, f)) > 0;) {
        size += got;
        if (size > max_size) {
            free(data);
            fclose(f);
            return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: larger than %zu bytes", path, max_size);
        }
        if (size == cap) {
            char *d2 = realloc(data, 2 * cap + 1);
            if (!d2) { free(data); fclose(f); return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory", path); }
            data = d2;
            cap *= 2;
        }
    }
    if (ferror(f)) return load_fail(f, data, path, err);
    fclose(f);
    data[size] = '\0';
    *r_text = data;
    *r_size = size;
    return PNPR_OK;
}

const char *pnpr_join_names(char *buf, size_t cap, const char *sep, const char *const *names, size_t count,
                            uint32_t skip)
{
    size_t len = 0;
    buf[0] = 0;
    for (size_t i = 0; i < count && len + 1 < cap; i++) {
        if (i < 32 && (skip & (1u << i))) continue;
        int m = snprintf(buf + len, cap - len, "%s%s", len ? sep : "", names[i]);
        if (m < 0) break;
        len += (size_t)m < cap - len ? (size_t)m : cap - len - 1;
    }
    return buf;
}
