/* Stroke-based splatting's preprocessing (Lopes et al. section 3.2; include/pointnpr/brush.h):
 *  1. splat size r + eps: r the mean distance to the k nearest neighbours, eps their standard
 *     deviation (or the user's eps);
 *  2. colour clusters by region growing (pnpr_segment_rgbgrow, Zhan et al., the clustering the
 *     paper uses); colourless clouds: connected components (the paper notes its clustering fails
 *     there, section 5.6);
 *  3. normals fitted to the points of the same cluster within normal_radius x r (the paper: 3r),
 *     at most the PNPR_BRUSH_NORMAL_NEIGHBOURS nearest (bounded work where a cluster is dense);
 *     where the cluster has fewer than 3 points there, to all points within the radius, else to
 *     the nearest. A normal's sign is not fixed here: the renderer turns it towards the camera.
 * Steps 1 and 3 query the tree point by point in parallel: no kNN lists are kept, so memory stays
 * a few bytes per point beyond the outputs. */
#include <pointnpr/brush.h>
#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <pointnpr/options.h>

#include "../core/internal.h"
#include "../core/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct prep_job {
    const pnpr_kdtree *tree;
    const float *xyz;
    const uint32_t *cluster;
    float *size, *normal;
    size_t k;
    float eps, normal_radius;
} prep_job;

/* Step 1 over points [begin, end): size = mean + (std or eps) of the distances to the k nearest
 * other points (the query's first hit is the point itself, or a duplicate of it). */
static void sizes_range(void *ctx, size_t begin, size_t end)
{
    const prep_job *j = ctx;
    uint32_t idx[PNPR_BRUSH_K_MAX + 1];
    float d2[PNPR_BRUSH_K_MAX + 1];
    for (size_t i = begin; i < end; i++) {
        const float *p = j->xyz + 3 * i;
        j->size[i] = 0.0f;
        if (!pnpr_finite3f(p)) continue;
        size_t found = pnpr_kdtree_knn(j->tree, p, j->k + 1, idx, d2);
        double s = 0, s2 = 0;
        size_t m = 0;
        for (size_t t = 0; t < found; t++) {
            if (idx[t] == (uint32_t)i) continue;
            double d = sqrt((double)d2[t]);
            s += d; s2 += d * d;
            if (++m == j->k) break;
        }
        if (m == 0 || !(s > 0)) continue;
        double mean = s / (double)m, var = s2 / (double)m - mean * mean;
        double eps = j->eps > 0 ? (double)j->eps : sqrt(var > 0 ? var : 0);
        j->size[i] = (float)(mean + eps);
    }
}

/* Step 3 over points [begin, end): the plane fit of the point's cluster mates within
 * normal_radius x r among its nearest (the points' own kNN normal code, one row). */
static void normals_range(void *ctx, size_t begin, size_t end)
{
    const prep_job *j = ctx;
    enum { K = PNPR_BRUSH_NORMAL_NEIGHBOURS };
    uint32_t idx[K], row[K];
    float d2[K];
    for (size_t i = begin; i < end; i++) {
        const float *p = j->xyz + 3 * i;
        float *n = j->normal + 3 * i;
        n[0] = n[1] = n[2] = 0.0f;
        if (!pnpr_finite3f(p)) continue;
        /* r: the size without eps is not kept; the size itself bounds it from above, which the
         * paper's 3r rule does not mind (it asks for a neighbourhood, not an exact radius) */
        double lim = (double)j->normal_radius * (double)j->size[i];
        size_t found = pnpr_kdtree_knn(j->tree, p, K, idx, d2), m = 0;
        for (size_t t = 0; t < found; t++)
            if (j->cluster[idx[t]] == j->cluster[i] && (double)d2[t] <= lim * lim) row[m++] = idx[t];
        /* a cluster of fewer than 3 points there (an isolated speck of colour): the fit over all
         * points within the radius, then over the nearest, so that no stroke is left without a
         * plane (it would face the camera and stick out of silhouettes) */
        for (int pass = 0; pass < 2 && m < 3; pass++) {
            m = 0;
            for (size_t t = 0; t < found; t++)
                if (pass == 1 || (double)d2[t] <= lim * lim) row[m++] = idx[t];
        }
        for (size_t t = m; t < K; t++) row[t] = PNPR_INDEX_NONE;
        /* the library's kNN plane fit on this one row: it fits "point 0" from row 0, and the
         * row's indices address the whole array (one thread: runs here, no thread started) */
        float nn[3];
        if (pnpr_estimate_normals(j->xyz, 1, row, K, 1, nn, NULL) == PNPR_OK) memcpy(n, nn, sizeof nn);
    }
}

