/* The leaves of Chi & Lee's sphere hierarchy (sec. 3.1; include/pointnpr/hierarchy.h):
 *  1. uniform resampling: a greedy Poisson-disk selection in point order on a hash grid of cell
 *     `spacing` (a point becomes a leaf when no leaf lies within `spacing`), standing in for the
 *     paper's mesh resampling with Turk's relaxation (a point cloud has no faces to relax over);
 *  2. every point joins its nearest leaf, so each point lies in exactly one leaf, at most `spacing`
 *     from its centre; a leaf's radius is its farthest point (at least spacing / 2), its colour the
 *     mean of its points;
 *  3. normal, curvature (surface variation, Pauly et al.) and principal direction by PCA over the
 *     k nearest leaves; the direction is the eigenvector of the largest eigenvalue (along ridges and
 *     creases: the direction of least curvature, which hatching follows), in the tangent plane;
 *  4. only the leaves of highest curvature (feature_fraction) keep it (the paper's feature points,
 *     after Hays & Essa); the others get the normalised Gaussian-RBF mean of the directions of their
 *     nearest feature leaves (axial: signs aligned first), projected into their tangent plane. A
 *     normalised kernel instead of a solved RBF system: no linear solve over 10^5 centres, and no
 *     overshoot between centres (docs/hierarchy.md). */
#include "sphere_internal.h"

#include <pointnpr/features.h>

#include "../core/internal.h"
#include "../core/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { RBF_K = 6 };

static int64_t cell_coord(float v, float spacing)
{
    double c = floor((double)v / (double)spacing);
    const double lim = 4.0e15;
    return (int64_t)(c < -lim ? -lim : c > lim ? lim : c);
}

static uint64_t cell_hash(int64_t x, int64_t y, int64_t z)
{
    uint64_t h = (uint64_t)x * 0x9E3779B97F4A7C15ull ^ (uint64_t)y * 0xC2B2AE3D27D4EB4Full ^ (uint64_t)z * 0x165667B19E3779F9ull;
    return h ^ (h >> 29);
}

typedef struct grid {
    uint32_t *head, mask; /* hash bucket -> first leaf (PNPR_INDEX_NONE), chained by next */
    uint32_t *next;
} grid;

static int near_leaf(const grid *g, const float *pts, const uint32_t *leaf_pt, const float *p, float spacing)
{
    int64_t c[3] = {cell_coord(p[0], spacing), cell_coord(p[1], spacing), cell_coord(p[2], spacing)};
    float s2 = spacing * spacing;
    for (int dx = -1; dx <= 1; dx++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dz = -1; dz <= 1; dz++) {
                uint32_t b = (uint32_t)(cell_hash(c[0] + dx, c[1] + dy, c[2] + dz) & g->mask);
                for (uint32_t l = g->head[b]; l != PNPR_INDEX_NONE; l = g->next[l]) {
                    const float *q = pts + 3 * (size_t)leaf_pt[l];
                    float d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
                    if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < s2) return 1;
                }
            }
    return 0;
}

/* Step 1: the seed point of each leaf into r_seed (count entries); *r_leaves. */
pnpr_status pnpr_sphere_pick_leaves(const float *xyz, size_t count, float spacing, uint32_t *r_seed,
                                    size_t *r_leaves)
{
    size_t cap = 1024;
    while (cap < 2 * count && cap < ((size_t)1 << 31)) cap <<= 1;
    grid g = {malloc(cap * sizeof *g.head), (uint32_t)(cap - 1), malloc((count ? count : 1) * sizeof *g.next)};
    if (!g.head || !g.next) { free(g.head); free(g.next); return PNPR_ERR_OUT_OF_MEMORY; }
    memset(g.head, 0xFF, cap * sizeof *g.head);
    size_t n = 0;
    for (size_t i = 0; i < count; i++) {
        const float *p = xyz + 3 * i;
        if (!pnpr_finite3f(p) || near_leaf(&g, xyz, r_seed, p, spacing)) continue;
        uint32_t b = (uint32_t)(cell_hash(cell_coord(p[0], spacing), cell_coord(p[1], spacing),
                                          cell_coord(p[2], spacing)) & g.mask);
        r_seed[n] = (uint32_t)i;
        g.next[n] = g.head[b];
        g.head[b] = (uint32_t)n++;
    }
    free(g.head); free(g.next);
    *r_leaves = n;
    return PNPR_OK;
}

