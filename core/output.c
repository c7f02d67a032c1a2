/* Output files that never destroy data (include/pointnpr/output.h, docs/security.md). */
#define _GNU_SOURCE /* realpath, getrandom */
#include <pointnpr/output.h>

#include "internal.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* The temporaries table: a slot is free (0), being filled or emptied (1), or holds the name of
 * an existing temporary (2). Only the signal handler reads it without owning the slot. */
#define OUT_SLOTS 32
static atomic_int out_slot_state[OUT_SLOTS];
static char out_slot_path[OUT_SLOTS][PNPR_OUTPUT_PATH_MAX];

static int out_slot_claim(const char *tmp)
{
    for (int s = 0; s < OUT_SLOTS; s++) {
        int expected = 0;
        if (!atomic_compare_exchange_strong(&out_slot_state[s], &expected, 1)) continue;
        memcpy(out_slot_path[s], tmp, strlen(tmp) + 1);
        atomic_store(&out_slot_state[s], 2);
        return s;
    }
    return -1; /* full: this temporary is not removed on a signal (documented) */
}

static void out_slot_release(int s)
{
    if (s >= 0 && s < OUT_SLOTS) atomic_store(&out_slot_state[s], 0);
}

void pnpr_output_remove_temporaries(void)
{
    for (int s = 0; s < OUT_SLOTS; s++)
        if (atomic_load(&out_slot_state[s]) == 2) unlink(out_slot_path[s]);
}

static void out_on_signal(int sig)
{
    pnpr_output_remove_temporaries();
    signal(sig, SIG_DFL);
    raise(sig);
}

int pnpr_output_cleanup_on_signals(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = out_on_signal;
    sigemptyset(&sa.sa_mask);
    int bad = 0;
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) bad |= sigaction(sigs[i], &sa, NULL) != 0;
    return bad ? -1 : 0;
}

/* 16 hex digits from the kernel's random source (a clock/address mix if it is unavailable). */
static void out_random_hex(char r[17])
{
    uint64_t v = 0;
    if (getrandom(&v, sizeof v, GRND_NONBLOCK) != (ssize_t)sizeof v) {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        v = ((uint64_t)ts.tv_nsec << 20) ^ (uint64_t)ts.tv_sec ^ ((uint64_t)getpid() << 40) ^ (uint64_t)(uintptr_t)r;
    }
    snprintf(r, 17, "%016llx", (unsigned long long)v);
}

/* What `path` is now: sets o->mode and o->target (a link to a regular file: its target). */
static pnpr_status out_resolve(pnpr_output *o, const char *path, pnpr_error *err)
{
    struct stat lsb, sb;
    snprintf(o->target, sizeof o->target, "%s", path);
    o->mode = PNPR_OUTPUT_REPLACE;
    if (lstat(path, &lsb) != 0) {
        if (errno == ENOENT) return PNPR_OK;
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, strerror(errno));
    }
    sb = lsb;
    if (S_ISLNK(lsb.st_mode) && stat(path, &sb) != 0)
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: a symbolic link to nothing (%s); refusing to create its target",
                              path, strerror(errno));
    if (S_ISDIR(sb.st_mode)) return pnpr_error_set(err, PNPR_ERR_IO, "%s: is a directory", path);
    if (!S_ISREG(sb.st_mode)) {
        o->mode = PNPR_OUTPUT_THROUGH;
        return PNPR_OK;
    }
    if (access(path, W_OK) != 0) /* a write-protected file is not replaced behind the user's back */
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: not writable (%s); not replaced", path, strerror(errno));
    if (S_ISLNK(lsb.st_mode)) {
        char *real = realpath(path, NULL);
        if (!real) return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, strerror(errno));
        int fits = strlen(real) < sizeof o->target;
        if (fits) memcpy(o->target, real, strlen(real) + 1);
        free(real);
        if (!fits) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: the link's target path is too long", path);
    }
    return PNPR_OK;
}

