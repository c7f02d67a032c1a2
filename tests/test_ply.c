/* PLY reader/writer: round trips in all encodings, property mapping, hand-built files, corrupt
 * input with precise errors, progress/cancel. */
#include "sparse_file.h"
#include "testutil.h"

#include <pointnpr/io.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Defined in io/ply.c (not in io.h). */
pnpr_status pnpr_read_ply_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                               pnpr_error *err);
pnpr_status pnpr_write_ply_file(const char *path, const pnpr_cloud *cloud,
                                const pnpr_write_options *opts, pnpr_error *err);

/* ---- helpers ---------------------------------------------------------------------------- */

typedef struct mem_sink {
    pnpr_mem_sink s;   /* the library's memory sink */
    size_t fail_after; /* 0 = never fail */
} mem_sink;

static int mem_write(void *user, const void *data, size_t size)
{
    mem_sink *m = user;
    if (m->fail_after && m->s.size + size > m->fail_after) return 1;
    return pnpr_mem_sink_write(&m->s, data, size);
}

static void mem_free(mem_sink *m)
{
    free(m->s.data);
    memset(m, 0, sizeof *m);
}

static pnpr_status read_str(const char *s, pnpr_cloud *c, pnpr_error *e)
{
    return pnpr_read_ply_memory(s, strlen(s), NULL, c, e);
}

static int contains(const char *hay, const char *needle)
{
    return strstr(hay, needle) != NULL;
}

static int cloud_is_zero(const pnpr_cloud *c)
{
    pnpr_cloud z;
    memset(&z, 0, sizeof z);
    return memcmp(c, &z, sizeof z) == 0;
}

/* Writes `c` with encoding `enc` into memory and reads it back into `out`. */
static pnpr_status round_trip(const pnpr_cloud *c, pnpr_ply_encoding enc, int force_double, pnpr_cloud *out)
{
    mem_sink m = {0};
    pnpr_write_options wo = {0};
    pnpr_error e;
    wo.encoding = enc;
    wo.force_double = force_double;
    pnpr_status st = pnpr_write_ply_stream(mem_write, &m, c, &wo, &e);
    CHECK_MSG(st == PNPR_OK, "write: %s", e.message);
    if (st == PNPR_OK) {
        st = pnpr_read_ply_memory(m.s.data, m.s.size, NULL, out, &e);
        CHECK_MSG(st == PNPR_OK, "read back (encoding %d): %s", (int)enc, e.message);
    }
    mem_free(&m);
    return st;
}

static const pnpr_type all_types[8] = {PNPR_TYPE_INT8,  PNPR_TYPE_UINT8,  PNPR_TYPE_INT16,   PNPR_TYPE_UINT16,
                                       PNPR_TYPE_INT32, PNPR_TYPE_UINT32, PNPR_TYPE_FLOAT32, PNPR_TYPE_FLOAT64};
static const char *const all_names[8] = {"p_int8", "p_uint8", "p_int16", "p_uint16",
                                         "p_int32", "p_uint32", "p_float", "p_double"};

/* A float cloud of n points with normals, colours, labels, every extra type and faces. */
static void make_full_cloud(pnpr_cloud *c, size_t n)
{
    pnpr_test_rng rng = {42};
    CHECK_STATUS(pnpr_cloud_alloc(c, n), PNPR_OK);
    c->src_coord_type = PNPR_TYPE_FLOAT32;
    CHECK_STATUS(pnpr_cloud_alloc_normals(c), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(c), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_labels(c), PNPR_OK);
    for (size_t i = 0; i < n; i++) {
        for (int a = 0; a < 3; a++) {
            c->xyz[3 * i + a] = (float)((pnpr_test_uniform(&rng) - 0.5) * 1000.0);
            c->normal[3 * i + a] = (float)(pnpr_test_uniform(&rng) * 2 - 1);
            c->rgb[3 * i + a] = (uint8_t)(i * 7 + (size_t)a * 50);
        }
        c->label[i] = (uint32_t)(i * 2654435761u);
    }
    c->xyz[0] = 0.1f;         /* not a short decimal */
    c->xyz[1] = -0.0f;
    c->xyz[2] = 1e-30f;
    c->xyz[3] = 3.4028235e38f; /* FLT_MAX */
    c->xyz[4] = 1.17549435e-38f;
    c->xyz[5] = 1.4e-45f;      /* smallest subnormal */
    c->label[0] = 4294967295u;
    c->label[1] = 0;
    for (int t = 0; t < 8; t++) {
        pnpr_property *p = NULL;
        CHECK_STATUS(pnpr_cloud_add_property(c, all_names[t], all_types[t], &p), PNPR_OK);
        if (!p) continue;
        for (size_t i = 0; i < n; i++) pnpr_type_set(p->type, p->data, i, (double)(i % 50) - 20.0);
    }
    /* edge values */
    ((int8_t *)pnpr_cloud_find_property(c, "p_int8")->data)[0] = -128;
    ((int8_t *)pnpr_cloud_find_property(c, "p_int8")->data)[1] = 127;
    ((uint8_t *)pnpr_cloud_find_property(c, "p_uint8")->data)[0] = 255;
    ((int16_t *)pnpr_cloud_find_property(c, "p_int16")->data)[0] = -32768;
    ((int16_t *)pnpr_cloud_find_property(c, "p_int16")->data)[1] = 32767;
    ((uint16_t *)pnpr_cloud_find_property(c, "p_uint16")->data)[0] = 65535;
    ((int32_t *)pnpr_cloud_find_property(c, "p_int32")->data)[0] = INT32_MIN;
    ((int32_t *)pnpr_cloud_find_property(c, "p_int32")->data)[1] = INT32_MAX;
    ((uint32_t *)pnpr_cloud_find_property(c, "p_uint32")->data)[0] = 4294967295u;
    ((float *)pnpr_cloud_find_property(c, "p_float")->data)[0] = NAN;
    ((float *)pnpr_cloud_find_property(c, "p_float")->data)[1] = INFINITY;
    ((float *)pnpr_cloud_find_property(c, "p_float")->data)[2] = -INFINITY;
    ((float *)pnpr_cloud_find_property(c, "p_float")->data)[3] = 0.3f;
    ((double *)pnpr_cloud_find_property(c, "p_double")->data)[0] = 0.1;
    ((double *)pnpr_cloud_find_property(c, "p_double")->data)[1] = -1e300;
    ((double *)pnpr_cloud_find_property(c, "p_double")->data)[2] = 5e-324;
    /* faces: a triangle, a quad, an empty face, a triangle using the last vertex */
    c->faces.count = 4;
    c->faces.offset = malloc(5 * sizeof(uint32_t));
    c->faces.index = malloc(10 * sizeof(uint32_t));
    uint32_t off[5] = {0, 3, 7, 7, 10}, idx[10] = {0, 1, 2, 3, 4, 5, 6, 0, 1, (uint32_t)n - 1};
    memcpy(c->faces.offset, off, sizeof off);
    memcpy(c->faces.index, idx, sizeof idx);
}

static int same_float_bits(float a, float b) { return memcmp(&a, &b, sizeof a) == 0; }

/* ---- round trips --------------------------------------------------------------------------- */