typedef struct assign_job {
    const pnpr_kdtree *tree;
    const float *xyz;
    uint32_t *point_leaf;
} assign_job;

static void assign_range(void *ctx, size_t begin, size_t end)
{
    const assign_job *j = ctx;
    for (size_t i = begin; i < end; i++) {
        uint32_t idx = PNPR_INDEX_NONE;
        float d2;
        if (pnpr_finite3f(j->xyz + 3 * i)) pnpr_kdtree_knn(j->tree, j->xyz + 3 * i, 1, &idx, &d2);
        j->point_leaf[i] = idx;
    }
}

/* Step 2: point -> nearest leaf (leaf tree built over the leaf centres); leaf radius and colour. */
pnpr_status pnpr_sphere_assign(const pnpr_cloud *c, const pnpr_kdtree *leaf_tree, sphere_build *b, int threads,
                               const pnpr_progress *progress)
{
    assign_job j = {leaf_tree, c->xyz, b->point_leaf};
    pnpr_status st = pnpr_parallel_for(c->count, 4096, threads, assign_range, &j, progress, "leaves");
    if (st != PNPR_OK) return st;
    double *sum = calloc(b->leaves ? 3 * b->leaves : 1, sizeof *sum);
    uint32_t *n = calloc(b->leaves ? b->leaves : 1, sizeof *n);
    if (!sum || !n) { free(sum); free(n); return PNPR_ERR_OUT_OF_MEMORY; }
    for (size_t i = 0; i < c->count; i++) {
        uint32_t l = b->point_leaf[i];
        if (l == PNPR_INDEX_NONE) continue;
        sphere_work *nd = &b->nodes[l];
        const float *p = c->xyz + 3 * i;
        float d[3] = {p[0] - nd->centre[0], p[1] - nd->centre[1], p[2] - nd->centre[2]};
        float r = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (r > nd->radius) nd->radius = r;
        n[l]++;
        for (int k = 0; k < 3; k++) sum[3 * l + k] += c->rgb ? c->rgb[3 * i + k] : PNPR_SPHERE_GREY;
    }
    for (size_t l = 0; l < b->leaves; l++)
        for (int k = 0; k < 3; k++) b->nodes[l].colour[k] = n[l] ? (float)(sum[3 * l + k] / n[l]) : PNPR_SPHERE_GREY;
    free(sum); free(n);
    return PNPR_OK;
}

/* Step 3 for one leaf from its kNN row. */
static void leaf_pca(sphere_work *nodes, size_t l, const uint32_t *row, size_t k)
{
    double m[3] = {0, 0, 0}, cov[3][3] = {{0}};
    size_t n = 0;
    for (size_t t = 0; t < k && row[t] != PNPR_INDEX_NONE; t++, n++)
        for (int a = 0; a < 3; a++) m[a] += nodes[row[t]].centre[a];
    sphere_work *nd = &nodes[l];
    if (n < 3) return; /* normal, direction unknown (0), curvature 0 */
    for (int a = 0; a < 3; a++) m[a] /= (double)n;
    for (size_t t = 0; t < n; t++) {
        double d[3];
        for (int a = 0; a < 3; a++) d[a] = nodes[row[t]].centre[a] - m[a];
        for (int a = 0; a < 3; a++)
            for (int e = 0; e < 3; e++) cov[a][e] += d[a] * d[e];
    }
    double w[3], v[3][3];
    pnpr_eigen_sym3(cov, w, v);
    double tr = w[0] + w[1] + w[2];
    nd->curvature = tr > 0 ? (float)(w[0] / tr) : 0.0f;
    for (int a = 0; a < 3; a++) {
        nd->normal[a] = (float)v[0][a];
        nd->dir[a] = (float)v[2][a];
    }
}

typedef struct pca_job {
    sphere_work *nodes;
    const uint32_t *knn;
    size_t k;
} pca_job;

static void pca_range(void *ctx, size_t begin, size_t end)
{
    const pca_job *j = ctx;
    for (size_t l = begin; l < end; l++) leaf_pca(j->nodes, l, j->knn + l * j->k, j->k);
}

/* The curvature above which a leaf is a feature leaf (the top `fraction`). */
static float feature_bound(const sphere_work *nodes, size_t leaves, float fraction)
{
    float *c = malloc((leaves ? leaves : 1) * sizeof *c);
    if (!c) return 0.0f;
    for (size_t l = 0; l < leaves; l++) c[l] = nodes[l].curvature;
    qsort(c, leaves, sizeof *c, pnpr_cmp_float);
    size_t at = (size_t)((1.0 - (double)fraction) * (double)leaves);
    float b = leaves ? c[at < leaves ? at : leaves - 1] : 0.0f;
    free(c);
    return b;
}

