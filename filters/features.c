/* The feature pipeline on a pnpr_cloud: kd-tree -> kNN -> normals (+ fit error) -> orientation
 * -> feature degree -> classification -> dithering, with per-stage timings and run counters. */
#include <pointnpr/features.h>
#include <pointnpr/knn.h>

#include "../core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *pnpr_stage_name(pnpr_stage stage)
{
    static const char *names[PNPR_STAGE_COUNT_] = {"kd-tree", "knn", "normals", "orient",
                                                   "feature degree", "classify", "dither"};
    return (unsigned)stage < PNPR_STAGE_COUNT_ ? names[stage] : "unknown";
}

typedef struct run {
    pnpr_features_stats *stats;
    const pnpr_progress *progress;
    double t0;
    pnpr_stage stage;
} run;

/* Starts a stage: progress at its beginning, returns non-zero when cancelled. */
static int stage_begin(run *r, pnpr_stage s)
{
    r->stage = s;
    r->t0 = pnpr_now();
    return pnpr_progress_report(r->progress, pnpr_stage_name(s), 0.0);
}

static pnpr_status stage_end(run *r, pnpr_status st)
{
    r->stats->seconds[r->stage] += pnpr_now() - r->t0;
    r->stats->runs[r->stage]++;
    if (st == PNPR_OK && pnpr_progress_report(r->progress, pnpr_stage_name(r->stage), 1.0))
        return PNPR_ERR_CANCELLED;
    return st;
}

static pnpr_status add_float(pnpr_cloud *c, const char *name, float **r)
{
    pnpr_property *p;
    pnpr_status st = pnpr_cloud_add_property(c, name, PNPR_TYPE_FLOAT32, &p);
    *r = st == PNPR_OK ? p->data : NULL;
    return st;
}

