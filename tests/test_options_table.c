/* The options tables (options.h) are the one place of every default and range:
 *  - each entry is well formed and its default lies within its range;
 *  - pnpr_X_defaults() equals the table's defaults field by field (and nothing else is set);
 *  - zero-initialised options compute exactly what pnpr_X_defaults() passed explicitly does
 *    (features, lines, jseg, rgbgrow, components, hierarchy, outliers: outputs compared bytewise);
 *  - pnpr_option_check refuses values out of range with a message naming the option and its range;
 *  - the CLI's usage text shows each option's default and range from the table, and its parser
 *    accepts exactly the table's range (runs the built `pointnpr`), render and animate included
 *    (pnpr_draw_option_table, pnpr_upload_option_table; tests/render/test_render_defaults.c draws
 *    zeroed and pnpr_draw_defaults() options and compares the bytes). */
#include "testutil.h"

#include <pointnpr/options.h>
#include <pointnpr/props.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef const pnpr_option_desc *(*table_fn)(size_t *r_count);
typedef struct table_case {
    const char *name;
    table_fn table;
    size_t size;  /* sizeof the struct */
    void *defaults; /* pnpr_X_defaults() */
} table_case;

/* The entry's default as its member holds it. */
static double as_stored(const pnpr_option_desc *d, double v)
{
    return d->type == PNPR_OPTION_FLOAT ? (double)(float)v : d->type == PNPR_OPTION_INT ? (double)(int)v
         : d->type == PNPR_OPTION_UINT ? (double)(uint32_t)v : v;
}

