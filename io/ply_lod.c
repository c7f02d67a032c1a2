/* A PLY file ordered for drawing (include/pointnpr/lod.h, docs/tiles.md "A file ordered for
 * drawing"): its grid and runs, the header and index parser, and the writer.
 *
 * The writer reads its input through the point filter (io/ply.c): one pass for the box of the
 * finite points and a stride sample (one more for the box of the points that are not far outliers
 * when the sample holds some), one for the runs' counts, then one per chunk of whole cells, which it holds,
 * orders by cell and run (a counting sort, stable: file order within a run) and writes through
 * the join's sink (io/ply_join.c), so that the records are those `pointnpr convert` writes. The
 * index goes after the vertices, the header is written again at the end with the count. */
#include "ply_join.h"

#include "../core/internal.h"
#include "../view/view_internal.h"
#include "file_bytes.h"
#include "io_util.h"
#include <pointnpr/lod.h>
#include <pointnpr/outliers.h>

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define LOD_L PNPR_LOD_LEVELS
#define LOD_POINTS_PER_CELL 8 /* the grid has at most a cell for this many finite points */
#define LOD_HEADER_MAX ((size_t)1 << 20)

uint64_t pnpr_lod_hash(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

int pnpr_lod_run_of(uint64_t i)
{
    uint64_t h = pnpr_lod_hash(i);
    int z = 0; /* leading zeros: the rank lies in [2^-(z+1), 2^-z) */
    while (z < LOD_L - 1 && !(h >> 63)) {
        h <<= 1;
        z++;
    }
    return LOD_L - 1 - z;
}

double pnpr_lod_run_high(int j) { return ldexp(1.0, j + 1 - LOD_L); }
double pnpr_lod_run_low(int j) { return j <= 0 ? 0.0 : ldexp(1.0, j - LOD_L); }

double pnpr_lod_rank(uint64_t v, int j)
{
    double lo = pnpr_lod_run_low(j), hi = pnpr_lod_run_high(j);
    double u = (double)(pnpr_lod_hash(v ^ 0x5851F42D4C957F2Dull) >> 11) * 0x1.0p-53; /* [0, 1) */
    double r = lo + u * (hi - lo);
    return r < hi ? r : lo; /* rounding never reaches the next run */
}

uint32_t pnpr_lod_cell(const pnpr_lod *l, const double p[3])
{
    uint32_t k[3];
    for (int a = 0; a < 3; a++) {
        double t = floor((p[a] - l->origin[a]) / l->side); /* NaN for a non-finite coordinate */
        if (!(t >= 0 && t < (double)l->n[a])) return l->cells;
        k[a] = (uint32_t)t;
    }
    return (k[2] * l->n[1] + k[1]) * l->n[0] + k[0];
}

void pnpr_lod_cell_ball(const pnpr_lod *l, uint32_t k, double r_centre[3], double *r_radius)
{
    uint32_t i[3] = {k % l->n[0], k / l->n[0] % l->n[1], k / l->n[0] / l->n[1]};
    for (int a = 0; a < 3; a++) r_centre[a] = l->origin[a] + ((double)i[a] + 0.5) * l->side;
    /* the half diagonal, and a little more for the rounding of the cell's division */
    *r_radius = l->side * (0.8660254037844387 + 1e-6);
}

size_t pnpr_lod_ranges(const pnpr_lod *l, const double *share, uint64_t *r, uint8_t *r_runs)
{
    size_t m = 0;
    for (uint32_t k = 0; k <= l->cells; k++) {
        int runs = 0;
        while (runs < LOD_L && share[k] > pnpr_lod_run_low(runs)) runs++;
        if (r_runs) r_runs[k] = (uint8_t)runs;
        uint64_t a = l->start[(size_t)k * LOD_L], b = l->start[(size_t)k * LOD_L + (size_t)runs];
        if (b == a) continue;
        if (m && r[2 * m - 1] == a) r[2 * m - 1] = b;
        else {
            r[2 * m] = a;
            r[2 * m + 1] = b;
            m++;
        }
    }
    return m;
}

int pnpr_lod_run_at(const pnpr_lod *l, uint64_t v, size_t *cursor)
{
    size_t r = *cursor, last = ((size_t)l->cells + 1) * LOD_L - 1;
    while (r < last && l->start[r + 1] <= v) r++;
    *cursor = r;
    return (int)(r % LOD_L);
}

int pnpr_lod_kept(const pnpr_lod *l, uint64_t v, size_t *cursor, double share)
{
    if (share >= 1) return 1;
    if (!(share > 0)) return 0;
    if (l) return pnpr_lod_rank(v, pnpr_lod_run_at(l, v, cursor)) < share;
    return pnpr_lod_hash(v) < (uint64_t)(share * 18446744073709551616.0);
}

void pnpr_lod_free(pnpr_lod *l)
{
    if (!l) return;
    free(l->start);
    memset(l, 0, sizeof *l);
}

/* ---- the header and the index ------------------------------------------------------------ */

typedef struct lod_header {
    int has_comment;
    const char *comment; /* the pnpr_lod comment's text after "comment pnpr_lod" (not NUL-ended) */
    size_t comment_len;
    uint64_t vertices, runs;
    size_t record;       /* a vertex record's bytes */
    size_t body;         /* the first byte after end_header */
    int structure_ok;    /* binary LE, the vertex element then pnpr_lod_run with one uint */
    char why[96];        /* what is wrong with the structure */
} lod_header;

/* Whether line [s, e) starts with word w followed by a space or its end; *r_rest after it. */
static int word(const char *s, const char *e, const char *w, const char **r_rest)
{
    size_t n = strlen(w);
    if ((size_t)(e - s) < n || memcmp(s, w, n) || (s + n < e && s[n] != ' ')) return 0;
    *r_rest = s + n < e ? s + n + 1 : e;
    return 1;
}

static int parse_count(const char *s, const char *e, uint64_t *r)
{
    uint64_t v = 0;
    if (s >= e) return 0;
    for (; s < e; s++) {
        if (*s < '0' || *s > '9' || v > (UINT64_MAX - 9) / 10) return 0;
        v = v * 10 + (uint64_t)(*s - '0');
    }
    *r = v;
    return 1;
}

/* The next line of the header d[0..cap) from *pos: [*r_s, *r_e) without its end (\n or \r\n);
 * 0 when no whole line is left. */
static int header_next(const char *d, size_t cap, size_t *pos, const char **r_s, const char **r_e)
{
    const char *s = d + *pos, *nl = *pos < cap ? memchr(s, '\n', cap - *pos) : NULL;
    if (!nl) return 0;
    *r_s = s;
    *r_e = nl > s && nl[-1] == '\r' ? nl - 1 : nl;
    *pos = (size_t)(nl - d) + 1;
    return 1;
}

/* Whether line [s, e) is "element NAME N": its name [*r_name, + *r_len) and count. */
static int element_line(const char *s, const char *e, const char **r_name, size_t *r_len, uint64_t *r_count)
{
    const char *rest, *sp;
    if (!word(s, e, "element", &rest) || !(sp = memchr(rest, ' ', (size_t)(e - rest))) || !parse_count(sp + 1, e, r_count))
        return 0;
    *r_name = rest;
    *r_len = (size_t)(sp - rest);
    return 1;
}

static int named(const char *name, size_t len, const char *w) { return len == strlen(w) && !memcmp(name, w, len); }

/* One header line [s, e) after "format": elements and properties in the order lod.h says. */
static void header_line(lod_header *h, const char *s, const char *e, int *elem)
{
    const char *rest;
    if (word(s, e, "comment", &rest)) {
        const char *r2;
        if (word(rest, e, "pnpr_lod", &r2)) {
            h->has_comment++;
            h->comment = r2;
            h->comment_len = (size_t)(e - r2);
        }
    } else if (word(s, e, "obj_info", &rest)) {
    } else if (word(s, e, "element", &rest)) {
        const char *name = NULL;
        size_t len = 0;
        uint64_t n = 0;
        int ok = element_line(s, e, &name, &len, &n);
        if (*elem == 0 && ok && named(name, len, "vertex")) h->vertices = n, *elem = 1;
        else if (*elem == 1 && ok && named(name, len, "pnpr_lod_run")) h->runs = n, *elem = 2;
        else if (!h->why[0]) snprintf(h->why, sizeof h->why, "elements other than vertex, then pnpr_lod_run");
    } else if (word(s, e, "property", &rest)) {
        const char *sp = memchr(rest, ' ', (size_t)(e - rest));
        size_t z = sp ? pnpr_ply_type_size(rest, (size_t)(sp - rest)) : 0;
        if (*elem == 1 && z && !memchr(sp + 1, ' ', (size_t)(e - sp - 1)) && sp + 1 < e) h->record += z;
        else if (*elem == 2 && z == 4 && (named(rest, (size_t)(sp - rest), "uint") || named(rest, (size_t)(sp - rest), "uint32")) &&
                 named(sp + 1, (size_t)(e - sp - 1), "count"))
            *elem = 3;
        else if (!h->why[0]) snprintf(h->why, sizeof h->why, "a property that is not a vertex scalar or the runs' uint count");
    } else if (!h->why[0]) {
        snprintf(h->why, sizeof h->why, "a header line it does not know");
    }
}

/* The header of data[0..size): the structure lod.h describes; UNSUPPORTED when it has no
 * pnpr_lod comment. */
static pnpr_status parse_header(const char *d, size_t size, lod_header *h, pnpr_error *err)
{
    memset(h, 0, sizeof *h);
    size_t pos = 0, cap = size < LOD_HEADER_MAX ? size : LOD_HEADER_MAX;
    int line = 0, elem = 0, binary_le = 0;
    const char *s, *e;
    while (header_next(d, cap, &pos, &s, &e)) {
        line++;
        if (line == 1) {
            if (e - s != 3 || memcmp(s, "ply", 3)) break;
        } else if (line == 2) {
            binary_le = e - s == 31 && !memcmp(s, "format binary_little_endian 1.0", 31);
        } else if (e - s == 10 && !memcmp(s, "end_header", 10)) {
            h->body = pos;
            h->structure_ok = binary_le && elem == 3 && !h->why[0] && h->has_comment == 1;
            if (!binary_le) snprintf(h->why, sizeof h->why, "not binary little-endian");
            else if (elem != 3 && !h->why[0]) snprintf(h->why, sizeof h->why, "no pnpr_lod_run element after the vertices");
            else if (h->has_comment > 1) snprintf(h->why, sizeof h->why, "more than one pnpr_lod comment");
            return h->has_comment ? PNPR_OK : pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "not a file ordered for drawing");
        } else {
            header_line(h, s, e, &elem);
        }
    }
    if (h->has_comment) return pnpr_error_set(err, PNPR_ERR_FORMAT, "its PLY header has no end (end_header)");
    return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "not a file ordered for drawing");
}