static void test_roundtrip_float(void)
{
    pnpr_cloud c = {0};
    const size_t n = 200;
    make_full_cloud(&c, n);
    for (int enc = 0; enc < 3; enc++) {
        pnpr_cloud r = {0};
        if (round_trip(&c, (pnpr_ply_encoding)enc, 0, &r) != PNPR_OK) continue;
        CHECK(r.count == n);
        CHECK(r.src_coord_type == PNPR_TYPE_FLOAT32);
        CHECK(r.src_xyz == NULL);
        CHECK(r.origin[0] == 0 && r.origin[1] == 0 && r.origin[2] == 0);
        int xyz_ok = 1, nrm_ok = 1;
        for (size_t i = 0; i < 3 * n; i++) {
            xyz_ok &= same_float_bits(r.xyz[i], c.xyz[i]);
            nrm_ok &= same_float_bits(r.normal[i], c.normal[i]);
        }
        CHECK_MSG(xyz_ok, "xyz differ after round trip, encoding %d", enc);
        CHECK_MSG(nrm_ok, "normals differ after round trip, encoding %d", enc);
        CHECK(signbit(r.xyz[1]) && r.xyz[1] == 0.0f);
        CHECK(r.rgb && memcmp(r.rgb, c.rgb, 3 * n) == 0);
        CHECK(r.label && memcmp(r.label, c.label, n * sizeof(uint32_t)) == 0);
        CHECK(r.label && r.label[0] == 4294967295u);
        CHECK(r.prop_count == 8);
        for (int t = 0; t < 8 && t < (int)r.prop_count; t++) {
            CHECK(strcmp(r.props[t].name, all_names[t]) == 0);
            CHECK(r.props[t].type == all_types[t]);
            const pnpr_property *o = pnpr_cloud_find_property(&c, all_names[t]);
            if (all_types[t] == PNPR_TYPE_FLOAT32) {
                const float *a = r.props[t].data, *b = o->data;
                CHECK(isnan(a[0]));
                CHECK(a[1] == INFINITY && a[2] == -INFINITY && a[3] == 0.3f);
                CHECK(memcmp(a + 1, b + 1, (n - 1) * sizeof(float)) == 0);
            } else {
                CHECK_MSG(memcmp(r.props[t].data, o->data, n * pnpr_type_size(all_types[t])) == 0,
                          "extra property %s differs, encoding %d", all_names[t], enc);
            }
        }
        CHECK(((int8_t *)r.props[0].data)[0] == -128);
        CHECK(((uint32_t *)r.props[5].data)[0] == 4294967295u);
        CHECK(((double *)r.props[7].data)[2] == 5e-324);
        CHECK(r.faces.count == 4);
        if (r.faces.count == 4) {
            CHECK(memcmp(r.faces.offset, c.faces.offset, 5 * sizeof(uint32_t)) == 0);
            CHECK(memcmp(r.faces.index, c.faces.index, 10 * sizeof(uint32_t)) == 0);
        }
        pnpr_cloud_free(&r);
    }
    pnpr_cloud_free(&c);
}

static void test_roundtrip_double(void)
{
    pnpr_cloud c = {0};
    const double off[3] = {5e6, -5e6, 1234.5};
    const size_t n = 500;
    CHECK_STATUS(pnpr_test_sphere(&c, n, 10.0, off, 7), PNPR_OK);
    CHECK(c.src_xyz != NULL);
    /* make some coordinates need all 17 digits */
    c.src_xyz[0] = 5000000.123456789;
    c.src_xyz[1] = -4999999.000000001;
    c.src_xyz[2] = 0.1 + 0.2;
    for (int enc = 0; enc < 3; enc++) {
        pnpr_cloud r = {0};
        if (round_trip(&c, (pnpr_ply_encoding)enc, 0, &r) != PNPR_OK) continue;
        CHECK(r.count == n);
        CHECK(r.src_coord_type == PNPR_TYPE_FLOAT64);
        CHECK(r.src_xyz != NULL);
        int exact = 1;
        for (size_t i = 0; i < n; i++) {
            double a[3], b[3];
            pnpr_cloud_world(&c, i, a);
            pnpr_cloud_world(&r, i, b);
            exact &= a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
        }
        CHECK_MSG(exact, "world coordinates not exact after round trip, encoding %d", enc);
        /* origin near the bbox centre, offsets small */
        CHECK_NEAR(r.origin[0], 5e6, 20.0);
        CHECK_NEAR(r.origin[1], -5e6, 20.0);
        CHECK(fabsf(r.xyz[3]) < 100.0f);
        pnpr_cloud_free(&r);
    }
    /* force_double on a float cloud: doubles in the file, values exact */
    {
        pnpr_cloud f = {0}, r = {0};
        make_full_cloud(&f, 20);
        if (round_trip(&f, PNPR_PLY_ASCII, 1, &r) == PNPR_OK) {
            CHECK(r.src_coord_type == PNPR_TYPE_FLOAT64);
            int exact = 1;
            for (size_t i = 0; i < 20; i++) {
                double w[3];
                pnpr_cloud_world(&r, i, w);
                for (int a = 0; a < 3; a++) exact &= w[a] == (double)f.xyz[3 * i + a];
            }
            CHECK(exact);
        }
        pnpr_cloud_free(&r);
        pnpr_cloud_free(&f);
    }
    pnpr_cloud_free(&c);
}

/* A cloud of unknown coordinate type with a large origin must not be squeezed into float. */
static void test_write_unknown_type_keeps_precision(void)
{
    pnpr_cloud c = {0}, r = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&c, 2), PNPR_OK);
    c.origin[0] = 5e6;
    c.xyz[0] = 0.125f;
    c.xyz[3] = -0.375f;
    mem_sink m = {0};
    CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, NULL, NULL), PNPR_OK);
    CHECK(m.s.data && contains((const char *)m.s.data, "property double x"));
    CHECK_STATUS(pnpr_read_ply_memory(m.s.data, m.s.size, NULL, &r, NULL), PNPR_OK);
    double w[3];
    pnpr_cloud_world(&r, 0, w);
    CHECK(w[0] == 5000000.125);
    pnpr_cloud_world(&r, 1, w);
    CHECK(w[0] == 4999999.625);
    mem_free(&m);
    pnpr_cloud_free(&r);
    /* the same cloud at origin 0 is written as float */
    c.origin[0] = 0;
    CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, NULL, NULL), PNPR_OK);
    CHECK(m.s.data && contains((const char *)m.s.data, "property float x"));
    mem_free(&m);
    pnpr_cloud_free(&c);
}

static void test_file_round_trip(void)
{
    const char *path = PNPR_TEST_SCRATCH "/ply_roundtrip.ply";
    pnpr_cloud c = {0}, r = {0};
    pnpr_error e;
    make_full_cloud(&c, 1000);
    pnpr_write_options wo = {0};
    wo.comment = "line one\nline two\r";
    CHECK_STATUS(pnpr_write_ply_file(path, &c, &wo, &e), PNPR_OK);
    CHECK(pnpr_test_temporaries(PNPR_TEST_SCRATCH, "ply_roundtrip.ply") == 0); /* renamed away */
    CHECK_STATUS(pnpr_read_ply_file(path, NULL, &r, &e), PNPR_OK);
    CHECK(r.count == 1000);
    CHECK(r.xyz && memcmp(r.xyz, c.xyz, 3000 * sizeof(float)) == 0);
    CHECK(r.faces.count == 4);
    pnpr_cloud_free(&r);
    /* the header holds the comment on one line plus the generator comment */
    FILE *fp = fopen(path, "rb");
    char head[2048] = {0};
    if (fp) {
        size_t got = fread(head, 1, sizeof head - 1, fp);
        head[got] = '\0';
        fclose(fp);
    }
    CHECK(contains(head, "comment line one line two \n"));
    CHECK(contains(head, "comment generated by pointnpr " PNPR_VERSION_STRING "\n"));
    CHECK(contains(head, "format binary_little_endian 1.0\n"));
    CHECK(contains(head, "property uint segment\n"));
    CHECK(contains(head, "property list uchar uint vertex_indices\n"));

    /* missing file: IO error naming the path */
    CHECK_STATUS(pnpr_read_ply_file(PNPR_TEST_SCRATCH "/ply_does_not_exist.ply", NULL, &r, &e), PNPR_ERR_IO);
    CHECK(contains(e.message, "ply_does_not_exist.ply"));
    /* errors from the memory reader get the path as prefix */
    fp = fopen(PNPR_TEST_SCRATCH "/ply_bad.ply", "wb");
    if (fp) {
        fputs("ply\nformat ascii 1.0\nelement vertex 1\nproperty flaot x\nend_header\n", fp);
        fclose(fp);
    }
    CHECK_STATUS(pnpr_read_ply_file(PNPR_TEST_SCRATCH "/ply_bad.ply", NULL, &r, &e), PNPR_ERR_FORMAT);
    CHECK_MSG(contains(e.message, "ply_bad.ply: line 4: unknown property type 'flaot'"), "%s", e.message);
    CHECK(e.line == 4);
    /* writing into a missing directory fails with IO and leaves nothing */
    CHECK_STATUS(pnpr_write_ply_file(PNPR_TEST_SCRATCH "/ply_no_such_dir/x.ply", &c, NULL, &e), PNPR_ERR_IO);
    CHECK(contains(e.message, "ply_no_such_dir"));
    pnpr_cloud_free(&c);
}

/* ---- property mapping ---------------------------------------------------------------------- */

