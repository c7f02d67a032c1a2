/* pointnpr — io/pcd.c: PCD (Point Cloud Library) reader and binary writer, plain C11.
 *
 * READING (pnpr_read_pcd_memory, pnpr_read_pcd_file)
 *  - Header: one keyword per line, in the order FIELDS before SIZE/TYPE/COUNT (the others in
 *    any order), DATA last; '#' lines are comments; blank lines, CR LF line ends tolerated.
 *      VERSION   0.5, 0.6 or 0.7 (also ".7"); optional.
 *      FIELDS    field names (COLUMNS is the 0.5 synonym); at most 4096. "_" is padding.
 *      SIZE      bytes per value: 1, 2, 4, 8         (absent: 4 for every field, as 0.5 files)
 *      TYPE      I (signed), U (unsigned), F (float) (absent: F); F needs SIZE 4 or 8
 *      COUNT     values per field and point, 1..65536 (absent: 1); at most 65536 values per point
 *      WIDTH, HEIGHT, POINTS   the point count is POINTS; when WIDTH and HEIGHT are both given
 *                their product must equal it; without POINTS it is WIDTH x HEIGHT (HEIGHT
 *                absent = 1). Organised clouds (HEIGHT > 1) keep their row-major order.
 *      VIEWPOINT tx ty tz qw qx qy qz (7 finite numbers): cloud->has_viewpoint = 1 and
 *                cloud->viewpoint = (tx, ty, tz), the sensor position in the cloud's (world)
 *                coordinates. The orientation is not kept (the cloud model has no field for it).
 *                PCL writes "0 0 0 1 0 0 0" when it knows nothing better; that still sets
 *                has_viewpoint (PCL's own sensors do sit at the origin).
 *      DATA      ascii | binary | binary_compressed; the data start after this line.
 *    Any other keyword is an error (it names the line).
 *  - Field mapping (names are case-sensitive, as PCL writes them):
 *      x y z          required, COUNT 1. All F4 (or 1-, 2-byte integers): origin 0 and the floats
 *                     bit for bit, src_coord_type FLOAT32. Any F8 or 4-, 8-byte integer: exact
 *                     doubles in src_xyz (FLOAT64) and offsets from the bounding-box centre
 *                     (pnpr_cloud_set_world), as io/ply.c does.
 *      normal_x normal_y normal_z   -> cloud->normal (float), when all three are present with
 *                     COUNT 1 (otherwise they are extra properties).
 *      rgb / rgba     the first of them with SIZE 4 and COUNT 1 -> cloud->rgb, whatever its TYPE:
 *                     the 32 bits are 0xAARRGGBB (PCL packs rgb into a float's bits); alpha is
 *                     dropped. Any other rgb/rgba field is an extra property.
 *      label          integer TYPE of 1-4 bytes, COUNT 1 -> cloud->label (uint32; negative values
 *                     wrap, as in io/ply.c). A float or 8-byte label is an extra property.
 *      _              padding: skipped (binary records only; ascii and binary_compressed data
 *                     carry no padding, as PCL writes them).
 *      anything else  an extra property (pnpr_property) of its own type: I1 I2 I4 U1 U2 U4 F4 F8
 *                     map to INT8 .. FLOAT64; 8-byte integers become FLOAT64 (exact up to 2^53).
 *                     A field with COUNT c > 1 becomes c properties NAME_0 .. NAME_{c-1}. Names
 *                     longer than 63 bytes are cut; at most 4096 extra properties.
 *  - Non-finite points (the holes of organised clouds are NaN) are kept, like the PLY reader
 *    does: every stage treats points with non-finite coordinates as invalid, and the point
 *    count and order match the file (row-major pixels stay addressable).
 *  - DATA ascii: one point per line, COUNT values per field in FIELDS order (padding excluded),
 *    numbers in the "C" form whatever LC_NUMERIC says (nan, inf accepted for F). Integer fields
 *    take integers (or integral decimals) inside the type's range; F4 is rounded once to float
 *    (so a packed rgb float written with 9 digits restores its bits). Blank lines are skipped;
 *    data after the last point is ignored.
 *  - DATA binary: little-endian records of sum(SIZE x COUNT) bytes, padding included.
 *  - DATA binary_compressed: uint32 compressed size, uint32 uncompressed size (little endian),
 *    then LZF data that expands to one array per non-padding field (all points' values of the
 *    first field, then the second, ...). The uncompressed size must equal points x bytes per
 *    point (padding excluded) and may not exceed 88 x the compressed size (the most an LZF
 *    stream can expand: 3 bytes for 264); both are checked before anything is allocated.
 *    The LZF decompressor is written here (20 lines, format of Marc Lehmann's liblzf, which
 *    PCL embeds): Debian's liblzf would be one more run-time dependency for that, and this one
 *    reports the byte offset of a corrupt back reference, which the library's return code
 *    cannot tell.
 *  - Errors: header problems name the line ("line 5: TYPE 'Q' of field 'x' is unknown ..."),
 *    ascii data the line and point, binary data the byte offset (err->line / err->offset are
 *    set). Data shorter than announced gives PNPR_ERR_TRUNCATED, anything malformed
 *    PNPR_ERR_FORMAT, F2 (half floats) PNPR_ERR_UNSUPPORTED. Every count is checked against
 *    the bytes present before the cloud is allocated (a 200-byte file that announces 10^12
 *    points fails at once); size arithmetic saturates. On error the cloud is left zeroed.
 *    pnpr_read_pcd_file maps the file (io/file_bytes.h), so that check comes before any of the
 *    data is read: a 2 GB sparse file that announces 10^9 points fails at once.
 *  - Progress stage "read pcd", every 65536 points; cancelling gives PNPR_ERR_CANCELLED.
 *
 * WRITING (pnpr_write_pcd_stream, pnpr_write_pcd_file): "VERSION 0.7", DATA binary (little
 *    endian), HEIGHT 1. Fields: x y z (F8 when the PLY writer would write double: src_xyz,
 *    FLOAT64 source, force_double, or an unknown-type cloud that float cannot reproduce; else
 *    F4), normal_x normal_y normal_z (F4) if normals, rgb (F4 holding 0x00RRGGBB, PCL's
 *    convention; "rgba" U4 0xFFRRGGBB when an extra property is named rgb) if colours, label
 *    (U4; "segment" when an extra property is named label) if labels, then every extra property
 *    with its own type. VIEWPOINT "tx ty tz 1 0 0 0" only when cloud->has_viewpoint. Faces are
 *    not written (PCD has none). opts->encoding is ignored. The file is written to path + ".tmp"
 *    and renamed. Progress stage "write pcd".
 */
#include <pointnpr/io.h>

#include "../core/internal.h"
#include <pointnpr/output.h>
#include "file_bytes.h"
#include "io_util.h"
#include "out_buf.h"
#include "text_token.h"

#include <errno.h>
#include <float.h>
#include <locale.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Exported beyond io.h (io/io.c declares them itself and dispatches to them). */
pnpr_status pnpr_read_pcd_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                               pnpr_error *err);
pnpr_status pnpr_write_pcd_file(const char *path, const pnpr_cloud *cloud,
                                const pnpr_write_options *opts, pnpr_error *err);

