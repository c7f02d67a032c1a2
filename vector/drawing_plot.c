/* Drawings for pen plotters (include/pointnpr/drawing.h): collinear hatches merged into one path,
 * and paths ordered to shorten the pen-up travel. Written here: both are a few dozen lines of
 * sorting and a uniform grid, and no Debian library does either on plain paths. */
#include <pointnpr/drawing.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- merging collinear two-vertex paths ------------------------------------------------------ */

typedef struct seg {
    size_t idx;     /* path index */
    uint64_t key;   /* colour and width: only equal keys merge */
    double angle;   /* direction in [0, pi) */
    double c, s0, s1; /* offset across the group's direction, extent along it */
} seg;

static int cmp_key_angle(const void *a, const void *b)
{
    const seg *x = a, *y = b;
    if (x->key != y->key) return x->key < y->key ? -1 : 1;
    return (x->angle > y->angle) - (x->angle < y->angle);
}
static int cmp_c(const void *a, const void *b)
{
    const seg *x = a, *y = b;
    return (x->c > y->c) - (x->c < y->c);
}
static int cmp_s0(const void *a, const void *b)
{
    const seg *x = a, *y = b;
    if (x->s0 != y->s0) return (x->s0 > y->s0) - (x->s0 < y->s0);
    return (x->idx > y->idx) - (x->idx < y->idx);
}

static int mergeable(const pnpr_drawing *d, size_t i, pnpr_drawing_layer layer)
{
    return d->layer[i] == layer && d->offset[i + 1] - d->offset[i] == 2 && !(d->flags[i] & (PNPR_PATH_CLOSED | PNPR_PATH_DOT));
}

static uint64_t seg_key(const pnpr_drawing *d, size_t i)
{
    uint32_t w;
    memcpy(&w, &d->stroke_width[i], sizeof w);
    uint32_t c;
    memcpy(&c, d->rgba + 4 * i, 4);
    return (uint64_t)w << 32 | c;
}

/* Merges the runs of one cluster (same line) sorted by s0; writes survivors' new ends. */
static void merge_cluster(pnpr_drawing *d, seg *s, size_t n, const double u[2], float gap, uint8_t *gone)
{
    qsort(s, n, sizeof *s, cmp_s0);
    size_t i = 0;
    while (i < n) {
        size_t j = i + 1, first = s[i].idx;
        double hi = s[i].s1, csum = s[i].c;
        while (j < n && s[j].s0 <= hi + gap) {
            if (s[j].s1 > hi) hi = s[j].s1;
            if (s[j].idx < first) first = s[j].idx;
            csum += s[j].c;
            j++;
        }
        if (j - i > 1) {
            double c = csum / (double)(j - i), nx = -u[1], ny = u[0];
            float *p = d->xy + 2 * d->offset[first];
            p[0] = (float)(u[0] * s[i].s0 + nx * c);
            p[1] = (float)(u[1] * s[i].s0 + ny * c);
            p[2] = (float)(u[0] * hi + nx * c);
            p[3] = (float)(u[1] * hi + ny * c);
            for (size_t k = i; k < j; k++)
                if (s[k].idx != first) gone[s[k].idx] = 1;
        }
        i = j;
    }
}

/* One group of similar direction: offsets across the mean direction, clusters, merges. */
static void merge_group(pnpr_drawing *d, seg *s, size_t n, float offset, float gap, uint8_t *gone)
{
    double a = 0;
    for (size_t i = 0; i < n; i++) a += s[i].angle;
    a /= (double)n;
    double u[2] = {cos(a), sin(a)};
    for (size_t i = 0; i < n; i++) {
        const float *p = d->xy + 2 * d->offset[s[i].idx];
        double c0 = -u[1] * p[0] + u[0] * p[1], c1 = -u[1] * p[2] + u[0] * p[3];
        double t0 = u[0] * p[0] + u[1] * p[1], t1 = u[0] * p[2] + u[1] * p[3];
        s[i].c = 0.5 * (c0 + c1);
        s[i].s0 = t0 < t1 ? t0 : t1;
        s[i].s1 = t0 < t1 ? t1 : t0;
    }
    qsort(s, n, sizeof *s, cmp_c);
    size_t i = 0;
    while (i < n) {
        size_t j = i + 1;
        while (j < n && s[j].c - s[i].c <= offset) j++;
        merge_cluster(d, s + i, j - i, u, gap, gone);
        i = j;
    }
}

