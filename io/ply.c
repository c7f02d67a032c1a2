/* pointnpr — io/ply.c: PLY reader and writer (plain C11, no external libraries).
 *
 * READING (pnpr_read_ply_memory, pnpr_read_ply_file)
 *  - Formats: "ascii 1.0", "binary_little_endian 1.0", "binary_big_endian 1.0".
 *  - Header: "comment" and "obj_info" lines are ignored; LF or CRLF line ends; blank lines are
 *    tolerated; at most 65536 elements and 4096 properties per element. Scalar types:
 *    char/int8 uchar/uint8 short/int16 ushort/uint16 int/int32 uint/uint32 float/float32
 *    double/float64; lists need an integer count type.
 *  - Elements may come in any order. "vertex" is required; "face" is read (see below); every
 *    other element (edge, material, ...) is skipped, lists included, in all three encodings.
 *  - Vertex properties, any order and any scalar type:
 *      x y z (required)       coordinates. If any of them is double, int or uint the cloud keeps
 *                             the exact values in src_xyz (src_coord_type = FLOAT64) and the
 *                             float offsets come from pnpr_cloud_set_world (origin = bbox
 *                             centre). Otherwise (float, or small integer types) the origin is 0
 *                             and xyz holds the values (floats bit for bit), src_xyz = NULL,
 *                             src_coord_type = FLOAT32. NaN/Inf are accepted as read.
 *      nx ny nz               normals (float), only when all three are present.
 *      red green blue         colours, only when all three are present; the first complete
 *                             triple of red/green/blue, diffuse_red/diffuse_green/diffuse_blue,
 *                             r/g/b is used (the others are kept as extra properties).
 *                             uchar: as is; ushort: (v*255+32767)/65535; float/double: v in
 *                             [0,1] times 255, rounded and clamped (NaN -> 0); char: the byte
 *                             itself (-1 -> 255); short/int/uint: clamped to [0,255].
 *                             The source colour type is not remembered (the writer uses uchar).
 *      label or segment       the first one of integer type -> cloud->label (uint32; negative
 *                             values wrap, -1 -> 4294967295). Float labels stay extra properties.
 *      anything else          kept as an extra property with its own type (names longer than
 *                             63 bytes are cut to 63). List properties in the vertex element are
 *                             skipped with their data and not kept.
 *  - Face element "face": the first list property named vertex_indices or vertex_index (any
 *    integer count type, any index type; float indices must be integral) goes to cloud->faces;
 *    every index must be < the vertex count. Other face properties are skipped.
 *  - Ascii bodies: one element per line (blank lines skipped), numbers as accepted by strtod
 *    ("1e-5", "-0", "nan", "inf", ...) with a fast exact path for ordinary decimals; floats are
 *    rounded once (correctly) to float. Integer properties take integers (or integral decimals)
 *    inside the type's range. Data after the last element is ignored.
 *  - Errors name the line (header, ascii) or byte offset (binary), what was expected and what
 *    was found; err->line / err->offset are set accordingly. Element indices in messages are
 *    0-based ("vertex 0" is the first). A body shorter than announced gives PNPR_ERR_TRUNCATED,
 *    anything malformed PNPR_ERR_FORMAT. Counts are checked against the bytes present before
 *    anything is allocated: binary bodies need their exact size (lists: at least their counts),
 *    ascii bodies 2 bytes a value ("0 0 1\n"; a line an item for elements read for nothing).
 *    An ascii body of at most 64 KiB that falls short is parsed anyway, storing nothing, so that
 *    the error names the line. Every size computation is overflow-checked. On error the cloud is
 *    left zeroed.
 *  - pnpr_read_ply_file maps the file (io/file_bytes.h) and parses the mapping: a header that
 *    announces more than the file holds fails having read the header's pages only.
 *  - Progress stage "read ply", about every 1% of the vertices; cancelling gives
 *    PNPR_ERR_CANCELLED.
 *
 * WRITING (pnpr_write_ply_stream, pnpr_write_ply_file)
 *  - Encodings from opts->encoding: binary little endian (default), ascii, binary big endian.
 *  - Vertex: x y z as double when cloud->src_xyz, src_coord_type == FLOAT64 or
 *    opts->force_double (values: pnpr_cloud_world, exact), else as float (origin + xyz; exact for
 *    float sources). A cloud of unknown coordinate type (NONE) whose origin + xyz is not exactly a
 *    float is written as double too, so that nothing is lost silently.
 *    Then nx ny nz (float) if normals, red green blue (uchar) if colours (diffuse_* or r g b when
 *    an extra property already uses those names), "uint segment" if labels ("label" if an extra
 *    is named segment), then the extra properties in cloud order with their own types.
 *  - Face element "face" with "property list uchar uint vertex_indices" (list uint uint when a
 *    face has more than 255 corners) if cloud->faces.count.
 *  - Ascii numbers round trip exactly: floats with 9 significant digits (the text of "%.9g"), doubles with
 *    the 15-digit form when it reads back identically, else 17 digits (as "%.17g"); "nan", "inf",
 *    "-inf". Both are produced by exact integer arithmetic for ordinary magnitudes.
 *  - Header comments: opts->comment (control characters replaced by spaces) and
 *    "comment generated by pointnpr <version>".
 *  - pnpr_write_ply_file writes path + ".tmp" and renames it, so a failed write leaves no half
 *    file. Progress stage "write ply".
 *
 * Numbers are written and read in the "C" form whatever LC_NUMERIC says.
 */
#include "../core/internal.h"
#include <pointnpr/output.h>
#include "file_bytes.h"
#include "io_util.h"
#include "out_buf.h"
#include "text_token.h"
#include <pointnpr/io.h>

#include <errno.h>
#include <float.h>
#include <locale.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Exported beyond io.h (io/io.c declares them itself and dispatches to them):
 * read a whole PLY file (errors are prefixed with the path) and write one atomically. */
pnpr_status pnpr_read_ply_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                               pnpr_error *err);
pnpr_status pnpr_write_ply_file(const char *path, const pnpr_cloud *cloud,
                                const pnpr_write_options *opts, pnpr_error *err);

/* ------------------------------------------------------------------------------------------ */
/* Small helpers                                                                               */


#define PLY_MAX_PROPS 4096        /* properties per element */
#define PLY_MAX_ELEMS 65536       /* elements per header */
#define PLY_NAME_SHOW 64          /* longest name quoted in a message */
#define PLY_TOKEN_MAX 256         /* longest ascii number token */

static int host_is_little(void)
{
    const uint16_t one = 1;
    uint8_t b;
    memcpy(&b, &one, 1);
    return b == 1;
}

/* Stores a double into a float without relying on out-of-range conversion behaviour. */
static float d2f(double v)
{
    if (v != v) return (float)v;
    if (v >= 0x1.ffffffp127) return INFINITY;   /* rounds to +inf */
    if (v <= -0x1.ffffffp127) return -INFINITY;
    if (v > FLT_MAX) return FLT_MAX;
    if (v < -FLT_MAX) return -FLT_MAX;
    return (float)v;
}

typedef pnpr_token ply_str;

static int show_len(ply_str a)
{
    return (int)(a.n > PLY_NAME_SHOW ? PLY_NAME_SHOW : a.n);
}

static pnpr_type type_from_name(ply_str t)
{
    static const struct { const char *name; pnpr_type type; } names[] = {
        {"char", PNPR_TYPE_INT8},     {"int8", PNPR_TYPE_INT8},
        {"uchar", PNPR_TYPE_UINT8},   {"uint8", PNPR_TYPE_UINT8},
        {"short", PNPR_TYPE_INT16},   {"int16", PNPR_TYPE_INT16},
        {"ushort", PNPR_TYPE_UINT16}, {"uint16", PNPR_TYPE_UINT16},
        {"int", PNPR_TYPE_INT32},     {"int32", PNPR_TYPE_INT32},
        {"uint", PNPR_TYPE_UINT32},   {"uint32", PNPR_TYPE_UINT32},
        {"float", PNPR_TYPE_FLOAT32}, {"float32", PNPR_TYPE_FLOAT32},
        {"double", PNPR_TYPE_FLOAT64}, {"float64", PNPR_TYPE_FLOAT64},
    };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (pnpr_token_is(t, names[i].name)) return names[i].type;
    return PNPR_TYPE_NONE;
}

static int type_is_int(pnpr_type t)
{
    return t >= PNPR_TYPE_INT8 && t <= PNPR_TYPE_UINT32;
}

static void type_range(pnpr_type t, double *lo, double *hi)
{
    switch (t) {
    case PNPR_TYPE_INT8: *lo = -128.0; *hi = 127.0; break;
    case PNPR_TYPE_UINT8: *lo = 0.0; *hi = 255.0; break;
    case PNPR_TYPE_INT16: *lo = -32768.0; *hi = 32767.0; break;
    case PNPR_TYPE_UINT16: *lo = 0.0; *hi = 65535.0; break;
    case PNPR_TYPE_INT32: *lo = -2147483648.0; *hi = 2147483647.0; break;
    case PNPR_TYPE_UINT32: *lo = 0.0; *hi = 4294967295.0; break;
    default: *lo = -INFINITY; *hi = INFINITY; break;
    }
}

/* ------------------------------------------------------------------------------------------ */
/* Header model                                                                                */

enum ply_encoding_ { PLY_ENC_NONE = 0, PLY_ENC_ASCII, PLY_ENC_LE, PLY_ENC_BE };

/* What a property's values become. */
enum ply_role {
    ROLE_SKIP = 0,
    ROLE_X, ROLE_Y, ROLE_Z,
    ROLE_NX, ROLE_NY, ROLE_NZ,
    ROLE_R, ROLE_G, ROLE_B,
    ROLE_LABEL,
    ROLE_EXTRA,
    ROLE_FACE /* the vertex index list of the face element */
};

typedef struct ply_prop {
    ply_str name;
    pnpr_type type;       /* scalar type, or the item type of a list */
    pnpr_type count_type; /* list count type; NONE for a scalar */
    long line;            /* header line */
    int role;
    size_t offset;        /* offset inside a fixed-size binary record */
    void *dst;            /* extra property data (ROLE_EXTRA) */
} ply_prop;

typedef struct ply_elem {
    ply_str name;
    uint64_t count;
    long line;
    ply_prop *props;
    size_t nprops, cap;
    int has_list;
    size_t min_size;      /* binary bytes per item, lists counted as their count only */
} ply_elem;

typedef struct ply_header {
    int encoding;
    ply_elem *elems;
    size_t nelems, cap;
    size_t body;          /* byte offset of the body */
    long body_line;       /* line number of the first body line */
    ply_elem *vertex, *face;
} ply_header;

static void header_free(ply_header *h)
{
    for (size_t i = 0; i < h->nelems; i++) free(h->elems[i].props);
    free(h->elems);
    memset(h, 0, sizeof *h);
}

