/* pointnpr — tiles.h: clouds larger than memory, processed tile by tile (docs/tiles.md).
 *
 * A plan lays a grid of at most PNPR_TILE_GRID x PNPR_TILE_GRID cells over the cloud's x/y
 * bounding box, counts the points per cell in one pass over the file, and splits the grid into
 * tiles of at most `tile_points` points by halving cell ranges on their counts (a cell is never
 * split, so a tile of one dense cell may hold more). Every point belongs to exactly one tile's
 * core, by the cell its coordinates fall in (pnpr_tile_cell: the same arithmetic in the plan and
 * in every job; points with NaN/Inf coordinates go to the first or last cell of their axis).
 * A tile job reads its core plus a halo (the points within `halo` of the core's cells in x and y)
 * through the reader's point filter, so that it holds only those; each point read carries its
 * index in the file (PNPR_PROP_SOURCE_INDEX). The jobs are independent; a merge writes their
 * results into one file in input order.
 *
 * Which results are equal to an in-memory run, and how a job checks it per point, is in
 * docs/tiles.md (pnpr_tile_certify). Input: binary PLY with fixed-size vertex records (what
 * pointnpr writes; `pointnpr convert` makes one from any input) and fewer than 2^32 points. */
#ifndef POINTNPR_TILES_H
#define POINTNPR_TILES_H

#include "cloud.h"
#include "io.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PNPR_TILE_GRID 256              /* cells along each axis, at most */
#define PNPR_TILE_POINTS_DEFAULT 4000000 /* core points per tile when not given */
#define PNPR_TILE_HALO_SPACINGS 64      /* automatic halo: this many point spacings (docs/tiles.md) */

typedef struct pnpr_tile_grid {
    double min[2];      /* the grid's corner in x and y (world units) */
    double cell[2];     /* a cell's size in x and y (> 0) */
    uint32_t cells[2];  /* cells along x and y (1..PNPR_TILE_GRID) */
    double origin[3];   /* the origin of every tile's float offsets (files with double
                         * coordinates), as a run in memory takes it: the centre of the box of
                         * the points that are not far outliers (pnpr_cloud_set_world) */
} pnpr_tile_grid;

typedef struct pnpr_tile {
    uint32_t lo[2], hi[2]; /* the core: cells lo <= c < hi along x and y */
    uint64_t points;       /* core points, as counted by the plan */
} pnpr_tile;

typedef struct pnpr_tile_plan {
    uint64_t points;       /* vertices in the file */
    pnpr_tile_grid grid;
    double spacing;        /* the point spacing estimated from the cell counts (0: none) */
    double halo;           /* the halo used (world units) */
    size_t record_bytes;   /* the file's bytes per point (its size over its points; 64 when unknown) */
    uint64_t tile_points;  /* the size asked (or from the memory limit); a tile of one cell may be larger */
    pnpr_tile *tiles;      /* count tiles; release with pnpr_tile_plan_free */
    size_t count;
} pnpr_tile_plan;

/* Zero is the default everywhere. */
typedef struct pnpr_tile_plan_options {
    uint64_t tile_points;  /* 0 = from memory_limit when set, else PNPR_TILE_POINTS_DEFAULT */
    size_t memory_limit;   /* bytes a tile's feature job may take (pnpr_tile_points_for_memory) */
    uint32_t features_k;   /* the jobs' k, for memory_limit (0 = 16) */
    size_t job_bytes;      /* for memory_limit: bytes a job takes per point beyond the file's record
                            * (halo included as PNPR_TILE_HALO_SHARE); 0 = a feature job's for features_k */
    double halo;           /* world units; 0 = PNPR_TILE_HALO_SPACINGS x the estimated spacing */
    pnpr_progress progress; /* the reader's, during the last pass (the counts) */
} pnpr_tile_plan_options;

