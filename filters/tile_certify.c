/* Which of a tile's core points have the results of the in-memory run (pointnpr/tiles.h,
 * docs/tiles.md).
 *
 * A point's neighbourhood is exact when the ball out to its (k+1)-th nearest point in the tile
 * lies inside the tile's box (core grown by the halo; x and y only, the tiles are columns): no
 * point of the whole cloud closer than that can be missing. Normals and fit errors need that
 * (hop 1), the smoothed errors their neighbours' too (hop 2), the degree's Laplacian theirs
 * (hop 3). A feature point's class and direction come from its 2k nearest feature points: exact
 * when their ball lies inside the box and every point that could be in it has an exact degree,
 * i.e. the ball stays farther from the box than any point whose degree is not exact (margins are
 * 1-Lipschitz, so a ball of radius r around a point of margin m holds only margins > m - r).
 * Points with NaN/Inf coordinates are exact: their results are the defined zeros either way. */
#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <pointnpr/props.h>
#include <pointnpr/tiles.h>

#include "../core/internal.h"
#include "../core/vec3.h"
#include "kdtree_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Distance from point i (world x, y) to the box's edge; +inf for a non-finite point. */
static double box_margin(const pnpr_cloud *c, size_t i, const double box[4])
{
    double w[3];
    pnpr_cloud_world(c, i, w);
    if (!pnpr_finite3f(c->xyz + 3 * i)) return INFINITY;
    double m = fmin(fmin(w[0] - box[0], box[2] - w[0]), fmin(w[1] - box[1], box[3] - w[1]));
    return m > 0 ? m : 0;
}

/* Radius of a row of kk entries (nearest first) around q: the distance to its last entry; +inf when
 * the row is not full (the tile holds fewer points than the whole cloud may around it), or when
 * ties may be cut otherwise than in the whole cloud: the kNN orders ties by input index, which a
 * tile keeps, but leaves the cut among exact duplicates (distance 0) to its tree, and beyond 256
 * neighbours any tie (knn.h). */
static double row_radius(const float *xyz, const float *q, const uint32_t *row, size_t kk)
{
    if (row[kk - 1] == PNPR_INDEX_NONE) return INFINITY;
    float last = -1;
    for (size_t j = kk > PNPR_KNN_SORTED_MAX ? 0 : kk - 1; j < kk; j++) {
        float d = pnpr_dist2f(q, xyz + 3 * (size_t)row[j]);
        if (d == last) return INFINITY;
        last = d;
    }
    return kk >= 2 && last == 0 ? INFINITY : sqrt((double)last);
}

/* lvl[i] = the hops (0..3) out to which point i's neighbourhoods are exact. */
static pnpr_status hop_levels(const pnpr_cloud *c, const double *margin, uint32_t k, int threads, uint8_t *lvl)
{
    const size_t n = c->count, kk = (size_t)k + 1;
    pnpr_kdtree *tree = NULL;
    uint32_t *idx = malloc(n * kk * sizeof *idx);
    pnpr_status st = idx ? pnpr_kdtree_build_threads(c->xyz, n, 0, threads, &tree) : PNPR_ERR_OUT_OF_MEMORY;
    pnpr_knn_options ko = {0};
    ko.threads = threads;
    if (st == PNPR_OK) st = pnpr_knn_self(tree, n, kk, &ko, idx, NULL);
    pnpr_kdtree_free(tree);
    for (size_t i = 0; st == PNPR_OK && i < n; i++)
        lvl[i] = isinf(margin[i]) ? 3 : row_radius(c->xyz, c->xyz + 3 * i, idx + i * kk, kk) < margin[i];
    for (uint8_t hop = 2; st == PNPR_OK && hop <= 3; hop++)
        for (size_t i = 0; i < n; i++) {
            if (lvl[i] != hop - 1) continue;
            int all = 1;
            for (size_t j = 0; j < kk && all; j++) {
                uint32_t q = idx[i * kk + j];
                all = q == PNPR_INDEX_NONE || lvl[q] >= hop - 1;
            }
            lvl[i] = (uint8_t)(hop - 1 + all); /* raised after its neighbours were read: a level per pass */
        }
    free(idx);
    return st;
}

