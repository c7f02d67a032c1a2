/* pointnpr — outliers.h: far outliers, and the robust centre and extent they are judged by
 * (GL-free, core library: filters/outliers.c).
 *
 * A scan may hold a few points far away from everything else (a multipath echo, a coordinate
 * written as 1e9 or 1e308 by a broken exporter). Bounding boxes, and everything sized from them,
 * then describe the outliers instead of the content. The robust estimates here ignore them:
 *   robust centre  per-axis median of the finite world coordinates;
 *   robust extent  the PNPR_OUTLIER_QUANTILE quantile of the finite points' distances from the
 *                  robust centre (both over a deterministic stride sample of at most
 *                  PNPR_OUTLIER_SAMPLES points, so at most 1 - PNPR_OUTLIER_QUANTILE of the
 *                  points may be outliers);
 *   far outlier    a point with finite world coordinates farther than factor x robust extent
 *                  from the robust centre (distance computed in double), or whose float offset
 *                  from the cloud's origin overflowed (beyond float range; see cloud.h).
 * A robust extent of 0 (most points coincide) gives no scale: then no point is a far outlier.
 * The readers' origin (pnpr_cloud_set_world) is the centre of the bounding box of the points
 * that are not far outliers by this definition (default factor), so one far point no longer
 * moves every other point's float offset. docs/features.md, "Far outliers", has the figures. */
#ifndef POINTNPR_OUTLIERS_H
#define POINTNPR_OUTLIERS_H

#include "cloud.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PNPR_OUTLIER_FACTOR 10.0     /* default factor: farther than 10 robust extents */
#define PNPR_OUTLIER_FACTOR_MIN 1.0  /* accepted range of pnpr_outlier_options.factor */
#define PNPR_OUTLIER_FACTOR_MAX 1e6
#define PNPR_OUTLIER_QUANTILE 0.9    /* the robust extent: this quantile of the distances */
#define PNPR_OUTLIER_SAMPLES 100000  /* the robust centre and extent look at most this many points */

typedef struct pnpr_outlier_options {
    double factor; /* far = farther than factor x robust extent; 0 = PNPR_OUTLIER_FACTOR, else in
                    * [PNPR_OUTLIER_FACTOR_MIN, PNPR_OUTLIER_FACTOR_MAX] (PNPR_ERR_INVALID_ARGUMENT) */
} pnpr_outlier_options;

typedef struct pnpr_outlier_info {
    double centre[3];     /* robust centre (world coordinates); 0 without a finite point */
    double extent;        /* robust extent (world units) */
    double limit;         /* factor x extent: farther is far; INFINITY when extent is 0 */
    size_t finite;        /* points with finite world coordinates */
    size_t far;           /* far outliers among them (beyond_float included) */
    size_t beyond_float;  /* finite world coordinates whose float offset is not finite: stages
                           * that work on offsets leave them out like NaN points */
} pnpr_outlier_info;

/* Far outliers of `count` world points (3 doubles each; NaN/Inf ones are not finite and never
 * far). r_far (optional, count bytes) receives 1 for a far outlier, else 0; r_info may be NULL.
 * PNPR_ERR_INVALID_ARGUMENT for a NULL world with count > 0 or a factor out of range. */
PNPR_NODISCARD pnpr_status pnpr_world_outliers(const double *world, size_t count, const pnpr_outlier_options *opts,
                                uint8_t *r_far, pnpr_outlier_info *r_info);

/* The robust centre, extent and limit (default factor) of a stride sample already taken: the
 * m <= PNPR_OUTLIER_SAMPLES finite points (3 doubles each) that pnpr_world_outliers takes from a
 * larger array (every (count / PNPR_OUTLIER_SAMPLES + 1)-th from the first, the finite ones, at
 * most PNPR_OUTLIER_SAMPLES), so that a pass over a file gives the frame of the whole cloud in
 * memory (the tile plan's origin, tiles.h). Only centre, extent and limit are written. */
PNPR_NODISCARD pnpr_status pnpr_outlier_frame_of_sample(const double *sample, size_t m, pnpr_outlier_info *r_info);

/* The same on a cloud's world coordinates (pnpr_cloud_world: src_xyz when present, else origin +
 * offset); also counts the points beyond float range (always far). */
PNPR_NODISCARD pnpr_status pnpr_cloud_outliers(const pnpr_cloud *cloud, const pnpr_outlier_options *opts, uint8_t *r_far,
                                pnpr_outlier_info *r_info);

/* Removes the far outliers of pnpr_cloud_outliers from the cloud (pnpr_cloud_keep; points with
 * NaN/Inf coordinates stay). r_info (may be NULL) describes the cloud before the removal. */
PNPR_NODISCARD pnpr_status pnpr_cloud_drop_outliers(pnpr_cloud *cloud, const pnpr_outlier_options *opts,
                                     pnpr_outlier_info *r_info);

/* Bounding box of the finite offsets of the points that are not far outliers (default factor;
 * the box pnpr_cloud_bounds gives when there are none, and also when memory runs out); returns
 * how many points it holds. The renderer's automatic near/far planes, pnpr_camera_fit and the
 * camera matrices use it, so that one far point does not push the content out of the depth range. */
size_t pnpr_cloud_inlier_bounds(const pnpr_cloud *cloud, float r_min[3], float r_max[3]);

/* Whether the world point w is a far outlier by info (not counting beyond-float offsets, which
 * only the cloud knows): finite and farther than info->limit from info->centre. */
int pnpr_outlier_is_far(const pnpr_outlier_info *info, const double w[3]);

#ifdef __cplusplus
}
#endif
#endif
