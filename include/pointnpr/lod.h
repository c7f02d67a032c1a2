/* pointnpr — lod.h: a PLY file ordered for drawing (io/ply_lod.c; docs/tiles.md "A file ordered
 * for drawing").
 *
 * `pointnpr convert IN.ply -o OUT.ply --lod` writes the points of IN again, every one, in an
 * order that lets `render` and `animate` read only what a view needs from a cloud larger than
 * memory, in the spirit of Potree's octree (Schütz 2016) but flat:
 *  - the cells: the smallest cubes, at most PNPR_VIEW_CELLS_MAX of them and at most one for 8
 *    points, over the box of the finite points that are not far outliers (outliers.h: the robust
 *    centre and extent of a stride sample) (the renderer's grid, view/view_cells.c); one more
 *    cell last for the far outliers and the points with a non-finite coordinate (a view reads all
 *    of them);
 *  - in each cell, PNPR_LOD_LEVELS runs by a rank of the point: its source index's hash, a number
 *    in [0, 1). Run 0 holds ranks below 2^-(L-1), run j > 0 ranks in [2^(j-L), 2^(j+1-L)): a
 *    prefix of a cell's runs is a uniform sample of it, which doubles with each run;
 *  - a point read keeps a rank of its own, uniform in its run's range (pnpr_lod_rank), so that a
 *    sample keeps a point exactly when its rank is below its share: the same points whatever the
 *    ranges read, as long as they hold every run whose lower bound is below the share.
 * The file stays an ordinary binary little-endian PLY (every reader reads every point): a header
 * comment holds the grid ("comment pnpr_lod 1 levels L grid NX NY NZ side S origin X Y Z") and an
 * element after the vertices, `pnpr_lod_run` with one `uint count` per run (cell by cell), the
 * index. Choice: one file rather than a folder of nodes (Potree's): nothing to keep together,
 * and MeshLab opens it. */
#ifndef POINTNPR_LOD_H
#define POINTNPR_LOD_H

#include <pointnpr/core.h>
#include <pointnpr/crq.h>
#include <pointnpr/io.h>

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PNPR_LOD_LEVELS 16
#define PNPR_LOD_VERSION 1

typedef struct pnpr_lod {
    uint64_t points;    /* vertices (fewer than 2^32) */
    double origin[3];   /* the grid's corner (world coordinates) */
    double side;        /* a cell's side */
    uint32_t n[3];      /* cells along each axis */
    uint32_t cells;     /* n[0] n[1] n[2]; cell `cells` holds the far outliers and the points with a
                         * non-finite coordinate */
    uint32_t *start;    /* (cells + 1) x PNPR_LOD_LEVELS + 1 entries: run r's first vertex (cell k's
                         * run j is r = k L + j), the last the vertex count */
} pnpr_lod;

typedef struct pnpr_lod_options {
    size_t memory;       /* bytes the points held at once may take: chunks of whole cells, each
                          * point its record x 1.5 and 40 bytes to order it (0: all at once) */
    size_t max_passes;   /* refuse (PNPR_ERR_OUT_OF_MEMORY, before writing) when the chunks would
                          * take more passes over the input than this (0: any number) */
    pnpr_progress progress; /* stages "lod scan" (the passes over the input) and "lod write" */
} pnpr_lod_options;

/* Writes the points of the binary PLY `in` (fixed-size records) to `out` ordered for drawing:
 * two passes over `in` (its box, the runs' counts; one more for the box without the far outliers
 * when there are some), then one more for each chunk of cells that fits in `memory`. Every
 * property of every point is kept (records as pointnpr convert writes them); out is written as
 * every output is (output.h), never over in. A file with faces or any element but its vertices is
 * refused (PNPR_ERR_UNSUPPORTED, naming them). *r_points: the points written. */
PNPR_NODISCARD pnpr_status pnpr_lod_write(const char *in, const char *out, const pnpr_lod_options *opts,
                                          uint64_t *r_points, pnpr_error *err);

