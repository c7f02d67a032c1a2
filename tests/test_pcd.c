/* PCD reader and writer: files the test writes itself (ascii, binary, binary_compressed with an
 * LZF compressor of its own), field mapping (coordinates, packed rgb/rgba, normals, labels,
 * extra fields, padding, COUNT > 1), NaN points, viewpoint, 0.5 headers, double coordinates at
 * a 5e6 offset, the writer's round trip, pnpr_read_file dispatch, and hostile input: lying
 * headers, truncated data, huge COUNT/SIZE, unknown TYPE, compressed sizes that lie, corrupt
 * LZF, each with its status and a message that names the line or byte. */
#include "sparse_file.h"
#include "testutil.h"

#include <pointnpr/io.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- byte buffers ----------------------------------------------------------------------- */

typedef struct buf {
    unsigned char *d;
    size_t n, cap;
    size_t fail_after; /* as a write sink: fail once this many bytes would be exceeded (0 = never) */
} buf;

static void put(buf *b, const void *p, size_t n)
{
    if (b->n + n > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->n + n) cap *= 2;
        unsigned char *g = realloc(b->d, cap);
        if (!g) abort();
        b->d = g;
        b->cap = cap;
    }
    memcpy(b->d + b->n, p, n);
    b->n += n;
}

static void put_str(buf *b, const char *s) { put(b, s, strlen(s)); }

static void put_le(buf *b, uint64_t v, unsigned size)
{
    unsigned char t[8];
    for (unsigned k = 0; k < size; k++) t[k] = (unsigned char)(v >> (8 * k));
    put(b, t, size);
}

static void buf_free(buf *b)
{
    free(b->d);
    memset(b, 0, sizeof *b);
}

static int sink(void *user, const void *data, size_t size)
{
    buf *b = user;
    if (b->fail_after && b->n + size > b->fail_after) return 1;
    put(b, data, size);
    return 0;
}

static int contains(const char *hay, const char *needle) { return strstr(hay, needle) != NULL; }

static int cloud_is_zero(const pnpr_cloud *c)
{
    pnpr_cloud z;
    memset(&z, 0, sizeof z);
    return memcmp(c, &z, sizeof z) == 0;
}

/* ---- an LZF compressor (greedy, brute force: test sizes only) ------------------------------ */

static void lzf_literals(buf *out, const unsigned char *p, size_t n)
{
    while (n) {
        size_t run = n > 32 ? 32 : n;
        unsigned char ctrl = (unsigned char)(run - 1);
        put(out, &ctrl, 1);
        put(out, p, run);
        p += run;
        n -= run;
    }
}

/* refs = 0: literal runs only. */
static void lzf_compress(const unsigned char *in, size_t n, buf *out, int refs)
{
    size_t ip = 0, lit = 0;
    while (ip < n) {
        size_t best = 0, best_off = 0, maxoff = ip < 8192 ? ip : 8192;
        for (size_t off = 1; refs && off <= maxoff; off++) {
            size_t l = 0;
            while (ip + l < n && l < 264 && in[ip + l - off] == in[ip + l]) l++;
            if (l > best) { best = l; best_off = off; }
        }
        if (best < 3) { ip++; continue; }
        lzf_literals(out, in + lit, ip - lit);
        size_t len = best - 2, o = best_off - 1;
        unsigned char t[3];
        t[0] = (unsigned char)(((len < 7 ? len : 7) << 5) | (o >> 8));
        put(out, t, 1);
        if (len >= 7) { t[1] = (unsigned char)(len - 7); put(out, t + 1, 1); }
        t[2] = (unsigned char)(o & 255);
        put(out, t + 2, 1);
        ip += best;
        lit = ip;
    }
    lzf_literals(out, in + lit, n - lit);
}

/* ---- building PCD files ------------------------------------------------------------------- */

typedef struct fspec {
    const char *name;
    unsigned size;
    char type;
    unsigned count;
} fspec;

enum { ASCII, BINARY, COMPRESSED, COMPRESSED_LITERALS };

static void bin_value(buf *b, const fspec *f, double v)
{
    if (f->type == 'F' && f->size == 4) {
        float x = (float)v;
        uint32_t u;
        memcpy(&u, &x, 4);
        put_le(b, u, 4);
    } else if (f->type == 'F') {
        uint64_t u;
        memcpy(&u, &v, 8);
        put_le(b, u, 8);
    } else {
        put_le(b, f->type == 'I' ? (uint64_t)(int64_t)v : (uint64_t)v, f->size);
    }
}

static void ascii_value(buf *b, const fspec *f, double v)
{
    char s[64];
    if (f->type == 'F') snprintf(s, sizeof s, f->size == 4 ? " %.9g" : " %.17g", v);
    else if (f->type == 'I') snprintf(s, sizeof s, " %lld", (long long)v);
    else snprintf(s, sizeof s, " %llu", (unsigned long long)v);
    put_str(b, s);
}

static size_t values_per_point(const fspec *fs, size_t nf)
{
    size_t v = 0;
    for (size_t j = 0; j < nf; j++) v += fs[j].count;
    return v;
}

static void header(buf *b, const fspec *fs, size_t nf, size_t npts, const char *extra, const char *data)
{
    char s[128];
    put_str(b, "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS");
    for (size_t j = 0; j < nf; j++) { put_str(b, " "); put_str(b, fs[j].name); }
    put_str(b, "\nSIZE");
    for (size_t j = 0; j < nf; j++) { snprintf(s, sizeof s, " %u", fs[j].size); put_str(b, s); }
    put_str(b, "\nTYPE");
    for (size_t j = 0; j < nf; j++) { snprintf(s, sizeof s, " %c", fs[j].type); put_str(b, s); }
    put_str(b, "\nCOUNT");
    for (size_t j = 0; j < nf; j++) { snprintf(s, sizeof s, " %u", fs[j].count); put_str(b, s); }
    snprintf(s, sizeof s, "\nWIDTH %zu\nHEIGHT 1\n", npts);
    put_str(b, s);
    if (extra) put_str(b, extra);
    snprintf(s, sizeof s, "POINTS %zu\nDATA %s\n", npts, data);
    put_str(b, s);
}