static void check_table(const table_case *tc)
{
    size_t n = 0;
    const pnpr_option_desc *t = tc->table(&n);
    CHECK_MSG(t && n > 0, "%s: empty table", tc->name);
    unsigned char *rest = malloc(tc->size), *zero = calloc(1, tc->size);
    memcpy(rest, tc->defaults, tc->size);
    for (size_t i = 0; i < n; i++) {
        const pnpr_option_desc *d = &t[i];
        CHECK_MSG(d->name && d->field && d->group && d->help && d->help[0], "%s: entry %zu lacks text", tc->name, i);
        CHECK_MSG(pnpr_option_find(t, n, d->name) == d, "%s: name %s twice", tc->name, d->name);
        CHECK_MSG(d->offset < tc->size, "%s.%s: offset outside the struct", tc->name, d->field);
        CHECK_MSG(d->min <= d->max, "%s.%s: min above max", tc->name, d->field);
        if (d->def != 0 || (d->flags & PNPR_OPTION_ZERO_IS_VALUE))
            CHECK_MSG(pnpr_option_in_range(d, d->def), "%s.%s: default %g outside its range", tc->name, d->field, d->def);
        else
            CHECK_MSG(d->auto_text != NULL, "%s.%s: default 0 without saying what it means", tc->name, d->field);
        double got = pnpr_option_get(d, tc->defaults);
        /* a default of some styles only: pnpr_X_defaults() leaves 0 (the style's default) */
        double want = (d->flags & PNPR_OPTION_STYLE_DEFAULT) ? 0 : as_stored(d, d->def);
        CHECK_MSG(got == want, "%s.%s: pnpr_%s_defaults() has %g, the table %g", tc->name, d->field,
                  tc->name, got, want);
        pnpr_option_set(d, rest, 0);
    }
    CHECK_MSG(memcmp(rest, zero, tc->size) == 0, "%s: pnpr_%s_defaults() sets members the table lacks", tc->name,
              tc->name);
    CHECK_STATUS(pnpr_option_check(t, n, tc->defaults, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_option_check(t, n, zero, NULL), PNPR_OK);
    free(rest);
    free(zero);
}

/* Out-of-range values are refused with the option, its value and its range in the message. */
static void check_refusals(const table_case *tc)
{
    size_t n = 0;
    const pnpr_option_desc *t = tc->table(&n);
    unsigned char *o = malloc(tc->size);
    for (size_t i = 0; i < n; i++) {
        const pnpr_option_desc *d = &t[i];
        if (d->type == PNPR_OPTION_FLOAT && d->max < PNPR_OPTION_UNBOUNDED) { /* stored as the float nearest */
            memcpy(o, tc->defaults, tc->size);
            pnpr_option_set(d, o, d->max);
            CHECK_MSG(pnpr_option_check(&t[i], 1, o, NULL) == PNPR_OK, "%s.%s = its max %g refused", tc->name, d->field, d->max);
        }
        double bad[2] = {d->max < PNPR_OPTION_UNBOUNDED ? d->max + 1 : NAN,
                         (d->flags & PNPR_OPTION_MIN_EXCLUSIVE) ? d->min : d->min - 1};
        for (int b = 0; b < 2; b++) {
            if (d->type != PNPR_OPTION_FLOAT && d->type != PNPR_OPTION_DOUBLE && isnan(bad[b])) continue;
            if (bad[b] == 0 && !(d->flags & PNPR_OPTION_ZERO_IS_VALUE)) continue; /* 0 = the default */
            if (bad[b] < 0 && ((d->flags & PNPR_OPTION_NEGATIVE_OFF) || d->type == PNPR_OPTION_UINT)) continue;
            memcpy(o, tc->defaults, tc->size);
            pnpr_option_set(d, o, bad[b]);
            pnpr_error err = {0};
            char range[64];
            pnpr_option_range_text(d, range, sizeof range);
            CHECK_MSG(pnpr_option_check(t, n, o, &err) == PNPR_ERR_INVALID_ARGUMENT, "%s.%s = %g accepted", tc->name,
                      d->field, bad[b]);
            CHECK_MSG(strstr(err.message, d->field) && strstr(err.message, range), "%s.%s: message '%s'", tc->name,
                      d->field, err.message);
        }
    }
    free(o);
}

/* The renderer's defaults of the style: the mask scale and the ink come from the table. */
static void renderer_defaults(void)
{
    size_t n;
    const pnpr_option_desc *t = pnpr_draw_option_table(&n);
    pnpr_draw_options z = {0};
    CHECK_MSG(pnpr_draw_mask_scale(&z, PNPR_STYLE_POINTS) == (float)pnpr_option_find(t, n, "mask-scale")->def,
              "mask scale default");
    CHECK_MSG(pnpr_draw_mask_scale(NULL, PNPR_STYLE_CARTOON) == (float)pnpr_option_find(t, n, "outline-scale")->def,
              "cartoon mask scale default");
    float ink[4];
    CHECK_MSG(pnpr_draw_ink(&z, ink) == 0 && ink[2] == (float)pnpr_option_find(t, n, "ink-b")->def &&
              ink[3] == (float)pnpr_option_find(t, n, "ink-a")->def, "ink default");
    z.ink[0] = 1;
    CHECK_MSG(pnpr_draw_ink(&z, ink) == 1 && ink[0] == 1 && ink[3] == 0, "given ink");
    pnpr_draw_options d = pnpr_draw_defaults();
    CHECK_MSG(d.style == PNPR_STYLE_POINTS && d.mask_scale == 0 && d.ink[3] == 0 && d.outline == 0, "style defaults left 0");
    /* the renderer's check: each tabled member against its entry, mask_scale against its style's */
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_draw_check(&d, &err), PNPR_OK);
    d.mask_scale = 0.5f; /* in "mask-scale"'s range, below "outline-scale"'s */
    CHECK_STATUS(pnpr_draw_check(&d, &err), PNPR_OK);
    d.style = PNPR_STYLE_CARTOON;
    CHECK_STATUS(pnpr_draw_check(&d, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "mask_scale") != NULL, "cartoon mask scale: '%s'", err.message);
    d.mask_scale = 3;
    CHECK_STATUS(pnpr_draw_check(&d, &err), PNPR_OK);
    d.outline_width = 65; /* "outline-width" ends at 64 */
    CHECK_STATUS(pnpr_draw_check(&d, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "outline_width") != NULL, "outline width: '%s'", err.message);
    d.outline_width = 0;
    d.levels = 1;
    CHECK_STATUS(pnpr_draw_check(&d, &err), PNPR_ERR_INVALID_ARGUMENT);
    d.levels = 0;
    d.point_scale = NAN;
    CHECK_STATUS(pnpr_draw_check(&d, &err), PNPR_ERR_INVALID_ARGUMENT);
}

/* A noisy coloured cube: feature lines along the edges, colours per face. */
static void make_cloud(pnpr_cloud *c)
{
    const double off[3] = {0, 0, 0};
    CHECK_STATUS(pnpr_test_cube(c, 1.0, 0.04, 0.002, off, 7), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(c), PNPR_OK);
    for (size_t i = 0; i < c->count; i++) {
        const float *p = c->xyz + 3 * i;
        int face = p[0] < 0.01f ? 0 : p[1] < 0.01f ? 1 : p[2] < 0.01f ? 2 : p[0] > 0.99f ? 3 : p[1] > 0.99f ? 4 : 5;
        for (int a = 0; a < 3; a++) c->rgb[3 * i + a] = (uint8_t)(40 * face + 30 * a);
    }
}

