/* The feature pipeline on a pnpr_cloud: kd-tree -> kNN -> normals (+ fit error) -> orientation
 * -> feature degree -> classification -> dithering, with per-stage timings and run counters. */
#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <pointnpr/options.h>

#include "../core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "../core/vec3.h"

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

/* Forward permutation in place by following cycles with perm[] itself as the visited marker
 * (it is restored afterwards): slow, for the out-of-memory path only. */
static void restore_in_place(void *data, size_t size, size_t n, uint32_t *perm)
{
    if (!data) return;
    char *a = data, carry[16], tmp[16];
    const uint32_t DONE = 0x80000000u; /* counts are < 2^31 on this path's users */
    for (size_t s = 0; s < n; s++) {
        if (perm[s] & DONE) continue;
        memcpy(carry, a + s * size, size);
        size_t p = s;
        do {
            size_t q = perm[p] & ~DONE;
            perm[p] |= DONE;
            memcpy(tmp, a + q * size, size);
            memcpy(a + q * size, carry, size);
            memcpy(carry, tmp, size);
            p = q;
        } while (p != s);
    }
    for (size_t s = 0; s < n; s++) perm[s] &= ~DONE;
}

pnpr_status pnpr_features_check_options(const pnpr_features_options *o, pnpr_error *err)
{
    if (!o) return PNPR_OK;
    if (o->want & ~(uint32_t)(PNPR_WANT_ALL | PNPR_WANT_NORMALS_ANY))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "features: want 0x%x has unknown bits", (unsigned)o->want);
    size_t n;
    const pnpr_option_desc *table = pnpr_features_option_table(&n);
    pnpr_status st = pnpr_option_check(table, n, o, err);
    if (st != PNPR_OK) return st;
    if (o->has_viewpoint && !(isfinite(o->viewpoint[0]) && isfinite(o->viewpoint[1]) && isfinite(o->viewpoint[2])))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "features: the viewpoint is not finite");
    return PNPR_OK;
}

/* One run of the pipeline: what the stages share. */
typedef struct feat_run {
    pnpr_cloud *cloud;
    const pnpr_features_options *opts;
    run r;
    size_t n, m, k;              /* points, valid points (tree positions first), neighbours */
    int need_dither, need_classify, need_degree, need_oriented, keep_normals;
    float *out[5];               /* degree, confidence, dir x, y, z (cloud properties) */
    uint8_t *cls;                /* feature_class (cloud property) */
    float *spacing;              /* point_spacing (cloud property) or NULL */
    uint32_t spacing_k;          /* its neighbour: the renderer's default spacing_k */
    float *normals;              /* the cloud's, or own_normals */
    float *own_normals, *fit, *xyz;
    pnpr_kdtree *tree;
    uint32_t *knn, *perm, *tree_index;
    char *scratch;
    int permuted;
} feat_run;

static const char *const feat_names[5] = {PNPR_PROP_FEATURE_DEGREE, PNPR_PROP_FEATURE_CONFIDENCE, PNPR_PROP_FEATURE_DIR_X, PNPR_PROP_FEATURE_DIR_Y,
                                          PNPR_PROP_FEATURE_DIR_Z};

/* An older point_spacing removed (stale after this run); none there is fine. */
static void drop_spacing(pnpr_cloud *cloud)
{
    pnpr_status st = pnpr_cloud_remove_property(cloud, PNPR_PROP_POINT_SPACING);
    (void)st; /* PNPR_ERR_NOT_FOUND: there was none */
}

/* The stages the wanted outputs need (docs/features.md, "Computing only what is needed"), and
 * the output properties, allocated first: a cloud that cannot hold them fails before the work. */
