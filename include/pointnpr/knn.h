/* pointnpr — knn.h: kd-tree over float points, k-nearest-neighbour and radius queries.
 *
 * The tree is opaque and immutable once built, so any number of threads may query it.
 * Points with a NaN/Inf coordinate are left out of the tree (never returned as neighbours).
 * Build is O(n log n) (median splits by quickselect on the widest axis, leaves of <= 12 points);
 * the tree keeps a reordered copy of the points (12 bytes/point) plus their indices (4 bytes). */
#ifndef POINTNPR_KNN_H
#define POINTNPR_KNN_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PNPR_INDEX_NONE 0xFFFFFFFFu /* "no neighbour" in index outputs */

typedef struct pnpr_kdtree pnpr_kdtree;

/* xyz: point i at (const char *)xyz + i*stride_bytes (stride 0 = 3 floats, tightly packed).
 * count must be < 2^32 - 1. An empty or all-invalid input gives a valid empty tree. */
PNPR_NODISCARD pnpr_status pnpr_kdtree_build(const float *xyz, size_t count, size_t stride_bytes,
                              pnpr_kdtree **r_tree);
/* Same, with the number of build threads (0 = all cores; the top levels are split sequentially,
 * then up to 16 subtrees are built in parallel). The tree does not depend on `threads`. */
PNPR_NODISCARD pnpr_status pnpr_kdtree_build_threads(const float *xyz, size_t count, size_t stride_bytes,
                                      int threads, pnpr_kdtree **r_tree);
void pnpr_kdtree_free(pnpr_kdtree *tree);

/* Frees the tree but hands over its arrays, for pipelines that work in tree order (spatially
 * coherent, so neighbour gathers hit the cache): r_points = the valid points in tree order
 * (3 * size floats), r_indices = the original index of each. Release both with pnpr_free. */
PNPR_NODISCARD pnpr_status pnpr_kdtree_detach(pnpr_kdtree *tree, float **r_points, uint32_t **r_indices);
size_t pnpr_kdtree_size(const pnpr_kdtree *tree); /* number of (valid) points in the tree */

/* Median distance from a point to its nearest distinct point (the sample spacing), over a
 * deterministic sample of at most max_samples tree points (0 = 20 000); 0 when the tree has
 * fewer than 2 distinct points. */
float pnpr_kdtree_median_spacing(const pnpr_kdtree *tree, size_t max_samples);

/* The k nearest points to q, nearest first (equal distances in a deterministic order). Writes
 * min(k, size) entries to r_idx (and squared distances to r_dist2 when not NULL), fills the
 * rest of the k entries with PNPR_INDEX_NONE / INFINITY, and returns the number found.
 * A query point with NaN/Inf finds nothing (returns 0). */
size_t pnpr_kdtree_knn(const pnpr_kdtree *tree, const float q[3], size_t k, uint32_t *r_idx,
                       float *r_dist2);

/* All points within `radius` of q (distance <= radius), in no particular order. Writes at most
 * `cap` indices and returns the total number of points in range (may exceed cap). */
size_t pnpr_kdtree_radius(const pnpr_kdtree *tree, const float q[3], float radius,
                          uint32_t *r_idx, size_t cap);

typedef struct pnpr_knn_options {
    int threads;           /* 0 = all cores */
    pnpr_progress progress; /* stage name "knn" */
    int tree_order;        /* pnpr_knn_self only: rows and neighbour ids are tree positions
                            * (0 .. size-1, see pnpr_kdtree_detach) instead of input indices */
} pnpr_knn_options;

/* kNN of many query points in parallel: row i of r_idx (k entries, and of r_dist2 when not
 * NULL) holds the neighbours of query point i as pnpr_kdtree_knn returns them. When the
 * queries are the tree's own points, each point is its own first neighbour. */
PNPR_NODISCARD pnpr_status pnpr_knn_all(const pnpr_kdtree *tree, const float *query_xyz, size_t query_count,
                         size_t query_stride_bytes, size_t k, const pnpr_knn_options *opts,
                         uint32_t *r_idx, float *r_dist2);

/* kNN of the tree's own points (the xyz array it was built from, `count` points including the
 * ones left out): row i belongs to point i. Faster than pnpr_knn_all on the same points because
 * queries run in tree order (memory locality). Rows of left-out points are all "none". */
PNPR_NODISCARD pnpr_status pnpr_knn_self(const pnpr_kdtree *tree, size_t count, size_t k,
                          const pnpr_knn_options *opts, uint32_t *r_idx, float *r_dist2);

/* ---- the local point spacing (filters/spacing.c) ---- */

#define PNPR_SPACING_CLAMP_LO 0.125f /* spacings are clamped to [LO, HI] x their median: */
#define PNPR_SPACING_CLAMP_HI 4.0f   /* duplicates (0) and isolated points (far) */

/* Optional neighbour lists handed over by pnpr_point_spacing: set `want` (the neighbours per point,
 * itself included); on return idx / d2 hold n x k entries (k >= want unless n is smaller; nearest
 * first, as pnpr_knn_self), or NULL when want is 0. Release both with free(). */
typedef struct pnpr_spacing_lists {
    size_t want;
    uint32_t *idx;
    float *d2;
    size_t k;
} pnpr_spacing_lists;

/* r_spacing[i] = the distance from point i of xyz[0..n) to its k-th nearest other point (fewer when
 * the cloud has fewer), clamped to [PNPR_SPACING_CLAMP_LO, PNPR_SPACING_CLAMP_HI] x the median
 * (a median of 0: the largest, else 1); a lone point: 1. Non-finite points get the low clamp.
 * The renderer's disk radii (render.h, pnpr_upload_options.spacing_k) and the SVG outlines'
 * surface buffer are this spacing times the mask scale. lists may be NULL. */
PNPR_NODISCARD pnpr_status pnpr_point_spacing(const float *xyz, size_t n, uint32_t k, int threads, float *r_spacing,
                                              pnpr_spacing_lists *lists);
/* The unclamped part of pnpr_point_spacing from neighbour lists already at hand (idx: n rows of kk
 * entries, nearest first, each point itself included, PNPR_INDEX_NONE padding, as pnpr_knn_self
 * gives them in input or tree order alike): r_spacing[i] = the distance from point i to the
 * farthest listed of its first min(k + 1, kk) entries, computed as the kd-tree computes it, so
 * that any exact lists with kk > k give the same floats; 0 for a row with no other point. The
 * feature stage stores it (PNPR_PROP_POINT_SPACING) and the upload then skips its own kNN. */
void pnpr_spacing_from_lists(const float *xyz, size_t n, const uint32_t *idx, size_t kk, uint32_t k, float *r_spacing);
/* The clamp of pnpr_point_spacing, in place: to [PNPR_SPACING_CLAMP_LO, PNPR_SPACING_CLAMP_HI] x
 * the median of r[0..n) (a median of 0: the largest, else 1; NaN: the low clamp). */
PNPR_NODISCARD pnpr_status pnpr_spacing_clamp(float *r, size_t n);

#ifdef __cplusplus
}
#endif
#endif
