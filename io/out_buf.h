/* A buffered output for the stream writers (io/ply.c, io/pcd.c); not installed. Bytes collect in
 * buf (PNPR_OUT_BUF bytes, allocated by the writer) and go to the caller's sink a buffer at a
 * time. After the sink fails once, nothing more is sent; `written` counts the bytes the sink
 * took, for the writer's error message. */
#ifndef PNPR_OUT_BUF_H
#define PNPR_OUT_BUF_H

#include <pointnpr/io.h>

#include <string.h>

#define PNPR_OUT_BUF ((size_t)1 << 20)

typedef struct pnpr_out_buf {
    pnpr_write_fn fn;
    void *user;
    char *buf;
    size_t len;
    unsigned long long written;
    int failed;
} pnpr_out_buf;

static inline void pnpr_out_flush(pnpr_out_buf *o)
{
    if (o->len && !o->failed) {
        if (o->fn(o->user, o->buf, o->len) != 0) o->failed = 1;
        else o->written += o->len;
    }
    o->len = 0;
}

static inline void pnpr_out_bytes(pnpr_out_buf *o, const void *data, size_t n)
{
    const char *s = data;
    while (n && !o->failed) {
        if (o->len == PNPR_OUT_BUF) pnpr_out_flush(o);
        size_t k = PNPR_OUT_BUF - o->len < n ? PNPR_OUT_BUF - o->len : n;
        memcpy(o->buf + o->len, s, k);
        o->len += k;
        s += k;
        n -= k;
    }
}

static inline void pnpr_out_str(pnpr_out_buf *o, const char *s) { pnpr_out_bytes(o, s, strlen(s)); }

/* Room for n more bytes at buf + len (n <= PNPR_OUT_BUF); the caller adds n to len. */
static inline char *pnpr_out_reserve(pnpr_out_buf *o, size_t n)
{
    if (PNPR_OUT_BUF - o->len < n) pnpr_out_flush(o);
    return o->buf + o->len;
}

#endif