/* The next space-separated token of *t as an unsigned integer at most `most` (1); 0 when it is
 * not one. */
static int next_uint(const char **t, unsigned long most, unsigned *r)
{
    char *end;
    if (**t < '0' || **t > '9') return 0;
    errno = 0;
    unsigned long v = strtoul(*t, &end, 10);
    if (errno || v > most || (*end != ' ' && *end != '\0')) return 0;
    *r = (unsigned)v;
    *t = *end ? end + 1 : end;
    return 1;
}

static int next_double(const char **t, double *r)
{
    char *end;
    *r = strtod(*t, &end);
    if (end == *t || (*end != ' ' && *end != '\0')) return 0;
    *t = *end ? end + 1 : end;
    return 1;
}

static int next_word(const char **t, const char *w)
{
    size_t n = strlen(w);
    if (strncmp(*t, w, n) || (*t)[n] != ' ') return 0;
    *t += n + 1;
    return 1;
}

/* The grid of the pnpr_lod comment into l: "1 levels L grid NX NY NZ side S origin X Y Z". */
static pnpr_status parse_grid(const lod_header *h, pnpr_lod *l, pnpr_error *err)
{
    char text[512];
    if (h->comment_len >= sizeof text) return pnpr_error_set(err, PNPR_ERR_FORMAT, "its pnpr_lod comment is too long");
    memcpy(text, h->comment, h->comment_len);
    text[h->comment_len] = '\0';
    const char *t = text;
    unsigned version = 0, levels = 0, n[3] = {0, 0, 0};
    int ok = next_uint(&t, 1000, &version) && next_word(&t, "levels") && next_uint(&t, 1000, &levels) &&
             next_word(&t, "grid");
    for (int a = 0; a < 3 && ok; a++) ok = next_uint(&t, PNPR_VIEW_CELLS_MAX + 1, &n[a]);
    ok = ok && next_word(&t, "side") && next_double(&t, &l->side) && next_word(&t, "origin");
    for (int a = 0; a < 3 && ok; a++) ok = next_double(&t, &l->origin[a]);
    if (!ok || *t)
        return pnpr_error_set(err, PNPR_ERR_FORMAT,
                              "its pnpr_lod comment is not \"%d levels L grid NX NY NZ side S origin X Y Z\"",
                              PNPR_LOD_VERSION);
    if (version != PNPR_LOD_VERSION || levels != LOD_L)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                              "ordered for drawing by version %u with %u levels; this pointnpr reads version %d with %d "
                              "(write it again: pointnpr convert --lod)", version, levels, PNPR_LOD_VERSION, LOD_L);
    double cells = (double)n[0] * n[1] * n[2];
    int finite = l->side > 0 && isfinite(l->side); /* every cell's corner a finite double */
    for (int a = 0; a < 3; a++) finite = finite && isfinite(l->origin[a] + l->side * n[a]) && isfinite(l->origin[a]);
    if (!n[0] || !n[1] || !n[2] || cells > PNPR_VIEW_CELLS_MAX || !finite)
        return pnpr_error_set(err, PNPR_ERR_FORMAT,
                              "its grid (%u x %u x %u cells of side %g from %g %g %g) is not 1 to %d cells of finite "
                              "corners", n[0], n[1], n[2], l->side, l->origin[0], l->origin[1], l->origin[2],
                              PNPR_VIEW_CELLS_MAX);
    memcpy(l->n, n, sizeof n);
    l->cells = n[0] * n[1] * n[2];
    return PNPR_OK;
}

