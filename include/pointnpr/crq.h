/* pointnpr — crq.h: the continuous resolution queue (PointWorks section 4.4) of the renderer:
 * the order in which a frame draws each group's points (a prefix of it) and how a frame's point
 * budget is shared among the groups. Pure CPU, in the core library `pointnpr` (view/crq.c); the
 * renderer (render.h, which includes this header) builds its queue with it at upload. */
#ifndef POINTNPR_CRQ_H
#define POINTNPR_CRQ_H

#include "core.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The queue order: a permutation of 0..count-1 grouped by `group` (group g's points come before
 * group g+1's; groups are 0..group_count-1, points with group >= group_count go last, in
 * their own group) and randomly shuffled inside each group with a generator seeded by `seed`
 * (same inputs, same order, on every machine). group may be NULL (one group).
 * r_group_start (optional, group_count + 2 entries) receives where each group starts, the
 * "other" group last, then count. */
PNPR_NODISCARD pnpr_status pnpr_crq_order(size_t count, const uint8_t *group, uint32_t group_count,
                           uint64_t seed, uint32_t *r_order, size_t *r_group_start);

/* How many points of each group a frame draws: `total` points shared among the groups in
 * proportion to their sizes (floor, then the largest remainders, ties to the lower group), so
 * that the counts sum to min(total, sum of sizes) exactly. */
void pnpr_crq_split(const size_t *group_size, size_t group_count, size_t total, size_t *r_draw);

/* ---- per-cell queues (PointWorks section 4.4: each object its own queue, drawn by the screen
 * space it covers) ----------------------------------------------------------------------------
 * The points of each group are also split by cell (the renderer's grid, view/view_cells.c); each
 * (group, cell) is its own queue, its points in the group's random order. A point's key is its
 * place in its queue as a fraction in PNPR_CRQ_KEYS steps, (rank + offset) / count, with an
 * offset in [0, 1) per queue so that a prefix of any fraction f holds f x count points on
 * average: the queues in order (group-major, then by cell) take the golden-ratio sequence
 * frac(s + m x 0.618...) from a start s drawn from the seed, so that the rounding of the queues
 * cancels out (the points drawn of a fraction f of all are f x all within a few). The group is then sorted by key, stable: every queue's prefix of fraction f lies in
 * the group's prefix of the keys below f, and a frame draws cell k's points whose key + 0.5 is
 * below its end E_k (PNPR_CRQ_KEYS x the fraction it wants), the vertex shaders dropping the
 * others (docs/rendering.md, "Continuous resolution queue"). */
#define PNPR_CRQ_KEYS 65536

typedef struct pnpr_crq_cells {
    size_t groups, cells;
    uint32_t *count; /* [g * cells + k]: the points of group g in cell k */
    uint32_t *cum;   /* [g * (PNPR_CRQ_KEYS + 1) + v]: the points of group g with a key below v */
    float *offset;   /* [g * cells + k]: the offset of queue (g, k) */
} pnpr_crq_cells;

/* The key of the point of rank `rank` of a queue of `count` points with offset `offset`. */
uint16_t pnpr_crq_key(size_t rank, size_t count, double offset);
/* The cell (< cells) of point `point`: the caller's grid (no array of them is kept). */
typedef uint32_t (*pnpr_crq_cell_fn)(const void *user, uint32_t point);
/* Sorts each group of `order` (a pnpr_crq_order result, group g at group_start[g] ..
 * group_start[g + 1]) by key, stable, cell_of(user, order[q]) being point order[q]'s cell;
 * r_key[q]: the key of the point at queue position q after the sort. Scratch: 4 bytes a point
 * of the largest group. Fills *r (free with pnpr_crq_cells_free; zeroed on failure, and
 * PNPR_ERR_INVALID_ARGUMENT for a cell out of range). */
PNPR_NODISCARD pnpr_status pnpr_crq_cells_make(uint32_t *order, const size_t *group_start, size_t groups,
                                               pnpr_crq_cell_fn cell_of, const void *user, size_t cells,
                                               uint64_t seed, uint16_t *r_key, pnpr_crq_cells *r);
