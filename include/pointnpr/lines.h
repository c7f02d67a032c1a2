/* pointnpr — lines.h: profile lines (PointWorks section 5.2, "Profile Lines").
 *
 * From the directional feature points: a graph connecting each point to the directional points
 * in its neighbourhood; every point shifted towards its neighbours across the feature (noise
 * reduction); points closer than a tolerance merged; a minimum spanning forest whose edge weight
 * combines 3D distance and the agreement of the edge with the points' feature directions; short
 * spurs pruned; the forest split into chains between leaves and junctions; chain ends that point
 * at a common corner joined there; each chain fitted with a least-squares cubic B-spline,
 * smoothed once more and sampled adaptively into a polyline. docs/lines.md documents every
 * formula and parameter. */
#ifndef POINTNPR_LINES_H
#define POINTNPR_LINES_H

#include "cloud.h"
#include "polylines.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Bounds that keep the cost linear in the number of directional points whatever the options:
 * at most PNPR_LINES_SHIFT_MAX shift iterations (more is refused), and the shift and the merge
 * take at most PNPR_LINES_NEIGHBOURS_MAX points within their radius (a radius that takes in the
 * whole cloud costs no more than that); the graph takes each node's 8 nearest nodes within
 * connect_radius; a knot span is sampled into at most 1024 pieces however small sample_tol is. */
#define PNPR_LINES_SHIFT_MAX 64
#define PNPR_LINES_NEIGHBOURS_MAX 256

/* Zero means the default in every numeric member; the defaults (some of them multiples of h) and
 * the ranges are the table of options.h (pnpr_lines_defaults, pnpr_lines_option_table). */
typedef struct pnpr_lines_options {
    float spacing;          /* sample spacing h (world units); 0 = median nearest-neighbour
                             * distance among the directional points */
    float connect_radius;   /* graph neighbourhood radius */
    float merge_tol;        /* points closer than this are merged */
    int shift_iterations;   /* noise-reducing shifts; negative = none, at most PNPR_LINES_SHIFT_MAX */
    float direction_weight; /* beta in the edge weight (see docs) */
    float min_length;       /* spurs and isolated chains shorter than this are dropped */
    float sample_tol;       /* max chord deviation of the output polylines */
    int no_corners;         /* 1 = do not join chain ends at corners */
    int threads;            /* worker threads of the shift, graph, edge sort and fit stages; 0 = all
                             * cores. The result does not depend on it */
    pnpr_progress progress;
} pnpr_lines_options;

/* The result, pnpr_polylines (with pnpr_lines_free and the OBJ/PLY writers): polylines.h. */

typedef struct pnpr_lines_stats {
    size_t directional_points, merged_nodes, graph_edges, forest_edges, chains, corners;
    float spacing_used;
    double total_length;
    double seconds_graph, seconds_mst, seconds_fit;
} pnpr_lines_stats;

/* Checks the options as pnpr_profile_lines does (pnpr_option_check over the options table,
 * options.h): PNPR_ERR_INVALID_ARGUMENT, with a message naming the option and its range in err (may
 * be NULL), for a negative or non-finite length or weight, or shift_iterations above
 * PNPR_LINES_SHIFT_MAX. opts NULL = all defaults (valid). */
PNPR_NODISCARD pnpr_status pnpr_lines_check_options(const pnpr_lines_options *opts, pnpr_error *err);

/* Profile lines of a cloud that carries the feature properties of pnpr_compute_features
 * (feature_class, feature_dir_x/y/z); PNPR_ERR_NOT_FOUND when they are missing. No directional
 * points: PNPR_OK with zero lines. stats may be NULL. */
PNPR_NODISCARD pnpr_status pnpr_profile_lines(const pnpr_cloud *cloud, const pnpr_lines_options *opts,
                               pnpr_polylines *r_lines, pnpr_lines_stats *r_stats);

/* The same from m directional points given directly: positions (offsets from `origin`) and unit
 * directions, 3 floats each. */
PNPR_NODISCARD pnpr_status pnpr_profile_lines_points(const float *xyz, const float *dir, size_t m,
                                      const double origin[3], const pnpr_lines_options *opts,
                                      pnpr_polylines *r_lines, pnpr_lines_stats *r_stats);

#ifdef __cplusplus
}
#endif
#endif
