/* Numerical stability: the feature pipeline on stiff and extreme inputs gives defined results, and
 * the same results wherever the cloud sits and whatever its scale (docs/stability.md).
 * Each case prints one row of the table in docs/stability.md. */
#include "testutil.h"
#include <pointnpr/features.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEG(x) ((x) * 57.29577951308232)

static double angle_deg(const float *a, const float *b)
{
    double c[3] = {(double)a[1] * b[2] - (double)a[2] * b[1], (double)a[2] * b[0] - (double)a[0] * b[2],
                   (double)a[0] * b[1] - (double)a[1] * b[0]};
    return DEG(atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2]));
}

static const float *prop(pnpr_cloud *c, const char *name)
{
    pnpr_property *p = pnpr_cloud_find_property(c, name);
    return p ? p->data : NULL;
}

/* All outputs finite and in range, normals unit or zero. Returns the number of bad values. */
static size_t bad_values(pnpr_cloud *c)
{
    const float *deg = prop(c, "feature_degree"), *conf = prop(c, "feature_confidence");
    const uint8_t *cls = (const uint8_t *)prop(c, "feature_class");
    size_t bad = 0;
    for (size_t i = 0; i < c->count; i++) {
        const float *n = c->normal + 3 * i;
        double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        bad += !(l == 0 || fabs(l - 1) < 1e-5);
        bad += !(deg[i] >= 0 && deg[i] <= 1) + !(conf[i] >= 0 && conf[i] <= 1) + (cls[i] > 3);
    }
    return bad;
}

/* Sphere on a 2^-20 grid, moved by `offset` and scaled by `scale` (both exact in double). */
static void make_sphere(pnpr_cloud *c, double offset, double scale)
{
    CHECK_STATUS(pnpr_test_sphere(c, 20000, 1.0, NULL, 5), PNPR_OK);
    for (size_t i = 0; i < 3 * c->count; i++)
        c->src_xyz[i] = offset + scale * (floor(c->src_xyz[i] * 1048576.0 + 0.5) / 1048576.0);
    CHECK_STATUS(pnpr_cloud_set_world(c, c->src_xyz), PNPR_OK);
}

/* Offsets 1e3 .. 1e8 and scales 1e-6 .. 1e6: normals within 0.01 degree, feature degrees within
 * 1e-4 and classes identical to the reference (offset 0, scale 1). */
static void test_offsets_and_scales(void)
{
    pnpr_cloud ref = {0};
    make_sphere(&ref, 0, 1);
    CHECK_STATUS(pnpr_compute_features(&ref, NULL, NULL), PNPR_OK);
    const double offsets[] = {1e3, 1e4, 1e5, 1e6, 5e6, 1e7, 1e8};
    const double scales[] = {1e-6, 1e-3, 1e3, 1e6};
    for (int pass = 0; pass < 2; pass++) {
        int n = pass ? 4 : 7;
        for (int t = 0; t < n; t++) {
            pnpr_cloud c = {0};
            double off = pass ? 0 : offsets[t], sc = pass ? scales[t] : 1;
            make_sphere(&c, off, sc);
            CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
            double worst = 0, dworst = 0;
            size_t cdiff = 0;
            const float *d0 = prop(&ref, "feature_degree"), *d1 = prop(&c, "feature_degree");
            const uint8_t *c0 = (const uint8_t *)prop(&ref, "feature_class"), *c1 = (const uint8_t *)prop(&c, "feature_class");
            for (size_t i = 0; i < c.count; i++) {
                double a = angle_deg(ref.normal + 3 * i, c.normal + 3 * i);
                if (a > worst) worst = a;
                if (fabs((double)d0[i] - d1[i]) > dworst) dworst = fabs((double)d0[i] - d1[i]);
                cdiff += c0[i] != c1[i];
            }
            fprintf(stderr, "| sphere 20k, %s %g | normals: largest difference %.2e deg | degree: %.2e | classes differing: %zu | bad values: %zu |\n",
                    pass ? "scale" : "offset", pass ? sc : off, worst, dworst, cdiff, bad_values(&c));
            CHECK(worst < 0.01);
            CHECK(dworst < 1e-4);
            CHECK(cdiff == 0);
            CHECK(bad_values(&c) == 0);
            pnpr_cloud_free(&c);
        }
    }
    pnpr_cloud_free(&ref);
}

/* Largest angle between a normal and the z axis (either sign). */
static double worst_from_z(const pnpr_cloud *c)
{
    const float z[3] = {0, 0, 1}, mz[3] = {0, 0, -1};
    double worst = 0;
    for (size_t i = 0; i < c->count; i++) {
        double a = fmin(angle_deg(c->normal + 3 * i, z), angle_deg(c->normal + 3 * i, mz));
        if (a > worst) worst = a;
    }
    return worst;
}

/* A plane 1 x 1 whose points are jittered by 1e-7 of its extent: normals within 0.01 degree of z,
 * no features. And a box 1 x 1 x 1e-7 (two faces 1e-7 apart): normals along z, defined. */
