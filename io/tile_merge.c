/* The merge of a tiled run (pointnpr/tiles.h): each tile's points written at their source index.
 *
 * Every tile is serialised as binary PLY in memory (one tile at a time: the bound of the run);
 * its records have a fixed size, so record i of the result lies at header + index * size. The
 * result's temporary (output.h) is sized once and mapped, and each record is copied to its place,
 * a 64 MiB window at a time, whose pages are then handed back to the kernel (which writes them to
 * the file), so the process holds a tile and its serialised copy, never the whole result. */
#define _DEFAULT_SOURCE /* madvise(MADV_DONTNEED) */
#include <pointnpr/output.h>
#include <pointnpr/props.h>
#include <pointnpr/tiles.h>

#include "../core/internal.h"
#include "tile_merge.h"
#include "io_util.h"

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
    int seams;           /* normals oriented per tile: make them agree across seams (pnpr_tile_merge) */
    long nx_off;         /* byte of nx in a record, -1: none (or not little-endian floats) */
    double top_z;        /* the highest core point so far, and its source index */
    uint32_t top;
    int have_top;
    pnpr_tile_merge_hook hook; /* called on every tile as read, or NULL */
    void *hook_user;
    size_t tile;               /* the tile being merged */
} merge_run;

/* The byte of "property float nx" in a vertex record of the layout sig (header_layout), -1 when
 * there is none or the floats are not little-endian as this machine's. */
static long normal_offset(const char *sig)
{
    const unsigned one = 1;
    if (!strstr(sig, "format binary_little_endian") || *(const unsigned char *)&one != 1) return -1;
    const char *s = strstr(sig, "element vertex "); /* its count cut off: the properties follow at once */
    long off = 0;
    for (s = s ? s + 15 : NULL; s && !strncmp(s, "property ", 9); s = strchr(s, '\n') ? strchr(s, '\n') + 1 : NULL) {
        const char *t = s + 9, *sp = strchr(t, ' ');
        if (!sp) return -1;
        if (!strncmp(sp + 1, "nx\n", 3)) return !strncmp(t, "float ", 6) ? off : -1;
        size_t z = pnpr_ply_type_size(t, (size_t)(sp - t));
        if (!z) return -1;
        off += (long)z;
    }
    return -1;
}

/* The placed normal of source index i. */
static void placed_normal(const merge_run *r, uint32_t i, float n[3])
{
    memcpy(n, r->map + r->head + (size_t)i * r->rec + (size_t)r->nx_off, 3 * sizeof(float));
}

/* Seams: a tile oriented by its own propagation agrees with the tiles already placed over its
 * halo, or its normals are turned; returns whether they were. */
static int orient_tile(merge_run *r, pnpr_cloud *c, const uint32_t *idx, const uint8_t *core)
{
    if (!r->seams || !r->map || r->nx_off < 0 || !c->normal) return 0;
    size_t agree = 0, differ = 0;
    for (size_t i = 0; i < c->count; i++) {
        if (core[i] || idx[i] >= r->points || !(r->seen[idx[i] >> 3] >> (idx[i] & 7) & 1)) continue;
        float n[3];
        placed_normal(r, idx[i], n);
        float d = n[0] * c->normal[3 * i] + n[1] * c->normal[3 * i + 1] + n[2] * c->normal[3 * i + 2];
        agree += d > 0;
        differ += d < 0;
    }
    if (differ <= agree) return 0;
    for (size_t i = 0; i < c->count; i++) { /* zero normals stay as they are (orient.c) */
        float *n = c->normal + 3 * i;
        if (n[0] != 0 || n[1] != 0 || n[2] != 0) { n[0] = -n[0]; n[1] = -n[1]; n[2] = -n[2]; }
    }
    return 1;
}

/* Seams, at the end: the highest point's normal faces up (the propagation's rule for the whole
 * cloud, orient.c), else every normal of the result turns. */
