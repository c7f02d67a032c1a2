/* Normals by PCA over the k nearest neighbours (PointWorks section 3: "a least-squares fitting
 * plane to all points adjacent to it"), with the plane-fit error that the feature degree uses.
 *
 * Covariance is accumulated in double around the neighbourhood centroid (two passes), so
 * georeferenced offsets and tiny scales are handled alike. Defined results:
 *  - fewer than 3 valid neighbours, or all neighbours coincident (zero covariance):
 *    normal (0,0,0), fit error 0 — "no normal", which later stages treat as unknown;
 *  - collinear neighbours: a unit normal perpendicular to the line (the eigenvector the solver
 *    returns for the zero eigenvalue; deterministic), fit error ~0;
 *  - invalid (NaN/Inf) points: normal (0,0,0), error 0. */
#include <pointnpr/features.h>
#include <pointnpr/knn.h>

#include "../core/internal.h"

#include <math.h>

typedef struct normals_job {
    const float *xyz;
    const uint32_t *knn;
    size_t k;
    float *normals, *err;
} normals_job;

static void normals_range(void *ctx, size_t begin, size_t end)
{
    const normals_job *j = ctx;
    for (size_t i = begin; i < end; i++) {
        const uint32_t *row = j->knn + i * j->k;
        double c[3] = {0, 0, 0};
        size_t m = 0;
        for (size_t r = 0; r < j->k; r++) {
            if (row[r] == PNPR_INDEX_NONE) continue;
            const float *p = j->xyz + 3 * (size_t)row[r];
            c[0] += p[0]; c[1] += p[1]; c[2] += p[2];
            m++;
        }
        float nbuf[3], *n = j->normals ? j->normals + 3 * i : nbuf;
        n[0] = n[1] = n[2] = 0.0f;
        if (j->err) j->err[i] = 0.0f;
        if (m < 3) continue;
        c[0] /= (double)m; c[1] /= (double)m; c[2] /= (double)m;
        double cov[3][3] = {{0}};
        for (size_t r = 0; r < j->k; r++) {
            if (row[r] == PNPR_INDEX_NONE) continue;
            const float *p = j->xyz + 3 * (size_t)row[r];
            double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
            for (int a = 0; a < 3; a++)
                for (int b = a; b < 3; b++) cov[a][b] += d[a] * d[b];
        }
        cov[1][0] = cov[0][1]; cov[2][0] = cov[0][2]; cov[2][1] = cov[1][2];
        double w[3], v[3][3];
        pnpr_eigen_sym3(cov, w, v);
        double trace = w[0] + w[1] + w[2];
        if (!(trace > 0.0)) continue;
        n[0] = (float)v[0][0]; n[1] = (float)v[0][1]; n[2] = (float)v[0][2];
        if (j->err) {
            double e = w[0] > 0 ? w[0] / trace : 0.0;
            j->err[i] = (float)e;
        }
    }
}

pnpr_status pnpr_estimate_normals(const float *xyz, size_t count, const uint32_t *knn, size_t k,
                                  int threads, float *r_normals, float *r_fit_error)
{
    if (count && (!xyz || !knn || (!r_normals && !r_fit_error) || k == 0)) return PNPR_ERR_INVALID_ARGUMENT;
    normals_job j = {xyz, knn, k, r_normals, r_fit_error};
    return pnpr_parallel_for(count, 2048, threads, normals_range, &j, NULL, "normals");
}
