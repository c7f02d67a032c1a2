/* The local point spacing (pnpr_point_spacing, knn.h): the distance from each point to its k-th
 * nearest other point, clamped to a band around the median. The renderer's disk radii and the
 * SVG outlines' surface buffer both take their disks from it, so the two draw the same surface. */
#include "../core/internal.h"
#include "../core/vec3.h"

#include <pointnpr/knn.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

pnpr_status pnpr_spacing_clamp(float *r, size_t n)
{
    if (n == 0) return PNPR_OK;
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

void pnpr_spacing_from_lists(const float *xyz, size_t n, const uint32_t *idx, size_t kk, uint32_t k, float *r_spacing)
{
    size_t kr = (size_t)k + 1 < kk ? (size_t)k + 1 : kk;
    for (size_t i = 0; i < n; i++) { /* the farthest of the first kr listed */
        const float *q = xyz + 3 * i;
        float best = 0;
        for (size_t j = 0; j < kr; j++) {
            uint32_t nb = idx[i * kk + j];
            if (nb == PNPR_INDEX_NONE || nb >= n) continue;
            float d = pnpr_dist2f(xyz + 3 * (size_t)nb, q); /* as knn_rec (kdtree.c) */
            if (d > best) best = d;
        }
        r_spacing[i] = sqrtf(best);
    }
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
    if (st == PNPR_OK) pnpr_spacing_from_lists(xyz, n, idx, kk, (uint32_t)(kr - 1), r_spacing);
    if (st == PNPR_OK) st = pnpr_spacing_clamp(r_spacing, n);
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