/* The order of the file at path (its header and index; the points are not read).
 * PNPR_ERR_UNSUPPORTED when it is not a file ordered for drawing (no pnpr_lod comment: an
 * ordinary PLY, or another format); PNPR_ERR_FORMAT, naming the file and what is wrong, when it
 * says it is one but its header or index lies (counts that do not add up, a grid out of range, a
 * truncated index). Release with pnpr_lod_free. */
PNPR_NODISCARD pnpr_status pnpr_lod_open(const char *path, pnpr_lod *r_lod, pnpr_error *err);
/* The same from a whole file in memory. */
PNPR_NODISCARD pnpr_status pnpr_lod_parse(const void *data, size_t size, pnpr_lod *r_lod, pnpr_error *err);
void pnpr_lod_free(pnpr_lod *lod);

/* The cell of world point p: lod->cells when a coordinate is not finite or p lies outside the
 * grid (a far outlier). */
uint32_t pnpr_lod_cell(const pnpr_lod *lod, const double p[3]);
/* The points of cell k (k = lod->cells: the far outliers and non-finite points). */
static inline uint32_t pnpr_lod_cell_points(const pnpr_lod *lod, uint32_t k)
{
    return lod->start[((size_t)k + 1) * PNPR_LOD_LEVELS] - lod->start[(size_t)k * PNPR_LOD_LEVELS];
}
/* A ball that holds every point of cell k < lod->cells. */
void pnpr_lod_cell_ball(const pnpr_lod *lod, uint32_t k, double r_centre[3], double *r_radius);
/* The hash that samples points by their index (splitmix64's finaliser): the samples of
 * render and animate and the runs of a file ordered for drawing. */
uint64_t pnpr_lod_hash(uint64_t i);
/* The run (0 .. PNPR_LOD_LEVELS - 1) of the point of source index i (by its hash). */
int pnpr_lod_run_of(uint64_t i);
/* Run j's ranks: [low, high). */
double pnpr_lod_run_low(int j);
double pnpr_lod_run_high(int j);
/* The rank of vertex v of the file, of run j: uniform in the run's range, by v's hash. */
double pnpr_lod_rank(uint64_t v, int j);

/* The vertex ranges to read (pnpr_read_options.ranges) for each cell's share: cell k's runs whose
 * lower bound is below share[k] (share: cells + 1 values; 0 reads nothing of the cell), adjacent
 * ranges merged. r_ranges: room for 2 (cells + 1) values; r_runs (NULL: none): each cell's runs
 * read, m of them being the sample of ranks below 2^(m - PNPR_LOD_LEVELS). Returns the ranges
 * written. */
size_t pnpr_lod_ranges(const pnpr_lod *lod, const double *share, uint64_t *r_ranges, uint8_t *r_runs);
/* The run of vertex v: *cursor (start at 0) is the run of the previous call, for calls in
 * ascending v (each call then costs O(1) amortised); v < lod->points. */
int pnpr_lod_run_at(const pnpr_lod *lod, uint64_t v, size_t *cursor);

/* Whether vertex v is in the sample of `share`: its rank below the share. lod NULL: an ordinary
 * file, whose rank is the hash of v (pnpr_lod_hash); else v's rank in its run (pnpr_lod_run_at's
 * cursor, for ascending v). */
int pnpr_lod_kept(const pnpr_lod *lod, uint64_t v, size_t *cursor, double share);

/* The points a sample opened for viewing holds unless asked for another count (MeshLab's "NPR:
 * Open a sample of a large PLY"). */
#define PNPR_LOD_SAMPLE_POINTS 5000000

/* A uniform sample of about `points` of the binary PLY at path (every point when it has no more):
 * each point kept when its rank is below points / its count, read through the point filter
 * (opts: progress; no keep). A file ordered for drawing reads only the runs that share reaches;
 * another file takes a pass over its coordinates to count them first (one whose index lies is read
 * so). *r_total (may be NULL): the file's points; *r_ordered (may be NULL): 1 when the order
 * was used. */
