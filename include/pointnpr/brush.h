/* pointnpr — brush.h: stroke-based splatting (Lopes et al., "Stroke-based splatting", the paper in
 * ../shared/papers/stroke-based-splatting.txt), the parts that need no GL: the preprocessing
 * (section 3.2: splat sizes r + eps from kNN distances, colour clusters, normals fitted per
 * cluster), the Householder tangent frames (3.3.1) and the Gaussian-sum brush textures (3.3.2).
 * The renderer's `brush` style draws them (render.h; docs/brush.md documents every choice the
 * paper leaves open). */
#ifndef POINTNPR_BRUSH_H
#define POINTNPR_BRUSH_H

#include "cloud.h"
#include "segment.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- preprocessing (section 3.2) ------------------------------------------------------------ */

/* Largest pnpr_brush_options.k. */
#define PNPR_BRUSH_K_MAX 64
/* Most neighbours a normal fit over normal_radius takes (the nearest ones within the cluster). */
#define PNPR_BRUSH_NORMAL_NEIGHBOURS 32

typedef struct pnpr_brush_options {
    uint32_t k;              /* the local resolution r of a point is its mean distance to its k
                              * nearest neighbours, eps their standard deviation */
    float eps;               /* > 0: eps in world units for every point instead (the paper's "chosen
                              * by the user"); 0 = the kNN standard deviation */
    float normal_radius;     /* normals are fitted to the points of the same cluster within this many
                              * r (the paper: 3 r) */
    int recompute_normals;   /* fit normals even when the cloud carries them (else they are kept) */
    int threads;             /* 0 = all cores */
    pnpr_rgbgrow_options cluster; /* the colour clusters (clouds without colours: connected
                              * components, pnpr_segment_components) */
    pnpr_progress progress;  /* stages "knn", "grow", "merge", "normals" */
} pnpr_brush_options;

typedef struct pnpr_brush_stats {
    size_t clusters;         /* colour clusters (or components) */
    double mean_size;        /* mean brush_size of the finite points */
    int normals_computed;    /* 1: cloud->normal was (re)computed per cluster */
    double seconds;
} pnpr_brush_stats;

/* Adds the properties PNPR_PROP_BRUSH_SIZE (float, r + eps in the cloud's units) and
 * PNPR_PROP_BRUSH_CLUSTER (uint, the colour cluster), replacing existing ones, and fills
 * cloud->normal by a plane fit over the cluster's points within normal_radius x r (kept when the
 * cloud carries normals, unless recompute_normals). Points with NaN/Inf coordinates get size 0,
 * the clusters' invalid label and normal (0,0,0); a point without a neighbour (one point, or all
 * duplicates) gets size 0 too (the renderer then draws it at its disk radius). Options outside
 * their ranges (pnpr_brush_option_table) give PNPR_ERR_INVALID_ARGUMENT with a message in err
 * (may be NULL). r_stats may be NULL. */
PNPR_NODISCARD pnpr_status pnpr_brush_prepare(pnpr_cloud *cloud, const pnpr_brush_options *opts,
                                              pnpr_brush_stats *r_stats, pnpr_error *err);

/* Whether the cloud carries the outputs of pnpr_brush_prepare (both properties and normals). */
int pnpr_brush_cloud_ready(const pnpr_cloud *cloud);

/* The renderer draws brush sizes of at most this many times their median. */
#define PNPR_BRUSH_SIZE_CAP 4.0f

/* Clusters of fewer points are painted in two layers (the renderer's brush style). */
#define PNPR_BRUSH_SMALL_CLUSTER 64

/* The longest brush a cluster's shape stretches to, in brush widths. */
#define PNPR_BRUSH_STRETCH_MAX 3.0f

/* The per-cluster brush adjustments of section 3.2.1 for every point: r_stretch[i] = the cluster's
 * long over short extent, sqrt(l1 / l2) of the two largest eigenvalues of its points' covariance,
 * clamped to 1..PNPR_BRUSH_STRETCH_MAX (longer brushes on longer clusters); r_layers[i] = 2 when
 * the cluster has fewer than `small` points (two-layered painting of small, detailed clusters),
 * else 1. Clusters are compared by label value; points with a non-finite coordinate count in no
 * cluster and get 1 and 1. */
