/* pointnpr — segment.h: segmentation of point clouds into regions, and the region hierarchy.
 *
 * Sources of segments (each one .c file in filters/):
 *   jseg        3D JSEG colour segmentation (Chi & Lee, "Stylized and Abstract Painterly
 *               Rendering System Using a Multiscale Segmented Sphere Hierarchy", sec. 3.2):
 *               colour quantisation in CIE L*a*b* -> class map -> local J per point over its
 *               neighbourhood -> seed regions of low J -> region growing in J order -> merging of
 *               similar and of small regions                              (segment_jseg.c)
 *   rag         region adjacency graph: merging by colour / size, and the paper's hierarchy by
 *               the merge evaluation e_ij (HSI distance, size rule); cut by count or threshold
 *                                                                         (segment_rag.c)
 *   components  connected components at a distance threshold, minimum size (segment_components.c)
 *   rgbgrow     colour region growing (Zhan et al., as used by stroke-based splatting)
 *                                                                         (segment_rgbgrow.c)
 *   labels      labels imported from a per-point property; mean colours, adjusted Rand index,
 *               over/under-segmentation counts                            (segment_common.c)
 * docs/segmentation.md documents every choice the papers leave open.
 *
 * Conventions:
 *  - xyz: 3*count floats, packed; rgb: 3*count bytes, packed. Caller-owned outputs:
 *    r_labels has `count` entries and receives labels 0 .. S-1 (S = segment count).
 *  - Points with a NaN/Inf coordinate cannot be placed: they all get ONE extra segment, the last
 *    label S-1, reported as info.invalid_segment (PNPR_LABEL_NONE when there are none).
 *  - Labels are numbered in order of first appearance along the point array, so results are
 *    deterministic and independent of the number of threads.
 *  - Options structs are valid when zero-initialised; every zero means the default. The defaults
 *    and ranges of the options structs are the tables of options.h (pnpr_jseg_defaults,
 *    pnpr_jseg_option_table, ...), written nowhere else. */
#ifndef POINTNPR_SEGMENT_H
#define POINTNPR_SEGMENT_H

#include "cloud.h"
#include "knn.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PNPR_LABEL_NONE 0xFFFFFFFFu

/* Upper ends of the count options (larger values are clamped to them): neighbourhood sizes
 * (jseg, rgbgrow; kNN lists take count x k entries) and the quantiser's colour classes. */
#define PNPR_SEGMENT_K_MAX 256
#define PNPR_JSEG_CLASSES_MAX 255
/* Deepest nesting of pnpr_segment_covariance_split (2^64 sub-regions: never reached by balanced
 * splits, only by skewed ones that peel off a few points at a time). */
#define PNPR_SPLIT_DEPTH_MAX 64

/* What a segmentation call reports besides the labels (all fields written; NULL ok). */
typedef struct pnpr_segment_info {
    uint32_t segment_count;   /* S: labels are 0 .. S-1 */
    uint32_t invalid_segment; /* label of the points with non-finite coordinates, or PNPR_LABEL_NONE */
    size_t valid_points;      /* points with finite coordinates */
    /* jseg only */
    uint32_t classes;         /* colour classes after quantisation */
    float mean_j;             /* mean J over the valid points */
    uint32_t seed_regions;    /* seed regions found */
    uint32_t grown_regions;   /* regions after growing (before merging) */
    double seconds;           /* wall time of the call */
} pnpr_segment_info;

/* ---- 3D JSEG ------------------------------------------------------------------------------ */