void pnpr_crq_cells_free(pnpr_crq_cells *q);
/* The prefix of group g holding every point whose key + 0.5 is below `end`. */
size_t pnpr_crq_cells_prefix(const pnpr_crq_cells *q, size_t g, float end);
/* The points a frame draws: over every group and cell k, those whose key + 0.5 is below
 * end[k * stride] (exactly as the shaders test it). */
size_t pnpr_crq_cells_drawn(const pnpr_crq_cells *q, const float *end, size_t stride);

/* ---- a sample for a view or a camera path (view/view_sample.c) -----------------------------
 * A cloud larger than memory drawn from known cameras: read the sample that their frames need
 * instead of a uniform one. A point that no view sees (outside every view's cone: the half-angle
 * of its diagonal, widened by PNPR_VIEW_SAMPLE_MARGIN, since disks reach in from outside; or
 * behind the eye) gets the share 0; the others min(1, c / z^2), z the least eye depth among the
 * views that see it, so that surfaces near and far keep about as many points per pixel in the
 * frame that sees them nearest (the renderer's per-cell queues then thin each frame by depth in
 * the same way). c comes from a histogram of those depths (PNPR_VIEW_SAMPLE_BINS bins, 16 an
 * octave from 2^-64, each with its count and its sum of 1/z^2, exact but in the one or two bins
 * where the share reaches 1) so that the expected count is `want`.
 * Use: init with the first view and add the others, or init_frames with a camera path's frames (up
 * to PNPR_VIEW_SAMPLE_VIEWS views, widened to stand for the frames between), add every point (a pass over the coordinates), solve, then keep
 * each point with its share (e.g. by a hash of its index). World coordinates throughout. */
#define PNPR_VIEW_SAMPLE_BINS 2048
#define PNPR_VIEW_SAMPLE_MARGIN 1.15
#define PNPR_VIEW_SAMPLE_VIEWS 64

/* A histogram of eye depths (in view only). */
typedef struct pnpr_view_depths {
    uint64_t visible;          /* depths added */
    double z_min, z_max;       /* their range (the solve's bounds) */
    uint64_t count[PNPR_VIEW_SAMPLE_BINS];
    double inv_z2[PNPR_VIEW_SAMPLE_BINS]; /* sum of 1/z^2 over the bin's depths */
} pnpr_view_depths;

typedef struct pnpr_view_sample {
    int views;
    /* by axis, then view (the cone tests of all views in one loop): the cone's apex (the eye, or
     * behind it for a widened view) and its axis, unit, 0 in the slots after `views` (their
     * depth is never positive) */
    double eye[3][PNPR_VIEW_SAMPLE_VIEWS], forward[3][PNPR_VIEW_SAMPLE_VIEWS];
    double tan2[PNPR_VIEW_SAMPLE_VIEWS]; /* the squared tangent of each view's cone's half-angle */
    /* a widened view (init_frames): its apex's distance behind the eye, the reach of the frames
     * it stands for and the cosine of their largest own half-angle (a plain view: 0, 0, 1) */
    double back[PNPR_VIEW_SAMPLE_VIEWS], reach[PNPR_VIEW_SAMPLE_VIEWS], cos_own[PNPR_VIEW_SAMPLE_VIEWS];
    double tan2_own[PNPR_VIEW_SAMPLE_VIEWS]; /* the view's own cone before widening (its frame's) */
    int widened;               /* some view is widened (init_frames with more frames than views) */
    double c;                  /* share = min(1, c / z^2); 0 until solved, HUGE_VAL: every point seen */
    pnpr_view_depths least;    /* each point's least depth among the views that see it */
    pnpr_view_depths *each;    /* NULL, or one histogram per view (caller-owned, `views` of them,
                                * zeroed): the depths its own frame sees (before widening), for
                                * the frame's cap of pnpr_view_sample_solve with more than one view */
} pnpr_view_sample;