#define PCD_MAX_FIELDS 4096      /* entries of FIELDS */
#define PCD_MAX_VALUES 65536u    /* values per point, all fields together */
#define PCD_MAX_PROPS 4096       /* extra properties */
#define PCD_LZF_RATIO 88u        /* most bytes one LZF input byte can expand to */
#define PCD_CHUNK 65536u         /* points between progress reports */
#define PCD_TOKEN_MAX 256        /* longest ascii number */
#define PCD_SHOW 64              /* longest name quoted in a message */


/* ------------------------------------------------------------------------------------------ */
/* Small helpers                                                                               */



static uint64_t rd_le(const unsigned char *p, unsigned size)
{
    uint64_t v = 0;
    for (unsigned k = size; k-- > 0;) v = (v << 8) | p[k];
    return v;
}

static void wr_le(unsigned char *p, uint64_t v, unsigned size)
{
    for (unsigned k = 0; k < size; k++) p[k] = (unsigned char)(v >> (8 * k));
}

/* A double into a float without out-of-range conversion. */
static float pcd_d2f(double v)
{
    if (v != v) return (float)v;
    if (v > FLT_MAX) return v >= 0x1.ffffffp127 ? INFINITY : FLT_MAX;
    if (v < -FLT_MAX) return v <= -0x1.ffffffp127 ? -INFINITY : -FLT_MAX;
    return (float)v;
}

typedef pnpr_token pcd_tok;

static int show(pcd_tok t)
{
    return (int)(t.n > PCD_SHOW ? PCD_SHOW : t.n);
}

/* Non-negative decimal integer; 0 on failure. */
static int parse_u64(pcd_tok t, uint64_t *out)
{
    uint64_t v = 0;
    if (t.n == 0) return 0;
    for (size_t i = 0; i < t.n; i++) {
        unsigned d = (unsigned)(unsigned char)t.s[i] - '0';
        if (d > 9 || v > (UINT64_MAX - d) / 10) return 0;
        v = v * 10 + d;
    }
    *out = v;
    return 1;
}

/* Copies a number token into buf (NUL-terminated) with '.' replaced by the locale's decimal
 * point, so that strtod/strtof read the "C" form whatever LC_NUMERIC says. */
static int c_number(pcd_tok t, char buf[PCD_TOKEN_MAX + 1])
{
    if (t.n == 0 || t.n > PCD_TOKEN_MAX) return 0;
    pnpr_token_c_number(t.s, t.n, buf);
    return 1;
}

static int parse_double(pcd_tok t, double *out)
{
    char buf[PCD_TOKEN_MAX + 1], *end;
    if (!c_number(t, buf)) return 0;
    *out = strtod(buf, &end);
    return end == buf + t.n;
}

static int parse_float(pcd_tok t, float *out)
{
    char buf[PCD_TOKEN_MAX + 1], *end;
    if (!c_number(t, buf)) return 0;
    *out = strtof(buf, &end);
    return end == buf + t.n;
}

/* ------------------------------------------------------------------------------------------ */
/* Header model                                                                                */

enum pcd_kw { KW_VERSION, KW_FIELDS, KW_SIZE, KW_TYPE, KW_COUNT, KW_WIDTH, KW_HEIGHT, KW_VIEWPOINT,
              KW_POINTS, KW_DATA, KW_N };
static const char *const kw_names[KW_N] = {"VERSION", "FIELDS", "SIZE",      "TYPE",   "COUNT",
                                           "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};

enum pcd_data { DATA_NONE = 0, DATA_ASCII, DATA_BINARY, DATA_COMPRESSED };

enum pcd_role { ROLE_PAD = 0, ROLE_X, ROLE_Y, ROLE_Z, ROLE_NX, ROLE_NY, ROLE_NZ, ROLE_RGB, ROLE_LABEL,
                ROLE_EXTRA };

typedef struct pcd_field {
    pcd_tok name;
    unsigned size;   /* bytes per value */
    char type;       /* 'I', 'U' or 'F' */
    uint32_t count;  /* values per point */
    int role;
    size_t offset;   /* byte offset inside a binary record */
    size_t soa;      /* byte offset of the field's array in binary_compressed data */
    size_t prop;     /* first extra property (ROLE_EXTRA) */
} pcd_field;

typedef struct pcd_header {
    pcd_field *fields;
    size_t nfields;
    long line[KW_N];     /* line of each keyword, 0 = absent */
    uint64_t num[KW_N];  /* WIDTH, HEIGHT, POINTS */
    double vp[7];
    int data;
    size_t body;         /* byte offset of the data */
    long body_line;
    size_t step;         /* bytes of a binary record (padding included) */
    size_t packed;       /* bytes per point without padding */
    size_t values;       /* ascii values per point */
    size_t n;            /* points */
    size_t nprops;       /* extra properties */
    int double_xyz, has_normal, has_rgb, has_label;
    uint32_t csize, usize; /* binary_compressed sizes */
} pcd_header;

/* Checks the token count of a SIZE/TYPE/COUNT line against FIELDS. */
static pnpr_status hdr_list_check(const pcd_header *h, int kw, size_t nt, long line, pnpr_error *err)
{
    if (!h->line[KW_FIELDS])
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1, "line %ld: %s comes before FIELDS", line, kw_names[kw]);
    if (nt != h->nfields)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1, "line %ld: %s has %zu entries, FIELDS (line %ld) has %zu",
                        line, kw_names[kw], nt, h->line[KW_FIELDS], h->nfields);
    return PNPR_OK;
}

static pnpr_status hdr_entry(pcd_field *f, int kw, pcd_tok t, long line, pnpr_error *err)
{
    uint64_t v = 0;
    if (kw == KW_SIZE) {
        if (!parse_u64(t, &v) || (v != 1 && v != 2 && v != 4 && v != 8))
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1, "line %ld: SIZE '%.*s' of field '%.*s' is not 1, 2, 4 or 8",
                            line, show(t), t.s, show(f->name), f->name.s);
        f->size = (unsigned)v;
    } else if (kw == KW_TYPE) {
        if (t.n != 1 || (t.s[0] != 'I' && t.s[0] != 'U' && t.s[0] != 'F'))
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1,
                            "line %ld: TYPE '%.*s' of field '%.*s' is unknown (expected I, U or F)",
                            line, show(t), t.s, show(f->name), f->name.s);
        f->type = t.s[0];
    } else {
        if (!parse_u64(t, &v) || v < 1 || v > PCD_MAX_VALUES)
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1, "line %ld: COUNT '%.*s' of field '%.*s' is not between 1 and %u",
                            line, show(t), t.s, show(f->name), f->name.s, PCD_MAX_VALUES);
        f->count = (uint32_t)v;
    }
    return PNPR_OK;
}

static pnpr_status hdr_list(pcd_header *h, int kw, const char *q, const char *le, long line, pnpr_error *err)
{
    pnpr_status st = hdr_list_check(h, kw, pnpr_token_count(q, le), line, err);
    pcd_tok t;
    for (size_t i = 0; st == PNPR_OK && pnpr_token_next(&q, le, &t); i++) st = hdr_entry(&h->fields[i], kw, t, line, err);
    return st;
}