typedef struct pnpr_jseg_options {
    uint32_t classes;        /* k-means classes of the quantiser before close centres merge; max
                              * PNPR_JSEG_CLASSES_MAX */
    float quant_distance;    /* class centres closer than this (CIE76 delta E) become one class; <0 = none */
    uint32_t k;              /* J neighbourhood: k nearest points including the point; max
                              * PNPR_SEGMENT_K_MAX */
    float radius;            /* > 0: J neighbourhood = those of the k nearest within radius (offset units) */
    float seed_factor;       /* seed points: J <= seed_factor * mean J */
    float grow_bound;        /* > 0: growth stops at points with J >= grow_bound * mean J (they form their
                              * own regions, merged later); 0 = no bound */
    uint32_t seed_min_size;  /* seed regions smaller than this are dropped; 0 = k */
    float merge_distance;    /* adjacent regions whose mean L*a*b* colours differ less merge; <0 = none */
    uint32_t min_size;       /* regions smaller than this merge into their closest-coloured neighbour;
                              * 0 = max(k, valid points / 1000) */
    uint64_t seed;           /* seed of the k-means++ initialisation; 0 = a fixed default */
    int threads;             /* 0 = all cores */
    pnpr_progress progress;  /* stages "knn", "quantise", "J", "grow", "merge" */
    /* optional per-point outputs (count entries each), NULL = not wanted */
    float *r_j;              /* J value of every point (0 for invalid points) */
    uint8_t *r_class;        /* colour class of every point (0 for invalid points) */
} pnpr_jseg_options;

/* rgb is required: a cloud without colours gives PNPR_ERR_INVALID_ARGUMENT (use components).
 * count == 0 gives PNPR_OK with S = 0. */
PNPR_NODISCARD pnpr_status pnpr_segment_jseg(const float *xyz, const uint8_t *rgb, size_t count,
                              const pnpr_jseg_options *opts, uint32_t *r_labels,
                              pnpr_segment_info *r_info);

/* ---- region adjacency graph: merging and the region hierarchy ------------------------------ */

/* Adjacency used by the RAG: point i touches the first `k` entries of row i of knn (rows of
 * `k_stride` entries as pnpr_knn_self writes them, PNPR_INDEX_NONE = missing). */
typedef struct pnpr_region_graph {
    const uint32_t *knn;
    size_t k_stride;
    size_t k;
} pnpr_region_graph;

/* Merges adjacent regions whose mean L*a*b* colours differ by less than max_distance (closest
 * pair first, means updated after each merge), then regions smaller than min_size into the
 * adjacent region of closest mean colour (smallest distance first). max_distance <= 0: no colour
 * merge; min_size <= 1: no size merge. Regions without neighbours stay as they are. Labels are
 * renumbered (first appearance); io_labels >= *io_segment_count (e.g. the invalid segment) are
 * left alone and keep their relative order after the others. */
PNPR_NODISCARD pnpr_status pnpr_segment_merge_regions(const uint8_t *rgb, size_t count, const pnpr_region_graph *graph,
                                       float max_distance, uint32_t min_size, uint32_t *io_labels,
                                       uint32_t *io_segment_count);

/* One merge of the hierarchy. Nodes 0 .. S-1 are the input segments; merge i creates node S + i
 * from nodes a and b. */
typedef struct pnpr_segment_merge {
    uint32_t a, b;     /* merged nodes */
    uint32_t size;     /* points in the new node */
    float cost;        /* merge evaluation value e_ij (eq. 4) */
    float distance;    /* HSI distance of the two mean colours */
    float level;       /* max(distance) over merges 0..i: monotone, what a threshold cut compares */
} pnpr_segment_merge;

typedef struct pnpr_hierarchy_options {
    float alpha;       /* size rule: "small" = size < alpha * mean initial size */
    float epsilon;     /* factor of pairs that are not both small */
    int no_join;       /* 0: after the graph is exhausted, disconnected parts are joined by colour
                        * (at most 1024 of them) so the hierarchy has one root; 1: do not join */
    pnpr_progress progress; /* stage "hierarchy" */
} pnpr_hierarchy_options;

/* Builds the paper's region hierarchy over S = segment_count segments: repeatedly merges the
 * adjacent pair with the smallest e_ij = d_HSI(mean colours) if both are small, else
 * epsilon * d_HSI. r_merges must hold segment_count - 1 entries (may be NULL when S <= 1);
 * *r_merge_count receives how many merges were made (S - 1 when everything joined).
 * Labels >= segment_count are ignored. rgb required. */
PNPR_NODISCARD pnpr_status pnpr_segment_hierarchy(const uint8_t *rgb, size_t count, const pnpr_region_graph *graph,
                                   const uint32_t *labels, uint32_t segment_count,
                                   const pnpr_hierarchy_options *opts, pnpr_segment_merge *r_merges,
                                   uint32_t *r_merge_count);