/* Creates o->tmp exclusively next to o->target and opens o->f on it. */
static pnpr_status out_open_temporary(pnpr_output *o, pnpr_error *err)
{
    const char *slash = strrchr(o->target, '/');
    int dir_len = slash ? (int)(slash - o->target + 1) : 0;
    const char *base = slash ? slash + 1 : o->target;
    struct stat sb;
    mode_t mode = stat(o->target, &sb) == 0 && S_ISREG(sb.st_mode) ? (sb.st_mode & 07777) : 0666;
    int fd = -1;
    for (int attempt = 0; attempt < 64 && fd < 0; attempt++) {
        char hex[17];
        out_random_hex(hex);
        /* the base is shortened so that the name stays within NAME_MAX (255) */
        int n = snprintf(o->tmp, sizeof o->tmp, "%.*s.%.200s.%s.part", dir_len, o->target, base, hex);
        if (n < 0 || (size_t)n >= sizeof o->tmp)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: path too long", o->path);
        /* read-write: a writer may map the temporary (pnpr_tile_merge places records by index) */
        fd = open(o->tmp, O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
        if (fd < 0 && errno != EEXIST)
            return pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot create a temporary file in its folder: %s", o->path,
                                  strerror(errno));
    }
    if (fd < 0) return pnpr_error_set(err, PNPR_ERR_IO, "%s: no free temporary name in its folder", o->path);
    if (mode != 0666) (void)fchmod(fd, mode); /* a replaced file keeps its permission bits */
    o->slot = out_slot_claim(o->tmp);
    o->f = fdopen(fd, "wb");
    if (!o->f) {
        int e = errno;
        close(fd);
        unlink(o->tmp);
        out_slot_release(o->slot);
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", o->path, strerror(e));
    }
    return PNPR_OK;
}

/* Opens a special file (device, FIFO, socket) to write through it. */
static pnpr_status out_open_through(pnpr_output *o, pnpr_error *err)
{
    int fd = open(o->path, O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", o->path, strerror(errno));
    struct stat sb;
    if (fstat(fd, &sb) != 0 || S_ISREG(sb.st_mode) || S_ISDIR(sb.st_mode)) {
        close(fd); /* it was replaced by a regular file since it was looked at: not written through */
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: changed while it was opened; not written", o->path);
    }
    o->f = fdopen(fd, "wb");
    if (!o->f) {
        int e = errno;
        close(fd);
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", o->path, strerror(e));
    }
    return PNPR_OK;
}

pnpr_status pnpr_output_open(pnpr_output *o, const char *path, pnpr_error *err)
{
    if (!o) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "pnpr_output_open: NULL output");
    memset(o, 0, offsetof(pnpr_output, path));
    o->slot = -1;
    o->path[0] = o->target[0] = o->tmp[0] = '\0';
    if (!path || !path[0]) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "no output path");
    if (strlen(path) >= sizeof o->path)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%.64s...: path too long", path);
    memcpy(o->path, path, strlen(path) + 1);
    if (!strcmp(path, "-")) {
        o->mode = PNPR_OUTPUT_STDOUT;
        o->f = stdout;
        return PNPR_OK;
    }
    pnpr_status st = out_resolve(o, path, err);
    if (st != PNPR_OK) return st;
    return o->mode == PNPR_OUTPUT_THROUGH ? out_open_through(o, err) : out_open_temporary(o, err);
}

int pnpr_output_sink(void *user, const void *data, size_t size)
{
    pnpr_output *o = user;
    if (fwrite(data, 1, size, o->f) == size) return 0;
    if (!o->write_errno) o->write_errno = errno ? errno : EIO;
    return 1;
}

/* Closes o->f (flushes stdout); returns 0 or the errno of the failure. A failed stdio write
 * keeps its data buffered, so the final flush fails again and tells the reason. */