static pnpr_status hdr_fields(pcd_header *h, const char *q, const char *le, long line, pnpr_error *err)
{
    size_t nt = pnpr_token_count(q, le);
    if (nt == 0 || nt > PCD_MAX_FIELDS)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1, "line %ld: FIELDS names %zu fields (expected 1 to %d)", line, nt,
                        PCD_MAX_FIELDS);
    h->fields = calloc(nt, sizeof *h->fields);
    if (!h->fields) return pnpr_io_fail(err, PNPR_ERR_OUT_OF_MEMORY, line, -1, "line %ld: out of memory", line);
    h->nfields = nt;
    for (size_t i = 0; i < nt; i++) {
        pnpr_token_next(&q, le, &h->fields[i].name);
        h->fields[i].size = 4; /* 0.5 files have no SIZE/TYPE/COUNT: 4-byte floats */
        h->fields[i].type = 'F';
        h->fields[i].count = 1;
    }
    return PNPR_OK;
}

static pnpr_status hdr_number(pcd_header *h, int kw, const char *q, const char *le, long line, pnpr_error *err)
{
    pcd_tok t = {"", 0};
    if (pnpr_token_count(q, le) != 1 || !pnpr_token_next(&q, le, &t) || !parse_u64(t, &h->num[kw]))
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1, "line %ld: %s wants one non-negative integer, found '%.*s'", line,
                        kw_names[kw], show(t), t.s);
    return PNPR_OK;
}

static pnpr_status hdr_viewpoint(pcd_header *h, const char *q, const char *le, long line, pnpr_error *err)
{
    pcd_tok t;
    size_t nt = pnpr_token_count(q, le);
    if (nt != 7)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1,
                        "line %ld: VIEWPOINT wants 7 numbers (tx ty tz qw qx qy qz), found %zu",
                        line, nt);
    for (int k = 0; k < 7 && pnpr_token_next(&q, le, &t); k++)
        if (!parse_double(t, &h->vp[k]) || !isfinite(h->vp[k]))
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1, "line %ld: VIEWPOINT value %d '%.*s' is not a finite number",
                            line, k + 1, show(t), t.s);
    return PNPR_OK;
}

static pnpr_status hdr_word(pcd_header *h, int kw, const char *q, const char *le, long line, pnpr_error *err)
{
    pcd_tok t = {"", 0};
    int one = pnpr_token_count(q, le) == 1 && pnpr_token_next(&q, le, &t);
    if (kw == KW_DATA) {
        h->data = !one ? DATA_NONE : pnpr_token_is(t, "ascii") ? DATA_ASCII : pnpr_token_is(t, "binary") ? DATA_BINARY
                  : pnpr_token_is(t, "binary_compressed") ? DATA_COMPRESSED : DATA_NONE;
        if (h->data == DATA_NONE)
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1,
                            "line %ld: unknown DATA '%.*s' (expected ascii, binary or binary_compressed)", line, show(t), t.s);
        return PNPR_OK;
    }
    static const char *const versions[] = {"0.7", ".7", "0.6", ".6", "0.5", ".5"};
    for (size_t i = 0; one && i < sizeof versions / sizeof versions[0]; i++)
        if (pnpr_token_is(t, versions[i])) return PNPR_OK;
    return pnpr_io_fail(err, PNPR_ERR_UNSUPPORTED, line, -1,
                    "line %ld: PCD version '%.*s' is not supported (0.5, 0.6 and 0.7 are)",
                    line, show(t), t.s);
}

static int keyword_of(pcd_tok t)
{
    if (pnpr_token_is(t, "COLUMNS")) return KW_FIELDS;
    for (int k = 0; k < KW_N; k++)
        if (pnpr_token_is(t, kw_names[k])) return k;
    return -1;
}

static pnpr_status hdr_line(pcd_header *h, pcd_tok kwt, const char *q, const char *le, long line, pnpr_error *err)
{
    int kw = keyword_of(kwt);
    if (kw < 0)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1,
                        "line %ld: unknown header keyword '%.*s' (expected VERSION, FIELDS, SIZE, TYPE, COUNT, WIDTH, "
                        "HEIGHT, VIEWPOINT, POINTS or DATA)", line, show(kwt), kwt.s);
    if (h->line[kw])
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1, "line %ld: second %s line (the first is line %ld)", line,
                        kw_names[kw], h->line[kw]);
    h->line[kw] = line;
    switch (kw) {
    case KW_FIELDS: return hdr_fields(h, q, le, line, err);
    case KW_SIZE: case KW_TYPE: case KW_COUNT: return hdr_list(h, kw, q, le, line, err);
    case KW_WIDTH: case KW_HEIGHT: case KW_POINTS: return hdr_number(h, kw, q, le, line, err);
    case KW_VIEWPOINT: return hdr_viewpoint(h, q, le, line, err);
    default: return hdr_word(h, kw, q, le, line, err);
    }
}

/* Reads header lines up to and including DATA. */
static pnpr_status parse_lines(const char *d, size_t size, pcd_header *h, pnpr_error *err)
{
    size_t pos = 0;
    long line = 0;
    while (pos < size) {
        const char *ls = d + pos, *nl = memchr(ls, '\n', size - pos), *le = nl ? nl : d + size, *q = ls;
        pcd_tok kw;
        line++;
        pos = (size_t)(le - d) + (nl ? 1 : 0);
        if (!pnpr_token_next(&q, le, &kw) || kw.s[0] == '#') continue;
        for (const char *c = ls; c < le; c++)
            if (((unsigned char)*c < 0x20 && !pnpr_is_blank(*c)) || (unsigned char)*c == 0x7f)
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)(c - d),
                                "line %ld: invalid character 0x%02x in the header", line, (unsigned char)*c);
        pnpr_status st = hdr_line(h, kw, q, le, line, err);
        if (st != PNPR_OK) return st;
        if (h->data) {
            h->body = pos;
            h->body_line = line + 1;
            return PNPR_OK;
        }
    }
    return pnpr_io_fail(err, size ? PNPR_ERR_FORMAT : PNPR_ERR_TRUNCATED, line, (long long)size,
                    "line %ld: the header ends without a DATA line", line);
}

/* ------------------------------------------------------------------------------------------ */
/* Header checks: types, roles, point count                                                    */

static pnpr_status check_types(const pcd_header *h, pnpr_error *err)
{
    size_t values = 0;
    for (size_t i = 0; i < h->nfields; i++) {
        const pcd_field *f = &h->fields[i];
        if (f->type == 'F' && f->size < 4) {
            long line = h->line[KW_TYPE] ? h->line[KW_TYPE] : h->line[KW_SIZE];
            return pnpr_io_fail(err, PNPR_ERR_UNSUPPORTED, line, -1,
                            "line %ld: field '%.*s' is a %u-byte float (F needs SIZE 4 or 8)", line, show(f->name),
                            f->name.s, f->size);
        }
        values += f->count;
    }
    if (values > PCD_MAX_VALUES)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, h->line[KW_COUNT], -1,
                        "line %ld: COUNT adds up to %zu values per point, more than %u",
                        h->line[KW_COUNT], values, PCD_MAX_VALUES);
    return PNPR_OK;
}

static int role_of_name(pcd_tok n)
{
    static const char *const names[] = {"x", "y", "z", "normal_x", "normal_y", "normal_z"};
    if (pnpr_token_is(n, "_")) return ROLE_PAD;
    for (int k = 0; k < 6; k++)
        if (pnpr_token_is(n, names[k])) return ROLE_X + k;
    return ROLE_EXTRA;
}

