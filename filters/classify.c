/* Point classification (PointWorks section 4.2).
 *
 * Feature points: degree >= threshold. For each feature point, its k nearest *feature* points
 * (itself included; a kd-tree over the feature points only) get a least-squares 3D line fit: the
 * line through their centroid along the principal eigenvector of their covariance. The fit error
 * relative to the spread, r = (mu_0 + mu_1) / (mu_0 + mu_1 + mu_2) in [0, 2/3] (mu ascending
 * eigenvalues), gives the confidence 1 - 1.5 r in [0,1]: 1 for points exactly on a line, 0 for an
 * isotropic blob. Confidence >= min_confidence: directional, else non-directional.
 * Defined results: fewer than 3 feature points in the neighbourhood, or all coincident:
 * non-directional, confidence 0, direction (0,0,0). Directions are sign-normalised (largest
 * component positive) so that results do not depend on the solver's sign choice.
 *
 * The automatic threshold: the triangle method on the degree histogram (see
 * pnpr_auto_threshold), clamped to [0.2, 0.5]: featureless clouds (a sphere, a plane) keep no
 * feature points, and scans with features split at the knee of the histogram. */
#include <pointnpr/features.h>
#include <pointnpr/knn.h>

#include "../core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define AUTO_MIN 0.2
#define AUTO_MAX 0.5

float pnpr_auto_threshold(const float *degree, size_t count)
{
    /* Triangle method (Zack et al. 1977) on a 100-bin histogram: the line from the histogram's
     * peak to its last non-empty bin; the threshold is the bin farthest below that line (the
     * knee where the many non-feature points give way to the tail of features). Suited to a
     * histogram with a dominant peak near 0 and a long tail, which is what feature degrees of
     * scans look like; Otsu's two-class split is pulled towards the big class there. */
    enum { NB = 100 };
    double hist[NB] = {0};
    size_t total = 0;
    for (size_t i = 0; i < count; i++) {
        float d = degree[i];
        if (!(d >= 0) || d > 1) continue;
        int b = (int)(d * NB);
        hist[b < NB ? b : NB - 1] += 1;
        total++;
    }
    if (total < 2) return (float)AUTO_MIN;
    int peak = 0, last = 0;
    for (int b = 0; b < NB; b++) {
        if (hist[b] > hist[peak]) peak = b;
        if (hist[b] > 0) last = b;
    }
    if (last <= peak + 1) return (float)AUTO_MIN; /* no tail: no features */
    double x0 = peak, y0 = hist[peak], x1 = last, y1 = hist[last];
    double nx = y1 - y0, ny = x0 - x1, nl = sqrt(nx * nx + ny * ny);
    int best = peak + 1;
    double best_d = -1;
    for (int b = peak + 1; b <= last; b++) {
        double dd = fabs(nx * (b - x0) + ny * (hist[b] - y0)) / nl;
        if (dd > best_d) { best_d = dd; best = b; }
    }
    double t = (best + 1.0) / NB;
    return (float)(t < AUTO_MIN ? AUTO_MIN : (t > AUTO_MAX ? AUTO_MAX : t));
}