static void orient_result(merge_run *r)
{
    if (!r->seams || !r->map || r->nx_off < 0 || !r->have_top) return;
    float n[3];
    placed_normal(r, r->top, n);
    if (!(n[2] < -1e-6f)) return; /* a horizontal one (orient.c: away from the centre) keeps the first tile's sign */
    for (uint64_t i = 0; i < r->points; i++) {
        unsigned char *p = r->map + r->head + (size_t)i * r->rec + (size_t)r->nx_off;
        float v[3];
        memcpy(v, p, sizeof v);
        if (v[0] == 0 && v[1] == 0 && v[2] == 0) continue;
        for (int a = 0; a < 3; a++) v[a] = -v[a];
        memcpy(p, v, sizeof v);
        if ((i & 0xFFFFF) == 0xFFFFF) (void)madvise(r->map, r->map_size, MADV_DONTNEED);
    }
}

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
    r->nx_off = normal_offset(r->sig);
    memcpy(r->map, m->data, before);
    memcpy(r->map + before, line, (size_t)ln);
    memcpy(r->map + before + ln, ve + 1, after);
    return PNPR_OK;
}

/* The tile's n records (src) at their source indices, a window of the result at a time: a tile
 * of a file in scan order has points all over it, and placing them in file order would make the
 * whole result resident. Each window's pages are handed back once it is written (a shared
 * mapping: they stay in the page cache for the kernel to write to the file). */
static pnpr_status place_records(merge_run *r, const uint32_t *idx, size_t n, const unsigned char *src)
{
    const size_t rec = r->rec, per = ((size_t)64 << 20) / rec + 1, nwin = (size_t)(r->points / per) + 1;
    size_t *start = calloc(nwin + 1, sizeof *start);
    uint32_t *order = malloc(n * sizeof *order);
    if (!start || !order) {
        free(start);
        free(order);
        return PNPR_ERR_OUT_OF_MEMORY;
    }
    for (size_t i = 0; i < n; i++) start[idx[i] / per + 1]++; /* counting sort by window */
    for (size_t w = 0; w < nwin; w++) start[w + 1] += start[w];
    for (size_t i = 0; i < n; i++) order[start[idx[i] / per]++] = (uint32_t)i;
    const size_t page = (size_t)sysconf(_SC_PAGESIZE);
    for (size_t w = 0, b = 0; w < nwin; b = start[w++]) {
        for (size_t j = b; j < start[w]; j++)
            memcpy(r->map + r->head + (size_t)idx[order[j]] * rec, src + (size_t)order[j] * rec, rec);
        size_t lo = (r->head + w * per * rec) / page * page, hi = r->head + (w + 1) * per * rec;
        if (start[w] > b) (void)madvise(r->map + lo, (hi < r->map_size ? hi : r->map_size) - lo, MADV_DONTNEED);
    }
    free(start);
    free(order);
    return PNPR_OK;
}

/* One tile: read, its halo compared (seams), its core checked, serialised without its source
 * index and core flags, records placed. */