pnpr_status pnpr_lod_parse(const void *data, size_t size, pnpr_lod *l, pnpr_error *err)
{
    if (!l || (!data && size)) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "lod: NULL argument");
    memset(l, 0, sizeof *l);
    lod_header h;
    const unsigned char *d = data;
    pnpr_status st = parse_header((const char *)d, size, &h, err);
    if (st != PNPR_OK) return st;
    if (!h.structure_ok)
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "says it is ordered for drawing, but its header has %s", h.why);
    if ((st = parse_grid(&h, l, err)) != PNPR_OK) return st;
    const uint64_t runs = ((uint64_t)l->cells + 1) * LOD_L;
    uint64_t index = pnpr_add_sat(h.body, pnpr_mul_sat(h.vertices, h.record));
    if (h.vertices > UINT32_MAX)
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "says it holds %llu points, more than a file ordered for drawing does",
                              (unsigned long long)h.vertices);
    if (h.runs != runs || h.record == 0)
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "its index has %llu runs where its grid has %llu",
                              (unsigned long long)h.runs, (unsigned long long)runs);
    if (index > size || size - index < 4 * runs)
        return pnpr_error_set(err, PNPR_ERR_FORMAT,
                              "is truncated: %zu bytes where its %llu points and index need %llu", size,
                              (unsigned long long)h.vertices, (unsigned long long)pnpr_add_sat(index, 4 * runs));
    if (!(l->start = malloc((size_t)(runs + 1) * sizeof *l->start)))
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "lod: out of memory for its index");
    uint64_t sum = 0;
    for (size_t r = 0; r < runs; r++) {
        const unsigned char *p = d + index + 4 * r;
        l->start[r] = (uint32_t)sum; /* sum != the header's count (< 2^32) below when it wraps */
        sum += (uint64_t)p[0] | (uint64_t)p[1] << 8 | (uint64_t)p[2] << 16 | (uint64_t)p[3] << 24;
    }
    l->start[runs] = (uint32_t)sum;
    l->points = h.vertices;
    if (sum != h.vertices) {
        pnpr_lod_free(l);
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "its index counts %llu points, its header %llu",
                              (unsigned long long)sum, (unsigned long long)h.vertices);
    }
    return PNPR_OK;
}