pnpr_status pnpr_compute_features(pnpr_cloud *cloud, const pnpr_features_options *opts,
                                  pnpr_features_stats *r_stats)
{
    static const pnpr_features_options defaults;
    pnpr_features_stats local;
    if (!r_stats) r_stats = &local;
    memset(r_stats, 0, sizeof *r_stats);
    if (!cloud || (cloud->count && !cloud->xyz)) return PNPR_ERR_INVALID_ARGUMENT;
    if (!opts) opts = &defaults;
    if (cloud->count >= PNPR_INDEX_NONE) return PNPR_ERR_UNSUPPORTED;
    if (!isfinite(opts->threshold) || opts->threshold < 0 || opts->threshold > 1) return PNPR_ERR_INVALID_ARGUMENT;
    if (opts->has_viewpoint && !(isfinite(opts->viewpoint[0]) && isfinite(opts->viewpoint[1]) && isfinite(opts->viewpoint[2])))
        return PNPR_ERR_INVALID_ARGUMENT;
    const size_t n = cloud->count;
    size_t k = opts->k ? opts->k : 16;
    if (k > 1024) return PNPR_ERR_INVALID_ARGUMENT; /* documented limit: huge k is refused, not slow */
    float min_conf = opts->direction_confidence > 0 ? opts->direction_confidence : 0.6f;
    run r = {r_stats, &opts->progress, 0, 0};

    /* outputs (allocated first: a cloud that cannot hold them fails before the work) */
    pnpr_status st;
    float *degree, *conf, *dx, *dy, *dz;
    pnpr_property *cls_prop;
    if ((st = add_float(cloud, "feature_degree", &degree)) != PNPR_OK ||
        (st = pnpr_cloud_add_property(cloud, "feature_class", PNPR_TYPE_UINT8, &cls_prop)) != PNPR_OK ||
        (st = add_float(cloud, "feature_confidence", &conf)) != PNPR_OK ||
        (st = add_float(cloud, "feature_dir_x", &dx)) != PNPR_OK ||
        (st = add_float(cloud, "feature_dir_y", &dy)) != PNPR_OK ||
        (st = add_float(cloud, "feature_dir_z", &dz)) != PNPR_OK)
        return st;
    /* add_property may move the props array: look the arrays up again */
    degree = pnpr_cloud_find_property(cloud, "feature_degree")->data;
    uint8_t *cls = pnpr_cloud_find_property(cloud, "feature_class")->data;
    conf = pnpr_cloud_find_property(cloud, "feature_confidence")->data;
    dx = pnpr_cloud_find_property(cloud, "feature_dir_x")->data;
    dy = pnpr_cloud_find_property(cloud, "feature_dir_y")->data;
    dz = pnpr_cloud_find_property(cloud, "feature_dir_z")->data;
    (void)cls_prop;
    int keep_normals = cloud->normal && !opts->recompute_normals;
    if ((st = pnpr_cloud_alloc_normals(cloud)) != PNPR_OK) return st;

    size_t valid = 0;
    for (size_t i = 0; i < n; i++) {
        const float *p = cloud->xyz + 3 * i;
        valid += isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
    }
    r_stats->valid_points = valid;
    if (k > valid) k = valid;
    r_stats->k_used = (uint32_t)k;
    if (valid < 3 || k < 3) {
        /* too few points for any plane: defined empty result */
        if (!keep_normals) memset(cloud->normal, 0, 3 * n * sizeof(float));
        r_stats->threshold_used = opts->threshold;
        return PNPR_OK;
    }

    pnpr_kdtree *tree = NULL;
    uint32_t *knn = NULL;
    float *fit = NULL, *normals_tmp = NULL, *dir = NULL;

    if (stage_begin(&r, PNPR_STAGE_KDTREE)) return PNPR_ERR_CANCELLED;
    st = stage_end(&r, pnpr_kdtree_build(cloud->xyz, n, 0, &tree));
    if (st != PNPR_OK) goto done;

    knn = malloc(n * k * sizeof *knn);
    if (!knn) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    if (stage_begin(&r, PNPR_STAGE_KNN)) { st = PNPR_ERR_CANCELLED; goto done; }
    pnpr_knn_options ko = {opts->threads, opts->progress};
    st = stage_end(&r, pnpr_knn_self(tree, n, k, &ko, knn, NULL));
    pnpr_kdtree_free(tree);
    tree = NULL;
    if (st != PNPR_OK) goto done;

    /* PCA always runs: its fit error drives the feature degree even when normals are kept */
    fit = malloc(n * sizeof *fit);
    normals_tmp = keep_normals ? malloc(3 * n * sizeof *normals_tmp) : NULL;
    if (!fit || (keep_normals && !normals_tmp)) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    if (stage_begin(&r, PNPR_STAGE_NORMALS)) { st = PNPR_ERR_CANCELLED; goto done; }
    st = stage_end(&r, pnpr_estimate_normals(cloud->xyz, n, knn, k, opts->threads,
                                             keep_normals ? normals_tmp : cloud->normal, fit));
    free(normals_tmp);
    normals_tmp = NULL;
    if (st != PNPR_OK) goto done;

    if (!keep_normals) {
        if (stage_begin(&r, PNPR_STAGE_ORIENT)) { st = PNPR_ERR_CANCELLED; goto done; }
        double vp[3];
        for (int a = 0; a < 3; a++) vp[a] = opts->viewpoint[a] - cloud->origin[a];
        st = stage_end(&r, pnpr_orient_normals(cloud->xyz, n, knn, k, opts->has_viewpoint ? vp : NULL,
                                               cloud->normal));
        if (st != PNPR_OK) goto done;
    }

    if (stage_begin(&r, PNPR_STAGE_FEATURE_DEGREE)) { st = PNPR_ERR_CANCELLED; goto done; }
    st = stage_end(&r, pnpr_feature_degree(cloud->xyz, cloud->rgb, cloud->normal, fit, n, knn, k,
                                           opts->weight_geometry, opts->weight_color, opts->threads,
                                           degree));
    free(fit);
    fit = NULL;
    if (st != PNPR_OK) goto done;

    float threshold = opts->threshold > 0 ? opts->threshold : pnpr_auto_threshold(degree, n);
    r_stats->threshold_used = threshold;
    dir = malloc(3 * n * sizeof *dir);
    if (!dir) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    if (stage_begin(&r, PNPR_STAGE_CLASSIFY)) { st = PNPR_ERR_CANCELLED; goto done; }
    st = stage_end(&r, pnpr_classify_features(cloud->xyz, degree, n, 2 * k, threshold, min_conf,
                                              opts->threads, cls, conf, dir));
    if (st != PNPR_OK) goto done;
    for (size_t i = 0; i < n; i++) {
        dx[i] = dir[3 * i]; dy[i] = dir[3 * i + 1]; dz[i] = dir[3 * i + 2];
        r_stats->feature_points += cls[i] != PNPR_CLASS_NONE;
        r_stats->directional_points += cls[i] == PNPR_CLASS_DIRECTIONAL;
    }
    free(dir);
    dir = NULL;

    if (stage_begin(&r, PNPR_STAGE_DITHER)) { st = PNPR_ERR_CANCELLED; goto done; }
    st = stage_end(&r, pnpr_dither(cloud->xyz, cloud->rgb, cloud->normal, NULL, n, knn, k,
                                   opts->dither_scale, cls, &r_stats->dither_points));
done:
    pnpr_kdtree_free(tree);
    free(knn);
    free(fit);
    free(normals_tmp);
    free(dir);
    return st;
}