/* Plans the tiles of the PLY file at path (three to six passes over the file: bounds, one to three
 * that keep far outliers off the grid, counts, and when a point may be a far outlier one for the
 * origin; nothing of the points kept but a stride sample).
 * Errors name the file; a halo < 0 or NaN is PNPR_ERR_INVALID_ARGUMENT. */
PNPR_NODISCARD pnpr_status pnpr_tile_plan_make(const char *path, const pnpr_tile_plan_options *opts,
                                               pnpr_tile_plan *r_plan, pnpr_error *err);
void pnpr_tile_plan_free(pnpr_tile_plan *plan);

/* The most core points a tile's feature job may hold within `limit` bytes: per point, the cloud as
 * read (record_bytes, the file's bytes per point), its source index and core flag, the feature
 * stage's estimate for k neighbours (memory.h) and the certification's neighbour lists, for the
 * core and a halo of PNPR_TILE_HALO_SHARE as many points again. 0 when not even 1000 fit. */
#define PNPR_TILE_HALO_SHARE 0.25
uint64_t pnpr_tile_points_for_memory(size_t limit, size_t record_bytes, uint32_t k);

/* The cell of a point (x, y of p), clamped into the grid; NaN goes to cell 0. */
void pnpr_tile_cell(const pnpr_tile_grid *grid, const double p[3], uint32_t r_cell[2]);
/* A tile's core box, and that box grown by halo, in world units (x0, y0, x1, y1); unbounded on the
 * sides where the tile reaches the grid's edge (its edge cells hold the points beyond it). */
void pnpr_tile_box(const pnpr_tile_grid *grid, const pnpr_tile *tile, double halo, double r_box[4]);
/* Whether the grid and tile are usable: finite corner and origin, finite positive cells,
 * 1..PNPR_TILE_GRID cells, lo < hi within the grid, halo finite and >= 0. PNPR_ERR_INVALID_ARGUMENT with a message otherwise. */
PNPR_NODISCARD pnpr_status pnpr_tile_check(const pnpr_tile_grid *grid, const pnpr_tile *tile, double halo,
                                           pnpr_error *err);

/* Reads one tile of the PLY file at path: its core and halo points, in file order, with
 * PNPR_PROP_SOURCE_INDEX; r_core[i] (malloc'ed, count bytes, release with free) is 1 for a core
 * point, 0 for a halo point. opts: progress (and format) only. */
PNPR_NODISCARD pnpr_status pnpr_tile_read(const char *path, const pnpr_tile_grid *grid, const pnpr_tile *tile,
                                          double halo, const pnpr_read_options *opts, pnpr_cloud *r_cloud,
                                          uint8_t **r_core, pnpr_error *err);

/* After pnpr_compute_features on a tile (core and halo) with k neighbours: which core points
 * have results equal to the in-memory run's (docs/tiles.md): their neighbourhoods, three hops
 * deep, and, for feature points, their 2k nearest feature points, lie inside the tile's box
 * grown by the halo (box: pnpr_tile_box), with every point that could change them exact itself.
 * r_exact (count bytes, may be NULL) gets 1 for those; r_uncertain the core points that are not.
 * Dithering points are chosen per tile (not compared); normals without a viewpoint are equal up
 * to their sign. */
PNPR_NODISCARD pnpr_status pnpr_tile_certify(const pnpr_cloud *cloud, const uint8_t *core, const double box[4],
                                             uint32_t k, int threads, uint8_t *r_exact, size_t *r_uncertain);

/* Writes the tile results at paths[0..count) (clouds with PNPR_PROP_SOURCE_INDEX, all with the
 * same properties; with PNPR_PROP_TILE_CORE, only the points marked 1 are the tile's, the others
 * its halo) as one binary PLY at out, each point at its source index, without those properties.
 * Every index of 0..points-1 must be a core point exactly once: a missing, repeated or
 * out-of-range index fails naming the tile and the index. seams: the tiles' normals were
 * oriented each by its own propagation (no viewpoint): a tile whose halo normals disagree with
 * those already placed for the same points, more often than they agree, has its normals turned,
 * and at the end the highest point's normal faces up (orient.c's rule), else all turn. Holds one
 * tile at a time; out must be a regular file (or a new name): it is written as every output. */