/* vals: npts x values_per_point doubles (padding included). */
static void make_pcd(buf *b, const fspec *fs, size_t nf, const double *vals, size_t npts, int kind, const char *extra)
{
    static const char *const names[] = {"ascii", "binary", "binary_compressed", "binary_compressed"};
    const size_t vpp = values_per_point(fs, nf);
    header(b, fs, nf, npts, extra, names[kind]);
    if (kind == ASCII || kind == BINARY) {
        for (size_t i = 0; i < npts; i++) {
            const double *v = vals + i * vpp;
            for (size_t j = 0; j < nf; v += fs[j].count, j++)
                for (unsigned k = 0; k < fs[j].count; k++)
                    if (kind == BINARY) bin_value(b, &fs[j], v[k]);
                    else if (strcmp(fs[j].name, "_") != 0) ascii_value(b, &fs[j], v[k]);
            if (kind == ASCII) put_str(b, "\n");
        }
        return;
    }
    buf soa = {0}, z = {0};
    for (size_t j = 0, first = 0; j < nf; first += fs[j].count, j++)
        for (size_t i = 0; strcmp(fs[j].name, "_") != 0 && i < npts; i++)
            for (unsigned k = 0; k < fs[j].count; k++) bin_value(&soa, &fs[j], vals[i * vpp + first + k]);
    lzf_compress(soa.d, soa.n, &z, kind == COMPRESSED);
    put_le(b, z.n, 4);
    put_le(b, soa.n, 4);
    if (z.n) put(b, z.d, z.n);
    buf_free(&soa);
    buf_free(&z);
}

static pnpr_status read_buf(const buf *b, pnpr_cloud *c, pnpr_error *e)
{
    return pnpr_read_pcd_memory(b->d, b->n, NULL, c, e);
}

static pnpr_status read_str(const char *s, pnpr_cloud *c, pnpr_error *e)
{
    return pnpr_read_pcd_memory(s, strlen(s), NULL, c, e);
}

/* ---- known values in every encoding -------------------------------------------------------- */

static const fspec mixed_fields[] = {
    {"x", 4, 'F', 1},         {"y", 4, 'F', 1},     {"z", 4, 'F', 1},   {"rgb", 4, 'U', 1},
    {"intensity", 2, 'U', 1}, {"_", 1, 'U', 3},     {"label", 2, 'I', 1}, {"fpfh", 4, 'F', 3},
    {"big", 8, 'I', 1},       {"dbl", 8, 'F', 1},   {"curvature", 4, 'F', 1}, {"tiny", 1, 'I', 1},
};
#define MIXED_NF (sizeof mixed_fields / sizeof mixed_fields[0])
#define MIXED_VPP 16

static void mixed_values(double *v, size_t npts)
{
    for (size_t i = 0; i < npts; i++) {
        double *p = v + i * MIXED_VPP;
        p[0] = 0.1 * (double)i + 0.25;
        p[1] = -1.5 * (double)i;
        p[2] = 3.0 + (double)(i % 7);
        p[3] = (double)(((i * 37u) & 255u) << 16 | ((i * 11u) & 255u) << 8 | ((i * 5u) & 255u));
        p[4] = (double)(i * 100 % 65536);
        p[5] = p[6] = p[7] = 0xAB; /* padding */
        p[8] = (double)((int)(i % 5) - 2);
        p[9] = 0.5 * (double)i;
        p[10] = -0.25;
        p[11] = (double)(i % 3);
        p[12] = -5e15 + (double)i;
        p[13] = 1.0 / 3.0 + (double)i;
        p[14] = 0.001 * (double)i;
        p[15] = (double)((int)(i % 256) - 128);
    }
    if (npts > 2) /* a hole, as in organised clouds */
        v[2 * MIXED_VPP] = v[2 * MIXED_VPP + 1] = v[2 * MIXED_VPP + 2] = NAN;
}

static void check_mixed(const pnpr_cloud *c, const double *v, size_t npts, const char *what)
{
    CHECK_MSG(c->count == npts, "%s: %zu points", what, c->count);
    if (c->count != npts) return;
    CHECK_MSG(c->rgb && c->label && !c->normal && !c->src_xyz && c->src_coord_type == PNPR_TYPE_FLOAT32, "%s: arrays", what);
    CHECK_MSG(c->prop_count == 8, "%s: %zu properties", what, c->prop_count);
    if (!c->rgb || !c->label || c->prop_count != 8) return;
    static const char *const names[8] = {"intensity", "fpfh_0", "fpfh_1", "fpfh_2", "big", "dbl", "curvature", "tiny"};
    static const pnpr_type types[8] = {PNPR_TYPE_UINT16,  PNPR_TYPE_FLOAT32, PNPR_TYPE_FLOAT32, PNPR_TYPE_FLOAT32,
                                       PNPR_TYPE_FLOAT64, PNPR_TYPE_FLOAT64, PNPR_TYPE_FLOAT32, PNPR_TYPE_INT8};
    static const int col[8] = {4, 9, 10, 11, 12, 13, 14, 15};
    for (int k = 0; k < 8; k++)
        CHECK_MSG(!strcmp(c->props[k].name, names[k]) && c->props[k].type == types[k], "%s: property %d is %s", what, k,
                  c->props[k].name);
    for (size_t i = 0; i < npts; i++) {
        const double *p = v + i * MIXED_VPP;
        for (int a = 0; a < 3; a++) {
            float want = (float)p[a], got = c->xyz[3 * i + a];
            CHECK_MSG((isnan(want) && isnan(got)) || memcmp(&want, &got, 4) == 0, "%s: point %zu axis %d", what, i, a);
        }
        uint32_t rgb = (uint32_t)p[3];
        CHECK(c->rgb[3 * i] == (rgb >> 16 & 255) && c->rgb[3 * i + 1] == (rgb >> 8 & 255) && c->rgb[3 * i + 2] == (rgb & 255));
        CHECK_MSG(c->label[i] == (uint32_t)(int32_t)p[8], "%s: label %zu = %u", what, i, c->label[i]);
        for (int k = 0; k < 8; k++) {
            double want = types[k] == PNPR_TYPE_FLOAT32 ? (double)(float)p[col[k]] : p[col[k]];
            CHECK_MSG(pnpr_type_get(c->props[k].type, c->props[k].data, i) == want, "%s: point %zu %s", what, i, names[k]);
        }
    }
}