/* A look-at view: eye and target apart and finite, fov_deg (vertical) in (0, 180), width and
 * height > 0; PNPR_ERR_INVALID_ARGUMENT otherwise. init empties v (each: NULL) and makes this
 * its only view; add_view adds one (PNPR_ERR_INVALID_ARGUMENT when v holds
 * PNPR_VIEW_SAMPLE_VIEWS already). Views are added before points. */
PNPR_NODISCARD pnpr_status pnpr_view_sample_init(pnpr_view_sample *v, const double eye[3], const double target[3],
                                                 double fov_deg, int width, int height);
PNPR_NODISCARD pnpr_status pnpr_view_sample_add_view(pnpr_view_sample *v, const double eye[3],
                                                     const double target[3], double fov_deg, int width, int height);
/* The views of a camera path's n frames (frame f: eyes[3 f..], targets[3 f..], fovs[f] vertical
 * degrees, all at width x height): up to PNPR_VIEW_SAMPLE_VIEWS of them, spread evenly over the
 * frames with the first and the last. With more frames than views, each view also stands for the
 * frames between it and its neighbours: its cone's half-angle grows by how far they turn (their
 * own half-angle plus the angle between the directions; at most 89.9 degrees), its apex moves
 * back along its axis by reach / sin(half-angle), reach the farthest of their eyes, so that its
 * cone holds theirs (unless a frame looks more than 89.9 degrees off the view's axis with its own
 * half-angle: a path that whips round between two views loses what only that frame sees; its
 * neighbours' views cover it on a smooth path), and a point's depth in it is the least those frames may see it at: (its
 * distance from the eye - reach) x the cosine of their largest own half-angle, at most its depth
 * from the eye (at least 1e-6 of its depth from the apex). Empties v first (each:
 * NULL). PNPR_ERR_INVALID_ARGUMENT when a frame is not a look-at view (eye and target apart and
 * finite, fov in (0, 180)) or n is 0. */
PNPR_NODISCARD pnpr_status pnpr_view_sample_init_frames(pnpr_view_sample *v, const double *eyes,
                                                        const double *targets, const double *fovs, size_t n,
                                                        int width, int height);
/* The least eye depth of p among the views that see it, else 0 (also for NaN and Inf). */
double pnpr_view_sample_depth(const pnpr_view_sample *v, const double p[3]);
void pnpr_view_sample_add(pnpr_view_sample *v, const double p[3]);
/* p standing for n points (a point of a uniform sample of 1/n of them). */
void pnpr_view_sample_add_n(pnpr_view_sample *v, const double p[3], uint64_t n);
/* Empties the histograms (each's too) and c; the views stay. */
void pnpr_view_sample_clear(pnpr_view_sample *v);
/* c for an expected count of `want` points (every point in view when fewer were added; none
 * when want is not positive), and when frame_want > 0 at most the c with which the frame that
 * needs the most draws frame_want points of its own: the largest of each view's own c (with one
 * view: its depths are `least`; with more: from `each`, no cap without it). Depths beyond 1e150
 * are out of view (their squares overflow). */
void pnpr_view_sample_solve(pnpr_view_sample *v, double want, double frame_want);
/* The share of p once solved: 0 out of view, else min(1, c / z^2). */
double pnpr_view_sample_share(const pnpr_view_sample *v, const double p[3]);
/* Balls instead of points (the cells of a file ordered for drawing, pointnpr/lod.h): add_ball
 * adds n points at the least depth a point within rho of c may have in the views that may see
 * one (at PNPR_VIEW_SAMPLE_NEAR when the ball reaches an eye), to each view's own histogram too;
 * ball_share is at least the share of every point in the ball once solved (1 when it reaches an
 * eye, 0 when no view sees any of it). */
#define PNPR_VIEW_SAMPLE_NEAR 1e-100
void pnpr_view_sample_add_ball(pnpr_view_sample *v, const double c[3], double rho, uint64_t n);
double pnpr_view_sample_ball_share(const pnpr_view_sample *v, const double c[3], double rho);

#ifdef __cplusplus
}
#endif
#endif
