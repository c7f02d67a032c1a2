/* pointnpr — io/text_points.c: text point clouds (XYZ, PTS, PWN, CSV, TXT), plain C11.
 *
 * No library reads these: they are a line per point, values separated by blanks, and each tool
 * picks its own columns (MeshLab: x y z [nx ny nz]; CGAL: .xyz / .pwn x y z [nx ny nz]; Leica
 * PTS: a count line, then x y z [intensity [r g b]]; CloudCompare: any columns, a "//X,Y,Z"
 * header). Debian has no package for them; the reader is one pass over the file's bytes (mapped,
 * io/file_bytes.h), keeping nothing but the points.
 *
 *  - Lines end with LF or CR LF. Values are separated by any run of blanks (space, tab, CR, VT,
 *    FF), commas and semicolons. '#' starts a comment to the end of the line; blank and comment
 *    lines are skipped. Bytes 0x00-0x08, 0x0E-0x1F and 0x7F are binary data: an error.
 *  - Columns, the first rule that applies:
 *      1. opts->columns ("x,y,z,nx,ny,nz,r,g,b,intensity,_"): those names. A first line that is
 *         not all numbers is then a header row and skipped.
 *      2. a header row: the first line that is not a comment, when any of its words is not a
 *         number (also "//X,Y,Z,R,G,B" as CloudCompare writes it; quotes around names dropped).
 *      3. the format's defaults, from the number of values on the first data line:
 *         PTS  3: x y z   4: x y z intensity   6: x y z r g b   7: x y z intensity r g b
 *         others (and PTS otherwise): x y z, then for n >= 6 nx ny nz (as CGAL and MeshLab
 *         write .xyz and .pwn), then extra properties scalar_k (k = the column, from 1). When
 *         columns 4-6 hold only integers 0..255 over the whole file and some exceed 1, they
 *         are colours r g b instead (x y z r g b, as CloudCompare writes), not normals (but
 *         always normals in .pwn, "points with normals").
 *  - Names (case-insensitive): x y z (required); nx ny nz or normal_x normal_y normal_z
 *    (normals, when all three); r g b or red green blue (colours, when all three); label or
 *    segment (labels: integers 0..2^32-1); _ or skip (the column is dropped); anything else is an
 *    extra property of that name (double). At most 1024 columns.
 *  - Every data line has exactly as many values as there are columns. A line with a single
 *    integer is a count line (Leica PTS, also the sections of multi-scan PTS files): the points
 *    up to the next count line or the end must be exactly that many (fewer: PNPR_ERR_TRUNCATED).
 *  - Values: decimal numbers in the "C" form ([+-]digits[.digits][e[+-]digits], finite), or nan /
 *    inf / -inf (kept as non-finite points, which every stage skips, as the PLY reader keeps
 *    them). Coordinates are kept as exact doubles (src_xyz, src_coord_type FLOAT64) with float
 *    offsets from the bounding-box centre (pnpr_cloud_set_world), as PLY doubles. Colours: when
 *    any colour value of the file is written with a '.' or an exponent, all are floats 0..1
 *    (x 255, rounded, clamped), else bytes 0..255 (larger values: an error).
 *  - Memory: the points' arrays grow by doubling as lines are read (no count is trusted); at most
 *    about 2 x (24 + 12 + 12 + 8 per extra column) bytes a point.
 *  - Errors: "FILE: line N: ..." (err->line = N), PNPR_ERR_FORMAT for malformed text,
 *    PNPR_ERR_TRUNCATED when a count line announces more points than follow. Progress stage
 *    "read text" every 65536 points.
 */
#include <pointnpr/io.h>

#include "../core/internal.h"
#include "file_bytes.h"
#include "io_util.h"
#include "text_token.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

pnpr_status pnpr_read_text_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud, pnpr_error *err);

#define TX_MAX_COLS 1024
#define TX_CHUNK 65536u
#define TX_SHOW 40
#define TX_NAME 64