static void test_known_values(void)
{
    const size_t npts = 300; /* compresses with back references */
    double *v = malloc(npts * MIXED_VPP * sizeof *v);
    mixed_values(v, npts);
    static const char *const what[] = {"ascii", "binary", "binary_compressed", "binary_compressed (literal runs)"};
    for (int kind = ASCII; kind <= COMPRESSED_LITERALS; kind++) {
        buf b = {0};
        pnpr_cloud c = {0};
        pnpr_error e;
        make_pcd(&b, mixed_fields, MIXED_NF, v, npts, kind, "VIEWPOINT 1.5 -2 1e6 1 0 0 0\n");
        pnpr_status st = read_buf(&b, &c, &e);
        CHECK_MSG(st == PNPR_OK, "%s: %s", what[kind], e.message);
        check_mixed(&c, v, npts, what[kind]);
        CHECK(c.has_viewpoint && c.viewpoint[0] == 1.5 && c.viewpoint[1] == -2 && c.viewpoint[2] == 1e6);
        CHECK(c.origin[0] == 0 && c.origin[1] == 0 && c.origin[2] == 0);
        pnpr_cloud_free(&c);
        buf_free(&b);
    }
    free(v);
}

/* rgb as PCL writes it: a float whose bits are 0x00RRGGBB (ascii: its 9-digit decimal), rgba as
 * U4 0xAARRGGBB, normals, and a 0.5 header without SIZE/TYPE/COUNT. */
static void test_rgb_normals_and_old_headers(void)
{
    const fspec fs[] = {{"x", 4, 'F', 1}, {"y", 4, 'F', 1}, {"z", 4, 'F', 1}, {"rgb", 4, 'F', 1},
                        {"normal_x", 4, 'F', 1}, {"normal_y", 4, 'F', 1}, {"normal_z", 4, 'F', 1}};
    const uint32_t packed[3] = {0x00FF8001u, 0x00010203u, 0x007F7F7Fu};
    double v[3 * 7];
    for (int i = 0; i < 3; i++) {
        float f;
        memcpy(&f, &packed[i], 4);
        double *p = v + 7 * i;
        p[0] = i; p[1] = 2 * i; p[2] = 3 * i; p[3] = f; p[4] = 0; p[5] = 0.6; p[6] = -0.8;
    }
    for (int kind = ASCII; kind <= COMPRESSED; kind++) {
        buf b = {0};
        pnpr_cloud c = {0};
        pnpr_error e;
        make_pcd(&b, fs, 7, v, 3, kind, NULL);
        CHECK_STATUS(read_buf(&b, &c, &e), PNPR_OK);
        CHECK(c.count == 3 && c.rgb && c.normal && c.prop_count == 0 && !c.has_viewpoint);
        for (int i = 0; c.rgb && c.normal && i < 3; i++) {
            CHECK_MSG(c.rgb[3 * i] == (packed[i] >> 16 & 255) && c.rgb[3 * i + 1] == (packed[i] >> 8 & 255) &&
                      c.rgb[3 * i + 2] == (packed[i] & 255), "kind %d point %d: %u %u %u", kind, i, c.rgb[3 * i],
                      c.rgb[3 * i + 1], c.rgb[3 * i + 2]);
            CHECK(c.normal[3 * i + 1] == 0.6f && c.normal[3 * i + 2] == -0.8f);
        }
        pnpr_cloud_free(&c);
        buf_free(&b);
    }
    /* rgba: alpha dropped; a second colour field stays an extra property */
    {
        pnpr_cloud c = {0};
        CHECK_STATUS(read_str("VERSION .7\nFIELDS x y z rgba rgb\nSIZE 4 4 4 4 4\nTYPE F F F U F\nCOUNT 1 1 1 1 1\n"
                              "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3 4294901760 0\n", &c, NULL), PNPR_OK);
        CHECK(c.rgb && c.rgb[0] == 0xFF && c.rgb[1] == 0x00 && c.rgb[2] == 0x00);
        CHECK(c.prop_count == 1 && !strcmp(c.props[0].name, "rgb") && c.props[0].type == PNPR_TYPE_FLOAT32);
        pnpr_cloud_free(&c);
    }
    /* version 0.5: COLUMNS, no SIZE/TYPE/COUNT (floats), POINTS only */
    {
        pnpr_cloud c = {0};
        pnpr_error e;
        CHECK_STATUS(read_str("# .PCD v.5 - Point Cloud Data file format\r\nVERSION .5\r\nCOLUMNS x y z i\r\nPOINTS 2\r\n"
                              "DATA ascii\r\n1 2 3 0.5\r\n\r\n4 5 6 nan\r\n", &c, &e), PNPR_OK);
        CHECK(c.count == 2 && c.xyz[5] == 6.0f && c.prop_count == 1 && c.props[0].type == PNPR_TYPE_FLOAT32);
        CHECK(c.prop_count == 1 && isnan(pnpr_type_get(c.props[0].type, c.props[0].data, 1)));
        pnpr_cloud_free(&c);
    }
    /* normals only when all three are there; a float label stays a property; WIDTH alone */
    {
        pnpr_cloud c = {0};
        CHECK_STATUS(read_str("FIELDS x y z normal_x normal_y label\nSIZE 4 4 4 4 4 4\nTYPE F F F F F F\nWIDTH 1\n"
                              "DATA ascii\n1 2 3 0 1 7.5\n", &c, NULL), PNPR_OK);
        CHECK(c.count == 1 && !c.normal && !c.label && c.prop_count == 3);
        CHECK(c.prop_count == 3 && !strcmp(c.props[2].name, "label") && pnpr_type_get(c.props[2].type, c.props[2].data, 0) == 7.5);
        pnpr_cloud_free(&c);
    }
}

