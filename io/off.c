/* pointnpr — io/off.c: the OFF reader (ascii), plain C11.
 *
 * Why our own: OFF as real tools write it (Geomview's specification) has '#' comments anywhere
 * (before the keyword, between data lines, after a colour: "0 0 0.9 #blue"), counts on the
 * keyword's line, colours as floats or bytes with or without alpha, and face colours after the
 * corners of any OFF. OpenMesh 9 reads none of these (it does not skip comments, and it guesses
 * colour types per line from the first word); CGAL's own data folder has 10 such files. The
 * format is small, and a reader of ours checks every count against the bytes present. Binary
 * OFF ("OFF BINARY") still goes through OpenMesh (io/mesh_openmesh.cpp, behind io/mesh_check.c).
 *
 *  - Keyword: the first word that is not in a comment, [ST][C][N]OFF; 4OFF / nOFF (other than 3
 *    dimensions) are PNPR_ERR_UNSUPPORTED. "BINARY" right after it: binary OFF (see above).
 *  - Counts: the next three words (vertices, faces, edges; the edge count is not used), on the
 *    keyword's line or later ones, non-negative integers below 2^32. Before anything is
 *    allocated they are checked against the bytes after them (a vertex takes 6 bytes or more,
 *    12 with normals, a face 2): PNPR_ERR_TRUNCATED.
 *  - Words are separated by white space; '#' starts a comment up to the end of its line (also
 *    inside a word: "0#red"). Bytes 0x00-0x08, 0x0E-0x1F and 0x7F are binary data: an error.
 *  - Numbers: [+-]digits[.digits][(e|E)[+-]digits], finite as doubles, read in the "C" form
 *    (no nan, inf, hex or "1,5": PNPR_ERR_FORMAT with the line and vertex).
 *  - A vertex: x y z (exact doubles: src_xyz, FLOAT64), then nx ny nz for N files (normalised,
 *    (0,0,0) when of length 0), words that may span lines. For C files the rest of its line is
 *    the colour: 3 or 4 numbers (alpha dropped; ST files: 2 more words, the texture coordinates,
 *    come last and are dropped); no word or 1 (a colour-map index) is no colour. The whole file's
 *    colours are floats in [0, 1] (x 255, rounded, clamped) when any colour value is written with
 *    a '.' or an exponent, else bytes 0..255 (larger: PNPR_ERR_FORMAT). Other files: the rest of a
 *    vertex's line is ignored.
 *  - A face: a corner count k and k vertex indices below the vertex count; the rest of its line
 *    (a face colour, in any OFF) is ignored. Faces of fewer than 3 corners are dropped (as
 *    before, when OpenMesh read OFF). Text after the last face is ignored.
 *  - Errors: "FILE: line N: ..." (err->line = N). Progress stage "read off".
 */
#include <pointnpr/io.h>

#include "../core/internal.h"
#include "file_bytes.h"
#include "text_token.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

pnpr_status pnpr_read_off_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud, pnpr_error *err);

#define OFF_SHOW 40         /* longest word quoted in a message */
#define OFF_CHUNK 65536u    /* vertices between progress reports */
#define ULL(x) ((unsigned long long)(x))

#if defined(__GNUC__)
#define OFF_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define OFF_PRINTF(a, b)
#endif

typedef struct off_rd {
    const char *d;
    size_t size, pos;
    long line;
    const char *path;
    pnpr_error *err;
    const pnpr_progress *progress;
    int st, color, normal, binary; /* the keyword */
    uint64_t nv, nf;
    float *colour;     /* 3 per vertex, as written (C files) */
    uint8_t *has_colour;
    int colour_fraction; /* a colour value was written with '.' or an exponent */
    long colour_big_line; /* first line with an integer colour value above 255, 0 = none */
    uint32_t *index;   /* face corners */
    size_t index_n, index_cap;
} off_rd;

static pnpr_status OFF_PRINTF(4, 5) off_fail(off_rd *r, pnpr_status st, long line, const char *fmt, ...)
{
    pnpr_error *err = r->err;
    if (!err) return st;
    int n = snprintf(err->message, sizeof err->message, "line %ld: ", line);
    if (n < 0 || (size_t)n >= sizeof err->message) n = 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message + n, sizeof err->message - (size_t)n, fmt, ap);
    va_end(ap);
    pnpr_error_prefix_path(err, r->path);
    err->line = line;
    err->offset = -1;
    return st;
}

