/* kd-tree: kNN and radius queries against brute force; degenerate inputs. */
#include "testutil.h"
#include <pointnpr/knn.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "../core/internal.h" /* pnpr_cmp_float */

static float d2(const float *a, const float *b)
{
    float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return dx * dx + dy * dy + dz * dz;
}

/* kNN distances equal the brute-force k smallest distances (indices may differ on ties). */
static void test_against_brute_force(void)
{
    enum { N = 3000, K = 10 };
    pnpr_test_rng rng = {7};
    float *p = malloc(N * 3 * sizeof(float));
    for (int i = 0; i < N * 3; i++) p[i] = (float)pnpr_test_uniform(&rng);
    for (int i = 0; i < 100; i++) { /* some exact duplicates */
        int a = (int)(pnpr_test_uniform(&rng) * N), b = (int)(pnpr_test_uniform(&rng) * N);
        p[3 * a] = p[3 * b]; p[3 * a + 1] = p[3 * b + 1]; p[3 * a + 2] = p[3 * b + 2];
    }
    pnpr_kdtree *t = NULL;
    CHECK_STATUS(pnpr_kdtree_build(p, N, 0, &t), PNPR_OK);
    CHECK(pnpr_kdtree_size(t) == N);
    uint32_t *idx = malloc(N * K * sizeof(uint32_t));
    float *dd = malloc(N * K * sizeof(float));
    pnpr_knn_options o = {0};
    CHECK_STATUS(pnpr_knn_all(t, p, N, 0, K, &o, idx, dd), PNPR_OK);
    int bad = 0;
    float *all = malloc(N * sizeof(float));
    for (int q = 0; q < N; q += 7) {
        for (int i = 0; i < N; i++) all[i] = d2(p + 3 * q, p + 3 * i);
        /* k smallest by partial selection sort */
        for (int j = 0; j < K; j++) {
            int m = j;
            for (int i = j + 1; i < N; i++) if (all[i] < all[m]) m = i;
            float tmp = all[j]; all[j] = all[m]; all[m] = tmp;
            if (dd[q * K + j] != all[j]) bad++;
            if (idx[q * K + j] >= N || d2(p + 3 * q, p + 3 * idx[q * K + j]) != dd[q * K + j]) bad++;
        }
    }
    CHECK_MSG(bad == 0, "%d mismatches", bad);
    /* radius query count equals brute force */
    float q[3] = {0.5f, 0.5f, 0.5f};
    size_t want = 0;
    for (int i = 0; i < N; i++) want += d2(q, p + 3 * i) <= 0.2f * 0.2f;
    uint32_t buf[4];
    CHECK(pnpr_kdtree_radius(t, q, 0.2f, buf, 4) == want);
    CHECK(want > 4);
    free(all); free(idx); free(dd); free(p);
    pnpr_kdtree_free(t);
}

/* pnpr_knn_self on both sides of the kd-tree's switch from a sorted list to a heap (k of 256):
 * each row's distances are the brute-force k smallest, nearest first, each point its own first
 * neighbour, and 1 and 2 threads give byte-identical rows. */