/* x y z as doubles 5e6 from the origin: exact in src_xyz, float offsets around the centre. */
static void test_double_coordinates(void)
{
    const fspec fs[] = {{"x", 8, 'F', 1}, {"y", 8, 'F', 1}, {"z", 4, 'F', 1}};
    double v[4 * 3];
    for (int i = 0; i < 4; i++) {
        v[3 * i] = 5000000.001 + 0.001 * i;
        v[3 * i + 1] = -4999999.5 - 1e-3 * i;
        v[3 * i + 2] = 0.25 * i;
    }
    for (int kind = ASCII; kind <= COMPRESSED; kind++) {
        buf b = {0};
        pnpr_cloud c = {0};
        make_pcd(&b, fs, 3, v, 4, kind, NULL);
        CHECK_STATUS(read_buf(&b, &c, NULL), PNPR_OK);
        CHECK(c.count == 4 && c.src_xyz && c.src_coord_type == PNPR_TYPE_FLOAT64);
        CHECK(fabs(c.origin[0] - 5000000.0025) < 1e-6);
        for (int i = 0; c.src_xyz && i < 4; i++) {
            double w[3];
            pnpr_cloud_world(&c, i, w);
            CHECK(w[0] == v[3 * i] && w[1] == v[3 * i + 1] && w[2] == (double)(float)v[3 * i + 2]);
            CHECK(fabs(c.origin[0] + c.xyz[3 * i] - v[3 * i]) < 1e-6);
        }
        pnpr_cloud_free(&c);
        buf_free(&b);
    }
}

/* ---- the writer ---------------------------------------------------------------------------- */

static void make_cloud(pnpr_cloud *c, size_t n)
{
    CHECK_STATUS(pnpr_cloud_alloc(c, n), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(c), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_normals(c), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_labels(c), PNPR_OK);
    pnpr_property *p = NULL;
    CHECK_STATUS(pnpr_cloud_add_property(c, "intensity", PNPR_TYPE_UINT16, &p), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_add_property(c, "score", PNPR_TYPE_FLOAT64, &p), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_add_property(c, "klass", PNPR_TYPE_INT8, &p), PNPR_OK);
    for (size_t i = 0; i < n; i++) {
        for (int a = 0; a < 3; a++) {
            c->xyz[3 * i + a] = (float)(0.1 * (double)i + a);
            c->normal[3 * i + a] = a == 2 ? 1.0f : 0.0f;
            c->rgb[3 * i + a] = (uint8_t)(i * 7 + (size_t)a * 50);
        }
        c->label[i] = (uint32_t)(i % 4);
        pnpr_type_set(c->props[0].type, c->props[0].data, i, (double)(i * 3));
        pnpr_type_set(c->props[1].type, c->props[1].data, i, 1.0 / (double)(i + 1));
        pnpr_type_set(c->props[2].type, c->props[2].data, i, -(double)(i % 100));
    }
    c->xyz[0] = NAN;
    c->src_coord_type = PNPR_TYPE_FLOAT32;
    c->has_viewpoint = 1;
    c->viewpoint[0] = 0.1;
    c->viewpoint[1] = -7;
    c->viewpoint[2] = 123456.75;
}

static void check_same(const pnpr_cloud *a, const pnpr_cloud *b)
{
    CHECK(a->count == b->count && a->prop_count == b->prop_count && !a->rgb == !b->rgb && !a->normal == !b->normal &&
          !a->label == !b->label && a->has_viewpoint == b->has_viewpoint);
    if (a->count != b->count || a->prop_count != b->prop_count) return;
    for (size_t i = 0; i < a->count; i++) {
        double wa[3], wb[3];
        pnpr_cloud_world(a, i, wa);
        pnpr_cloud_world(b, i, wb);
        for (int k = 0; k < 3; k++) CHECK((isnan(wa[k]) && isnan(wb[k])) || wa[k] == wb[k]);
    }
    if (a->rgb && b->rgb) CHECK(memcmp(a->rgb, b->rgb, 3 * a->count) == 0);
    if (a->normal && b->normal) CHECK(memcmp(a->normal, b->normal, 3 * a->count * sizeof(float)) == 0);
    if (a->label && b->label) CHECK(memcmp(a->label, b->label, a->count * sizeof(uint32_t)) == 0);
    for (size_t k = 0; k < a->prop_count; k++) {
        CHECK(!strcmp(a->props[k].name, b->props[k].name) && a->props[k].type == b->props[k].type);
        CHECK(memcmp(a->props[k].data, b->props[k].data, a->count * pnpr_type_size(a->props[k].type)) == 0);
    }
    if (a->has_viewpoint && b->has_viewpoint) CHECK(memcmp(a->viewpoint, b->viewpoint, sizeof a->viewpoint) == 0);
}