/* A level of the hierarchy: applies the first m merges, where m is the largest prefix such that
 * (target_segments > 0) at least target_segments segments remain, and (threshold > 0) every
 * applied merge has level <= threshold. Labels >= segment_count pass through as one extra
 * segment (the last). r_labels may equal labels. */
PNPR_NODISCARD pnpr_status pnpr_segment_hierarchy_cut(const uint32_t *labels, size_t count, uint32_t segment_count,
                                       const pnpr_segment_merge *merges, uint32_t merge_count,
                                       uint32_t target_segments, float threshold,
                                       uint32_t *r_labels, uint32_t *r_segment_count);

/* The covariance split's two settings (pnpr_segment_covariance_split takes them as arguments);
 * their defaults and ranges: pnpr_split_option_table (options.h). Zero = the default. */
typedef struct pnpr_split_options {
    float max_variation; /* split regions whose surface variation exceeds this */
    uint32_t min_size;   /* no split leaves a part smaller than this */
} pnpr_split_options;

/* Covariance splitting within regions (Chi & Lee sec. 3.2, Pauly et al.): every region whose
 * surface variation (PCA: lambda_min / trace) exceeds max_variation is split by the
 * plane through its centroid perpendicular to its direction of greatest variation, recursively,
 * while both halves keep at least min_size points (0 for either: the default of
 * pnpr_split_option_table; out of its range: PNPR_ERR_INVALID_ARGUMENT), at most PNPR_SPLIT_DEPTH_MAX levels
 * deep (the cost is at most that many passes over the points). Output: sub-region labels in
 * r_labels (may equal labels), numbered by first appearance; points with label >= segment_count
 * or non-finite coordinates share one extra label, the last. (segment_split.c) */
PNPR_NODISCARD pnpr_status pnpr_segment_covariance_split(const float *xyz, size_t count, const uint32_t *labels,
                                          uint32_t segment_count, float max_variation,
                                          uint32_t min_size, uint32_t *r_labels,
                                          uint32_t *r_segment_count);

/* ---- connected components ----------------------------------------------------------------- */

typedef struct pnpr_components_options {
    float distance;     /* points closer than this (<=) are connected; 0 = a multiple (options.h) of the
                         * median nearest-neighbour distance */
    uint32_t min_size;  /* components smaller than this join the component of their nearest
                         * point in a kept component; 1 = keep all */
    int threads;
    pnpr_progress progress; /* stages "knn", "components" */
} pnpr_components_options;

/* rgb not needed. */
PNPR_NODISCARD pnpr_status pnpr_segment_components(const float *xyz, size_t count, const pnpr_components_options *opts,
                                    uint32_t *r_labels, pnpr_segment_info *r_info);

/* Median distance from a point to its nearest distinct neighbour, over a stride sample of the
 * tree's points (every (count / PNPR_SEGMENT_SPACING_SAMPLE + 1)-th of the array xyz/count the tree
 * was built from, from the first; points whose 8 nearest all coincide with them count no
 * distance); 0 when all points coincide. The default distances of components and rgbgrow are a
 * multiple of this (options.h). pnpr_tile_components_distance (tiles.h) gives the same value for
 * a file larger than memory. */
#define PNPR_SEGMENT_SPACING_SAMPLE 10000
float pnpr_segment_median_spacing(const pnpr_kdtree *tree, const float *xyz, size_t count);
/* One point's term of that median: the distance from p to the nearest of its 8 nearest points that
 * does not coincide with it (0: all 8 coincide); *r_eighth (may be NULL) gets the 8th's distance
 * (INFINITY when the tree has fewer than 8 points). */
float pnpr_segment_nn_distinct(const pnpr_kdtree *tree, const float p[3], float *r_eighth);
/* The distance components connect at: opts->distance when > 0, else the options table's multiple
 * of median_spacing (pnpr_segment_median_spacing). */
float pnpr_components_distance(const pnpr_components_options *opts, float median_spacing);

/* ---- colour region growing (Zhan et al.) -------------------------------------------------- */

