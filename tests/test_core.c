/* Status strings, property management, append/merge of clouds, origin handling, style maps. */
#include "testutil.h"

#include <pointnpr/look.h>
#include <pointnpr/options.h>

#include <pointnpr/memory.h>
#include <pointnpr/style.h>
#include "../core/internal.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void test_status_strings(void)
{
    for (int s = 0; s < PNPR_STATUS_COUNT_; s++) {
        const char *t = pnpr_status_string((pnpr_status)s);
        CHECK(t && t[0]);
        CHECK(strcmp(t, "unknown status") != 0);
    }
    CHECK(strcmp(pnpr_status_string((pnpr_status)999), "unknown status") == 0);
    CHECK(strcmp(pnpr_status_string(PNPR_ERR_TRUNCATED), "file is truncated") == 0);
}

static void test_zero_cloud_is_valid(void)
{
    pnpr_cloud c = {0};
    float lo[3], hi[3];
    CHECK(pnpr_cloud_bounds(&c, lo, hi) == 0);
    pnpr_cloud_free(&c);
    pnpr_cloud_free(NULL);
    CHECK(c.count == 0 && c.xyz == NULL);
}

static void test_properties(void)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&c, 4), PNPR_OK);
    pnpr_property *p = NULL;
    CHECK_STATUS(pnpr_cloud_add_property(&c, "intensity", PNPR_TYPE_UINT16, &p), PNPR_OK);
    CHECK(p && p->type == PNPR_TYPE_UINT16);
    pnpr_type_set(p->type, p->data, 3, 70000.0); /* saturates */
    CHECK(pnpr_type_get(p->type, p->data, 3) == 65535.0);
    pnpr_type_set(PNPR_TYPE_INT8, p->data, 0, NAN); /* NaN -> 0 for integers */
    CHECK(((int8_t *)p->data)[0] == 0);
    CHECK_STATUS(pnpr_cloud_add_property(&c, "", PNPR_TYPE_UINT8, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_cloud_add_property(&c, "x", PNPR_TYPE_NONE, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(pnpr_cloud_find_property(&c, "intensity") != NULL);
    CHECK_STATUS(pnpr_cloud_remove_property(&c, "intensity"), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_remove_property(&c, "intensity"), PNPR_ERR_NOT_FOUND);
    pnpr_cloud_free(&c);
}

/* Two tiles ~5e6 away from the origin merge with exact world coordinates and offsets that
 * are precise to well below a millimetre. */
static void test_append_georeferenced(void)
{
    pnpr_cloud a = {0}, b = {0}, m = {0};
    const double oa[3] = {5e6 + 0.123, 4e6, 250.0}, ob[3] = {5e6 + 20.456, 4e6 + 5.0, 251.0};
    CHECK_STATUS(pnpr_test_plane(&a, 10, 10, 0.01, oa), PNPR_OK);
    CHECK_STATUS(pnpr_test_plane(&b, 5, 5, 0.01, ob), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_add_property(&b, "intensity", PNPR_TYPE_UINT16, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_append(&m, &a), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_append(&m, &b), PNPR_OK);
    CHECK(m.count == 125);
    CHECK(m.src_xyz != NULL);
    double w[3];
    pnpr_cloud_world(&m, 100, w);
    CHECK(w[0] == ob[0] && w[1] == ob[1] && w[2] == ob[2]);
    for (size_t i = 0; i < m.count; i++)
        for (int k = 0; k < 3; k++) {
            double rel = m.origin[k] + (double)m.xyz[3 * i + k];
            CHECK_NEAR(rel, m.src_xyz[3 * i + k], 1e-5);
        }
    pnpr_property *p = pnpr_cloud_find_property(&m, "intensity");
    CHECK(p && p->type == PNPR_TYPE_UINT16);
    pnpr_cloud_free(&a); pnpr_cloud_free(&b); pnpr_cloud_free(&m);
}

/* Style maps from memory: entries in file order, the last default, NAME:LINE errors. */
static void test_style_map(void)
{
    static const char text[] = "# map\n0 points\n4294967295 Sketchy # case\n\n* cartoon\n7 lines\n* stipple";
    pnpr_style_map m;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_style_map_parse(text, sizeof text - 1, "m.txt", &m, &err), PNPR_OK);
    CHECK(m.count == 3 && m.have_default && m.default_style == PNPR_STYLE_STIPPLE);
    CHECK(m.count == 3 && m.entries[0].label == 0 && m.entries[0].style == PNPR_STYLE_POINTS);
    CHECK(m.count == 3 && m.entries[1].label == 4294967295u && m.entries[1].style == PNPR_STYLE_SKETCHY);
    CHECK(m.count == 3 && m.entries[2].label == 7 && m.entries[2].style == PNPR_STYLE_LINES);
    pnpr_style_map_free(&m);
    CHECK(m.entries == NULL && m.count == 0 && !m.have_default);
    CHECK_STATUS(pnpr_style_map_parse("", 0, "e.txt", &m, &err), PNPR_OK);
    CHECK(m.count == 0 && !m.have_default);
    static const struct { const char *text, *message; } bad[] = {
        {"1 points\n2 nosuch\n", "b.txt:2: unknown style 'nosuch' (points, sketchy, lines, stipple, cartoon, painterly, brush, hierarchy)"},
        {"4294967296 points\n", "b.txt:1: label '4294967296' is not an integer in 0..4294967295 or '*'"},
        {"-1 points\n", "b.txt:1: label '-1' is not an integer in 0..4294967295 or '*'"},
        {"\n\n1 points extra\n", "b.txt:3: want 'LABEL STYLE' or '* STYLE'"},
        {"1\n", "b.txt:1: want 'LABEL STYLE' or '* STYLE'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        CHECK_STATUS(pnpr_style_map_parse(bad[i].text, strlen(bad[i].text), "b.txt", &m, &err), PNPR_ERR_FORMAT);
        CHECK_MSG(!strcmp(err.message, bad[i].message), "got '%s'", err.message);
        CHECK(m.entries == NULL && m.count == 0);
    }
    char longline[1100];
    memset(longline, 'x', sizeof longline);
    CHECK_STATUS(pnpr_style_map_parse(longline, sizeof longline, "l.txt", &m, &err), PNPR_ERR_FORMAT);
    CHECK_MSG(!strcmp(err.message, "l.txt:1: line longer than 1022 characters") && err.line == 1, "got '%s'", err.message);
}

/* pnpr_select_float / _double (core/median.c) against qsort: every k of small arrays with many
 * duplicates, the partition property, sorted / reversed / constant 1M arrays (a quadratic
 * selection would run for minutes there), NaN present (terminates, the finite k-th unaffected when
 * the NaNs are not in play is not promised: only that it returns) */
static void test_select(void)
{
    pnpr_test_rng rng = {11};
    enum { SMALL = 37 };
    float a[SMALL], b[SMALL], sorted[SMALL];
    for (int round = 0; round < 50; round++) {
        size_t n = 1 + (size_t)(pnpr_test_uniform(&rng) * SMALL);
        for (size_t i = 0; i < n; i++) sorted[i] = a[i] = (float)(int)(pnpr_test_uniform(&rng) * (round % 5 + 1));
        qsort(sorted, n, sizeof *sorted, pnpr_cmp_float);
        for (size_t k = 0; k < n; k++) {
            memcpy(b, a, n * sizeof *a);
            float v = pnpr_select_float(b, n, k);
            CHECK_MSG(v == sorted[k] && b[k] == v, "round %d: the %zu-th of %zu is %g, not %g", round, k, n, v, sorted[k]);
            int split = 1;
            for (size_t i = 0; i < n; i++) split &= i < k ? b[i] <= v : b[i] >= v;
            CHECK_MSG(split, "round %d: %zu-th of %zu: not partitioned", round, k, n);
        }
        CHECK(pnpr_median_float(a, n) == sorted[n / 2]);
    }
    enum { BIG = 1000000 };
    double *d = malloc(BIG * sizeof *d);
    CHECK(d != NULL);
    for (int kind = 0; d && kind < 3; kind++) {
        for (size_t i = 0; i < BIG; i++) d[i] = kind == 0 ? (double)i : kind == 1 ? (double)(BIG - i) : 2.5;
        double want = kind == 0 ? BIG / 2 : kind == 1 ? BIG / 2 + 1 : 2.5; /* 0..BIG-1, 1..BIG, constant */
        CHECK_MSG(pnpr_select_double(d, BIG, BIG / 2) == want, "kind %d: median %g, want %g", kind, d[BIG / 2], want);
    }
    free(d);
    float withnan[5] = {3, NAN, 1, NAN, 2};
    (void)pnpr_select_float(withnan, 5, 2); /* returns */
    float one = 4;
    CHECK(pnpr_select_float(&one, 1, 0) == 4);
}

/* memory.h: sizes parsed and printed, the estimate's parts (the feature stage at k, the renderer's
 * frame in tiles beyond 8192 px) and its saturation, the check's two messages. */
static void test_memory(void)
{
    static const struct { const char *text; size_t bytes; } ok[] = {
        {"512M", (size_t)512 << 20}, {"4G", (size_t)4 << 30}, {"1.5G", (size_t)3 << 29}, {"4GiB", (size_t)4 << 30},
        {"4gb", (size_t)4 << 30}, {"100", 100}, {"2k", 2048}, {"1T", (size_t)1 << 40}};
    for (size_t i = 0; i < sizeof ok / sizeof *ok; i++) {
        size_t b = 0;
        CHECK_MSG(pnpr_memory_parse(ok[i].text, &b) == 0 && b == ok[i].bytes, "'%s' -> %zu", ok[i].text, b);
    }
    static const char *const bad[] = {"0", "-1", "abc", "4X", "1e30", "", "4 G", "0.5", "nan", "inf"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        size_t b = 7;
        CHECK_MSG(pnpr_memory_parse(bad[i], &b) == -1 && b == 7, "'%s' accepted", bad[i]);
    }
    char buf[32];
    CHECK(!strcmp(pnpr_memory_text(0, buf, sizeof buf), "0 B"));
    CHECK(!strcmp(pnpr_memory_text(1536, buf, sizeof buf), "1.5 KiB"));
    CHECK(!strcmp(pnpr_memory_text((size_t)730 << 20, buf, sizeof buf), "730 MiB"));
    CHECK(!strcmp(pnpr_memory_text((size_t)1 << 30, buf, sizeof buf), "1.0 GiB"));

    pnpr_memory_estimate e;
    pnpr_memory_plan p = {1000000, 16, 1, 0, 0, 0, 0, 0};
    pnpr_memory_estimate_plan(&p, &e);
    CHECK(e.render == 0 && e.stages > 0 && e.total == e.kept + e.stages);
    pnpr_memory_plan p32 = p;
    p32.features_k = 32; /* 4 bytes a neighbour more per point */
    pnpr_memory_estimate e32;
    pnpr_memory_estimate_plan(&p32, &e32);
    CHECK_MSG(e32.stages - e.stages == (size_t)16 * 4 * 1000000, "k 32 vs 16: %zu more", e32.stages - e.stages);
    /* a frame of 16384 x 16384 is drawn in tiles of 8192: its pixels beyond one tile cost 8 bytes */
    pnpr_memory_plan r1 = {1000, 0, 0, 0, 1u << PNPR_STYLE_POINTS, 8192, 8192, 0}, r2 = r1;
    r2.width = r2.height = 16384;
    pnpr_memory_estimate a, b;
    pnpr_memory_estimate_plan(&r1, &a);
    pnpr_memory_estimate_plan(&r2, &b);
    CHECK_MSG(b.render - a.render == (size_t)8 * (16384ull * 16384 - 8192ull * 8192), "tiles: %zu", b.render - a.render);
    /* drawing: 286 bytes a drawn point (points style) up to 138 MiB; drawn 0 = every point */
    pnpr_memory_plan d0 = {100000, 0, 0, 0, 1u << PNPR_STYLE_POINTS, 64, 48, 10000}, d1 = d0, d2 = d0;
    d1.drawn = 20000;
    d2.drawn = 0;
    pnpr_memory_estimate_plan(&d0, &a);
    pnpr_memory_estimate_plan(&d1, &b);
    CHECK_MSG(b.render - a.render == (size_t)286 * 10000, "10000 drawn points more: %zu", b.render - a.render);
    pnpr_memory_estimate_plan(&d2, &b);
    CHECK_MSG(b.render - a.render == (size_t)286 * 90000, "every point drawn: %zu", b.render - a.render);
    d1.points = d1.drawn = 10000000;
    d2 = d1;
    d2.drawn = 20000000; /* past the cap (138 MiB at 482k drawn): no more */
    pnpr_memory_estimate_plan(&d1, &a);
    pnpr_memory_estimate_plan(&d2, &b);
    CHECK(a.render == b.render && a.render - (size_t)72 * 10000000 - ((size_t)96 << 20) - 64 * 48 * 52 == (size_t)138 << 20);
    pnpr_memory_plan huge = {SIZE_MAX / 2, 1024, 1, 1, ~0u, 1 << 30, 1 << 30, 0};
    pnpr_memory_estimate_plan(&huge, &e);
    CHECK(e.total == SIZE_MAX && e.render == SIZE_MAX);

    pnpr_error err = {0};
    CHECK_STATUS(pnpr_memory_check(SIZE_MAX / 2, 0, "a huge cloud", &err), PNPR_ERR_OUT_OF_MEMORY);
    CHECK_MSG(strstr(err.message, "a huge cloud needs about") && strstr(err.message, "available"), "%s", err.message);
    CHECK_STATUS(pnpr_memory_check(1, 1024, "x", &err), pnpr_memory_resident() ? PNPR_ERR_OUT_OF_MEMORY : PNPR_OK);
    CHECK_STATUS(pnpr_memory_check(1, (size_t)1 << 50, "x", NULL), PNPR_OK);
}

/* The looks (look.h): names unique, lower case without spaces, found case-insensitively; applied to
 * zeroed options they give option values in the draw table's ranges and an opaque paper; an explicit
 * choice of the caller stays. */
static void test_looks(void)
{
    size_t n = 0;
    const pnpr_look *looks = pnpr_looks(&n);
    CHECK(looks != NULL && n >= 5);
    size_t nt = 0;
    const pnpr_option_desc *table = pnpr_draw_option_table(&nt);
    for (size_t i = 0; i < n; i++) {
        const char *name = looks[i].name;
        CHECK(name && name[0] && looks[i].description && looks[i].description[0]);
        for (const char *c = name; *c; c++) CHECK_MSG(*c >= 'a' && *c <= 'z', "look '%s'", name);
        for (size_t j = 0; j < i; j++) CHECK(strcmp(name, looks[j].name) != 0);
        size_t k = 99;
        char upper[32];
        snprintf(upper, sizeof upper, "%s", name);
        for (char *c = upper; *c; c++) *c = (char)(*c - 'a' + 'A');
        CHECK_STATUS(pnpr_look_find(upper, &k), PNPR_OK);
        CHECK(k == i);
        pnpr_draw_options o;
        memset(&o, 0, sizeof o);
        pnpr_look_apply(&looks[i], &o);
        CHECK(o.style == looks[i].style && (unsigned)o.style < PNPR_STYLE_COUNT_);
        CHECK(o.background[3] == 1 && o.background[0] == looks[i].paper[0] / 255.0f);
        pnpr_error err = {0};
        CHECK_MSG(pnpr_option_check(table, nt, &o, &err) == PNPR_OK, "look '%s': %s", name, err.message);
    }
    size_t k = 0;
    CHECK_STATUS(pnpr_look_find("crayon", &k), PNPR_ERR_NOT_FOUND);
    CHECK_STATUS(pnpr_look_find(NULL, &k), PNPR_ERR_INVALID_ARGUMENT);
    char buf[256];
    CHECK(strncmp(pnpr_look_list(buf, sizeof buf, ", "), looks[0].name, strlen(looks[0].name)) == 0);
    /* sepia: its ink and paper on zeroed options; a given line width, ink and background stay */
    CHECK_STATUS(pnpr_look_find("sepia", &k), PNPR_OK);
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    pnpr_look_apply(&looks[k], &o);
    CHECK(o.style == PNPR_STYLE_SKETCHY && o.outline == 1 && o.ink[0] > o.ink[2] && o.background[0] > o.background[2]);
    memset(&o, 0, sizeof o);
    o.line_width = 3;
    o.ink[3] = 0.5f;
    o.background[3] = 1; /* opaque black, given */
    o.sketch_variant = PNPR_SKETCH_DIRECTIONAL;
    pnpr_look_apply(&looks[k], &o);
    CHECK(o.line_width == 3 && o.ink[0] == 0 && o.ink[3] == 0.5f && o.background[0] == 0 && o.background[3] == 1);
    CHECK(o.sketch_variant == PNPR_SKETCH_DIRECTIONAL);
    pnpr_look_apply(NULL, &o); /* no crash */
    pnpr_look_apply(&looks[k], NULL);
}

int main(void)
{
    test_select();
    test_memory();
    test_looks();
    test_status_strings();
    test_zero_cloud_is_valid();
    test_properties();
    test_append_georeferenced();
    test_style_map();
    return pnpr_test_finish("test_core");
}