/* Splits [s, e) into blank-separated tokens; returns the number of tokens (stores at most max). */
static size_t tokenize(const char *s, const char *e, ply_str *tok, size_t max)
{
    size_t n = 0;
    while (s < e) {
        while (s < e && pnpr_is_blank(*s)) s++;
        if (s >= e) break;
        const char *b = s;
        while (s < e && !pnpr_is_blank(*s)) s++;
        if (n < max) { tok[n].s = b; tok[n].n = (size_t)(s - b); }
        n++;
    }
    return n;
}

/* Parses a non-negative decimal count; 0 on failure. */
static int parse_count(ply_str t, uint64_t *out)
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

static pnpr_status parse_header(const char *data, size_t size, ply_header *h, pnpr_error *err)
{
    size_t pos = 0;
    long line = 0;
    int have_end = 0, seen_vertex = 0, seen_face = 0;

    if (size < 3 || memcmp(data, "ply", 3) != 0 || (size > 3 && data[3] != '\n' && !pnpr_is_blank(data[3])))
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, 1, 0, "line 1: expected 'ply' magic");

    while (pos < size && !have_end) {
        const char *ls = data + pos;
        const char *nl = memchr(ls, '\n', size - pos);
        const char *le = nl ? nl : data + size;
        size_t line_off = pos;
        ply_str tok[8];
        size_t nt;

        line++;
        pos = (size_t)(le - data) + (nl ? 1 : 0);
        nt = tokenize(ls, le, tok, 8);
        if (line == 1) {
            if (nt != 1 || !pnpr_token_is(tok[0], "ply"))
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, 1, 0, "line 1: expected 'ply' magic");
            continue;
        }
        if (nt == 0) continue; /* blank line */
        if (pnpr_token_is(tok[0], "comment") || pnpr_token_is(tok[0], "obj_info")) continue;
        for (const char *c = ls; c < le; c++) {
            unsigned char u = (unsigned char)*c;
            if ((u < 0x20 && !pnpr_is_blank(*c)) || u == 0x7f)
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)(c - data),
                               "line %ld: invalid character 0x%02x in header", line, u);
        }
        if (pnpr_token_is(tok[0], "format")) {
            if (h->encoding)
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: second 'format' line", line);
            if (nt != 3)
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'", line);
            if (pnpr_token_is(tok[1], "ascii")) h->encoding = PLY_ENC_ASCII;
            else if (pnpr_token_is(tok[1], "binary_little_endian")) h->encoding = PLY_ENC_LE;
            else if (pnpr_token_is(tok[1], "binary_big_endian")) h->encoding = PLY_ENC_BE;
            else
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: unknown format '%.*s' (expected ascii, binary_little_endian or binary_big_endian)",
                               line, show_len(tok[1]), tok[1].s);
            if (!pnpr_token_is(tok[2], "1.0") && !pnpr_token_is(tok[2], "1"))
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: unsupported PLY version '%.*s' (expected 1.0)", line,
                               show_len(tok[2]), tok[2].s);
        } else if (pnpr_token_is(tok[0], "element")) {
            ply_elem *e;
            if (nt != 3)
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: expected 'element <name> <count>'", line);
            uint64_t count;
            if (!parse_count(tok[2], &count))
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: element '%.*s' has a negative/invalid count '%.*s'", line,
                               show_len(tok[1]), tok[1].s, show_len(tok[2]), tok[2].s);
            if ((pnpr_token_is(tok[1], "vertex") && seen_vertex++) || (pnpr_token_is(tok[1], "face") && seen_face++))
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: second '%.*s' element", line, show_len(tok[1]), tok[1].s);
            if (h->nelems >= PLY_MAX_ELEMS)
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: more than %d elements in the header", line, PLY_MAX_ELEMS);
            if (h->nelems == h->cap) {
                size_t cap = h->cap ? 2 * h->cap : 4;
                ply_elem *grown = realloc(h->elems, cap * sizeof *grown);
                if (!grown) return pnpr_io_fail(err, PNPR_ERR_OUT_OF_MEMORY, line, -1, "out of memory");
                h->elems = grown;
                h->cap = cap;
            }
            e = &h->elems[h->nelems++];
            memset(e, 0, sizeof *e);
            e->name = tok[1];
            e->count = count;
            e->line = line;
        } else if (pnpr_token_is(tok[0], "property")) {
            ply_elem *e = h->nelems ? &h->elems[h->nelems - 1] : NULL;
            ply_prop p;
            memset(&p, 0, sizeof p);
            p.line = line;
            if (!e)
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: 'property' before any 'element'", line);
            if (nt >= 2 && pnpr_token_is(tok[1], "list")) {
                if (nt != 5)
                    return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                                   "line %ld: expected 'property list <count type> <item type> <name>'", line);
                p.count_type = type_from_name(tok[2]);
                p.type = type_from_name(tok[3]);
                p.name = tok[4];
                if (!p.count_type)
                    return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                                   "line %ld: unknown property type '%.*s'", line, show_len(tok[2]), tok[2].s);
                if (!p.type)
                    return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                                   "line %ld: unknown property type '%.*s'", line, show_len(tok[3]), tok[3].s);
                if (!type_is_int(p.count_type))
                    return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                                   "line %ld: list count type must be an integer type, found '%.*s'", line,
                                   show_len(tok[2]), tok[2].s);
            } else {
                if (nt != 3)
                    return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                                   "line %ld: expected 'property <type> <name>'", line);
                p.type = type_from_name(tok[1]);
                p.name = tok[2];
                if (!p.type)
                    return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                                   "line %ld: unknown property type '%.*s'", line, show_len(tok[1]), tok[1].s);
            }
            if (e->nprops >= PLY_MAX_PROPS)
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: more than %d properties in element '%.*s'", line, PLY_MAX_PROPS,
                               show_len(e->name), e->name.s);
            if (e->nprops == e->cap) {
                size_t cap = e->cap ? 2 * e->cap : 8;
                ply_prop *grown = realloc(e->props, cap * sizeof *grown);
                if (!grown) return pnpr_io_fail(err, PNPR_ERR_OUT_OF_MEMORY, line, -1, "out of memory");
                e->props = grown;
                e->cap = cap;
            }
            if (p.count_type) {
                e->has_list = 1;
                e->min_size += pnpr_type_size(p.count_type);
            } else {
                p.offset = e->min_size;
                e->min_size += pnpr_type_size(p.type);
            }
            e->props[e->nprops++] = p;
        } else if (pnpr_token_is(tok[0], "end_header")) {
            if (nt != 1)
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                               "line %ld: unexpected text after 'end_header'", line);
            have_end = 1;
        } else {
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)line_off,
                           "line %ld: unknown header keyword '%.*s'", line, show_len(tok[0]), tok[0].s);
        }
    }
    if (!have_end)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, (long long)size, "header: no 'end_header' line");
    if (!h->encoding)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, line, -1, "header: no 'format' line");
    h->body = pos;
    h->body_line = line + 1;
    for (size_t i = 0; i < h->nelems; i++) {
        if (pnpr_token_is(h->elems[i].name, "vertex")) h->vertex = &h->elems[i];
        if (pnpr_token_is(h->elems[i].name, "face")) h->face = &h->elems[i];
    }
    if (!h->vertex)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, 0, -1, "header: no 'vertex' element");
    return PNPR_OK;
}

/* Finds a scalar (non-list) property by name; NULL if absent. */
static ply_prop *find_scalar(ply_elem *e, const char *name)
{
    for (size_t i = 0; i < e->nprops; i++)
        if (!e->props[i].count_type && pnpr_token_is(e->props[i].name, name)) return &e->props[i];
    return NULL;
}

/* Decides what each vertex and face property becomes. Sets *double_xyz. */
static pnpr_status assign_roles(ply_header *h, int *double_xyz, pnpr_error *err)
{
    ply_elem *v = h->vertex;
    static const char *const axes[3] = {"x", "y", "z"};
    static const char *const normals[3] = {"nx", "ny", "nz"};
    static const char *const colours[3][3] = {
        {"red", "green", "blue"}, {"diffuse_red", "diffuse_green", "diffuse_blue"}, {"r", "g", "b"}};

    for (size_t i = 0; i < v->nprops; i++) {
        ply_prop *p = &v->props[i];
        if (p->count_type) {
            if (pnpr_token_is(p->name, "x") || pnpr_token_is(p->name, "y") || pnpr_token_is(p->name, "z"))
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, p->line, -1,
                               "line %ld: vertex property '%.*s' must be a scalar, not a list", p->line,
                               show_len(p->name), p->name.s);
            continue;
        }
        for (size_t j = 0; j < i; j++)
            if (!v->props[j].count_type && pnpr_token_eq(v->props[j].name, p->name))
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, p->line, -1,
                               "line %ld: duplicate vertex property '%.*s'", p->line, show_len(p->name), p->name.s);
        p->role = ROLE_EXTRA;
    }
    *double_xyz = 0;
    for (int a = 0; a < 3; a++) {
        ply_prop *p = find_scalar(v, axes[a]);
        if (!p)
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, v->line, -1,
                           "line %ld: vertex element has no '%s' property (x, y and z are required)", v->line,
                           axes[a]);
        p->role = ROLE_X + a;
        if (p->type == PNPR_TYPE_FLOAT64 || p->type == PNPR_TYPE_INT32 || p->type == PNPR_TYPE_UINT32)
            *double_xyz = 1;
    }
    if (find_scalar(v, "nx") && find_scalar(v, "ny") && find_scalar(v, "nz"))
        for (int a = 0; a < 3; a++) find_scalar(v, normals[a])->role = ROLE_NX + a;
    for (int set = 0; set < 3; set++) {
        if (find_scalar(v, colours[set][0]) && find_scalar(v, colours[set][1]) && find_scalar(v, colours[set][2])) {
            for (int a = 0; a < 3; a++) find_scalar(v, colours[set][a])->role = ROLE_R + a;
            break;
        }
    }
    for (size_t i = 0; i < v->nprops; i++) {
        ply_prop *p = &v->props[i];
        if (p->role == ROLE_EXTRA && type_is_int(p->type) && (pnpr_token_is(p->name, PNPR_PROP_LABEL) || pnpr_token_is(p->name, PNPR_PROP_SEGMENT))) {
            p->role = ROLE_LABEL;
            break;
        }
    }
    if (h->face) {
        for (size_t i = 0; i < h->face->nprops; i++) {
            ply_prop *p = &h->face->props[i];
            if (p->count_type && (pnpr_token_is(p->name, "vertex_indices") || pnpr_token_is(p->name, "vertex_index"))) {
                p->role = ROLE_FACE;
                break;
            }
        }
    }
    return PNPR_OK;
}

/* Whether any property of e is stored: an ascii line of such an element is split into all its
 * values; a line of an element read for nothing is only counted. */
static int elem_is_read(const ply_elem *e)
{
    for (size_t k = 0; k < e->nprops; k++)
        if (e->props[k].role != ROLE_SKIP) return 1;
    return 0;
}

