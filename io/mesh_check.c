/* pointnpr — io/mesh_check.c: the validating pre-pass of the OBJ/OFF reader (mesh_check.h).
 * pnpr_read_file reads ascii OFF with io/off.c; this pass guards OBJ, binary OFF, and ascii OFF
 * handed to pnpr_read_mesh_file directly (which keeps OpenMesh's OFF rules: no comments).
 *
 * OpenMesh 9 trusts the files it reads: an OFF header's counts drive its loops and its reserve()
 * (a 20-byte file asks for 137 GB, "3 -1 0" loops over 2^32 faces), a number that does not parse
 * leaves its stream failed (every later value is stale), an OBJ vertex that does not parse is
 * dropped (later faces then name the wrong vertices), a face corner without a vertex index makes
 * it write out of bounds. This pass walks the file once before OpenMesh does, streaming (a 16 KB
 * buffer), tokenising it the way OpenMesh's readers do, and fails with the file, the line and the
 * value at the first thing OpenMesh would get wrong. Nothing it checks is allocated.
 *
 * Text (OFF ascii, OBJ)
 *  - Bytes 0x00-0x08, 0x0E-0x1F and 0x7F are binary data: PNPR_ERR_FORMAT (random bytes are not
 *    an empty cloud). Bytes >= 0x80 (UTF-8 names and comments) are text.
 *  - Numbers are whole words of the form [+-]digits[.digits][(e|E)[+-]digits] (what C++ streams
 *    read; no nan, inf, hex, or trailing text as in "1,5"), at most 256 characters, inside
 *    float's range (OpenMesh reads floats: 1e39 fails its stream; underflow to 0 is accepted).
 *    Each vertex's exact doubles go to the callback, read in the "C" form whatever LC_NUMERIC
 *    says. Integers are [+-]digits within the range of the C++ type OpenMesh reads them into.
 *
 * OFF: line 1 starts with [ST][C][N]OFF, optionally " BINARY" (exactly one blank before it, as
 *   OpenMesh tests), then only blanks or a '#' comment; 4OFF / nOFF: PNPR_ERR_UNSUPPORTED.
 *   Ascii: the vertex, face and edge counts are the next three words (blank lines allowed; no
 *   comments, which OpenMesh does not skip), non-negative integers below 2^32, and the bytes after
 *   them must be able to hold what they announce (every word needs a character and a separator:
 *   a vertex 6 bytes, 12 with normals, a face of k corners 2(k+1)), else PNPR_ERR_TRUNCATED
 *   before anything else is read. More than 2^31-1 vertices: PNPR_ERR_UNSUPPORTED. A vertex is 3
 *   coordinates (3 more numbers for N), words that may span lines as in OpenMesh, then the rest of
 *   the line. For C files that rest must be what OpenMesh's colour classifier takes without
 *   complaint: nothing, 1 or 2 words (ignored), 3/4 integers (RGB/RGBA) or 3/4 numbers when the
 *   first has a '.' (words counted by single spaces, as OpenMesh counts them; ST files: 2 more
 *   words, the texture coordinates). A face is a corner count k (checked against the bytes left)
 *   and k vertex indices below the vertex count (out of range: PNPR_ERR_FORMAT), then for C files
 *   a colour as above. Text after the last face is ignored.
 *   Binary: the rest of line 1 is the header; then little-endian uint32 counts; vertices of 12
 *   bytes (+12 with N, +12 with C: three int32, +8 with ST); faces of a uint32 k and k uint32
 *   indices (face colours are read by OpenMesh only on request, and not requested). The counts
 *   are checked against the file size, then each face's k and indices. Float values are not
 *   checked (a NaN coordinate stays NaN, as in the PLY and PCD readers).
 * OBJ: lines as OpenMesh sees them (" \t\r" trimmed; empty lines, '#' lines and lines starting
 *   with \v or \f skipped); the statement keyword is the first word.
 *   v   3 numbers (later words are OpenMesh's business: a colour that does not parse is not
 *       used). A vertex that does not parse is an error, not a dropped vertex, so that face
 *       indices always name the vertices the file means.
 *   vn  3 numbers; vt 2 numbers (OpenMesh fails the whole file otherwise).
 *   f   corners v, v/vt, v//vn or v/vt/vn; every index a non-zero int; negative ones count back
 *       from the statements of their kind read so far and must not reach before the first;
 *       positive ones must not exceed the file's total (checked at the end). At most 65536
 *       corners a face and 2^32 corners^2 over all faces (OpenMesh removes repeated corners
 *       pairwise): PNPR_ERR_UNSUPPORTED beyond.
 *   mtllib  OpenMesh opens the named file next to the OBJ: a name that exists and is neither a
 *       regular file nor a folder (a FIFO, a device such as /dev/zero) is refused with
 *       PNPR_ERR_UNSUPPORTED, before OpenMesh could block on it or read it without end.
 *   Other statements (o, g, s, usemtl, l, p, curves ...) and unknown keywords are skipped, as
 *   OpenMesh skips them, but the file must hold at least one statement of the OBJ specification.
 *   More than 2^31-1 vertices: PNPR_ERR_UNSUPPORTED.
 */
#include "mesh_check.h"

#include "../core/internal.h"