static int out_finish_stream(pnpr_output *o)
{
    int had_error = ferror(o->f), e = 0;
    errno = 0;
    int rc = o->mode == PNPR_OUTPUT_STDOUT ? fflush(o->f) : fclose(o->f);
    if (rc != 0) e = errno ? errno : EIO;
    else if (had_error) e = o->write_errno ? o->write_errno : EIO;
    o->f = NULL;
    return e;
}

pnpr_status pnpr_output_close(pnpr_output *o, pnpr_status writer_status, pnpr_error *err)
{
    if (!o || !o->f) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "pnpr_output_close: not open");
    int e = out_finish_stream(o);
    if (!e) e = o->write_errno;
    if (!e && writer_status == PNPR_ERR_IO && !(err && err->message[0])) e = EIO;
    if (writer_status == PNPR_OK && !e && o->mode == PNPR_OUTPUT_REPLACE && rename(o->tmp, o->target) != 0)
        e = errno;
    if (o->mode == PNPR_OUTPUT_REPLACE && (writer_status != PNPR_OK || e)) unlink(o->tmp);
    out_slot_release(o->slot);
    o->slot = -1;
    if (e && (writer_status == PNPR_OK || writer_status == PNPR_ERR_IO))
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot write: %s", o->path, strerror(e));
    return writer_status;
}

/* Whether the folder that holds `target` (a file name) can take a new file. */
static pnpr_status out_check_folder(const char *path, const char *target, pnpr_error *err)
{
    char dir[PNPR_OUTPUT_PATH_MAX];
    const char *slash = strrchr(target, '/');
    if (!slash) memcpy(dir, ".", 2);
    else if (slash == target) memcpy(dir, "/", 2);
    else snprintf(dir, sizeof dir, "%.*s", (int)(slash - target), target);
    if (access(dir, W_OK | X_OK) != 0)
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot write into the folder %s: %s", path, dir, strerror(errno));
    return PNPR_OK;
}

pnpr_status pnpr_output_check(const char *path, const char *const *inputs, size_t input_count, pnpr_error *err)
{
    if (!path || !path[0]) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "no output path");
    if (!strcmp(path, "-")) return PNPR_OK;
    if (strlen(path) >= PNPR_OUTPUT_PATH_MAX)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%.64s...: path too long", path);
    pnpr_output *o = malloc(sizeof *o);
    if (!o) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    memcpy(o->path, path, strlen(path) + 1);
    pnpr_status st = out_resolve(o, path, err);
    struct stat sb, ib;
    int exists = st == PNPR_OK && stat(path, &sb) == 0;
    for (size_t i = 0; exists && i < input_count; i++)
        if (inputs[i] && stat(inputs[i], &ib) == 0 && ib.st_dev == sb.st_dev && ib.st_ino == sb.st_ino)
            st = pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT,
                                "%s: is the input %s; refusing to write over it (name another output file)", path,
                                inputs[i]);
    if (st == PNPR_OK && o->mode == PNPR_OUTPUT_THROUGH && access(path, W_OK) != 0)
        st = pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, strerror(errno));
    if (st == PNPR_OK && o->mode == PNPR_OUTPUT_REPLACE) st = out_check_folder(path, o->target, err);
    free(o);
    return st;
}

pnpr_status pnpr_output_write(const char *path, pnpr_output_fn fn, const void *ctx, pnpr_error *err)
{
    pnpr_output *o = malloc(sizeof *o);
    if (!o) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory", path ? path : "output");
    pnpr_status st = pnpr_output_open(o, path, err);
    if (st == PNPR_OK) {
        if (err) err->message[0] = '\0';
        int bad = fn(o->f, ctx);
        if (bad && ferror(o->f) && !o->write_errno) o->write_errno = errno ? errno : EIO;
        st = pnpr_output_close(o, bad ? PNPR_ERR_IO : PNPR_OK, err);
    }
    free(o);
    return st;
}