static void test_thin(void)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_plane(&c, 100, 100, 0.01, NULL), PNPR_OK);
    pnpr_test_rng rng = {3};
    for (size_t i = 0; i < c.count; i++) c.src_xyz[3 * i + 2] = 1e-7 * (pnpr_test_uniform(&rng) - 0.5);
    CHECK_STATUS(pnpr_cloud_set_world(&c, c.src_xyz), PNPR_OK);
    pnpr_features_stats s;
    CHECK_STATUS(pnpr_compute_features(&c, NULL, &s), PNPR_OK);
    double worst = worst_from_z(&c);
    fprintf(stderr, "| plane with 1e-7 jitter | normals: worst %.2e deg from z | feature points %zu | bad values %zu |\n", worst,
            s.feature_points, bad_values(&c));
    CHECK(worst < 0.01);
    CHECK(s.feature_points == 0);
    CHECK(bad_values(&c) == 0);
    pnpr_cloud_free(&c);
    /* two sheets 1e-7 apart: each point's neighbourhood mixes both sheets; normals stay along z */
    CHECK_STATUS(pnpr_test_plane(&c, 60, 60, 0.01, NULL), PNPR_OK);
    pnpr_cloud top = {0};
    const double up[3] = {0, 0, 1e-7};
    CHECK_STATUS(pnpr_test_plane(&top, 60, 60, 0.01, up), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_append(&c, &top), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, &s), PNPR_OK);
    worst = worst_from_z(&c);
    fprintf(stderr, "| two sheets 1e-7 apart | normals: worst %.2e deg from z | feature points %zu | bad values %zu |\n", worst,
            s.feature_points, bad_values(&c));
    CHECK(worst < 0.01);
    CHECK(bad_values(&c) == 0);
    pnpr_cloud_free(&c);
    pnpr_cloud_free(&top);
}

/* Nearly collinear (1e-9 jitter across a line) and clusters of exact duplicates (each point 20
 * times, more than k): defined, finite results. */
static void test_collinear_and_duplicates(void)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&c, 2000), PNPR_OK);
    pnpr_test_rng rng = {9};
    for (size_t i = 0; i < c.count; i++) {
        c.xyz[3 * i] = 0.001f * (float)i;
        c.xyz[3 * i + 1] = (float)(1e-9 * (pnpr_test_uniform(&rng) - 0.5));
        c.xyz[3 * i + 2] = (float)(1e-9 * (pnpr_test_uniform(&rng) - 0.5));
    }
    pnpr_features_stats s;
    CHECK_STATUS(pnpr_compute_features(&c, NULL, &s), PNPR_OK);
    size_t along = 0;
    for (size_t i = 0; i < c.count; i++) along += fabsf(c.normal[3 * i]) > 1e-3f;
    fprintf(stderr, "| nearly collinear (1e-9 jitter) | normals along the line: %zu | bad values %zu |\n", along, bad_values(&c));
    CHECK(along == 0);
    CHECK(bad_values(&c) == 0);
    pnpr_cloud_free(&c);

    pnpr_cloud plane = {0}, dup = {0};
    CHECK_STATUS(pnpr_test_plane(&plane, 20, 20, 0.05, NULL), PNPR_OK);
    for (int r = 0; r < 20; r++) CHECK_STATUS(pnpr_cloud_append(&dup, &plane), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&dup, NULL, &s), PNPR_OK);
    size_t zero = 0;
    for (size_t i = 0; i < dup.count; i++) zero += dup.normal[3 * i] == 0 && dup.normal[3 * i + 1] == 0 && dup.normal[3 * i + 2] == 0;
    fprintf(stderr, "| 400 points x 20 exact duplicates, k=16 | zero normals (no plane in a neighbourhood): %zu of %zu | feature points %zu | bad values %zu |\n",
            zero, dup.count, s.feature_points, bad_values(&dup));
    CHECK(zero == dup.count); /* every neighbourhood is 16 copies of one point: no plane */
    CHECK(s.feature_points == 0);
    CHECK(bad_values(&dup) == 0);
    /* with k larger than a cluster and its four nearest clusters, the plane is found again */
    pnpr_features_options o = {0};
    o.k = 128;
    CHECK_STATUS(pnpr_compute_features(&dup, &o, &s), PNPR_OK);
    size_t up = 0;
    for (size_t i = 0; i < dup.count; i++) up += fabsf(dup.normal[3 * i + 2]) > 0.999f;
    fprintf(stderr, "| same, k=128 | normals along z: %zu of %zu |\n", up, dup.count);
    CHECK(up == dup.count);
    pnpr_cloud_free(&plane);
    pnpr_cloud_free(&dup);
}

/* Huge k: 1024 works (and is clamped to the point count), 1025 is refused; a single colour gives no
 * colour features; 8-bit colours from 16-bit input are covered by test_ply/test_las. */
static void test_k_and_colours(void)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_sphere(&c, 3000, 1, NULL, 2), PNPR_OK);
    pnpr_features_options o = {0};
    pnpr_features_stats s;
    o.k = 1024;
    CHECK_STATUS(pnpr_compute_features(&c, &o, &s), PNPR_OK);
    CHECK(s.k_used == 1024 && bad_values(&c) == 0);
    o.k = 1025;
    CHECK_STATUS(pnpr_compute_features(&c, &o, &s), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    memset(c.rgb, 77, 3 * c.count);
    o.k = 0;
    o.weight_geometry = 0; o.weight_color = 1; /* colour term only */
    CHECK_STATUS(pnpr_compute_features(&c, &o, &s), PNPR_OK);
    const float *deg = prop(&c, "feature_degree");
    float mx = 0;
    for (size_t i = 0; i < c.count; i++) if (deg[i] > mx) mx = deg[i];
    fprintf(stderr, "| single colour, colour term only | largest degree %.3g | feature points %zu |\n", mx, s.feature_points);
    CHECK(mx == 0);
    CHECK(s.feature_points == 0);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_offsets_and_scales();
    test_thin();
    test_collinear_and_duplicates();
    test_k_and_colours();
    return pnpr_test_finish("test_stability");
}