static pnpr_status check_names(const pcd_header *h, pnpr_error *err)
{
    for (size_t i = 0; i < h->nfields; i++) {
        const pcd_field *f = &h->fields[i];
        if (pnpr_token_is(f->name, "_")) continue;
        for (size_t j = 0; j < i; j++)
            if (pnpr_token_eq(f->name, h->fields[j].name))
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, h->line[KW_FIELDS], -1, "line %ld: field '%.*s' appears twice",
                                h->line[KW_FIELDS], show(f->name), f->name.s);
    }
    return PNPR_OK;
}

/* The role of each field (see the top of the file). */
static pnpr_status assign_roles(pcd_header *h, pnpr_error *err)
{
    int seen[ROLE_EXTRA] = {0};
    for (size_t i = 0; i < h->nfields; i++) {
        pcd_field *f = &h->fields[i];
        f->role = role_of_name(f->name);
        if (f->role != ROLE_PAD && f->role != ROLE_EXTRA && f->count == 1) seen[f->role] = 1;
        if (f->role >= ROLE_X && f->role <= ROLE_Z && f->count != 1)
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, h->line[KW_COUNT], -1,
                            "line %ld: field '%.*s' has COUNT %lu (coordinates need 1)",
                            h->line[KW_COUNT], show(f->name), f->name.s, (unsigned long)f->count);
    }
    if (!seen[ROLE_X] || !seen[ROLE_Y] || !seen[ROLE_Z])
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, h->line[KW_FIELDS], -1, "line %ld: FIELDS has no %s field", h->line[KW_FIELDS],
                        !seen[ROLE_X] ? "x" : !seen[ROLE_Y] ? "y" : "z");
    h->has_normal = seen[ROLE_NX] && seen[ROLE_NY] && seen[ROLE_NZ];
    for (size_t i = 0; i < h->nfields; i++) {
        pcd_field *f = &h->fields[i];
        if (f->role >= ROLE_NX && f->role <= ROLE_NZ && (!h->has_normal || f->count != 1)) f->role = ROLE_EXTRA;
        if (f->role >= ROLE_X && f->role <= ROLE_Z && (f->type == 'F' ? f->size == 8 : f->size >= 4)) h->double_xyz = 1;
        if (f->role == ROLE_EXTRA && !h->has_rgb && (pnpr_token_is(f->name, "rgb") || pnpr_token_is(f->name, "rgba")) &&
            f->size == 4 && f->count == 1)
            f->role = ROLE_RGB, h->has_rgb = 1;
        else if (f->role == ROLE_EXTRA && !h->has_label && pnpr_token_is(f->name, PNPR_PROP_LABEL) && f->type != 'F' && f->size <= 4 &&
                 f->count == 1)
            f->role = ROLE_LABEL, h->has_label = 1;
        if (f->role == ROLE_EXTRA) { f->prop = h->nprops; h->nprops += f->count; }
    }
    if (h->nprops > PCD_MAX_PROPS)
        return pnpr_io_fail(err, PNPR_ERR_UNSUPPORTED, h->line[KW_FIELDS], -1,
                        "line %ld: %zu extra values per point, at most %d are kept",
                        h->line[KW_FIELDS], h->nprops, PCD_MAX_PROPS);
    return PNPR_OK;
}

/* Point count from POINTS / WIDTH / HEIGHT. */
static pnpr_status point_count(pcd_header *h, uint64_t *r_n, pnpr_error *err)
{
    const long lp = h->line[KW_POINTS], lw = h->line[KW_WIDTH], lh = h->line[KW_HEIGHT];
    const uint64_t wh = pnpr_mul_sat(h->num[KW_WIDTH], lh ? h->num[KW_HEIGHT] : 1);
    if (lp) {
        if (lw && lh && wh != h->num[KW_POINTS])
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, lp, -1, "line %ld: POINTS %llu but WIDTH x HEIGHT = %llu x %llu", lp,
                            (unsigned long long)h->num[KW_POINTS], (unsigned long long)h->num[KW_WIDTH],
                            (unsigned long long)h->num[KW_HEIGHT]);
        *r_n = h->num[KW_POINTS];
        return PNPR_OK;
    }
    if (!lw)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, h->line[KW_DATA], -1,
                        "line %ld: no POINTS or WIDTH line before DATA: the point count is unknown",
                        h->line[KW_DATA]);
    if (wh == UINT64_MAX)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, lw, -1, "line %ld: WIDTH x HEIGHT overflows", lw);
    *r_n = wh;
    return PNPR_OK;
}

/* Record layout: binary offsets, compressed array offsets (after n is known), ascii values. */
static void layout(pcd_header *h)
{
    size_t soa = 0;
    for (size_t i = 0; i < h->nfields; i++) {
        pcd_field *f = &h->fields[i];
        const size_t bytes = (size_t)f->size * f->count;
        f->offset = h->step;
        h->step += bytes;
        if (f->role == ROLE_PAD) continue;
        f->soa = soa;
        soa += bytes * h->n;
        h->packed += bytes;
        h->values += f->count;
    }
}

/* The data the header announces must be present: checked before anything is allocated. */
static pnpr_status check_body(pcd_header *h, const unsigned char *d, size_t size, uint64_t n, pnpr_error *err)
{
    const size_t avail = size - h->body;
    const long long at = (long long)h->body;
    if (h->data == DATA_BINARY && pnpr_mul_sat(n, h->step) > avail) {
        const uint64_t first = avail / h->step;
        return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, 0, (long long)(h->body + first * h->step),
                        "byte %llu: the data ends inside point %llu of %llu (%zu bytes per point, %zu bytes after the header)",
                        (unsigned long long)(h->body + first * h->step), (unsigned long long)first, (unsigned long long)n,
                        h->step, avail);
    }
    if (h->data == DATA_ASCII && pnpr_mul_sat(n, h->values) > avail / 2 + 1)
        return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, h->body_line, at,
                        "line %ld: %llu points of %zu values need more text than the %zu bytes after the header",
                        h->body_line, (unsigned long long)n, h->values, avail);
    if (h->data != DATA_COMPRESSED) return PNPR_OK;
    if (avail < 8)
        return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, 0, (long long)size,
                        "byte %zu: the data ends inside the 8-byte size header of binary_compressed",
                        size);
    h->csize = (uint32_t)rd_le(d + h->body, 4);
    h->usize = (uint32_t)rd_le(d + h->body + 4, 4);
    if (h->csize > avail - 8)
        return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, 0, at, "byte %lld: compressed size %lu, but only %zu bytes follow", at,
                        (unsigned long)h->csize, avail - 8);
    if (pnpr_mul_sat(n, h->packed) != h->usize)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, 0, at + 4,
                        "byte %lld: uncompressed size %lu, but %llu points of %zu bytes need %llu",
                        at + 4, (unsigned long)h->usize, (unsigned long long)n, h->packed,
                        (unsigned long long)pnpr_mul_sat(n, h->packed));
    if (h->usize > (uint64_t)h->csize * PCD_LZF_RATIO)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, 0, at,
                        "byte %lld: %lu compressed bytes cannot expand to %lu (LZF expands at most %ux)",
                        at, (unsigned long)h->csize, (unsigned long)h->usize, PCD_LZF_RATIO);
    return PNPR_OK;
}