/* Removes the paths marked gone, keeping the order; returns how many went. */
static size_t compact(pnpr_drawing *d, const uint8_t *gone)
{
    size_t before = d->count;
    size_t out = 0, v_out = 0;
    for (size_t i = 0; i < d->count; i++) {
        size_t a = d->offset[i], b = d->offset[i + 1];
        if (gone[i]) continue;
        memmove(d->xy + 2 * v_out, d->xy + 2 * a, 2 * (b - a) * sizeof *d->xy);
        d->stroke_width[out] = d->stroke_width[i];
        memmove(d->rgba + 4 * out, d->rgba + 4 * i, 4);
        d->layer[out] = d->layer[i];
        d->flags[out] = d->flags[i];
        d->offset[out] = v_out;
        v_out += b - a;
        out++;
    }
    d->count = out;
    if (d->offset) d->offset[out] = v_out;
    return before - out;
}

pnpr_status pnpr_drawing_merge_collinear(pnpr_drawing *d, pnpr_drawing_layer layer, float angle_deg, float offset_px,
                                         float gap_px, size_t *r_merged)
{
    if (r_merged) *r_merged = 0;
    if (!d || (unsigned)layer >= PNPR_LAYER_COUNT_ || !(angle_deg >= 0) || !(offset_px >= 0) || !(gap_px >= 0) ||
        !isfinite(angle_deg + offset_px + gap_px))
        return PNPR_ERR_INVALID_ARGUMENT;
    size_t n = 0;
    for (size_t i = 0; i < d->count; i++) n += mergeable(d, i, layer);
    if (n < 2) return PNPR_OK;
    seg *s = malloc(n * sizeof *s);
    uint8_t *gone = calloc(d->count, 1);
    if (!s || !gone) { free(s); free(gone); return PNPR_ERR_OUT_OF_MEMORY; }
    const double pi = 3.14159265358979323846, tol = angle_deg * pi / 180;
    n = 0;
    for (size_t i = 0; i < d->count; i++) {
        if (!mergeable(d, i, layer)) continue;
        const float *p = d->xy + 2 * d->offset[i];
        double a = atan2((double)p[3] - p[1], (double)p[2] - p[0]);
        if (a < 0) a += pi;
        if (a >= pi) a -= pi;
        s[n++] = (seg){i, seg_key(d, i), a, 0, 0, 0};
    }
    qsort(s, n, sizeof *s, cmp_key_angle);
    size_t i = 0;
    while (i < n) {
        size_t j = i + 1;
        while (j < n && s[j].key == s[i].key && s[j].angle - s[i].angle <= tol) j++;
        merge_group(d, s + i, j - i, offset_px, gap_px, gone);
        i = j;
    }
    size_t merged = compact(d, gone);
    if (r_merged) *r_merged = merged;
    free(s);
    free(gone);
    return PNPR_OK;
}

/* ---- duplicates ---------------------------------------------------------------------------- */

typedef struct dup_key {
    size_t idx;
    int64_t q[4];      /* the ends on a grid of `tol`, in a canonical order */
    uint64_t style;    /* width, colour */
    uint8_t layer, flags, n;
} dup_key;

static int cmp_dup(const void *a, const void *b)
{
    const dup_key *x = a, *y = b;
    if (x->layer != y->layer) return x->layer < y->layer ? -1 : 1;
    if (x->flags != y->flags) return x->flags < y->flags ? -1 : 1;
    if (x->n != y->n) return x->n < y->n ? -1 : 1;
    if (x->style != y->style) return x->style < y->style ? -1 : 1;
    for (int k = 0; k < 4; k++)
        if (x->q[k] != y->q[k]) return x->q[k] < y->q[k] ? -1 : 1;
    return (x->idx > y->idx) - (x->idx < y->idx);
}

/* The opacity of `times` marks of opacity *a drawn over each other, as the frame blends them. */
static void composite_alpha(uint8_t *a, size_t times)
{
    double clear = pow(1 - *a / 255.0, (double)times);
    *a = (uint8_t)((1 - clear) * 255 + 0.5);
}