#if defined(__GNUC__)
#define TX_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define TX_PRINTF(a, b)
#endif

enum tx_role { R_X, R_Y, R_Z, R_NX, R_NY, R_NZ, R_R, R_G, R_B, R_LABEL, R_SKIP, R_EXTRA };

typedef struct tx_col {
    int role;
    size_t extra; /* R_EXTRA: index of its array */
    char name[TX_NAME];
} tx_col;

typedef struct tx_rd {
    const char *d;
    size_t size, pos;
    long line;
    pnpr_file_format fmt;
    pnpr_error *err;
    const pnpr_progress *progress;
    pnpr_token tok[TX_MAX_COLS + 1];
    size_t ntok;
    tx_col cols[TX_MAX_COLS];
    size_t ncols;
    int from_option, header_seen;
    /* points */
    size_t n, cap, nextra;
    double *xyz;
    float *nrm, *col;
    uint32_t *lab;
    double *extra[TX_MAX_COLS];
    int has_nrm, has_rgb, has_lab;
    int colour_fraction;
    long colour_big_line;
    int guess_rgb;     /* default columns 4-6: normals, unless every value is a byte and some > 1 */
    int not_bytes, above_one;
    /* count lines */
    uint64_t section_count;
    long section_line;
    size_t section_start;
} tx_rd;

static pnpr_status TX_PRINTF(4, 5) tx_fail(tx_rd *r, pnpr_status st, long line, const char *fmt, ...)
{
    pnpr_error *err = r->err;
    if (!err) return st;
    int n = line > 0 ? snprintf(err->message, sizeof err->message, "line %ld: ", line) : 0;
    if (n < 0 || (size_t)n >= sizeof err->message) n = 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message + n, sizeof err->message - (size_t)n, fmt, ap);
    va_end(ap);
    err->line = line > 0 ? line : 0;
    err->offset = -1;
    return st;
}

/* A double into a float without an out-of-range conversion (undefined in C). */
static float tx_d2f(double v)
{
    return v != v ? (float)v : v > FLT_MAX ? INFINITY : v < -FLT_MAX ? -INFINITY : (float)v;
}

static int show(pnpr_token t) { return (int)(t.n > TX_SHOW ? TX_SHOW : t.n); }
static int tx_sep(char c) { return pnpr_is_blank(c) || c == ',' || c == ';'; }
static int tx_binary(unsigned char c) { return (c < 0x20 && c != '\t' && c != '\n' && (c < 0x0b || c > 0x0d)) || c == 0x7f; }

/* Splits [ls, le) into r->tok (comment cut); more than TX_MAX_COLS values is an error. */
static pnpr_status tx_split(tx_rd *r, const char *ls, const char *le)
{
    r->ntok = 0;
    for (const char *c = ls; c < le; c++) {
        if (tx_binary((unsigned char)*c))
            return tx_fail(r, PNPR_ERR_FORMAT, r->line, "byte 0x%02x (offset %zu) is not text: binary data, not a text "
                           "point cloud", (unsigned char)*c, (size_t)(c - r->d));
        if (*c == '#') { le = c; break; }
    }
    for (const char *p = ls; p < le;) {
        while (p < le && tx_sep(*p)) p++;
        if (p >= le) break;
        const char *s = p;
        while (p < le && !tx_sep(*p)) p++;
        if (r->ntok == TX_MAX_COLS)
            return tx_fail(r, PNPR_ERR_UNSUPPORTED, r->line, "more than %d values on one line", TX_MAX_COLS);
        r->tok[r->ntok].s = s;
        r->tok[r->ntok++].n = (size_t)(p - s);
    }
    return PNPR_OK;
}

static int tx_lower_is(pnpr_token t, const char *lit)
{
    size_t n = strlen(lit);
    if (t.n != n) return 0;
    for (size_t i = 0; i < n; i++) {
        char c = t.s[i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != lit[i]) return 0;
    }
    return 1;
}

