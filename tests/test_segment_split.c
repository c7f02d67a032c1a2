/* Covariance splitting within regions: a folded region (two perpendicular sheets) is split at the
 * fold into pure parts, a flat one is left whole; invalid points and bad arguments are defined. */
#include "testutil.h"
#include <pointnpr/segment.h>
#include <math.h>
#include <stdlib.h>

int main(void)
{
    /* region 0: a flat sheet 40 x 40 (z = 0, x in [2, 2.4]); region 1: a fold, sheet A in z = 0
     * (x in [0, 0.4]) and sheet B in x = 0.4 (z in [0, 0.4]) */
    enum { G = 40, N = 3 * G * G + 2 };
    float *xyz = malloc(N * 3 * sizeof(float));
    uint32_t *lab = malloc(N * sizeof(uint32_t)), *out = malloc(N * sizeof(uint32_t)), *truth = malloc(N * sizeof(uint32_t));
    size_t n = 0;
    for (int i = 0; i < G; i++)
        for (int j = 0; j < G; j++) {
            float *p = xyz + 3 * n;
            p[0] = 2.0f + 0.01f * i; p[1] = 0.01f * j; p[2] = 0;
            lab[n] = 0; truth[n++] = 0;
        }
    for (int sheet = 0; sheet < 2; sheet++)
        for (int i = 0; i < G; i++)
            for (int j = 0; j < G; j++) {
                float *p = xyz + 3 * n;
                if (sheet == 0) { p[0] = 0.01f * i; p[1] = 0.01f * j; p[2] = 0; }
                else { p[0] = 0.4f; p[1] = 0.01f * j; p[2] = 0.01f * (i + 1); }
                lab[n] = 1; truth[n++] = 1 + (uint32_t)sheet;
            }
    /* one NaN point and one point with an out-of-range label */
    xyz[3 * n] = NAN; xyz[3 * n + 1] = 0; xyz[3 * n + 2] = 0; lab[n] = 0; truth[n++] = 99;
    xyz[3 * n] = 5; xyz[3 * n + 1] = 5; xyz[3 * n + 2] = 5; lab[n] = 7; truth[n++] = 99;

    uint32_t S = 0;
    CHECK_STATUS(pnpr_segment_covariance_split(xyz, n, lab, 2, 0, 0, out, &S), PNPR_OK);
    /* the flat region stays one sub-region */
    uint32_t flat = out[0];
    size_t flat_ok = 0;
    for (size_t i = 0; i < (size_t)G * G; i++) flat_ok += out[i] == flat;
    CHECK(flat_ok == (size_t)G * G);
    /* the fold: every sub-region is pure (>= 95% one sheet), and both sheets are represented */
    uint32_t *cnt = calloc((size_t)S * 3, sizeof(uint32_t));
    for (size_t i = (size_t)G * G; i < (size_t)3 * G * G; i++) cnt[3 * out[i] + (truth[i] - 1)]++;
    size_t parts = 0, impure = 0;
    for (uint32_t s = 0; s < S; s++) {
        uint32_t a = cnt[3 * s], b = cnt[3 * s + 1];
        if (a + b == 0) continue;
        parts++;
        uint32_t mx = a > b ? a : b;
        impure += mx < 0.95 * (a + b);
        CHECK(s != flat);
    }
    fprintf(stderr, "fold split into %zu parts (%zu impure), %u sub-regions in all\n", parts, impure, S);
    CHECK(parts >= 2);
    CHECK(impure == 0);
    /* invalid points: one shared label, the last */
    CHECK(out[n - 1] == S - 1 && out[n - 2] == S - 1);
    /* in place works the same */
    uint32_t S2 = 0;
    CHECK_STATUS(pnpr_segment_covariance_split(xyz, n, lab, 2, 0, 0, lab, &S2), PNPR_OK);
    CHECK(S2 == S);
    int same = 1;
    for (size_t i = 0; i < n; i++) same &= lab[i] == out[i];
    CHECK(same);
    /* a huge threshold splits nothing; defined results for degenerate calls */
    for (size_t i = 0; i < n; i++) lab[i] = truth[i] == 0 ? 0 : (truth[i] == 99 ? 9 : 1);
    CHECK_STATUS(pnpr_segment_covariance_split(xyz, n, lab, 2, 0.34f, 0, out, &S2), PNPR_OK);
    CHECK(S2 == 3); /* two regions + the invalid label */
    CHECK_STATUS(pnpr_segment_covariance_split(xyz, n, lab, 2, 0.5f, 0, out, &S2), PNPR_ERR_INVALID_ARGUMENT); /* beyond the table's range */
    CHECK_STATUS(pnpr_segment_covariance_split(xyz, 0, lab, 2, 0, 0, out, &S2), PNPR_OK);
    CHECK(S2 == 0);
    CHECK_STATUS(pnpr_segment_covariance_split(xyz, n, lab, 2, -1, 0, out, &S2), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_segment_covariance_split(xyz, n, lab, 2, NAN, 0, out, &S2), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_segment_covariance_split(xyz, n, lab, 2, 0, 0, NULL, &S2), PNPR_ERR_INVALID_ARGUMENT);
    free(cnt); free(xyz); free(lab); free(out); free(truth);
    return pnpr_test_finish("test_segment_split");
}