/* Feature points (class 1, 2) of the core: their 2k nearest feature points inside the box and
 * farther than `worst` from its edge; exact[i] cleared for the others. */
static pnpr_status check_classes(const pnpr_cloud *c, const uint8_t *core, const double *margin, double worst,
                                 uint32_t k, int threads, uint8_t *exact)
{
    const pnpr_property *cls = pnpr_cloud_find_property(c, PNPR_PROP_FEATURE_CLASS);
    if (!cls || cls->type != PNPR_TYPE_UINT8) return PNPR_OK; /* no classes computed: nothing more to check */
    const uint8_t *cl = cls->data;
    const size_t n = c->count, kk = 2 * (size_t)k + 1; /* the classes' 2k, and the next for its ties */
    size_t nf = 0;
    for (size_t i = 0; i < n; i++) nf += cl[i] == PNPR_CLASS_NONDIRECTIONAL || cl[i] == PNPR_CLASS_DIRECTIONAL;
    float *fx = malloc((nf ? nf : 1) * 3 * sizeof *fx);
    uint32_t *row = malloc(kk * sizeof *row);
    pnpr_kdtree *tree = NULL;
    pnpr_status st = fx && row ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0, f = 0; st == PNPR_OK && i < n; i++)
        if (cl[i] == PNPR_CLASS_NONDIRECTIONAL || cl[i] == PNPR_CLASS_DIRECTIONAL) memcpy(fx + 3 * f++, c->xyz + 3 * i, 12);
    if (st == PNPR_OK) st = pnpr_kdtree_build_threads(fx, nf, 0, threads, &tree);
    for (size_t i = 0; st == PNPR_OK && i < n; i++) {
        if (!core[i] || !exact[i] || isinf(margin[i]) ||
            (cl[i] != PNPR_CLASS_NONDIRECTIONAL && cl[i] != PNPR_CLASS_DIRECTIONAL))
            continue;
        size_t got = pnpr_kdtree_knn(tree, c->xyz + 3 * i, kk, row, NULL);
        double r = got < kk ? INFINITY : row_radius(fx, c->xyz + 3 * i, row, kk);
        exact[i] = r < margin[i] - (worst > 0 ? worst : 0);
    }
    pnpr_kdtree_free(tree);
    free(fx);
    free(row);
    return st;
}

pnpr_status pnpr_tile_certify(const pnpr_cloud *cloud, const uint8_t *core, const double box[4], uint32_t k,
                              int threads, uint8_t *r_exact, size_t *r_uncertain)
{
    if (!cloud || (!core && cloud->count) || !box || k < 1 || (cloud->count && !cloud->xyz))
        return PNPR_ERR_INVALID_ARGUMENT;
    const size_t n = cloud->count;
    double *margin = malloc((n ? n : 1) * sizeof *margin);
    uint8_t *lvl = malloc(n ? n : 1);
    if (!margin || !lvl) {
        free(margin);
        free(lvl);
        return PNPR_ERR_OUT_OF_MEMORY;
    }
    for (size_t i = 0; i < n; i++) margin[i] = box_margin(cloud, i, box);
    pnpr_status st = hop_levels(cloud, margin, k, threads, lvl);
    double worst = -INFINITY; /* the largest margin of a point whose degree may differ */
    for (size_t i = 0; st == PNPR_OK && i < n; i++) {
        if (lvl[i] < 3 && margin[i] > worst) worst = margin[i];
        lvl[i] = lvl[i] == 3;
    }
    if (st == PNPR_OK) st = check_classes(cloud, core, margin, worst, k, threads, lvl);
    size_t uncertain = 0;
    for (size_t i = 0; st == PNPR_OK && i < n; i++) uncertain += core[i] && !lvl[i];
    if (st == PNPR_OK && r_exact) memcpy(r_exact, lvl, n);
    if (st == PNPR_OK && r_uncertain) *r_uncertain = uncertain;
    free(margin);
    free(lvl);
    return st;
}