/* A value: a decimal number, or nan / inf / -inf. */
static int tx_value(pnpr_token t, double *v, int *frac)
{
    *frac = 0;
    if (pnpr_token_decimal(t, v, frac)) return 1;
    pnpr_token u = t;
    int neg = u.n && (u.s[0] == '-' || u.s[0] == '+');
    if (neg) { neg = u.s[0] == '-'; u.s++; u.n--; }
    if (tx_lower_is(u, "nan")) { *v = NAN; return 1; }
    if (tx_lower_is(u, "inf") || tx_lower_is(u, "infinity")) { *v = neg ? -INFINITY : INFINITY; return 1; }
    return 0;
}

static int tx_all_numbers(const tx_rd *r)
{
    double v;
    int frac;
    for (size_t k = 0; k < r->ntok; k++)
        if (!tx_value(r->tok[k], &v, &frac)) return 0;
    return 1;
}

/* ------------------------------------------------------------------------------------------ */
/* Columns                                                                                     */

static int tx_role_of(pnpr_token t)
{
    static const char *const names[][3] = {{"x", "", ""}, {"y", "", ""}, {"z", "", ""},
                                           {"nx", "normal_x", ""}, {"ny", "normal_y", ""}, {"nz", "normal_z", ""},
                                           {"r", "red", ""}, {"g", "green", ""}, {"b", "blue", ""},
                                           {PNPR_PROP_LABEL, PNPR_PROP_SEGMENT, ""}, {"_", "skip", ""}};
    for (int role = 0; role <= R_SKIP; role++)
        for (int k = 0; k < 3 && names[role][k][0]; k++)
            if (tx_lower_is(t, names[role][k])) return role;
    return R_EXTRA;
}

static pnpr_status tx_add_col(tx_rd *r, pnpr_token t, long line)
{
    if (t.n >= 2 && (t.s[0] == '"' || t.s[0] == '\'') && t.s[t.n - 1] == t.s[0]) t.s++, t.n -= 2;
    if (t.n == 0 || t.n >= TX_NAME)
        return tx_fail(r, line ? PNPR_ERR_FORMAT : PNPR_ERR_INVALID_ARGUMENT, line,
                   "column %zu: the name '%.*s' is empty or longer than %d bytes",
                       r->ncols + 1, show(t), t.s, TX_NAME - 1);
    tx_col *c = &r->cols[r->ncols];
    c->role = tx_role_of(t);
    memcpy(c->name, t.s, t.n);
    c->name[t.n] = '\0';
    for (size_t k = 0; k < r->ncols; k++)
        if (c->role != R_SKIP && strcmp(r->cols[k].name, c->name) == 0)
            return tx_fail(r, line ? PNPR_ERR_FORMAT : PNPR_ERR_INVALID_ARGUMENT, line, "column '%s' appears twice", c->name);
    r->ncols++;
    return PNPR_OK;
}

/* Roles that need all three of a group fall back to extra properties; x y z are required. */
static pnpr_status tx_finish_cols(tx_rd *r, long line)
{
    int seen[R_EXTRA] = {0};
    for (size_t k = 0; k < r->ncols; k++)
        if (r->cols[k].role < R_EXTRA) seen[r->cols[k].role]++;
    if (!seen[R_X] || !seen[R_Y] || !seen[R_Z])
        return tx_fail(r, line ? PNPR_ERR_FORMAT : PNPR_ERR_INVALID_ARGUMENT, line, "the columns (%s) have no %s column",
                       r->from_option ? "--columns" : "header",
                       !seen[R_X] ? "x" : !seen[R_Y] ? "y" : "z");
    r->has_nrm = seen[R_NX] && seen[R_NY] && seen[R_NZ];
    r->has_rgb = seen[R_R] && seen[R_G] && seen[R_B];
    r->has_lab = seen[R_LABEL] > 0;
    for (size_t k = 0; k < r->ncols; k++) {
        tx_col *c = &r->cols[k];
        if ((c->role >= R_NX && c->role <= R_NZ && !r->has_nrm) || (c->role >= R_R && c->role <= R_B && !r->has_rgb))
            c->role = R_EXTRA;
        if (c->role == R_EXTRA) c->extra = r->nextra++;
    }
    return PNPR_OK;
}