static int same_property(const pnpr_cloud *a, const pnpr_cloud *b, const char *name)
{
    const pnpr_property *pa = pnpr_cloud_find_property((pnpr_cloud *)a, name);
    const pnpr_property *pb = pnpr_cloud_find_property((pnpr_cloud *)b, name);
    return pa && pb && pa->type == pb->type &&
           memcmp(pa->data, pb->data, a->count * pnpr_type_size(pa->type)) == 0;
}

static int same_lines(const pnpr_polylines *a, const pnpr_polylines *b)
{
    if (a->count != b->count) return 0;
    if (!a->count) return 1;
    return !memcmp(a->offset, b->offset, (a->count + 1) * sizeof *a->offset) &&
           !memcmp(a->xyz, b->xyz, 3 * a->offset[a->count] * sizeof *a->xyz) &&
           !memcmp(a->closed, b->closed, a->count);
}

static void features_and_lines_zero_equals_defaults(void)
{
    pnpr_cloud z = {0}, d = {0};
    make_cloud(&z);
    make_cloud(&d);
    pnpr_features_options zo = {0}, dopt = pnpr_features_defaults();
    pnpr_features_stats zs, ds;
    CHECK_STATUS(pnpr_compute_features(&z, &zo, &zs), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&d, &dopt, &ds), PNPR_OK);
    CHECK(zs.k_used == ds.k_used && zs.threshold_used == ds.threshold_used && zs.dither_points == ds.dither_points);
    CHECK(memcmp(z.normal, d.normal, 3 * z.count * sizeof(float)) == 0);
    static const char *const props[] = {PNPR_PROP_FEATURE_DEGREE, PNPR_PROP_FEATURE_CLASS, PNPR_PROP_FEATURE_CONFIDENCE,
                                        PNPR_PROP_FEATURE_DIR_X, PNPR_PROP_FEATURE_DIR_Y, PNPR_PROP_FEATURE_DIR_Z};
    for (size_t i = 0; i < sizeof props / sizeof props[0]; i++)
        CHECK_MSG(same_property(&z, &d, props[i]), "features: %s differs between zero and the defaults", props[i]);
    printf("features: %zu points, %zu directional, %zu dithering\n", z.count, zs.directional_points, zs.dither_points);
    CHECK(zs.directional_points > 0);

    pnpr_lines_options lz = {0}, ld = pnpr_lines_defaults();
    pnpr_polylines pz = {0}, pd = {0};
    CHECK_STATUS(pnpr_profile_lines(&z, &lz, &pz, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_profile_lines(&z, &ld, &pd, NULL), PNPR_OK);
    printf("lines: %zu polylines\n", pz.count);
    CHECK(pz.count > 0);
    CHECK_MSG(same_lines(&pz, &pd), "lines differ between zero and the defaults");
    pnpr_lines_free(&pz);
    pnpr_lines_free(&pd);
    pnpr_cloud_free(&z);
    pnpr_cloud_free(&d);
}

static int labels_equal(const uint32_t *a, const uint32_t *b, size_t n, const pnpr_segment_info *ia,
                        const pnpr_segment_info *ib)
{
    return ia->segment_count == ib->segment_count && memcmp(a, b, n * sizeof *a) == 0;
}

