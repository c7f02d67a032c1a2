/* Input files as one read-only byte range (io/file_bytes.h): mapped when regular, read otherwise. */
#define _DEFAULT_SOURCE /* madvise(MADV_DONTNEED): POSIX's posix_madvise ignores DONTNEED on glibc */
#include "file_bytes.h"
#include "../core/internal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#define FB_CHUNK ((size_t)1 << 30) /* largest single read() */

/* Reads the rest of fd into a heap buffer that grows by doubling; hint = expected size or 0. */
static pnpr_status fb_read_all(int fd, const char *path, size_t hint, pnpr_file_bytes *fb, pnpr_error *err)
{
    size_t cap = hint && hint < SIZE_MAX ? hint + 1 : 65536, len = 0; /* + 1: the end is seen without growing */
    unsigned char *buf = malloc(cap);
    while (buf) {
        if (len == cap) {
            unsigned char *grown = cap <= SIZE_MAX / 2 ? realloc(buf, 2 * cap) : NULL;
            if (!grown) break;
            buf = grown;
            cap *= 2;
        }
        size_t want = cap - len < FB_CHUNK ? cap - len : FB_CHUNK;
        ssize_t got = read(fd, buf + len, want);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            int e = errno;
            free(buf);
            return pnpr_error_set(err, PNPR_ERR_IO, "%s: read error: %s", path, strerror(e));
        }
        if (got == 0) {
            fb->copy = buf;
            fb->data = buf;
            fb->size = len;
            return PNPR_OK;
        }
        len += (size_t)got;
    }
    free(buf);
    return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: file too large for memory", path);
}

/* A regular file: mapped read-only; read instead when it cannot be mapped or reports size 0
 * (files of /proc and the like have content but no size). */
static pnpr_status fb_map(int fd, const char *path, off_t st_size, pnpr_file_bytes *fb, pnpr_error *err)
{
    if ((uintmax_t)st_size > (uintmax_t)SIZE_MAX)
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: %lld bytes do not fit in the address space", path,
                              (long long)st_size);
    size_t size = (size_t)st_size;
    if (size == 0) return fb_read_all(fd, path, 0, fb, err);
    void *m = mmap(NULL, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (m == MAP_FAILED) return fb_read_all(fd, path, size, fb, err);
    (void)posix_madvise(m, size, POSIX_MADV_SEQUENTIAL); /* a hint: failure changes nothing */
    fb->map = m;
    fb->data = m;
    fb->size = size;
    return PNPR_OK;
}

pnpr_status pnpr_file_bytes_open(const char *path, pnpr_file_bytes *fb, pnpr_error *err)
{
    memset(fb, 0, sizeof *fb);
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    struct stat sb;
    pnpr_status st;
    if (fstat(fd, &sb) != 0)
        st = pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, strerror(errno));
    else if (S_ISDIR(sb.st_mode))
        st = pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, strerror(EISDIR));
    else if (S_ISREG(sb.st_mode))
        st = fb_map(fd, path, sb.st_size, fb, err);
    else
        st = fb_read_all(fd, path, 0, fb, err);
    close(fd);
    if (st != PNPR_OK) memset(fb, 0, sizeof *fb);
    return st;
}

void pnpr_file_bytes_drop(const pnpr_file_bytes *fb, size_t from, size_t upto)
{
    if (!fb || !fb->map || upto > fb->size) return;
    size_t page = (size_t)sysconf(_SC_PAGESIZE), lo = (from + page - 1) / page * page, hi = upto / page * page;
    if (hi > lo) (void)madvise((unsigned char *)fb->map + lo, hi - lo, MADV_DONTNEED); /* private, read-only */
}

void pnpr_file_bytes_close(pnpr_file_bytes *fb)
{
    if (!fb) return;
    if (fb->map) munmap(fb->map, fb->size);
    free(fb->copy);
    memset(fb, 0, sizeof *fb);
}

pnpr_status pnpr_file_bytes_read(const char *path, pnpr_memory_reader read, const pnpr_read_options *opts,
                                 pnpr_cloud *cloud, pnpr_error *err)
{
    pnpr_cloud_free(cloud);
    pnpr_file_bytes fb; /* mapped: each reader checks its header against the size before the body */
    pnpr_status st = pnpr_file_bytes_open(path, &fb, err);
    if (st != PNPR_OK) return st;
    st = read(fb.data, fb.size, opts, cloud, err);
    pnpr_file_bytes_close(&fb);
    if (st != PNPR_OK) pnpr_error_prefix_path(err, path);
    return st;
}