#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MC_BUF 16384      /* read buffer */
#define MC_TOKEN_MAX 256  /* longest word kept (longer words are no number) */
#define MC_LINE_MAX 4096  /* OFF line 1, OFF colour parts, mtllib names */
#define MC_SHOW 40        /* longest word quoted in a message */
#define ULL(x) ((unsigned long long)(x))

#if defined(__GNUC__)
#define MC_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define MC_PRINTF(a, b)
#endif

typedef struct mc_in {
    FILE *f;
    unsigned char buf[MC_BUF];
    size_t pos, len;
    uint64_t off;  /* file offset of buf[pos] */
    uint64_t size; /* file size */
    long line;     /* line of buf[pos], from 1 */
    int failed;    /* read error */
} mc_in;

typedef struct mc_tok {
    char s[MC_TOKEN_MAX + 1];
    size_t n;
    long line;
    int too_long;
} mc_tok;

typedef struct mc_ctx {
    mc_in in;
    const char *path;
    pnpr_mesh_check *mc;
    pnpr_error *err;
    char dp; /* the locale's decimal point */
} mc_ctx;

/* ------------------------------------------------------------------------------------------ */
/* Errors, input, words                                                                        */

static pnpr_status MC_PRINTF(5, 6)
mc_fail(mc_ctx *m, pnpr_status st, long line, long long offset, const char *fmt, ...)
{
    pnpr_error *err = m->err;
    if (!err) return st;
    int n = line > 0 ? snprintf(err->message, sizeof err->message, "line %ld: ", line)
                     : snprintf(err->message, sizeof err->message, "byte %lld: ", offset);
    if (n < 0 || (size_t)n >= sizeof err->message) n = 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message + n, sizeof err->message - (size_t)n, fmt, ap);
    va_end(ap);
    pnpr_error_prefix_path(err, m->path);
    err->line = line > 0 ? line : 0;
    err->offset = offset;
    return st;
}

static int in_peek(mc_in *in)
{
    if (in->pos == in->len) {
        in->pos = 0;
        in->len = fread(in->buf, 1, sizeof in->buf, in->f);
        if (in->len == 0) {
            if (ferror(in->f)) in->failed = 1;
            return -1;
        }
    }
    return in->buf[in->pos];
}

static int in_get(mc_in *in)
{
    int c = in_peek(in);
    if (c >= 0) {
        in->pos++;
        in->off++;
        if (c == '\n') in->line++;
    }
    return c;
}

static uint64_t in_left(const mc_in *in)
{
    return in->off < in->size ? in->size - in->off : 0;
}

/* Skips n bytes of binary data; 0 when the file ends first. */
static int in_skip(mc_in *in, uint64_t n)
{
    if (n <= in->len - in->pos) {
        in->pos += (size_t)n;
        in->off += n;
        return 1;
    }
    if (n > in_left(in)) return 0;
    uint64_t target = in->off + n;
    if (fseeko(in->f, (off_t)target, SEEK_SET) != 0) {
        in->failed = 1;
        return 0;
    }
    in->off = target;
    in->pos = in->len = 0;
    return 1;
}

static int mc_space(int c) { return c == ' ' || (c >= '\t' && c <= '\r'); } /* C isspace */
static int mc_blank(int c) { return mc_space(c) && c != '\n'; }
static int mc_binary(int c) { return (c < 0x20 && !mc_space(c)) || c == 0x7f; }
static int mc_digit(int c) { return c >= '0' && c <= '9'; }

static pnpr_status text_binary(mc_ctx *m, int c, uint64_t offset)
{
    return mc_fail(m, PNPR_ERR_FORMAT, m->in.line, (long long)offset,
                   "byte 0x%02x (offset %llu) is not text: binary data, not an %s file", c, ULL(offset),
                   m->mc->format == PNPR_FORMAT_OBJ ? "OBJ" : "ascii OFF");
}

/* Skips blanks (newlines too when cross_lines), then reads one word into t. *found = 0 at the end
 * of the file, or of the line when !cross_lines (the newline is not consumed). */
static pnpr_status next_token(mc_ctx *m, int cross_lines, mc_tok *t, int *found)
{
    int c;
    while ((c = in_peek(&m->in)) >= 0 && (cross_lines ? mc_space(c) : mc_blank(c))) in_get(&m->in);
    *found = 0;
    if (c < 0 || c == '\n') return PNPR_OK;
    t->n = 0;
    t->line = m->in.line;
    t->too_long = 0;
    for (; c >= 0 && !mc_space(c); c = in_peek(&m->in)) {
        if (mc_binary(c)) return text_binary(m, c, m->in.off);
        if (t->n < MC_TOKEN_MAX) t->s[t->n++] = (char)c;
        else t->too_long = 1;
        in_get(&m->in);
    }
    t->s[t->n] = '\0';
    *found = 1;
    return PNPR_OK;
}

/* Consumes the rest of the line and its newline; keeps it in buf (NUL-terminated) when buf is
 * not NULL, where a longer line is an error. */
