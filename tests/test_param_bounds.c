/* Parameters whose cost used to grow without bound, with known answers: connected components at a
 * radius beyond the cloud's diagonal (one component, in O(n): 100k points took 58 s before), the
 * components at every radius equal to brute force, profile lines with a spacing that takes in the
 * whole cloud, the covariance split of a region that peels off a few points per level, and the
 * refused ranges (features k, lines shift_iterations) with messages
 * that name the option. The time is not asserted: CTest's timeout catches a quadratic return. */
#include "testutil.h"

#include <pointnpr/features.h>
#include <pointnpr/lines.h>
#include <pointnpr/segment.h>

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* n points on a unit sphere around c, into xyz (floats). */
static void sphere(float *xyz, size_t n, const float c[3], pnpr_test_rng *rng)
{
    for (size_t i = 0; i < n; i++) {
        double v[3], l = 0;
        for (int a = 0; a < 3; a++) { v[a] = pnpr_test_normal(rng); l += v[a] * v[a]; }
        l = sqrt(l);
        for (int a = 0; a < 3; a++) xyz[3 * i + a] = c[a] + (float)(v[a] / l);
    }
}

static uint32_t components(const float *xyz, size_t n, float distance, int threads, uint32_t *labels)
{
    pnpr_components_options o = {0};
    o.distance = distance;
    o.threads = threads;
    pnpr_segment_info info;
    CHECK_STATUS(pnpr_segment_components(xyz, n, &o, labels, &info), PNPR_OK);
    return info.segment_count;
}

/* 20 000 points in two spheres 100 apart: a radius of 1e30 (or FLT_MAX) joins them at once. */
static void test_huge_radius(void)
{
    enum { N = 20000 };
    float *xyz = malloc(3 * N * sizeof *xyz);
    uint32_t *labels = malloc(N * sizeof *labels);
    pnpr_test_rng rng = {11};
    const float c0[3] = {0, 0, 0}, c1[3] = {100, 0, 0};
    sphere(xyz, N / 2, c0, &rng);
    sphere(xyz + 3 * (N / 2), N / 2, c1, &rng);
    CHECK(components(xyz, N, 1e30f, 0, labels) == 1);
    CHECK(components(xyz, N, 3.4e38f, 0, labels) == 1);
    CHECK(components(xyz, N, 50, 0, labels) == 2 && labels[0] == 0 && labels[N - 1] == 1);
    CHECK(components(xyz, N, 150, INT_MAX, labels) == 1); /* threads beyond PNPR_THREADS_MAX: clamped */
    for (size_t i = 0; i < N; i++) CHECK(labels[i] == 0);
    free(xyz);
    free(labels);
}

static uint32_t root(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

/* The same partition as brute force (all pairs, the kd-tree's float distance test) at every
 * radius, on clusters with NaN points among them. */
static void test_against_brute_force(void)
{
    enum { N = 1500 };
    float *xyz = malloc(3 * N * sizeof *xyz);
    uint32_t *labels = malloc(N * sizeof *labels), *truth = malloc(N * sizeof *truth);
    pnpr_test_rng rng = {5};
    for (size_t i = 0; i < N; i++) {
        int cl = (int)(pnpr_test_uniform(&rng) * 6);
        for (int a = 0; a < 3; a++) xyz[3 * i + a] = (float)(cl * (a == 0 ? 0.7 : 0.0) + 0.15 * pnpr_test_uniform(&rng));
    }
    xyz[3 * 7] = NAN;
    xyz[3 * 700 + 2] = INFINITY;
    const float radii[6] = {1e-6f, 0.004f, 0.01f, 0.05f, 0.6f, 1e30f};
    for (int r = 0; r < 6; r++) {
        uint32_t s = components(xyz, N, radii[r], 0, labels);
        for (size_t i = 0; i < N; i++) truth[i] = (uint32_t)i;
        const float r2 = radii[r] * radii[r];
        for (size_t i = 0; i < N; i++)
            for (size_t j = i + 1; j < N; j++) {
                const float *p = xyz + 3 * i, *q = xyz + 3 * j;
                float dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
                if (!(dx * dx + dy * dy + dz * dz <= r2)) continue;
                uint32_t a = root(truth, (uint32_t)i), b = root(truth, (uint32_t)j);
                truth[a > b ? a : b] = a < b ? a : b;
            }
        for (size_t i = 0; i < N; i++) truth[i] = root(truth, (uint32_t)i);
        pnpr_segment_info info;
        CHECK_STATUS(pnpr_segment_finish(xyz, N, truth, &info), PNPR_OK);
        printf("components at %g: %u segments (brute force %u)\n", radii[r], s, info.segment_count);
        CHECK_MSG(s == info.segment_count && memcmp(labels, truth, N * sizeof *labels) == 0,
                  "radius %g: %u segments, brute force %u", radii[r], s, info.segment_count);
    }
    free(xyz);
    free(labels);
    free(truth);
}

static void test_features_k(void)
{
    pnpr_features_options o = {0};
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_features_check_options(NULL, &err), PNPR_OK);
    CHECK_STATUS(pnpr_features_check_options(&o, &err), PNPR_OK);
    o.k = PNPR_FEATURES_K_MAX;
    CHECK_STATUS(pnpr_features_check_options(&o, &err), PNPR_OK);
    o.k = PNPR_FEATURES_K_MAX + 1;
    CHECK_STATUS(pnpr_features_check_options(&o, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "features: k 1025") != NULL, "message: %s", err.message);
    pnpr_cloud c = {0};
    const double off[3] = {0, 0, 0};
    CHECK_STATUS(pnpr_test_sphere(&c, 100, 1, off, 3), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&c, &o, NULL), PNPR_ERR_INVALID_ARGUMENT);
    o.k = 0;
    o.direction_confidence = 2;
    CHECK_STATUS(pnpr_features_check_options(&o, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "direction_confidence") != NULL, "message: %s", err.message);
    pnpr_cloud_free(&c);
}