pnpr_status pnpr_lod_open(const char *path, pnpr_lod *l, pnpr_error *err)
{
    struct stat sb;
    if (!path || !l) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "lod: NULL argument");
    memset(l, 0, sizeof *l);
    if (pnpr_format_from_path(path) != PNPR_FORMAT_PLY || stat(path, &sb) != 0 || !S_ISREG(sb.st_mode))
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: not a file ordered for drawing", path);
    pnpr_file_bytes fb;
    pnpr_status st = pnpr_file_bytes_open(path, &fb, err);
    if (st != PNPR_OK) return st;
    st = pnpr_lod_parse(fb.data, fb.size, l, err); /* touches the header's and the index's pages */
    pnpr_file_bytes_close(&fb);
    if (st != PNPR_OK) pnpr_error_prefix_path(err, path);
    return st;
}

/* ---- the writer ---------------------------------------------------------------------------- */

/* The box pass keeps every step-th finite point (step doubling whenever PNPR_OUTLIER_SAMPLES are
 * kept): the robust centre and extent of far outliers (outliers.h) from that stride sample. */
#define LOD_SAMPLES PNPR_OUTLIER_SAMPLES

typedef struct lod_scan {
    const pnpr_lod *l;
    double lo[3], hi[3];
    uint64_t finite;
    double *sample;        /* LOD_SAMPLES points */
    size_t m;
    uint64_t step;
    uint64_t *counts;      /* the runs' pass: each run's points */
    uint32_t c0, c1;       /* a chunk's pass: its cells [c0, c1) */
    const pnpr_outlier_info *far; /* the inlier pass: the far-outlier frame */
    uint64_t inliers;
    uint32_t *key;         /* each point kept: its run, counted from the chunk's first */
    size_t nkey, cap;
} lod_scan;