static void test_property_order(void)
{
    const char *a =
        "ply\nformat ascii 1.0\nelement vertex 2\n"
        "property uchar red\nproperty float x\nproperty float nx\nproperty float y\n"
        "property uchar blue\nproperty float z\nproperty uchar green\nend_header\n"
        "10 1.5 0.25 2.5 30 3.5 20\n"
        "200 -1 1 -2 100 -3 150\n";
    const char *b =
        "ply\nformat ascii 1.0\nelement vertex 2\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float nx\nend_header\n"
        "1.5 2.5 3.5 10 20 30 0.25\n"
        "-1 -2 -3 200 150 100 1\n";
    pnpr_cloud ca = {0}, cb = {0};
    pnpr_error e;
    CHECK_STATUS(read_str(a, &ca, &e), PNPR_OK);
    CHECK_STATUS(read_str(b, &cb, &e), PNPR_OK);
    CHECK(ca.count == 2 && cb.count == 2);
    if (ca.count == 2 && cb.count == 2) {
        CHECK(memcmp(ca.xyz, cb.xyz, 6 * sizeof(float)) == 0);
        CHECK(ca.xyz[0] == 1.5f && ca.xyz[1] == 2.5f && ca.xyz[2] == 3.5f && ca.xyz[5] == -3.0f);
        CHECK(ca.rgb && cb.rgb && memcmp(ca.rgb, cb.rgb, 6) == 0);
        CHECK(ca.rgb && ca.rgb[0] == 10 && ca.rgb[1] == 20 && ca.rgb[2] == 30 && ca.rgb[3] == 200);
        CHECK(ca.normal == NULL); /* nx alone is not a normal */
        CHECK(ca.prop_count == 1 && strcmp(ca.props[0].name, "nx") == 0);
        CHECK(ca.prop_count == 1 && ((float *)ca.props[0].data)[0] == 0.25f);
        CHECK(cb.prop_count == 1 && ((float *)cb.props[0].data)[1] == 1.0f);
    }
    pnpr_cloud_free(&ca);
    pnpr_cloud_free(&cb);
}

static void test_colour_types(void)
{
    pnpr_cloud c = {0};
    pnpr_error e;
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nproperty ushort red\nproperty ushort green\nproperty ushort blue\n"
                          "end_header\n0 0 0 65535 32768 0\n1 1 1 257 128 65534\n2 2 2 32767 1 2\n",
                          &c, &e),
                 PNPR_OK);
    CHECK(c.rgb != NULL);
    if (c.rgb) {
        CHECK(c.rgb[0] == 255 && c.rgb[1] == 128 && c.rgb[2] == 0);
        CHECK(c.rgb[3] == 1 && c.rgb[4] == 0 && c.rgb[5] == 255);
        CHECK(c.rgb[6] == 127 && c.rgb[7] == 0 && c.rgb[8] == 0);
    }
    CHECK(c.prop_count == 0);
    pnpr_cloud_free(&c);
    /* float colours, diffuse_* names */
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                          "property float z\nproperty float diffuse_red\nproperty float diffuse_green\n"
                          "property double diffuse_blue\nend_header\n0 0 0 1.0 0.5 0\n0 0 0 2 -1 nan\n",
                          &c, &e),
                 PNPR_OK);
    CHECK(c.rgb != NULL);
    if (c.rgb) {
        CHECK(c.rgb[0] == 255 && c.rgb[1] == 128 && c.rgb[2] == 0);
        CHECK(c.rgb[3] == 255 && c.rgb[4] == 0 && c.rgb[5] == 0);
    }
    pnpr_cloud_free(&c);
    /* r g b with "red" alone present: r g b is the colour, red stays extra */
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                          "property float z\nproperty uchar red\nproperty uchar r\nproperty uchar g\n"
                          "property uchar b\nend_header\n0 0 0 9 1 2 3\n",
                          &c, &e),
                 PNPR_OK);
    CHECK(c.rgb && c.rgb[0] == 1 && c.rgb[1] == 2 && c.rgb[2] == 3);
    CHECK(c.prop_count == 1 && strcmp(c.props[0].name, "red") == 0);
    /* writing it back uses diffuse_* names (red is taken) and reads back the same */
    {
        pnpr_cloud r = {0};
        if (round_trip(&c, PNPR_PLY_ASCII, 0, &r) == PNPR_OK) {
            CHECK(r.rgb && r.rgb[0] == 1 && r.rgb[1] == 2 && r.rgb[2] == 3);
            CHECK(r.prop_count == 1 && strcmp(r.props[0].name, "red") == 0 && ((uint8_t *)r.props[0].data)[0] == 9);
        }
        pnpr_cloud_free(&r);
    }
    pnpr_cloud_free(&c);
}

static void test_labels_and_extras(void)
{
    pnpr_cloud c = {0};
    pnpr_error e;
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                          "property float z\nproperty float label\nproperty short segment\n"
                          "property uchar alpha\nproperty float intensity\nproperty int quality\n"
                          "property list uchar int neighbours\nend_header\n"
                          "0 0 0 1.5 -1 200 0.5 -7 2 5 6\n1 1 1 2.5 42 0 0.25 8 0\n",
                          &c, &e),
                 PNPR_OK);
    CHECK(c.label != NULL);
    if (c.label) CHECK(c.label[0] == 4294967295u && c.label[1] == 42);
    CHECK(c.prop_count == 4);
    if (c.prop_count == 4) {
        CHECK(strcmp(c.props[0].name, "label") == 0 && c.props[0].type == PNPR_TYPE_FLOAT32);
        CHECK(((float *)c.props[0].data)[1] == 2.5f);
        CHECK(strcmp(c.props[1].name, "alpha") == 0 && c.props[1].type == PNPR_TYPE_UINT8);
        CHECK(((uint8_t *)c.props[1].data)[0] == 200);
        CHECK(strcmp(c.props[2].name, "intensity") == 0 && ((float *)c.props[2].data)[1] == 0.25f);
        CHECK(strcmp(c.props[3].name, "quality") == 0 && c.props[3].type == PNPR_TYPE_INT32);
        CHECK(((int32_t *)c.props[3].data)[0] == -7);
    }
    CHECK(pnpr_cloud_find_property(&c, "neighbours") == NULL);
    /* writing: labels go out as "label" since "segment"... is free here, and back in */
    {
        pnpr_cloud r = {0};
        for (int enc = 0; enc < 3; enc++) {
            if (round_trip(&c, (pnpr_ply_encoding)enc, 0, &r) != PNPR_OK) continue;
            CHECK(r.label && r.label[0] == 4294967295u && r.label[1] == 42);
            CHECK(r.prop_count == 4 && strcmp(r.props[0].name, "label") == 0);
            pnpr_cloud_free(&r);
        }
    }
    pnpr_cloud_free(&c);
}

/* Hand-built big-endian and little-endian files decode to known values. */
static void test_binary_by_hand(void)
{
    static const char hdr_be[] = "ply\nformat binary_big_endian 1.0\nelement vertex 2\n"
                                 "property float x\nproperty float y\nproperty float z\n"
                                 "property short temp\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                                 "property double w\nend_header\n";
    /* vertex 0: 1.0 -2.0 0.5, -2, (255,0,16), 1e10; vertex 1: 3.25 0 -0.0, 258, (1,2,3), -0.5 */
    static const unsigned char body_be[] = {
        0x3f, 0x80, 0x00, 0x00, 0xc0, 0x00, 0x00, 0x00, 0x3f, 0x00, 0x00, 0x00, 0xff, 0xfe, 0xff, 0x00, 0x10,
        0x42, 0x02, 0xa0, 0x5f, 0x20, 0x00, 0x00, 0x00,
        0x40, 0x50, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x00, 0x00, 0x00, 0x01, 0x02, 0x01, 0x02, 0x03,
        0xbf, 0xe0, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00};
    unsigned char buf[512];
    size_t hl = strlen(hdr_be);
    memcpy(buf, hdr_be, hl);
    memcpy(buf + hl, body_be, sizeof body_be);
    pnpr_cloud c = {0};
    pnpr_error e;
    CHECK_STATUS(pnpr_read_ply_memory(buf, hl + sizeof body_be, NULL, &c, &e), PNPR_OK);
    CHECK(c.count == 2);
    if (c.count == 2) {
        CHECK(c.xyz[0] == 1.0f && c.xyz[1] == -2.0f && c.xyz[2] == 0.5f);
        CHECK(c.xyz[3] == 3.25f && c.xyz[4] == 0.0f && signbit(c.xyz[5]));
        CHECK(c.rgb && c.rgb[0] == 255 && c.rgb[1] == 0 && c.rgb[2] == 16 && c.rgb[5] == 3);
        pnpr_property *t = pnpr_cloud_find_property(&c, "temp"), *w = pnpr_cloud_find_property(&c, "w");
        CHECK(t && t->type == PNPR_TYPE_INT16 && ((int16_t *)t->data)[0] == -2 && ((int16_t *)t->data)[1] == 258);
        CHECK(w && w->type == PNPR_TYPE_FLOAT64 && ((double *)w->data)[0] == 1e10 && ((double *)w->data)[1] == -0.5);
    }
    pnpr_cloud_free(&c);

    /* the same content little-endian, with double x y z */
    static const char hdr_le[] = "ply\r\nformat binary_little_endian 1.0\r\ncomment made by hand\r\n"
                                 "obj_info nothing\r\nelement vertex 1\r\nproperty double x\r\nproperty double y\r\n"
                                 "property double z\r\nproperty uint segment\r\nend_header\r\n";
    static const unsigned char body_le[] = {
        0x00, 0x00, 0x00, 0x00, 0xd0, 0x12, 0x53, 0x41, /* 5000000.0 */
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0xbf, /* -1.0 */
        0x9a, 0x99, 0x99, 0x99, 0x99, 0x99, 0xb9, 0x3f, /* 0.1 */
        0x07, 0x00, 0x00, 0x00};
    hl = strlen(hdr_le);
    memcpy(buf, hdr_le, hl);
    memcpy(buf + hl, body_le, sizeof body_le);
    CHECK_STATUS(pnpr_read_ply_memory(buf, hl + sizeof body_le, NULL, &c, &e), PNPR_OK);
    CHECK(c.count == 1 && c.src_coord_type == PNPR_TYPE_FLOAT64 && c.src_xyz);
    if (c.src_xyz) {
        CHECK(c.src_xyz[0] == 5000000.0 && c.src_xyz[1] == -1.0 && c.src_xyz[2] == 0.1);
        CHECK(c.origin[0] == 5000000.0 && c.xyz[0] == 0.0f);
    }
    CHECK(c.label && c.label[0] == 7);
    pnpr_cloud_free(&c);
}