static pnpr_status parse_header(const unsigned char *d, size_t size, pcd_header *h, pnpr_error *err)
{
    uint64_t n = 0;
    pnpr_status st = parse_lines((const char *)d, size, h, err);
    if (st == PNPR_OK && !h->line[KW_FIELDS])
        st = pnpr_io_fail(err, PNPR_ERR_FORMAT, h->line[KW_DATA], -1, "line %ld: no FIELDS line before DATA", h->line[KW_DATA]);
    if (st == PNPR_OK) st = check_types(h, err);
    if (st == PNPR_OK) st = check_names(h, err);
    if (st == PNPR_OK) st = assign_roles(h, err);
    if (st == PNPR_OK) st = point_count(h, &n, err);
    if (st != PNPR_OK) return st;
    layout(h); /* step, packed, values (n is still 0: array offsets are set again below) */
    if ((st = check_body(h, d, size, n, err)) != PNPR_OK) return st;
    if (n > SIZE_MAX / (3 * sizeof(double)))
        return pnpr_io_fail(err, PNPR_ERR_OUT_OF_MEMORY, h->line[KW_POINTS], -1, "%llu points do not fit in memory",
                        (unsigned long long)n);
    h->n = (size_t)n;
    h->step = h->packed = h->values = 0;
    layout(h);
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* Values                                                                                      */

typedef struct pcd_reader {
    const unsigned char *data;
    size_t size;
    const pcd_header *h;
    pnpr_cloud *c;
    const pnpr_progress *progress;
    pnpr_error *err;
} pcd_reader;

/* Little-endian value of a field's type, as double. */
static double load(const unsigned char *p, const pcd_field *f)
{
    uint64_t u = rd_le(p, f->size);
    if (f->type == 'F') {
        if (f->size == 4) {
            uint32_t b = (uint32_t)u;
            float v;
            memcpy(&v, &b, sizeof v);
            return v;
        }
        double v;
        memcpy(&v, &u, sizeof v);
        return v;
    }
    if (f->type == 'U') return (double)u;
    if (f->size < 8 && ((u >> (8 * f->size - 1)) & 1u)) u |= ~UINT64_C(0) << (8 * f->size);
    int64_t s;
    memcpy(&s, &u, sizeof s);
    return (double)s;
}

static uint32_t load_label(const unsigned char *p, const pcd_field *f)
{
    double v = load(p, f); /* integer of at most 32 bits: exact */
    return v < 0 ? (uint32_t)(int64_t)v : (uint32_t)v;
}

static void store(const pcd_reader *r, const pcd_field *f, uint32_t k, size_t i, const unsigned char *p)
{
    pnpr_cloud *c = r->c;
    switch (f->role) {
    case ROLE_X: case ROLE_Y: case ROLE_Z:
        if (c->src_xyz) c->src_xyz[3 * i + (size_t)(f->role - ROLE_X)] = load(p, f);
        else c->xyz[3 * i + (size_t)(f->role - ROLE_X)] = (float)load(p, f); /* F4 or small integer: exact */
        break;
    case ROLE_NX: case ROLE_NY: case ROLE_NZ:
        c->normal[3 * i + (size_t)(f->role - ROLE_NX)] = pcd_d2f(load(p, f));
        break;
    case ROLE_RGB: {
        uint32_t b = (uint32_t)rd_le(p, 4);
        c->rgb[3 * i] = (uint8_t)(b >> 16);
        c->rgb[3 * i + 1] = (uint8_t)(b >> 8);
        c->rgb[3 * i + 2] = (uint8_t)b;
        break;
    }
    case ROLE_LABEL: c->label[i] = load_label(p, f); break;
    case ROLE_EXTRA: {
        pnpr_property *pp = &c->props[f->prop + k];
        pnpr_type_set(pp->type, pp->data, i, load(p, f));
        break;
    }
    default: break;
    }
}

static pnpr_status cancelled(const pcd_reader *r, size_t i)
{
    return pnpr_io_fail(r->err, PNPR_ERR_CANCELLED, 0, -1, "read pcd: cancelled at point %zu of %zu", i, r->h->n);
}

/* Binary records (soa = 0) or binary_compressed arrays (soa = 1) starting at base. */
static pnpr_status store_points(const pcd_reader *r, const unsigned char *base, int soa)
{
    const pcd_header *h = r->h;
    for (size_t b = 0; b < h->n; b += PCD_CHUNK) {
        const size_t e = h->n - b < PCD_CHUNK ? h->n : b + PCD_CHUNK;
        if (pnpr_progress_report(r->progress, "read pcd", (double)b / (double)h->n)) return cancelled(r, b);
        for (size_t j = 0; j < h->nfields; j++) {
            const pcd_field *f = &h->fields[j];
            const size_t bytes = (size_t)f->size * f->count, stride = soa ? bytes : h->step;
            const unsigned char *p0 = base + (soa ? f->soa : f->offset);
            if (f->role == ROLE_PAD) continue;
            for (size_t i = b; i < e; i++)
                for (uint32_t k = 0; k < f->count; k++) store(r, f, k, i, p0 + i * stride + (size_t)k * f->size);
        }
    }
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* binary_compressed: LZF                                                                      */

/* Expands LZF data (liblzf's format) into out[0, cap). Returns the bytes produced, or stops at a
 * corrupt instruction: *r_bad = its offset in `in` and *r_why the reason. */
static size_t lzf_expand(const unsigned char *in, size_t n, unsigned char *out, size_t cap, size_t *r_bad,
                         const char **r_why)
{
    size_t ip = 0, op = 0;
    *r_why = NULL;
    while (ip < n) {
        const size_t at = ip;
        size_t ctrl = in[ip++], len, back;
        if (ctrl < 32) { /* literal run of ctrl + 1 bytes */
            len = ctrl + 1;
            *r_why = len > n - ip     ? "literal run past the end of the data"
                     : len > cap - op ? "output longer than announced" : NULL;
            if (*r_why) { *r_bad = at; return op; }
            memcpy(out + op, in + ip, len);
            ip += len;
        } else { /* back reference: length (3 bits, + a byte when 7), distance 13 bits */
            len = ctrl >> 5;
            if (len == 7 && ip < n) len += in[ip++];
            back = ((ctrl & 31u) << 8) + 1;
            if (ip < n) back += in[ip++];
            else *r_why = "back reference past the end of the data";
            len += 2;
            if (!*r_why)
                *r_why = back > op       ? "back reference before the start of the output"
                         : len > cap - op ? "output longer than announced" : NULL;
            if (*r_why) { *r_bad = at; return op; }
            for (size_t k = 0; k < len; k++) out[op + k] = out[op - back + k]; /* may overlap */
        }
        op += len;
    }
    return op;
}

static pnpr_status read_compressed(const pcd_reader *r)
{
    const pcd_header *h = r->h;
    const size_t start = h->body + 8;
    unsigned char *buf = malloc(h->usize ? h->usize : 1);
    if (!buf) return pnpr_io_fail(r->err, PNPR_ERR_OUT_OF_MEMORY, 0, -1,
                              "read pcd: cannot allocate %lu bytes", (unsigned long)h->usize);
    size_t bad = 0;
    const char *why;
    size_t got = lzf_expand(r->data + start, h->csize, buf, h->usize, &bad, &why);
    pnpr_status st = PNPR_OK;
    if (why)
        st = pnpr_io_fail(r->err, PNPR_ERR_FORMAT, 0, (long long)(start + bad),
                      "byte %zu: corrupt LZF data: %s", start + bad, why);
    else if (got != h->usize)
        st = pnpr_io_fail(r->err, PNPR_ERR_FORMAT, 0, (long long)(start + h->csize),
                      "byte %zu: LZF data ends after %zu of the %lu announced bytes", start + h->csize, got,
                      (unsigned long)h->usize);
    if (st == PNPR_OK) st = store_points(r, buf, 1);
    free(buf);
    return st;
}

/* ------------------------------------------------------------------------------------------ */
/* ascii                                                                                       */

/* Integer token (or an integral decimal) as magnitude + sign; 0 if it is not one. */
static int parse_integer(pcd_tok t, uint64_t *r_mag, int *r_neg)
{
    const char *s = t.s, *e = t.s + t.n;
    *r_neg = s < e && *s == '-';
    if (s < e && (*s == '-' || *s == '+')) s++;
    pcd_tok digits = {s, (size_t)(e - s)};
    if (parse_u64(digits, r_mag)) return 1;
    double v;
    if (!parse_double(t, &v) || !isfinite(v) || v != floor(v) || fabs(v) >= 0x1p64) return 0;
    *r_neg = v < 0;
    *r_mag = (uint64_t)fabs(v);
    return 1;
}

/* One ascii value into the little-endian bytes of the field's type. 0: not a number of that
 * type, -1: out of the type's range. */
static int parse_value(pcd_tok t, const pcd_field *f, unsigned char raw[8])
{
    if (f->type == 'F' && f->size == 4) {
        float v;
        uint32_t b;
        if (!parse_float(t, &v)) return 0;
        memcpy(&b, &v, sizeof b);
        wr_le(raw, b, 4);
        return 1;
    }
    if (f->type == 'F') {
        double v;
        uint64_t b;
        if (!parse_double(t, &v)) return 0;
        memcpy(&b, &v, sizeof b);
        wr_le(raw, b, 8);
        return 1;
    }
    uint64_t m;
    int neg;
    if (!parse_integer(t, &m, &neg)) return 0;
    const unsigned bits = 8 * f->size;
    const uint64_t umax = bits == 64 ? UINT64_MAX : (UINT64_C(1) << bits) - 1, half = UINT64_C(1) << (bits - 1);
    if (m == 0) neg = 0;
    if (f->type == 'U' ? (neg || m > umax) : (neg ? m > half : m > half - 1)) return -1;
    wr_le(raw, neg ? (uint64_t)0 - m : m, f->size);
    return 1;
}

static pnpr_status ascii_point(const pcd_reader *r, size_t i, const char *ls, const char *le, long line)
{
    const pcd_header *h = r->h;
    const char *q = ls;
    const size_t found = pnpr_token_count(ls, le);
    pcd_tok t;
    if (found != h->values)
        return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, line, (long long)(ls - (const char *)r->data),
                        "line %ld: point %zu has %zu values, the header announces %zu", line, i, found, h->values);
    for (size_t j = 0; j < h->nfields; j++) {
        const pcd_field *f = &h->fields[j];
        for (uint32_t k = 0; f->role != ROLE_PAD && k < f->count && pnpr_token_next(&q, le, &t); k++) {
            unsigned char raw[8];
            int ok = parse_value(t, f, raw);
            if (ok <= 0)
                return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, line, (long long)(t.s - (const char *)r->data),
                                "line %ld: point %zu, field '%.*s': '%.*s' is %s type %c%u", line, i, show(f->name),
                                f->name.s, show(t), t.s, ok < 0 ? "out of range for" : "not a number of", f->type, f->size);
            store(r, f, k, i, raw);
        }
    }
    return PNPR_OK;
}

