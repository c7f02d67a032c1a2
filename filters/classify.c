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
 * The automatic threshold: Otsu's split of the degree histogram over the points with a degree
 * above a noise floor (0.05), never below 0.15: featureless clouds (a sphere, a plane) keep
 * no feature points, and clouds with features split where the histogram separates. */
#include <pointnpr/features.h>
#include <pointnpr/knn.h>

#include "../core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define AUTO_FLOOR 0.05
#define AUTO_MIN 0.15
#define HIST 256

float pnpr_auto_threshold(const float *degree, size_t count)
{
    double hist[HIST] = {0};
    double total = 0;
    for (size_t i = 0; i < count; i++) {
        float d = degree[i];
        if (!(d >= AUTO_FLOOR)) continue;
        int b = (int)(d * (HIST - 1) + 0.5);
        if (b > HIST - 1) b = HIST - 1;
        hist[b] += 1;
        total += 1;
    }
    if (total < 2) return (float)AUTO_MIN;
    double sum_all = 0;
    for (int b = 0; b < HIST; b++) sum_all += b * hist[b];
    double w0 = 0, sum0 = 0, best = -1;
    int best_b = 0;
    for (int b = 0; b < HIST - 1; b++) {
        w0 += hist[b];
        sum0 += b * hist[b];
        double w1 = total - w0;
        if (w0 == 0 || w1 == 0) continue;
        double m0 = sum0 / w0, m1 = (sum_all - sum0) / w1;
        double between = w0 * w1 * (m0 - m1) * (m0 - m1);
        if (between > best) { best = between; best_b = b; }
    }
    double t = (best_b + 0.5) / (HIST - 1);
    return (float)(t > AUTO_MIN ? t : AUTO_MIN);
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
static int is_inlier(const float *p, const float *pi, const double d[3], double tol)
{
    double e[3] = {p[0] - pi[0], p[1] - pi[1], p[2] - pi[2]};
    double t = e[0] * d[0] + e[1] * d[1] + e[2] * d[2];
    return e[0] * e[0] + e[1] * e[1] + e[2] * e[2] - t * t <= tol * tol;
}

static size_t robust_line(const float *fxyz, const uint32_t *idx, size_t got, const float *pi,
                          double tol, double r_c[3], double r_dir[3])
{
    double best_dir[3] = {0, 0, 0};
    size_t best = 0;
    for (size_t cand = got / 4; cand < got; cand += 2) {
        const float *q = fxyz + 3 * (size_t)idx[cand];
        double d[3] = {q[0] - pi[0], q[1] - pi[1], q[2] - pi[2]};
        double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(l > 0)) continue;
        d[0] /= l; d[1] /= l; d[2] /= l;
        size_t in = 0;
        for (size_t r = 0; r < got; r++) in += is_inlier(fxyz + 3 * (size_t)idx[r], pi, d, tol);
        if (in > best) { best = in; memcpy(best_dir, d, sizeof d); }
    }
    if (best < 3) return 0;
    double c[3] = {0, 0, 0}, cov[3][3] = {{0}};
    for (size_t r = 0; r < got; r++) {
        const float *p = fxyz + 3 * (size_t)idx[r];
        if (is_inlier(p, pi, best_dir, tol)) for (int a = 0; a < 3; a++) c[a] += p[a];
    }
    for (int a = 0; a < 3; a++) c[a] /= (double)best;
    for (size_t r = 0; r < got; r++) {
        const float *p = fxyz + 3 * (size_t)idx[r];
        if (!is_inlier(p, pi, best_dir, tol)) continue;
        double e[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
        for (int x = 0; x < 3; x++)
            for (int y = 0; y < 3; y++) cov[x][y] += e[x] * e[y];
    }
    double w[3], v[3][3];
    pnpr_eigen_sym3(cov, w, v);
    if (!(w[2] > 0)) return 0;
    memcpy(r_c, c, sizeof c);
    memcpy(r_dir, v[2], sizeof v[2]);
    return best;
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

pnpr_status pnpr_classify_features(const float *xyz, const float *degree, size_t count, size_t k,
                                   float threshold, float min_confidence, int threads,
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
        for (size_t i = 0; i < count; i++) {
            const float *p = xyz + 3 * i;
            if (!is_feature(p, degree[i], threshold)) continue;
            fxyz[3 * f] = p[0]; fxyz[3 * f + 1] = p[1]; fxyz[3 * f + 2] = p[2];
            fid[f++] = (uint32_t)i;
        }
        st = pnpr_kdtree_build(fxyz, nf, 0, &tree);
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