/* s's box grown by p, the box of the `before` points already in it (0: p alone). */
static void box_grow(lod_scan *s, uint64_t before, const double p[3])
{
    for (int a = 0; a < 3; a++) {
        if (!before || p[a] < s->lo[a]) s->lo[a] = p[a];
        if (!before || p[a] > s->hi[a]) s->hi[a] = p[a];
    }
}

static int scan_box(void *u, uint64_t i, const double p[3])
{
    (void)i;
    lod_scan *s = u;
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) return 0;
    box_grow(s, s->finite, p);
    if (s->finite++ % s->step) return 0;
    if (s->m == LOD_SAMPLES) { /* every other one: the stride doubles */
        for (size_t k = 1; 2 * k < LOD_SAMPLES; k++) memcpy(s->sample + 3 * k, s->sample + 6 * k, 3 * sizeof *p);
        s->m = LOD_SAMPLES / 2;
        s->step *= 2;
        if ((s->finite - 1) % s->step) return 0;
    }
    memcpy(s->sample + 3 * s->m++, p, 3 * sizeof *p);
    return 0;
}

static int scan_runs(void *u, uint64_t i, const double p[3])
{
    lod_scan *s = u;
    s->counts[(size_t)pnpr_lod_cell(s->l, p) * LOD_L + (size_t)pnpr_lod_run_of(i)]++;
    return 0;
}

static int scan_chunk(void *u, uint64_t i, const double p[3])
{
    lod_scan *s = u;
    uint32_t k = pnpr_lod_cell(s->l, p);
    if (k < s->c0 || k >= s->c1 || s->nkey == s->cap) return 0; /* the count pass sized key */
    s->key[s->nkey++] = (k - s->c0) * LOD_L + (uint32_t)pnpr_lod_run_of(i);
    return 1;
}

/* One pass over `in` with keep (nothing kept but by scan_chunk). */
static pnpr_status scan_pass(const char *in, int (*keep)(void *, uint64_t, const double *), lod_scan *s,
                             pnpr_cloud *r_cloud, pnpr_error *err)
{
    pnpr_read_options ro = {0};
    ro.keep = keep;
    ro.keep_user = s;
    pnpr_cloud none = {0};
    pnpr_status st = pnpr_read_file(in, &ro, r_cloud ? r_cloud : &none, err);
    pnpr_cloud_free(&none);
    return st;
}

/* The box pass again when the stride sample holds far outliers (outliers.h): the box of the
 * points that are not far by its frame. */
static int scan_inliers(void *u, uint64_t i, const double p[3])
{
    (void)i;
    lod_scan *s = u;
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]) || pnpr_outlier_is_far(s->far, p)) return 0;
    box_grow(s, s->inliers, p);
    s->inliers++;
    return 0;
}

/* The box the grid covers: every finite point's when the stride sample holds no far outlier (as
 * `info` judges them: outliers.h), else that of the points not far by the sample's frame (one
 * pass more). The points outside it, far outliers, go to the last cell with the non-finite ones. */