static pnpr_status features_outputs(feat_run *f)
{
    pnpr_cloud *cloud = f->cloud;
    const uint32_t want = f->opts->want ? f->opts->want : PNPR_WANT_ALL;
    f->need_dither = (want & PNPR_WANT_DITHER) != 0;
    f->need_classify = f->need_dither || (want & PNPR_WANT_CLASSES);
    f->need_degree = f->need_classify || (want & PNPR_WANT_DEGREE);
    /* the tone's lighting is two-sided (tone.h): dithering needs no oriented normals */
    f->need_oriented = (want & PNPR_WANT_NORMALS) != 0;
    pnpr_status st;
    int nout = f->need_classify ? 5 : (f->need_degree ? 1 : 0);
    for (int i = 0; i < nout; i++)
        if ((st = pnpr_cloud_add_property(cloud, feat_names[i], PNPR_TYPE_FLOAT32, NULL)) != PNPR_OK) return st;
    if (f->need_classify && (st = pnpr_cloud_add_property(cloud, PNPR_PROP_FEATURE_CLASS, PNPR_TYPE_UINT8, NULL)) != PNPR_OK)
        return st;
    /* the renderer's disk radii come from these neighbour lists when they reach its spacing
     * neighbour (an older point_spacing would be stale: replaced, or removed below) */
    f->spacing_k = pnpr_upload_defaults().spacing_k;
    if (f->opts->k > f->spacing_k &&
        (st = pnpr_cloud_add_property(cloud, PNPR_PROP_POINT_SPACING, PNPR_TYPE_FLOAT32, NULL)) != PNPR_OK)
        return st;
    for (int i = 0; i < nout; i++) f->out[i] = pnpr_cloud_find_property(cloud, feat_names[i])->data; /* after all adds */
    f->cls = f->need_classify ? pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_CLASS)->data : NULL;
    if (f->opts->k > f->spacing_k) f->spacing = pnpr_cloud_find_property(cloud, PNPR_PROP_POINT_SPACING)->data;
    else drop_spacing(cloud);
    /* input normals are kept unless asked otherwise, or unless most of them are missing (zero or
     * non-finite: a layer that carries a normal field without data) */
    f->keep_normals = cloud->normal && !f->opts->recompute_normals;
    if (f->keep_normals) {
        size_t have = 0;
        for (size_t i = 0; i < f->n; i++) {
            const float *v = cloud->normal + 3 * i;
            have += isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]) && (v[0] != 0 || v[1] != 0 || v[2] != 0);
        }
        if (2 * have < f->n) f->keep_normals = 0;
    }
    /* unoriented normals are not handed out: when nobody wants normals, they live in a scratch
     * array (the colour term needs the tangent plane) and the cloud gets none */
    if (f->keep_normals || f->need_oriented || cloud->normal || (want & PNPR_WANT_NORMALS_ANY)) {
        if ((st = pnpr_cloud_alloc_normals(cloud)) != PNPR_OK) return st;
        f->normals = cloud->normal;
    }
    return PNPR_OK;
}

/* The kd-tree and the neighbour lists; then the cloud's coordinates, colours and kept normals
 * take the tree order (the tree's copy is released: 12 bytes/point less for the rest of the run),
 * the points left out (NaN/Inf) follow in input order. */
static pnpr_status features_tree_order(feat_run *f)
{
    pnpr_cloud *cloud = f->cloud;
    const size_t n = f->n, m = f->m, k = f->k;
    if (stage_begin(&f->r, PNPR_STAGE_KDTREE)) return PNPR_ERR_CANCELLED;
    pnpr_status st = stage_end(&f->r, pnpr_kdtree_build_threads(cloud->xyz, n, 0, f->opts->threads, &f->tree));
    if (st != PNPR_OK) return st;
    if (!(f->knn = malloc(m * k * sizeof *f->knn))) return PNPR_ERR_OUT_OF_MEMORY;
    if (stage_begin(&f->r, PNPR_STAGE_KNN)) return PNPR_ERR_CANCELLED;
    pnpr_knn_options ko = {f->opts->threads, f->opts->progress, 1};
    if ((st = stage_end(&f->r, pnpr_knn_self(f->tree, m, k, &ko, f->knn, NULL))) != PNPR_OK) return st;
    st = pnpr_kdtree_detach(f->tree, &f->xyz, &f->tree_index);
    f->tree = NULL;
    if (st != PNPR_OK) return st;
    if (f->spacing) pnpr_spacing_from_lists(f->xyz, m, f->knn, k, f->spacing_k, f->spacing);

    /* full permutation: tree positions first, then the invalid points in input order */
    f->perm = malloc(n * sizeof *f->perm);
    /* scratch for the permutations, sized for what moves now (colours, kept normals); it grows to
     * a normal per point for the way back, once the neighbour lists are gone */
    f->scratch = malloc(n * (f->keep_normals ? 3 * sizeof(float) : 3));
    if (!f->perm || !f->scratch) return PNPR_ERR_OUT_OF_MEMORY;
    memcpy(f->perm, f->tree_index, m * sizeof *f->perm);
    pnpr_free(f->tree_index);
    f->tree_index = NULL;
    if (m < n) {
        size_t q = m;
        for (size_t i = 0; i < n; i++)
            if (!pnpr_finite3f(cloud->xyz + 3 * i)) f->perm[q++] = (uint32_t)i;
        float *bad = malloc((n - m) * 3 * sizeof(float));
        if (!bad) return PNPR_ERR_OUT_OF_MEMORY;
        for (q = m; q < n; q++) memcpy(bad + 3 * (q - m), cloud->xyz + 3 * (size_t)f->perm[q], 3 * sizeof(float));
        memcpy(cloud->xyz + 3 * m, bad, (n - m) * 3 * sizeof(float));
        free(bad);
    }
    memcpy(cloud->xyz, f->xyz, m * 3 * sizeof(float));
    pnpr_free(f->xyz);
    f->xyz = cloud->xyz;
    pnpr_permute(cloud->rgb, 3, n, f->perm, 0, f->scratch);
    if (f->keep_normals) pnpr_permute(cloud->normal, 3 * sizeof(float), n, f->perm, 0, f->scratch);
    f->permuted = 1;
    free(f->scratch);
    f->scratch = NULL;
    return PNPR_OK;
}