static void test_writer_round_trip(void)
{
    pnpr_cloud c = {0}, r = {0};
    pnpr_error e;
    make_cloud(&c, 1000);
    {
        buf b = {0};
        CHECK_STATUS(pnpr_write_pcd_stream(sink, &b, &c, NULL, &e), PNPR_OK);
        CHECK(b.n > 40 && contains((const char *)b.d, "FIELDS x y z normal_x normal_y normal_z rgb label intensity score klass\n"));
        CHECK(contains((const char *)b.d, "TYPE F F F F F F F U U F I\n"));
        CHECK(contains((const char *)b.d, "VIEWPOINT 0.10000000000000001 -7 123456.75 1 0 0 0\n"));
        CHECK_STATUS(read_buf(&b, &r, &e), PNPR_OK);
        check_same(&c, &r);
        pnpr_cloud_free(&r);
        buf_free(&b);
    }
    /* double coordinates */
    {
        pnpr_cloud d = {0};
        buf b = {0};
        double world[6] = {5e6 + 0.001, 1, 2, 5e6 - 0.002, 3, 4};
        CHECK_STATUS(pnpr_cloud_alloc(&d, 2), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_alloc_src_xyz(&d), PNPR_OK);
        memcpy(d.src_xyz, world, sizeof world);
        d.src_coord_type = PNPR_TYPE_FLOAT64;
        CHECK_STATUS(pnpr_cloud_set_world(&d, world), PNPR_OK);
        CHECK_STATUS(pnpr_write_pcd_stream(sink, &b, &d, NULL, &e), PNPR_OK);
        CHECK(contains((const char *)b.d, "SIZE 8 8 8\n"));
        CHECK_STATUS(read_buf(&b, &r, &e), PNPR_OK);
        check_same(&d, &r);
        CHECK(r.src_xyz && r.src_xyz[0] == 5e6 + 0.001 && r.src_xyz[3] == 5e6 - 0.002);
        pnpr_cloud_free(&r);
        pnpr_cloud_free(&d);
        buf_free(&b);
    }
    /* through files: extension, and the magic bytes of a file without one */
    {
        const char *path = PNPR_TEST_SCRATCH "/pcd_round.pcd", *bare = PNPR_TEST_SCRATCH "/pcd_round_noext";
        CHECK_STATUS(pnpr_write_file(path, &c, NULL, &e), PNPR_OK);
        CHECK_STATUS(pnpr_read_file(path, NULL, &r, &e), PNPR_OK);
        check_same(&c, &r);
        pnpr_cloud_free(&r);
        pnpr_write_options wo = {0};
        wo.format = PNPR_FORMAT_PCD;
        CHECK_STATUS(pnpr_write_file(bare, &c, &wo, &e), PNPR_OK);
        CHECK_STATUS(pnpr_read_file(bare, NULL, &r, &e), PNPR_OK);
        check_same(&c, &r);
        pnpr_cloud_free(&r);
        CHECK(pnpr_format_from_path("a/B.PCD") == PNPR_FORMAT_PCD && pnpr_format_from_path("x.pcdx") == PNPR_FORMAT_AUTO);
    }
    /* names: an extra "rgb" moves the colours to rgba (U4), an extra "label" moves labels to segment */
    {
        buf b = {0};
        CHECK_STATUS(pnpr_cloud_add_property(&c, "rgb", PNPR_TYPE_FLOAT32, NULL), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_add_property(&c, "label", PNPR_TYPE_FLOAT32, NULL), PNPR_OK);
        CHECK_STATUS(pnpr_write_pcd_stream(sink, &b, &c, NULL, &e), PNPR_OK);
        CHECK(contains((const char *)b.d, "normal_z rgba segment intensity score klass rgb label\n"));
        CHECK_STATUS(read_buf(&b, &r, &e), PNPR_OK);
        CHECK(r.rgb && memcmp(r.rgb, c.rgb, 3 * c.count) == 0 && !r.label && pnpr_cloud_find_property(&r, "segment"));
        pnpr_cloud_free(&r);
        buf_free(&b);
        CHECK_STATUS(pnpr_cloud_add_property(&c, "rgba", PNPR_TYPE_FLOAT32, NULL), PNPR_OK);
        CHECK_STATUS(pnpr_write_pcd_stream(sink, &b, &c, NULL, &e), PNPR_ERR_INVALID_ARGUMENT);
        CHECK(contains(e.message, "colours"));
        buf_free(&b);
        CHECK_STATUS(pnpr_cloud_remove_property(&c, "rgba"), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_add_property(&c, "normal_x", PNPR_TYPE_FLOAT32, NULL), PNPR_OK);
        CHECK_STATUS(pnpr_write_pcd_stream(sink, &b, &c, NULL, &e), PNPR_ERR_INVALID_ARGUMENT);
        CHECK(contains(e.message, "'normal_x' clashes"));
        buf_free(&b);
        CHECK_STATUS(pnpr_cloud_remove_property(&c, "normal_x"), PNPR_OK);
    }
    /* a failing sink */
    {
        buf b = {0};
        b.fail_after = 10;
        CHECK_STATUS(pnpr_write_pcd_stream(sink, &b, &c, NULL, &e), PNPR_ERR_IO);
        CHECK(contains(e.message, "sink failed"));
        buf_free(&b);
    }
    pnpr_cloud_free(&c);
}

/* ---- hostile input ------------------------------------------------------------------------- */

typedef struct bad_case {
    const char *text;
    pnpr_status status;
    long line;          /* expected err.line (0: not checked) */
    const char *needle; /* part of the message */
} bad_case;

#define HDR3 "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"