static int dedupable(const pnpr_drawing *d, size_t i)
{
    return d->offset[i + 1] - d->offset[i] <= 2 && !(d->flags[i] & (PNPR_PATH_FILL | PNPR_PATH_SUBPATH | PNPR_PATH_CLOSED));
}

pnpr_status pnpr_drawing_dedupe(pnpr_drawing *d, float tol, size_t *r_removed)
{
    if (r_removed) *r_removed = 0;
    if (!d || !(tol > 0) || !isfinite(tol)) return PNPR_ERR_INVALID_ARGUMENT;
    size_t n = 0;
    for (size_t i = 0; i < d->count; i++) n += dedupable(d, i);
    if (n < 2) return PNPR_OK;
    dup_key *k = malloc(n * sizeof *k);
    uint8_t *gone = calloc(d->count, 1);
    if (!k || !gone) { free(k); free(gone); return PNPR_ERR_OUT_OF_MEMORY; }
    n = 0;
    for (size_t i = 0; i < d->count; i++) {
        if (!dedupable(d, i)) continue;
        const float *p = d->xy + 2 * d->offset[i];
        size_t nv = d->offset[i + 1] - d->offset[i];
        int64_t q[4];
        for (size_t v = 0; v < 2; v++)
            for (int c = 0; c < 2; c++) q[2 * v + c] = (int64_t)llround(p[2 * (v < nv ? v : 0) + c] / tol);
        int swap = q[2] < q[0] || (q[2] == q[0] && q[3] < q[1]); /* a stroke drawn either way */
        dup_key key = {i, {swap ? q[2] : q[0], swap ? q[3] : q[1], swap ? q[0] : q[2], swap ? q[1] : q[3]},
                       seg_key(d, i), d->layer[i], d->flags[i], (uint8_t)nv};
        k[n++] = key;
    }
    qsort(k, n, sizeof *k, cmp_dup);
    size_t first = 0; /* the sort puts the first of equals first */
    for (size_t j = 1; j <= n; j++) {
        dup_key a = k[first], b = k[j < n ? j : first];
        a.idx = b.idx = 0;
        if (j < n && !cmp_dup(&a, &b)) { gone[k[j].idx] = 1; continue; }
        composite_alpha(d->rgba + 4 * k[first].idx + 3, j - first);
        first = j;
    }
    size_t removed = compact(d, gone);
    if (r_removed) *r_removed = removed;
    free(k);
    free(gone);
    return PNPR_OK;
}

/* ---- short marks ------------------------------------------------------------------------------ */

static double path_length(const pnpr_drawing *d, size_t i)
{
    double len = 0;
    for (size_t v = d->offset[i] + 1; v < d->offset[i + 1]; v++)
        len += hypot((double)d->xy[2 * v] - d->xy[2 * v - 2], (double)d->xy[2 * v + 1] - d->xy[2 * v - 1]);
    return len;
}

pnpr_status pnpr_drawing_drop_short(pnpr_drawing *d, float min_px, size_t *r_removed)
{
    if (r_removed) *r_removed = 0;
    if (!d || !(min_px >= 0) || !isfinite(min_px)) return PNPR_ERR_INVALID_ARGUMENT;
    uint8_t *gone = calloc(d->count ? d->count : 1, 1);
    if (!gone) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; i < d->count; i++)
        gone[i] = !(d->flags[i] & (PNPR_PATH_DOT | PNPR_PATH_FILL | PNPR_PATH_SUBPATH | PNPR_PATH_CLOSED)) &&
                  path_length(d, i) < min_px;
    size_t removed = compact(d, gone);
    if (r_removed) *r_removed = removed;
    free(gone);
    return PNPR_OK;
}

/* ---- ordering for plotters -------------------------------------------------------------------- */

/* The ends of the paths of one layer in a uniform grid (cells of about two ends). */
typedef struct end_grid {
    const pnpr_drawing *d;
    const size_t *path;   /* the layer's paths */
    size_t n;
    double x0, y0, cell;
    int nx, ny;
    size_t *start;        /* nx * ny + 1 */
    uint32_t *entry;      /* 2 * local path + end (0: first vertex, 1: last) */
    size_t *live;         /* per cell: entries of unused paths */
    uint8_t *used;
} end_grid;