/* Step 2: the clusters into `labels` (count entries). */
static pnpr_status clusters(const pnpr_cloud *c, const pnpr_brush_options *o, uint32_t *labels, size_t *r_count)
{
    pnpr_segment_info info;
    pnpr_status st;
    if (c->rgb) {
        pnpr_rgbgrow_options ro = o->cluster;
        ro.threads = o->threads;
        ro.progress = o->progress;
        st = pnpr_segment_rgbgrow(c->xyz, c->rgb, c->count, &ro, labels, &info);
    } else {
        pnpr_components_options co = {0};
        co.threads = o->threads;
        co.progress = o->progress;
        st = pnpr_segment_components(c->xyz, c->count, &co, labels, &info);
    }
    *r_count = st == PNPR_OK ? info.segment_count - (info.invalid_segment != PNPR_LABEL_NONE) : 0;
    return st;
}

static pnpr_status check_options(const pnpr_brush_options *opts, pnpr_brush_options *o, pnpr_error *err)
{
    *o = opts ? *opts : (pnpr_brush_options){0};
    size_t n;
    const pnpr_option_desc *t = pnpr_brush_option_table(&n);
    pnpr_status st = pnpr_option_check(t, n, o, err);
    if (st != PNPR_OK) return st;
    pnpr_option_fill_defaults(t, n, o);
    return PNPR_OK;
}

pnpr_status pnpr_brush_prepare(pnpr_cloud *cloud, const pnpr_brush_options *opts, pnpr_brush_stats *r_stats,
                               pnpr_error *err)
{
    double t0 = pnpr_now();
    if (r_stats) memset(r_stats, 0, sizeof *r_stats);
    if (!cloud || (cloud->count && !cloud->xyz))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "brush: no cloud or no coordinates");
    if (cloud->count >= 0x7FFFFFFFu)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "brush: too many points (%zu)", cloud->count);
    pnpr_brush_options o;
    pnpr_status st = check_options(opts, &o, err);
    if (st != PNPR_OK) return st;
    size_t n = cloud->count, nclusters = 0;
    int fit = !cloud->normal || o.recompute_normals;
    float *size = malloc((n ? n : 1) * sizeof *size), *normal = fit ? malloc((n ? n : 1) * 3 * sizeof *normal) : NULL;
    uint32_t *label = malloc((n ? n : 1) * sizeof *label);
    pnpr_kdtree *tree = NULL;
    if (!size || !label || (fit && !normal)) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    if ((st = pnpr_kdtree_build_threads(cloud->xyz, n, 0, o.threads, &tree)) != PNPR_OK) goto done;
    prep_job j = {tree, cloud->xyz, label, size, normal, o.k, o.eps, o.normal_radius};
    if ((st = pnpr_parallel_for(n, 4096, o.threads, sizes_range, &j, &o.progress, "knn")) != PNPR_OK) goto done;
    if (n && (st = clusters(cloud, &o, label, &nclusters)) != PNPR_OK) goto done;
    if (fit && (st = pnpr_parallel_for(n, 2048, o.threads, normals_range, &j, &o.progress, "normals")) != PNPR_OK)
        goto done;
    if ((st = pnpr_cloud_add_property(cloud, PNPR_PROP_BRUSH_SIZE, PNPR_TYPE_FLOAT32, NULL)) != PNPR_OK) goto done;
    if ((st = pnpr_cloud_add_property(cloud, PNPR_PROP_BRUSH_CLUSTER, PNPR_TYPE_UINT32, NULL)) != PNPR_OK) goto done;
    /* found after both are added: adding one may move the property array */
    pnpr_property *ps = pnpr_cloud_find_property(cloud, PNPR_PROP_BRUSH_SIZE);
    pnpr_property *pc = pnpr_cloud_find_property(cloud, PNPR_PROP_BRUSH_CLUSTER);
    if (n) {
        memcpy(ps->data, size, n * sizeof *size);
        memcpy(pc->data, label, n * sizeof *label);
    }
    if (fit && n) {
        if ((st = pnpr_cloud_alloc_normals(cloud)) != PNPR_OK) goto done;
        memcpy(cloud->normal, normal, n * 3 * sizeof *normal);
    }
    if (r_stats) {
        double s = 0;
        size_t m = 0;
        for (size_t i = 0; i < n; i++)
            if (size[i] > 0) { s += size[i]; m++; }
        r_stats->clusters = nclusters;
        r_stats->mean_size = m ? s / (double)m : 0;
        r_stats->normals_computed = fit && n;
    }