static const bad_case bad_headers[] = {
    {"", PNPR_ERR_TRUNCATED, 0, "without a DATA line"},
    {"ply\nformat ascii 1.0\n", PNPR_ERR_FORMAT, 1, "line 1: unknown header keyword 'ply'"},
    {HDR3 "WIDTH 2\nHEIGHT 1\nPOINTS 2\n", PNPR_ERR_FORMAT, 8, "without a DATA line"},
    {HDR3 "WIDTH 3\nHEIGHT 2\nPOINTS 10\nDATA ascii\n", PNPR_ERR_FORMAT, 8, "line 8: POINTS 10 but WIDTH x HEIGHT = 3 x 2"},
    {HDR3 "WIDTH -1\n", PNPR_ERR_FORMAT, 6, "line 6: WIDTH wants one non-negative integer"},
    {HDR3 "POINTS 1 2\n", PNPR_ERR_FORMAT, 6, "line 6: POINTS wants one"},
    {"VERSION 0.7\nFIELDS x y z\nSIZE 4 4 3\n", PNPR_ERR_FORMAT, 3, "line 3: SIZE '3' of field 'z' is not 1, 2, 4 or 8"},
    {"VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F Q F\n", PNPR_ERR_FORMAT, 4, "line 4: TYPE 'Q' of field 'y' is unknown"},
    {"VERSION 0.7\nFIELDS x y z\nSIZE 4 4 2\nTYPE F F F\nPOINTS 1\nDATA ascii\n", PNPR_ERR_UNSUPPORTED, 4, "line 4: field 'z' is a 2-byte float"},
    {"VERSION 0.7\nFIELDS x y z\nSIZE 4 4\n", PNPR_ERR_FORMAT, 3, "line 3: SIZE has 2 entries, FIELDS (line 2) has 3"},
    {"VERSION 0.7\nSIZE 4 4 4\nFIELDS x y z\n", PNPR_ERR_FORMAT, 2, "line 2: SIZE comes before FIELDS"},
    {"VERSION 0.7\nFIELDS x y z\nCOUNT 1 1 4000000000\n", PNPR_ERR_FORMAT, 3, "line 3: COUNT '4000000000' of field 'z' is not between 1 and 65536"},
    {"VERSION 0.7\nFIELDS x y z\nCOUNT 1 1 0\n", PNPR_ERR_FORMAT, 3, "is not between 1"},
    {"VERSION 0.7\nFIELDS x y z a b\nCOUNT 1 1 1 65536 2\nPOINTS 1\nDATA ascii\n", PNPR_ERR_FORMAT, 3, "line 3: COUNT adds up to 65541 values per point"},
    {"FIELDS x y z f\nCOUNT 1 1 1 5000\nPOINTS 1\nDATA ascii\n", PNPR_ERR_UNSUPPORTED, 1, "line 1: 5000 extra values per point, at most 4096"},
    {"VERSION 0.7\nFIELDS x y z\nCOUNT 1 2 1\nPOINTS 1\nDATA ascii\n", PNPR_ERR_FORMAT, 3, "line 3: field 'y' has COUNT 2"},
    {"VERSION 0.7\nFIELDS x y q\nPOINTS 1\nDATA ascii\n", PNPR_ERR_FORMAT, 2, "line 2: FIELDS has no z field"},
    {"VERSION 0.7\nFIELDS x y z y\nPOINTS 1\nDATA ascii\n", PNPR_ERR_FORMAT, 2, "line 2: field 'y' appears twice"},
    {"VERSION 0.7\nFIELDS x y z a a_0\nCOUNT 1 1 1 2 1\nPOINTS 1\nDATA ascii\n1 2 3 4 5 6\n", PNPR_ERR_FORMAT, 2, "gives the property name 'a_0' twice"},
    {"VERSION 0.7\nFIELDS x y z\nFIELDS x y z\n", PNPR_ERR_FORMAT, 3, "line 3: second FIELDS line (the first is line 2)"},
    {"VERSION 0.9\n", PNPR_ERR_UNSUPPORTED, 1, "line 1: PCD version '0.9' is not supported"},
    {HDR3 "VIEWPOINT 0 0 0 1 0 0\n", PNPR_ERR_FORMAT, 6, "line 6: VIEWPOINT wants 7 numbers"},
    {HDR3 "VIEWPOINT 0 0 nan 1 0 0 0\n", PNPR_ERR_FORMAT, 6, "line 6: VIEWPOINT value 3 'nan' is not a finite number"},
    {HDR3 "POINTS 1\nDATA binary_lzma\n", PNPR_ERR_FORMAT, 7, "line 7: unknown DATA 'binary_lzma'"},
    {HDR3 "DATA ascii\n", PNPR_ERR_FORMAT, 6, "line 6: no POINTS or WIDTH line before DATA"},
    {"VERSION 0.7\nPOINTS 1\nDATA ascii\n", PNPR_ERR_FORMAT, 3, "line 3: no FIELDS line before DATA"},
    {HDR3 "WID\001TH 1\n", PNPR_ERR_FORMAT, 6, "line 6: invalid character 0x01 in the header"},
    {HDR3 "POINTS 3\nDATA ascii\n1   2   3\n4   5   6\n", PNPR_ERR_TRUNCATED, 10, "line 10: the data ends after 2 of 3 points"},
    {HDR3 "POINTS 1000\nDATA ascii\n1 2 3\n", PNPR_ERR_TRUNCATED, 8, "1000 points of 3 values need more text"},
    {HDR3 "POINTS 2\nDATA ascii\n1 2 3\n4 5\n", PNPR_ERR_FORMAT, 9, "line 9: point 1 has 2 values, the header announces 3"},
    {HDR3 "POINTS 2\nDATA ascii\n1 2 3\n\n4 5 6 7\n", PNPR_ERR_FORMAT, 10, "line 10: point 1 has 4 values"},
    {HDR3 "POINTS 1\nDATA ascii\n1 2 3x\n", PNPR_ERR_FORMAT, 8, "line 8: point 0, field 'z': '3x' is not a number of type F4"},
    {"FIELDS x y z i\nSIZE 4 4 4 1\nTYPE F F F U\nPOINTS 1\nDATA ascii\n1 2 3 256\n", PNPR_ERR_FORMAT, 6,
     "line 6: point 0, field 'i': '256' is out of range for type U1"},
    {"FIELDS x y z i\nSIZE 4 4 4 2\nTYPE F F F I\nPOINTS 1\nDATA ascii\n1 2 3 1.5\n", PNPR_ERR_FORMAT, 6, "'1.5' is not a number of type I2"},
    {"FIELDS x y z i\nSIZE 4 4 4 1\nTYPE F F F U\nPOINTS 1\nDATA ascii\n1 2 3 -1\n", PNPR_ERR_FORMAT, 6, "'-1' is out of range"},
};

static void test_bad_headers_and_ascii(void)
{
    for (size_t t = 0; t < sizeof bad_headers / sizeof bad_headers[0]; t++) {
        const bad_case *bc = &bad_headers[t];
        pnpr_cloud c = {0};
        pnpr_error e;
        pnpr_status st = read_str(bc->text, &c, &e);
        CHECK_MSG(st == bc->status, "case %zu: status %s, expected %s (%s)", t, pnpr_status_string(st),
                  pnpr_status_string(bc->status), e.message);
        CHECK_MSG(contains(e.message, bc->needle), "case %zu: message '%s' lacks '%s'", t, e.message, bc->needle);
        CHECK_MSG(bc->line == 0 || e.line == bc->line, "case %zu: err.line %ld, expected %ld", t, e.line, bc->line);
        CHECK_MSG(cloud_is_zero(&c), "case %zu: cloud not zeroed", t);
    }
    /* integer edge values are accepted */
    pnpr_cloud c = {0};
    CHECK_STATUS(read_str("FIELDS x y z a b c d\nSIZE 4 4 4 1 2 4 8\nTYPE F F F I I U U\nPOINTS 1\nDATA ascii\n"
                          "1 2 3 -128 -32768 4294967295 18446744073709551615\n", &c, NULL), PNPR_OK);
    CHECK(c.prop_count == 4 && pnpr_type_get(c.props[0].type, c.props[0].data, 0) == -128 &&
          pnpr_type_get(c.props[1].type, c.props[1].data, 0) == -32768 &&
          pnpr_type_get(c.props[2].type, c.props[2].data, 0) == 4294967295.0 &&
          pnpr_type_get(c.props[3].type, c.props[3].data, 0) == 18446744073709551616.0);
    pnpr_cloud_free(&c);
}

static const fspec xyz_fields[] = {{"x", 4, 'F', 1}, {"y", 4, 'F', 1}, {"z", 4, 'F', 1}};

