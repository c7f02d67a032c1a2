/* Far outliers (outliers.h) with known answers: a 7 x 7 x 7 grid of the unit cube plus one point
 * at 1e9 or 1e308. The robust centre is the grid's centre, the robust extent the 309th smallest of
 * the 344 distances (sqrt(19)/6), the far point the only far outlier; the readers' origin
 * (pnpr_cloud_set_world) stays the grid's centre, so the grid's float offsets and its feature
 * analysis are exactly those without the far point (before the fix: 0 feature points, and with
 * 1e308 no valid point at all). Dropping keeps every array and the faces consistent. */
#include "testutil.h"

#include <pointnpr/features.h>
#include <pointnpr/outliers.h>
#include <pointnpr/props.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { G = 7, NG = G * G * G };

/* The grid (i/6, j/6, k/6), plus one point at (far, 0, 0) when far != 0: 3 * (NG + 1) doubles. */
static double *grid_world(double far, size_t *r_n)
{
    double *w = malloc(3 * (NG + 1) * sizeof *w);
    size_t n = 0;
    for (int i = 0; i < G; i++)
        for (int j = 0; j < G; j++)
            for (int k = 0; k < G; k++, n++) {
                w[3 * n] = i / 6.0;
                w[3 * n + 1] = j / 6.0;
                w[3 * n + 2] = k / 6.0;
            }
    if (far != 0) {
        w[3 * n] = far;
        w[3 * n + 1] = w[3 * n + 2] = 0;
        n++;
    }
    *r_n = n;
    return w;
}

/* A cloud as a reader builds it from double coordinates: set_world, exact src_xyz. */
static void grid_cloud(pnpr_cloud *c, double far)
{
    size_t n;
    double *w = grid_world(far, &n);
    CHECK_STATUS(pnpr_cloud_alloc(c, n), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_set_world(c, w), PNPR_OK);
    c->src_xyz = w;
    c->src_coord_type = PNPR_TYPE_FLOAT64;
}

static void test_robust_frame(void)
{
    size_t n;
    double *w = grid_world(1e9, &n);
    uint8_t far[NG + 1];
    pnpr_outlier_info oi;
    CHECK_STATUS(pnpr_world_outliers(w, n, NULL, far, &oi), PNPR_OK);
    const double extent = sqrt(19.0) / 6; /* the 309th of the sorted distances a^2+b^2+c^2 <= 19 */
    printf("grid + 1e9: centre %g %g %g, extent %.12g, limit %.12g, far %zu\n", oi.centre[0], oi.centre[1],
           oi.centre[2], oi.extent, oi.limit, oi.far);
    for (int a = 0; a < 3; a++) CHECK(oi.centre[a] == 0.5);
    CHECK_NEAR(oi.extent, extent, 1e-12);
    CHECK_NEAR(oi.limit, PNPR_OUTLIER_FACTOR * extent, 1e-11);
    CHECK(oi.finite == NG + 1 && oi.far == 1 && oi.beyond_float == 0);
    size_t flagged = 0;
    for (size_t i = 0; i < n; i++) flagged += far[i];
    CHECK(flagged == 1 && far[NG] == 1);
    /* factor 1: the grid points beyond one robust extent are far too (a^2+b^2+c^2 > 19) */
    size_t beyond = 0;
    for (int a = -3; a <= 3; a++)
        for (int b = -3; b <= 3; b++)
            for (int c = -3; c <= 3; c++) beyond += a * a + b * b + c * c > 19;
    pnpr_outlier_options one = {1.0};
    CHECK_STATUS(pnpr_world_outliers(w, n, &one, NULL, &oi), PNPR_OK);
    CHECK_MSG(oi.far == beyond + 1, "factor 1: %zu far, expected %zu", oi.far, beyond + 1);
    /* the factor's range */
    pnpr_outlier_options bad[3] = {{0.5}, {NAN}, {2 * PNPR_OUTLIER_FACTOR_MAX}};
    for (int b = 0; b < 3; b++) CHECK_STATUS(pnpr_world_outliers(w, n, &bad[b], NULL, &oi), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_world_outliers(NULL, 3, NULL, NULL, &oi), PNPR_ERR_INVALID_ARGUMENT);
    free(w);
}

