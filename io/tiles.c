/* Clouds larger than memory in tiles (pointnpr/tiles.h): the plan, a tile's reading, the merge.
 * The certification of a tile's results is filters/tile_certify.c; docs/tiles.md has the why. */
#include <pointnpr/memory.h>
#include <pointnpr/outliers.h>
#include <pointnpr/props.h>
#include <pointnpr/tiles.h>

#include "../core/internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ------------------------------------------------------------------------------------------ */
/* The grid                                                                                    */

static uint32_t axis_cell(double v, double min, double cell, uint32_t cells)
{
    double c = (v - min) / cell;
    if (!(c >= 0)) return 0; /* below the grid, or NaN */
    if (c >= (double)cells) return cells - 1;
    return (uint32_t)c;
}

void pnpr_tile_cell(const pnpr_tile_grid *g, const double p[3], uint32_t r_cell[2])
{
    for (int a = 0; a < 2; a++) r_cell[a] = axis_cell(p[a], g->min[a], g->cell[a], g->cells[a]);
}

void pnpr_tile_box(const pnpr_tile_grid *g, const pnpr_tile *t, double halo, double r_box[4])
{
    for (int a = 0; a < 2; a++) { /* the grid's edge cells hold every point beyond them: so does the box */
        r_box[a] = t->lo[a] == 0 ? -INFINITY : g->min[a] + (double)t->lo[a] * g->cell[a] - halo;
        r_box[2 + a] = t->hi[a] >= g->cells[a] ? INFINITY : g->min[a] + (double)t->hi[a] * g->cell[a] + halo;
    }
}

pnpr_status pnpr_tile_check(const pnpr_tile_grid *g, const pnpr_tile *t, double halo, pnpr_error *err)
{
    if (!g || !t) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "tile: NULL grid or tile");
    for (int a = 0; a < 2; a++) {
        if (!isfinite(g->min[a]) || !(g->cell[a] > 0) || !isfinite(g->cell[a]) || g->cells[a] < 1 ||
            g->cells[a] > PNPR_TILE_GRID)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT,
                                  "tile: the grid needs a finite corner, cells of finite positive size and 1..%d "
                                  "cells per axis", PNPR_TILE_GRID);
        if (!isfinite(g->origin[a]) || !isfinite(g->origin[2]))
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "tile: the origin must be finite");
        if (t->lo[a] >= t->hi[a] || t->hi[a] > g->cells[a])
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "tile: cells %u..%u of axis %c are not inside 0..%u",
                                  t->lo[a], t->hi[a], "xy"[a], g->cells[a]);
    }
    if (!(halo >= 0) || !isfinite(halo))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "tile: the halo must be finite and >= 0");
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* The plan                                                                                    */

typedef struct plan_scan {
    pnpr_tile_grid g;
    double lo[2], hi[2]; /* the finite x/y bounds */
    double lo3[3], hi3[3]; /* the box of the points with three finite coordinates */
    uint64_t points;
    uint64_t *counts;    /* cells[0] x cells[1], row-major in y; NULL during the bounds pass */
    uint64_t *hist;      /* PLAN_BINS per axis over [lo, hi] (narrow_bounds), or NULL */
    /* the origin as a run in memory takes it (world_centre, core/cloud.c): the far-outlier
     * frame of the same stride sample (taken in the counts pass), then, when a point may be far,
     * the box of the others (a pass of its own) */
    double *sample;      /* PNPR_OUTLIER_SAMPLES points, or NULL */
    size_t sample_m;
    uint64_t sample_step;
    const pnpr_outlier_info *far; /* the inlier box pass: the frame, else NULL */
    double in_lo[3], in_hi[3];
} plan_scan;

#define PLAN_BINS 4096