static pnpr_status merge_tile(merge_run *r, const char *path, pnpr_error *err)
{
    pnpr_cloud c = {0};
    pnpr_mem_sink m = {0};
    uint32_t *idx = NULL;
    uint8_t *core = NULL;
    int has_core = 0;
    pnpr_status st = pnpr_read_file(path, NULL, &c, err);
    pnpr_property *si = st == PNPR_OK ? pnpr_cloud_find_property(&c, PNPR_PROP_SOURCE_INDEX) : NULL;
    pnpr_property *tc = st == PNPR_OK ? pnpr_cloud_find_property(&c, PNPR_PROP_TILE_CORE) : NULL;
    if (st == PNPR_OK && (!si || si->type != PNPR_TYPE_UINT32 || (tc && tc->type != PNPR_TYPE_UINT8)))
        st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: no uint property %s: not a tile's result", path, PNPR_PROP_SOURCE_INDEX);
    if (st == PNPR_OK && !r->hook && pnpr_cloud_find_property(&c, PNPR_PROP_TILE_COMPONENT))
        st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: a tile of `pointnpr segment`: its components join only in the "
                                                  "merge of segments (merge-tiles --segments)", path);
    if (st == PNPR_OK && (!(idx = malloc((c.count ? c.count : 1) * sizeof *idx)) || !(core = malloc(c.count + 1))))
        st = PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) {
        memcpy(idx, si->data, c.count * sizeof *idx);
        for (size_t i = 0; i < c.count; i++) core[i] = !tc || ((const uint8_t *)tc->data)[i] != 0;
        has_core = tc != NULL; /* the hook may add and remove properties: tc is not looked at after it */
        if (r->hook) st = r->hook(r->hook_user, r->tile, path, &c, idx, core, err);
        orient_tile(r, &c, idx, core);
        size_t n = 0;
        for (size_t i = 0; i < c.count; i++)
            if (core[i]) idx[n++] = idx[i];
        if (st == PNPR_OK && has_core && (st = pnpr_cloud_keep(&c, core, NULL)) == PNPR_OK)
            st = pnpr_cloud_remove_property(&c, PNPR_PROP_TILE_CORE);
    }
    for (size_t i = 0; i < c.count && st == PNPR_OK; i++) {
        if (idx[i] >= r->points || (r->seen[idx[i] >> 3] >> (idx[i] & 7) & 1)) {
            st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: core point %zu: source index %u %s", path, i, idx[i],
                                idx[i] >= r->points ? "beyond the file's points" : "comes twice (tiles overlap)");
            break;
        }
        r->seen[idx[i] >> 3] |= (uint8_t)(1u << (idx[i] & 7));
        double w[3];
        pnpr_cloud_world(&c, i, w);
        if (w[2] == w[2] && (!r->have_top || w[2] > r->top_z)) { r->top_z = w[2]; r->top = idx[i]; r->have_top = 1; }
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
    if (st == PNPR_OK && c.count) st = place_records(r, idx, c.count, m.data + head);
    if (st == PNPR_OK && r->map) (void)madvise(r->map, r->map_size, MADV_DONTNEED);
    free(idx);
    free(core);
    free(m.data);
    pnpr_cloud_free(&c);
    if (st == PNPR_ERR_OUT_OF_MEMORY && !err->message[0]) pnpr_error_set(err, st, "%s: merge: out of memory", path);
    return st;
}

pnpr_status pnpr_tile_merge(const char *const *paths, size_t count, uint64_t points, int seams, const char *out,
                            const pnpr_progress *progress, pnpr_error *err)
{
    return pnpr_tile_merge_with(paths, count, points, seams, out, progress, NULL, NULL, err);
}

pnpr_status pnpr_tile_merge_with(const char *const *paths, size_t count, uint64_t points, int seams, const char *out,
                                 const pnpr_progress *progress, pnpr_tile_merge_hook hook, void *user, pnpr_error *err)
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
    r.seams = seams;
    r.nx_off = -1;
    r.hook = hook;
    r.hook_user = user;
    if (!(r.seen = calloc((size_t)points / 8 + 1, 1))) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: merge: out of memory", out);
    pnpr_status st = pnpr_output_open(&r.o, out, err);
    for (size_t t = 0; st == PNPR_OK && t < count; t++) {
        r.tile = t;
        st = merge_tile(&r, paths[t], err);
        if (st == PNPR_OK && pnpr_progress_report(progress, "merge", (double)(t + 1) / (double)count))
            st = pnpr_error_set(err, PNPR_ERR_CANCELLED, "%s: merge cancelled", out);
    }
    for (uint64_t i = 0; st == PNPR_OK && i < points; i++)
        if (!(r.seen[i >> 3] >> (i & 7) & 1))
            st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: merge: point %llu of %llu is in no tile (a tile missing?)", out,
                                (unsigned long long)i, (unsigned long long)points);
    if (st == PNPR_OK && !r.map) st = pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: merge: no tiles", out);
    if (st == PNPR_OK) orient_result(&r);
    if (r.map && munmap(r.map, r.map_size) != 0 && st == PNPR_OK)
        st = pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", out, strerror(errno));
    free(r.seen);
    if (r.o.f) st = pnpr_output_close(&r.o, st, err);
    return st;
}