static pnpr_status read_ascii(const pcd_reader *r)
{
    const char *p = (const char *)r->data + r->h->body, *end = (const char *)r->data + r->size;
    long line = r->h->body_line;
    for (size_t i = 0; i < r->h->n; line++) {
        if (p >= end)
            return pnpr_io_fail(r->err, PNPR_ERR_TRUNCATED, line, (long long)r->size,
                            "line %ld: the data ends after %zu of %zu points",
                            line, i, r->h->n);
        const char *nl = memchr(p, '\n', (size_t)(end - p)), *le = nl ? nl : end, *ls = p, *q = p;
        pcd_tok t;
        p = nl ? nl + 1 : end;
        if (!pnpr_token_next(&q, le, &t)) continue; /* blank line */
        if (i % PCD_CHUNK == 0 && pnpr_progress_report(r->progress, "read pcd", (double)i / (double)r->h->n))
            return cancelled(r, i);
        pnpr_status st = ascii_point(r, i++, ls, le, line);
        if (st != PNPR_OK) return st;
    }
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* The cloud                                                                                   */

static pnpr_type prop_type(const pcd_field *f)
{
    if (f->type == 'F') return f->size == 4 ? PNPR_TYPE_FLOAT32 : PNPR_TYPE_FLOAT64;
    switch (f->size) {
    case 1: return f->type == 'I' ? PNPR_TYPE_INT8 : PNPR_TYPE_UINT8;
    case 2: return f->type == 'I' ? PNPR_TYPE_INT16 : PNPR_TYPE_UINT16;
    case 4: return f->type == 'I' ? PNPR_TYPE_INT32 : PNPR_TYPE_UINT32;
    default: return PNPR_TYPE_FLOAT64;
    }
}

static pnpr_status add_props(const pcd_header *h, pnpr_cloud *c, pnpr_error *err)
{
    for (size_t j = 0; j < h->nfields; j++) {
        const pcd_field *f = &h->fields[j];
        for (uint32_t k = 0; f->role == ROLE_EXTRA && k < f->count; k++) {
            char name[sizeof(((pnpr_property *)0)->name)];
            const int cut = (int)(f->name.n < sizeof name - 1 ? f->name.n : sizeof name - 1);
            if (f->count == 1) snprintf(name, sizeof name, "%.*s", cut, f->name.s);
            else snprintf(name, sizeof name, "%.*s_%lu", cut > 50 ? 50 : cut, f->name.s, (unsigned long)k);
            if (pnpr_cloud_find_property(c, name))
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, h->line[KW_FIELDS], -1,
                                "line %ld: field '%.*s' gives the property name '%s' twice", h->line[KW_FIELDS], show(f->name),
                                f->name.s, name);
            pnpr_status st = pnpr_cloud_add_property(c, name, prop_type(f), NULL);
            if (st != PNPR_OK) return pnpr_io_fail(err, st, 0, -1, "read pcd: cannot allocate property '%s'", name);
        }
    }
    return PNPR_OK;
}

static pnpr_status prepare_cloud(const pcd_header *h, pnpr_cloud *c, pnpr_error *err)
{
    pnpr_status st = pnpr_cloud_alloc(c, h->n);
    if (st == PNPR_OK && h->has_normal) st = pnpr_cloud_alloc_normals(c);
    if (st == PNPR_OK && h->has_rgb) st = pnpr_cloud_alloc_rgb(c);
    if (st == PNPR_OK && h->has_label) st = pnpr_cloud_alloc_labels(c);
    if (st == PNPR_OK && h->double_xyz) st = pnpr_cloud_alloc_src_xyz(c);
    if (st != PNPR_OK) return pnpr_io_fail(err, st, 0, -1, "read pcd: cannot allocate %zu points", h->n);
    return add_props(h, c, err);
}