static int scan_point(void *user, uint64_t index, const double p[3])
{
    plan_scan *s = user;
    s->points = index + 1;
    if (s->hist) {
        for (int a = 0; a < 2; a++) {
            double b = (p[a] - s->lo[a]) / (s->hi[a] - s->lo[a]) * PLAN_BINS;
            if (b >= 0 && b <= PLAN_BINS) s->hist[a * PLAN_BINS + (b < PLAN_BINS ? (size_t)b : PLAN_BINS - 1)]++;
        }
        return 0;
    }
    if (s->far) {
        if (isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) && !pnpr_outlier_is_far(s->far, p))
            for (int a = 0; a < 3; a++) {
                if (p[a] < s->in_lo[a]) s->in_lo[a] = p[a];
                if (p[a] > s->in_hi[a]) s->in_hi[a] = p[a];
            }
        return 0;
    }
    if (s->counts) {
        uint32_t c[2];
        pnpr_tile_cell(&s->g, p, c);
        s->counts[(size_t)c[1] * s->g.cells[0] + c[0]]++;
        if (s->sample && index % s->sample_step == 0 && s->sample_m < PNPR_OUTLIER_SAMPLES && isfinite(p[0]) &&
            isfinite(p[1]) && isfinite(p[2]))
            memcpy(s->sample + 3 * s->sample_m++, p, 3 * sizeof *p);
        return 0;
    }
    if (isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]))
        for (int a = 0; a < 3; a++) {
            if (p[a] < s->lo3[a]) s->lo3[a] = p[a];
            if (p[a] > s->hi3[a]) s->hi3[a] = p[a];
        }
    for (int a = 0; a < 2; a++)
        if (isfinite(p[a])) {
            if (p[a] < s->lo[a]) s->lo[a] = p[a];
            if (p[a] > s->hi[a]) s->hi[a] = p[a];
        }
    return 0;
}

/* The bins of one axis' histogram that hold the cloud without its far outliers: from the
 * 0.1% to the 99.9% quantile, grown over every occupied bin closer to it than its own width
 * (a cloud in one piece keeps all of its bins; a point 1e7 away is left out). */
static void axis_core(const uint64_t *h, uint64_t total, size_t *r_lo, size_t *r_hi)
{
    uint64_t cut = total / 1000, sum = 0;
    size_t b0 = 0, b1 = PLAN_BINS - 1;
    while (b0 < PLAN_BINS - 1 && (sum += h[b0]) <= cut) b0++;
    for (sum = 0; b1 > b0 && (sum += h[b1]) <= cut; b1--) {}
    size_t gap = b1 - b0 + 1;
    for (size_t b = b0; b-- > 0 && b0 - b <= gap;)
        if (h[b]) b0 = b;
    for (size_t b = b1 + 1; b < PLAN_BINS && b - b1 <= gap; b++)
        if (h[b]) b1 = b;
    *r_lo = b0;
    *r_hi = b1;
}

/* Far outliers would stretch the grid until the cloud fills one cell (which is never split): the
 * x/y bounds shrink to the part that holds the cloud (axis_core), a histogram pass at a time while
 * that takes off more than 15/16 of a side (at most 3 passes; usually one, which changes nothing).
 * The points left outside go to the edge cells, whose tiles read everything beyond the edge
 * (pnpr_tile_box). */
static pnpr_status narrow_bounds(plan_scan *s, const char *path, pnpr_read_options *ro, pnpr_error *err)
{
    uint64_t *hist = malloc(2 * PLAN_BINS * sizeof *hist);
    if (!hist) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: tile plan: out of memory", path);
    pnpr_status st = PNPR_OK;
    for (int pass = 0, narrowed = 1; pass < 3 && narrowed && st == PNPR_OK; pass++) {
        if (!(s->lo[0] < s->hi[0]) || !(s->lo[1] < s->hi[1]) || !isfinite(s->hi[0] - s->lo[0]) ||
            !isfinite(s->hi[1] - s->lo[1]))
            break;
        memset(hist, 0, 2 * PLAN_BINS * sizeof *hist);
        s->hist = hist;
        pnpr_cloud none = {0};
        st = pnpr_read_file(path, ro, &none, err);
        pnpr_cloud_free(&none);
        s->hist = NULL;
        narrowed = 0;
        for (int a = 0; a < 2 && st == PNPR_OK; a++) {
            uint64_t total = 0;
            for (size_t b = 0; b < PLAN_BINS; b++) total += hist[a * PLAN_BINS + b];
            size_t b0, b1;
            axis_core(hist + a * PLAN_BINS, total, &b0, &b1);
            if (!total || 16 * (b1 - b0 + 1) > PLAN_BINS) continue;
            double w = (s->hi[a] - s->lo[a]) / PLAN_BINS, lo = s->lo[a];
            s->lo[a] = lo + (double)b0 * w;
            s->hi[a] = fmin(lo + (double)(b1 + 1) * w, s->hi[a]);
            narrowed = 1;
        }
    }
    free(hist);
    return st;
}