static void test_self(size_t k)
{
    enum { N = 2000 };
    pnpr_test_rng rng = {11};
    float *p = malloc(N * 3 * sizeof(float)), *all = malloc(N * sizeof(float));
    for (int i = 0; i < N * 3; i++) p[i] = (float)pnpr_test_uniform(&rng);
    for (int i = 0; i < 50; i++) memcpy(p + 3 * (2 * i + 1), p + 3 * (2 * i), 3 * sizeof(float)); /* duplicates */
    pnpr_kdtree *t = NULL;
    CHECK_STATUS(pnpr_kdtree_build(p, N, 0, &t), PNPR_OK);
    uint32_t *idx[2] = {malloc(N * k * sizeof(uint32_t)), malloc(N * k * sizeof(uint32_t))};
    float *dd[2] = {malloc(N * k * sizeof(float)), malloc(N * k * sizeof(float))};
    for (int th = 0; th < 2; th++) {
        pnpr_knn_options o = {th + 1, {0}, 0};
        CHECK_STATUS(pnpr_knn_self(t, N, k, &o, idx[th], dd[th]), PNPR_OK);
    }
    CHECK_MSG(!memcmp(idx[0], idx[1], N * k * sizeof(uint32_t)) && !memcmp(dd[0], dd[1], N * k * sizeof(float)),
              "k %zu: rows differ between 1 and 2 threads", k);
    int bad = 0;
    for (int q = 0; q < N; q += 37) {
        for (int i = 0; i < N; i++) all[i] = d2(p + 3 * q, p + 3 * i);
        qsort(all, N, sizeof(float), pnpr_cmp_float);
        bad += dd[0][q * k] != 0;
        for (size_t j = 0; j < k; j++)
            bad += dd[0][q * k + j] != all[j] || d2(p + 3 * q, p + 3 * idx[0][q * k + j]) != all[j];
    }
    CHECK_MSG(bad == 0, "k %zu: %d mismatches against brute force", k, bad);
    for (int th = 0; th < 2; th++) { free(idx[th]); free(dd[th]); }
    free(all); free(p);
    pnpr_kdtree_free(t);
}