PNPR_NODISCARD pnpr_status pnpr_brush_cluster_shapes(const float *xyz, const uint32_t *cluster, size_t count,
                                                     uint32_t small, float *r_stretch, uint8_t *r_layers);

/* ---- the strokes (section 3.3) -------------------------------------------------------------- */

/* The tangent t and bitangent b of unit normal n by the Householder formula: with
 * h = (n_x + |n|, n_y, n_z), the reflection H = I - 2 h h^T / h^T h maps e_x to -n/|n|; t and b
 * are its second and third columns, so (t, b, n) is a right-handed orthonormal frame that depends
 * smoothly on n everywhere but at n = -e_x (h = 0), where the frame is t = e_z, b = e_y (the
 * limit depends on the direction of approach). A zero or non-finite n gives t = e_y, b = e_z.
 * render/shaders/brush.vert.glsl computes the same. */
void pnpr_householder_frame(const float n[3], float r_t[3], float r_b[3]);

/* A brush: the sum of `gaussians` functions of eq. (1),
 *   z = A exp(-1/2 |x'/sigma_x|^lambda) exp(-1/2 |y'/sigma_y|^lambda)
 * with (x', y') the texel's offset from the centre P0, rotated by the column's theta, clamped to 1. */
typedef struct pnpr_brush_shape {
    float amplitude;         /* A: the overall opacity */
    float dev;               /* the spacing of the centres P0 on their grid (texture units) */
    float lambda;            /* the shape exponent (2 = Gaussian, larger = squarer) */
    float sigma_x, sigma_y;  /* decay along the stroke and across it (texture units) */
    uint32_t gaussians;      /* 6 (3 columns of 2) or 9 (3 x 3), the paper's range */
    float theta_dev;         /* degrees: a column's theta differs from the previous one's by at most this */
    float jitter;            /* bounded random deviation of each Gaussian's A and P0, fraction (0..0.5) */
} pnpr_brush_shape;

typedef struct pnpr_brush_preset {
    const char *name;
    const char *description;
    pnpr_brush_shape shape;
} pnpr_brush_preset;

/* How many presets there are (pnpr_brush_presets). */
#define PNPR_BRUSH_PRESET_COUNT 3

/* The presets in order (the parameters of the paper's figure 4 c, d, b); index 0 is the default. */
const pnpr_brush_preset *pnpr_brush_presets(size_t *r_count);
/* The presets' names in order, joined by `sep`, into buf (cap > 0 bytes, NUL-terminated,
 * truncated to fit). Returns buf. */
const char *pnpr_brush_preset_list(char *buf, size_t cap, const char *sep);
/* The preset index of a name (case ignored); PNPR_ERR_NOT_FOUND. */
PNPR_NODISCARD pnpr_status pnpr_brush_preset_find(const char *name, uint32_t *r_index);

/* Texture variants per brush: points pick one by a hash of their position, so the strokes differ
 * from point to point but stay the same from frame to frame. */
#define PNPR_BRUSH_VARIANTS 16

/* The alpha of variant `variant` of brush `s` as w x h bytes (row 0 = v 0; u along the stroke):
 * eq. (1) summed over the grid, each column's theta a bounded random walk from 0 and each
 * Gaussian's A and P0 jittered, seeded by `variant` only; faded to 0 over the outer 8% of the
 * square so that no stroke ends in a hard edge. PNPR_ERR_INVALID_ARGUMENT for a bad size (1..1024)
 * or a shape outside its ranges (non-finite, sigma <= 0, lambda outside 0.5..8, gaussians not 6
 * or 9). */
PNPR_NODISCARD pnpr_status pnpr_brush_texture(const pnpr_brush_shape *s, uint32_t variant, int w, int h,
                                              uint8_t *r_alpha);

#ifdef __cplusplus
}
#endif
#endif