typedef struct rbf_job {
    sphere_work *nodes;
    const pnpr_kdtree *ftree;
    const uint32_t *feature; /* feature leaf of each ftree index */
    const uint8_t *is_feature;
    float sigma;
} rbf_job;

/* Step 4 for one non-feature leaf. */
static void rbf_leaf(const rbf_job *j, size_t l)
{
    sphere_work *nd = &j->nodes[l];
    uint32_t idx[RBF_K];
    float d2[RBF_K];
    size_t found = pnpr_kdtree_knn(j->ftree, nd->centre, RBF_K, idx, d2);
    double acc[3] = {0, 0, 0}, first[3] = {0, 0, 0};
    for (size_t t = 0; t < found; t++) {
        const float *fd = j->nodes[j->feature[idx[t]]].dir;
        double w = exp(-0.5 * (double)d2[t] / ((double)j->sigma * j->sigma)) + 1e-12;
        double s = t == 0 ? 1.0 : (fd[0] * first[0] + fd[1] * first[1] + fd[2] * first[2] < 0 ? -1.0 : 1.0);
        for (int a = 0; a < 3; a++) {
            if (t == 0) first[a] = fd[a];
            acc[a] += s * w * fd[a];
        }
    }
    pnpr_sphere_tangent(nd->normal, acc, nd->dir);
}

static void rbf_range(void *ctx, size_t begin, size_t end)
{
    const rbf_job *j = ctx;
    for (size_t l = begin; l < end; l++)
        if (!j->is_feature[l]) rbf_leaf(j, l);
}

/* Steps 3 and 4: knn holds k leaf neighbours per leaf (the leaf itself first). */
pnpr_status pnpr_sphere_leaf_shape(sphere_build *b, const uint32_t *knn, size_t k, float fraction, int threads,
                                   const pnpr_progress *progress)
{
    pca_job pj = {b->nodes, knn, k};
    pnpr_status st = pnpr_parallel_for(b->leaves, 2048, threads, pca_range, &pj, progress, "knn");
    if (st != PNPR_OK || b->leaves == 0) return st;
    float bound = feature_bound(b->nodes, b->leaves, fraction);
    uint8_t *is_f = calloc(b->leaves, 1);
    uint32_t *feat = malloc(b->leaves * sizeof *feat);
    float *fxyz = malloc(3 * b->leaves * sizeof *fxyz);
    size_t nf = 0;
    if (!is_f || !feat || !fxyz) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    for (size_t l = 0; l < b->leaves; l++)
        if (b->nodes[l].curvature >= bound && b->nodes[l].dir[0] * b->nodes[l].dir[0] + b->nodes[l].dir[1] * b->nodes[l].dir[1] +
                                                      b->nodes[l].dir[2] * b->nodes[l].dir[2] > 0.5f) {
            is_f[l] = 1;
            feat[nf] = (uint32_t)l;
            memcpy(fxyz + 3 * nf++, b->nodes[l].centre, 3 * sizeof(float));
        }
    pnpr_kdtree *ft = NULL;
    if (nf && (st = pnpr_kdtree_build_threads(fxyz, nf, 0, threads, &ft)) == PNPR_OK) {
        /* sigma: the typical distance between feature leaves, sqrt(1 / fraction) leaf spacings */
        rbf_job rj = {b->nodes, ft, feat, is_f, b->spacing * sqrtf(1.0f / fraction)};
        st = pnpr_parallel_for(b->leaves, 2048, threads, rbf_range, &rj, progress, "knn");
    }
    pnpr_kdtree_free(ft);
done:
    free(is_f); free(feat); free(fxyz);
    return st;
}

void pnpr_sphere_tangent(const float n[3], const double v[3], float r_dir[3])
{
    double nn[3] = {n[0], n[1], n[2]}, t[3] = {v[0], v[1], v[2]};
    double d = pnpr_dot3(nn, t);
    for (int a = 0; a < 3; a++) t[a] -= d * nn[a];
    double len = pnpr_normalize3(t);
    for (int a = 0; a < 3; a++) r_dir[a] = len > 1e-12 ? (float)t[a] : 0.0f;
}