/* Square cells over the finite bounds: PNPR_TILE_GRID along the longer side. */
static void plan_grid(plan_scan *s)
{
    double side = 0;
    for (int a = 0; a < 2; a++) {
        if (!(s->lo[a] <= s->hi[a])) s->lo[a] = s->hi[a] = 0; /* no finite coordinate */
        double d = s->hi[a] - s->lo[a];
        if (d > side) side = d;
    }
    for (int a = 0; a < 3; a++) /* as pnpr_cloud_set_world when no point is far (plan_origin) */
        s->g.origin[a] = s->lo3[a] <= s->hi3[a] ? 0.5 * s->lo3[a] + 0.5 * s->hi3[a] : 0.0;
    double cell = side / PNPR_TILE_GRID;
    if (!(cell > 0)) cell = 1;
    if (!isfinite(cell)) cell = DBL_MAX / PNPR_TILE_GRID;
    for (int a = 0; a < 2; a++) {
        double n = ceil((s->hi[a] - s->lo[a]) / cell);
        s->g.min[a] = s->lo[a];
        s->g.cell[a] = cell;
        s->g.cells[a] = n >= PNPR_TILE_GRID ? PNPR_TILE_GRID : n >= 1 ? (uint32_t)n : 1;
    }
}

/* Points in cells [x0, x1) x [y0, y1) from the summed-area table (cells[0] + 1 columns). */
static uint64_t rect_count(const uint64_t *sum, uint32_t w, const uint32_t lo[2], const uint32_t hi[2])
{
    size_t s = (size_t)w + 1;
    return sum[hi[1] * s + hi[0]] - sum[lo[1] * s + hi[0]] - sum[hi[1] * s + lo[0]] + sum[lo[1] * s + lo[0]];
}

/* The mean spacing of a 2.5D scan: the occupied area shared by its points, counted in blocks of
 * b x b cells, b doubled until an occupied block holds 16 points on average (cells finer than the
 * spacing are mostly empty and would shrink the area). */
static double plan_spacing(const uint64_t *sum, uint32_t w, uint32_t h, double cell, uint64_t points)
{
    if (!points) return 0;
    for (uint32_t b = 1;; b *= 2) {
        uint64_t occupied = 0;
        for (uint32_t y = 0; y < h; y += b)
            for (uint32_t x = 0; x < w; x += b) {
                uint32_t lo[2] = {x, y}, hi[2] = {x + b < w ? x + b : w, y + b < h ? y + b : h};
                occupied += rect_count(sum, w, lo, hi) > 0;
            }
        if ((double)points >= 16.0 * (double)occupied || b >= PNPR_TILE_GRID)
            return sqrt((double)occupied * b * b * cell * cell / (double)points);
    }
}

typedef struct plan_split {
    const uint64_t *sum;
    uint32_t w;
    uint64_t max_points;
    pnpr_tile *tiles;
    size_t count;
} plan_split;

/* Halves the tile along its longer side (in cells) where the count reaches half, until a tile
 * holds at most max_points or is a single cell. At most cells[0] x cells[1] tiles. */