static void test_faces_and_skipped_elements(void)
{
    const char *ascii =
        "ply\nformat ascii 1.0\ncomment skip edge and material\n"
        "element material 2\nproperty uchar ambient_red\nproperty list uchar float coeffs\n"
        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty uchar flags\nproperty list uchar float texcoord\n"
        "property list uchar int vertex_indices\nproperty list uchar uint vertex_index\n"
        "element edge 3\nproperty int vertex1\nproperty int vertex2\nproperty list ushort uchar tags\n"
        "end_header\n"
        "1 2 0.5 0.25\n"
        "2 0\n"
        "0 0 0\n1 0 0\n1 1 0\n\n0 1 0\n"
        "7 2 0.1 0.2 3 0 1 2 1 9\n"
        "0 0 4 3 2 1 0 0\n"
        "0 1 0\n1 2 3 1 2 3\n2 3 0\n";
    pnpr_cloud c = {0};
    pnpr_error e;
    CHECK_STATUS(read_str(ascii, &c, &e), PNPR_OK);
    CHECK_MSG(c.count == 4, "%s", e.message);
    CHECK(c.faces.count == 2);
    if (c.faces.count == 2) {
        CHECK(c.faces.offset[0] == 0 && c.faces.offset[1] == 3 && c.faces.offset[2] == 7);
        const uint32_t want[7] = {0, 1, 2, 3, 2, 1, 0};
        CHECK(memcmp(c.faces.index, want, sizeof want) == 0);
    }
    CHECK(c.xyz && c.xyz[9] == 0.0f && c.xyz[10] == 1.0f);
    CHECK(c.prop_count == 0);

    /* the same file in binary (little and big endian), built by the writer's rules by hand */
    for (int be = 0; be < 2; be++) {
        unsigned char buf[1024];
        size_t n = 0;
        const char *h = be ? "ply\nformat binary_big_endian 1.0\n" : "ply\nformat binary_little_endian 1.0\n";
        const char *rest =
            "element material 2\nproperty uchar ambient_red\nproperty list uchar float coeffs\n"
            "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 2\nproperty uchar flags\nproperty list uchar float texcoord\n"
            "property list uchar int vertex_indices\n"
            "element edge 1\nproperty int vertex1\nproperty list ushort uchar tags\nend_header\n";
        memcpy(buf, h, strlen(h));
        n += strlen(h);
        memcpy(buf + n, rest, strlen(rest));
        n += strlen(rest);
#define PUT8(v) (buf[n++] = (unsigned char)(v))
#define PUT32(v) do { uint32_t u_ = (v); for (int k_ = 0; k_ < 4; k_++) PUT8(be ? u_ >> (24 - 8 * k_) : u_ >> (8 * k_)); } while (0)
#define PUTF(f) do { float f_ = (f); uint32_t u2_; memcpy(&u2_, &f_, 4); PUT32(u2_); } while (0)
        /* material: 1 [0.5 0.25] ; 2 [] */
        PUT8(1); PUT8(2); PUTF(0.5f); PUTF(0.25f);
        PUT8(2); PUT8(0);
        /* vertices */
        const float v[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
        for (int k = 0; k < 12; k++) PUTF(v[k]);
        /* faces */
        PUT8(7); PUT8(1); PUTF(0.1f); PUT8(3); PUT32(0); PUT32(1); PUT32(2);
        PUT8(0); PUT8(0); PUT8(4); PUT32(3); PUT32(2); PUT32(1); PUT32(0);
        /* edge: int, list ushort uchar */
        PUT32(5); PUT8(be ? 0 : 2); PUT8(be ? 2 : 0); PUT8(9); PUT8(9);
#undef PUT8
#undef PUT32
#undef PUTF
        pnpr_cloud b = {0};
        CHECK_STATUS(pnpr_read_ply_memory(buf, n, NULL, &b, &e), PNPR_OK);
        CHECK_MSG(b.count == 4, "binary %s: %s", be ? "BE" : "LE", e.message);
        CHECK(b.xyz && memcmp(b.xyz, c.xyz, 12 * sizeof(float)) == 0);
        CHECK(b.faces.count == 2);
        if (b.faces.count == 2 && c.faces.count == 2) {
            CHECK(memcmp(b.faces.offset, c.faces.offset, 3 * sizeof(uint32_t)) == 0);
            CHECK(memcmp(b.faces.index, c.faces.index, 7 * sizeof(uint32_t)) == 0);
        }
        pnpr_cloud_free(&b);
        /* cut the edge list short: truncated, naming the edge */
        CHECK_STATUS(pnpr_read_ply_memory(buf, n - 1, NULL, &b, &e), PNPR_ERR_TRUNCATED);
        CHECK_MSG(contains(e.message, "edge 0 of 1"), "%s", e.message);
        CHECK(cloud_is_zero(&b));
    }
    pnpr_cloud_free(&c);
}

/* Faces with more than 255 corners are written with a uint count. */
static void test_wide_faces(void)
{
    pnpr_cloud c = {0}, r = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&c, 300), PNPR_OK);
    c.faces.count = 1;
    c.faces.offset = malloc(2 * sizeof(uint32_t));
    c.faces.index = malloc(300 * sizeof(uint32_t));
    c.faces.offset[0] = 0;
    c.faces.offset[1] = 300;
    for (uint32_t i = 0; i < 300; i++) c.faces.index[i] = 299 - i;
    for (int enc = 0; enc < 3; enc++) {
        mem_sink m = {0};
        pnpr_write_options wo = {0};
        wo.encoding = (pnpr_ply_encoding)enc;
        CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, &wo, NULL), PNPR_OK);
        CHECK(m.s.data && contains((const char *)m.s.data, "property list uint uint vertex_indices"));
        CHECK_STATUS(pnpr_read_ply_memory(m.s.data, m.s.size, NULL, &r, NULL), PNPR_OK);
        CHECK(r.faces.count == 1 && r.faces.offset[1] == 300 && r.faces.index[0] == 299 && r.faces.index[299] == 0);
        pnpr_cloud_free(&r);
        mem_free(&m);
    }
    /* a face pointing past the cloud is refused by the writer */
    c.faces.index[5] = 300;
    mem_sink m = {0};
    pnpr_error e;
    CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, NULL, &e), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(contains(e.message, "face 0"));
    mem_free(&m);
    pnpr_cloud_free(&c);
}

/* ---- ascii numbers ------------------------------------------------------------------------- */