static pnpr_status lod_box(const char *in, lod_scan *s, pnpr_error *err)
{
    pnpr_outlier_info far = {{0, 0, 0}, 0, INFINITY, 0, 0, 0};
    if (!s->m || pnpr_outlier_frame_of_sample(s->sample, s->m, &far) != PNPR_OK) return PNPR_OK;
    size_t any = 0;
    for (size_t i = 0; i < s->m; i++) any += pnpr_outlier_is_far(&far, s->sample + 3 * i);
    if (!any) return PNPR_OK;
    s->far = &far;
    s->inliers = 0;
    pnpr_status st = scan_pass(in, scan_inliers, s, NULL, err);
    s->far = NULL;
    return st;
}

/* The grid (view/view_cells.c's cells) over the box: at most a cell for LOD_POINTS_PER_CELL
 * points; a single cell covers the box too (side: its longest extent). */
static void lod_grid(const lod_scan *s, pnpr_lod *l)
{
    float zero[3] = {0, 0, 0}, ext[3];
    double longest = 0;
    for (int a = 0; a < 3; a++) { /* 1e-5 more: the box's far faces inside the float grid */
        double e = s->finite ? (s->hi[a] - s->lo[a]) * (1 + 1e-5) : 0.0;
        ext[a] = (float)e;
        longest = e > longest ? e : longest;
        l->origin[a] = s->finite ? s->lo[a] : 0.0;
    }
    float side;
    uint64_t most = s->finite / LOD_POINTS_PER_CELL; /* a cell's 16 runs, 64 bytes, for 8 points at least */
    pnpr_view_cells_grid(zero, ext, most < PNPR_VIEW_CELLS_MAX ? (uint32_t)most : PNPR_VIEW_CELLS_MAX, &side, l->n);
    l->cells = l->n[0] * l->n[1] * l->n[2];
    l->side = l->cells > 1 ? side : longest > 0 && isfinite(longest) ? longest : longest > 0 ? DBL_MAX : 1.0;
}

/* The points of cells [c0, c1) (`count` of them), ordered by cell and run, into the output. */
static pnpr_status write_chunk(const char *in, pnpr_join_sink *j, lod_scan *s, uint64_t count, pnpr_error *err)
{
    const size_t keys = (size_t)(s->c1 - s->c0) * LOD_L;
    pnpr_cloud c = {0};
    s->nkey = 0;
    s->cap = (size_t)count;
    s->key = malloc((s->cap ? s->cap : 1) * sizeof *s->key);
    uint32_t *perm = malloc((s->cap ? s->cap : 1) * sizeof *perm);
    size_t *at = calloc(keys + 1, sizeof *at);
    pnpr_status st = s->key && perm && at ? scan_pass(in, scan_chunk, s, &c, err)
                                          : pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory for a chunk of %llu points",
                                                           in, (unsigned long long)count);
    if (st == PNPR_OK && (c.count != s->nkey || s->nkey != count))
        st = pnpr_error_set(err, PNPR_ERR_IO, "%s: changed while it was read (%zu points in cells %u-%u, %llu before)", in,
                            c.count, s->c0, s->c1 - 1, (unsigned long long)count);
    if (st == PNPR_OK) { /* a stable counting sort by key */
        for (size_t i = 0; i < c.count; i++) at[s->key[i] + 1]++;
        for (size_t k = 0; k < keys; k++) at[k + 1] += at[k];
        for (size_t i = 0; i < c.count; i++) perm[at[s->key[i]]++] = (uint32_t)i;
        st = pnpr_cloud_permute(&c, perm);
        if (st != PNPR_OK) pnpr_error_set(err, st, "%s: out of memory to order a chunk", in);
    }
    pnpr_write_options wo = {0};
    if (st == PNPR_OK) st = pnpr_join_cloud(j, &c, &wo, in, err);
    pnpr_cloud_free(&c);
    free(s->key);
    s->key = NULL;
    free(perm);
    free(at);
    return st;
}

/* The most points a chunk holds in `memory` bytes (0: all), whole cells; a point's bytes: its
 * record (the file's share), the reader's growth, its key, order and scratch. */
static uint64_t chunk_points(const char *in, const pnpr_lod *l, size_t memory)
{
    struct stat sb;
    double rec = stat(in, &sb) == 0 && l->points ? (double)sb.st_size / (double)l->points : 64.0;
    double fit = memory ? (double)memory / (1.5 * rec + 40.0) : 0;
    return !memory ? UINT64_MAX : fit >= 1 ? (uint64_t)fit : 1;
}