static int off_space(unsigned char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }
static int off_binary_byte(unsigned char c) { return (c < 0x20 && !off_space(c)) || c == 0x7f; }
static int show(pnpr_token t) { return (int)(t.n > OFF_SHOW ? OFF_SHOW : t.n); }

static pnpr_status off_not_text(off_rd *r, size_t at)
{
    return off_fail(r, PNPR_ERR_FORMAT, r->line, "byte 0x%02x (offset %zu) is not text: binary data, not an ascii OFF file",
                    (unsigned char)r->d[at], at);
}

/* Skips a comment up to (not including) its newline. */
static pnpr_status skip_comment(off_rd *r)
{
    for (; r->pos < r->size && r->d[r->pos] != '\n'; r->pos++)
        if (off_binary_byte((unsigned char)r->d[r->pos])) return off_not_text(r, r->pos);
    return PNPR_OK;
}

/* The next word into *t (*found = 0 at the end of the file, or of the line when !cross_lines;
 * the newline is then not consumed). Comments are skipped. */
static pnpr_status next_word(off_rd *r, int cross_lines, pnpr_token *t, int *found)
{
    pnpr_status s = PNPR_OK;
    *found = 0;
    while (s == PNPR_OK && r->pos < r->size) {
        unsigned char c = (unsigned char)r->d[r->pos];
        if (c == '\n' && !cross_lines) return PNPR_OK;
        if (c == '#') s = skip_comment(r);
        else if (off_space(c)) r->line += c == '\n', r->pos++;
        else break;
    }
    if (s != PNPR_OK || r->pos >= r->size) return s;
    t->s = r->d + r->pos;
    for (; r->pos < r->size; r->pos++) {
        unsigned char c = (unsigned char)r->d[r->pos];
        if (off_space(c) || c == '#') break;
        if (off_binary_byte(c)) return off_not_text(r, r->pos);
    }
    t->n = (size_t)(r->d + r->pos - t->s);
    *found = 1;
    return PNPR_OK;
}

/* The words left on the current line (at most `cap` kept in w; *n counts them all); consumes the
 * line's newline. */
static pnpr_status rest_of_line(off_rd *r, pnpr_token *w, size_t cap, size_t *n)
{
    pnpr_token t;
    int found = 1;
    pnpr_status s = PNPR_OK;
    *n = 0;
    while (s == PNPR_OK && (s = next_word(r, 0, &t, &found)) == PNPR_OK && found) {
        if (*n < cap) w[*n] = t;
        ++*n;
    }
    if (s == PNPR_OK && r->pos < r->size) r->pos++, r->line++;
    return s;
}

/* ------------------------------------------------------------------------------------------ */
/* Header                                                                                      */

static pnpr_status off_keyword(off_rd *r)
{
    pnpr_token t;
    int found, other_dim = 0;
    pnpr_status s = next_word(r, 1, &t, &found);
    if (s != PNPR_OK) return s;
    size_t i = 0;
    const char *w = found ? t.s : "";
    const size_t n = found ? t.n : 0;
    if (n >= 2 && w[0] == 'S' && w[1] == 'T') i = 2;
    r->st = i == 2;
    if (i < n && w[i] == 'C') r->color = 1, i++;
    if (i < n && w[i] == 'N') r->normal = 1, i++;
    if (i < n && w[i] == '4') other_dim = 1, i++;
    if (i < n && w[i] == 'n') other_dim = 1, i++;
    if (n != i + 3 || memcmp(w + i, "OFF", 3) != 0)
        return off_fail(r, PNPR_ERR_FORMAT, found ? r->line : 1,
                        "no OFF keyword ([ST][C][N]OFF) at the start of the file%s", found ? "" : " (it is empty)");
    if (other_dim)
        return off_fail(r, PNPR_ERR_UNSUPPORTED, r->line, "%.*s: vertices of other than 3 dimensions are not supported",
                        show(t), t.s);
    const long line = r->line;
    size_t save = r->pos;
    if ((s = next_word(r, 0, &t, &found)) != PNPR_OK) return s;
    if (found && pnpr_token_is(t, "BINARY")) r->binary = 1;
    else r->pos = save, r->line = line;
    return PNPR_OK;
}

/* [+-]digits: sign and magnitude (saturated); 0 when t is no integer. */
static int off_int(pnpr_token t, int *neg, uint64_t *v)
{
    size_t i = t.n && (t.s[0] == '-' || t.s[0] == '+');
    *neg = i && t.s[0] == '-';
    *v = 0;
    if (i == t.n) return 0;
    for (; i < t.n; i++) {
        unsigned dg = (unsigned)(unsigned char)t.s[i] - '0';
        if (dg > 9) return 0;
        *v = *v > (UINT64_MAX - dg) / 10 ? UINT64_MAX : *v * 10 + dg;
    }
    return 1;
}