/* A binary file of n points, then cut / patched to lie. */
static void test_bad_binary(void)
{
    double v[30];
    for (int i = 0; i < 30; i++) v[i] = i;
    buf b = {0};
    pnpr_cloud c = {0};
    pnpr_error e;
    make_pcd(&b, xyz_fields, 3, v, 10, BINARY, NULL);
    const size_t body = b.n - 120;
    char want[128];
    /* one byte short: point 9 is missing */
    CHECK_STATUS(pnpr_read_pcd_memory(b.d, b.n - 1, NULL, &c, &e), PNPR_ERR_TRUNCATED);
    snprintf(want, sizeof want, "byte %zu: the data ends inside point 9 of 10", body + 108);
    CHECK_MSG(contains(e.message, want) && e.offset == (long long)(body + 108), "%s", e.message);
    CHECK(cloud_is_zero(&c));
    buf_free(&b);
    /* a tiny file announcing 10^12 points fails before allocating */
    header(&b, xyz_fields, 3, 1000000000000ull, NULL, "binary");
    put_str(&b, "0123456789");
    CHECK_STATUS(read_buf(&b, &c, &e), PNPR_ERR_TRUNCATED);
    CHECK_MSG(contains(e.message, "inside point 0 of 1000000000000"), "%s", e.message);
    buf_free(&b);
    /* huge COUNT with binary data: the record is bigger than the file */
    put_str(&b, "FIELDS x y z _\nSIZE 4 4 4 8\nTYPE F F F F\nCOUNT 1 1 1 60000\nPOINTS 2\nDATA binary\nabc");
    CHECK_STATUS(read_buf(&b, &c, &e), PNPR_ERR_TRUNCATED);
    CHECK_MSG(contains(e.message, "480012 bytes per point"), "%s", e.message);
    buf_free(&b);
}

