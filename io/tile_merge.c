/* The merge of a tiled run (pointnpr/tiles.h): each tile's points written at their source index.
 *
 * Every tile is serialised as binary PLY in memory (one tile at a time: the bound of the run);
 * its records have a fixed size, so record i of the result lies at header + index * size. The
 * result's temporary (output.h) is sized once and mapped, and each record is copied to its place;
 * after each tile the mapping's pages are handed back to the kernel, which writes them to the
 * file, so the process holds a tile and its serialised copy, never the whole result. */
#define _DEFAULT_SOURCE /* madvise(MADV_DONTNEED) */
#include <pointnpr/output.h>
#include <pointnpr/props.h>
#include <pointnpr/tiles.h>

#include "../core/internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

/* The header of a serialised tile: its length, and its text without comments and with the vertex
 * count left out (the layout every tile must share) in sig. 0 when it has no end. */
static size_t header_layout(const pnpr_mem_sink *m, char *sig, size_t cap)
{
    const char *s = (const char *)m->data, *end = s + m->size;
    size_t n = 0;
    while (s < end) {
        const char *e = memchr(s, '\n', (size_t)(end - s));
        if (!e) return 0;
        size_t len = (size_t)(e - s) + 1;
        const char *keep = s;
        if (len > 15 && !strncmp(s, "element vertex ", 15)) len = 15;
        if (!strncmp(s, "comment ", 8)) len = 0;
        if (n + len >= cap) return 0;
        memcpy(sig + n, keep, len);
        n += len;
        sig[n] = '\0';
        s = e + 1;
        if (!strncmp(keep, "end_header\n", 11)) return (size_t)(s - (const char *)m->data);
    }
    return 0;
}

typedef struct merge_run {
    const char *out;
    uint64_t points;
    pnpr_output o;
    unsigned char *map;  /* the mapped result, or NULL before the first tile */
    size_t map_size, head, rec;
    char sig[16384];
    uint8_t *seen;       /* a bit per source index */
} merge_run;