static pnpr_status off_count(off_rd *r, const char *what, uint64_t *v, long *line)
{
    pnpr_token t;
    int found, neg;
    pnpr_status s = next_word(r, 1, &t, &found);
    if (s != PNPR_OK) return s;
    if (!found) return off_fail(r, PNPR_ERR_TRUNCATED, r->line, "the file ends before the %s count", what);
    *line = r->line;
    if (!off_int(t, &neg, v))
        return off_fail(r, PNPR_ERR_FORMAT, *line, "the %s count '%.*s' is not an integer", what, show(t), t.s);
    if (neg && *v) return off_fail(r, PNPR_ERR_FORMAT, *line, "the %s count %.*s is negative", what, show(t), t.s);
    if (*v > UINT32_MAX)
        return off_fail(r, PNPR_ERR_FORMAT, *line, "the %s count %.*s is more than 2^32-1", what, show(t), t.s);
    return PNPR_OK;
}

static pnpr_status off_counts(off_rd *r)
{
    uint64_t ne;
    long line;
    pnpr_status s = off_count(r, "vertex", &r->nv, &line);
    if (s == PNPR_OK) s = off_count(r, "face", &r->nf, &line);
    if (s == PNPR_OK) s = off_count(r, "edge", &ne, &line);
    if (s != PNPR_OK) return s;
    const uint64_t per_vertex = r->normal ? 12 : 6, left = r->size - r->pos;
    if (r->nv * per_vertex + r->nf * 2 > left)
        return off_fail(r, PNPR_ERR_TRUNCATED, line,
                        "the header announces %llu vertices and %llu faces, more than the %llu bytes after it can "
                        "hold (a vertex takes %llu bytes or more, a face 2)",
                        ULL(r->nv), ULL(r->nf), ULL(left), ULL(per_vertex));
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* Vertices                                                                                    */

static pnpr_status off_numbers(off_rd *r, double *out, const char *what, uint64_t i)
{
    for (int a = 0; a < 3; a++) {
        pnpr_token t;
        int found;
        pnpr_status s = next_word(r, 1, &t, &found);
        if (s != PNPR_OK) return s;
        if (!found)
            return off_fail(r, PNPR_ERR_TRUNCATED, r->line, "the file ends after %llu of the %llu vertices its header announces",
                            ULL(i), ULL(r->nv));
        if (!pnpr_token_decimal(t, &out[a], NULL))
            return off_fail(r, PNPR_ERR_FORMAT, r->line, "vertex %llu: %s '%.*s' is not a number (finite, decimal)",
                            ULL(i), what, show(t), t.s);
    }
    return PNPR_OK;
}

/* The rest of a C file's vertex line: the colour (see the top of the file). */
static pnpr_status off_colour(off_rd *r, uint64_t i)
{
    pnpr_token w[8];
    size_t n;
    const long line = r->line;
    pnpr_status s = rest_of_line(r, w, 8, &n);
    if (s != PNPR_OK) return s;
    if (r->st && n >= 2) n -= 2;
    if (n <= 1) return PNPR_OK;
    if (n != 3 && n != 4)
        return off_fail(r, PNPR_ERR_FORMAT, line, "vertex %llu: %zu colour values (expected 3 or 4, or none)", ULL(i), n);
    for (size_t k = 0; k < 3; k++) {
        double v;
        int frac;
        if (!pnpr_token_decimal(w[k], &v, &frac))
            return off_fail(r, PNPR_ERR_FORMAT, line, "vertex %llu: colour value %zu '%.*s' is not a number", ULL(i), k + 1,
                            show(w[k]), w[k].s);
        r->colour_fraction |= frac;
        if (!frac && (v > 255 || v < 0) && !r->colour_big_line) r->colour_big_line = line;
        r->colour[3 * i + k] = (float)(v > 1e6 ? 1e6 : v < -1e6 ? -1e6 : v); /* clamped below anyway */
    }
    r->has_colour[i] = 1;
    return PNPR_OK;
}

static void store_normal(float *dst, const double n[3])
{
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int a = 0; a < 3; a++) dst[a] = len > 0 && isfinite(len) ? (float)(n[a] / len) : 0.0f;
}