static pnpr_status tx_columns_from_names(tx_rd *r, const char *const *names, size_t n, long line)
{
    pnpr_status s = PNPR_OK;
    for (size_t k = 0; k < n && s == PNPR_OK; k++) {
        pnpr_token t = {names[k], strlen(names[k])};
        s = tx_add_col(r, t, line);
    }
    return s == PNPR_OK ? tx_finish_cols(r, line) : s;
}

/* opts->columns: comma-separated names. */
static pnpr_status tx_columns_option(tx_rd *r, const char *spec)
{
    r->from_option = 1;
    const char *p = spec, *e = spec + strlen(spec);
    while (p <= e) {
        const char *q = memchr(p, ',', (size_t)(e - p));
        if (!q) q = e;
        pnpr_token t = {p, (size_t)(q - p)};
        if (r->ncols == TX_MAX_COLS) return tx_fail(r, PNPR_ERR_INVALID_ARGUMENT, 0, "--columns: more than %d names", TX_MAX_COLS);
        if (tx_add_col(r, t, 0) != PNPR_OK) return PNPR_ERR_INVALID_ARGUMENT;
        p = q + 1;
    }
    return tx_finish_cols(r, 0) == PNPR_OK ? PNPR_OK : PNPR_ERR_INVALID_ARGUMENT;
}

/* The defaults of the format for n values (see the top of the file). */
static pnpr_status tx_columns_default(tx_rd *r, size_t n)
{
    static const char *const pts4[] = {"x", "y", "z", PNPR_PROP_INTENSITY}, *const pts6[] = {"x", "y", "z", "r", "g", "b"},
                             *const pts7[] = {"x", "y", "z", PNPR_PROP_INTENSITY, "r", "g", "b"},
                             *const n6[] = {"x", "y", "z", "nx", "ny", "nz"};
    if (n < 3)
        return tx_fail(r, PNPR_ERR_FORMAT, r->line, "%zu value%s on the first data line: a point needs x y z", n,
                       n == 1 ? "" : "s");
    if (r->fmt == PNPR_FORMAT_PTS && (n == 4 || n == 6 || n == 7))
        return tx_columns_from_names(r, n == 4 ? pts4 : n == 6 ? pts6 : pts7, n, r->line);
    const size_t named = n >= 6 ? 6 : 3;
    r->guess_rgb = named == 6 && r->fmt != PNPR_FORMAT_PWN; /* PWN: normals by definition */
    pnpr_status s = PNPR_OK;
    for (size_t k = 0; k < n && s == PNPR_OK; k++) {
        char name[32];
        snprintf(name, sizeof name, "scalar_%zu", k + 1);
        pnpr_token t = {k < named ? n6[k] : name, strlen(k < named ? n6[k] : name)};
        s = tx_add_col(r, t, r->line);
    }
    return s == PNPR_OK ? tx_finish_cols(r, r->line) : s;
}

static pnpr_status tx_header(tx_rd *r)
{
    pnpr_token *t = &r->tok[0];
    if (t->n >= 2 && t->s[0] == '/' && t->s[1] == '/') t->s += 2, t->n -= 2; /* CloudCompare's "//X,Y,Z" */
    size_t first = t->n ? 0 : 1;
    pnpr_status s = PNPR_OK;
    for (size_t k = first; k < r->ntok && s == PNPR_OK; k++) s = tx_add_col(r, r->tok[k], r->line);
    return s == PNPR_OK ? tx_finish_cols(r, r->line) : s;
}

/* ------------------------------------------------------------------------------------------ */
/* Points                                                                                      */

static int tx_grow_one(void **p, size_t cap, size_t size)
{
    void *g = realloc(*p, cap * size);
    if (!g) return 0;
    *p = g;
    return 1;
}