static pnpr_status ascii_short(pnpr_error *err, const ply_elem *e, size_t size, size_t avail, uint64_t need)
{
    return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, e->line, (long long)size,
                   "line %ld: element '%.*s' announces %llu items, but the ascii body has only %zu bytes "
                   "(at least %llu needed)",
                   e->line, show_len(e->name), e->name.s, (unsigned long long)e->count, avail,
                   (unsigned long long)need - 1);
}

/* Largest ascii body that fails the 2-bytes-a-value bound but is still parsed (storing nothing)
 * to name the line where it goes wrong. */
#define PLY_ASCII_PROBE ((size_t)1 << 16)

/* Ascii bodies hold an item a non-blank line: at least 2 bytes ("v\n"), and 2 bytes a value
 * ("v v v\n") when the element's values are read; the very last line may lack its newline.
 * A body short of the first bound fails here. One that holds a line an item but not the values
 * is broken or truncated inside: above PLY_ASCII_PROBE bytes it fails here too (a header that
 * lies costs nothing), smaller ones set *r_dry so that the parser finds the line. */
static pnpr_status check_ascii_size(const ply_header *h, size_t size, int probe, int *r_dry, pnpr_error *err)
{
    const size_t avail = size - h->body;
    uint64_t lines = 0, bytes = 0;
    for (size_t i = 0; i < h->nelems; i++) {
        const ply_elem *e = &h->elems[i];
        if (!e->nprops) continue; /* items without values take no text */
        lines = pnpr_add_sat(lines, pnpr_mul_sat(e->count, 2));
        if (lines > (uint64_t)avail + 1) return ascii_short(err, e, size, avail, lines);
    }
    for (size_t i = 0; i < h->nelems; i++) {
        const ply_elem *e = &h->elems[i];
        if (!e->nprops) continue;
        bytes = pnpr_add_sat(bytes, pnpr_mul_sat(e->count, elem_is_read(e) ? pnpr_mul_sat(e->nprops, 2) : 2));
        if (bytes <= (uint64_t)avail + 1) continue;
        if (probe && avail <= PLY_ASCII_PROBE) {
            *r_dry = 1;
            return PNPR_OK;
        }
        return ascii_short(err, e, size, avail, bytes);
    }
    return PNPR_OK;
}

/* Checks that the body can hold what the header announces, before anything is allocated (see
 * check_ascii_size for probe and *r_dry). */
static pnpr_status check_body_size(const ply_header *h, size_t size, int probe, int *r_dry, pnpr_error *err)
{
    const size_t avail = size - h->body;
    uint64_t cum = 0;
    *r_dry = 0;
    if (h->encoding == PLY_ENC_ASCII) return check_ascii_size(h, size, probe, r_dry, err);
    uint64_t total = 0;
    int any_list = 0;
    for (size_t i = 0; i < h->nelems; i++) {
        total = pnpr_add_sat(total, pnpr_mul_sat(h->elems[i].count, h->elems[i].min_size));
        any_list |= h->elems[i].has_list;
    }
    for (size_t i = 0; i < h->nelems; i++) {
        const ply_elem *e = &h->elems[i];
        uint64_t need = pnpr_mul_sat(e->count, e->min_size);
        if (pnpr_add_sat(cum, need) > avail) {
            if (!e->has_list && e->min_size) {
                uint64_t idx = (avail - cum) / e->min_size;
                return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, 0, (long long)size,
                               "byte %zu: file ends inside %.*s %llu of %llu (binary body needs %s%llu bytes, %zu present)",
                               size, show_len(e->name), e->name.s, (unsigned long long)idx,
                               (unsigned long long)e->count, any_list ? "at least " : "",
                               (unsigned long long)total, avail);
            }
            return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, 0, (long long)size,
                           "byte %zu: file ends inside element '%.*s' (%llu items; binary body needs at least %llu bytes, %zu present)",
                           size, show_len(e->name), e->name.s, (unsigned long long)e->count,
                           (unsigned long long)total, avail);
        }
        cum += need;
    }
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* Values                                                                                      */

static uint16_t bswap16(uint16_t v) { return (uint16_t)((v >> 8) | (v << 8)); }
static uint32_t bswap32(uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}
static uint64_t bswap64(uint64_t v)
{
    return ((uint64_t)bswap32((uint32_t)v) << 32) | bswap32((uint32_t)(v >> 32));
}

/* Reads one binary scalar: v = its value; f = the float itself for FLOAT32 (exact bits). */
static void load_value(const uint8_t *p, pnpr_type t, int swap, double *v, float *f)
{
    switch (t) {
    case PNPR_TYPE_INT8: { int8_t x; memcpy(&x, p, 1); *v = x; break; }
    case PNPR_TYPE_UINT8: *v = p[0]; break;
    case PNPR_TYPE_INT16: case PNPR_TYPE_UINT16: {
        uint16_t u; memcpy(&u, p, 2); if (swap) u = bswap16(u);
        if (t == PNPR_TYPE_UINT16) *v = u; else { int16_t x; memcpy(&x, &u, 2); *v = x; }
        break;
    }
    case PNPR_TYPE_INT32: case PNPR_TYPE_UINT32: case PNPR_TYPE_FLOAT32: {
        uint32_t u; memcpy(&u, p, 4); if (swap) u = bswap32(u);
        if (t == PNPR_TYPE_UINT32) *v = u;
        else if (t == PNPR_TYPE_INT32) { int32_t x; memcpy(&x, &u, 4); *v = x; }
        else { float x; memcpy(&x, &u, 4); *f = x; *v = x; }
        break;
    }
    case PNPR_TYPE_FLOAT64: {
        uint64_t u; memcpy(&u, p, 8); if (swap) u = bswap64(u);
        memcpy(v, &u, 8);
        break;
    }
    default: *v = 0; break;
    }
}

/* Copies one binary scalar to native order (exact bits). */
static void copy_raw(void *dst, const uint8_t *p, size_t sz, int swap)
{
    if (!swap || sz == 1) { memcpy(dst, p, sz); return; }
    if (sz == 2) { uint16_t u; memcpy(&u, p, 2); u = bswap16(u); memcpy(dst, &u, 2); }
    else if (sz == 4) { uint32_t u; memcpy(&u, p, 4); u = bswap32(u); memcpy(dst, &u, 4); }
    else { uint64_t u; memcpy(&u, p, 8); u = bswap64(u); memcpy(dst, &u, 8); }
}

static uint8_t colour8(double v, pnpr_type t)
{
    switch (t) {
    case PNPR_TYPE_UINT8: return (uint8_t)v;
    case PNPR_TYPE_INT8: return (uint8_t)(int)v; /* the byte itself: -1 -> 255 */
    case PNPR_TYPE_UINT16: return (uint8_t)(((uint32_t)v * 255u + 32767u) / 65535u);
    case PNPR_TYPE_FLOAT32: case PNPR_TYPE_FLOAT64: {
        if (!(v > 0.0)) return 0;
        v = floor(v * 255.0 + 0.5);
        return v >= 255.0 ? 255 : (uint8_t)v;
    }
    default: return v <= 0.0 ? 0 : v >= 255.0 ? 255 : (uint8_t)v;
    }
}

/* Stores an integral value already known to lie in t's range. */
static void store_typed(void *data, size_t i, pnpr_type t, double v, float f)
{
    switch (t) {
    case PNPR_TYPE_INT8: ((int8_t *)data)[i] = (int8_t)v; break;
    case PNPR_TYPE_UINT8: ((uint8_t *)data)[i] = (uint8_t)v; break;
    case PNPR_TYPE_INT16: ((int16_t *)data)[i] = (int16_t)v; break;
    case PNPR_TYPE_UINT16: ((uint16_t *)data)[i] = (uint16_t)v; break;
    case PNPR_TYPE_INT32: ((int32_t *)data)[i] = (int32_t)v; break;
    case PNPR_TYPE_UINT32: ((uint32_t *)data)[i] = (uint32_t)v; break;
    case PNPR_TYPE_FLOAT32: ((float *)data)[i] = f; break;
    case PNPR_TYPE_FLOAT64: ((double *)data)[i] = v; break;
    default: break;
    }
}

/* Reader state shared by the binary and ascii bodies. */
typedef struct ply_reader {
    const uint8_t *data;
    size_t size;
    const ply_header *h;
    pnpr_cloud *c;
    int double_xyz;
    int swap;
    const pnpr_progress *progress;
    pnpr_error *err;
    size_t index_cap;   /* capacity of c->faces.index */
    size_t nindex;      /* indices stored */
    int dry;            /* parse only to find the body's first error: nothing is stored */
    const uint8_t *kept; /* the keep filter's bit per vertex (filter_vertices), or NULL = all */
    pnpr_file_bytes *fb; /* the mapped file (pages behind the decoding handed back), or NULL */
    size_t dropped;      /* the pass over the records handed back the pages before this byte */
} ply_reader;

/* A pass over the records of a mapped file hands back the pages behind it every 64 MiB
 * (pnpr_file_bytes_drop); start: the pass begins at `at`. */
static void drop_behind(ply_reader *r, size_t at, int start)
{
    if (start) r->dropped = at;
    else if (at >= r->dropped + ((size_t)64 << 20)) {
        pnpr_file_bytes_drop(r->fb, r->dropped, at);
        r->dropped = at;
    }
}

/* Stores vertex property p of vertex i. f is meaningful for FLOAT32 properties only. */
static void store_vertex(ply_reader *r, const ply_prop *p, size_t i, double v, float f)
{
    pnpr_cloud *c = r->c;
    if (r->dry) return;
    switch (p->role) {
    case ROLE_X: case ROLE_Y: case ROLE_Z: {
        size_t k = 3 * i + (size_t)(p->role - ROLE_X);
        if (r->double_xyz) c->src_xyz[k] = v;
        else c->xyz[k] = p->type == PNPR_TYPE_FLOAT32 ? f : d2f(v);
        break;
    }
    case ROLE_NX: case ROLE_NY: case ROLE_NZ:
        c->normal[3 * i + (size_t)(p->role - ROLE_NX)] = p->type == PNPR_TYPE_FLOAT32 ? f : d2f(v);
        break;
    case ROLE_R: case ROLE_G: case ROLE_B:
        c->rgb[3 * i + (size_t)(p->role - ROLE_R)] = colour8(v, p->type);
        break;
    case ROLE_LABEL:
        c->label[i] = (uint32_t)(int64_t)v; /* integer types only: exact, negatives wrap */
        break;
    case ROLE_EXTRA:
        store_typed(p->dst, i, p->type, v, f);
        break;
    default: break;
    }
}

/* Progress countdown: every ~1% of the vertices. */
typedef struct ply_tick {
    size_t step, left;
} ply_tick;

static void tick_init(ply_tick *t, size_t count)
{
    t->step = count >= 100 ? count / 100 : 1;
    t->left = t->step;
}