/* The end of the chunk from cell c0: whole cells up to `most` points (one cell at least);
 * *r_count its points. */
static uint32_t chunk_end(const pnpr_lod *l, uint32_t c0, uint64_t most, uint64_t *r_count)
{
    uint64_t count = 0;
    uint32_t c1 = c0;
    while (c1 <= l->cells) {
        uint64_t n = pnpr_lod_cell_points(l, c1);
        if (c1 > c0 && count + n > most) break;
        count += n;
        c1++;
    }
    *r_count = count;
    return c1;
}

/* The chunks' passes over the input. */
static size_t chunk_passes(const pnpr_lod *l, uint64_t most)
{
    size_t passes = 0;
    uint64_t count;
    for (uint32_t c0 = 0; c0 <= l->cells; c0 = chunk_end(l, c0, most, &count)) passes++;
    return passes;
}

/* The chunks, each written. */
static pnpr_status write_chunks(const char *in, pnpr_join_sink *j, lod_scan *s, const pnpr_lod_options *o,
                                pnpr_error *err)
{
    const pnpr_lod *l = s->l;
    const uint64_t most = chunk_points(in, l, o->memory);
    uint32_t c0 = 0;
    pnpr_status st = PNPR_OK;
    while (st == PNPR_OK && c0 <= l->cells) {
        uint64_t count = 0;
        uint32_t c1 = chunk_end(l, c0, most, &count);
        s->c0 = c0;
        s->c1 = c1;
        st = write_chunk(in, j, s, count, err);
        if (st == PNPR_OK && pnpr_progress_report(&o->progress, "lod write", (double)l->start[(size_t)c1 * LOD_L] /
                                                                               (double)(l->points ? l->points : 1)))
            st = pnpr_error_set(err, PNPR_ERR_CANCELLED, "cancelled; nothing written");
        c0 = c1;
    }
    return st;
}

/* The index (each run's count, uint32 little-endian) after the vertices. */
static int write_index(pnpr_output *out, const pnpr_lod *l)
{
    const size_t runs = ((size_t)l->cells + 1) * LOD_L;
    unsigned char b[4 * 256];
    for (size_t r = 0; r < runs; r += 256) {
        size_t m = runs - r < 256 ? runs - r : 256;
        for (size_t i = 0; i < m; i++) {
            uint64_t n = l->start[r + i + 1] - l->start[r + i];
            for (int k = 0; k < 4; k++) b[4 * i + (size_t)k] = (unsigned char)(n >> (8 * k));
        }
        if (pnpr_output_sink(out, b, 4 * m)) return 1;
    }
    return 0;
}

/* A file ordered for drawing holds points only: an input with faces (or any element but its
 * vertices) is refused, naming them, rather than written without them. Reads the header alone. */
static pnpr_status points_only(const char *in, pnpr_error *err)
{
    pnpr_file_bytes fb;
    pnpr_status st = pnpr_file_bytes_open(in, &fb, err);
    if (st != PNPR_OK) return st;
    const char *d = (const char *)fb.data;
    size_t pos = 0, cap = fb.size < LOD_HEADER_MAX ? fb.size : LOD_HEADER_MAX;
    const char *s, *e, *name;
    size_t len;
    uint64_t n;
    while (st == PNPR_OK && header_next(d, cap, &pos, &s, &e) && !(e - s == 10 && !memcmp(s, "end_header", 10)))
        if (element_line(s, e, &name, &len, &n) && n > 0 && !named(name, len, "vertex"))
            st = pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                                "%s: holds %llu %.*s besides its points; a file ordered for drawing holds points only "
                                "(render and animate read the file as it is)", in, (unsigned long long)n, (int)len, name);
    pnpr_file_bytes_close(&fb);
    return st;
}