/* m directional points along 40 parallel lines, direction +x. */
static void line_points(float *xyz, float *dir, size_t m, pnpr_test_rng *rng)
{
    for (size_t i = 0; i < m; i++) {
        xyz[3 * i] = (float)(10 * pnpr_test_uniform(rng));
        xyz[3 * i + 1] = (float)(i % 40) * 0.5f;
        xyz[3 * i + 2] = 0;
        dir[3 * i] = 1;
        dir[3 * i + 1] = dir[3 * i + 2] = 0;
    }
}

static void test_lines(void)
{
    enum { M = 20000 };
    float *xyz = malloc(3 * M * sizeof *xyz), *dir = malloc(3 * M * sizeof *dir);
    pnpr_test_rng rng = {9};
    line_points(xyz, dir, M, &rng);
    const double origin[3] = {0, 0, 0};
    pnpr_lines_options o = {0};
    pnpr_polylines lines = {0};
    pnpr_lines_stats st;
    pnpr_error err = {0};
    /* a spacing (and so shift and merge radii) that takes in the whole cloud: at most
     * PNPR_LINES_NEIGHBOURS_MAX neighbours per query */
    o.spacing = 1e30f;
    CHECK_STATUS(pnpr_profile_lines_points(xyz, dir, M, origin, &o, &lines, &st), PNPR_OK);
    printf("lines with spacing 1e30: %zu points, %zu nodes, %zu chains\n", st.directional_points, st.merged_nodes,
           st.chains);
    CHECK(st.directional_points == M && st.merged_nodes >= M / (PNPR_LINES_NEIGHBOURS_MAX + 1) && st.merged_nodes < M);
    pnpr_lines_free(&lines);
    o.spacing = 0;
    o.merge_tol = 1e30f;
    o.shift_iterations = PNPR_LINES_SHIFT_MAX;
    CHECK_STATUS(pnpr_profile_lines_points(xyz, dir, M, origin, &o, &lines, &st), PNPR_OK);
    CHECK(st.merged_nodes >= M / (PNPR_LINES_NEIGHBOURS_MAX + 1) && st.merged_nodes < M);
    pnpr_lines_free(&lines);
    o.shift_iterations = PNPR_LINES_SHIFT_MAX + 1;
    CHECK_STATUS(pnpr_lines_check_options(&o, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "shift_iterations 65") != NULL, "message: %s", err.message);
    CHECK_STATUS(pnpr_profile_lines_points(xyz, dir, M, origin, &o, &lines, &st), PNPR_ERR_INVALID_ARGUMENT);
    o.shift_iterations = 0;
    o.sample_tol = -1;
    CHECK_STATUS(pnpr_lines_check_options(&o, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "sample_tol") != NULL, "message: %s", err.message);
    free(xyz);
    free(dir);
}

/* A region that centroid splits peel a few points at a time (coordinates growing 2x a point, in
 * three dimensions), split down to single points (min_size 1): it completes with 57 sub-regions
 * (measured; the same without the depth bound: float coordinates cannot make a chain of
 * PNPR_SPLIT_DEPTH_MAX centroid splits, the bound only guarantees the cost). */
static void test_split_depth(void)
{
    enum { N = 100 };
    float xyz[3 * N];
    uint32_t labels[N], out[N], s = 0;
    for (int i = 0; i < N; i++) {
        float v = ldexpf(1.0f, i);
        xyz[3 * i] = v;
        xyz[3 * i + 1] = (i % 2 ? 0.5f : -0.5f) * v;
        xyz[3 * i + 2] = (i % 3 ? 0.3f : -0.3f) * v;
        labels[i] = 0;
    }
    CHECK_STATUS(pnpr_segment_covariance_split(xyz, N, labels, 1, 1e-6f, 1, out, &s), PNPR_OK);
    printf("covariance split of a peeling region: %u segments\n", s);
    CHECK_MSG(s == 57, "%u segments", s);
}

int main(void)
{
    test_huge_radius();
    test_against_brute_force();
    test_features_k();
    test_lines();
    test_split_depth();
    return pnpr_test_finish("test_param_bounds");
}