static void test_ascii_numbers(void)
{
    pnpr_cloud c = {0};
    pnpr_error e;
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
                          "property float z\nproperty double d\nproperty char i8\nend_header\n"
                          "1e-5 -0 nan 0.1 -128\n"
                          "inf -inf +1.5 5000000.123456789 127\n"
                          ".5 5. 1E+3 -4999999.000000001 1.0\n"
                          "1.000000059604644775390625 1.000000059604644775390626 3.4028235677973366e38 1e400 -0\n"
                          "\t 0.100000001490116119384765625  1e-46   -1.4e-45 2.2250738585072014e-308 +0 \r\n"
                          "123456789012345678901234 0.000000000000000000000000000000000001 1e39 -NAN 1e1\n",
                          &c, &e),
                 PNPR_OK);
    CHECK_MSG(c.count == 6, "%s", e.message);
    if (c.count == 6) {
        const float *x = c.xyz;
        const pnpr_property *d = pnpr_cloud_find_property(&c, "d"), *i8 = pnpr_cloud_find_property(&c, "i8");
        CHECK(x[0] == 1e-5f && x[1] == 0.0f && signbit(x[1]) && isnan(x[2]));
        CHECK(x[3] == INFINITY && x[4] == -INFINITY && x[5] == 1.5f);
        CHECK(x[6] == 0.5f && x[7] == 5.0f && x[8] == 1000.0f);
        CHECK(x[9] == 1.0f);              /* exact midpoint: ties to even */
        CHECK(x[10] == 1.00000012f);      /* just above the midpoint */
        CHECK(x[11] == 3.4028235e38f);
        CHECK(x[12] == 0.1f && x[13] == 0.0f && x[14] == -1.4e-45f);
        CHECK(x[15] == 1.23456789e23f && x[16] == 1e-36f && x[17] == INFINITY);
        CHECK(d && ((double *)d->data)[0] == 0.1 && ((double *)d->data)[1] == 5000000.123456789);
        CHECK(d && ((double *)d->data)[2] == -4999999.000000001 && ((double *)d->data)[3] == INFINITY);
        CHECK(d && ((double *)d->data)[4] == 2.2250738585072014e-308 && isnan(((double *)d->data)[5]));
        CHECK(i8 && ((int8_t *)i8->data)[0] == -128 && ((int8_t *)i8->data)[1] == 127);
        CHECK(i8 && ((int8_t *)i8->data)[2] == 1 && ((int8_t *)i8->data)[3] == 0 && ((int8_t *)i8->data)[5] == 10);
    }
    pnpr_cloud_free(&c);
    /* 1.2 is not an integer */
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                          "property float z\nproperty char i8\nend_header\n1 2 3 1.2\n", &c, &e),
                 PNPR_ERR_FORMAT);
    CHECK_MSG(contains(e.message, "vertex 0 (line 9): expected an integer for char property 'i8', found '1.2'"),
              "%s", e.message);
    /* out of range integer */
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                          "property float z\nproperty uchar red\nend_header\n1 2 3 256\n", &c, &e),
                 PNPR_ERR_FORMAT);
    CHECK_MSG(contains(e.message, "out of range for uchar property 'red'"), "%s", e.message);
    CHECK(e.line == 9);
    /* not a number */
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                          "property float z\nend_header\n1 2 3\n1 2 x3\n", &c, &e),
                 PNPR_ERR_FORMAT);
    CHECK_MSG(contains(e.message, "vertex 1 (line 9)") && contains(e.message, "'x3'"), "%s", e.message);
    CHECK(e.line == 9);
    CHECK(cloud_is_zero(&c));
}

/* Ascii floats read back bit for bit over many bit patterns (every exponent, random mantissas). */
static void test_ascii_float_sweep(void)
{
    const size_t n = 200000;
    pnpr_cloud c = {0}, r = {0};
    pnpr_test_rng rng = {99};
    CHECK_STATUS(pnpr_cloud_alloc(&c, n), PNPR_OK);
    c.src_coord_type = PNPR_TYPE_FLOAT32;
    for (size_t i = 0; i < 3 * n; i++) {
        uint32_t bits;
        if (i < 3 * 256) /* each exponent with a random mantissa, then the extremes */
            bits = ((uint32_t)(i % 256) << 23) | (uint32_t)(pnpr_test_uniform(&rng) * 8388608.0);
        else if (i < 3 * 512)
            bits = ((uint32_t)(i % 256) << 23) | ((i / 256) % 3 == 0 ? 0u : (i / 256) % 3 == 1 ? 1u : 0x7fffffu);
        else
            bits = (uint32_t)(pnpr_test_uniform(&rng) * 4294967296.0);
        if ((bits & 0x7f800000u) == 0x7f800000u) bits &= 0xff7fffffu; /* no NaN/Inf here */
        if (i & 1) bits |= 0x80000000u;
        memcpy(&c.xyz[i], &bits, 4);
    }
    if (round_trip(&c, PNPR_PLY_ASCII, 0, &r) == PNPR_OK) {
        size_t bad = 0;
        for (size_t i = 0; i < 3 * n; i++)
            if (!same_float_bits(r.xyz[i], c.xyz[i])) {
                if (!bad) fprintf(stderr, "first mismatch: %.9g read back as %.9g\n", c.xyz[i], r.xyz[i]);
                bad++;
            }
        CHECK_MSG(bad == 0, "%zu floats changed through ascii", bad);
    }
    /* the text is the short form for simple values */
    {
        pnpr_cloud s = {0};
        mem_sink m = {0};
        pnpr_write_options wo = {0};
        wo.encoding = PNPR_PLY_ASCII;
        CHECK_STATUS(pnpr_cloud_alloc(&s, 2), PNPR_OK);
        const float v[6] = {0.5f, -0.25f, 1e-7f, 123456.75f, 3e20f, -1.5e-42f};
        memcpy(s.xyz, v, sizeof v);
        CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &s, &wo, NULL), PNPR_OK);
        CHECK(mem_write(&m, "", 1) == 0);
        CHECK_MSG(m.s.data && contains((const char *)m.s.data, "end_header\n0.5 -0.25 1.00000001e-07\n123456.75 3.00000006e+20 -1.49938936e-42\n"),
                  "%s", m.s.data ? (const char *)m.s.data : "");
        mem_free(&m);
        pnpr_cloud_free(&s);
    }
    pnpr_cloud_free(&r);
    pnpr_cloud_free(&c);
}

/* Ascii doubles read back bit for bit: coordinates, short decimals, random bit patterns. */
static void test_ascii_double_sweep(void)
{
    const size_t n = 100000;
    pnpr_cloud c = {0}, r = {0};
    pnpr_test_rng rng = {123};
    CHECK_STATUS(pnpr_cloud_alloc(&c, n), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_src_xyz(&c), PNPR_OK);
    c.src_coord_type = PNPR_TYPE_FLOAT64;
    for (size_t i = 0; i < 3 * n; i++) {
        double v;
        switch (i % 6) {
        case 0: v = 5e6 + pnpr_test_uniform(&rng) * 1000.0; break;            /* georeferenced */
        case 1: v = floor(pnpr_test_uniform(&rng) * 1e10) / 1000.0 - 4e6; break; /* mm decimals */
        case 2: v = (pnpr_test_uniform(&rng) - 0.5) * pow(10.0, floor(pnpr_test_uniform(&rng) * 40) - 10); break;
        case 3: v = ldexp(1.0, (int)(pnpr_test_uniform(&rng) * 120) - 60) * (1 + 1e-16 * (double)(i % 7)); break;
        default: {
            uint64_t bits = (uint64_t)(pnpr_test_uniform(&rng) * 18446744073709551616.0);
            memcpy(&v, &bits, 8);
            if (!isfinite(v)) v = 1.0 / 3.0;
        }
        }
        c.src_xyz[i] = v;
    }
    c.src_xyz[0] = 0.1 + 0.2;
    c.src_xyz[1] = 999999999999999.9;
    c.src_xyz[2] = 0.001;
    c.src_xyz[3] = 1e15 - 0.125;
    c.src_xyz[4] = 0.0009999999999999998;
    c.src_xyz[5] = 1e-3 * (1 + 2.2e-16);
    CHECK_STATUS(pnpr_cloud_set_world(&c, c.src_xyz), PNPR_OK);
    if (round_trip(&c, PNPR_PLY_ASCII, 0, &r) == PNPR_OK && r.src_xyz) {
        size_t bad = 0;
        for (size_t i = 0; i < 3 * n; i++)
            if (memcmp(&r.src_xyz[i], &c.src_xyz[i], 8) != 0) {
                if (!bad) fprintf(stderr, "first mismatch: %.17g read back as %.17g\n", c.src_xyz[i], r.src_xyz[i]);
                bad++;
            }
        CHECK_MSG(bad == 0, "%zu doubles changed through ascii", bad);
    }
    pnpr_cloud_free(&r);
    /* short decimals stay short; others get 17 digits */
    {
        pnpr_cloud s = {0};
        mem_sink m = {0};
        pnpr_write_options wo = {0};
        wo.encoding = PNPR_PLY_ASCII;
        wo.force_double = 1;
        CHECK_STATUS(pnpr_cloud_alloc(&s, 1), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_alloc_src_xyz(&s), PNPR_OK);
        s.src_xyz[0] = 5000000.123;
        s.src_xyz[1] = 0.1 + 0.2;
        s.src_xyz[2] = -0.015625;
        CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &s, &wo, NULL), PNPR_OK);
        CHECK(mem_write(&m, "", 1) == 0);
        CHECK_MSG(m.s.data && contains((const char *)m.s.data, "end_header\n5000000.123 0.30000000000000004 -0.015625\n"),
                  "%s", m.s.data ? (const char *)m.s.data : "");
        mem_free(&m);
        pnpr_cloud_free(&s);
    }
    pnpr_cloud_free(&c);
}