/* k more vertices done (done of count in all): a report when the countdown runs out. */
static int tick_by(ply_reader *r, ply_tick *t, size_t k, size_t done, size_t count)
{
    if (t->left > k) {
        t->left -= k;
        return 0;
    }
    t->left = t->step;
    return pnpr_progress_report(r->progress, "read ply", (double)done / (double)count);
}

static int tick(ply_reader *r, ply_tick *t, size_t done, size_t count) { return tick_by(r, t, 1, done, count); }

/* Appends index v to face storage (capacity grows by doubling; the total stays < 2^32). */
static int push_index(ply_reader *r, uint32_t v)
{
    pnpr_faces *fc = &r->c->faces;
    if (r->dry) return 1;
    if (r->nindex == r->index_cap) {
        size_t cap = r->index_cap ? 2 * r->index_cap : 1024;
        if (cap > UINT32_MAX) cap = UINT32_MAX;
        if (cap <= r->nindex) return 0;
        uint32_t *grown = realloc(fc->index, cap * sizeof *grown);
        if (!grown) return 0;
        fc->index = grown;
        r->index_cap = cap;
    }
    fc->index[r->nindex++] = v;
    return 1;
}

/* ------------------------------------------------------------------------------------------ */
/* Binary body                                                                                 */

static pnpr_status cancelled(ply_reader *r, size_t i, size_t count)
{
    return pnpr_io_fail(r->err, PNPR_ERR_CANCELLED, 0, -1, "read ply: cancelled at vertex %zu of %zu", i, count);
}

/* Element without lists: records of fixed size; the vertex element is decoded in a tight loop. */
static pnpr_status binary_fixed(ply_reader *r, const ply_elem *e, size_t *pos)
{
    const size_t rs = e->min_size, avail = r->size - *pos;
    const uint64_t need = pnpr_mul_sat(e->count, rs);
    if (need > avail) {
        size_t idx = (size_t)(avail / (rs ? rs : 1));
        return pnpr_io_fail(r->err, PNPR_ERR_TRUNCATED, 0, (long long)r->size,
                       "byte %zu: file ends inside %.*s %zu of %llu (binary body needs %llu bytes from byte %zu, %zu present)",
                       r->size, show_len(e->name), e->name.s, idx, (unsigned long long)e->count,
                       (unsigned long long)need, *pos, avail);
    }
    if (e == r->h->vertex) {
        const size_t n = (size_t)e->count;
        const uint8_t *base = r->data + *pos;
        ply_prop *slots[PLY_MAX_PROPS];
        size_t ns = 0;
        ply_tick t;
        for (size_t k = 0; k < e->nprops; k++)
            if (e->props[k].role != ROLE_SKIP) slots[ns++] = &e->props[k];
        tick_init(&t, n);
        for (size_t i = 0, j = 0; i < n; i++) {
            uint64_t none = 1; /* 64 vertices from i, none kept: one step (a sample of a file ordered
                                * for drawing keeps a few runs of 200M vertices) */
            if (r->kept && (i & 63) == 0 && n - i >= 64) memcpy(&none, r->kept + (i >> 3), sizeof none);
            if (!none) {
                if ((i & 0xFFFF) == 0) drop_behind(r, *pos + i * rs, i == 0);
                if (tick_by(r, &t, 64, i + 64, n)) return cancelled(r, i + 64, n);
                i += 63;
                continue;
            }
            const uint8_t *rec = base + i * rs;
            for (size_t k = 0; k < ns && (!r->kept || (r->kept[i >> 3] >> (i & 7) & 1)); k++) {
                const ply_prop *p = slots[k];
                if (p->role == ROLE_EXTRA) {
                    size_t sz = pnpr_type_size(p->type);
                    copy_raw((uint8_t *)p->dst + j * sz, rec + p->offset, sz, r->swap);
                } else {
                    double v;
                    float f = 0.0f;
                    load_value(rec + p->offset, p->type, r->swap, &v, &f);
                    store_vertex(r, p, j, v, f);
                }
            }
            j += !r->kept || (r->kept[i >> 3] >> (i & 7) & 1);
            if ((i & 0xFFFF) == 0) drop_behind(r, *pos + i * rs, i == 0);
            if (tick(r, &t, i + 1, n)) return cancelled(r, i + 1, n);
        }
    }
    *pos += (size_t)need;
    return PNPR_OK;
}

/* Element with lists: walks every item. Handles the vertex element (lists skipped), the face
 * element (vertex index list kept) and skipped elements. */
static pnpr_status binary_lists(ply_reader *r, const ply_elem *e, size_t *pos)
{
    const int is_vertex = e == r->h->vertex, is_face = e == r->h->face;
    const size_t n = (size_t)e->count; /* fits: checked against the bytes present */
    const uint64_t vcount = r->h->vertex->count;
    pnpr_faces *fc = &r->c->faces;
    size_t p0 = *pos, cur = 0;
    ply_tick t;
    tick_init(&t, n);
    for (size_t i = 0; i < n; i++) {
        int face_done = 0;
        cur = i;
        for (size_t k = 0; k < e->nprops; k++) {
            const ply_prop *p = &e->props[k];
            const size_t sz = pnpr_type_size(p->type);
            if (!p->count_type) {
                if (r->size - p0 < sz) goto truncated;
                if (is_vertex && p->role != ROLE_SKIP) {
                    double v;
                    float f = 0.0f;
                    load_value(r->data + p0, p->type, r->swap, &v, &f);
                    store_vertex(r, p, i, v, f);
                }
                p0 += sz;
                continue;
            }
            const size_t csz = pnpr_type_size(p->count_type);
            double cv;
            float cf;
            if (r->size - p0 < csz) goto truncated;
            load_value(r->data + p0, p->count_type, r->swap, &cv, &cf);
            if (cv < 0)
                return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, 0, (long long)p0,
                               "byte %zu: %.*s %zu: negative list count %.0f for property '%.*s'", p0,
                               show_len(e->name), e->name.s, i, cv, show_len(p->name), p->name.s);
            p0 += csz;
            const uint64_t items = (uint64_t)cv, bytes = pnpr_mul_sat(items, sz);
            if (bytes > r->size - p0)
                return pnpr_io_fail(r->err, PNPR_ERR_TRUNCATED, 0, (long long)p0,
                               "byte %zu: file ends inside %.*s %zu of %zu (list '%.*s' of %llu items needs %llu bytes, %zu present)",
                               p0, show_len(e->name), e->name.s, i, n, show_len(p->name), p->name.s,
                               (unsigned long long)items, (unsigned long long)bytes, r->size - p0);
            if (is_face && p->role == ROLE_FACE && !face_done) {
                for (uint64_t j = 0; j < items; j++) {
                    double v;
                    float f;
                    load_value(r->data + p0 + j * sz, p->type, r->swap, &v, &f);
                    if (!(v >= 0 && v < (double)vcount && v == floor(v)))
                        return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, 0, (long long)(p0 + j * sz),
                                       "byte %llu: face %zu: vertex index %.17g out of range (vertex count %llu)",
                                       (unsigned long long)(p0 + j * sz), i, v, (unsigned long long)vcount);
                    if (!push_index(r, (uint32_t)v))
                        return pnpr_io_fail(r->err, PNPR_ERR_OUT_OF_MEMORY, 0, (long long)p0,
                                       "face %zu: out of memory (or more than 2^32-1 face indices)", i);
                }
                face_done = 1;
            }
            p0 += (size_t)bytes;
        }
        if (is_face && fc->offset) fc->offset[i + 1] = (uint32_t)r->nindex;
        if (is_vertex && tick(r, &t, i + 1, n)) return cancelled(r, i + 1, n);
    }
    *pos = p0;
    return PNPR_OK;
truncated:
    return pnpr_io_fail(r->err, PNPR_ERR_TRUNCATED, 0, (long long)r->size,
                   "byte %zu: file ends inside %.*s %zu of %zu (element starts at byte %zu)", r->size,
                   show_len(e->name), e->name.s, cur, n, *pos);
}

