/* Memory estimates and what the machine has (include/pointnpr/memory.h). The per-point figures
 * are peaks measured with GNU time on a 1M-point generated farm and the 342k-point lion
 * (docs/benchmarks.md, "Memory of `render` per style" and "Memory estimate"): bytes per point
 * beyond the cloud in memory, which the caller's process already holds when it asks. */
#include <pointnpr/memory.h>
#include <pointnpr/style.h>

#include "internal.h"

#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The feature stage: its kNN lists (4 bytes a neighbour), the tree's copy, the permutation and
 * its scratch while it runs; the outputs it keeps (degree, confidence, direction, class, spacing;
 * normals when the cloud had none). Measured 113 bytes/point in all at k = 16. */
#define FEATURE_RUN_PER_NEIGHBOUR 4
#define FEATURE_RUN_BASE 13
#define FEATURE_KEPT 25
#define NORMALS_KEPT 12
/* JSEG while it runs (measured 137 bytes/point in all) and the labels it keeps. */
#define SEGMENTS_RUN 133
#define SEGMENTS_KEPT 4
/* The renderer: the GL context and Mesa's llvmpipe (a one-point render: 92.5 MB above reading the
 * same file); per point by style, the upload (the vertices in the GL buffer, written to it a chunk
 * at a time, painterly's copy in its own order too; queue, style data; painterly's bins and RGB
 * colours per pass, its neighbour lists freed before the GL copies; the brush and hierarchy
 * stages' data), measured on the 1M-point farm with features; per pixel by style, the frame (colour,
 * depth-stencil, the surface info in RGBA32F, the outline and colour-area passes, the read-back and
 * the PNG rows), measured on the lion between 64x48 and 2048x1536. Images beyond RENDER_TILE px a
 * side are drawn in tiles of at most that: their other pixels cost the image and its rows alone. */
#define RENDER_CONTEXT ((size_t)96 << 20)
#define RENDER_PER_IMAGE_PIXEL 8
#define RENDER_TILE ((size_t)8192)
static const unsigned short render_cost[PNPR_STYLE_COUNT_][2] = {
    /* bytes per point, per pixel: points sketchy lines stipple cartoon painterly brush hierarchy */
    {72, 52}, {72, 50}, {72, 88}, {72, 64}, {90, 105}, {149, 56}, {117, 86}, {152, 72}};
/* What drawing costs beyond that: Mesa's llvmpipe bins every primitive of a frame before it
 * rasterises, so the peak grows with the points a frame draws, up to the scenes it keeps (the
 * growth slows down and stops). Per style: bytes per drawn point (the slope from 10k to 250k
 * drawn) and the most it reaches (MiB, at 1M drawn), measured with --budget on the 1M-point farm
 * at 1024x768 (docs/benchmarks.md "Memory of drawing"). */
static const unsigned short drawn_cost[PNPR_STYLE_COUNT_][2] = {
    {286, 138}, {287, 137}, {236, 138}, {287, 137}, {342, 205}, {364, 191}, {402, 236}, {216, 115}};

/* a * b + c, saturating at SIZE_MAX */
static size_t mul_add(size_t a, size_t b, size_t c)
{
    if (b && a > (SIZE_MAX - c) / b) return SIZE_MAX;
    return a * b + c;
}

static size_t add(size_t a, size_t b)
{
    return a > SIZE_MAX - b ? SIZE_MAX : a + b;
}

void pnpr_memory_estimate_plan(const pnpr_memory_plan *p, pnpr_memory_estimate *r)
{
    memset(r, 0, sizeof *r);
    if (!p) return;
    size_t n = p->points;
    if (p->features_k) {
        size_t per = (size_t)FEATURE_RUN_PER_NEIGHBOUR * p->features_k + FEATURE_RUN_BASE;
        r->stages = mul_add(n, per, 0);
        r->kept = mul_add(n, FEATURE_KEPT + (p->normals_stored ? NORMALS_KEPT : 0), 0);
    }
    if (p->segments) {
        size_t run = mul_add(n, SEGMENTS_RUN, 0);
        r->stages = run > r->stages ? run : r->stages;
        r->kept = add(r->kept, mul_add(n, SEGMENTS_KEPT, 0));
    }
    if (p->styles) {
        unsigned per_point = 0, per_pixel = 0;
        size_t drawn = p->drawn && p->drawn < n ? p->drawn : n, scene = 0;
        for (int s = 0; s < PNPR_STYLE_COUNT_; s++) {
            if (!((p->styles >> s) & 1u)) continue;
            if (render_cost[s][0] > per_point) per_point = render_cost[s][0];
            if (render_cost[s][1] > per_pixel) per_pixel = render_cost[s][1];
            size_t d = mul_add(drawn, drawn_cost[s][0], 0), cap = (size_t)drawn_cost[s][1] << 20;
            d = d < cap ? d : cap;
            if (d > scene) scene = d;
        }
        size_t w = p->width > 0 ? (size_t)p->width : 0, h = p->height > 0 ? (size_t)p->height : 0;
        size_t pixels = h && w > SIZE_MAX / h ? SIZE_MAX : w * h;
        size_t tw = w < RENDER_TILE ? w : RENDER_TILE, th = h < RENDER_TILE ? h : RENDER_TILE;
        size_t frame = add(mul_add(tw * th, per_pixel - RENDER_PER_IMAGE_PIXEL, 0), mul_add(pixels, RENDER_PER_IMAGE_PIXEL, 0));
        r->render = add(add(add(RENDER_CONTEXT, mul_add(n, per_point, 0)), frame), scene);
    }
    r->total = add(r->kept, r->stages > r->render ? r->stages : r->render);
}