/* ---- degenerate and corrupt input --------------------------------------------------------- */

typedef struct bad_case {
    const char *text;
    pnpr_status status;
    const char *words; /* must appear in the message */
    long line;         /* expected err.line, or -1 = don't care */
} bad_case;

static void test_corrupt(void)
{
    static const bad_case cases[] = {
        {"", PNPR_ERR_FORMAT, "expected 'ply' magic", 1},
        {"ply", PNPR_ERR_FORMAT, "no 'end_header' line", -1},
        {"ply\n", PNPR_ERR_FORMAT, "no 'end_header' line", -1},
        {"PLY\nformat ascii 1.0\nend_header\n", PNPR_ERR_FORMAT, "line 1: expected 'ply' magic", 1},
        {"plyx\nformat ascii 1.0\nend_header\n", PNPR_ERR_FORMAT, "line 1: expected 'ply' magic", 1},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", PNPR_ERR_FORMAT,
         "header: no 'end_header' line", -1},
        {"ply\nformat binary_middle_endian 1.0\nend_header\n", PNPR_ERR_FORMAT,
         "line 2: unknown format 'binary_middle_endian'", 2},
        {"ply\nformat ascii 2.0\nend_header\n", PNPR_ERR_FORMAT, "line 2: unsupported PLY version '2.0'", 2},
        {"ply\nelement vertex 0\nproperty float x\nend_header\n", PNPR_ERR_FORMAT, "no 'format' line", -1},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty flaot y\nend_header\n",
         PNPR_ERR_FORMAT, "line 5: unknown property type 'flaot'", 5},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar intt x\nend_header\n",
         PNPR_ERR_FORMAT, "line 4: unknown property type 'intt'", 4},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n",
         PNPR_ERR_FORMAT, "list count type must be an integer type", 4},
        {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", PNPR_ERR_FORMAT,
         "line 3: 'property' before any 'element'", 3},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\nend_header\n0 0\n",
         PNPR_ERR_FORMAT, "no 'x' property", 3},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\nproperty float y\n"
         "property float z\nend_header\n1 0 0 0\n",
         PNPR_ERR_FORMAT, "must be a scalar", 4},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
         "property float x\nend_header\n0 0 0 0\n",
         PNPR_ERR_FORMAT, "line 7: duplicate vertex property 'x'", 7},
        {"ply\nformat ascii 1.0\nelement face 0\nend_header\n", PNPR_ERR_FORMAT, "no 'vertex' element", -1},
        {"ply\nformat ascii 1.0\nelement vertex -5\nproperty float x\nend_header\n", PNPR_ERR_FORMAT,
         "line 3: element 'vertex' has a negative/invalid count '-5'", 3},
        {"ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nproperty float x\nend_header\n",
         PNPR_ERR_FORMAT, "negative/invalid count", 3},
        {"ply\nformat ascii 1.0\nelement vertex 12x\nend_header\n", PNPR_ERR_FORMAT, "negative/invalid count", 3},
        {"ply\nformat ascii 1.0\nelement vertex\nend_header\n", PNPR_ERR_FORMAT, "expected 'element <name> <count>'", 3},
        {"ply\nformat ascii 1.0\nelement vertex 1\nelement vertex 1\nend_header\n", PNPR_ERR_FORMAT,
         "second 'vertex' element", 4},
        {"ply\nformat ascii 1.0\nelement vertex 1\nbogus line\nend_header\n", PNPR_ERR_FORMAT,
         "line 4: unknown header keyword 'bogus'", 4},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float\nend_header\n", PNPR_ERR_FORMAT,
         "expected 'property <type> <name>'", 4},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\x01\nend_header\n", PNPR_ERR_FORMAT,
         "invalid character 0x01", 4},
        {"ply\nformat ascii 1.0\nend_header extra\n", PNPR_ERR_FORMAT, "after 'end_header'", 3},
        /* huge counts fail before allocating anything */
        {"ply\nformat ascii 1.0\nelement vertex 999999999999\nproperty float x\nproperty float y\n"
         "property float z\nend_header\n1 2 3\n",
         PNPR_ERR_TRUNCATED, "element 'vertex' announces 999999999999 items", 3},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 999999999999\nproperty float x\n"
         "property float y\nproperty float z\nend_header\n0123456789ab",
         PNPR_ERR_TRUNCATED, "file ends inside vertex 1 of 999999999999", -1},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\nproperty double x\n"
         "property double y\nproperty double z\nend_header\n",
         PNPR_ERR_TRUNCATED, "file ends inside vertex 0 of 18446744073709551615", -1},
        {"ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
         "property float z\nelement face 4000000000\nproperty list uint uint vertex_indices\nend_header\n"
         "0123456789ab",
         PNPR_ERR_TRUNCATED, "element 'face'", -1},
        /* ascii body problems */
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
         "0 0 0 1 2 3\n1 1 1 1 2\n2 2 2 1 2 3\n",
         PNPR_ERR_FORMAT, "vertex 1 (line 12): expected 6 values, found 5", 12},
        {"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
         "end_header\n0 0 0\n1 1 1 1\n",
         PNPR_ERR_FORMAT, "vertex 1 (line 9): expected 3 values, found 4", 9},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "end_header\n0 0 0\n1 1 1\n",
         PNPR_ERR_TRUNCATED, "file ends inside vertex 2 of 3", -1},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 1 1\n2 2 2\n3 0 1 3\n",
         PNPR_ERR_FORMAT, "face 0 (line 13): vertex index 3 out of range (vertex count 3)", 13},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 1 1\n2 2 2\n3 0 1 -1\n",
         PNPR_ERR_FORMAT, "vertex index -1 out of range", 13},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 1 1\n2 2 2\n200 0 1 2\n",
         PNPR_ERR_FORMAT, "face 0 (line 13): expected 201 values, found 4", 13},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 1 1\n2 2 2\n-3 0 1 2\n",
         PNPR_ERR_FORMAT, "invalid list count '-3'", 13},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 1 1\n2 2 2\n",
         PNPR_ERR_TRUNCATED, "file ends inside face 0 of 1", -1},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const bad_case *bc = &cases[k];
        pnpr_cloud c = {0};
        pnpr_error e;
        memset(&e, 0, sizeof e);
        pnpr_status st = read_str(bc->text, &c, &e);
        CHECK_MSG(st == bc->status, "case %zu: status %s, expected %s (%s)", k, pnpr_status_string(st),
                  pnpr_status_string(bc->status), e.message);
        CHECK_MSG(contains(e.message, bc->words), "case %zu: message '%s' lacks '%s'", k, e.message, bc->words);
        if (bc->line >= 0) CHECK_MSG(e.line == bc->line, "case %zu: err.line %ld, expected %ld", k, e.line, bc->line);
        CHECK_MSG(cloud_is_zero(&c), "case %zu: cloud not zeroed", k);
    }
    /* NULL arguments */
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_read_ply_memory(NULL, 10, NULL, &c, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_read_ply_memory("ply\n", 4, NULL, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_read_ply_memory(NULL, 0, NULL, &c, NULL), PNPR_ERR_FORMAT);
}