PNPR_NODISCARD pnpr_status pnpr_tile_merge(const char *const *paths, size_t count, uint64_t points, int seams,
                                           const char *out, const pnpr_progress *progress, pnpr_error *err);

/* ---- connected components in tiles (filters/segment_tiles.c) ------------------------------
 * `pointnpr segment --method components` on a file larger than memory: each tile's job runs
 * pnpr_segment_components at one distance on its core and a halo of pnpr_tile_components_halo,
 * keeps both (PNPR_PROP_TILE_CORE) with its own labels, and pnpr_tile_merge_segments joins the
 * tiles' components over the points several tiles read. Labels, their numbering and the mean
 * colours equal a run in memory (docs/tiles.md). Components smaller than a minimum size are not
 * joined to others in tiles (their nearest kept point may lie anywhere). */
struct pnpr_components_options;

/* The distance the components connect at: opts->distance when > 0, else as
 * pnpr_segment_components takes it (a multiple of pnpr_segment_median_spacing over the whole
 * file), found with passes that read the sample and the points near it only (REACH, in the .c).
 * Errors name the file; when the points near the sample are more than a round may read (64M, and
 * what memory_limit bytes hold at the file's record size plus 48; 0: no limit but the 64M),
 * PNPR_ERR_OUT_OF_MEMORY says to give the distance. */
PNPR_NODISCARD pnpr_status pnpr_tile_components_distance(const char *path, const pnpr_tile_plan *plan,
                                                         const struct pnpr_components_options *opts,
                                                         size_t memory_limit, float *r_distance, pnpr_error *err);
/* The halo that holds every point within `distance` of a tile's core, with a margin for the
 * rounding of the float offsets. */
double pnpr_tile_components_halo(const pnpr_tile_grid *grid, float distance);
/* A components job's bytes per point beyond the record (pnpr_tile_plan_options.job_bytes): the
 * source index, core flag, labels, the kd-tree and the union-find. Measured: a 5M-point tile of
 * 15-byte records peaked at 318 MiB (the whole process), 50 bytes a point beyond them; 68 takes
 * 6 more and the 12 of the float offsets that a file of double coordinates holds beside them. */
#define PNPR_TILE_COMPONENTS_BYTES 68
/* A components job on a tile read by pnpr_tile_read (its core flags `core`): the tile's own
 * components at `distance` (> 0; FLT_MIN stands for 0) as PNPR_PROP_TILE_COMPONENT, its core flags
 * as PNPR_PROP_TILE_CORE; the tile is then written as binary PLY for the merge. r_components (may
 * be NULL): the tile's components. */
PNPR_NODISCARD pnpr_status pnpr_tile_components_job(pnpr_cloud *tile, const uint8_t *core, float distance, int threads,
                                                    uint32_t *r_components);
/* Writes the tiles' results (pnpr_tile_components_job's, all with the same properties) as one
 * binary PLY at out, in input order, each point's label (pnpr_cloud.label) the whole cloud's
 * component (numbered by first appearance; points with a non-finite coordinate the last) and,
 * when the tiles have colours, the components' mean colours (pnpr_segment_add_colors); the body is
 * byte for byte the run in memory's. Reads each tile three times; holds one tile, 4 bytes per point
 * of the file and 44 bytes per component of a tile (as many as points at worst: a distance below
 * the spacing). Every index must be a core point exactly once. pnpr_tile_merge refuses these
 * tiles. */
PNPR_NODISCARD pnpr_status pnpr_tile_merge_segments(const char *const *paths, size_t count, uint64_t points,
                                                    const char *out, const pnpr_progress *progress,
                                                    uint32_t *r_segment_count, pnpr_error *err);

#ifdef __cplusplus
}
#endif
#endif