static pnpr_status tx_grow(tx_rd *r)
{
    size_t cap = r->cap ? 2 * r->cap : 1024;
    int ok = cap < SIZE_MAX / (3 * sizeof(double)) && tx_grow_one((void **)&r->xyz, cap, 3 * sizeof(double));
    if (ok && r->has_nrm) ok = tx_grow_one((void **)&r->nrm, cap, 3 * sizeof(float));
    if (ok && r->has_rgb) ok = tx_grow_one((void **)&r->col, cap, 3 * sizeof(float));
    if (ok && r->has_lab) ok = tx_grow_one((void **)&r->lab, cap, sizeof(uint32_t));
    for (size_t k = 0; ok && k < r->nextra; k++) ok = tx_grow_one((void **)&r->extra[k], cap, sizeof(double));
    if (!ok) return tx_fail(r, PNPR_ERR_OUT_OF_MEMORY, r->line, "out of memory after %zu points", r->n);
    r->cap = cap;
    return PNPR_OK;
}

static pnpr_status tx_store(tx_rd *r, const tx_col *c, pnpr_token t, double v, int frac)
{
    const size_t i = r->n;
    switch (c->role) {
    case R_X: case R_Y: case R_Z: r->xyz[3 * i + (size_t)(c->role - R_X)] = v; break;
    case R_NX: case R_NY: case R_NZ:
        r->nrm[3 * i + (size_t)(c->role - R_NX)] = tx_d2f(v);
        r->not_bytes |= frac || !(v >= 0 && v <= 255);
        r->above_one |= v > 1;
        break;
    case R_R: case R_G: case R_B:
        if (!(v == v) || v < 0)
            return tx_fail(r, PNPR_ERR_FORMAT, r->line, "colour '%s' value '%.*s' is not a number >= 0", c->name, show(t), t.s);
        r->colour_fraction |= frac;
        if (!frac && v > 255 && !r->colour_big_line) r->colour_big_line = r->line;
        r->col[3 * i + (size_t)(c->role - R_R)] = (float)(v > 1e6 ? 1e6 : v);
        break;
    case R_LABEL:
        if (frac || !(v >= 0 && v <= UINT32_MAX))
            return tx_fail(r, PNPR_ERR_FORMAT, r->line, "label '%.*s' is not an integer 0..2^32-1", show(t), t.s);
        r->lab[i] = (uint32_t)v;
        break;
    case R_EXTRA: r->extra[c->extra][i] = v; break;
    default: break;
    }
    return PNPR_OK;
}

static pnpr_status tx_point(tx_rd *r)
{
    if (r->ntok != r->ncols)
        return tx_fail(r, PNPR_ERR_FORMAT, r->line, "%zu values, the columns give %zu", r->ntok, r->ncols);
    pnpr_status s = r->n == r->cap ? tx_grow(r) : PNPR_OK;
    for (size_t k = 0; k < r->ncols && s == PNPR_OK; k++) {
        double v;
        int frac;
        if (!tx_value(r->tok[k], &v, &frac))
            return tx_fail(r, PNPR_ERR_FORMAT, r->line, "point %zu, column %zu (%s): '%.*s' is not a number", r->n, k + 1,
                           r->cols[k].name, show(r->tok[k]), r->tok[k].s);
        s = tx_store(r, &r->cols[k], r->tok[k], v, frac);
    }
    if (s == PNPR_OK && ++r->n % TX_CHUNK == 0 &&
        pnpr_progress_report(r->progress, "read text", 0.9 * (double)r->pos / (double)(r->size ? r->size : 1)))
        s = tx_fail(r, PNPR_ERR_CANCELLED, r->line, "cancelled after %zu points", r->n);
    return s;
}

/* The points since the last count line must be as many as it announced. */
static pnpr_status tx_close_section(tx_rd *r)
{
    if (!r->section_line) return PNPR_OK;
    const uint64_t got = r->n - r->section_start;
    if (got == r->section_count) return PNPR_OK;
    return tx_fail(r, got < r->section_count ? PNPR_ERR_TRUNCATED : PNPR_ERR_FORMAT, r->section_line,
                   "the count line announces %llu points, %llu follow", (unsigned long long)r->section_count,
                   (unsigned long long)got);
}