static int is_feature(const float *p, float degree, float threshold)
{
    return degree >= threshold && degree > 0 && isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

typedef struct classify_job {
    const float *fxyz;       /* feature point coordinates, compact */
    const uint32_t *fid;     /* feature point -> cloud index */
    const pnpr_kdtree *tree; /* over fxyz */
    size_t k;
    float min_conf;
    uint8_t *cls;
    float *conf, *dir[3];
} classify_job;

/* Robust direction: among candidate lines through the point itself (towards its farther
 * neighbours), the one with most neighbours within `tol` of it; then the least-squares line
 * (PCA) over those inliers. Near corners and junctions this keeps the points of the other
 * branches from tilting the direction. Returns the number of inliers (0 = no line). */
/* Whether p lies within tol of the line through `a` along unit direction d. */
static int is_inlier(const float *p, const double a[3], const double d[3], double tol)
{
    double e[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    double t = e[0] * d[0] + e[1] * d[1] + e[2] * d[2];
    return e[0] * e[0] + e[1] * e[1] + e[2] * e[2] - t * t <= tol * tol;
}

static size_t robust_line(const float *fxyz, const uint32_t *idx, size_t got, const float *pi,
                          double tol, double r_c[3], double r_dir[3])
{
    double best_dir[3] = {0, 0, 0};
    const double pid[3] = {pi[0], pi[1], pi[2]};
    size_t best = 0;
    for (size_t cand = got / 4; cand < got; cand += 2) {
        const float *q = fxyz + 3 * (size_t)idx[cand];
        double d[3] = {q[0] - pi[0], q[1] - pi[1], q[2] - pi[2]};
        double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(l > 0)) continue;
        d[0] /= l; d[1] /= l; d[2] /= l;
        size_t in = 0;
        for (size_t r = 0; r < got; r++) in += is_inlier(fxyz + 3 * (size_t)idx[r], pid, d, tol);
        if (in > best) { best = in; memcpy(best_dir, d, sizeof d); }
    }
    if (best < 3) return 0;
    /* least-squares line of the inliers, refined twice with the inliers of the fitted line itself
     * (a candidate through the point is slightly tilted inside a feature band several points
     * wide; its refit converges to the band's axis) */
    double c[3], d[3] = {best_dir[0], best_dir[1], best_dir[2]}, ac[3] = {pi[0], pi[1], pi[2]};
    size_t in = 0;
    for (int pass = 0; pass < 3; pass++) {
        double cov[3][3] = {{0}}, s[3] = {0, 0, 0};
        in = 0;
        for (size_t r = 0; r < got; r++) {
            const float *p = fxyz + 3 * (size_t)idx[r];
            if (!is_inlier(p, ac, d, tol)) continue;
            for (int a = 0; a < 3; a++) s[a] += p[a];
            in++;
        }
        if (in < 3) return 0;
        for (int a = 0; a < 3; a++) c[a] = s[a] / (double)in;
        for (size_t r = 0; r < got; r++) {
            const float *p = fxyz + 3 * (size_t)idx[r];
            if (!is_inlier(p, ac, d, tol)) continue;
            double f[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
            for (int x = 0; x < 3; x++)
                for (int y = 0; y < 3; y++) cov[x][y] += f[x] * f[y];
        }
        double w[3], v[3][3];
        pnpr_eigen_sym3(cov, w, v);
        if (!(w[2] > 0)) return 0;
        memcpy(d, v[2], sizeof d);
        memcpy(ac, c, sizeof ac);
    }
    memcpy(r_c, c, sizeof c);
    memcpy(r_dir, d, sizeof d);
    return in;
}

static void classify_range(void *ctx, size_t begin, size_t end)
{
    const classify_job *j = ctx;
    uint32_t idx[256];
    float dist2[256];
    for (size_t f = begin; f < end; f++) {
        const float *pi = j->fxyz + 3 * f;
        size_t got = pnpr_kdtree_knn(j->tree, pi, j->k, idx, dist2);
        uint32_t i = j->fid[f];
        j->cls[i] = PNPR_CLASS_NONDIRECTIONAL;
        j->conf[i] = 0.0f;
        for (int a = 0; a < 3; a++) if (j->dir[a]) j->dir[a][i] = 0.0f;
        if (got < 3) continue;
        /* inlier tolerance: a quarter of the median neighbour distance */
        double tol = 0.25 * sqrt((double)dist2[got / 2]);
        double c[3], d[3];
        if (!(tol > 0) || robust_line(j->fxyz, idx, got, pi, tol, c, d) == 0) continue;
        /* confidence from the fit error of all neighbours about the line */
        double par = 0, perp = 0;
        for (size_t r = 0; r < got; r++) {
            const float *p = j->fxyz + 3 * (size_t)idx[r];
            double e[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
            double t = e[0] * d[0] + e[1] * d[1] + e[2] * d[2];
            par += t * t;
            perp += e[0] * e[0] + e[1] * e[1] + e[2] * e[2] - t * t;
        }
        if (perp < 0) perp = 0;
        if (!(par + perp > 0)) continue;
        double conf = 1.0 - 1.5 * perp / (par + perp);
        conf = conf < 0 ? 0 : (conf > 1 ? 1 : conf);
        j->conf[i] = (float)conf;
        if (conf >= j->min_conf) j->cls[i] = PNPR_CLASS_DIRECTIONAL;
        int big = 0;
        for (int a = 1; a < 3; a++) if (fabs(d[a]) > fabs(d[big])) big = a;
        double s = d[big] < 0 ? -1.0 : 1.0;
        for (int a = 0; a < 3; a++) if (j->dir[a]) j->dir[a][i] = (float)(s * d[a]);
    }
}

/* The feature points' positions fid[0..nf) in input_index order (the kd-tree's ties follow it). */
static int order_by_input(uint32_t *fid, size_t nf, const uint32_t *input_index)
{
    uint64_t *pair = malloc(nf * sizeof *pair);
    if (!pair) return 0;
    for (size_t f = 0; f < nf; f++) pair[f] = (uint64_t)input_index[fid[f]] << 32 | fid[f];
    qsort(pair, nf, sizeof *pair, pnpr_cmp_u64);
    for (size_t f = 0; f < nf; f++) fid[f] = (uint32_t)pair[f];
    free(pair);
    return 1;
}

pnpr_status pnpr_classify_features(const float *xyz, const float *degree, size_t count, size_t k,
                                   float threshold, float min_confidence, int threads,
                                   const uint32_t *input_index,
                                   uint8_t *r_class, float *r_confidence, float *r_dir_x,
                                   float *r_dir_y, float *r_dir_z)
{
    float *dirs[3] = {r_dir_x, r_dir_y, r_dir_z};
    if (count && (!xyz || !degree || !r_class || !r_confidence)) return PNPR_ERR_INVALID_ARGUMENT;
    if (!isfinite(threshold) || !isfinite(min_confidence)) return PNPR_ERR_INVALID_ARGUMENT;
    if (k == 0) k = 16;
    if (k > 256) k = 256;
    size_t nf = 0;
    for (size_t i = 0; i < count; i++) {
        r_class[i] = PNPR_CLASS_NONE;
        r_confidence[i] = 0.0f;
        for (int a = 0; a < 3; a++) if (dirs[a]) dirs[a][i] = 0.0f;
        nf += is_feature(xyz + 3 * i, degree[i], threshold);
    }
    if (nf == 0) return PNPR_OK;
    float *fxyz = malloc(nf * 3 * sizeof(float));
    uint32_t *fid = malloc(nf * sizeof(uint32_t));
    pnpr_kdtree *tree = NULL;
    pnpr_status st = PNPR_ERR_OUT_OF_MEMORY;
    if (fxyz && fid) {
        size_t f = 0;
        for (size_t i = 0; i < count; i++)
            if (is_feature(xyz + 3 * i, degree[i], threshold)) fid[f++] = (uint32_t)i;
        st = !input_index || order_by_input(fid, nf, input_index) ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
        for (f = 0; st == PNPR_OK && f < nf; f++) memcpy(fxyz + 3 * f, xyz + 3 * (size_t)fid[f], 3 * sizeof(float));
        if (st == PNPR_OK) st = pnpr_kdtree_build(fxyz, nf, 0, &tree);
    }
    if (st == PNPR_OK) {
        classify_job j = {fxyz, fid, tree, k, min_confidence, r_class, r_confidence, {r_dir_x, r_dir_y, r_dir_z}};
        st = pnpr_parallel_for(nf, 1024, threads, classify_range, &j, NULL, "classify");
    }
    pnpr_kdtree_free(tree);
    free(fxyz);
    free(fid);
    return st;
}