static pnpr_status finish_cloud(const pcd_header *h, pnpr_cloud *c, pnpr_error *err)
{
    if (h->line[KW_VIEWPOINT]) {
        c->has_viewpoint = 1;
        memcpy(c->viewpoint, h->vp, sizeof c->viewpoint);
    }
    c->src_coord_type = h->double_xyz ? PNPR_TYPE_FLOAT64 : PNPR_TYPE_FLOAT32;
    if (!h->double_xyz) return PNPR_OK;
    pnpr_status st = pnpr_cloud_set_world(c, c->src_xyz);
    return st == PNPR_OK ? st : pnpr_io_fail(err, st, 0, -1, "read pcd: cannot set the coordinates");
}

pnpr_status pnpr_read_pcd_memory(const void *data, size_t size, const pnpr_read_options *opts, pnpr_cloud *cloud,
                                 pnpr_error *err)
{
    if (err) { err->message[0] = '\0'; err->line = 0; err->offset = -1; }
    if (!cloud || (!data && size))
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "read pcd: NULL cloud or data");
    pnpr_cloud_free(cloud);
    if (pnpr_io_no_filter(opts, err, "read pcd") != PNPR_OK) return PNPR_ERR_UNSUPPORTED;
    pcd_header h;
    pnpr_cloud c;
    memset(&h, 0, sizeof h);
    memset(&c, 0, sizeof c);
    pcd_reader r = {data ? data : "", size, &h, &c, opts ? &opts->progress : NULL, err};
    pnpr_status st = parse_header(r.data, size, &h, err);
    if (st == PNPR_OK) st = prepare_cloud(&h, &c, err);
    if (st == PNPR_OK)
        st = h.data == DATA_ASCII ? read_ascii(&r) : h.data == DATA_BINARY ? store_points(&r, r.data + h.body, 0)
                                                                           : read_compressed(&r);
    if (st == PNPR_OK) st = finish_cloud(&h, &c, err);
    if (st == PNPR_OK && pnpr_progress_report(r.progress, "read pcd", 1.0)) st = cancelled(&r, h.n);
    free(h.fields);
    if (st != PNPR_OK) {
        pnpr_cloud_free(&c);
        return st;
    }
    *cloud = c;
    return PNPR_OK;
}

pnpr_status pnpr_read_pcd_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud, pnpr_error *err)
{
    if (!path || !cloud) return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "read pcd: NULL path or cloud");
    return pnpr_file_bytes_read(path, pnpr_read_pcd_memory, opts, cloud, err);
}

/* ------------------------------------------------------------------------------------------ */
/* Writer                                                                                      */

typedef pnpr_out_buf pcd_out;

static void out_le(pcd_out *o, uint64_t v, unsigned size)
{
    unsigned char b[8];
    wr_le(b, v, size);
    pnpr_out_bytes(o, b, size);
}

/* A double in the "C" form, exact (17 significant digits). */
static void out_double(pcd_out *o, double v)
{
    char s[40];
    snprintf(s, sizeof s, "%.17g", v);
    const struct lconv *lc = localeconv();
    char dp = lc && lc->decimal_point && lc->decimal_point[0] ? lc->decimal_point[0] : '.';
    char *c = dp != '.' ? strchr(s, dp) : NULL;
    if (c) *c = '.';
    pnpr_out_str(o, s);
}

/* The writer's columns (see the top of the file). */
enum pcd_col_kind { COL_X, COL_NX, COL_RGB, COL_LABEL, COL_PROP };

typedef struct pcd_col {
    const char *name;
    char type;
    unsigned size;
    int kind;
    size_t index; /* axis (COL_X, COL_NX) or extra property */
} pcd_col;

typedef struct pcd_plan {
    pcd_col *cols;
    size_t ncols;
    int use_double;
} pcd_plan;

static int pcd_name_ok(const char *s)
{
    if (!*s || !strcmp(s, "_")) return 0;
    for (; *s; s++)
        if ((unsigned char)*s <= 0x20 || (unsigned char)*s == 0x7f) return 0;
    return 1;
}

static int coords_need_double(const pnpr_cloud *c, const pnpr_write_options *opts)
{
    if (c->src_xyz || c->src_coord_type == PNPR_TYPE_FLOAT64 || (opts && opts->force_double)) return 1;
    if (c->src_coord_type != PNPR_TYPE_NONE || (c->origin[0] == 0 && c->origin[1] == 0 && c->origin[2] == 0)) return 0;
    for (size_t i = 0; i < 3 * c->count; i++) {
        double w = c->origin[i % 3] + (double)c->xyz[i];
        if (w == w && (double)pcd_d2f(w) != w) return 1;
    }
    return 0;
}

static void add_col(pcd_plan *pl, const char *name, char type, unsigned size, int kind, size_t index)
{
    pcd_col col = {name, type, size, kind, index};
    pl->cols[pl->ncols++] = col;
}

static void prop_code(pnpr_type t, char *r_type)
{
    *r_type = t == PNPR_TYPE_FLOAT32 || t == PNPR_TYPE_FLOAT64 ? 'F'
              : t == PNPR_TYPE_INT8 || t == PNPR_TYPE_INT16 || t == PNPR_TYPE_INT32 ? 'I' : 'U';
}

/* x y z, normals, colour, labels: the names a cloud's standard arrays take. */
static void standard_cols(const pnpr_cloud *c, pcd_plan *pl)
{
    static const char *const xyz[3] = {"x", "y", "z"}, *const nrm[3] = {"normal_x", "normal_y", "normal_z"};
    for (size_t a = 0; a < 3; a++) add_col(pl, xyz[a], 'F', pl->use_double ? 8 : 4, COL_X, a);
    for (size_t a = 0; c->normal && a < 3; a++) add_col(pl, nrm[a], 'F', 4, COL_NX, a);
    if (c->rgb && !pnpr_cloud_find_property(c, "rgb")) add_col(pl, "rgb", 'F', 4, COL_RGB, 0);
    else if (c->rgb && !pnpr_cloud_find_property(c, "rgba")) add_col(pl, "rgba", 'U', 4, COL_RGB, 0);
    if (c->label && !pnpr_cloud_find_property(c, PNPR_PROP_LABEL)) add_col(pl, PNPR_PROP_LABEL, 'U', 4, COL_LABEL, 0);
    else if (c->label && !pnpr_cloud_find_property(c, PNPR_PROP_SEGMENT)) add_col(pl, PNPR_PROP_SEGMENT, 'U', 4, COL_LABEL, 0);
}

static int has_kind(const pcd_plan *pl, int kind)
{
    for (size_t j = 0; j < pl->ncols; j++)
        if (pl->cols[j].kind == kind) return 1;
    return 0;
}

static pnpr_status check_prop(const pnpr_cloud *c, const pcd_plan *pl, size_t k, pnpr_error *err)
{
    const pnpr_property *p = &c->props[k];
    if (!memchr(p->name, '\0', sizeof p->name) || !pcd_name_ok(p->name))
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1,
                        "write pcd: extra property %zu has an empty name, \"_\" or a name with blanks", k);
    if (pnpr_type_size(p->type) == 0 || (c->count && !p->data))
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1,
                        "write pcd: extra property '%s' has no type or data", p->name);
    for (size_t j = 0; j < pl->ncols; j++)
        if (!strcmp(p->name, pl->cols[j].name))
            return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1,
                            "write pcd: extra property '%s' clashes with another field",
                            p->name);
    return PNPR_OK;
}