static pnpr_status read_binary(ply_reader *r)
{
    size_t pos = r->h->body;
    for (size_t i = 0; i < r->h->nelems; i++) {
        const ply_elem *e = &r->h->elems[i];
        pnpr_status st = e->has_list ? binary_lists(r, e, &pos) : binary_fixed(r, e, &pos);
        if (st != PNPR_OK) return st;
    }
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* Ascii numbers                                                                               */

static const double pow10_tab[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                     1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* strtod/strtof on a NUL-terminated copy of the token; accepts "nan", "inf", long mantissas.
 * Retries with the locale's decimal point if the C form is not accepted. */
static int parse_slow(ply_str t, int as_float, double *v, float *f)
{
    char buf[PLY_TOKEN_MAX + 1];
    char *end;
    if (t.n == 0 || t.n > PLY_TOKEN_MAX) return 0;
    for (int attempt = 0; attempt < 2; attempt++) {
        memcpy(buf, t.s, t.n);
        buf[t.n] = '\0';
        if (attempt == 1) {
            const struct lconv *lc = localeconv();
            char dp = lc && lc->decimal_point && lc->decimal_point[0] ? lc->decimal_point[0] : '.';
            char *dot = memchr(buf, '.', t.n);
            if (dp == '.' || !dot) return 0;
            *dot = dp;
        }
        if (as_float) {
            float x = strtof(buf, &end);
            if (end == buf + t.n) { *f = x; *v = x; return 1; }
        } else {
            double x = strtod(buf, &end);
            if (end == buf + t.n) { *v = x; return 1; }
        }
    }
    return 0;
}

/* Decimal token to double, correctly rounded. Fast exact path for mantissas up to 2^53 with
 * small exponents (one IEEE operation on exact operands), strtod otherwise. */
static int parse_f64(ply_str t, double *out)
{
    const char *s = t.s, *e = t.s + t.n;
    int neg = 0, digits = 0, sig = 0;
    uint64_t m = 0;
    long exp10 = 0;
    if (s < e && (*s == '-' || *s == '+')) neg = *s++ == '-';
    for (; s < e && (unsigned)(*s - '0') < 10; s++, digits++) {
        if (sig < 19) { m = m * 10 + (uint64_t)(*s - '0'); if (m) sig++; }
        else goto slow;
    }
    if (s < e && *s == '.') {
        for (s++; s < e && (unsigned)(*s - '0') < 10; s++, digits++) {
            if (sig < 19) { m = m * 10 + (uint64_t)(*s - '0'); if (m) sig++; exp10--; }
            else goto slow;
        }
    }
    if (!digits) goto slow;
    if (s < e && (*s == 'e' || *s == 'E')) {
        int eneg = 0, edigits = 0;
        long x = 0;
        s++;
        if (s < e && (*s == '-' || *s == '+')) eneg = *s++ == '-';
        for (; s < e && (unsigned)(*s - '0') < 10; s++, edigits++) {
            if (x > 100000) goto slow;
            x = x * 10 + (*s - '0');
        }
        if (!edigits) goto slow;
        exp10 += eneg ? -x : x;
    }
    if (s != e) goto slow;
    if (m == 0) { *out = neg ? -0.0 : 0.0; return 1; }
    if (m > (UINT64_C(1) << 53) || exp10 < -22 || exp10 > 22) goto slow;
    {
        double v = (double)m;
        v = exp10 >= 0 ? v * pow10_tab[exp10] : v / pow10_tab[-exp10];
        *out = neg ? -v : v;
        return 1;
    }
slow:
    {
        float f;
        return parse_slow(t, 0, out, &f);
    }
}

/* Decimal token to float, correctly rounded: the double result rounds to the right float unless
 * it sits exactly on a midpoint between two floats (or outside the normal float range). */
static int parse_f32(ply_str t, float *out)
{
    double d;
    if (!parse_f64(t, &d)) return 0;
    double a = fabs(d);
    if (a != a || a == 0.0 || a == INFINITY) { *out = (float)d; return 1; }
    if (a >= FLT_MIN && a <= FLT_MAX) {
        uint64_t bits;
        memcpy(&bits, &d, 8);
        if ((bits & 0x1FFFFFFFu) != 0x10000000u) { *out = (float)d; return 1; }
    }
    return parse_slow(t, 1, &d, out);
}

/* Integer token (or an integral decimal) inside [lo, hi].
 * 0: not a number, -1: out of range, -2: not an integer. */
static int parse_int(ply_str t, double lo, double hi, double *out)
{
    const char *s = t.s, *e = t.s + t.n;
    int neg = 0;
    uint64_t m = 0;
    if (s < e && (*s == '-' || *s == '+')) neg = *s++ == '-';
    if (s < e && e - s <= 18) {
        const char *d = s;
        for (; d < e && (unsigned)(*d - '0') < 10; d++) m = m * 10 + (uint64_t)(*d - '0');
        if (d == e) {
            double v = neg ? -(double)m : (double)m;
            if (v < lo || v > hi) return -1;
            *out = v;
            return 1;
        }
    }
    double v;
    if (!parse_f64(t, &v)) return 0;
    if (v != v) return 0;
    if (v != floor(v) && fabs(v) != INFINITY) return -2;
    if (!(v >= lo && v <= hi)) return -1;
    *out = v + 0.0; /* -0 -> 0 */
    return 1;
}

/* ------------------------------------------------------------------------------------------ */
/* Ascii body                                                                                  */

typedef struct ply_cursor {
    const char *p, *end;
    long line;       /* number of the line starting at p */
} ply_cursor;

/* Next non-blank line [*ls, *le); returns its number, or 0 at the end of the data. */
static long next_line(ply_cursor *cur, const char **ls, const char **le)
{
    while (cur->p < cur->end) {
        const char *s = cur->p;
        const char *nl = memchr(s, '\n', (size_t)(cur->end - s));
        const char *e = nl ? nl : cur->end;
        long no = cur->line++;
        cur->p = nl ? nl + 1 : cur->end;
        for (const char *c = s; c < e; c++)
            if (!pnpr_is_blank(*c)) { *ls = s; *le = e; return no; }
    }
    return 0;
}

/* One element of an ascii body: one item per non-blank line. */
static pnpr_status ascii_element(ply_reader *r, const ply_elem *e, ply_cursor *cur)
{
    const int is_vertex = e == r->h->vertex, is_face = e == r->h->face;
    const size_t n = (size_t)e->count; /* fits: checked against the bytes present */
    const uint64_t vcount = r->h->vertex->count;
    const char *base = (const char *)r->data;
    const int keep = elem_is_read(e);
    ply_tick t;
    if (e->nprops == 0) return PNPR_OK; /* items without values take no text */
    tick_init(&t, n);
    for (size_t i = 0; i < n; i++) {
        const char *ls, *le, *q;
        long line = next_line(cur, &ls, &le);
        size_t expected = 0, found = 0;
        int open = 0; /* lists ahead: the expected count is a minimum */
        ply_str tok;
        if (!line)
            return pnpr_io_fail(r->err, PNPR_ERR_TRUNCATED, cur->line, (long long)r->size,
                           "line %ld: file ends inside %.*s %zu of %zu", cur->line, show_len(e->name), e->name.s,
                           i, n);
        if (!keep) continue;
        q = ls;
        for (size_t k = 0; k < e->nprops; k++) {
            const ply_prop *p = &e->props[k];
            double v = 0;
            float f = 0;
            if (!pnpr_token_next(&q, le, &tok)) {
                expected += e->nprops - k;
                for (size_t j = k + 1; j < e->nprops; j++) open |= e->props[j].count_type != 0;
                goto too_few;
            }
            found++;
            expected++;
            if (p->count_type) {
                double lo, hi, cnt;
                int rc;
                type_range(p->count_type, &lo, &hi);
                if (lo < 0) lo = 0;
                rc = parse_int(tok, lo, hi, &cnt);
                if (rc <= 0)
                    return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, line, (long long)(tok.s - base),
                                   "%.*s %zu (line %ld): invalid list count '%.*s' for property '%.*s'",
                                   show_len(e->name), e->name.s, i, line, show_len(tok), tok.s,
                                   show_len(p->name), p->name.s);
                expected += (size_t)cnt;
                for (uint64_t j = 0; j < (uint64_t)cnt; j++) {
                    if (!pnpr_token_next(&q, le, &tok)) {
                        expected += e->nprops - 1 - k;
                        for (size_t jj = k + 1; jj < e->nprops; jj++) open |= e->props[jj].count_type != 0;
                        goto too_few;
                    }
                    found++;
                    if (is_face && p->role == ROLE_FACE) {
                        double iv;
                        int irc = parse_int(tok, 0, 4294967295.0, &iv);
                        if (irc == 0 || irc == -2)
                            return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, line, (long long)(tok.s - base),
                                           "face %zu (line %ld): invalid vertex index '%.*s'", i, line,
                                           show_len(tok), tok.s);
                        if (irc < 0 || (uint64_t)iv >= vcount)
                            return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, line, (long long)(tok.s - base),
                                           "face %zu (line %ld): vertex index %.*s out of range (vertex count %llu)",
                                           i, line, show_len(tok), tok.s, (unsigned long long)vcount);
                        if (!push_index(r, (uint32_t)iv))
                            return pnpr_io_fail(r->err, PNPR_ERR_OUT_OF_MEMORY, line, -1,
                                           "face %zu (line %ld): out of memory", i, line);
                    }
                }
                continue;
            }
            if (!is_vertex || p->role == ROLE_SKIP) continue;
            if (p->type == PNPR_TYPE_FLOAT32) {
                if (!parse_f32(tok, &f)) goto bad_number;
                v = f;
            } else if (p->type == PNPR_TYPE_FLOAT64) {
                if (!parse_f64(tok, &v)) goto bad_number;
            } else {
                double lo, hi;
                int rc;
                type_range(p->type, &lo, &hi);
                rc = parse_int(tok, lo, hi, &v);
                if (rc == 0 || rc == -2) goto bad_number;
                if (rc < 0)
                    return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, line, (long long)(tok.s - base),
                                   "%.*s %zu (line %ld): value '%.*s' out of range for %s property '%.*s'",
                                   show_len(e->name), e->name.s, i, line, show_len(tok), tok.s,
                                   pnpr_type_ply_name(p->type), show_len(p->name), p->name.s);
            }
            store_vertex(r, p, i, v, f);
            continue;
        bad_number:
            return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, line, (long long)(tok.s - base),
                           "%.*s %zu (line %ld): expected %s for %s property '%.*s', found '%.*s'",
                           show_len(e->name), e->name.s, i, line, type_is_int(p->type) ? "an integer" : "a number",
                           pnpr_type_ply_name(p->type), show_len(p->name), p->name.s, show_len(tok), tok.s);
        }
        if (pnpr_token_next(&q, le, &tok)) {
            found += 1 + pnpr_token_count(q, le);
            return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, line, (long long)(ls - base),
                           "%.*s %zu (line %ld): expected %zu values, found %zu", show_len(e->name), e->name.s, i,
                           line, expected, found);
        }
        if (is_face && r->c->faces.offset) r->c->faces.offset[i + 1] = (uint32_t)r->nindex;
        if (is_vertex && tick(r, &t, i + 1, n)) return cancelled(r, i + 1, n);
        continue;
    too_few:
        return pnpr_io_fail(r->err, PNPR_ERR_FORMAT, line, (long long)(ls - base),
                       "%.*s %zu (line %ld): expected %s%zu values, found %zu", show_len(e->name), e->name.s, i,
                       line, open ? "at least " : "", expected, found);
    }
    return PNPR_OK;
}