/* No scale, no far outliers: most points coincide (extent 0); NaN points are not finite. */
static void test_degenerate(void)
{
    double w[3 * 12];
    for (int i = 0; i < 12; i++) w[3 * i] = w[3 * i + 1] = w[3 * i + 2] = 5;
    w[3 * 10] = 1e9;
    w[3 * 11] = NAN;
    pnpr_outlier_info oi;
    CHECK_STATUS(pnpr_world_outliers(w, 12, NULL, NULL, &oi), PNPR_OK);
    CHECK(oi.extent == 0 && isinf(oi.limit) && oi.far == 0 && oi.finite == 11);
    CHECK_STATUS(pnpr_world_outliers(NULL, 0, NULL, NULL, &oi), PNPR_OK);
    CHECK(oi.finite == 0 && oi.far == 0);
}

/* The origin is the grid's centre with or without the far point; the grid's offsets are
 * identical; a 1e308 offset overflows and is counted as beyond float range. */
static void test_origin(void)
{
    pnpr_cloud clean = {0}, c = {0};
    grid_cloud(&clean, 0);
    for (int a = 0; a < 3; a++) CHECK(clean.origin[a] == 0.5);
    const double fars[2] = {1e9, 1e308};
    for (int f = 0; f < 2; f++) {
        grid_cloud(&c, fars[f]);
        for (int a = 0; a < 3; a++) CHECK_MSG(c.origin[a] == 0.5, "far %g: origin %g", fars[f], c.origin[a]);
        CHECK(memcmp(c.xyz, clean.xyz, 3 * NG * sizeof(float)) == 0);
        pnpr_outlier_info oi;
        CHECK_STATUS(pnpr_cloud_outliers(&c, NULL, NULL, &oi), PNPR_OK);
        CHECK(oi.finite == NG + 1 && oi.far == 1 && oi.beyond_float == (size_t)f);
        CHECK(isfinite(c.xyz[3 * NG]) == (f == 0));
        pnpr_cloud_free(&c);
    }
    pnpr_cloud_free(&clean);
}

/* A cloud as a reader builds it: `base` (n world points) plus (far, y0, z0) when far != 0. */
static void cloud_plus(pnpr_cloud *c, const double *base, size_t n, double far)
{
    size_t m = n + (far != 0);
    double *w = malloc(3 * m * sizeof *w);
    memcpy(w, base, 3 * n * sizeof *w);
    if (far != 0) {
        w[3 * n] = far;
        w[3 * n + 1] = base[1];
        w[3 * n + 2] = base[2];
    }
    CHECK_STATUS(pnpr_cloud_alloc(c, m), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_set_world(c, w), PNPR_OK);
    c->src_xyz = w;
    c->src_coord_type = PNPR_TYPE_FLOAT64;
}

static pnpr_features_stats features_of(const double *base, size_t n, double far, int drop)
{
    pnpr_cloud c = {0};
    pnpr_features_stats s;
    memset(&s, 0, sizeof s);
    cloud_plus(&c, base, n, far);
    if (drop) CHECK_STATUS(pnpr_cloud_drop_outliers(&c, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, &s), PNPR_OK);
    /* the shape's own feature points: the far point's class says nothing (its k nearest are all
     * about as far; ties by input index) */
    const pnpr_property *cls = pnpr_cloud_find_property(&c, PNPR_PROP_FEATURE_CLASS);
    s.feature_points = s.directional_points = 0;
    for (size_t i = 0; cls && i < n; i++) {
        uint8_t v = ((const uint8_t *)cls->data)[i];
        s.feature_points += v == PNPR_CLASS_NONDIRECTIONAL || v == PNPR_CLASS_DIRECTIONAL;
        s.directional_points += v == PNPR_CLASS_DIRECTIONAL;
    }
    pnpr_cloud_free(&c);
    return s;
}

/* One shape with and without a far point (1e9: kept or dropped; 1e308: beyond float range): the
 * shape's results are those without it in every case. On an exact lattice this holds because the
 * kNN orders ties by input index: when it cut them by kd-tree position, a far point in the tree
 * moved its median splits and the grid kept 69 of its 79 feature points. */