static void segment_zero_equals_defaults(void)
{
    pnpr_cloud c = {0};
    make_cloud(&c);
    const size_t n = c.count;
    uint32_t *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    pnpr_segment_info ia, ib;
    pnpr_jseg_options jz = {0}, jd = pnpr_jseg_defaults();
    CHECK_STATUS(pnpr_segment_jseg(c.xyz, c.rgb, n, &jz, a, &ia), PNPR_OK);
    CHECK_STATUS(pnpr_segment_jseg(c.xyz, c.rgb, n, &jd, b, &ib), PNPR_OK);
    CHECK_MSG(labels_equal(a, b, n, &ia, &ib), "jseg differs between zero and the defaults");
    printf("jseg: %u segments\n", ia.segment_count);

    /* the hierarchy over the jseg segments */
    enum { K = 8 };
    uint32_t *knn = malloc(n * K * sizeof *knn);
    pnpr_kdtree *tree = NULL;
    CHECK_STATUS(pnpr_kdtree_build(c.xyz, n, 0, &tree), PNPR_OK);
    pnpr_knn_options ko = {0, {0}, 0};
    CHECK_STATUS(pnpr_knn_self(tree, n, K, &ko, knn, NULL), PNPR_OK);
    pnpr_region_graph g = {knn, K, K};
    uint32_t S = ia.segment_count, mz = 0, md = 0;
    pnpr_segment_merge *merges_z = calloc(S, sizeof *merges_z), *merges_d = calloc(S, sizeof *merges_d);
    pnpr_hierarchy_options hz = {0}, hd = pnpr_hierarchy_defaults();
    CHECK_STATUS(pnpr_segment_hierarchy(c.rgb, n, &g, a, S, &hz, merges_z, &mz), PNPR_OK);
    CHECK_STATUS(pnpr_segment_hierarchy(c.rgb, n, &g, a, S, &hd, merges_d, &md), PNPR_OK);
    CHECK_MSG(mz == md && memcmp(merges_z, merges_d, mz * sizeof *merges_z) == 0, "hierarchy differs");
    free(merges_z); free(merges_d); free(knn);
    pnpr_kdtree_free(tree);

    pnpr_rgbgrow_options rz = {0}, rd = pnpr_rgbgrow_defaults();
    CHECK_STATUS(pnpr_segment_rgbgrow(c.xyz, c.rgb, n, &rz, a, &ia), PNPR_OK);
    CHECK_STATUS(pnpr_segment_rgbgrow(c.xyz, c.rgb, n, &rd, b, &ib), PNPR_OK);
    CHECK_MSG(labels_equal(a, b, n, &ia, &ib), "rgbgrow differs between zero and the defaults");
    pnpr_components_options cz = {0}, cd = pnpr_components_defaults();
    CHECK_STATUS(pnpr_segment_components(c.xyz, n, &cz, a, &ia), PNPR_OK);
    CHECK_STATUS(pnpr_segment_components(c.xyz, n, &cd, b, &ib), PNPR_OK);
    CHECK_MSG(labels_equal(a, b, n, &ia, &ib), "components differ between zero and the defaults");

    pnpr_outlier_options oz = {0}, od = pnpr_outlier_defaults();
    pnpr_outlier_info iz, id;
    CHECK_STATUS(pnpr_cloud_outliers(&c, &oz, NULL, &iz), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_outliers(&c, &od, NULL, &id), PNPR_OK);
    CHECK(memcmp(&iz, &id, sizeof iz) == 0);
    free(a); free(b);
    pnpr_cloud_free(&c);
}

/* ---- the CLI ------------------------------------------------------------------------------- */

/* Output (stdout and stderr) of `pointnpr ARGS`, malloc'd. */
static char *run_cli(const char *args)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "'%s' %s 2>&1", PNPR_CLI, args);
    FILE *p = popen(cmd, "r");
    if (!p) return NULL;
    size_t cap = 1 << 16, len = 0;
    char *buf = malloc(cap);
    size_t got;
    while ((got = fread(buf + len, 1, cap - 1 - len, p)) > 0) {
        len += got;
        if (len + 1 == cap) buf = realloc(buf, cap *= 2);
    }
    buf[len] = 0;
    pclose(p);
    return buf;
}

/* The text of the usage entry of --name: its line and its continuation lines, newlines as spaces. */
static void usage_entry(const char *usage, const char *name, char *r, size_t cap)
{
    char key[80];
    snprintf(key, sizeof key, "\n  --%s ", name);
    const char *s = strstr(usage, key);
    r[0] = 0;
    if (!s) return;
    s += 1;
    size_t len = 0;
    for (const char *e = s; *e && len + 1 < cap; e++) {
        if (*e == '\n' && (e[1] != ' ' || e[2] != ' ' || e[3] != ' ')) break; /* not a continuation */
        r[len++] = *e == '\n' ? ' ' : *e;
    }
    r[len] = 0;
}

static void check_usage_entry(const char *cmd, const char *usage, const pnpr_option_desc *d)
{
    char entry[1024], want[256], def[64], range[64];
    usage_entry(usage, d->name, entry, sizeof entry);
    pnpr_option_default_text(d, def, sizeof def);
    pnpr_option_range_text(d, range, sizeof range);
    snprintf(want, sizeof want, "(default %s, %s)", def, range);
    CHECK_MSG(strstr(entry, want) != NULL, "%s --help: --%s shows '%s', the table says '%s'", cmd, d->name, entry, want);
}

/* The parser takes the bounds of the range and refuses just beyond them; below the minimum, a
 * NEGATIVE_OFF entry takes a negative value (off). */