static void split_tile(plan_split *p, pnpr_tile t)
{
    t.points = rect_count(p->sum, p->w, t.lo, t.hi);
    int a = t.hi[0] - t.lo[0] >= t.hi[1] - t.lo[1] ? 0 : 1;
    if (t.hi[a] - t.lo[a] < 2) a = 1 - a;
    if (t.points <= p->max_points || t.hi[a] - t.lo[a] < 2) {
        p->tiles[p->count++] = t;
        return;
    }
    pnpr_tile first = t, second = t;
    uint32_t cut = t.lo[a] + 1;
    for (; cut + 1 < t.hi[a]; cut++) {
        first.hi[a] = cut;
        if (2 * rect_count(p->sum, p->w, first.lo, first.hi) >= t.points) break;
    }
    first.hi[a] = cut;
    second.lo[a] = cut;
    split_tile(p, first);
    split_tile(p, second);
}

static pnpr_status plan_tiles(const plan_scan *s, uint64_t max_points, pnpr_tile_plan *r)
{
    const uint32_t w = s->g.cells[0], h = s->g.cells[1];
    uint64_t *sum = calloc(((size_t)w + 1) * ((size_t)h + 1), sizeof *sum);
    r->tiles = malloc((size_t)w * h * sizeof *r->tiles);
    if (!sum || !r->tiles) {
        free(sum);
        return PNPR_ERR_OUT_OF_MEMORY;
    }
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++)
            sum[(size_t)(y + 1) * (w + 1) + x + 1] = s->counts[(size_t)y * w + x] + sum[(size_t)y * (w + 1) + x + 1] +
                                                     sum[(size_t)(y + 1) * (w + 1) + x] - sum[(size_t)y * (w + 1) + x];
    r->spacing = plan_spacing(sum, w, h, s->g.cell[0], s->points);
    plan_split p = {sum, w, max_points, r->tiles, 0};
    pnpr_tile all = {{0, 0}, {w, h}, 0};
    split_tile(&p, all);
    r->count = p.count;
    free(sum);
    return PNPR_OK;
}

/* The core points a job of `per` bytes a point holds within limit, with a halo of
 * PNPR_TILE_HALO_SHARE as many again; 0 when not even 1000 fit. */
static uint64_t points_within(size_t limit, double per)
{
    double n = (double)limit / (per * (1.0 + PNPR_TILE_HALO_SHARE));
    return n >= 1000 ? (uint64_t)n : 0;
}

uint64_t pnpr_tile_points_for_memory(size_t limit, size_t record_bytes, uint32_t k)
{
    if (!k) k = 16;
    const size_t probe = 1000000; /* the estimate is linear in the points: take it per point */
    pnpr_memory_plan mp = {probe, k, 1, 0, 0, 0, 0, 0};
    pnpr_memory_estimate e;
    pnpr_memory_estimate_plan(&mp, &e);
    return points_within(limit, (double)record_bytes + 5.0 + (double)e.total / (double)probe + 4.0 * (k + 1) + 9.0);
}

/* The origin a run in memory takes (pnpr_cloud_set_world): the centre of the box of the points
 * that are not far outliers by the frame of the stride sample. When no corner of the box of all
 * points is far, no point is, and the box is that one; else a pass finds the others' box. */
static pnpr_status plan_origin(plan_scan *s, const char *path, pnpr_read_options *ro, pnpr_error *err)
{
    if (!s->sample_m) return PNPR_OK;
    pnpr_outlier_info info;
    pnpr_status st = pnpr_outlier_frame_of_sample(s->sample, s->sample_m, &info);
    if (st != PNPR_OK) return pnpr_error_set(err, st, "%s: tile plan: %s", path, pnpr_status_string(st));
    int any_far = 0;
    for (int k = 0; k < 8; k++) {
        double c[3] = {(k & 1) ? s->hi3[0] : s->lo3[0], (k & 2) ? s->hi3[1] : s->lo3[1], (k & 4) ? s->hi3[2] : s->lo3[2]};
        any_far |= pnpr_outlier_is_far(&info, c);
    }
    if (!any_far) return PNPR_OK;
    for (int a = 0; a < 3; a++) { s->in_lo[a] = INFINITY; s->in_hi[a] = -INFINITY; }
    s->far = &info;
    pnpr_cloud none = {0};
    st = pnpr_read_file(path, ro, &none, err);
    pnpr_cloud_free(&none);
    s->far = NULL;
    for (int a = 0; a < 3 && st == PNPR_OK; a++)
        s->g.origin[a] = s->in_lo[a] <= s->in_hi[a] ? 0.5 * s->in_lo[a] + 0.5 * s->in_hi[a] : 0.0;
    return st;
}