static pnpr_status plan_columns(const pnpr_cloud *c, const pnpr_write_options *opts, pcd_plan *pl, pnpr_error *err)
{
    pl->cols = malloc((8 + c->prop_count) * sizeof *pl->cols);
    if (!pl->cols) return pnpr_io_fail(err, PNPR_ERR_OUT_OF_MEMORY, 0, -1, "write pcd: out of memory");
    pl->use_double = coords_need_double(c, opts);
    standard_cols(c, pl);
    const int no_rgb = c->rgb && !has_kind(pl, COL_RGB), no_label = c->label && !has_kind(pl, COL_LABEL);
    if (no_rgb || no_label)
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "write pcd: extra properties take every name for the %s",
                        no_rgb ? "colours (rgb, rgba)" : "labels (label, segment)");
    for (size_t k = 0; k < c->prop_count; k++) {
        pnpr_status st = check_prop(c, pl, k, err);
        if (st != PNPR_OK) return st;
        char t;
        prop_code(c->props[k].type, &t);
        add_col(pl, c->props[k].name, t, (unsigned)pnpr_type_size(c->props[k].type), COL_PROP, k);
    }
    return PNPR_OK;
}

static void out_header(pcd_out *o, const pnpr_cloud *c, const pcd_plan *pl)
{
    char s[96];
    pnpr_out_str(o, "# .PCD v0.7 - Point Cloud Data file format\n# generated by pointnpr " PNPR_VERSION_STRING "\nVERSION 0.7\n");
    for (int row = 0; row < 4; row++) {
        pnpr_out_str(o, row == 0 ? "FIELDS" : row == 1 ? "SIZE" : row == 2 ? "TYPE" : "COUNT");
        for (size_t j = 0; j < pl->ncols; j++) {
            const pcd_col *col = &pl->cols[j];
            if (row == 0) { pnpr_out_str(o, " "); pnpr_out_str(o, col->name); continue; }
            snprintf(s, sizeof s, row == 1 ? " %u" : row == 2 ? " %c" : " 1", row == 1 ? col->size : (unsigned)col->type);
            pnpr_out_str(o, s);
        }
        pnpr_out_str(o, "\n");
    }
    snprintf(s, sizeof s, "WIDTH %zu\nHEIGHT 1\n", c->count);
    pnpr_out_str(o, s);
    if (c->has_viewpoint) {
        pnpr_out_str(o, "VIEWPOINT");
        for (int a = 0; a < 3; a++) { pnpr_out_str(o, " "); out_double(o, c->viewpoint[a]); }
        pnpr_out_str(o, " 1 0 0 0\n");
    }
    snprintf(s, sizeof s, "POINTS %zu\nDATA binary\n", c->count);
    pnpr_out_str(o, s);
}

/* The bits of element i of a native-order array of `size`-byte values. */
static uint64_t native_bits(const void *data, size_t i, unsigned size)
{
    const unsigned char *p = (const unsigned char *)data + i * size;
    uint8_t u8;
    uint16_t u16;
    uint32_t u32;
    uint64_t u64;
    switch (size) {
    case 1: memcpy(&u8, p, 1); return u8;
    case 2: memcpy(&u16, p, 2); return u16;
    case 4: memcpy(&u32, p, 4); return u32;
    default: memcpy(&u64, p, 8); return u64;
    }
}

static uint64_t coord_bits(const pnpr_cloud *c, int use_double, size_t i, size_t a)
{
    if (use_double) {
        double w = c->src_xyz ? c->src_xyz[3 * i + a] : c->origin[a] + (double)c->xyz[3 * i + a];
        return native_bits(&w, 0, 8);
    }
    float f = c->origin[a] == 0 ? c->xyz[3 * i + a] : pcd_d2f(c->origin[a] + (double)c->xyz[3 * i + a]);
    return native_bits(&f, 0, 4);
}

static void out_point(pcd_out *o, const pnpr_cloud *c, const pcd_plan *pl, size_t i)
{
    for (size_t j = 0; j < pl->ncols; j++) {
        const pcd_col *col = &pl->cols[j];
        uint64_t v = 0;
        switch (col->kind) {
        case COL_X: v = coord_bits(c, pl->use_double, i, col->index); break;
        case COL_NX: v = native_bits(c->normal, 3 * i + col->index, 4); break;
        case COL_RGB:
            v = (col->type == 'U' ? 0xFF000000u : 0u) | (uint32_t)c->rgb[3 * i] << 16 | (uint32_t)c->rgb[3 * i + 1] << 8 |
                c->rgb[3 * i + 2];
            break;
        case COL_LABEL: v = c->label[i]; break;
        default: v = native_bits(c->props[col->index].data, i, col->size); break;
        }
        out_le(o, v, col->size);
    }
}

pnpr_status pnpr_write_pcd_stream(pnpr_write_fn fn, void *user, const pnpr_cloud *cloud, const pnpr_write_options *opts,
                                  pnpr_error *err)
{
    const pnpr_progress *progress = opts ? &opts->progress : NULL;
    if (err) { err->message[0] = '\0'; err->line = 0; err->offset = -1; }
    if (!fn || !cloud || (cloud->count && !cloud->xyz) || (cloud->prop_count && !cloud->props))
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "write pcd: NULL sink, cloud, coordinates or properties");
    pcd_plan pl = {NULL, 0, 0};
    pcd_out o = {fn, user, NULL, 0, 0, 0};
    pnpr_status st = plan_columns(cloud, opts, &pl, err);
    if (st == PNPR_OK && !(o.buf = malloc(PNPR_OUT_BUF)))
        st = pnpr_io_fail(err, PNPR_ERR_OUT_OF_MEMORY, 0, -1, "write pcd: out of memory");
    if (st == PNPR_OK) out_header(&o, cloud, &pl);
    for (size_t i = 0; st == PNPR_OK && i < cloud->count && !o.failed; i++) {
        if (i % PCD_CHUNK == 0 && pnpr_progress_report(progress, "write pcd", (double)i / (double)cloud->count))
            st = pnpr_io_fail(err, PNPR_ERR_CANCELLED, 0, -1, "write pcd: cancelled at point %zu of %zu", i, cloud->count);
        else out_point(&o, cloud, &pl, i);
    }
    if (st == PNPR_OK) pnpr_out_flush(&o);
    if (st == PNPR_OK && o.failed)
        st = pnpr_io_fail(err, PNPR_ERR_IO, 0, (long long)o.written,
                      "write pcd: the output sink failed after %llu bytes", o.written);
    if (st == PNPR_OK && pnpr_progress_report(progress, "write pcd", 1.0))
        st = pnpr_io_fail(err, PNPR_ERR_CANCELLED, 0, -1, "write pcd: cancelled");
    free(o.buf);
    free(pl.cols);
    return st;
}

pnpr_status pnpr_write_pcd_file(const char *path, const pnpr_cloud *cloud, const pnpr_write_options *opts, pnpr_error *err)
{
    return pnpr_io_write_path(path, cloud, opts, err, "write pcd", pnpr_write_pcd_stream);
}