static size_t path_end(const pnpr_drawing *d, size_t p, int end)
{
    return end ? d->offset[p + 1] - 1 : d->offset[p];
}
static int two_ends(const pnpr_drawing *d, size_t p)
{
    return d->offset[p + 1] - d->offset[p] > 1 && !(d->flags[p] & (PNPR_PATH_CLOSED | PNPR_PATH_DOT));
}

static int cell_of(const end_grid *g, double x, double y, int *cx, int *cy)
{
    int ix = (int)floor((x - g->x0) / g->cell), iy = (int)floor((y - g->y0) / g->cell);
    *cx = ix < 0 ? 0 : ix >= g->nx ? g->nx - 1 : ix;
    *cy = iy < 0 ? 0 : iy >= g->ny ? g->ny - 1 : iy;
    return *cy * g->nx + *cx;
}

static int grid_build(end_grid *g)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (size_t k = 0; k < g->n; k++)
        for (int e = 0; e < 2; e++) {
            const float *p = g->d->xy + 2 * path_end(g->d, g->path[k], e);
            x0 = fmin(x0, p[0]); y0 = fmin(y0, p[1]); x1 = fmax(x1, p[0]); y1 = fmax(y1, p[1]);
        }
    double area = (x1 - x0 + 1) * (y1 - y0 + 1);
    g->cell = sqrt(area / (double)g->n) + 1e-9;
    g->x0 = x0;
    g->y0 = y0;
    double nx = floor((x1 - x0) / g->cell) + 1, ny = floor((y1 - y0) / g->cell) + 1;
    if (nx * ny > 4.0 * (double)g->n + 16) return 0; /* cannot happen with the cell above */
    g->nx = (int)nx;
    g->ny = (int)ny;
    size_t cells = (size_t)g->nx * (size_t)g->ny;
    g->start = calloc(cells + 1, sizeof *g->start);
    g->live = calloc(cells, sizeof *g->live);
    g->entry = malloc(2 * g->n * sizeof *g->entry);
    g->used = calloc(g->n, 1);
    if (!g->start || !g->live || !g->entry || !g->used) return 0;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t k = 0; k < g->n; k++)
            for (int e = 0; e < 1 + two_ends(g->d, g->path[k]); e++) {
                const float *p = g->d->xy + 2 * path_end(g->d, g->path[k], e);
                int cx, cy, c = cell_of(g, p[0], p[1], &cx, &cy);
                if (pass == 0) g->start[c + 1]++;
                else g->entry[g->start[c] + g->live[c]++] = (uint32_t)(2 * k + (size_t)e);
            }
        if (pass == 0)
            for (size_t c = 0; c < cells; c++) g->start[c + 1] += g->start[c];
    }
    return 1;
}

static void grid_free(end_grid *g)
{
    free(g->start);
    free(g->live);
    free(g->entry);
    free(g->used);
}

/* The nearest end of an unused path to (x, y): rings of cells around it until no nearer end can
 * be left. Returns the entry, or UINT32_MAX when every path is used. */
static uint32_t grid_nearest(const end_grid *g, double x, double y)
{
    int cx, cy;
    cell_of(g, x, y, &cx, &cy);
    double ox = fmax(fmax(g->x0 - x, x - (g->x0 + g->nx * g->cell)), 0);
    double oy = fmax(fmax(g->y0 - y, y - (g->y0 + g->ny * g->cell)), 0);
    double outside = hypot(ox, oy), best = INFINITY;
    uint32_t found = UINT32_MAX;
    int rmax = g->nx > g->ny ? g->nx : g->ny;
    for (int r = 0; r <= rmax; r++) {
        if ((r - 1) * g->cell - outside > best) break;
        for (int iy = cy - r; iy <= cy + r; iy++) {
            if (iy < 0 || iy >= g->ny) continue;
            int step = (iy == cy - r || iy == cy + r) ? 1 : 2 * r;
            for (int ix = cx - r; ix <= cx + r; ix += step ? step : 1) {
                if (ix < 0 || ix >= g->nx) continue;
                size_t c = (size_t)iy * (size_t)g->nx + (size_t)ix;
                if (!g->live[c]) continue;
                for (size_t k = g->start[c]; k < g->start[c + 1]; k++) {
                    uint32_t e = g->entry[k];
                    if (g->used[e / 2]) continue;
                    const float *p = g->d->xy + 2 * path_end(g->d, g->path[e / 2], (int)(e & 1));
                    double dd = hypot(p[0] - x, p[1] - y);
                    if (dd < best || (dd == best && e < found)) { best = dd; found = e; }
                }
                if (r == 0) break;
            }
        }
    }
    return found;
}