/* A line of one value: a count line when it is a non-negative integer. */
static pnpr_status tx_count_line(tx_rd *r)
{
    pnpr_token t = r->tok[0];
    uint64_t v = 0;
    for (size_t k = 0; k < t.n; k++) {
        unsigned dg = (unsigned)(unsigned char)t.s[k] - '0';
        if (dg > 9 || v > (UINT64_MAX - dg) / 10)
            return tx_fail(r, PNPR_ERR_FORMAT, r->line, "'%.*s' alone on a line is neither a point nor a point count",
                           show(t), t.s);
        v = v * 10 + dg;
    }
    pnpr_status s = tx_close_section(r);
    r->section_count = v;
    r->section_line = r->line;
    r->section_start = r->n;
    return s;
}

static pnpr_status tx_line(tx_rd *r)
{
    if (r->ntok == 1) return tx_count_line(r);
    if (!r->ncols) {
        if (!tx_all_numbers(r)) {
            r->header_seen = 1;
            return tx_header(r);
        }
        pnpr_status s = tx_columns_default(r, r->ntok);
        if (s != PNPR_OK) return s;
    } else if (r->from_option && !r->header_seen && r->n == 0 && !tx_all_numbers(r)) {
        r->header_seen = 1; /* the file's header row, overridden by --columns */
        return PNPR_OK;
    }
    return tx_point(r);
}

static pnpr_status tx_lines(tx_rd *r)
{
    pnpr_status s = PNPR_OK;
    while (s == PNPR_OK && r->pos < r->size) {
        const char *ls = r->d + r->pos, *nl = memchr(ls, '\n', r->size - r->pos), *le = nl ? nl : r->d + r->size;
        r->pos = (size_t)(le - r->d) + (nl ? 1 : 0);
        s = tx_split(r, ls, le);
        if (s == PNPR_OK && r->ntok) s = tx_line(r);
        if (s == PNPR_OK) r->line++;
    }
    return s == PNPR_OK ? tx_close_section(r) : s;
}

/* ------------------------------------------------------------------------------------------ */
/* The cloud                                                                                   */

static pnpr_status tx_colours(tx_rd *r, pnpr_cloud *c)
{
    if (!r->colour_fraction && r->colour_big_line)
        return tx_fail(r, PNPR_ERR_FORMAT, r->colour_big_line,
                       "integer colour values are bytes 0..255 (write floats 0..1 with a '.')");
    pnpr_status s = pnpr_cloud_alloc_rgb(c);
    if (s != PNPR_OK) return tx_fail(r, s, 0, "out of memory for the colours");
    for (size_t i = 0; i < 3 * c->count; i++) {
        float v = r->col[i];
        if (r->colour_fraction) v = !(v > 0.0f) ? 0.0f : v >= 1.0f ? 255.0f : v * 255.0f + 0.5f;
        c->rgb[i] = (uint8_t)v;
    }
    return PNPR_OK;
}

/* Default columns 4-6 that hold only bytes, some above 1, are colours (x y z r g b, as
 * CloudCompare writes them), not normals. */
static pnpr_status tx_normals_or_colours(tx_rd *r, pnpr_cloud *c)
{
    if (!r->guess_rgb || r->not_bytes || !r->above_one || !r->n) {
        if (r->has_nrm) c->normal = r->nrm, r->nrm = NULL;
        return PNPR_OK;
    }
    pnpr_status s = pnpr_cloud_alloc_rgb(c);
    if (s != PNPR_OK) return tx_fail(r, s, 0, "out of memory for the colours");
    for (size_t i = 0; i < 3 * c->count; i++) c->rgb[i] = (uint8_t)r->nrm[i];
    return PNPR_OK;
}

