/* Feature degree (PointWorks section 4.1) on an unorganised cloud.
 *
 * The paper encodes the plane-fit error of every point into a range-image-shaped grey image,
 * runs an edge-detection filter over it, and adds a colour-gradient term from an edge filter
 * over the colour image, with weights (e.g. 0.5/0.5). A scan that is no longer a range image has
 * no pixel grid, so both filters run over each point's k nearest neighbours instead:
 *
 *  Geometry G: a crease does not make a step in the fit error e but a ridge: e is largest on the
 *    crease and falls off over one neighbourhood radius on both sides. A gradient-magnitude edge
 *    filter would answer on the two flanks and vanish on the crest; the discrete Laplacian (the
 *    other classic edge filter) answers on the crest. We use its positive part,
 *        L_i = e_i - mean_{j in N(i), j != i} e_j,   G_i = clamp(L_i / GEO_SCALE, 0, 1),
 *    which is 0 wherever e is uniform — the paper's sphere example: high error, no feature.
 *  Colour C: least-squares fit of a linear colour field c(p) = c0 + g.(p - centroid) in the
 *    tangent plane (normal known; otherwise the PCA plane), per RGB channel with values in
 *    [0,1]; |g| = sqrt(sum over channels |g_c|^2). |g| * r_i (r_i = RMS neighbour distance) is
 *    the colour change across the neighbourhood and is scale-free: C_i = clamp(|g| r_i /
 *    COLOR_SCALE, 0, 1).
 *  degree = (w_g G + w_c C) / (w_g + w_c), in [0,1]. Without colours C is absent and the degree is
 *    G. Both scales are absolute (not normalised by the cloud's own maximum), so a featureless
 *    cloud keeps degrees near 0 instead of amplifying noise to 1. */
#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <pointnpr/options.h>

#include "../core/internal.h"

#include <math.h>
#include <stdlib.h>

#define GEO_SCALE 0.02   /* Laplacian of the smoothed surface variation that counts as a full feature */
#define COLOR_SCALE 0.5  /* RGB change (0..sqrt 3) across a neighbourhood that counts as full */

typedef struct degree_job {
    const float *xyz, *normals, *err, *raw_err;
    float *smooth_out;
    const uint8_t *rgb;
    const uint32_t *knn;
    size_t k;
    double wg, wc;
    float *degree;
} degree_job;

static double clamp01(double v)
{
    return v > 0 ? (v < 1 ? v : 1) : 0; /* NaN -> 0 */
}

/* Tangent basis (u, v) of a unit normal n. */
static void tangent_basis(const double n[3], double u[3], double v[3])
{
    double a[3] = {1, 0, 0};
    if (fabs(n[0]) > 0.8) { a[0] = 0; a[1] = 1; }
    u[0] = a[1] * n[2] - a[2] * n[1];
    u[1] = a[2] * n[0] - a[0] * n[2];
    u[2] = a[0] * n[1] - a[1] * n[0];
    double l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    u[0] /= l; u[1] /= l; u[2] /= l;
    v[0] = n[1] * u[2] - n[2] * u[1];
    v[1] = n[2] * u[0] - n[0] * u[2];
    v[2] = n[0] * u[1] - n[1] * u[0];
}

