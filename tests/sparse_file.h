/* Readers against a header that lies (tests/test_ply.c, test_pcd.c, test_las.c): a 2 GiB sparse
 * file whose header announces 10^9 points must fail from its header, at once, without reading or
 * allocating for the body. Before the readers mapped their files (io/file_bytes.h) such a file
 * took 16-23 s and 2.1 GB of memory to fail. Call pnpr_sparse_check before any other test of the
 * executable: the process's peak RSS (getrusage) is then the read's own, and its growth means
 * something. The sparse file is removed afterwards. */
#ifndef PNPR_SPARSE_FILE_H
#define PNPR_SPARSE_FILE_H

#include "testutil.h"

#include <pointnpr/io.h>

#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#define PNPR_SPARSE_SIZE ((off_t)2 << 30)   /* 2 GiB, all of it a hole after the header */
#define PNPR_SPARSE_MAX_RSS_KB (64L * 1024) /* allowed growth of the peak RSS */

static inline long pnpr_sparse_peak_kb(void)
{
    struct rusage ru;
    return getrusage(RUSAGE_SELF, &ru) == 0 ? ru.ru_maxrss : -1;
}

static inline double pnpr_sparse_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Writes head, then extends the file to PNPR_SPARSE_SIZE bytes without writing them. */
static inline int pnpr_sparse_write(const char *path, const void *head, size_t n)
{
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) return 0;
    int ok = write(fd, head, n) == (ssize_t)n && ftruncate(fd, PNPR_SPARSE_SIZE) == 0;
    return close(fd) == 0 && ok;
}

/* Reads the sparse file made of head through pnpr_read_file: expects `expected`, the message
 * "<path>: <message>" exactly, an empty cloud and little memory (the old readers read the whole
 * file first: 2.1 GB). The time is printed, not asserted: a loaded machine must not fail a test. */
static inline void pnpr_sparse_check(const char *path, const void *head, size_t n, pnpr_status expected,
                                     const char *message)
{
    if (!pnpr_sparse_write(path, head, n)) {
        CHECK_MSG(0, "%s: cannot create the sparse file", path);
        remove(path);
        return;
    }
    pnpr_cloud c = {0};
    pnpr_error err;
    memset(&err, 0, sizeof err);
    const long rss0 = pnpr_sparse_peak_kb();
    const double t0 = pnpr_sparse_now();
    pnpr_status st = pnpr_read_file(path, NULL, &c, &err);
    const double seconds = pnpr_sparse_now() - t0;
    const long grown = pnpr_sparse_peak_kb() - rss0;
    remove(path);
    char want[sizeof err.message + 64];
    snprintf(want, sizeof want, "%s: %s", path, message);
    printf("sparse %s: %.3f s, peak RSS +%ld KB: %s\n", strrchr(path, '/') + 1, seconds, grown, err.message);
    CHECK_STATUS(st, expected);
    CHECK_MSG(strcmp(err.message, want) == 0, "got  \"%s\"\nwant \"%s\"", err.message, want);
    CHECK_MSG(rss0 > 0 && grown < PNPR_SPARSE_MAX_RSS_KB, "%s: peak RSS grew by %ld KB", path, grown);
    CHECK(c.count == 0 && c.xyz == NULL);
    pnpr_cloud_free(&c);
}

#endif