static pnpr_status read_ascii(ply_reader *r)
{
    ply_cursor cur;
    cur.p = (const char *)r->data + r->h->body;
    cur.end = (const char *)r->data + r->size;
    cur.line = r->h->body_line;
    for (size_t i = 0; i < r->h->nelems; i++) {
        pnpr_status st = ascii_element(r, &r->h->elems[i], &cur);
        if (st != PNPR_OK) return st;
    }
    return PNPR_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* Reader entry points                                                                         */

/* The keep filter (pnpr_read_options.keep): one pass over the vertex records' coordinates marks
 * the kept vertices in a bit set (*r_bits, count/8 bytes: 25 MB for 2e8 points) and counts them.
 * Only a binary body whose vertex records have a fixed size and start at a known byte. */
static pnpr_status filter_vertices(ply_reader *r, const pnpr_read_options *o, uint8_t **r_bits, size_t *r_kept)
{
    const ply_header *h = r->h;
    const ply_elem *v = h->vertex;
    size_t pos = h->body;
    int lists = 0; /* an element with lists before the vertices: their start is not known */
    for (size_t i = 0; i < h->nelems && &h->elems[i] != v; i++) {
        lists |= h->elems[i].has_list;
        if (!lists) pos += (size_t)h->elems[i].count * h->elems[i].min_size; /* sizes checked by check_body_size */
    }
    if (h->encoding == PLY_ENC_ASCII || v->has_list || lists)
        return pnpr_io_fail(r->err, PNPR_ERR_UNSUPPORTED, 0, -1,
                            "read ply: a point filter (a tile) needs a binary body whose vertex records have a fixed "
                            "size and follow no list element (convert it: pointnpr convert IN -o OUT.ply)");
    const ply_prop *xyz[3] = {NULL, NULL, NULL};
    for (size_t k = 0; k < v->nprops; k++)
        if (v->props[k].role >= ROLE_X && v->props[k].role <= ROLE_Z) xyz[v->props[k].role - ROLE_X] = &v->props[k];
    const size_t n = (size_t)v->count, rs = v->min_size;
    uint8_t *bits = calloc(n / 8 + 1, 1);
    if (!bits) return pnpr_io_fail(r->err, PNPR_ERR_OUT_OF_MEMORY, 0, -1, "read ply: out of memory");
    size_t kept = 0, done = 0, visits = 0;
    const uint64_t all[2] = {0, n}, *range = o->ranges ? o->ranges : all;
    const size_t groups = o->ranges ? o->range_count : 1;
    for (size_t g = 0; g < groups; g++) { /* checked before keep sees a point */
        if (range[2 * g] > range[2 * g + 1] || range[2 * g + 1] > n || (g && range[2 * g] < range[2 * g - 1])) {
            free(bits);
            return pnpr_io_fail(r->err, PNPR_ERR_INVALID_ARGUMENT, 0, -1,
                                "read ply: vertex range %zu [%llu, %llu) is not ascending within the %zu vertices", g,
                                (unsigned long long)range[2 * g], (unsigned long long)range[2 * g + 1], n);
        }
        visits += (size_t)(range[2 * g + 1] - range[2 * g]);
    }
    ply_tick t;
    tick_init(&t, visits);
    for (size_t g = 0; g < groups; g++) {
        for (size_t i = (size_t)range[2 * g]; i < (size_t)range[2 * g + 1]; i++, done++) {
            const uint8_t *rec = r->data + pos + i * rs;
            double w[3];
            float f;
            for (int a = 0; a < 3; a++) load_value(rec + xyz[a]->offset, xyz[a]->type, r->swap, &w[a], &f);
            if (o->keep(o->keep_user, i, w)) {
                bits[i >> 3] |= (uint8_t)(1u << (i & 7));
                kept++;
            }
            if ((done & 0xFFFF) == 0) drop_behind(r, pos + i * rs, done == 0);
            if (tick(r, &t, done + 1, visits)) {
                free(bits);
                return cancelled(r, done + 1, visits);
            }
        }
    }
    *r_bits = bits;
    *r_kept = kept;
    return PNPR_OK;
}

/* Allocates every cloud array the header asks for (count vertices) and points extra properties
 * at their data. */
static pnpr_status prepare_cloud(ply_reader *r, ply_header *h, size_t count, pnpr_error *err)
{
    pnpr_cloud *c = r->c;
    ply_elem *v = h->vertex;
    int has_normal = 0, has_rgb = 0, has_label = 0;
    pnpr_status st = pnpr_cloud_alloc(c, count);
    for (size_t k = 0; st == PNPR_OK && k < v->nprops; k++) {
        ply_prop *p = &v->props[k];
        has_normal |= p->role == ROLE_NX;
        has_rgb |= p->role == ROLE_R;
        has_label |= p->role == ROLE_LABEL;
        if (p->role == ROLE_EXTRA) {
            char name[sizeof(((pnpr_property *)0)->name)];
            size_t len = p->name.n < sizeof name - 1 ? p->name.n : sizeof name - 1;
            memcpy(name, p->name.s, len);
            name[len] = '\0';
            if (pnpr_cloud_find_property(c, name))
                return pnpr_io_fail(err, PNPR_ERR_FORMAT, p->line, -1,
                               "line %ld: property name '%.*s' clashes with another one once cut to %zu characters",
                               p->line, show_len(p->name), p->name.s, sizeof name - 1);
            st = pnpr_cloud_add_property(c, name, p->type, NULL);
        }
    }
    if (st == PNPR_OK && has_normal) st = pnpr_cloud_alloc_normals(c);
    if (st == PNPR_OK && has_rgb) st = pnpr_cloud_alloc_rgb(c);
    if (st == PNPR_OK && has_label) st = pnpr_cloud_alloc_labels(c);
    if (st == PNPR_OK && r->double_xyz) st = pnpr_cloud_alloc_src_xyz(c);
    if (st == PNPR_OK && h->face) {
        for (size_t k = 0; k < h->face->nprops; k++)
            if (h->face->props[k].role == ROLE_FACE) {
                if (h->face->count >= SIZE_MAX / sizeof(uint32_t) ||
                    !(c->faces.offset = calloc((size_t)h->face->count + 1, sizeof(uint32_t))))
                    st = PNPR_ERR_OUT_OF_MEMORY;
                else
                    c->faces.count = (size_t)h->face->count;
            }
    }
    if (st != PNPR_OK)
        return pnpr_io_fail(err, st, 0, -1, "read ply: cannot allocate %zu vertices (%s)", count,
                            pnpr_status_string(st));
    for (size_t k = 0, e = 0; k < v->nprops; k++)
        if (v->props[k].role == ROLE_EXTRA) v->props[k].dst = c->props[e++].data;
    return PNPR_OK;
}

static pnpr_status ply_read(const void *data, size_t size, const pnpr_read_options *opts, pnpr_cloud *cloud,
                            pnpr_error *err, pnpr_file_bytes *fb);

pnpr_status pnpr_read_ply_memory(const void *data, size_t size, const pnpr_read_options *opts,
                                 pnpr_cloud *cloud, pnpr_error *err)
{
    return ply_read(data, size, opts, cloud, err, NULL);
}

/* fb: the mapped file data lies in, or NULL. */
static pnpr_status ply_read(const void *data, size_t size, const pnpr_read_options *opts, pnpr_cloud *cloud,
                            pnpr_error *err, pnpr_file_bytes *fb)
{
    ply_header h;
    ply_reader r;
    pnpr_cloud c;
    pnpr_status st;
    uint8_t *kept = NULL;

    if (err) { err->message[0] = '\0'; err->line = 0; err->offset = -1; }
    if (!cloud || (!data && size))
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "read ply: NULL cloud or data");
    pnpr_cloud_free(cloud);
    if (size == 0)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, 1, 0, "line 1: expected 'ply' magic (empty input)");

    memset(&h, 0, sizeof h);
    memset(&c, 0, sizeof c);
    memset(&r, 0, sizeof r);
    st = parse_header((const char *)data, size, &h, err);
    if (st == PNPR_OK) st = assign_roles(&h, &r.double_xyz, err);
    if (st == PNPR_OK) st = check_body_size(&h, size, 1, &r.dry, err);
    if (st == PNPR_OK) {
        r.data = data;
        r.size = size;
        r.h = &h;
        r.c = &c;
        r.swap = (h.encoding == PLY_ENC_LE) != host_is_little();
        r.progress = opts && !r.dry ? &opts->progress : NULL;
        r.err = err;
        r.fb = fb;
        size_t count = (size_t)h.vertex->count;
        if (opts && opts->ranges && !opts->keep)
            st = pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "read ply: vertex ranges without a point filter (keep)");
        else if (!r.dry && opts && opts->keep) {
            st = filter_vertices(&r, opts, &kept, &count);
            h.face = NULL; /* a tile has no faces */
        }
        if (!r.dry && st == PNPR_OK) st = prepare_cloud(&r, &h, count, err);
        r.kept = kept;
    }
    if (st == PNPR_OK) st = h.encoding == PLY_ENC_ASCII ? read_ascii(&r) : read_binary(&r);
    if (st == PNPR_OK && r.dry) /* cannot pass (the bound is exact); if it did, the bound speaks */
        st = check_body_size(&h, size, 0, &r.dry, err);
    if (st == PNPR_OK && pnpr_progress_report(r.progress, "read ply", 1.0))
        st = cancelled(&r, c.count, c.count);
    if (st == PNPR_OK) {
        if (r.double_xyz) {
            c.src_coord_type = PNPR_TYPE_FLOAT64;
            st = opts && opts->origin ? pnpr_cloud_set_world_at(&c, c.src_xyz, opts->origin)
                                      : pnpr_cloud_set_world(&c, c.src_xyz);
            if (st != PNPR_OK) pnpr_io_fail(err, st, 0, -1, "read ply: cannot set coordinates");
        } else {
            c.src_coord_type = PNPR_TYPE_FLOAT32;
        }
    }
    if (st == PNPR_OK && c.faces.index && r.nindex < r.index_cap) {
        uint32_t *shrunk = realloc(c.faces.index, r.nindex * sizeof *shrunk);
        if (shrunk) c.faces.index = shrunk;
    }
    if (st == PNPR_OK && c.faces.count && !c.faces.index) {
        c.faces.index = malloc(sizeof(uint32_t)); /* all faces empty: keep a valid pointer */
        if (!c.faces.index) st = pnpr_io_fail(err, PNPR_ERR_OUT_OF_MEMORY, 0, -1, "read ply: out of memory");
    }
    header_free(&h);
    free(kept);
    if (st != PNPR_OK) {
        pnpr_cloud_free(&c);
        return st;
    }
    *cloud = c;
    return PNPR_OK;
}

pnpr_status pnpr_read_ply_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                               pnpr_error *err)
{
    if (!path || !cloud)
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "read ply: NULL path or cloud");
    pnpr_cloud_free(cloud);
    pnpr_file_bytes fb; /* as pnpr_file_bytes_read, with the mapping passed on */
    pnpr_status st = pnpr_file_bytes_open(path, &fb, err);
    if (st != PNPR_OK) return st;
    st = ply_read(fb.data, fb.size, opts, cloud, err, &fb);
    pnpr_file_bytes_close(&fb);
    if (st != PNPR_OK) pnpr_error_prefix_path(err, path);
    return st;
}

/* ------------------------------------------------------------------------------------------ */
/* Writer                                                                                      */

typedef struct ply_out {
    pnpr_out_buf b;
    int swap;        /* binary output in non-host order */
    char dp;         /* the locale's decimal point, replaced by '.' in ascii numbers */
} ply_out;

/* Binary scalar in the output byte order. */
static void out_bin(ply_out *o, const void *v, size_t sz)
{
    char *d = pnpr_out_reserve(&o->b, sz);
    copy_raw(d, v, sz, o->swap);
    o->b.len += sz;
}

static size_t fmt_u64(char *d, uint64_t v)
{
    char tmp[24];
    size_t n = 0;
    do { tmp[n++] = (char)('0' + v % 10); v /= 10; } while (v);
    for (size_t i = 0; i < n; i++) d[i] = tmp[n - 1 - i];
    return n;
}

static size_t fmt_i64(char *d, int64_t v)
{
    if (v < 0) { d[0] = '-'; return 1 + fmt_u64(d + 1, (uint64_t)0 - (uint64_t)v); }
    return fmt_u64(d, (uint64_t)v);
}

static size_t fmt_float9(char *out, float f);
static size_t fmt_double(char *out, double v);