/* Normals (PCA always runs: its fit error drives the feature degree even when normals are kept),
 * the feature degree (only the tangent plane matters, so it runs before the orientation, and the
 * fit errors are gone before the orientation's queue is built), the orientation. */
static pnpr_status features_geometry(feat_run *f)
{
    const size_t m = f->m, k = f->k;
    const pnpr_features_options *o = f->opts;
    if (f->need_degree && !(f->fit = malloc(m * sizeof *f->fit))) return PNPR_ERR_OUT_OF_MEMORY;
    if (!f->normals && !(f->normals = f->own_normals = malloc(m * 3 * sizeof *f->normals))) return PNPR_ERR_OUT_OF_MEMORY;
    if (stage_begin(&f->r, PNPR_STAGE_NORMALS)) return PNPR_ERR_CANCELLED;
    pnpr_status st = stage_end(&f->r, pnpr_estimate_normals(f->xyz, m, f->knn, k, o->threads,
                                                            f->keep_normals ? NULL : f->normals, f->fit));
    if (st != PNPR_OK) return st;
    if (f->need_degree) {
        if (stage_begin(&f->r, PNPR_STAGE_FEATURE_DEGREE)) return PNPR_ERR_CANCELLED;
        st = stage_end(&f->r, pnpr_feature_degree(f->xyz, f->cloud->rgb, f->normals, f->fit, m, f->knn, k,
                                                  o->weight_geometry, o->weight_color, o->threads, f->out[0]));
        free(f->fit);
        f->fit = NULL;
        if (st != PNPR_OK) return st;
    }
    if (!f->keep_normals && f->need_oriented) {
        if (stage_begin(&f->r, PNPR_STAGE_ORIENT)) return PNPR_ERR_CANCELLED;
        double vp[3];
        for (int a = 0; a < 3; a++) vp[a] = o->viewpoint[a] - f->cloud->origin[a];
        st = stage_end(&f->r, pnpr_orient_normals(f->xyz, m, f->knn, k, o->has_viewpoint ? vp : NULL, f->normals));
    }
    return st;
}

/* The threshold, the classes and the dithering points. */
static pnpr_status features_classes(feat_run *f)
{
    const size_t m = f->m, k = f->k;
    const pnpr_features_options *o = f->opts;
    pnpr_features_stats *stats = f->r.stats;
    float min_conf = o->direction_confidence; /* filled from the options table */
    pnpr_status st = PNPR_OK;
    if (f->need_degree) stats->threshold_used = o->threshold > 0 ? o->threshold : pnpr_auto_threshold(f->out[0], m);
    if (f->need_classify) {
        if (stage_begin(&f->r, PNPR_STAGE_CLASSIFY)) return PNPR_ERR_CANCELLED;
        st = stage_end(&f->r, pnpr_classify_features(f->xyz, f->out[0], m, 2 * k, stats->threshold_used, min_conf,
                                                     o->threads, f->perm, f->cls, f->out[1], f->out[2], f->out[3],
                                                     f->out[4]));
        if (st != PNPR_OK) return st;
        for (size_t i = 0; i < m; i++) {
            stats->feature_points += f->cls[i] != PNPR_CLASS_NONE;
            stats->directional_points += f->cls[i] == PNPR_CLASS_DIRECTIONAL;
        }
    }
    if (f->need_dither) {
        if (stage_begin(&f->r, PNPR_STAGE_DITHER)) return PNPR_ERR_CANCELLED;
        float *tone = malloc((m ? m : 1) * sizeof *tone);
        st = tone ? pnpr_tone(f->cloud->rgb, f->normals, m, &o->tone, tone) : PNPR_ERR_OUT_OF_MEMORY;
        if (st == PNPR_OK)
            st = pnpr_dither(f->xyz, f->cloud->rgb, f->normals, tone, m, f->knn, k, o->dither_scale, f->cls,
                             &stats->dither_points);
        free(tone);
        st = stage_end(&f->r, st);
    }
    return st;
}

/* Back to input order (inputs always, outputs too: meaningful only on success) and the run's
 * memory released; returns st, or PNPR_ERR_OUT_OF_MEMORY when there was none for the way back. */
