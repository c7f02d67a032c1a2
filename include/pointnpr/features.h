/* pointnpr — features.h: the PointWorks feature analysis of a point cloud (Xu, Gossett & Chen,
 * "Abstraction and Depiction of Sparsely Scanned Outdoor Environments", sections 3-4.2).
 *
 * Stages (each a function below, each one .c file in filters/):
 *   knn            k nearest neighbours of every point (kd-tree)
 *   normals        PCA plane fit per neighbourhood -> unit normal + plane-fit error
 *   orient         consistent normal orientation (viewpoint, else propagation)
 *   feature degree edge filter over the fit error (its variation) + colour gradient, in [0,1]
 *   classify       feature points by threshold; directional / non-directional by a 3D line fit
 *                  over neighbouring feature points (confidence + direction)
 *   dither         dithering points: non-feature points chosen by Ostromoukhov's variable-
 *                  coefficient error diffusion along the kd-tree's space-filling order
 * docs/features.md documents every choice the paper leaves open.
 *
 * Arrays are caller-owned: per-point outputs have `count` entries (3*count for vectors). */
#ifndef POINTNPR_FEATURES_H
#define POINTNPR_FEATURES_H

#include "cloud.h"
#include "tone.h"

#ifdef __cplusplus
extern "C" {
#endif

/* feature_class values (as written to PLY) */
enum {
    PNPR_CLASS_NONE = 0,
    PNPR_CLASS_NONDIRECTIONAL = 1,
    PNPR_CLASS_DIRECTIONAL = 2,
    PNPR_CLASS_DITHER = 3
};

/* Outputs of pnpr_compute_features; options.want = a combination, 0 = all. Only the stages the
 * wanted outputs need run (stats.runs tells which did):
 *   NORMALS  oriented normals (cloud->normal)        kd-tree, knn, normals, orient
 *   DEGREE   feature_degree                           kd-tree, knn, normals (fit error), degree
 *   CLASSES  + feature_class/confidence/dir           ... + classify
 *   DITHER   + dithering points in feature_class     ... + classify, dither (+ orient without colours)
 * Normals the input carries are kept (and reused for the tangent plane); normals computed but not
 * wanted (and not oriented) are not stored in the cloud. */
enum {
    PNPR_WANT_NORMALS = 1,
    PNPR_WANT_DEGREE = 2,
    PNPR_WANT_CLASSES = 4,
    PNPR_WANT_DITHER = 8,
    PNPR_WANT_ALL = 15,          /* everything `pointnpr features` writes */
    PNPR_WANT_NORMALS_ANY = 16   /* normals in cloud->normal, either orientation (outlines and the
                                  * two-sided shading need no more): no orientation stage */
};

/* Largest neighbourhood size: kNN lists take count x k entries and the classification reads 2k
 * neighbours, so a larger k is refused rather than slow. */
#define PNPR_FEATURES_K_MAX 1024

/* Zero means the default in every numeric member; the defaults and ranges are the table of
 * options.h (pnpr_features_defaults, pnpr_features_option_table), written nowhere else. */
typedef struct pnpr_features_options {
    uint32_t want;           /* PNPR_WANT_* bits; 0 = all */
    uint32_t k;              /* neighbourhood size, at most PNPR_FEATURES_K_MAX. Clamped to the number
                              * of valid points. */
    float threshold;         /* feature-degree threshold for feature points; 0 = automatic */
    float weight_geometry;   /* weights of the two terms; both 0 = the defaults */
    float weight_color;      /*   they are normalised to sum 1; colourless clouds use geometry only */
    float direction_confidence; /* min line-fit confidence of a directional point */
    float dither_scale;      /* multiplies the tone before dithering (density) */
    pnpr_tone_options tone;  /* the tone the dithering points follow (tone.h); zero = automatic */
    int has_viewpoint;       /* orient normals towards `viewpoint` (world coordinates) */
    double viewpoint[3];
    int recompute_normals;   /* recompute even when the cloud carries normals */
    int threads;             /* 0 = all cores */
    pnpr_progress progress;
} pnpr_features_options;

/* Per-stage timings and run counters filled by pnpr_compute_features (for benchmarks and for
 * tests that prove skipped stages did not run). */
typedef enum pnpr_stage {
    PNPR_STAGE_KDTREE = 0,
    PNPR_STAGE_KNN,
    PNPR_STAGE_NORMALS,
    PNPR_STAGE_ORIENT,
    PNPR_STAGE_FEATURE_DEGREE,
    PNPR_STAGE_CLASSIFY,
    PNPR_STAGE_DITHER,
    PNPR_STAGE_COUNT_
} pnpr_stage;

const char *pnpr_stage_name(pnpr_stage stage);

typedef struct pnpr_features_stats {
    double seconds[PNPR_STAGE_COUNT_];
    uint32_t runs[PNPR_STAGE_COUNT_];
    uint32_t k_used;          /* effective k */
    float threshold_used;     /* effective feature threshold */
    size_t valid_points;      /* points the analysis uses: finite offsets (xyz) */
    size_t beyond_float;      /* points left out although their world coordinates (src_xyz) are
                               * finite: their offset from the origin overflows float (outliers.h) */
    size_t feature_points, directional_points, dither_points;
} pnpr_features_stats;

/* Checks the options as pnpr_compute_features does: PNPR_ERR_INVALID_ARGUMENT, with a message
 * naming the option and its range in err (may be NULL), for unknown want bits, a non-finite
 * viewpoint, or a numeric member outside its range in the options table (options.h:
 * pnpr_option_check; e.g. k above PNPR_FEATURES_K_MAX). opts NULL = all defaults (valid). */
PNPR_NODISCARD pnpr_status pnpr_features_check_options(const pnpr_features_options *opts, pnpr_error *err);

/* ---- the whole pipeline on a cloud ---------------------------------------------------------
 * Computes normals (kept from the input unless opts->recompute_normals or unless more than half
 * of them are zero/non-finite; stored in cloud->normal) and adds the extra properties
 * feature_degree (float), feature_class (uchar), feature_confidence (float), feature_dir_x/y/z
 * (float), replacing existing ones of that name — those of opts->want (default: all).
 * Points with NaN/Inf coordinates get normal (0,0,0), degree 0, class 0, confidence 0.
 * stats may be NULL. */
PNPR_NODISCARD pnpr_status pnpr_compute_features(pnpr_cloud *cloud, const pnpr_features_options *opts,
                                  pnpr_features_stats *r_stats);

/* ---- the stages, for hosts that keep their own arrays -------------------------------------- */

/* Symmetric 3x3 eigen-decomposition (cyclic Jacobi in double, scale-normalised): eigenvalues
 * ascending in r_values, unit eigenvectors in the rows of r_vectors (r_vectors[i] belongs to
 * r_values[i]), right-handed. Non-finite input gives values 0 and the identity. */
void pnpr_eigen_sym3(const double a[3][3], double r_values[3], double r_vectors[3][3]);

/* Normals and plane-fit error from kNN rows (k entries per point, PNPR_INDEX_NONE = missing).
 * Covariance accumulated in double around the neighbourhood centroid. fit error =
 * lambda_min / (lambda_0 + lambda_1 + lambda_2) in [0, 1/3] (scale-invariant "surface
 * variation"). Fewer than 3 distinct neighbours: normal (0,0,0), error 0 (see docs).
 * Either output may be NULL (not both). */
PNPR_NODISCARD pnpr_status pnpr_estimate_normals(const float *xyz, size_t count, const uint32_t *knn, size_t k,
                                  int threads, float *r_normals, float *r_fit_error);

/* Orients normals consistently: towards `viewpoint` (offset coordinates, i.e. world minus the
 * cloud origin) when not NULL; else by propagation over the kNN graph from the highest point of
 * each connected component (that seed pointing +z), visiting the most parallel neighbours first. */
PNPR_NODISCARD pnpr_status pnpr_orient_normals(const float *xyz, size_t count, const uint32_t *knn, size_t k,
                                const double *viewpoint, float *normals);

/* Feature degree in [0,1] = w_g * G + w_c * C (weights normalised), see docs/features.md:
 *   G = min(1, max(0, s_i - mean_{j in N(i)} s_j) / 0.02), s = e averaged over each
 *       neighbourhood: positive part of the Laplacian of the smoothed fit error e (an edge
 *       filter whose response peaks on the crest of the error ridge that a crease produces;
 *       uniform error, as on a sphere, gives 0);
 *   C = min(1, |grad c| * r_i / 0.5): least-squares gradient of the RGB colour (0..1 per
 *       channel) in the tangent plane, times the RMS neighbour distance r_i = colour change across
 *       the neighbourhood. rgb may be NULL (then C = 0 and w_g = 1). */
PNPR_NODISCARD pnpr_status pnpr_feature_degree(const float *xyz, const uint8_t *rgb, const float *normals,
                                const float *fit_error, size_t count, const uint32_t *knn,
                                size_t k, float weight_geometry, float weight_color, int threads,
                                float *r_degree);

/* Automatic feature threshold from the degree histogram (see docs/features.md). */
float pnpr_auto_threshold(const float *degree, size_t count);

/* Feature points (degree >= threshold) get class NONDIRECTIONAL or DIRECTIONAL from a
 * least-squares 3D line fit over their k nearest feature points: confidence =
 * 1 - 1.5 * (mu_0 + mu_1) / (mu_0 + mu_1 + mu_2) in [0,1] (mu = covariance eigenvalues);
 * direction = principal eigenvector (components in r_dir_x/y/z, each may be NULL).
 * Non-feature points get class NONE, confidence 0, direction 0. input_index (count entries, may
 * be NULL = array order) orders feature points at equal distances, as the kNN does (knn.h): the
 * feature stage passes each point's input index, so that a tile of a cloud (tiles.h) cuts ties
 * as the whole cloud does. */
PNPR_NODISCARD pnpr_status pnpr_classify_features(const float *xyz, const float *degree, size_t count, size_t k,
                                   float threshold, float min_confidence, int threads,
                                   const uint32_t *input_index,
                                   uint8_t *r_class, float *r_confidence, float *r_dir_x,
                                   float *r_dir_y, float *r_dir_z);

/* Dithering points among the points of class NONE: Ostromoukhov's variable-coefficient error
 * diffusion over the kNN graph, scanning the points in array order — pass them in a spatially
 * coherent order (kd-tree order, as pnpr_compute_features does, or a Morton order). tone: per point darkness in
 * [0,1] (NULL = derived from rgb, else from normals lit from +z). Sets class DITHER on the
 * chosen points; returns their number in r_chosen (may be NULL). */
PNPR_NODISCARD pnpr_status pnpr_dither(const float *xyz, const uint8_t *rgb, const float *normals,
                        const float *tone, size_t count, const uint32_t *knn, size_t k,
                        float tone_scale, uint8_t *io_class, size_t *r_chosen);

#ifdef __cplusplus
}
#endif
#endif