/* Round-trip decimal: 9 significant digits for float, %.17g for double; "nan", "inf", "-inf". */
static size_t fmt_real(char *d, double v, int is_double, char dp)
{
    if (v != v) { memcpy(d, "nan", 3); return 3; }
    if (v == INFINITY) { memcpy(d, "inf", 3); return 3; }
    if (v == -INFINITY) { memcpy(d, "-inf", 4); return 4; }
    if (v == 0 && signbit(v)) { memcpy(d, "-0", 2); return 2; }
    if (v == floor(v) && fabs(v) < 1e9) return fmt_i64(d, (int64_t)v); /* what %.9g would print */
    if (!is_double) return fmt_float9(d, (float)v);
    size_t fast = fmt_double(d, v);
    if (fast) return fast;
    int n = snprintf(d, 32, "%.17g", v);
    if (n < 0) n = 0;
    if (dp != '.')
        for (int i = 0; i < n; i++)
            if (d[i] == dp) d[i] = '.';
    return (size_t)n;
}

/* 10^k for k in [-32, 56] (the literals are correctly rounded by the compiler). */
static double pow10_wide(int k)
{
    static const double neg[33] = {1e0,   1e-1,  1e-2,  1e-3,  1e-4,  1e-5,  1e-6,  1e-7,  1e-8,
                                   1e-9,  1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15, 1e-16, 1e-17,
                                   1e-18, 1e-19, 1e-20, 1e-21, 1e-22, 1e-23, 1e-24, 1e-25, 1e-26,
                                   1e-27, 1e-28, 1e-29, 1e-30, 1e-31, 1e-32};
    static const double pos[57] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                   1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22, 1e23,
                                   1e24, 1e25, 1e26, 1e27, 1e28, 1e29, 1e30, 1e31, 1e32, 1e33, 1e34, 1e35,
                                   1e36, 1e37, 1e38, 1e39, 1e40, 1e41, 1e42, 1e43, 1e44, 1e45, 1e46, 1e47,
                                   1e48, 1e49, 1e50, 1e51, 1e52, 1e53, 1e54, 1e55, 1e56};
    return k < 0 ? neg[-k] : pos[k];
}

/* A finite non-zero float as 9 significant digits (trailing zeros dropped), in %g style.
 * d = round(|f| * 10^(8-e)) is computed in double: its error (a few 1e-16 relative) plus the
 * half-unit of the 9th digit (<= 5e-9 relative) stays far below half a float ulp (>= 2.9e-8
 * relative), so the text always reads back to the same float. */
static size_t fmt_float9(char *out, float f)
{
    double x = fabs((double)f);
    int e2, e10;
    uint64_t d = 0;
    char dig[12];
    size_t n = 0, nd = 9;
    (void)frexp(x, &e2);
    e10 = (int)floor((e2 - 1) * 0.30102999566398120); /* floor(log10(x)), maybe one too low */
    for (int tries = 0; tries < 3; tries++) {
        double m = x * pow10_wide(8 - e10);
        if (m >= 999999999.5) { e10++; continue; }
        if (m < 99999999.5) { e10--; continue; }
        {   /* round half to even, as printf does (m's fraction is exact here) */
            double fl = floor(m), fr = m - fl;
            d = (uint64_t)fl;
            if (fr > 0.5 || (fr == 0.5 && (d & 1))) d++;
        }
        if (d == UINT64_C(1000000000)) { d = UINT64_C(100000000); e10++; }
        break;
    }
    if (d == 0) return (size_t)snprintf(out, 32, "%.9g", (double)f); /* not reached */
    for (int i = 8; i >= 0; i--) { dig[i] = (char)('0' + d % 10); d /= 10; }
    while (nd > 1 && dig[nd - 1] == '0') nd--;
    if (f < 0) out[n++] = '-';
    if (e10 >= -5 && e10 < 9) {
        if (e10 >= 0) {
            for (int i = 0; i <= e10; i++) out[n++] = (size_t)i < nd ? dig[i] : '0';
            if ((size_t)e10 + 1 < nd) {
                out[n++] = '.';
                for (size_t i = (size_t)e10 + 1; i < nd; i++) out[n++] = dig[i];
            }
        } else {
            out[n++] = '0';
            out[n++] = '.';
            for (int i = -1; i > e10; i--) out[n++] = '0';
            for (size_t i = 0; i < nd; i++) out[n++] = dig[i];
        }
    } else {
        out[n++] = dig[0];
        if (nd > 1) {
            out[n++] = '.';
            for (size_t i = 1; i < nd; i++) out[n++] = dig[i];
        }
        out[n++] = 'e';
        out[n++] = e10 < 0 ? '-' : '+';
        if (e10 < 0) e10 = -e10;
        if (e10 < 10) out[n++] = '0';
        n += fmt_u64(out + n, (uint64_t)e10);
    }
    return n;
}

/* round(M * 10^k / 2^s) for M < 2^53, 10^k < 2^64, 1 <= s < 128, exactly (128-bit product in
 * 32-bit pieces, ties to even); 0 when the result does not fit in 64 bits. */
static uint64_t mul_pow10_shift(uint64_t m, int k, int s)
{
    uint64_t p = 1, hi, lo, q, rem_hi, rem_lo, half_hi, half_lo;
    for (int i = 0; i < k; i++) p *= 10;
    {
        const uint64_t a0 = m & 0xffffffffu, a1 = m >> 32, b0 = p & 0xffffffffu, b1 = p >> 32;
        const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
        const uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
        lo = (p00 & 0xffffffffu) | (mid << 32);
        hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    }
    if (s >= 64) {
        if (s - 64 < 64 && (hi >> (s - 64)) >> 63 != 0) return 0;
        q = s - 64 < 64 ? hi >> (s - 64) : 0;
        rem_hi = s - 64 < 64 ? hi & ((UINT64_C(1) << (s - 64)) - 1) : hi;
        rem_lo = lo;
        half_hi = s == 64 ? 0 : UINT64_C(1) << (s - 65);
        half_lo = s == 64 ? UINT64_C(1) << 63 : 0;
    } else {
        if (hi >> s) return 0;
        q = (lo >> s) | (s ? hi << (64 - s) : 0);
        rem_hi = 0;
        rem_lo = lo & ((UINT64_C(1) << s) - 1);
        half_hi = 0;
        half_lo = UINT64_C(1) << (s - 1);
    }
    if (rem_hi > half_hi || (rem_hi == half_hi && (rem_lo > half_lo || (rem_lo == half_lo && (q & 1)))))
        q++;
    return q;
}

/* A double in [1e-3, 1e15) with a fractional part, exactly: the 15-significant-digit decimal
 * when it reads back to the same double (checked with the reader's exact fast path), else the
 * correctly rounded 17-digit one (which always does). Returns 0 for other values (the caller
 * uses %.17g). */
static size_t fmt_double(char *out, double v)
{
    double x = fabs(v), fr;
    int e2, e10, s, nd;
    uint64_t m, d = 0;
    char dig[20];
    size_t n = 0;
    if (!(x >= 1e-3 && x < 1e15)) return 0;
    fr = frexp(x, &e2);                      /* x = fr * 2^e2, fr in [0.5, 1) */
    m = (uint64_t)ldexp(fr, 53);             /* x = m * 2^(e2-53), m < 2^53 exact */
    s = 53 - e2;                             /* x = m / 2^s */
    if (s < 1 || s > 127) return 0;
    e10 = (int)floor((e2 - 1) * 0.30102999566398120);
    for (int tries = 0; tries < 3; tries++) { /* find e10 = floor(log10(x)) from the digits */
        const int k = 16 - e10;
        if (k < 0 || k > 19) return 0;
        d = mul_pow10_shift(m, k, s);
        if (d >= UINT64_C(100000000000000000)) { e10++; continue; }
        if (d < UINT64_C(10000000000000000)) { e10--; continue; }
        break;
    }
    if (d < UINT64_C(10000000000000000) || d >= UINT64_C(100000000000000000)) return 0;
    nd = 17;
    if (14 - e10 >= 0 && 14 - e10 <= 22) { /* try 15 digits */
        uint64_t d15 = mul_pow10_shift(m, 14 - e10, s);
        if (d15 && d15 <= UINT64_C(1000000000000000) &&
            (double)d15 / pow10_tab[14 - e10] == x) {
            d = d15;
            nd = 15;
            if (d == UINT64_C(1000000000000000)) { d /= 10; e10++; }
        }
    }
    for (int i = nd - 1; i >= 0; i--) { dig[i] = (char)('0' + d % 10); d /= 10; }
    while (nd > 1 && dig[nd - 1] == '0') nd--;
    if (v < 0) out[n++] = '-';
    if (e10 >= 0) {
        for (int i = 0; i <= e10; i++) out[n++] = i < nd ? dig[i] : '0';
        if (e10 + 1 < nd) {
            out[n++] = '.';
            for (int i = e10 + 1; i < nd; i++) out[n++] = dig[i];
        }
    } else {
        out[n++] = '0';
        out[n++] = '.';
        for (int i = -1; i > e10; i--) out[n++] = '0';
        for (int i = 0; i < nd; i++) out[n++] = dig[i];
    }
    return n;
}

/* One ascii value followed by a separator. */
static void out_ascii(ply_out *o, pnpr_type t, double v, char sep)
{
    char *d = pnpr_out_reserve(&o->b, 40);
    size_t n;
    switch (t) {
    case PNPR_TYPE_FLOAT32: n = fmt_real(d, v, 0, o->dp); break;
    case PNPR_TYPE_FLOAT64: n = fmt_real(d, v, 1, o->dp); break;
    default: n = fmt_i64(d, (int64_t)v); break;
    }
    d[n++] = sep;
    o->b.len += n;
}

/* Writes value v of type t (binary or ascii). For FLOAT32, v must already be a float value. */
static void out_value(ply_out *o, int ascii, pnpr_type t, const void *raw, double v, char sep)
{
    if (ascii) out_ascii(o, t, v, sep);
    else out_bin(o, raw, pnpr_type_size(t));
}

/* A PLY property name: non-empty, no blanks or control characters. */
static int valid_name(const char *s)
{
    if (!s || !*s) return 0;
    for (; *s; s++)
        if ((unsigned char)*s <= 0x20 || (unsigned char)*s == 0x7f) return 0;
    return 1;
}

static int name_used(const pnpr_cloud *c, const char *name)
{
    return pnpr_cloud_find_property(c, name) != NULL;
}