typedef struct pnpr_rgbgrow_options {
    uint32_t k;              /* neighbours considered per point; max PNPR_SEGMENT_K_MAX */
    float distance;          /* neighbours farther than this are ignored; 0 = a multiple (options.h) of the
                              * median nearest-neighbour distance */
    float point_distance;    /* a neighbour joins when its colour differs from the point's by less
                              * (Euclidean RGB, 0..255 units) */
    float region_distance;   /* adjacent regions whose mean colours differ less (CIE76 delta E) merge;
                              * <0 = none */
    uint32_t min_size;       /* smaller regions merge into their closest-coloured neighbour */
    int threads;
    pnpr_progress progress;  /* stages "knn", "grow", "merge" */
} pnpr_rgbgrow_options;

/* rgb required (PNPR_ERR_INVALID_ARGUMENT without). */
PNPR_NODISCARD pnpr_status pnpr_segment_rgbgrow(const float *xyz, const uint8_t *rgb, size_t count,
                                 const pnpr_rgbgrow_options *opts, uint32_t *r_labels,
                                 pnpr_segment_info *r_info);

/* ---- labels, colours, evaluation ---------------------------------------------------------- */

/* Segments from per-point values (any pnpr_type): each distinct value is a segment, numbered in
 * ascending value order; NaN values form one segment after all others. */
PNPR_NODISCARD pnpr_status pnpr_segment_from_values(pnpr_type type, const void *values, size_t count,
                                     uint32_t *r_labels, uint32_t *r_segment_count);

/* Normalises a labelling the way every source here returns it: labels of the points with finite
 * coordinates are renumbered 0 .. S'-1 by first appearance (any uint32 value is one segment);
 * all points with a non-finite coordinate get the one last label S'. Fills r_info's
 * segment_count, invalid_segment and valid_points (r_info may be NULL). xyz may be NULL (all
 * points valid). */
PNPR_NODISCARD pnpr_status pnpr_segment_finish(const float *xyz, size_t count, uint32_t *io_labels,
                                pnpr_segment_info *r_info);

/* Renumbers labels to 0 .. S-1 in order of first appearance (in place). */
PNPR_NODISCARD pnpr_status pnpr_segment_compact(uint32_t *io_labels, size_t count, uint32_t *r_segment_count);

/* Mean colour (0..255, 3 floats per segment) and size of each segment. Labels >= segment_count
 * are ignored; empty segments get colour 0 and size 0. rgb NULL: colours 0. Either output may be
 * NULL. */
PNPR_NODISCARD pnpr_status pnpr_segment_mean_colors(const uint8_t *rgb, const uint32_t *labels, size_t count,
                                     uint32_t segment_count, float *r_rgb, uint32_t *r_sizes);

/* The segments' mean colours as properties of the cloud: seg_red, seg_green, seg_blue (uchar;
 * PNPR_PROP_SEG_RED..., an existing one is replaced in place), each point's the mean of its label
 * (cloud->label, required; mean_rgb: 3 floats per segment as pnpr_segment_mean_colors gives them)
 * rounded to the nearest byte; labels >= segment_count get 0. What `pointnpr segment` writes, in
 * memory and in tiles. */
PNPR_NODISCARD pnpr_status pnpr_segment_add_colors(pnpr_cloud *cloud, const float *mean_rgb, uint32_t segment_count);

/* sRGB (8 bit, D65) to CIE L*a*b*. */
void pnpr_rgb_to_lab(const uint8_t rgb[3], float r_lab[3]);

/* Comparison of a segmentation with ground truth (arbitrary uint32 labels in both). */
typedef struct pnpr_segment_score {
    double ari;                /* adjusted Rand index (1 = identical partitions; 1 when both are trivial) */
    uint32_t truth_segments, result_segments;
    uint32_t over_segmented;   /* true segments split: >= 2 result segments that each hold >= 10% of
                                * it and are mostly (> 50%) made of it */
    uint32_t under_segmented;  /* result segments holding >= 10% of each of >= 2 true segments */
} pnpr_segment_score;

PNPR_NODISCARD pnpr_status pnpr_segment_score_labels(const uint32_t *truth, const uint32_t *result, size_t count,
                                      pnpr_segment_score *r_score);

#ifdef __cplusplus
}
#endif
#endif