/* The passes over `in` for the box and the runs: l's grid and starts. */
static pnpr_status plan_lod(const char *in, const pnpr_lod_options *o, lod_scan *s, pnpr_lod *l, pnpr_error *err)
{
    pnpr_status st0 = points_only(in, err);
    if (st0 != PNPR_OK) return st0;
    s->step = 1;
    if (!(s->sample = malloc(3 * LOD_SAMPLES * sizeof *s->sample)))
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "out of memory for the sample");
    pnpr_status st = scan_pass(in, scan_box, s, NULL, err);
    if (st != PNPR_OK) return st;
    if ((st = lod_box(in, s, err)) != PNPR_OK) return st;
    if (pnpr_progress_report(&o->progress, "lod scan", 0.5)) return pnpr_error_set(err, PNPR_ERR_CANCELLED, "cancelled");
    lod_grid(s, l);
    const size_t runs = ((size_t)l->cells + 1) * LOD_L;
    s->l = l;
    if (!(s->counts = calloc(runs, sizeof *s->counts)) || !(l->start = malloc((runs + 1) * sizeof *l->start)))
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "out of memory for the runs");
    if ((st = scan_pass(in, scan_runs, s, NULL, err)) != PNPR_OK) return st;
    uint64_t sum = 0;
    for (size_t r = 0; r < runs; r++) {
        l->start[r] = (uint32_t)sum; /* refused below when it wraps */
        sum += s->counts[r];
    }
    l->start[runs] = (uint32_t)sum;
    l->points = sum;
    if (sum > UINT32_MAX)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%llu points, more than a file ordered for drawing holds (%u)",
                              (unsigned long long)sum, UINT32_MAX);
    return pnpr_progress_report(&o->progress, "lod scan", 1.0) ? pnpr_error_set(err, PNPR_ERR_CANCELLED, "cancelled")
                                                                : PNPR_OK;
}

pnpr_status pnpr_lod_write(const char *in, const char *out_path, const pnpr_lod_options *opts, uint64_t *r_points,
                           pnpr_error *err)
{
    pnpr_lod_options o = opts ? *opts : (pnpr_lod_options){0};
    if (r_points) *r_points = 0;
    if (!in || !out_path) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "lod: no input or no output");
    pnpr_status st = pnpr_output_check(out_path, &in, 1, err);
    if (st != PNPR_OK) return st;
    lod_scan s = {0};
    pnpr_lod l = {0};
    st = plan_lod(in, &o, &s, &l, err);
    const size_t passes = st == PNPR_OK && o.max_passes ? chunk_passes(&l, chunk_points(in, &l, o.memory)) : 0;
    if (passes > o.max_passes)
        st = pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY,
                            "%s: %zu chunks of whole cells would fit the memory given, a pass over the file each (at "
                            "most %zu asked): give more memory", in, passes, o.max_passes);
    if (st != PNPR_OK) {
        if (!strstr(err ? err->message : "", in)) pnpr_error_prefix_path(err, in);
        free(s.counts);
        free(s.sample);
        pnpr_lod_free(&l);
        return st;
    }
    pnpr_output out;
    if ((st = pnpr_output_open(&out, out_path, err)) == PNPR_OK && out.mode != PNPR_OUTPUT_REPLACE) {
        pnpr_status discarded = pnpr_output_close(&out, PNPR_ERR_UNSUPPORTED, NULL);
        st = pnpr_error_set(err, discarded, "%s: a file ordered for drawing is written into a regular file (not a "
                                            "device, pipe or standard output)", out_path);
    } else if (st == PNPR_OK) {
        char comment[256], elems[96];
        snprintf(comment, sizeof comment, "comment pnpr_lod %d levels %d grid %u %u %u side %.17g origin %.17g %.17g %.17g\n",
                 PNPR_LOD_VERSION, LOD_L, l.n[0], l.n[1], l.n[2], l.side, l.origin[0], l.origin[1], l.origin[2]);
        snprintf(elems, sizeof elems, "element pnpr_lod_run %zu\nproperty uint count\n", ((size_t)l.cells + 1) * LOD_L);
        pnpr_join_sink j = {&out, {0}, 0, NULL, 0, 0, 0, comment, elems};
        st = write_chunks(in, &j, &s, &o, err);
        if (st == PNPR_OK && (write_index(&out, &l) || fflush(out.f) != 0 || fseek(out.f, 0, SEEK_SET) != 0 ||
                              pnpr_join_header(&j, l.points)))
            st = PNPR_ERR_IO;
        free(j.head.data);
        free(j.first);
        st = pnpr_output_close(&out, st, err);
    }
    if (st == PNPR_OK && r_points) *r_points = l.points;
    free(s.counts);
    free(s.sample);
    pnpr_lod_free(&l);
    return st;
}