static pnpr_status rest_of_line(mc_ctx *m, char *buf, size_t cap)
{
    size_t n = 0;
    long line = m->in.line;
    int c;
    while ((c = in_get(&m->in)) >= 0 && c != '\n') {
        if (mc_binary(c)) return text_binary(m, c, m->in.off - 1);
        if (!buf) continue;
        if (n + 1 >= cap) return mc_fail(m, PNPR_ERR_FORMAT, line, -1, "line longer than %zu bytes", cap - 1);
        buf[n++] = (char)c;
    }
    if (buf) buf[n] = '\0';
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* Numbers                                                                                     */

/* [+-]digits[.digits][(e|E)[+-]digits] with at least one mantissa digit, and nothing else. */
static int mc_decimal(const char *p)
{
    int digits = 0;
    if (*p == '+' || *p == '-') p++;
    for (; mc_digit(*p); p++) digits++;
    if (*p == '.')
        for (p++; mc_digit(*p); p++) digits++;
    if (!digits) return 0;
    if (*p == 'e' || *p == 'E') {
        p++;
        if (*p == '+' || *p == '-') p++;
        if (!mc_digit(*p)) return 0;
        while (mc_digit(*p)) p++;
    }
    return *p == '\0';
}

/* A word that C++ streams read whole as a float: its exact double in *out, the float OpenMesh
 * reads in *out_f (may be NULL). dp: the locale's decimal point, which strtod expects. */
static int mc_float(const mc_tok *t, char dp, double *out, float *out_f)
{
    if (t->too_long || !mc_decimal(t->s)) return 0;
    char buf[MC_TOKEN_MAX + 1];
    memcpy(buf, t->s, t->n + 1);
    char *dot = dp != '.' ? strchr(buf, '.') : NULL;
    if (dot) *dot = dp;
    float f = strtof(buf, NULL);
    if (isinf(f)) return 0; /* float overflow fails OpenMesh's stream */
    *out = strtod(buf, NULL);
    if (out_f) *out_f = f;
    return 1;
}

/* [+-]digits: sign and magnitude (saturated). 0 when s is no integer. */
static int mc_int(const char *s, size_t n, int *neg, uint64_t *mag)
{
    size_t i = 0;
    *neg = 0;
    *mag = 0;
    if (i < n && (s[i] == '+' || s[i] == '-')) *neg = s[i++] == '-';
    if (i == n) return 0;
    for (; i < n; i++) {
        if (!mc_digit(s[i])) return 0;
        unsigned d = (unsigned)(s[i] - '0');
        *mag = *mag > (UINT64_MAX - d) / 10 ? UINT64_MAX : *mag * 10 + d;
    }
    return 1;
}

/* A non-negative integer below 2^32 (what OpenMesh's unsigned int takes). */
static int mc_uint32(const mc_tok *t, uint64_t *v)
{
    int neg;
    if (t->too_long || !mc_int(t->s, t->n, &neg, v)) return 0;
    return (!neg || *v == 0) && *v <= UINT32_MAX;
}

/* An int (what OpenMesh's int takes). */
static int mc_int32(const char *s, size_t n)
{
    int neg;
    uint64_t mag;
    return mc_int(s, n, &neg, &mag) && mag <= (neg ? 2147483648u : 2147483647u);
}

/* ------------------------------------------------------------------------------------------ */
/* OFF                                                                                         */

typedef struct off_kind {
    int st, color, normal, binary;
} off_kind;

/* [ST][C][N][4][n]OFF at the start of line: the index after "OFF", 0 if absent. */
static size_t off_prefix(const char *line, off_kind *k, int *other_dim)
{
    size_t i = 0;
    if (line[i] == 'S' && line[i + 1] == 'T') { k->st = 1; i += 2; }
    if (line[i] == 'C') { k->color = 1; i++; }
    if (line[i] == 'N') { k->normal = 1; i++; }
    if (line[i] == '4') { *other_dim = 1; i++; }
    if (line[i] == 'n') { *other_dim = 1; i++; }
    return strncmp(line + i, "OFF", 3) == 0 ? i + 3 : 0;
}

/* Checks line[0..n) (line 1 without its newline, cut at MC_LINE_MAX - 1 when `cut`). */
static pnpr_status off_header(mc_ctx *m, const char *line, int cut, off_kind *k)
{
    int other_dim = 0;
    size_t i = off_prefix(line, k, &other_dim);
    if (!i)
        return mc_fail(m, PNPR_ERR_FORMAT, 1, -1, "no OFF keyword ([ST][C][N]OFF) at the start of the file");
    if (line[i] && !mc_blank((unsigned char)line[i]))
        return mc_fail(m, PNPR_ERR_FORMAT, 1, -1, "'%.*s' is not an OFF keyword", MC_SHOW, line);
    if (other_dim)
        return mc_fail(m, PNPR_ERR_UNSUPPORTED, 1, -1, "%.*s: vertices of other than 3 dimensions are not supported",
                       (int)i, line);
    size_t j = i;
    if (line[i] && strncmp(line + i + 1, "BINARY", 6) == 0) {
        k->binary = 1;
        j = i + 7;
    }
    while (mc_blank((unsigned char)line[j])) j++;
    if (line[j] && line[j] != '#')
        return mc_fail(m, PNPR_ERR_FORMAT, 1, -1,
                       "text after the keyword ('%.*s'): the counts go on the next line, and BINARY follows "
                       "the keyword after one blank", MC_SHOW, line + j);
    if (cut && line[j] != '#')
        return mc_fail(m, PNPR_ERR_FORMAT, 1, -1, "line 1 is longer than %d bytes", MC_LINE_MAX - 1);
    return PNPR_OK;
}

static pnpr_status off_keyword(mc_ctx *m, off_kind *k)
{
    char line[MC_LINE_MAX];
    size_t n = 0;
    int c;
    while ((c = in_peek(&m->in)) >= 0 && c != '\n' && n + 1 < sizeof line) {
        if (mc_binary(c)) return text_binary(m, c, m->in.off);
        line[n++] = (char)c;
        in_get(&m->in);
    }
    line[n] = '\0';
    pnpr_status st = off_header(m, line, c >= 0 && c != '\n', k);
    return st != PNPR_OK ? st : rest_of_line(m, NULL, 0);
}

static pnpr_status off_count(mc_ctx *m, const char *what, uint64_t *v, long *line)
{
    mc_tok t;
    int found, neg;
    pnpr_status st = next_token(m, 1, &t, &found);
    if (st != PNPR_OK) return st;
    if (!found) return mc_fail(m, PNPR_ERR_TRUNCATED, m->in.line, -1, "the file ends before the %s count", what);
    *line = t.line;
    if (t.too_long || !mc_int(t.s, t.n, &neg, v))
        return mc_fail(m, PNPR_ERR_FORMAT, t.line, -1,
                       "the %s count '%.*s' is not an integer (OFF allows no comments before the data)", what,
                       MC_SHOW, t.s);
    if (neg && *v)
        return mc_fail(m, PNPR_ERR_FORMAT, t.line, -1, "the %s count %.*s is negative", what, MC_SHOW, t.s);
    if (*v > UINT32_MAX)
        return mc_fail(m, PNPR_ERR_FORMAT, t.line, -1, "the %s count %.*s is more than 2^32-1", what, MC_SHOW, t.s);
    return PNPR_OK;
}

/* OpenMesh's getColorType: the words of s (trimmed in place, *r_s its start) counted by single
 * spaces, minus 2 with texture coordinates; 3 or 4 with a '.' in the first word become 5 or 6. */
static int off_color_type(char *s, int texcoords, char **r_s)
{
    *r_s = s;
    if (!s[0]) return 0;
    while (mc_space((unsigned char)*s)) s++;
    size_t n = strlen(s);
    while (n && mc_space((unsigned char)s[n - 1])) s[--n] = '\0';
    *r_s = s;
    int count = n ? 1 : 0;
    for (size_t i = 0; i < n; i++) count += s[i] == ' ';
    if (texcoords) count -= 2;
    if (count == 3 || count == 4) {
        const char *sp = strchr(s, ' ');
        size_t first = sp ? (size_t)(sp - s) : n;
        if (memchr(s, '.', first)) count += 2;
    }
    return count;
}

/* The first `count` words of s are ints (or floats). */
static pnpr_status off_color_values(mc_ctx *m, const char *s, int count, int floats, long line, const char *what,
                                    uint64_t index)
{
    const char *whole = s;
    for (int k = 0; k < count; k++) {
        while (mc_space((unsigned char)*s)) s++;
        size_t n = 0;
        while (s[n] && !mc_space((unsigned char)s[n])) n++;
        mc_tok t;
        t.too_long = n > MC_TOKEN_MAX;
        t.n = t.too_long ? 0 : n;
        memcpy(t.s, s, t.n);
        t.s[t.n] = '\0';
        double d;
        if (!n)
            return mc_fail(m, PNPR_ERR_FORMAT, line, -1,
                           "%s %llu: colour '%.*s' is not 3 or 4 values separated by single spaces", what,
                           ULL(index), MC_SHOW, whole);
        if (!(floats ? mc_float(&t, m->dp, &d, NULL) : mc_int32(s, n)))
            return mc_fail(m, PNPR_ERR_FORMAT, line, -1, "%s %llu: colour value %d '%.*s' is not %s", what, ULL(index),
                           k + 1, MC_SHOW, t.s, floats ? "a number float can hold" : "an int");
        s += n;
    }
    return PNPR_OK;
}

/* The rest of a vertex's or face's line in a C file. */
static pnpr_status off_color(mc_ctx *m, int texcoords, const char *what, uint64_t index)
{
    char buf[MC_LINE_MAX], *s;
    long line = m->in.line;
    pnpr_status st = rest_of_line(m, buf, sizeof buf);
    if (st != PNPR_OK) return st;
    int type = off_color_type(buf, texcoords, &s);
    if (type >= 0 && type <= 2) return PNPR_OK; /* no colour; 1 or 2 words are ignored by OpenMesh */
    if (type > 6)
        return mc_fail(m, PNPR_ERR_FORMAT, line, -1,
                       "%s %llu: colour '%.*s' is not 3 or 4 values separated by single spaces", what, ULL(index),
                       MC_SHOW, s);
    return off_color_values(m, s, type == 3 || type == 5 ? 3 : 4, type >= 5, line, what, index);
}

static pnpr_status off_numbers(mc_ctx *m, double *out, float *out_f, const char *what, uint64_t i, uint64_t nv)
{
    for (int a = 0; a < 3; a++) {
        mc_tok t;
        int found;
        pnpr_status st = next_token(m, 1, &t, &found);
        if (st != PNPR_OK) return st;
        if (!found)
            return mc_fail(m, PNPR_ERR_TRUNCATED, m->in.line, -1,
                           "the file ends after %llu of the %llu vertices its header announces", ULL(i), ULL(nv));
        if (!mc_float(&t, m->dp, &out[a], &out_f[a]))
            return mc_fail(m, PNPR_ERR_FORMAT, t.line, -1, "vertex %llu: %s '%.*s' is not a number float can hold",
                           ULL(i), what, MC_SHOW, t.s);
    }
    return PNPR_OK;
}

static pnpr_status off_vertex(mc_ctx *m, const off_kind *k, uint64_t i, uint64_t nv)
{
    double xyz[3], normal[3];
    float xyz_f[3], normal_f[3];
    pnpr_status st = off_numbers(m, xyz, xyz_f, "coordinate", i, nv);
    if (st == PNPR_OK && k->normal) st = off_numbers(m, normal, normal_f, "normal component", i, nv);
    if (st != PNPR_OK) return st;
    if (m->mc->vertex && m->mc->vertex(m->mc->user, xyz, xyz_f))
        return mc_fail(m, PNPR_ERR_OUT_OF_MEMORY, m->in.line, -1, "out of memory at vertex %llu", ULL(i));
    return k->color ? off_color(m, k->st, "vertex", i) : rest_of_line(m, NULL, 0);
}

static pnpr_status off_face(mc_ctx *m, const off_kind *k, uint64_t f, uint64_t nf, uint64_t nv)
{
    mc_tok t;
    int found;
    uint64_t nc, v;
    pnpr_status st = next_token(m, 1, &t, &found);
    if (st != PNPR_OK) return st;
    if (!found)
        return mc_fail(m, PNPR_ERR_TRUNCATED, m->in.line, -1,
                       "the file ends after %llu of the %llu faces its header announces", ULL(f), ULL(nf));
    if (!mc_uint32(&t, &nc))
        return mc_fail(m, PNPR_ERR_FORMAT, t.line, -1, "face %llu: corner count '%.*s' is not an integer 0..2^32-1",
                       ULL(f), MC_SHOW, t.s);
    if (nc > in_left(&m->in) / 2)
        return mc_fail(m, PNPR_ERR_TRUNCATED, t.line, -1,
                       "face %llu announces %llu corners, more than the %llu bytes left can hold", ULL(f), ULL(nc),
                       ULL(in_left(&m->in)));
    for (uint64_t j = 0; j < nc; j++) {
        if ((st = next_token(m, 1, &t, &found)) != PNPR_OK) return st;
        if (!found)
            return mc_fail(m, PNPR_ERR_TRUNCATED, m->in.line, -1, "the file ends inside face %llu", ULL(f));
        if (!mc_uint32(&t, &v) || v >= nv)
            return mc_fail(m, PNPR_ERR_FORMAT, t.line, -1,
                           "face %llu, corner %llu: vertex index '%.*s' is out of range (the file has %llu vertices)",
                           ULL(f), ULL(j), MC_SHOW, t.s, ULL(nv));
    }
    return k->color ? off_color(m, 0, "face", f) : PNPR_OK;
}

static pnpr_status off_ascii(mc_ctx *m, const off_kind *k)
{
    uint64_t nv, nf, ne;
    long line;
    pnpr_status st = off_count(m, "vertex", &nv, &line);
    if (st == PNPR_OK) st = off_count(m, "face", &nf, &line);
    if (st == PNPR_OK) st = off_count(m, "edge", &ne, &line);
    if (st != PNPR_OK) return st;
    const uint64_t per_vertex = k->normal ? 12 : 6, left = in_left(&m->in);
    if (nv * per_vertex + nf * 2 > left)
        return mc_fail(m, PNPR_ERR_TRUNCATED, line, -1,
                       "the header announces %llu vertices and %llu faces, more than the %llu bytes after it can "
                       "hold (a vertex takes %llu bytes or more, a face 2)",
                       ULL(nv), ULL(nf), ULL(left), ULL(per_vertex));
    if (nv > PNPR_MESH_MAX_VERTICES)
        return mc_fail(m, PNPR_ERR_UNSUPPORTED, line, -1, "%llu vertices: OpenMesh reads at most 2^31-1", ULL(nv));
    for (uint64_t i = 0; i < nv && st == PNPR_OK; i++) st = off_vertex(m, k, i, nv);
    for (uint64_t f = 0; f < nf && st == PNPR_OK; f++) st = off_face(m, k, f, nf, nv);
    m->mc->vertices = nv;
    m->mc->faces = nf;
    return st;
}

static int bin_u32(mc_in *in, uint32_t *v)
{
    uint32_t x = 0;
    for (int b = 0; b < 4; b++) {
        int c = in_get(in);
        if (c < 0) return 0;
        x |= (uint32_t)c << (8 * b);
    }
    *v = x;
    return 1;
}

static pnpr_status off_binary_face(mc_ctx *m, uint64_t f, uint32_t nf, uint32_t nv)
{
    uint32_t nc, v;
    uint64_t at = m->in.off;
    if (!bin_u32(&m->in, &nc))
        return mc_fail(m, PNPR_ERR_TRUNCATED, 0, (long long)at, "the file ends after %llu of the %u faces its header "
                       "announces", ULL(f), nf);
    if ((uint64_t)nc * 4 > in_left(&m->in))
        return mc_fail(m, PNPR_ERR_TRUNCATED, 0, (long long)at,
                       "face %llu announces %u corners, more than the %llu bytes left can hold", ULL(f), nc,
                       ULL(in_left(&m->in)));
    for (uint32_t j = 0; j < nc; j++) {
        at = m->in.off;
        if (!bin_u32(&m->in, &v))
            return mc_fail(m, PNPR_ERR_TRUNCATED, 0, (long long)at, "the file ends inside face %llu", ULL(f));
        if (v >= nv)
            return mc_fail(m, PNPR_ERR_FORMAT, 0, (long long)at,
                           "face %llu, corner %u: vertex index %u is out of range (the file has %u vertices)", ULL(f),
                           j, v, nv);
    }
    return PNPR_OK;
}

static pnpr_status off_binary(mc_ctx *m, const off_kind *k)
{
    uint32_t nv, nf, ne;
    uint64_t at = m->in.off;
    if (!bin_u32(&m->in, &nv) || !bin_u32(&m->in, &nf) || !bin_u32(&m->in, &ne))
        return mc_fail(m, PNPR_ERR_TRUNCATED, 0, (long long)at, "the file ends inside the binary counts");
    const uint64_t per_vertex = 12u + (k->normal ? 12u : 0u) + (k->color ? 12u : 0u) + (k->st ? 8u : 0u);
    const uint64_t left = in_left(&m->in);
    if (nv * per_vertex + (uint64_t)nf * 4 > left)
        return mc_fail(m, PNPR_ERR_TRUNCATED, 0, (long long)at,
                       "the header announces %u vertices (%llu bytes each) and %u faces (4 bytes or more each), "
                       "more than the %llu bytes after it hold", nv, ULL(per_vertex), nf, ULL(left));
    if (nv > PNPR_MESH_MAX_VERTICES)
        return mc_fail(m, PNPR_ERR_UNSUPPORTED, 0, (long long)at, "%u vertices: OpenMesh reads at most 2^31-1", nv);
    if (!in_skip(&m->in, nv * per_vertex))
        return mc_fail(m, PNPR_ERR_TRUNCATED, 0, (long long)m->in.off, "the file ends inside the vertices");
    pnpr_status st = PNPR_OK;
    for (uint64_t f = 0; f < nf && st == PNPR_OK; f++) st = off_binary_face(m, f, nf, nv);
    m->mc->vertices = nv;
    m->mc->faces = nf;
    return st;
}

static pnpr_status off_check(mc_ctx *m)
{
    off_kind k = {0, 0, 0, 0};
    pnpr_status st = off_keyword(m, &k);
    if (st != PNPR_OK) return st;
    m->mc->binary = k.binary;
    return k.binary ? off_binary(m, &k) : off_ascii(m, &k);
}

/* ------------------------------------------------------------------------------------------ */
/* OBJ                                                                                         */

enum { OBJ_V, OBJ_VT, OBJ_VN, OBJ_KINDS };
static const char *const obj_kind_name[OBJ_KINDS] = {"vertex", "texture coordinate", "normal"};

typedef struct obj_state {
    uint64_t count[OBJ_KINDS];   /* statements of each kind so far */
    uint64_t max_ref[OBJ_KINDS]; /* largest positive index named by a face */
    long max_line[OBJ_KINDS];    /* ... on this line */
    uint64_t work;               /* sum of corners^2 */
    uint64_t statements;         /* statements of the OBJ specification */
    long unknown_line;           /* first line with another keyword, 0 = none */
    char unknown[MC_SHOW + 1];   /* ... that keyword */
} obj_state;

static int obj_known(const mc_tok *kw)
{
    static const char *const known[] = {
        "v",     "vt",   "vn",   "vp",   "vc",    "f",        "fo",       "l",      "p",      "o",
        "g",     "s",    "mg",   "mtllib", "usemtl", "usemap", "maplib", "cstype", "deg",    "bmat",
        "step",  "curv", "curv2", "surf", "parm",  "trim",     "hole",     "scrv",   "sp",     "end",
        "con",   "bevel", "c_interp", "d_interp", "lod", "shadow_obj", "trace_obj", "ctech", "stech", "call",
        "csh"};
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (strcmp(kw->s, known[i]) == 0) return 1;
    return 0;
}

static pnpr_status obj_numbers(mc_ctx *m, const char *kw, int count, double *out, float *out_f, uint64_t index)
{
    for (int a = 0; a < count; a++) {
        mc_tok t;
        int found;
        pnpr_status st = next_token(m, 0, &t, &found);
        if (st != PNPR_OK) return st;
        if (!found)
            return mc_fail(m, PNPR_ERR_FORMAT, m->in.line, -1, "'%s' statement %llu has %d numbers, it needs %d", kw,
                           ULL(index), a, count);
        if (!mc_float(&t, m->dp, &out[a], &out_f[a]))
            return mc_fail(m, PNPR_ERR_FORMAT, t.line, -1,
                           "'%s' statement %llu: '%.*s' is not a number float can hold (no nan, inf or 1e39)", kw,
                           ULL(index), MC_SHOW, t.s);
    }
    return PNPR_OK;
}

static pnpr_status obj_vertex(mc_ctx *m, obj_state *s)
{
    double xyz[3];
    float xyz_f[3];
    pnpr_status st = obj_numbers(m, "v", 3, xyz, xyz_f, s->count[OBJ_V] + 1);
    if (st != PNPR_OK) return st;
    if (++s->count[OBJ_V] > PNPR_MESH_MAX_VERTICES)
        return mc_fail(m, PNPR_ERR_UNSUPPORTED, m->in.line, -1, "more than 2^31-1 vertices (OpenMesh's limit)");
    if (m->mc->vertex && m->mc->vertex(m->mc->user, xyz, xyz_f))
        return mc_fail(m, PNPR_ERR_OUT_OF_MEMORY, m->in.line, -1, "out of memory at vertex %llu",
                       ULL(s->count[OBJ_V]));
    return PNPR_OK;
}

static pnpr_status obj_index(mc_ctx *m, obj_state *s, int kind, const char *txt, size_t n, const mc_tok *t,
                             uint64_t corner)
{
    int neg;
    uint64_t mag;
    if (!mc_int32(txt, n))
        return mc_fail(m, PNPR_ERR_FORMAT, t->line, -1, "face corner %llu '%.*s': the %s index is not an int",
                       ULL(corner), MC_SHOW, t->s, obj_kind_name[kind]);
    mc_int(txt, n, &neg, &mag);
    if (mag == 0)
        return mc_fail(m, PNPR_ERR_FORMAT, t->line, -1, "face corner %llu '%.*s': %s index 0 (OBJ counts from 1)",
                       ULL(corner), MC_SHOW, t->s, obj_kind_name[kind]);
    if (neg && mag > s->count[kind])
        return mc_fail(m, PNPR_ERR_FORMAT, t->line, -1,
                       "face corner %llu '%.*s': relative %s index -%llu reaches before the first (%llu so far)",
                       ULL(corner), MC_SHOW, t->s, obj_kind_name[kind], ULL(mag), ULL(s->count[kind]));
    if (!neg && mag > s->max_ref[kind]) {
        s->max_ref[kind] = mag;
        s->max_line[kind] = t->line;
    }
    return PNPR_OK;
}

/* v, v/vt, v//vn or v/vt/vn. */
static pnpr_status obj_corner(mc_ctx *m, obj_state *s, const mc_tok *t, uint64_t corner)
{
    const char *part[3], *p = t->s, *end = t->s + t->n;
    size_t len[3];
    int n = 0, ok = !t->too_long;
    while (ok) {
        const char *slash = memchr(p, '/', (size_t)(end - p));
        if (n == 3) { ok = 0; break; }
        part[n] = p;
        len[n++] = slash ? (size_t)(slash - p) : (size_t)(end - p);
        if (!slash) break;
        p = slash + 1;
    }
    ok = ok && len[0] > 0 && (n == 1 || (n == 2 && len[1] > 0) || (n == 3 && len[2] > 0));
    if (!ok)
        return mc_fail(m, PNPR_ERR_FORMAT, t->line, -1, "face corner %llu '%.*s' is not v, v/vt, v//vn or v/vt/vn",
                       ULL(corner), MC_SHOW, t->s);
    pnpr_status st = PNPR_OK;
    for (int k = 0; k < n && st == PNPR_OK; k++)
        if (len[k]) st = obj_index(m, s, k, part[k], len[k], t, corner);
    return st;
}

static pnpr_status obj_face(mc_ctx *m, obj_state *s)
{
    uint64_t corners = 0;
    long line = m->in.line;
    for (;;) {
        mc_tok t;
        int found;
        pnpr_status st = next_token(m, 0, &t, &found);
        if (st != PNPR_OK) return st;
        if (!found) break;
        if (++corners > PNPR_MESH_MAX_CORNERS)
            return mc_fail(m, PNPR_ERR_UNSUPPORTED, line, -1, "a face with more than %u corners", PNPR_MESH_MAX_CORNERS);
        if ((st = obj_corner(m, s, &t, corners)) != PNPR_OK) return st;
    }
    s->work += corners * corners;
    if (s->work > PNPR_MESH_MAX_CORNER_WORK)
        return mc_fail(m, PNPR_ERR_UNSUPPORTED, line, -1,
                       "the faces so far have %llu corners^2 in all, more than OpenMesh's pairwise corner checks "
                       "can take (2^32)", ULL(s->work));
    m->mc->faces++;
    return PNPR_OK;
}

/* OpenMesh opens the named file (the rest of the line, trimmed) in the OBJ's folder. */
static pnpr_status obj_mtllib(mc_ctx *m, long line)
{
    char name[MC_LINE_MAX];
    pnpr_status st = rest_of_line(m, name, sizeof name);
    if (st != PNPR_OK) return st;
    const char *s = name;
    while (*s == ' ' || *s == '\t' || *s == '\r') s++;
    size_t n = strlen(s);
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r')) n--;
    const char *om = m->mc->openmesh_path ? m->mc->openmesh_path : m->path;
    const char *slash = strrchr(om, '/');
    size_t dir = slash ? (size_t)(slash - om) + 1 : 0;
    char *full = malloc(dir + n + 3);
    if (!full) return mc_fail(m, PNPR_ERR_OUT_OF_MEMORY, line, -1, "out of memory");
    if (slash) memcpy(full, om, dir);
    else memcpy(full, "./", dir = 2);
    memcpy(full + dir, s, n);
    full[dir + n] = '\0';
    struct stat sb;
    int special = stat(full, &sb) == 0 && !S_ISREG(sb.st_mode) && !S_ISDIR(sb.st_mode);
    free(full);
    if (special)
        return mc_fail(m, PNPR_ERR_UNSUPPORTED, line, -1,
                       "mtllib '%.*s' is not a regular file (a device or FIFO: reading it might never end)",
                       (int)(n < 60 ? n : 60), s);
    return PNPR_OK;
}

static pnpr_status obj_statement(mc_ctx *m, obj_state *s)
{
    mc_tok kw;
    int found;
    pnpr_status st = next_token(m, 0, &kw, &found);
    if (st != PNPR_OK || !found) return st;
    double unused[3];
    float unused_f[3];
    if (obj_known(&kw)) {
        s->statements++;
    } else if (!s->unknown_line) {
        s->unknown_line = kw.line;
        size_t n = kw.n < MC_SHOW ? kw.n : MC_SHOW;
        memcpy(s->unknown, kw.s, n);
        s->unknown[n] = '\0';
    }
    if (strcmp(kw.s, "v") == 0) st = obj_vertex(m, s);
    else if (strcmp(kw.s, "vn") == 0) st = obj_numbers(m, "vn", 3, unused, unused_f, ++s->count[OBJ_VN]);
    else if (strcmp(kw.s, "vt") == 0) st = obj_numbers(m, "vt", 2, unused, unused_f, ++s->count[OBJ_VT]);
    else if (strcmp(kw.s, "f") == 0) st = obj_face(m, s);
    else if (strcmp(kw.s, "mtllib") == 0) return obj_mtllib(m, kw.line);
    return st != PNPR_OK ? st : rest_of_line(m, NULL, 0);
}

static pnpr_status obj_finish(mc_ctx *m, const obj_state *s)
{
    if (!s->statements && s->unknown_line)
        return mc_fail(m, PNPR_ERR_FORMAT, s->unknown_line, -1,
                       "'%s' is no OBJ statement, and the file has no OBJ statement (v, vn, vt, f, o, g ...) at all: "
                       "not an OBJ file", s->unknown);
    if (!s->statements)
        return mc_fail(m, PNPR_ERR_FORMAT, 1, -1, "the file is empty or only comments: no OBJ statement");
    for (int k = 0; k < OBJ_KINDS; k++)
        if (s->max_ref[k] > s->count[k])
            return mc_fail(m, PNPR_ERR_FORMAT, s->max_line[k], -1, "a face names %s %llu, the file has %llu",
                           obj_kind_name[k], ULL(s->max_ref[k]), ULL(s->count[k]));
    m->mc->vertices = s->count[OBJ_V];
    return PNPR_OK;
}

static pnpr_status obj_check(mc_ctx *m)
{
    obj_state s;
    memset(&s, 0, sizeof s);
    for (;;) {
        int c;
        while ((c = in_peek(&m->in)) == ' ' || c == '\t' || c == '\r') in_get(&m->in);
        if (c < 0) break;
        pnpr_status st;
        if (c == '\n') st = (in_get(&m->in), PNPR_OK);
        else if (c == '#' || c == '\v' || c == '\f') st = rest_of_line(m, NULL, 0);
        else st = obj_statement(m, &s);
        if (st != PNPR_OK) return st;
    }
    return obj_finish(m, &s);
}

/* ------------------------------------------------------------------------------------------ */

pnpr_status pnpr_mesh_check_file(const char *path, pnpr_mesh_check *mc, pnpr_error *err)
{
    if (!path || !mc) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "pnpr_mesh_check_file: NULL argument");
    mc->vertices = mc->faces = 0;
    mc->binary = 0;
    if (mc->format != PNPR_FORMAT_OBJ && mc->format != PNPR_FORMAT_OFF)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: not an OBJ or OFF format", path);
    mc_ctx *m = calloc(1, sizeof *m);
    if (!m) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    m->path = path;
    m->mc = mc;
    m->err = err;
    m->in.line = 1;
    const struct lconv *lc = localeconv();
    m->dp = lc && lc->decimal_point && lc->decimal_point[0] ? lc->decimal_point[0] : '.';
    pnpr_status st;
    struct stat sb;
    if (!(m->in.f = fopen(path, "rb")) || fstat(fileno(m->in.f), &sb) != 0) {
        st = pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, strerror(errno));
    } else {
        m->in.size = (uint64_t)sb.st_size;
        st = mc->format == PNPR_FORMAT_OBJ ? obj_check(m) : off_check(m);
        if (m->in.failed) st = pnpr_error_set(err, PNPR_ERR_IO, "%s: read error at byte %llu", path, ULL(m->in.off));
    }
    if (m->in.f) fclose(m->in.f);
    free(m);
    return st;
}