static void test_truncated_binary(void)
{
    const char *hdr = "ply\nformat binary_little_endian 1.0\nelement vertex 10\nproperty float x\n"
                      "property float y\nproperty float z\nend_header\n";
    unsigned char buf[512];
    size_t hl = strlen(hdr);
    memcpy(buf, hdr, hl);
    memset(buf + hl, 0, 120);
    pnpr_cloud c = {0};
    pnpr_error e;
    CHECK_STATUS(pnpr_read_ply_memory(buf, hl + 120, NULL, &c, &e), PNPR_OK);
    CHECK(c.count == 10);
    pnpr_cloud_free(&c);
    /* 5.5 vertices present */
    CHECK_STATUS(pnpr_read_ply_memory(buf, hl + 66, NULL, &c, &e), PNPR_ERR_TRUNCATED);
    CHECK_MSG(contains(e.message, "file ends inside vertex 5 of 10") &&
                  contains(e.message, "needs 120 bytes, 66 present"), "%s", e.message);
    CHECK(e.offset == (long long)(hl + 66));
    CHECK(cloud_is_zero(&c));
    /* a body that ends exactly between vertices */
    CHECK_STATUS(pnpr_read_ply_memory(buf, hl + 108, NULL, &c, &e), PNPR_ERR_TRUNCATED);
    CHECK_MSG(contains(e.message, "vertex 9 of 10"), "%s", e.message);

    /* binary face list with an absurd count */
    const char *fh = "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
                     "property float y\nproperty float z\nelement face 1\nproperty list uint int vertex_indices\n"
                     "end_header\n";
    hl = strlen(fh);
    memcpy(buf, fh, hl);
    memset(buf + hl, 0, 12);
    const unsigned char huge[4] = {0xff, 0xff, 0xff, 0x7f};
    memcpy(buf + hl + 12, huge, 4);
    memset(buf + hl + 16, 0, 8);
    CHECK_STATUS(pnpr_read_ply_memory(buf, hl + 24, NULL, &c, &e), PNPR_ERR_TRUNCATED);
    CHECK_MSG(contains(e.message, "face 0 of 1") && contains(e.message, "2147483647 items"), "%s", e.message);
    CHECK(cloud_is_zero(&c));
    /* negative count in a signed count type */
    const char *nh = "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
                     "property float y\nproperty float z\nelement face 1\nproperty list char int vertex_indices\n"
                     "end_header\n";
    hl = strlen(nh);
    memcpy(buf, nh, hl);
    memset(buf + hl, 0, 12);
    buf[hl + 12] = 0xff;
    memset(buf + hl + 13, 0, 8);
    CHECK_STATUS(pnpr_read_ply_memory(buf, hl + 21, NULL, &c, &e), PNPR_ERR_FORMAT);
    CHECK_MSG(contains(e.message, "negative list count -1"), "%s", e.message);
    /* face index out of range in binary */
    buf[hl + 12] = 2;
    memset(buf + hl + 13, 0, 8);
    buf[hl + 17] = 1; /* second index = 1, vertex count 1 */
    CHECK_STATUS(pnpr_read_ply_memory(buf, hl + 21, NULL, &c, &e), PNPR_ERR_FORMAT);
    CHECK_MSG(contains(e.message, "face 0: vertex index 1 out of range (vertex count 1)"), "%s", e.message);
    CHECK(e.offset == (long long)(hl + 17));
    CHECK(cloud_is_zero(&c));
}

/* Ascii bodies hold at least 2 bytes a value ("0 0 1\n"; the very last line may lack its
 * newline). A body above 64 KiB that holds less fails from the header, before anything is
 * allocated; a smaller one is still parsed (storing nothing) so that the error names the line. */
static char *ascii_lines(const char *head, size_t n, const char *line, size_t *r_len)
{
    const size_t hl = strlen(head), ll = strlen(line);
    char *b = malloc(hl + n * ll);
    if (!b) return NULL;
    memcpy(b, head, hl);
    for (size_t i = 0; i < n; i++) memcpy(b + hl + i * ll, line, ll);
    *r_len = hl + n * ll;
    return b;
}

static void test_ascii_body_bound(void)
{
    pnpr_cloud c = {0};
    pnpr_error e;
    size_t len = 0;
    char *b = ascii_lines("ply\nformat ascii 1.0\nelement vertex 12000\nproperty float x\nproperty float y\n"
                          "property float z\nend_header\n", 12000, "0 0 1\n", &len);
    CHECK(b != NULL);
    if (!b) return;
    /* exactly the least: 12000 lines of 6 bytes, the last one without its newline */
    CHECK_STATUS(pnpr_read_ply_memory(b, len - 1, NULL, &c, &e), PNPR_OK);
    CHECK(c.count == 12000 && c.xyz && c.xyz[3 * 11999 + 2] == 1.0f);
    /* one byte less ("0 0 " ends the body): 71998 bytes, above 64 KiB, fail from the header */
    CHECK_STATUS(pnpr_read_ply_memory(b, len - 2, NULL, &c, &e), PNPR_ERR_TRUNCATED);
    CHECK_MSG(strcmp(e.message, "line 3: element 'vertex' announces 12000 items, but the ascii body has only "
                                "71998 bytes (at least 71999 needed)") == 0, "%s", e.message);
    CHECK(e.line == 3 && c.count == 0 && c.xyz == NULL);
    free(b);
    /* the same shortfall in a small body: the parser names the line (header: 7 lines) */
    b = ascii_lines("ply\nformat ascii 1.0\nelement vertex 100\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n", 100, "0 0 1\n", &len);
    CHECK(b != NULL);
    if (!b) return;
    CHECK_STATUS(pnpr_read_ply_memory(b, len - 2, NULL, &c, &e), PNPR_ERR_FORMAT);
    CHECK_MSG(strcmp(e.message, "vertex 99 (line 107): expected 3 values, found 2") == 0, "%s", e.message);
    CHECK(e.line == 107 && c.count == 0 && c.xyz == NULL);
    free(b);
    /* an element read for nothing needs a non-blank line an item, not its values */
    b = ascii_lines("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                    "property float z\nelement edge 40000\nproperty int vertex1\nproperty int vertex2\nend_header\n",
                    40000, "7\n", &len);
    CHECK(b != NULL);
    if (!b) return;
    CHECK_STATUS(pnpr_read_ply_memory(b, len, NULL, &c, &e), PNPR_OK);
    CHECK(c.count == 0);
    pnpr_cloud_free(&c);
    free(b);
}

/* A 2 GiB sparse file announcing 10^9 vertices fails from the header (before: 16-23 s, 2.1 GB). */
static void test_sparse_headers(void)
{
    static const char bin[] = "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
                              "property float y\nproperty float z\nend_header\n";
    static const char asc[] = "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\n"
                              "property float y\nproperty float z\nend_header\n";
    CHECK(sizeof bin - 1 == 124 && sizeof asc - 1 == 109); /* the byte counts below follow */
    pnpr_sparse_check(PNPR_TEST_SCRATCH "/ply_sparse_binary.ply", bin, sizeof bin - 1, PNPR_ERR_TRUNCATED,
                      "byte 2147483648: file ends inside vertex 178956960 of 1000000000 "
                      "(binary body needs 12000000000 bytes, 2147483524 present)");
    pnpr_sparse_check(PNPR_TEST_SCRATCH "/ply_sparse_ascii.ply", asc, sizeof asc - 1, PNPR_ERR_TRUNCATED,
                      "line 3: element 'vertex' announces 1000000000 items, but the ascii body has only "
                      "2147483539 bytes (at least 5999999999 needed)");
}

