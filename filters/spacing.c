/* The local point spacing (pnpr_point_spacing, knn.h): the distance from each point to its k-th
 * nearest other point, clamped to a band around the median. The renderer's disk radii and the
 * SVG outlines' surface buffer both take their disks from it, so the two draw the same surface. */
#include "../core/internal.h"

#include <pointnpr/knn.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Clamps r[0..n) to [PNPR_SPACING_CLAMP_LO, PNPR_SPACING_CLAMP_HI] x their median; a median of 0
 * (mostly duplicates) is replaced by the largest value, else 1. */
static pnpr_status clamp_to_median(float *r, size_t n)
{
    float *sorted = malloc(n * sizeof *sorted);
    if (!sorted) return PNPR_ERR_OUT_OF_MEMORY;
    memcpy(sorted, r, n * sizeof *sorted);
    float med = pnpr_median_float(sorted, n);
    if (!(med > 0)) { /* the largest, from the upper half the selection left */
        float top = 0;
        for (size_t i = n / 2; i < n; i++) top = sorted[i] > top ? sorted[i] : top;
        med = top > 0 ? top : 1;
    }
    free(sorted);
    for (size_t i = 0; i < n; i++) {
        if (r[i] > PNPR_SPACING_CLAMP_HI * med) r[i] = PNPR_SPACING_CLAMP_HI * med;
        if (!(r[i] >= PNPR_SPACING_CLAMP_LO * med)) r[i] = PNPR_SPACING_CLAMP_LO * med;
    }
    return PNPR_OK;
}

pnpr_status pnpr_point_spacing(const float *xyz, size_t n, uint32_t k, int threads, float *r_spacing,
                               pnpr_spacing_lists *lists)
{
    if (lists) { lists->idx = NULL; lists->d2 = NULL; lists->k = 0; }
    if (n == 0) return PNPR_OK;
    if (!xyz || !r_spacing || k == 0) return PNPR_ERR_INVALID_ARGUMENT;
    if (n == 1) { r_spacing[0] = 1; return PNPR_OK; }
    size_t kr = (size_t)k + 1 < n ? (size_t)k + 1 : n; /* + the point itself */
    size_t want = lists ? lists->want : 0;
    size_t kk = kr > want ? kr : want < n ? want : n;
    pnpr_kdtree *tree = NULL;
    pnpr_status st = pnpr_kdtree_build_threads(xyz, n, 0, threads, &tree);
    if (st != PNPR_OK) return st;
    uint32_t *idx = malloc(n * kk * sizeof *idx);
    float *d2 = malloc(n * kk * sizeof *d2);
    pnpr_knn_options ko;
    memset(&ko, 0, sizeof ko);
    ko.threads = threads;
    st = idx && d2 ? pnpr_knn_self(tree, n, kk, &ko, idx, d2) : PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; st == PNPR_OK && i < n; i++) { /* the farthest of the first kr found */
        r_spacing[i] = 0;
        for (size_t j = kr; j-- > 0;)
            if (idx[i * kk + j] != PNPR_INDEX_NONE && isfinite(d2[i * kk + j])) { r_spacing[i] = sqrtf(d2[i * kk + j]); break; }
    }
    if (st == PNPR_OK) st = clamp_to_median(r_spacing, n);
    if (st == PNPR_OK && lists && want > 0) { /* hand the lists over */
        lists->idx = idx; lists->d2 = d2; lists->k = kk;
        idx = NULL;
        d2 = NULL;
    }
    free(idx);
    free(d2);
    pnpr_kdtree_free(tree);
    return st;
}