PNPR_NODISCARD pnpr_status pnpr_lod_read_sample(const char *path, uint64_t points, const pnpr_read_options *opts,
                                                pnpr_cloud *cloud, uint64_t *r_total, int *r_ordered, pnpr_error *err);

/* ---- a sample by views (io/lod_read.c): render and animate with cameras, the MeshLab
 * decoration's stream ------------------------------------------------------------------------ */

/* The cells into v's histograms (crq.h), each with its points at the least depth one of them may
 * have in the views: a bound that counts too many points in view (c solved on it is too small),
 * without reading a point. Not the last cell (far outliers, non-finite), which the passes read
 * whole. */
void pnpr_lod_add_cells(const pnpr_lod *lod, pnpr_view_sample *v);
/* The ranges of a pass (r_ranges: 2 (cells + 1) values, r_runs: cells + 1, *r_count: the ranges):
 * each cell's runs that the share of its points may reach, by the views of v once solved (its
 * ball's share, pnpr_view_sample_ball_share; the last cell whole) or `uniform` (v NULL). Returns
 * the points the ranges hold, or -1 when memory runs out. */
double pnpr_lod_plan_ranges(const pnpr_lod *lod, const pnpr_view_sample *v, double uniform, uint64_t *r_ranges,
                            uint8_t *r_runs, size_t *r_count);
/* v solved on the cells' bound (pnpr_lod_add_cells, pnpr_view_sample_solve) made again from the
 * points of the runs that bound reaches, each standing for the points of its cell's runs not read,
 * and solved for want (and frame_want, pnpr_view_sample_solve): c as a pass over every point of
 * the file at path would give it, to sampling noise. One pass over those ranges (progress may be
 * NULL). */
PNPR_NODISCARD pnpr_status pnpr_lod_view_refine(const char *path, const pnpr_lod *lod, pnpr_view_sample *v,
                                                double want, double frame_want, const pnpr_progress *progress,
                                                pnpr_error *err);

/* The stored point spacing (PNPR_PROP_POINT_SPACING, float; the renderer's disk radii) of a
 * sample grown by 1/sqrt of each point's share, as the spacing of a thinned surface grows: the
 * share by the views of v once solved, or `uniform` (v NULL). Returns the whole cloud's mean
 * spacing as the sample estimates it (each point standing for 1/share of them, with its spacing
 * before growing): the tone hatches' length (pnpr_upload_options.tone_radius), which the grown
 * spacing would stretch; 0 without a stored spacing. */
float pnpr_lod_grow_spacing(pnpr_cloud *cloud, const pnpr_view_sample *v, double uniform);

typedef struct pnpr_lod_read_info {
    uint64_t total;    /* the file's points */
    uint64_t visited;  /* the points of the ranges the last pass read (ordered), else total */
    uint64_t in_view;  /* the points some view sees (estimated from the runs read when ordered) */
    int ordered;       /* 1: the file's order was used */
} pnpr_lod_read_info;

/* A sample of about `points` of the binary PLY at path for the views of v (pnpr_view_sample_init,
 * add_view or init_frames, no points added: its histograms and c are filled here), as render
 * draws a cloud larger than memory from a camera: every point kept whose rank is below its share
 * min(1, c / z^2) (0 out of view), c solved so that about `points` are kept (every point in view
 * when they are fewer; none for 0). A file ordered for drawing: the cells' bound, a pass over the
 * runs it reaches (pnpr_lod_view_refine), then the read of the runs the share reaches. Another
 * binary PLY: a pass over the coordinates, then the read. opts: progress over both passes
 * (stage "sample"; cancelling stops at the next report with PNPR_ERR_CANCELLED), the origin;
 * no keep, no ranges. *r_info (may be NULL) on success. */
PNPR_NODISCARD pnpr_status pnpr_lod_read_view(const char *path, pnpr_view_sample *v, uint64_t points,
                                              const pnpr_read_options *opts, pnpr_cloud *cloud,
                                              pnpr_lod_read_info *r_info, pnpr_error *err);

#ifdef __cplusplus
}
#endif
#endif