static void features_with_far(const char *name, const double *base, size_t n)
{
    pnpr_features_stats clean = features_of(base, n, 0, 0);
    printf("%s: %zu feature points of %zu\n", name, clean.feature_points, clean.valid_points);
    CHECK(clean.valid_points == n && clean.feature_points > 0);
    const double fars[2] = {1e9, 1e308};
    for (int f = 0; f < 2; f++)
        for (int drop = 0; drop < 2; drop++) {
            pnpr_features_stats s = features_of(base, n, fars[f], drop);
            printf("%s + %g%s: %zu feature points, valid %zu, beyond float %zu\n", name, fars[f],
                   drop ? " (dropped)" : "", s.feature_points, s.valid_points, s.beyond_float);
            CHECK_MSG(s.feature_points == clean.feature_points && s.directional_points == clean.directional_points,
                      "%s + %g, drop %d: %zu feature points, expected %zu", name, fars[f], drop, s.feature_points,
                      clean.feature_points);
            CHECK(s.valid_points == (drop || f == 1 ? n : n + 1));
            CHECK(s.beyond_float == (size_t)(f == 1 && !drop));
        }
}

/* The user report: one far point emptied the analysis. */
static void test_features(void)
{
    size_t n;
    double *w = grid_world(0, &n);
    features_with_far("7x7x7 grid", w, n);
    free(w);
    /* the sampled cube of the other tests, georeferenced, with noise: no ties */
    pnpr_cloud cube = {0};
    const double off[3] = {5123456.789, 4012345.678, 250.125};
    CHECK_STATUS(pnpr_test_cube(&cube, 1.0, 0.05, 0.002, off, 7), PNPR_OK);
    w = malloc(3 * cube.count * sizeof *w);
    for (size_t i = 0; i < cube.count; i++) pnpr_cloud_world(&cube, i, w + 3 * i);
    features_with_far("noisy cube", w, cube.count);
    free(w);
    pnpr_cloud_free(&cube);
    /* too few usable points: the count says why */
    double t[9] = {0, 0, 0, 1, 0, 0, 1e308, 0, 0};
    pnpr_cloud c = {0};
    cloud_plus(&c, t, 3, 0);
    pnpr_features_stats s;
    CHECK_STATUS(pnpr_compute_features(&c, NULL, &s), PNPR_OK);
    CHECK(s.valid_points == 2 && s.beyond_float == 1 && s.feature_points == 0);
    pnpr_cloud_free(&c);
}

/* Dropping: order, every array, the extra properties and the faces follow; NaN points stay. */
static void test_drop(void)
{
    double w[3 * 6] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1e9, 1e9, 0, 1, 1, 0, NAN, 0, 0};
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&c, 6), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_set_world(&c, w), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_src_xyz(&c), PNPR_OK);
    memcpy(c.src_xyz, w, sizeof w);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_labels(&c), PNPR_OK);
    pnpr_property *p = NULL;
    CHECK_STATUS(pnpr_cloud_add_property(&c, "tag", PNPR_TYPE_INT16, &p), PNPR_OK);
    for (size_t i = 0; i < 6; i++) {
        c.rgb[3 * i] = (uint8_t)(10 * i);
        c.label[i] = (uint32_t)(100 + i);
        ((int16_t *)p->data)[i] = (int16_t)(-(int)i);
    }
    /* faces: (0 1 2) and (1 3 4): the second touches the far point 3 */
    c.faces.count = 2;
    c.faces.offset = malloc(3 * sizeof(uint32_t));
    c.faces.index = malloc(6 * sizeof(uint32_t));
    const uint32_t off[3] = {0, 3, 6}, idx[6] = {0, 1, 2, 1, 3, 4};
    memcpy(c.faces.offset, off, sizeof off);
    memcpy(c.faces.index, idx, sizeof idx);
    pnpr_outlier_info oi;
    CHECK_STATUS(pnpr_cloud_drop_outliers(&c, NULL, &oi), PNPR_OK);
    CHECK(oi.far == 1 && oi.finite == 5);
    CHECK(c.count == 5);
    const size_t kept[5] = {0, 1, 2, 4, 5};
    for (size_t i = 0; i < 5; i++) {
        CHECK(c.rgb[3 * i] == 10 * kept[i]);
        CHECK(c.label[i] == 100 + kept[i]);
        CHECK(((int16_t *)pnpr_cloud_find_property(&c, "tag")->data)[i] == -(int)kept[i]);
        CHECK(c.src_xyz[3 * i + 1] == w[3 * kept[i] + 1] || (isnan(w[3 * kept[i]]) && isnan(c.src_xyz[3 * i])));
    }
    CHECK(c.faces.count == 1 && c.faces.offset[1] == 3 && c.faces.index[0] == 0 && c.faces.index[2] == 2);
    CHECK_STATUS(pnpr_cloud_keep(NULL, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_robust_frame();
    test_degenerate();
    test_origin();
    test_features();
    test_drop();
    return pnpr_test_finish("test_outliers");
}