static pnpr_status tx_extras(tx_rd *r, pnpr_cloud *c)
{
    for (size_t k = 0; k < r->ncols; k++) {
        const tx_col *col = &r->cols[k];
        if (col->role != R_EXTRA) continue;
        pnpr_property *p;
        pnpr_status s = pnpr_cloud_add_property(c, col->name, PNPR_TYPE_FLOAT64, &p);
        if (s != PNPR_OK) return tx_fail(r, s, 0, "cannot allocate property '%s'", col->name);
        if (c->count) memcpy(p->data, r->extra[col->extra], c->count * sizeof(double));
    }
    return PNPR_OK;
}

static pnpr_status tx_cloud(tx_rd *r, pnpr_cloud *c)
{
    pnpr_status s = pnpr_cloud_alloc(c, r->n);
    if (s != PNPR_OK) return tx_fail(r, s, 0, "cannot allocate %zu points", r->n);
    double *shrunk = r->n ? realloc(r->xyz, r->n * 3 * sizeof(double)) : NULL;
    if (shrunk) r->xyz = shrunk;
    c->src_xyz = r->xyz ? r->xyz : calloc(1, sizeof(double));
    r->xyz = NULL;
    c->src_coord_type = PNPR_TYPE_FLOAT64;
    if (r->has_lab) c->label = r->lab, r->lab = NULL;
    if (!c->src_xyz || (r->n && r->has_lab && !c->label)) return tx_fail(r, PNPR_ERR_OUT_OF_MEMORY, 0, "out of memory");
    if ((s = tx_normals_or_colours(r, c)) != PNPR_OK) return s;
    if (r->has_rgb && r->n && (s = tx_colours(r, c)) != PNPR_OK) return s;
    if ((s = tx_extras(r, c)) != PNPR_OK) return s;
    s = pnpr_cloud_set_world(c, c->src_xyz);
    return s == PNPR_OK ? s : tx_fail(r, s, 0, "cannot set the coordinates");
}

static void tx_free(tx_rd *r)
{
    free(r->xyz);
    free(r->nrm);
    free(r->col);
    free(r->lab);
    for (size_t k = 0; k < r->nextra; k++) free(r->extra[k]);
}

pnpr_status pnpr_read_text_memory(const void *data, size_t size, const pnpr_read_options *opts, pnpr_cloud *cloud,
                                  pnpr_error *err)
{
    if (err) { err->message[0] = '\0'; err->line = 0; err->offset = -1; }
    if (!cloud || (!data && size)) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "read text: NULL cloud or data");
    pnpr_cloud_free(cloud);
    if (pnpr_io_no_filter(opts, err, "read text") != PNPR_OK) return PNPR_ERR_UNSUPPORTED;
    tx_rd *r = calloc(1, sizeof *r);
    if (!r) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "read text: out of memory");
    r->d = data ? data : "";
    r->size = size;
    r->line = 1;
    r->fmt = opts ? opts->format : PNPR_FORMAT_AUTO;
    r->err = err;
    r->progress = opts ? &opts->progress : NULL;
    pnpr_cloud c;
    memset(&c, 0, sizeof c);
    pnpr_status s = opts && opts->columns ? tx_columns_option(r, opts->columns) : PNPR_OK;
    if (s == PNPR_OK) s = tx_lines(r);
    if (s == PNPR_OK) s = tx_cloud(r, &c);
    if (s == PNPR_OK && pnpr_progress_report(r->progress, "read text", 1.0))
        s = tx_fail(r, PNPR_ERR_CANCELLED, 0, "cancelled");
    tx_free(r);
    free(r);
    if (s != PNPR_OK) {
        pnpr_cloud_free(&c);
        return s;
    }
    *cloud = c;
    return PNPR_OK;
}

pnpr_status pnpr_read_text_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud, pnpr_error *err)
{
    if (!path || !cloud) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "read text: NULL path or cloud");
    return pnpr_file_bytes_read(path, pnpr_read_text_memory, opts, cloud, err);
}