static double color_term(const degree_job *j, size_t i, const uint32_t *row)
{
    const float *nf = j->normals ? j->normals + 3 * i : NULL;
    double n[3] = {nf ? nf[0] : 0, nf ? nf[1] : 0, nf ? nf[2] : 0};
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(nl > 0.5)) return 0.0; /* no plane: no tangent gradient */
    n[0] /= nl; n[1] /= nl; n[2] /= nl;
    double u[3], v[3];
    tangent_basis(n, u, v);
    double pc[3] = {0, 0, 0}, cc[3] = {0, 0, 0};
    size_t m = 0;
    int uniform = 1; /* all colours equal: exactly no gradient (the mean would leave rounding dust) */
    const uint8_t *c0 = j->rgb + 3 * i;
    for (size_t r = 0; r < j->k; r++) {
        if (row[r] == PNPR_INDEX_NONE) continue;
        const float *p = j->xyz + 3 * (size_t)row[r];
        const uint8_t *c = j->rgb + 3 * (size_t)row[r];
        for (int a = 0; a < 3; a++) { pc[a] += p[a]; cc[a] += c[a] / 255.0; }
        uniform &= c[0] == c0[0] && c[1] == c0[1] && c[2] == c0[2];
        m++;
    }
    if (m < 3 || uniform) return 0.0;
    for (int a = 0; a < 3; a++) { pc[a] /= (double)m; cc[a] /= (double)m; }
    double s_uu = 0, s_uv = 0, s_vv = 0, b_u[3] = {0, 0, 0}, b_v[3] = {0, 0, 0}, rsum = 0;
    const float *pi = j->xyz + 3 * i;
    for (size_t r = 0; r < j->k; r++) {
        if (row[r] == PNPR_INDEX_NONE) continue;
        const float *p = j->xyz + 3 * (size_t)row[r];
        const uint8_t *c = j->rgb + 3 * (size_t)row[r];
        double d[3] = {p[0] - pc[0], p[1] - pc[1], p[2] - pc[2]};
        double du = d[0] * u[0] + d[1] * u[1] + d[2] * u[2], dv = d[0] * v[0] + d[1] * v[1] + d[2] * v[2];
        s_uu += du * du; s_uv += du * dv; s_vv += dv * dv;
        for (int ch = 0; ch < 3; ch++) {
            double dc = c[ch] / 255.0 - cc[ch];
            b_u[ch] += du * dc;
            b_v[ch] += dv * dc;
        }
        double e[3] = {p[0] - pi[0], p[1] - pi[1], p[2] - pi[2]};
        rsum += e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    }
    double det = s_uu * s_vv - s_uv * s_uv;
    /* a (nearly) collinear neighbourhood has no 2D gradient */
    if (!(det > 1e-12 * (s_uu + s_vv) * (s_uu + s_vv))) return 0.0;
    double g2 = 0;
    for (int ch = 0; ch < 3; ch++) {
        double gu = (s_vv * b_u[ch] - s_uv * b_v[ch]) / det;
        double gv = (s_uu * b_v[ch] - s_uv * b_u[ch]) / det;
        g2 += gu * gu + gv * gv;
    }
    double r_rms = sqrt(rsum / (double)(m > 1 ? m - 1 : 1)); /* the point itself adds 0 */
    return clamp01(sqrt(g2) * r_rms / COLOR_SCALE);
}

/* Mean of values[] over a kNN row (skipping `skip`, e.g. the point itself); 0 neighbours: NaN. */
static double row_mean(const uint32_t *row, size_t k, const float *values, size_t skip)
{
    double sum = 0;
    size_t m = 0;
    for (size_t r = 0; r < k; r++) {
        if (row[r] == PNPR_INDEX_NONE || row[r] == skip) continue;
        sum += values[row[r]];
        m++;
    }
    return m ? sum / (double)m : NAN;
}

/* Box filter of the fit error over each neighbourhood (the point included). */
static void smooth_range(void *ctx, size_t begin, size_t end)
{
    const degree_job *j = ctx;
    for (size_t i = begin; i < end; i++) {
        double mean = row_mean(j->knn + i * j->k, j->k, j->raw_err, PNPR_INDEX_NONE);
        j->smooth_out[i] = mean == mean ? (float)mean : j->raw_err[i];
    }
}

static void degree_range(void *ctx, size_t begin, size_t end)
{
    const degree_job *j = ctx;
    for (size_t i = begin; i < end; i++) {
        const uint32_t *row = j->knn + i * j->k;
        double mean = row_mean(row, j->k, j->err, i);
        double g = mean == mean ? clamp01((j->err[i] - mean) / GEO_SCALE) : 0.0;
        double c = (j->rgb && j->wc > 0) ? color_term(j, i, row) : 0.0;
        j->degree[i] = (float)clamp01(j->wg * g + j->wc * c);
    }
}

pnpr_status pnpr_feature_degree(const float *xyz, const uint8_t *rgb, const float *normals,
                                const float *fit_error, size_t count, const uint32_t *knn,
                                size_t k, float weight_geometry, float weight_color, int threads,
                                float *r_degree)
{
    if (count && (!xyz || !fit_error || !knn || !r_degree || k == 0)) return PNPR_ERR_INVALID_ARGUMENT;
    double wg = weight_geometry, wc = weight_color;
    if (!(wg >= 0) || !(wc >= 0) || !isfinite(wg) || !isfinite(wc)) return PNPR_ERR_INVALID_ARGUMENT;
    if (wg == 0 && wc == 0) { /* both 0: the defaults (options.h) */
        const pnpr_features_options d = pnpr_features_defaults();
        wg = d.weight_geometry;
        wc = d.weight_color;
    }
    if (!rgb) wc = 0;
    if (wg + wc == 0) wg = 1; /* colour-only weights on a colourless cloud: geometry decides */
    double s = wg + wc;
    float *smooth = malloc((count ? count : 1) * sizeof *smooth);
    if (!smooth) return PNPR_ERR_OUT_OF_MEMORY;
    degree_job j = {xyz, normals, smooth, fit_error, smooth, rgb, knn, k, wg / s, wc / s, r_degree};
    pnpr_status st = pnpr_parallel_for(count, 2048, threads, smooth_range, &j, NULL, "feature degree");
    if (st == PNPR_OK) st = pnpr_parallel_for(count, 2048, threads, degree_range, &j, NULL, "feature degree");
    free(smooth);
    return st;
}