size_t pnpr_memory_resident(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    if (!f) return 0;
    unsigned long long size = 0, rss = 0;
    int ok = fscanf(f, "%llu %llu", &size, &rss) == 2;
    fclose(f);
    long page = sysconf(_SC_PAGESIZE);
    return ok && page > 0 && rss < SIZE_MAX / (size_t)page ? (size_t)rss * (size_t)page : 0;
}

/* The first number of the line of `path` that starts with `key` (NULL key: the first line);
 * "max" reads as SIZE_MAX; -1 when there is none. */
static int read_number(const char *path, const char *key, unsigned long long *r)
{
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    char line[256];
    int found = -1;
    while (found < 0 && fgets(line, sizeof line, f)) {
        if (key && strncmp(line, key, strlen(key)) != 0) continue;
        const char *v = line + (key ? strlen(key) : 0);
        while (*v == ' ' || *v == '\t') v++;
        if (!strncmp(v, "max", 3)) { *r = SIZE_MAX; found = 0; break; }
        errno = 0;
        char *end;
        unsigned long long x = strtoull(v, &end, 10);
        if (end != v && !errno) { *r = x; found = 0; }
        else break;
    }
    fclose(f);
    return found;
}

size_t pnpr_memory_available(void)
{
    size_t avail = SIZE_MAX;
    unsigned long long kb, max, cur;
    if (read_number("/proc/meminfo", "MemAvailable:", &kb) == 0 && kb < SIZE_MAX / 1024) avail = (size_t)kb * 1024;
    if (read_number("/sys/fs/cgroup/memory.max", NULL, &max) == 0 && max != SIZE_MAX &&
        read_number("/sys/fs/cgroup/memory.current", NULL, &cur) == 0) {
        size_t left = cur < max ? (size_t)(max - cur) : 0;
        if (left < avail) avail = left;
    }
    return avail;
}

const char *pnpr_memory_text(size_t bytes, char *buf, size_t cap)
{
    static const char *const units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double v = (double)bytes;
    int u = 0;
    while (v >= 1024 && u < 6) { v /= 1024; u++; }
    if (cap) snprintf(buf, cap, u == 0 ? "%.0f %s" : v < 10 ? "%.1f %s" : "%.0f %s", v, units[u]);
    return buf;
}

int pnpr_memory_parse(const char *text, size_t *r_bytes)
{
    if (!text || !r_bytes) return -1;
    errno = 0;
    char *end;
    double v = strtod(text, &end);
    if (end == text || errno || !(v > 0)) return -1;
    double scale = 1;
    const char *s = end;
    switch (toupper((unsigned char)*s)) {
    case 'K': scale = 1024.0; s++; break;
    case 'M': scale = 1048576.0; s++; break;
    case 'G': scale = 1073741824.0; s++; break;
    case 'T': scale = 1099511627776.0; s++; break;
    default: break;
    }
    if (scale > 1 && *s == 'i') s++;
    if (*s == 'B' || *s == 'b') s++;
    double bytes = v * scale;
    if (*s || !(bytes >= 1) || bytes > 4611686018427387904.0) return -1; /* 2^62 */
    *r_bytes = (size_t)bytes;
    return 0;
}

pnpr_status pnpr_memory_check(size_t need, size_t limit, const char *what, pnpr_error *err)
{
    size_t resident = pnpr_memory_resident();
    size_t room = limit ? (limit > resident ? limit - resident : 0) : pnpr_memory_available();
    if (need <= room) return PNPR_OK;
    char a[32], b[32], c[32], d[32];
    pnpr_memory_text(need, a, sizeof a);
    pnpr_memory_text(room, b, sizeof b);
    if (limit)
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s needs about %s more, but the limit of %s leaves %s (the process holds %s)",
                              what ? what : "this", a, pnpr_memory_text(limit, c, sizeof c), b,
                              pnpr_memory_text(resident, d, sizeof d));
    return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY,
                          "%s needs about %s more, but only %s are available (MemAvailable, the cgroup's memory.max)",
                          what ? what : "this", a, b);
}