static void check_parser(const char *cmd, const pnpr_option_desc *d)
{
    char args[256], refusal[96];
    snprintf(refusal, sizeof refusal, "--%s wants", d->name);
    double ok[2] = {d->max < PNPR_OPTION_UNBOUNDED ? d->max : d->min + 1, (d->flags & PNPR_OPTION_MIN_EXCLUSIVE) ? d->min + 1e-3 : d->min};
    double bad[2] = {d->max < PNPR_OPTION_UNBOUNDED ? d->max * 2 + 1 : NAN,
                     (d->flags & PNPR_OPTION_MIN_EXCLUSIVE) ? d->min : d->min - 1};
    for (int i = 0; i < 2; i++) {
        if (ok[i] > d->max) continue;
        snprintf(args, sizeof args, "%s --%s %.17g", cmd, d->name, ok[i]);
        char *out = run_cli(args);
        CHECK_MSG(out && !strstr(out, refusal), "pointnpr %s: refused: %s", args, out ? out : "");
        free(out);
        if (isnan(bad[i])) continue;
        snprintf(args, sizeof args, "%s --%s %.17g", cmd, d->name, bad[i]);
        out = run_cli(args);
        if (i == 1 && (d->flags & PNPR_OPTION_NEGATIVE_OFF) && bad[i] < 0)
            CHECK_MSG(out && !strstr(out, refusal), "pointnpr %s: a negative (off) refused: %s", args, out ? out : "");
        else
            CHECK_MSG(out && strstr(out, refusal), "pointnpr %s: not refused: %s", args, out ? out : "");
        free(out);
    }
}

/* Every option of `names` (entries of table) in `cmd --help`, and its parsing. */
static void check_cli_options(const char *cmd, table_fn table_of, const char *const *names)
{
    size_t n;
    const pnpr_option_desc *t = table_of(&n);
    char args[64];
    snprintf(args, sizeof args, "%s --help", cmd);
    char *usage = run_cli(args);
    CHECK_MSG(usage && strstr(usage, "usage: pointnpr"), "%s --help printed no usage", cmd);
    for (size_t i = 0; usage && names[i]; i++) {
        const pnpr_option_desc *d = pnpr_option_find(t, n, names[i]);
        CHECK_MSG(d != NULL, "no table entry %s", names[i]);
        if (!d) continue;
        check_usage_entry(cmd, usage, d);
        check_parser(cmd, d);
    }
    free(usage);
}

/* segment: one usage entry per option, with each method's default and the range. */
static void check_segment_usage(void)
{
    char *usage = run_cli("segment --help");
    static const char *const names[] = {"radius", "min-size", "k", "classes"};
    static const struct { const char *method; table_fn table; } methods[3] = {
        {"jseg", pnpr_jseg_option_table}, {"rgbgrow", pnpr_rgbgrow_option_table},
        {"components", pnpr_components_option_table}};
    for (int o = 0; usage && o < 4; o++) {
        char entry[1024], want[128], def[64], range[64] = "";
        usage_entry(usage, names[o], entry, sizeof entry);
        for (int m = 0; m < 3; m++) {
            size_t n;
            const pnpr_option_desc *t = methods[m].table(&n), *d = pnpr_option_find(t, n, names[o]);
            if (!d) continue;
            pnpr_option_default_text(d, def, sizeof def);
            if (!range[0]) pnpr_option_range_text(d, range, sizeof range);
            snprintf(want, sizeof want, "%s %s", methods[m].method, def);
            CHECK_MSG(strstr(entry, want) != NULL, "segment --help: --%s shows '%s', wants '%s'", names[o], entry, want);
        }
        CHECK_MSG(strstr(entry, range) != NULL, "segment --help: --%s lacks the range %s", names[o], range);
    }
    free(usage);
    size_t n;
    const pnpr_option_desc *t = pnpr_jseg_option_table(&n);
    check_parser("segment", pnpr_option_find(t, n, "k"));
    check_parser("segment", pnpr_option_find(t, n, "classes"));
}