static void test_degenerate(void)
{
    pnpr_kdtree *t = NULL;
    uint32_t idx[5];
    float dd[5];
    /* empty */
    CHECK_STATUS(pnpr_kdtree_build(NULL, 0, 0, &t), PNPR_OK);
    float q[3] = {0, 0, 0};
    CHECK(pnpr_kdtree_knn(t, q, 5, idx, dd) == 0);
    CHECK(idx[0] == PNPR_INDEX_NONE && isinf(dd[0]));
    pnpr_kdtree_free(t);
    /* fewer points than k, NaN points skipped */
    float p[4 * 3] = {0, 0, 0, 1, 0, 0, NAN, 0, 0, 0, INFINITY, 0};
    CHECK_STATUS(pnpr_kdtree_build(p, 4, 0, &t), PNPR_OK);
    CHECK(pnpr_kdtree_size(t) == 2);
    CHECK(pnpr_kdtree_knn(t, q, 5, idx, dd) == 2);
    CHECK(idx[0] == 0 && idx[1] == 1 && idx[2] == PNPR_INDEX_NONE);
    float qn[3] = {NAN, 0, 0};
    CHECK(pnpr_kdtree_knn(t, qn, 5, idx, NULL) == 0);
    pnpr_kdtree_free(t);
    /* 200k identical points: must not degrade to a full scan per query (finishes quickly) */
    size_t n = 200000;
    float *same = calloc(n * 3, sizeof(float));
    CHECK_STATUS(pnpr_kdtree_build(same, n, 0, &t), PNPR_OK);
    uint32_t *rows = malloc(n * 8 * sizeof(uint32_t));
    CHECK_STATUS(pnpr_knn_all(t, same, n, 0, 8, NULL, rows, NULL), PNPR_OK);
    int ok = 1;
    for (size_t i = 0; i < n * 8; i++) ok &= rows[i] < n;
    CHECK(ok);
    free(rows); free(same);
    pnpr_kdtree_free(t);
    /* invalid arguments */
    CHECK_STATUS(pnpr_kdtree_build(p, 4, 0, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_kdtree_build(NULL, 4, 0, &t), PNPR_ERR_INVALID_ARGUMENT);
}

/* Stride: points embedded in a larger struct. */
static void test_stride(void)
{
    struct { float pos[3]; int tag; } pts[50];
    for (int i = 0; i < 50; i++) { pts[i].pos[0] = (float)i; pts[i].pos[1] = 0; pts[i].pos[2] = 0; pts[i].tag = i; }
    pnpr_kdtree *t = NULL;
    CHECK_STATUS(pnpr_kdtree_build(pts[0].pos, 50, sizeof pts[0], &t), PNPR_OK);
    float q[3] = {20.2f, 0, 0};
    uint32_t idx[3];
    CHECK(pnpr_kdtree_knn(t, q, 3, idx, NULL) == 3);
    CHECK(idx[0] == 20 && idx[1] == 21 && idx[2] == 19);
    pnpr_kdtree_free(t);
}

/* pnpr_point_spacing's known answers: a square grid of step h (its 4th nearest other point is at h),
 * a far point clamped to 4 x the median, duplicates raised to 1/8 of it, a NaN point at 1/8, a lone
 * point 1; the handed-over lists are pnpr_knn_self's rows. */
static void test_spacing(void)
{
    enum { G = 20, N = G * G + 4 };
    const float h = 0.25f;
    float *xyz = calloc(3 * N, sizeof *xyz), *sp = malloc(N * sizeof *sp);
    for (int i = 0; i < G * G; i++) { xyz[3 * i] = h * (float)(i % G); xyz[3 * i + 1] = h * (float)(i / G); }
    float *far = xyz + 3 * (G * G), *nanp = far + 3;
    far[0] = 1000;                          /* isolated: spacing about 1000 before the clamp */
    nanp[0] = NAN;
    for (int d = 0; d < 2; d++) {           /* two duplicates of point 0 (with it: 3 at one place) */
        float *p = nanp + 3 * (d + 1);
        p[0] = p[1] = p[2] = 0;
    }
    pnpr_spacing_lists lists = {6, NULL, NULL, 0};
    CHECK_STATUS(pnpr_point_spacing(xyz, N, 4, 1, sp, &lists), PNPR_OK);
    CHECK_MSG(fabsf(sp[G * 5 + 5] - h) < 1e-6f, "interior grid point: %g, want %g", (double)sp[G * 5 + 5], (double)h);
    CHECK_MSG(fabsf(sp[G * G] - 4 * h) < 1e-6f, "far point: %g, want 4 x the median %g", (double)sp[G * G], (double)(4 * h));
    CHECK_MSG(fabsf(sp[G * G + 1] - 0.125f * h) < 1e-6f, "NaN point: %g", (double)sp[G * G + 1]);
    /* point 0 has its two duplicates, then its grid neighbours at h and h: its 4th other is at h */
    CHECK_MSG(fabsf(sp[0] - h) < 1e-6f, "corner with duplicates: %g", (double)sp[0]);
    CHECK_MSG(lists.idx && lists.d2 && lists.k == 6 && lists.idx[6 * (G * 5 + 5)] == G * 5 + 5 && lists.d2[6 * (G * 5 + 5) + 1] > 0,
              "lists: k %zu", lists.k);
    free(lists.idx);
    free(lists.d2);
    /* all duplicates: a median of 0 becomes the largest (0) then 1; spacing 1/8 */
    float dup[9] = {1, 2, 3, 1, 2, 3, 1, 2, 3};
    CHECK_STATUS(pnpr_point_spacing(dup, 3, 4, 1, sp, NULL), PNPR_OK);
    CHECK_MSG(sp[0] == 0.125f && sp[2] == 0.125f, "duplicates: %g", (double)sp[0]);
    CHECK_STATUS(pnpr_point_spacing(xyz, 1, 4, 1, sp, NULL), PNPR_OK);
    CHECK_MSG(sp[0] == 1, "lone point: %g", (double)sp[0]);
    CHECK_STATUS(pnpr_point_spacing(xyz, 0, 4, 1, sp, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_point_spacing(xyz, 4, 0, 1, sp, NULL), PNPR_ERR_INVALID_ARGUMENT);
    free(xyz);
    free(sp);
}

int main(void)
{
    test_against_brute_force();
    test_self(10);
    test_self(256);
    test_self(300);
    test_degenerate();
    test_stride();
    test_spacing();
    return pnpr_test_finish("test_knn");
}