static void test_small_files(void)
{
    pnpr_cloud c = {0};
    pnpr_error e;
    /* zero vertices: valid */
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                          "property float z\nend_header\n", &c, &e), PNPR_OK);
    CHECK(c.count == 0 && c.faces.count == 0);
    pnpr_cloud_free(&c);
    CHECK_STATUS(read_str("ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
                          "property float y\nproperty float z\nend_header", &c, &e), PNPR_OK);
    CHECK(c.count == 0);
    /* and it writes back */
    {
        pnpr_cloud r = {0};
        for (int enc = 0; enc < 3; enc++) {
            CHECK_STATUS(round_trip(&c, (pnpr_ply_encoding)enc, 0, &r), PNPR_OK);
            CHECK(r.count == 0);
            pnpr_cloud_free(&r);
        }
    }
    pnpr_cloud_free(&c);
    /* one vertex, no trailing newline, CRLF everywhere, comments and obj_info, blank header line */
    CHECK_STATUS(read_str("ply\r\nformat ascii 1.0\r\ncomment hello\r\nobj_info scanner X\r\n\r\n"
                          "element vertex 1\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
                          "end_header\r\n  -1.25\t2.5 3e2", &c, &e), PNPR_OK);
    CHECK(c.count == 1 && c.xyz && c.xyz[0] == -1.25f && c.xyz[1] == 2.5f && c.xyz[2] == 300.0f);
    CHECK(c.rgb == NULL && c.normal == NULL && c.label == NULL && c.prop_count == 0);
    pnpr_cloud_free(&c);
    /* normals need all three */
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                          "property float z\nproperty double nx\nproperty short ny\nproperty float nz\n"
                          "end_header\n0 0 0 0.5 -1 0.25\n", &c, &e), PNPR_OK);
    CHECK(c.normal && c.normal[0] == 0.5f && c.normal[1] == -1.0f && c.normal[2] == 0.25f);
    pnpr_cloud_free(&c);
    /* integer coordinates: small ones as float, int ones exact through src_xyz */
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 1\nproperty short x\nproperty uchar y\n"
                          "property char z\nend_header\n-300 200 -100\n", &c, &e), PNPR_OK);
    CHECK(c.src_coord_type == PNPR_TYPE_FLOAT32 && c.xyz[0] == -300.0f && c.xyz[1] == 200.0f && c.xyz[2] == -100.0f);
    pnpr_cloud_free(&c);
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\nproperty uint y\n"
                          "property float z\nend_header\n-2147483648 4294967295 1\n", &c, &e), PNPR_OK);
    CHECK(c.src_coord_type == PNPR_TYPE_FLOAT64 && c.src_xyz && c.src_xyz[0] == -2147483648.0 &&
          c.src_xyz[1] == 4294967295.0 && c.src_xyz[2] == 1.0);
    pnpr_cloud_free(&c);
    /* an ascii file with trailing blank lines and extra data after the last element */
    CHECK_STATUS(read_str("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                          "property float z\nend_header\n\n\n1 2 3\n\n\n", &c, &e), PNPR_OK);
    CHECK(c.count == 1 && c.xyz[2] == 3.0f);
    pnpr_cloud_free(&c);
}

/* ---- progress / cancel -------------------------------------------------------------------- */

typedef struct progress_log {
    int calls;
    int cancel_at; /* cancel on this call (1-based), 0 = never */
    double last;
    int monotonic;
    char stage[32];
} progress_log;

static int progress_cb(void *user, const char *stage, double fraction)
{
    progress_log *l = user;
    l->calls++;
    if (fraction < l->last) l->monotonic = 0;
    l->last = fraction;
    snprintf(l->stage, sizeof l->stage, "%s", stage);
    return l->cancel_at && l->calls >= l->cancel_at;
}

static void test_progress_and_cancel(void)
{
    pnpr_cloud c = {0}, r = {0};
    const size_t n = 10000;
    CHECK_STATUS(pnpr_cloud_alloc(&c, n), PNPR_OK);
    for (size_t i = 0; i < 3 * n; i++) c.xyz[i] = (float)i;
    for (int enc = 0; enc < 3; enc++) {
        mem_sink m = {0};
        progress_log wl = {0, 0, 0.0, 1, ""};
        pnpr_write_options wo = {0};
        wo.encoding = (pnpr_ply_encoding)enc;
        wo.progress.fn = progress_cb;
        wo.progress.user = &wl;
        CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, &wo, NULL), PNPR_OK);
        CHECK(wl.calls >= 50 && wl.calls <= 210 && wl.monotonic && wl.last == 1.0);
        CHECK(strcmp(wl.stage, "write ply") == 0);

        progress_log rl = {0, 0, 0.0, 1, ""};
        pnpr_read_options ro = {0};
        ro.progress.fn = progress_cb;
        ro.progress.user = &rl;
        CHECK_STATUS(pnpr_read_ply_memory(m.s.data, m.s.size, &ro, &r, NULL), PNPR_OK);
        CHECK(r.count == n);
        CHECK(rl.calls >= 50 && rl.calls <= 210 && rl.monotonic && rl.last == 1.0);
        CHECK(strcmp(rl.stage, "read ply") == 0);
        pnpr_cloud_free(&r);

        /* cancel half way */
        progress_log cl = {0, 50, 0.0, 1, ""};
        pnpr_error e;
        ro.progress.user = &cl;
        CHECK_STATUS(pnpr_read_ply_memory(m.s.data, m.s.size, &ro, &r, &e), PNPR_ERR_CANCELLED);
        CHECK(cloud_is_zero(&r));
        CHECK(cl.calls == 50);
        CHECK(contains(e.message, "cancelled"));
        mem_free(&m);

        /* cancelling the writer */
        progress_log wc = {0, 10, 0.0, 1, ""};
        wo.progress.user = &wc;
        CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, &wo, &e), PNPR_ERR_CANCELLED);
        mem_free(&m);
    }
    /* a cancelled file write leaves neither the file nor the temporary */
    {
        progress_log wc = {0, 1, 0.0, 1, ""};
        pnpr_write_options wo = {0};
        struct stat sb;
        wo.progress.fn = progress_cb;
        wo.progress.user = &wc;
        remove(PNPR_TEST_SCRATCH "/ply_cancelled.ply");
        CHECK_STATUS(pnpr_write_ply_file(PNPR_TEST_SCRATCH "/ply_cancelled.ply", &c, &wo, NULL), PNPR_ERR_CANCELLED);
        CHECK(stat(PNPR_TEST_SCRATCH "/ply_cancelled.ply", &sb) != 0);
        CHECK(pnpr_test_temporaries(PNPR_TEST_SCRATCH, "ply_cancelled.ply") == 0);
    }
    /* a failing sink gives an IO error */
    {
        mem_sink m = {0};
        pnpr_error e;
        m.fail_after = 100;
        CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, NULL, &e), PNPR_ERR_IO);
        CHECK(contains(e.message, "sink failed"));
        mem_free(&m);
    }
    pnpr_cloud_free(&c);
}

static void test_writer_arguments(void)
{
    pnpr_cloud c = {0};
    mem_sink m = {0};
    pnpr_error e;
    CHECK_STATUS(pnpr_cloud_alloc(&c, 2), PNPR_OK);
    CHECK_STATUS(pnpr_write_ply_stream(NULL, &m, &c, NULL, &e), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, NULL, NULL, &e), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_write_options wo = {0};
    wo.encoding = (pnpr_ply_encoding)7;
    CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, &wo, &e), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_cloud_add_property(&c, "bad name", PNPR_TYPE_UINT8, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, NULL, &e), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(contains(e.message, "blanks"));
    CHECK_STATUS(pnpr_cloud_remove_property(&c, "bad name"), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_add_property(&c, "x", PNPR_TYPE_UINT8, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, NULL, &e), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(contains(e.message, "'x' clashes"));
    CHECK_STATUS(pnpr_cloud_remove_property(&c, "x"), PNPR_OK);
    /* labels plus an extra "segment": labels are written as "label" */
    CHECK_STATUS(pnpr_cloud_alloc_labels(&c), PNPR_OK);
    c.label[1] = 5;
    CHECK_STATUS(pnpr_cloud_add_property(&c, "segment", PNPR_TYPE_FLOAT32, NULL), PNPR_OK);
    m.s.size = 0;
    wo.encoding = PNPR_PLY_ASCII;
    CHECK_STATUS(pnpr_write_ply_stream(mem_write, &m, &c, &wo, &e), PNPR_OK);
    CHECK(m.s.data && contains((const char *)m.s.data, "property uint label\nproperty float segment\n"));
    pnpr_cloud r = {0};
    CHECK_STATUS(pnpr_read_ply_memory(m.s.data, m.s.size, NULL, &r, &e), PNPR_OK);
    CHECK(r.label && r.label[1] == 5 && r.prop_count == 1);
    pnpr_cloud_free(&r);
    mem_free(&m);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_sparse_headers(); /* first: the peak RSS it measures is its own */
    test_roundtrip_float();
    test_roundtrip_double();
    test_write_unknown_type_keeps_precision();
    test_file_round_trip();
    test_property_order();
    test_colour_types();
    test_labels_and_extras();
    test_binary_by_hand();
    test_faces_and_skipped_elements();
    test_wide_faces();
    test_ascii_numbers();
    test_ascii_float_sweep();
    test_ascii_double_sweep();
    test_corrupt();
    test_truncated_binary();
    test_ascii_body_bound();
    test_small_files();
    test_progress_and_cancel();
    test_writer_arguments();
    return pnpr_test_finish("test_ply");
}