pnpr_status pnpr_tile_plan_make(const char *path, const pnpr_tile_plan_options *opts, pnpr_tile_plan *r_plan,
                                pnpr_error *err)
{
    if (!path || !r_plan) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "tile plan: NULL argument");
    memset(r_plan, 0, sizeof *r_plan);
    pnpr_tile_plan_options o = {0};
    if (opts) o = *opts;
    if (!(o.halo >= 0) || !isfinite(o.halo))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: tile plan: the halo must be finite and >= 0", path);
    plan_scan s;
    memset(&s, 0, sizeof s);
    s.lo[0] = s.lo[1] = s.lo3[0] = s.lo3[1] = s.lo3[2] = INFINITY;
    s.hi[0] = s.hi[1] = s.hi3[0] = s.hi3[1] = s.hi3[2] = -INFINITY;
    pnpr_read_options ro = {0};
    ro.format = PNPR_FORMAT_PLY;
    ro.keep = scan_point;
    ro.keep_user = &s;
    pnpr_cloud none = {0};
    pnpr_status st = pnpr_read_file(path, &ro, &none, err); /* bounds */
    pnpr_cloud_free(&none); /* keeps no point: an empty cloud */
    if (st == PNPR_OK && s.points >= UINT32_MAX)
        st = pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: %llu points: tiles take fewer than 2^32", path,
                            (unsigned long long)s.points);
    if (st == PNPR_OK) st = narrow_bounds(&s, path, &ro, err);
    if (st != PNPR_OK) return st;
    plan_grid(&s);
    uint64_t points = s.points;
    struct stat sb;
    size_t rec = stat(path, &sb) == 0 && points ? (size_t)((uint64_t)sb.st_size / points) : 64;
    if (!o.tile_points && o.memory_limit) {
        o.tile_points = o.job_bytes ? points_within(o.memory_limit, (double)(rec + o.job_bytes))
                                    : pnpr_tile_points_for_memory(o.memory_limit, rec, o.features_k);
        if (!o.tile_points) {
            char a[32];
            return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: a memory limit of %s leaves no room for a tile", path,
                                  pnpr_memory_text(o.memory_limit, a, sizeof a));
        }
    }
    s.counts = calloc((size_t)s.g.cells[0] * s.g.cells[1], sizeof *s.counts);
    s.sample = malloc(3 * PNPR_OUTLIER_SAMPLES * sizeof *s.sample);
    s.sample_step = points / PNPR_OUTLIER_SAMPLES + 1;
    if (!s.counts || !s.sample) {
        free(s.counts);
        free(s.sample);
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: tile plan: out of memory", path);
    }
    ro.progress = o.progress;
    st = pnpr_read_file(path, &ro, &none, err); /* counts, and the stride sample */
    pnpr_cloud_free(&none);
    ro.progress.fn = NULL;
    if (st == PNPR_OK && s.points == points) st = plan_origin(&s, path, &ro, err);
    free(s.sample);
    if (st == PNPR_OK && s.points != points)
        st = pnpr_error_set(err, PNPR_ERR_IO, "%s: the file changed while it was planned (%llu, then %llu points)", path,
                            (unsigned long long)points, (unsigned long long)s.points);
    if (st == PNPR_OK) {
        r_plan->points = points;
        r_plan->grid = s.g;
        r_plan->record_bytes = rec;
        r_plan->tile_points = o.tile_points ? o.tile_points : PNPR_TILE_POINTS_DEFAULT;
        if (plan_tiles(&s, r_plan->tile_points, r_plan) != PNPR_OK)
            st = pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: tile plan: out of memory", path);
        r_plan->halo = o.halo > 0 ? o.halo : PNPR_TILE_HALO_SPACINGS * r_plan->spacing;
    }
    free(s.counts);
    if (st != PNPR_OK) pnpr_tile_plan_free(r_plan);
    return st;
}