static void check_cli(void)
{
    static const char *const features[] = {"k", "threshold", "confidence", "dither-scale", NULL};
    static const char *const lines[] = {"spacing", "radius", "merge-tol", "min-length", "direction-weight", NULL};
    static const char *const lines_features[] = {"k", "threshold", NULL};
    static const char *const outliers[] = {"outlier-factor", NULL};
    check_cli_options("features", pnpr_features_option_table, features);
    check_cli_options("features", pnpr_outlier_option_table, outliers);
    check_cli_options("lines", pnpr_lines_option_table, lines);
    check_cli_options("lines", pnpr_features_option_table, lines_features);
    check_cli_options("segment", pnpr_outlier_option_table, outliers);
    static const char *const split[] = {"split", "split-min", NULL};
    check_cli_options("segment", pnpr_split_option_table, split);
    static const char *const svg[] = {"stroke-width", "taper", "outline-width", "outline-jump", NULL};
    check_cli_options("lines", pnpr_svg_option_table, svg);
    static const char *const tone[] = {"tone-gamma", "tone-contrast", NULL};
    check_cli_options("render", pnpr_tone_option_table, tone);
    static const char *const preset[] = {"duration", "degrees", NULL};
    check_cli_options("animate", pnpr_camera_preset_option_table, preset);
    check_cli_options("info", pnpr_outlier_option_table, outliers);
    check_segment_usage();
    /* render and animate: the draw and upload options of the renderer's tables */
    static const char *const draw[] = {"stroke-texture", "stroke-max", "density", "point-scale", "line-width", "line-min",
                                       "dot-size", "queue-fade", "levels", "outline-scale", "outline-width",
                                       "outline-jump", "outline-hole", "faint", NULL};
    static const char *const upload[] = {"paint-bins", NULL};
    check_cli_options("render", pnpr_draw_option_table, draw);
    check_cli_options("render", pnpr_upload_option_table, upload);
    check_cli_options("animate", pnpr_draw_option_table, draw);
    check_cli_options("animate", pnpr_upload_option_table, upload);
    /* --weights G,C: both defaults of the table */
    size_t n;
    const pnpr_option_desc *t = pnpr_features_option_table(&n);
    char want[64];
    snprintf(want, sizeof want, "(default %g,%g,", pnpr_option_find(t, n, "weight-geometry")->def,
             pnpr_option_find(t, n, "weight-color")->def);
    char *usage = run_cli("features --help");
    CHECK_MSG(usage && strstr(usage, want), "features --help: --weights lacks '%s'", want);
    free(usage);
}

int main(void)
{
    pnpr_features_options f = pnpr_features_defaults();
    pnpr_lines_options l = pnpr_lines_defaults();
    pnpr_jseg_options j = pnpr_jseg_defaults();
    pnpr_rgbgrow_options r = pnpr_rgbgrow_defaults();
    pnpr_components_options c = pnpr_components_defaults();
    pnpr_hierarchy_options h = pnpr_hierarchy_defaults();
    pnpr_outlier_options o = pnpr_outlier_defaults();
    pnpr_split_options sp = pnpr_split_defaults();
    pnpr_tone_options tn = pnpr_tone_defaults();
    pnpr_draw_options dr = pnpr_draw_defaults();
    pnpr_upload_options up = pnpr_upload_defaults();
    pnpr_svg_options sv = {0};
    size_t nsv;
    const pnpr_option_desc *svt = pnpr_svg_option_table(&nsv);
    pnpr_option_set_defaults(svt, nsv, &sv);
    pnpr_camera_preset_options pr = {0, 0};
    size_t npr;
    const pnpr_option_desc *prt = pnpr_camera_preset_option_table(&npr);
    pnpr_option_set_defaults(prt, npr, &pr);
    const table_case cases[] = {
        {"features", pnpr_features_option_table, sizeof f, &f},
        {"lines", pnpr_lines_option_table, sizeof l, &l},
        {"jseg", pnpr_jseg_option_table, sizeof j, &j},
        {"rgbgrow", pnpr_rgbgrow_option_table, sizeof r, &r},
        {"components", pnpr_components_option_table, sizeof c, &c},
        {"hierarchy", pnpr_hierarchy_option_table, sizeof h, &h},
        {"outlier", pnpr_outlier_option_table, sizeof o, &o},
        {"split", pnpr_split_option_table, sizeof sp, &sp},
        {"tone", pnpr_tone_option_table, sizeof tn, &tn},
        {"draw", pnpr_draw_option_table, sizeof dr, &dr},
        {"upload", pnpr_upload_option_table, sizeof up, &up},
        {"svg", pnpr_svg_option_table, sizeof sv, &sv},
        {"camera preset", pnpr_camera_preset_option_table, sizeof pr, &pr},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        check_table(&cases[i]);
        check_refusals(&cases[i]);
    }
    renderer_defaults();
    features_and_lines_zero_equals_defaults();
    segment_zero_equals_defaults();
    check_cli();
    return pnpr_test_finish("test_options_table");
}