static void grid_take(end_grid *g, size_t k)
{
    g->used[k] = 1;
    for (int e = 0; e < 1 + two_ends(g->d, g->path[k]); e++) {
        const float *p = g->d->xy + 2 * path_end(g->d, g->path[k], e);
        int cx, cy;
        g->live[cell_of(g, p[0], p[1], &cx, &cy)]--;
    }
}

/* Appends path p of `src` to `dst` (reversed when asked). */
static void copy_path(pnpr_drawing *dst, const pnpr_drawing *src, size_t p, int reversed)
{
    size_t a = src->offset[p], b = src->offset[p + 1], at = dst->offset[dst->count];
    for (size_t v = a; v < b; v++) {
        size_t from = reversed ? a + b - 1 - v : v;
        dst->xy[2 * (at + v - a)] = src->xy[2 * from];
        dst->xy[2 * (at + v - a) + 1] = src->xy[2 * from + 1];
    }
    dst->stroke_width[dst->count] = src->stroke_width[p];
    memcpy(dst->rgba + 4 * dst->count, src->rgba + 4 * p, 4);
    dst->layer[dst->count] = src->layer[p];
    dst->flags[dst->count] = src->flags[p];
    dst->offset[++dst->count] = at + b - a;
}

/* Orders one layer's paths into `dst`, pen starting at (*x, *y); 0 when out of memory. */
static int order_layer(pnpr_drawing *dst, const pnpr_drawing *src, const size_t *path, size_t n, double *x, double *y)
{
    end_grid g;
    memset(&g, 0, sizeof g);
    g.d = src;
    g.path = path;
    g.n = n;
    if (!grid_build(&g)) { grid_free(&g); return 0; }
    for (size_t done = 0; done < n; done++) {
        uint32_t e = grid_nearest(&g, *x, *y);
        if (e == UINT32_MAX) break;
        size_t k = e / 2, p = path[k];
        grid_take(&g, k);
        copy_path(dst, src, p, (int)(e & 1));
        const float *q = src->xy + 2 * ((src->flags[p] & PNPR_PATH_CLOSED) ? src->offset[p] : path_end(src, p, !(e & 1)));
        *x = q[0];
        *y = q[1];
    }
    grid_free(&g);
    return 1;
}

pnpr_status pnpr_drawing_order_for_plotter(pnpr_drawing *d)
{
    if (!d) return PNPR_ERR_INVALID_ARGUMENT;
    if (d->count < 2) return PNPR_OK;
    pnpr_drawing out;
    memset(&out, 0, sizeof out);
    size_t nv = d->offset[d->count];
    out.offset = malloc((d->count + 1) * sizeof *out.offset);
    out.xy = malloc(2 * nv * sizeof *out.xy);
    out.stroke_width = malloc(d->count * sizeof *out.stroke_width);
    out.rgba = malloc(4 * d->count);
    out.layer = malloc(d->count);
    out.flags = malloc(d->count);
    size_t *path = malloc(d->count * sizeof *path);
    int ok = out.offset && out.xy && out.stroke_width && out.rgba && out.layer && out.flags && path;
    if (ok) out.offset[0] = 0;
    double x = 0, y = 0;
    for (int L = 0; ok && L < PNPR_LAYER_COUNT_; L++) {
        size_t n = 0;
        for (size_t i = 0; i < d->count; i++)
            if (d->layer[i] == L) path[n++] = i;
        if (n && L == PNPR_LAYER_FILLS) /* areas (and their holes) keep their order: no pen */
            for (size_t k = 0; k < n; k++) copy_path(&out, d, path[k], 0);
        else if (n) ok = order_layer(&out, d, path, n, &x, &y);
    }
    free(path);
    if (!ok) {
        pnpr_drawing_free(&out);
        return PNPR_ERR_OUT_OF_MEMORY;
    }
    out.width = d->width;
    out.height = d->height;
    memcpy(out.background, d->background, 4);
    out.cap_paths = d->count;
    out.cap_vertices = nv;
    pnpr_drawing_free(d);
    *d = out;
    return PNPR_OK;
}