done:
    pnpr_kdtree_free(tree);
    free(size); free(normal); free(label);
    if (r_stats) r_stats->seconds = pnpr_now() - t0;
    if (st != PNPR_OK && err && !err->message[0]) pnpr_error_set(err, st, "brush: %s", pnpr_status_string(st));
    return st;
}

int pnpr_brush_cloud_ready(const pnpr_cloud *cloud)
{
    return cloud && cloud->normal && pnpr_cloud_find_property(cloud, PNPR_PROP_BRUSH_SIZE) &&
           pnpr_cloud_find_property(cloud, PNPR_PROP_BRUSH_CLUSTER);
}

/* ---- per-cluster shapes --------------------------------------------------------------------- */

typedef struct label_index { uint32_t label, i; } label_index;

static int cmp_label_index(const void *a, const void *b)
{
    const label_index *x = a, *y = b;
    if (x->label != y->label) return x->label < y->label ? -1 : 1;
    return x->i < y->i ? -1 : x->i > y->i;
}

/* The stretch of the points li[0..m) (one cluster): sqrt(l1 / l2) clamped. */
static float cluster_stretch(const float *xyz, const label_index *li, size_t m)
{
    double c[3] = {0, 0, 0}, cov[3][3] = {{0}};
    for (size_t t = 0; t < m; t++)
        for (int a = 0; a < 3; a++) c[a] += xyz[3 * (size_t)li[t].i + a];
    for (int a = 0; a < 3; a++) c[a] /= (double)m;
    for (size_t t = 0; t < m; t++) {
        const float *p = xyz + 3 * (size_t)li[t].i;
        double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) cov[a][b] += d[a] * d[b];
    }
    double w[3], v[3][3];
    pnpr_eigen_sym3(cov, w, v);
    if (!(w[1] > 0)) return w[2] > 0 ? PNPR_BRUSH_STRETCH_MAX : 1.0f;
    double s = sqrt(w[2] / w[1]);
    return s > PNPR_BRUSH_STRETCH_MAX ? PNPR_BRUSH_STRETCH_MAX : (float)s;
}

pnpr_status pnpr_brush_cluster_shapes(const float *xyz, const uint32_t *cluster, size_t count, uint32_t small,
                                      float *r_stretch, uint8_t *r_layers)
{
    if (!count) return PNPR_OK;
    if (!xyz || !cluster || !r_stretch || !r_layers) return PNPR_ERR_INVALID_ARGUMENT;
    label_index *li = malloc(count * sizeof *li);
    if (!li) return PNPR_ERR_OUT_OF_MEMORY;
    size_t m = 0;
    for (size_t i = 0; i < count; i++) {
        r_stretch[i] = 1.0f;
        r_layers[i] = 1;
        if (pnpr_finite3f(xyz + 3 * i)) li[m++] = (label_index){cluster[i], (uint32_t)i};
    }
    qsort(li, m, sizeof *li, cmp_label_index);
    for (size_t a = 0, b; a < m; a = b) {
        for (b = a + 1; b < m && li[b].label == li[a].label; b++) {}
        float s = cluster_stretch(xyz, li + a, b - a);
        uint8_t layers = (b - a) < small ? 2 : 1;
        for (size_t t = a; t < b; t++) { r_stretch[li[t].i] = s; r_layers[li[t].i] = layers; }
    }
    free(li);
    return PNPR_OK;
}