static pnpr_status off_vertices(off_rd *r, pnpr_cloud *c)
{
    pnpr_status s = PNPR_OK;
    size_t n;
    pnpr_token unused[1];
    for (uint64_t i = 0; i < r->nv && s == PNPR_OK; i++) {
        if (i % OFF_CHUNK == 0 && pnpr_progress_report(r->progress, "read off", 0.9 * (double)i / (double)r->nv))
            return off_fail(r, PNPR_ERR_CANCELLED, r->line, "cancelled at vertex %llu", ULL(i));
        double nrm[3];
        s = off_numbers(r, c->src_xyz + 3 * i, "coordinate", i);
        if (s == PNPR_OK && r->normal && (s = off_numbers(r, nrm, "normal component", i)) == PNPR_OK)
            store_normal(c->normal + 3 * i, nrm);
        if (s == PNPR_OK) s = r->color ? off_colour(r, i) : rest_of_line(r, unused, 0, &n);
    }
    return s;
}

/* Colours into bytes, once the whole file has told whether they are floats or bytes. */
static pnpr_status off_colours_to_bytes(off_rd *r, pnpr_cloud *c)
{
    if (!r->colour_fraction && r->colour_big_line)
        return off_fail(r, PNPR_ERR_FORMAT, r->colour_big_line,
                        "integer colour values are bytes 0..255 (write floats 0..1 with a '.')");
    for (size_t i = 0; i < 3 * c->count; i++) {
        float v = r->colour[i];
        if (r->colour_fraction) v = !(v > 0.0f) ? 0.0f : v >= 1.0f ? 255.0f : v * 255.0f + 0.5f;
        c->rgb[i] = (uint8_t)v;
    }
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* Faces                                                                                       */

static pnpr_status index_push(off_rd *r, uint32_t v)
{
    if (r->index_n == r->index_cap) {
        size_t cap = r->index_cap ? 2 * r->index_cap : 1024;
        uint32_t *g = cap < SIZE_MAX / sizeof *g ? realloc(r->index, cap * sizeof *g) : NULL;
        if (!g) return off_fail(r, PNPR_ERR_OUT_OF_MEMORY, r->line, "out of memory for the face corners");
        r->index = g;
        r->index_cap = cap;
    }
    r->index[r->index_n++] = v;
    return PNPR_OK;
}

static pnpr_status off_corner_count(off_rd *r, uint64_t f, uint64_t *k)
{
    pnpr_token t;
    int found;
    int neg;
    pnpr_status s = next_word(r, 1, &t, &found);
    if (s != PNPR_OK) return s;
    if (!found)
        return off_fail(r, PNPR_ERR_TRUNCATED, r->line, "the file ends after %llu of the %llu faces its header announces",
                        ULL(f), ULL(r->nf));
    if (!off_int(t, &neg, k) || (neg && *k) || *k > UINT32_MAX)
        return off_fail(r, PNPR_ERR_FORMAT, r->line, "face %llu: corner count '%.*s' is not an integer 0..2^32-1", ULL(f),
                        show(t), t.s);
    if (*k > (r->size - r->pos) / 2)
        return off_fail(r, PNPR_ERR_TRUNCATED, r->line, "face %llu announces %llu corners, more than the %llu bytes left can hold",
                        ULL(f), ULL(*k), ULL(r->size - r->pos));
    return PNPR_OK;
}

static pnpr_status off_face(off_rd *r, uint64_t f, uint32_t *offset)
{
    uint64_t k = 0;
    pnpr_status s = off_corner_count(r, f, &k);
    const size_t start = r->index_n;
    for (uint64_t j = 0; s == PNPR_OK && j < k; j++) {
        pnpr_token t;
        int found, neg;
        uint64_t v;
        if ((s = next_word(r, 1, &t, &found)) != PNPR_OK) return s;
        if (!found) return off_fail(r, PNPR_ERR_TRUNCATED, r->line, "the file ends inside face %llu", ULL(f));
        if (!off_int(t, &neg, &v) || (neg && v) || v >= r->nv)
            return off_fail(r, PNPR_ERR_FORMAT, r->line,
                            "face %llu, corner %llu: vertex index '%.*s' is out of range (the file has %llu vertices)",
                            ULL(f), ULL(j), show(t), t.s, ULL(r->nv));
        s = index_push(r, (uint32_t)v);
    }
    size_t n;
    pnpr_token unused[1];
    if (s == PNPR_OK) s = rest_of_line(r, unused, 0, &n); /* a face colour, ignored */
    if (s == PNPR_OK && k < 3) r->index_n = start;         /* fewer than 3 corners: dropped */
    if (s == PNPR_OK && r->index_n > UINT32_MAX)
        return off_fail(r, PNPR_ERR_UNSUPPORTED, r->line, "more than 2^32-1 face corners in all");
    if (s == PNPR_OK && r->index_n > start) offset[0]++, offset[offset[0]] = (uint32_t)r->index_n;
    return s;
}

/* offset[0] counts the faces kept while reading; offsets follow from offset[1]. */
static pnpr_status off_faces(off_rd *r, pnpr_cloud *c)
{
    if (!r->nf) return PNPR_OK;
    uint32_t *offset = malloc((size_t)(r->nf + 1) * sizeof *offset);
    if (!offset) return off_fail(r, PNPR_ERR_OUT_OF_MEMORY, r->line, "out of memory for %llu faces", ULL(r->nf));
    offset[0] = 0;
    pnpr_status s = PNPR_OK;
    for (uint64_t f = 0; f < r->nf && s == PNPR_OK; f++) s = off_face(r, f, offset);
    if (s != PNPR_OK || offset[0] == 0) {
        free(offset);
        return s;
    }
    c->faces.count = offset[0];
    offset[0] = 0;
    c->faces.offset = offset;
    c->faces.index = r->index;
    r->index = NULL;
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */

static pnpr_status off_prepare(off_rd *r, pnpr_cloud *c)
{
    pnpr_status s = pnpr_cloud_alloc(c, (size_t)r->nv);
    if (s == PNPR_OK) s = pnpr_cloud_alloc_src_xyz(c);
    if (s == PNPR_OK && r->normal) s = pnpr_cloud_alloc_normals(c);
    if (s == PNPR_OK && r->color) {
        r->colour = calloc((size_t)r->nv * 3 + 1, sizeof *r->colour);
        r->has_colour = calloc((size_t)r->nv + 1, 1);
        if (!r->colour || !r->has_colour) s = PNPR_ERR_OUT_OF_MEMORY;
    }
    return s == PNPR_OK ? s : off_fail(r, s, r->line, "cannot allocate %llu vertices", ULL(r->nv));
}

static pnpr_status off_finish(off_rd *r, pnpr_cloud *c)
{
    int any = 0;
    for (size_t i = 0; r->has_colour && i < c->count && !any; i++) any = r->has_colour[i];
    pnpr_status s = any ? pnpr_cloud_alloc_rgb(c) : PNPR_OK;
    if (s == PNPR_OK && any) s = off_colours_to_bytes(r, c);
    if (s != PNPR_OK) return s;
    c->src_coord_type = PNPR_TYPE_FLOAT64;
    s = pnpr_cloud_set_world(c, c->src_xyz);
    if (s != PNPR_OK) return off_fail(r, s, r->line, "cannot set the coordinates");
    return pnpr_progress_report(r->progress, "read off", 1.0) ? off_fail(r, PNPR_ERR_CANCELLED, r->line, "cancelled")
                                                              : PNPR_OK;
}

static pnpr_status off_read(off_rd *r, pnpr_cloud *c)
{
    pnpr_status s = off_counts(r);
    if (s == PNPR_OK) s = off_prepare(r, c);
    if (s == PNPR_OK) s = off_vertices(r, c);
    if (s == PNPR_OK) s = off_faces(r, c);
    if (s == PNPR_OK) s = off_finish(r, c);
    return s;
}

pnpr_status pnpr_read_off_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud, pnpr_error *err)
{
    if (err) { err->message[0] = '\0'; err->line = 0; err->offset = -1; }
    if (!path || !cloud) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "read off: NULL path or cloud");
    pnpr_cloud_free(cloud);
    pnpr_file_bytes fb;
    pnpr_status s = pnpr_file_bytes_open(path, &fb, err);
    if (s != PNPR_OK) return s;
    off_rd r;
    memset(&r, 0, sizeof r);
    r.d = (const char *)fb.data;
    r.size = fb.size;
    r.line = 1;
    r.path = path;
    r.err = err;
    r.progress = opts ? &opts->progress : NULL;
    pnpr_cloud c;
    memset(&c, 0, sizeof c);
    s = off_keyword(&r);
    if (s == PNPR_OK && !r.binary) s = off_read(&r, &c);
    pnpr_file_bytes_close(&fb);
    free(r.colour);
    free(r.has_colour);
    free(r.index);
    if (s == PNPR_OK && r.binary) return pnpr_read_mesh_file(path, opts, cloud, err); /* OpenMesh */
    if (s != PNPR_OK) {
        pnpr_cloud_free(&c);
        return s;
    }
    *cloud = c;
    return PNPR_OK;
}