pnpr_status pnpr_write_ply_stream(pnpr_write_fn fn, void *user, const pnpr_cloud *cloud,
                                  const pnpr_write_options *opts, pnpr_error *err)
{
    static const char *const colour_names[3][3] = {
        {"red", "green", "blue"}, {"diffuse_red", "diffuse_green", "diffuse_blue"}, {"r", "g", "b"}};
    const pnpr_progress *progress = opts ? &opts->progress : NULL;
    const pnpr_ply_encoding enc = opts ? opts->encoding : PNPR_PLY_BINARY_LE;
    const int ascii = enc == PNPR_PLY_ASCII;
    int use_double, colour_set = 0, wide_faces = 0;
    const char *label_name = PNPR_PROP_SEGMENT;
    ply_out o;

    if (err) { err->message[0] = '\0'; err->line = 0; err->offset = -1; }
    if (!fn || !cloud || (cloud->count && !cloud->xyz))
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "write ply: NULL sink, cloud or coordinates");
    if (enc != PNPR_PLY_BINARY_LE && enc != PNPR_PLY_ASCII && enc != PNPR_PLY_BINARY_BE)
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "write ply: unknown encoding %d", (int)enc);
    if (cloud->prop_count && !cloud->props)
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "write ply: prop_count without props");

    /* Names: the standard ones move aside for extra properties of the same name. */
    if (cloud->rgb) {
        while (colour_set < 3 && (name_used(cloud, colour_names[colour_set][0]) ||
                                  name_used(cloud, colour_names[colour_set][1]) ||
                                  name_used(cloud, colour_names[colour_set][2])))
            colour_set++;
        if (colour_set == 3)
            return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1,
                           "write ply: extra properties use every colour name (red, diffuse_red, r ...)");
    }
    if (cloud->label && name_used(cloud, PNPR_PROP_SEGMENT)) {
        label_name = PNPR_PROP_LABEL;
        if (name_used(cloud, PNPR_PROP_LABEL))
            return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1,
                           "write ply: extra properties 'segment' and 'label' leave no name for the labels");
    }
    for (size_t k = 0; k < cloud->prop_count; k++) {
        const pnpr_property *p = &cloud->props[k];
        const char *nm = p->name;
        if (memchr(p->name, '\0', sizeof p->name) == NULL || !valid_name(nm))
            return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1,
                           "write ply: extra property %zu has an empty name or one with blanks/control characters", k);
        if (pnpr_type_size(p->type) == 0 || (cloud->count && !p->data))
            return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "write ply: extra property '%s' has no type or data", nm);
        int clash = !strcmp(nm, "x") || !strcmp(nm, "y") || !strcmp(nm, "z") ||
                    (cloud->normal && (!strcmp(nm, "nx") || !strcmp(nm, "ny") || !strcmp(nm, "nz")));
        for (size_t j = 0; j < k; j++) clash |= !strcmp(nm, cloud->props[j].name);
        if (clash)
            return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1,
                           "write ply: extra property '%s' clashes with another property of the same name", nm);
    }
    if (cloud->faces.count) {
        const pnpr_faces *fc = &cloud->faces;
        if (!fc->offset || (!fc->index && fc->offset[fc->count]))
            return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "write ply: faces without offset/index arrays");
        for (size_t f = 0; f < fc->count; f++) {
            if (fc->offset[f + 1] < fc->offset[f])
                return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "write ply: face %zu has a decreasing offset", f);
            if (fc->offset[f + 1] - fc->offset[f] > 255) wide_faces = 1;
            for (uint32_t j = fc->offset[f]; j < fc->offset[f + 1]; j++)
                if (fc->index[j] >= cloud->count)
                    return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1,
                                   "write ply: face %zu references vertex %u but the cloud has %zu points", f,
                                   (unsigned)fc->index[j], cloud->count);
        }
    }

    use_double = cloud->src_xyz || cloud->src_coord_type == PNPR_TYPE_FLOAT64 || (opts && opts->force_double);
    if (!use_double && cloud->src_coord_type == PNPR_TYPE_NONE &&
        (cloud->origin[0] != 0 || cloud->origin[1] != 0 || cloud->origin[2] != 0)) {
        for (size_t i = 0; i < cloud->count && !use_double; i++)
            for (int a = 0; a < 3; a++) {
                double w = cloud->origin[a] + (double)cloud->xyz[3 * i + a];
                if (w == w && (double)d2f(w) != w) use_double = 1;
            }
    }

    memset(&o, 0, sizeof o);
    o.b.fn = fn;
    o.b.user = user;
    o.swap = enc == PNPR_PLY_BINARY_BE ? host_is_little() : enc == PNPR_PLY_BINARY_LE ? !host_is_little() : 0;
    {
        const struct lconv *lc = localeconv();
        o.dp = lc && lc->decimal_point && lc->decimal_point[0] ? lc->decimal_point[0] : '.';
    }
    o.b.buf = malloc(PNPR_OUT_BUF);
    if (!o.b.buf) return pnpr_io_fail(err, PNPR_ERR_OUT_OF_MEMORY, 0, -1, "write ply: out of memory");

    /* Header */
    {
        char line[160];
        const char *coord = use_double ? "double" : "float";
        pnpr_out_str(&o.b, "ply\nformat ");
        pnpr_out_str(&o.b, ascii ? "ascii" : enc == PNPR_PLY_BINARY_BE ? "binary_big_endian" : "binary_little_endian");
        pnpr_out_str(&o.b, " 1.0\n");
        if (opts && opts->comment && opts->comment[0]) {
            pnpr_out_str(&o.b, "comment ");
            for (const char *s = opts->comment; *s; s++) {
                char ch = ((unsigned char)*s < 0x20 || *s == 0x7f) ? ' ' : *s;
                pnpr_out_bytes(&o.b, &ch, 1);
            }
            pnpr_out_str(&o.b, "\n");
        }
        pnpr_out_str(&o.b, "comment generated by pointnpr " PNPR_VERSION_STRING "\n");
        snprintf(line, sizeof line, "element vertex %zu\n", cloud->count);
        pnpr_out_str(&o.b, line);
        snprintf(line, sizeof line, "property %s x\nproperty %s y\nproperty %s z\n", coord, coord, coord);
        pnpr_out_str(&o.b, line);
        if (cloud->normal) pnpr_out_str(&o.b, "property float nx\nproperty float ny\nproperty float nz\n");
        if (cloud->rgb) {
            snprintf(line, sizeof line, "property uchar %s\nproperty uchar %s\nproperty uchar %s\n",
                     colour_names[colour_set][0], colour_names[colour_set][1], colour_names[colour_set][2]);
            pnpr_out_str(&o.b, line);
        }
        if (cloud->label) {
            snprintf(line, sizeof line, "property uint %s\n", label_name);
            pnpr_out_str(&o.b, line);
        }
        for (size_t k = 0; k < cloud->prop_count; k++) {
            pnpr_out_str(&o.b, "property ");
            pnpr_out_str(&o.b, pnpr_type_ply_name(cloud->props[k].type));
            pnpr_out_str(&o.b, " ");
            pnpr_out_str(&o.b, cloud->props[k].name);
            pnpr_out_str(&o.b, "\n");
        }
        if (cloud->faces.count) {
            snprintf(line, sizeof line, "element face %zu\nproperty list %s uint vertex_indices\n",
                     cloud->faces.count, wide_faces ? "uint" : "uchar");
            pnpr_out_str(&o.b, line);
        }
        pnpr_out_str(&o.b, "end_header\n");
    }

    /* Vertices */
    {
        const size_t n = cloud->count;
        const size_t step = n >= 100 ? n / 100 : 1;
        size_t left = step;
        const int last_is_xyz = !cloud->normal && !cloud->rgb && !cloud->label && !cloud->prop_count;
        for (size_t i = 0; i < n && !o.b.failed; i++) {
            for (int a = 0; a < 3; a++) {
                const char sep = a == 2 && last_is_xyz ? '\n' : ' ';
                if (use_double) {
                    double w = cloud->src_xyz ? cloud->src_xyz[3 * i + a]
                                              : cloud->origin[a] + (double)cloud->xyz[3 * i + a];
                    out_value(&o, ascii, PNPR_TYPE_FLOAT64, &w, w, sep);
                } else {
                    float f = cloud->origin[a] == 0 ? cloud->xyz[3 * i + a]
                                                    : d2f(cloud->origin[a] + (double)cloud->xyz[3 * i + a]);
                    out_value(&o, ascii, PNPR_TYPE_FLOAT32, &f, f, sep);
                }
            }
            if (cloud->normal)
                for (int a = 0; a < 3; a++) {
                    const char sep = a == 2 && !cloud->rgb && !cloud->label && !cloud->prop_count ? '\n' : ' ';
                    const float f = cloud->normal[3 * i + a];
                    out_value(&o, ascii, PNPR_TYPE_FLOAT32, &f, f, sep);
                }
            if (cloud->rgb)
                for (int a = 0; a < 3; a++) {
                    const char sep = a == 2 && !cloud->label && !cloud->prop_count ? '\n' : ' ';
                    out_value(&o, ascii, PNPR_TYPE_UINT8, &cloud->rgb[3 * i + a], cloud->rgb[3 * i + a], sep);
                }
            if (cloud->label)
                out_value(&o, ascii, PNPR_TYPE_UINT32, &cloud->label[i], cloud->label[i],
                          cloud->prop_count ? ' ' : '\n');
            for (size_t k = 0; k < cloud->prop_count; k++) {
                const pnpr_property *p = &cloud->props[k];
                const size_t sz = pnpr_type_size(p->type);
                const void *raw = (const char *)p->data + i * sz;
                const char sep = k + 1 == cloud->prop_count ? '\n' : ' ';
                if (ascii) {
                    double v = pnpr_type_get(p->type, p->data, i);
                    out_ascii(&o, p->type, v, sep);
                } else {
                    out_bin(&o, raw, sz);
                }
            }
            if (--left == 0) {
                left = step;
                if (pnpr_progress_report(progress, "write ply", (double)(i + 1) / (double)n)) {
                    free(o.b.buf);
                    return pnpr_io_fail(err, PNPR_ERR_CANCELLED, 0, -1, "write ply: cancelled at vertex %zu of %zu",
                                   i + 1, n);
                }
            }
        }
    }

    /* Faces */
    for (size_t f = 0; f < cloud->faces.count && !o.b.failed; f++) {
        const pnpr_faces *fc = &cloud->faces;
        const uint32_t b = fc->offset[f], e = fc->offset[f + 1], nc = e - b;
        if (wide_faces) out_value(&o, ascii, PNPR_TYPE_UINT32, &nc, nc, e > b ? ' ' : '\n');
        else {
            const uint8_t c8 = (uint8_t)nc;
            out_value(&o, ascii, PNPR_TYPE_UINT8, &c8, c8, e > b ? ' ' : '\n');
        }
        for (uint32_t j = b; j < e; j++)
            out_value(&o, ascii, PNPR_TYPE_UINT32, &fc->index[j], fc->index[j], j + 1 == e ? '\n' : ' ');
    }

    pnpr_out_flush(&o.b);
    free(o.b.buf);
    if (o.b.failed)
        return pnpr_io_fail(err, PNPR_ERR_IO, 0, (long long)o.b.written, "write ply: the output sink failed after %llu bytes",
                       o.b.written);
    if (pnpr_progress_report(progress, "write ply", 1.0))
        return pnpr_io_fail(err, PNPR_ERR_CANCELLED, 0, -1, "write ply: cancelled");
    return PNPR_OK;
}

pnpr_status pnpr_write_ply_file(const char *path, const pnpr_cloud *cloud,
                                const pnpr_write_options *opts, pnpr_error *err)
{
    return pnpr_io_write_path(path, cloud, opts, err, "write ply", pnpr_write_ply_stream);
}