void pnpr_tile_plan_free(pnpr_tile_plan *plan)
{
    if (!plan) return;
    free(plan->tiles);
    memset(plan, 0, sizeof *plan);
}

/* ------------------------------------------------------------------------------------------ */
/* Reading a tile                                                                              */

typedef struct tile_keep {
    const pnpr_tile_grid *g;
    const pnpr_tile *t;
    double box[4];
    uint32_t *index;
    uint8_t *core;
    size_t n, cap;
    int failed; /* out of memory, or an index beyond uint32 */
} tile_keep;

static int keep_tile(void *user, uint64_t i, const double p[3])
{
    tile_keep *k = user;
    uint32_t c[2];
    pnpr_tile_cell(k->g, p, c);
    int core = c[0] >= k->t->lo[0] && c[0] < k->t->hi[0] && c[1] >= k->t->lo[1] && c[1] < k->t->hi[1];
    if (!core && !(p[0] >= k->box[0] && p[0] <= k->box[2] && p[1] >= k->box[1] && p[1] <= k->box[3])) return 0;
    if (k->failed || i >= UINT32_MAX) { k->failed = 1; return 0; }
    if (k->n == k->cap) {
        size_t cap = k->cap ? 2 * k->cap : 4096;
        uint32_t *index = realloc(k->index, cap * sizeof *index);
        if (index) k->index = index;
        uint8_t *cr = index ? realloc(k->core, cap) : NULL;
        if (!cr) { k->failed = 1; return 0; }
        k->core = cr;
        k->cap = cap;
    }
    k->index[k->n] = (uint32_t)i;
    k->core[k->n++] = (uint8_t)core;
    return 1;
}

pnpr_status pnpr_tile_read(const char *path, const pnpr_tile_grid *grid, const pnpr_tile *tile, double halo,
                           const pnpr_read_options *opts, pnpr_cloud *r_cloud, uint8_t **r_core, pnpr_error *err)
{
    if (!path || !r_cloud || !r_core) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "tile: NULL argument");
    *r_core = NULL;
    pnpr_cloud_free(r_cloud);
    pnpr_status st = pnpr_tile_check(grid, tile, halo, err);
    if (st != PNPR_OK) return st;
    tile_keep k;
    memset(&k, 0, sizeof k);
    k.g = grid;
    k.t = tile;
    pnpr_tile_box(grid, tile, halo, k.box);
    pnpr_read_options ro = {0};
    if (opts) ro = *opts;
    ro.keep = keep_tile;
    ro.keep_user = &k;
    ro.origin = grid->origin;
    st = pnpr_read_file(path, &ro, r_cloud, err);
    if (st == PNPR_OK && (k.failed || k.n != r_cloud->count))
        st = pnpr_error_set(err, k.failed ? PNPR_ERR_OUT_OF_MEMORY : PNPR_ERR_IO,
                            "%s: tile: %s", path, k.failed ? "out of memory (or 2^32 points or more)" : "the file changed");
    pnpr_property *si = NULL;
    if (st == PNPR_OK && (st = pnpr_cloud_add_property(r_cloud, PNPR_PROP_SOURCE_INDEX, PNPR_TYPE_UINT32, &si)) != PNPR_OK)
        pnpr_error_set(err, st, "%s: tile: out of memory", path);
    if (st == PNPR_OK && k.n) memcpy(si->data, k.index, k.n * sizeof *k.index);
    free(k.index);
    if (st != PNPR_OK) {
        free(k.core);
        pnpr_cloud_free(r_cloud);
        return st;
    }
    *r_core = k.core ? k.core : calloc(1, 1);
    if (!*r_core) {
        pnpr_cloud_free(r_cloud);
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: tile: out of memory", path);
    }
    return PNPR_OK;
}