static pnpr_status features_finish(feat_run *f, pnpr_status st)
{
    pnpr_cloud *cloud = f->cloud;
    const size_t n = f->n;
    free(f->knn);
    free(f->fit);
    free(f->scratch);
    f->scratch = NULL;
    if (f->permuted && !(f->scratch = malloc(n * 3 * sizeof(float)))) {
        /* no memory for the way back: restore the inputs in place (slow but allocation-free) */
        st = PNPR_ERR_OUT_OF_MEMORY;
        restore_in_place(cloud->xyz, 3 * sizeof(float), n, f->perm);
        restore_in_place(cloud->rgb, 3, n, f->perm);
        restore_in_place(cloud->normal, 3 * sizeof(float), n, f->perm);
        f->permuted = 0;
    }
    if (f->permuted) {
        pnpr_permute(cloud->xyz, 3 * sizeof(float), n, f->perm, 1, f->scratch);
        pnpr_permute(cloud->rgb, 3, n, f->perm, 1, f->scratch);
        pnpr_permute(cloud->normal, 3 * sizeof(float), n, f->perm, 1, f->scratch);
        for (int i = 0; i < 5; i++) pnpr_permute(f->out[i], sizeof(float), n, f->perm, 1, f->scratch);
        pnpr_permute(f->spacing, sizeof(float), n, f->perm, 1, f->scratch);
        pnpr_permute(f->cls, 1, n, f->perm, 1, f->scratch);
    }
    pnpr_kdtree_free(f->tree);
    if (f->xyz != cloud->xyz) pnpr_free(f->xyz);
    pnpr_free(f->tree_index);
    free(f->perm);
    free(f->scratch);
    free(f->own_normals);
    return st;
}

/* The pipeline works in kd-tree order: the tree's reordered copy of the points is spatially
 * coherent, so the neighbour gathers of every stage hit the cache (on a 1M-point cloud in random
 * order this more than halves the time of the normal, orientation and feature-degree stages).
 * The cloud's own arrays (coordinates, colours, normals, outputs) are permuted into tree order and
 * back at the end through one scratch buffer, instead of keeping tree-order copies of them all. Points with
 * NaN/Inf coordinates sit after the valid ones and get zero outputs. */
pnpr_status pnpr_compute_features(pnpr_cloud *cloud, const pnpr_features_options *opts,
                                  pnpr_features_stats *r_stats)
{
    pnpr_features_options filled = opts ? *opts : pnpr_features_defaults();
    pnpr_features_stats local;
    if (!r_stats) r_stats = &local;
    memset(r_stats, 0, sizeof *r_stats);
    if (!cloud || (cloud->count && !cloud->xyz)) return PNPR_ERR_INVALID_ARGUMENT;
    if (cloud->count >= 0x80000000u) return PNPR_ERR_UNSUPPORTED; /* 2^31 points at most */
    pnpr_status st = pnpr_features_check_options(&filled, NULL);
    if (st != PNPR_OK) return st; /* huge k is refused, not slow */
    size_t table_count;
    const pnpr_option_desc *table = pnpr_features_option_table(&table_count);
    pnpr_option_fill_defaults(table, table_count, &filled); /* zeros -> the table's defaults */
    opts = &filled;
    feat_run f;
    memset(&f, 0, sizeof f);
    f.cloud = cloud;
    f.opts = opts;
    f.r = (run){r_stats, &opts->progress, 0, 0};
    f.n = cloud->count;
    if ((st = features_outputs(&f)) != PNPR_OK) return st;

    size_t valid = 0;
    for (size_t i = 0; i < f.n; i++) {
        const double *w = cloud->src_xyz ? cloud->src_xyz + 3 * i : NULL;
        int ok = pnpr_finite3f(cloud->xyz + 3 * i);
        valid += ok;
        r_stats->beyond_float += !ok && w && pnpr_finite3d(w);
    }
    r_stats->valid_points = f.m = valid;
    f.k = opts->k;
    if (f.k > valid) f.k = valid;
    r_stats->k_used = (uint32_t)f.k;
    if (f.spacing && f.k <= f.spacing_k) { /* too few points for the lists to reach it */
        drop_spacing(cloud);
        f.spacing = NULL;
    }
    if (valid < 3 || f.k < 3) {
        /* too few points for any plane: defined empty result */
        if (f.normals && !f.keep_normals) memset(f.normals, 0, 3 * f.n * sizeof(float));
        r_stats->threshold_used = opts->threshold;
        return PNPR_OK;
    }
    st = features_tree_order(&f);
    if (st == PNPR_OK) st = features_geometry(&f);
    if (st == PNPR_OK) st = features_classes(&f);
    return features_finish(&f, st);
}