/* The result's temporary sized and mapped, its header written: from the first tile. */
static pnpr_status merge_start(merge_run *r, const pnpr_mem_sink *m, size_t head, size_t rec, pnpr_error *err)
{
    char line[64];
    int ln = snprintf(line, sizeof line, "element vertex %llu\n", (unsigned long long)r->points);
    const char *v = strstr((const char *)m->data, "element vertex ");
    const char *ve = v ? memchr(v, '\n', head - (size_t)(v - (const char *)m->data)) : NULL;
    if (!ve) return pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: merge: a tile's header has no vertex count", r->out);
    size_t before = (size_t)(v - (const char *)m->data), after = head - before - (size_t)(ve + 1 - v);
    r->head = before + (size_t)ln + after;
    r->rec = rec;
    r->map_size = r->head + (size_t)r->points * rec;
    if (r->o.mode != PNPR_OUTPUT_REPLACE)
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: merge: the result is placed by index and must be a regular file", r->out);
    int fd = fileno(r->o.f);
    if (ftruncate(fd, (off_t)r->map_size) != 0)
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot size the result: %s", r->out, strerror(errno));
    void *p = mmap(NULL, r->map_size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (p == MAP_FAILED) return pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot map the result: %s", r->out, strerror(errno));
    r->map = p;
    memcpy(r->map, m->data, before);
    memcpy(r->map + before, line, (size_t)ln);
    memcpy(r->map + before + ln, ve + 1, after);
    return PNPR_OK;
}

/* One tile: read, checked, serialised without its source index, records placed. */
static pnpr_status merge_tile(merge_run *r, const char *path, pnpr_error *err)
{
    pnpr_cloud c = {0};
    pnpr_mem_sink m = {0};
    uint32_t *idx = NULL;
    pnpr_status st = pnpr_read_file(path, NULL, &c, err);
    pnpr_property *si = st == PNPR_OK ? pnpr_cloud_find_property(&c, PNPR_PROP_SOURCE_INDEX) : NULL;
    if (st == PNPR_OK && (!si || si->type != PNPR_TYPE_UINT32))
        st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: no uint property %s: not a tile's result", path, PNPR_PROP_SOURCE_INDEX);
    if (st == PNPR_OK && !(idx = malloc((c.count ? c.count : 1) * sizeof *idx))) st = PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) {
        memcpy(idx, si->data, c.count * sizeof *idx);
        for (size_t i = 0; i < c.count && st == PNPR_OK; i++) {
            if (idx[i] >= r->points || (r->seen[idx[i] >> 3] >> (idx[i] & 7) & 1))
                st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: point %zu: source index %u %s", path, i, idx[i],
                                    idx[i] >= r->points ? "beyond the file's points" : "comes twice (tiles overlap)");
            else r->seen[idx[i] >> 3] |= (uint8_t)(1u << (idx[i] & 7));
        }
    }
    pnpr_write_options wo = {0};
    if (st == PNPR_OK && (st = pnpr_cloud_remove_property(&c, PNPR_PROP_SOURCE_INDEX)) == PNPR_OK)
        st = pnpr_write_ply_stream(pnpr_mem_sink_write, &m, &c, &wo, err);
    char sig[sizeof r->sig];
    size_t head = st == PNPR_OK ? header_layout(&m, sig, sizeof sig) : 0;
    if (st == PNPR_OK && !head) st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: merge: a header too long", path);
    size_t rec = st == PNPR_OK && c.count ? (m.size - head) / c.count : 0;
    if (st == PNPR_OK && c.count && (m.size - head) % c.count)
        st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: merge: records of varying size", path);
    if (st == PNPR_OK && !r->map && (c.count || !r->points)) {
        memcpy(r->sig, sig, sizeof sig);
        st = merge_start(r, &m, head, rec, err);
    } else if (st == PNPR_OK && r->map && (strcmp(sig, r->sig) || (c.count && rec != r->rec))) {
        st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: its properties differ from the first tile's", path);
    }
    for (size_t i = 0; st == PNPR_OK && i < c.count; i++)
        memcpy(r->map + r->head + (size_t)idx[i] * rec, m.data + head + i * rec, rec);
    /* a shared mapping: the records stay in the page cache for the kernel to write back; the
     * process stops holding them, or the whole result would count as its own by the end */
    if (st == PNPR_OK && r->map) (void)madvise(r->map, r->map_size, MADV_DONTNEED);
    free(idx);
    free(m.data);
    pnpr_cloud_free(&c);
    if (st == PNPR_ERR_OUT_OF_MEMORY && !err->message[0]) pnpr_error_set(err, st, "%s: merge: out of memory", path);
    return st;
}

pnpr_status pnpr_tile_merge(const char *const *paths, size_t count, uint64_t points, const char *out,
                            const pnpr_progress *progress, pnpr_error *err)
{
    pnpr_error local = {0};
    if (!err) err = &local;
    err->message[0] = '\0';
    if ((!paths && count) || !out) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "merge: NULL argument");
    if (points >= UINT32_MAX) return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: merge: tiles take fewer than 2^32 points", out);
    merge_run r;
    memset(&r, 0, sizeof r);
    r.out = out;
    r.points = points;
    if (!(r.seen = calloc((size_t)points / 8 + 1, 1))) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: merge: out of memory", out);
    pnpr_status st = pnpr_output_open(&r.o, out, err);
    for (size_t t = 0; st == PNPR_OK && t < count; t++) {
        st = merge_tile(&r, paths[t], err);
        if (st == PNPR_OK && pnpr_progress_report(progress, "merge", (double)(t + 1) / (double)count))
            st = pnpr_error_set(err, PNPR_ERR_CANCELLED, "%s: merge cancelled", out);
    }
    for (uint64_t i = 0; st == PNPR_OK && i < points; i++)
        if (!(r.seen[i >> 3] >> (i & 7) & 1))
            st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: merge: point %llu of %llu is in no tile (a tile missing?)", out,
                                (unsigned long long)i, (unsigned long long)points);
    if (st == PNPR_OK && !r.map) st = pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: merge: no tiles", out);
    if (r.map && munmap(r.map, r.map_size) != 0 && st == PNPR_OK)
        st = pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", out, strerror(errno));
    free(r.seen);
    if (r.o.f) st = pnpr_output_close(&r.o, st, err);
    return st;
}