/* binary_compressed whose sizes or LZF stream lie. */
static void test_bad_compressed(void)
{
    double v[30];
    for (int i = 0; i < 30; i++) v[i] = i % 4;
    buf good = {0};
    pnpr_cloud c = {0};
    pnpr_error e;
    make_pcd(&good, xyz_fields, 3, v, 10, COMPRESSED, NULL);
    const char *dl = strstr((const char *)good.d, "DATA binary_compressed\n");
    const size_t body = (size_t)(dl - (const char *)good.d) + strlen("DATA binary_compressed\n");
    const uint32_t csize = (uint32_t)(good.n - body - 8);
    char want[160];
    CHECK_STATUS(read_buf(&good, &c, &e), PNPR_OK);
    CHECK(c.count == 10 && c.xyz[29] == 1.0f);
    pnpr_cloud_free(&c);

    /* the 8-byte size header is cut */
    CHECK_STATUS(pnpr_read_pcd_memory(good.d, body + 5, NULL, &c, &e), PNPR_ERR_TRUNCATED);
    CHECK_MSG(contains(e.message, "inside the 8-byte size header"), "%s", e.message);
    /* the compressed data is cut */
    CHECK_STATUS(pnpr_read_pcd_memory(good.d, good.n - 1, NULL, &c, &e), PNPR_ERR_TRUNCATED);
    snprintf(want, sizeof want, "byte %zu: compressed size %lu, but only %lu bytes follow", body, (unsigned long)csize,
             (unsigned long)csize - 1);
    CHECK_MSG(contains(e.message, want) && e.offset == (long long)body, "%s", e.message);
    CHECK(cloud_is_zero(&c));

    buf b = {0};
    /* uncompressed size that does not match the points */
    put(&b, good.d, good.n);
    b.d[body + 4] ^= 4;
    CHECK_STATUS(read_buf(&b, &c, &e), PNPR_ERR_FORMAT);
    snprintf(want, sizeof want, "byte %zu: uncompressed size 124, but 10 points of 12 bytes need 120", body + 4);
    CHECK_MSG(contains(e.message, want) && e.offset == (long long)(body + 4), "%s", e.message);
    buf_free(&b);
    /* more expansion than LZF can give: 1 compressed byte for 120 bytes */
    header(&b, xyz_fields, 3, 10, NULL, "binary_compressed");
    put_le(&b, 1, 4);
    put_le(&b, 120, 4);
    put(&b, "", 1);
    CHECK_STATUS(read_buf(&b, &c, &e), PNPR_ERR_FORMAT);
    CHECK_MSG(contains(e.message, "1 compressed bytes cannot expand to 120"), "%s", e.message);
    buf_free(&b);
    /* a back reference before the start of the output: the literal 'A', then a reference 2 back */
    header(&b, xyz_fields, 3, 1, NULL, "binary_compressed");
    {
        const size_t at = b.n + 8;
        const unsigned char lzf[] = {0x00, 'A', 0x20, 0x01, 0x07, 'a', 'b', 'c', 'd', 'e', 'f', 'g', 'h'};
        put_le(&b, sizeof lzf, 4);
        put_le(&b, 12, 4);
        put(&b, lzf, sizeof lzf);
        CHECK_STATUS(read_buf(&b, &c, &e), PNPR_ERR_FORMAT);
        snprintf(want, sizeof want, "byte %zu: corrupt LZF data: back reference before the start of the output", at + 2);
        CHECK_MSG(contains(e.message, want) && e.offset == (long long)(at + 2), "%s", e.message);
    }
    buf_free(&b);
    /* a literal run longer than the data, and data that stops short of the announced size */
    header(&b, xyz_fields, 3, 1, NULL, "binary_compressed");
    {
        const unsigned char lzf[] = {0x05, 'a', 'b', 'c', 0x1f, 'x'};
        put_le(&b, 4, 4); /* 4 bytes: the literal run of 6 runs past them */
        put_le(&b, 12, 4);
        put(&b, lzf, sizeof lzf);
        CHECK_STATUS(read_buf(&b, &c, &e), PNPR_ERR_FORMAT);
        CHECK_MSG(contains(e.message, "literal run past the end of the data"), "%s", e.message);
        buf_free(&b);
        header(&b, xyz_fields, 3, 1, NULL, "binary_compressed");
        put_le(&b, 6, 4);
        put_le(&b, 12, 4);
        const unsigned char short_lzf[] = {0x04, '1', '2', '3', '4', '5'};
        put(&b, short_lzf, sizeof short_lzf);
        CHECK_STATUS(read_buf(&b, &c, &e), PNPR_ERR_FORMAT);
        CHECK_MSG(contains(e.message, "LZF data ends after 5 of the 12 announced bytes"), "%s", e.message);
    }
    buf_free(&b);
    /* output longer than announced */
    header(&b, xyz_fields, 3, 1, NULL, "binary_compressed");
    {
        const unsigned char lzf[] = {0x0c, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
        put_le(&b, sizeof lzf, 4);
        put_le(&b, 12, 4);
        put(&b, lzf, sizeof lzf);
        CHECK_STATUS(read_buf(&b, &c, &e), PNPR_ERR_FORMAT);
        CHECK_MSG(contains(e.message, "output longer than announced"), "%s", e.message);
    }
    buf_free(&b);
    /* an empty compressed cloud */
    header(&b, xyz_fields, 3, 0, NULL, "binary_compressed");
    put_le(&b, 0, 4);
    put_le(&b, 0, 4);
    CHECK_STATUS(read_buf(&b, &c, &e), PNPR_OK);
    CHECK(c.count == 0);
    pnpr_cloud_free(&c);
    buf_free(&b);
    buf_free(&good);
}

/* Errors through pnpr_read_file name the file. */
static void test_file_errors(void)
{
    const char *path = PNPR_TEST_SCRATCH "/pcd_bad.pcd";
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return;
    fputs(HDR3 "POINTS 2\nDATA ascii\n1 2 3\n4 5 six\n", f);
    fclose(f);
    pnpr_cloud c = {0};
    pnpr_error e;
    CHECK_STATUS(pnpr_read_file(path, NULL, &c, &e), PNPR_ERR_FORMAT);
    CHECK_MSG(contains(e.message, path) && contains(e.message, "line 9: point 1, field 'z': 'six'"), "%s", e.message);
    CHECK(e.line == 9 && cloud_is_zero(&c));
    CHECK_STATUS(pnpr_read_file(PNPR_TEST_SCRATCH "/pcd_missing.pcd", NULL, &c, &e), PNPR_ERR_IO);
}

/* A 2 GiB sparse file announcing 10^9 points fails from the header (before: 16 s, 2.1 GB). */
static void test_sparse_headers(void)
{
#define SPARSE_HDR "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1000000000\nHEIGHT 1\n" \
                   "POINTS 1000000000\nDATA "
    static const char bin[] = SPARSE_HDR "binary\n", asc[] = SPARSE_HDR "ascii\n", lzf[] = SPARSE_HDR "binary_compressed\n";
#undef SPARSE_HDR
    CHECK(sizeof bin - 1 == 115 && sizeof asc - 1 == 114 && sizeof lzf - 1 == 126); /* the byte counts below follow */
    pnpr_sparse_check(PNPR_TEST_SCRATCH "/pcd_sparse_binary.pcd", bin, sizeof bin - 1, PNPR_ERR_TRUNCATED,
                      "byte 2147483647: the data ends inside point 178956961 of 1000000000 "
                      "(12 bytes per point, 2147483533 bytes after the header)");
    pnpr_sparse_check(PNPR_TEST_SCRATCH "/pcd_sparse_ascii.pcd", asc, sizeof asc - 1, PNPR_ERR_TRUNCATED,
                      "line 10: 1000000000 points of 3 values need more text than the 2147483534 bytes after the header");
    pnpr_sparse_check(PNPR_TEST_SCRATCH "/pcd_sparse_compressed.pcd", lzf, sizeof lzf - 1, PNPR_ERR_FORMAT,
                      "byte 130: uncompressed size 0, but 1000000000 points of 12 bytes need 12000000000");
}

typedef struct progress_log {
    int calls, cancel_at;
    double last;
    char stage[32];
} progress_log;

static int progress_cb(void *user, const char *stage, double fraction)
{
    progress_log *l = user;
    l->calls++;
    l->last = fraction;
    snprintf(l->stage, sizeof l->stage, "%s", stage);
    return l->cancel_at && l->calls >= l->cancel_at;
}

static void test_progress_and_cancel(void)
{
    pnpr_cloud c = {0}, r = {0};
    buf b = {0};
    pnpr_error e;
    CHECK_STATUS(pnpr_cloud_alloc(&c, 200000), PNPR_OK);
    CHECK_STATUS(pnpr_write_pcd_stream(sink, &b, &c, NULL, &e), PNPR_OK);
    progress_log l = {0, 0, 0.0, ""};
    pnpr_read_options ro = {0};
    ro.progress.fn = progress_cb;
    ro.progress.user = &l;
    CHECK_STATUS(pnpr_read_pcd_memory(b.d, b.n, &ro, &r, &e), PNPR_OK);
    CHECK(l.calls >= 4 && l.last == 1.0 && !strcmp(l.stage, "read pcd"));
    pnpr_cloud_free(&r);
    progress_log cl = {0, 2, 0.0, ""};
    ro.progress.user = &cl;
    CHECK_STATUS(pnpr_read_pcd_memory(b.d, b.n, &ro, &r, &e), PNPR_ERR_CANCELLED);
    CHECK(cloud_is_zero(&r) && contains(e.message, "cancelled"));
    buf_free(&b);
    pnpr_write_options wo = {0};
    progress_log wl = {0, 2, 0.0, ""};
    wo.progress.fn = progress_cb;
    wo.progress.user = &wl;
    CHECK_STATUS(pnpr_write_pcd_stream(sink, &b, &c, &wo, &e), PNPR_ERR_CANCELLED);
    CHECK(!strcmp(wl.stage, "write pcd"));
    struct stat sb;
    remove(PNPR_TEST_SCRATCH "/pcd_cancelled.pcd");
    wl.calls = 0;
    CHECK_STATUS(pnpr_write_file(PNPR_TEST_SCRATCH "/pcd_cancelled.pcd", &c, &wo, &e), PNPR_ERR_CANCELLED);
    CHECK(stat(PNPR_TEST_SCRATCH "/pcd_cancelled.pcd", &sb) != 0 && pnpr_test_temporaries(PNPR_TEST_SCRATCH, "pcd_cancelled.pcd") == 0);
    buf_free(&b);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_sparse_headers(); /* first: the peak RSS it measures is its own */
    test_known_values();
    test_rgb_normals_and_old_headers();
    test_double_coordinates();
    test_writer_round_trip();
    test_bad_headers_and_ascii();
    test_bad_binary();
    test_bad_compressed();
    test_file_errors();
    test_progress_and_cancel();
    return pnpr_test_finish("test_pcd");
}
