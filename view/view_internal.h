/* Internal helpers of the cameras (view/camera.c), shared by the SVG line drawings
 * (view/svg_lines.c, view/svg_outline.c) and the renderer (render/render_internal.h includes
 * this header). Pure CPU; not installed. */
#ifndef PNPR_VIEW_INTERNAL_H
#define PNPR_VIEW_INTERNAL_H

#include <pointnpr/camera.h>

#include <stddef.h>
#include <stdint.h>

/* Column-major 4x4 matrices (OpenGL layout): m[col * 4 + row]. */
typedef struct pnpr_frame_camera {
    float view[16], proj[16];
    float pixels_per_unit; /* proj[1][1] * height / 2 (times the view's uniform scale) */
    double near_plane, far_plane; /* eye-space distances (orthographic: may be <= 0) */
    int ortho;             /* orthographic projection: clip w = 1 everywhere */
} pnpr_frame_camera;

/* View and projection for `cam` relative to `origin` (eye - origin computed in double), with
 * automatic near/far from the box [bmin, bmax] (offset coordinates) when the camera leaves
 * them at 0. PNPR_ERR_NUMERIC for non-finite or degenerate cameras. */
pnpr_status pnpr_frame_camera_make(const pnpr_camera *cam, const double origin[3],
                                   const float bmin[3], const float bmax[3], int have_box,
                                   int width, int height, pnpr_frame_camera *r, pnpr_error *err);

/* View and projection from explicit world matrices (pnpr_camera_matrices), the view rebased on
 * `origin` in double. PNPR_ERR_NUMERIC for matrices the renderer cannot use. */
pnpr_status pnpr_frame_camera_from_matrices(const pnpr_camera_matrices *m, const double origin[3],
                                            int width, int height, pnpr_frame_camera *r, pnpr_error *err);

/* Screen pixels covered by the projected box (clipped to the viewport); the whole viewport
 * when a corner is behind the eye. */
double pnpr_box_coverage(const pnpr_frame_camera *fc, const float bmin[3], const float bmax[3],
                         int width, int height);

/* The points of a cloud counted on a grid of cells over its box (cubes, the smallest side for
 * which the grid has at most PNPR_VIEW_CELLS_MAX cells: a long road gets cells of a few metres
 * along its length and across, not 32 slices of its whole width), so that a frame knows how many
 * of them its view can show and each cell's queue is drawn by its depth (renderer.c,
 * docs/rendering.md). */
#define PNPR_VIEW_CELLS_MAX 32768
typedef struct pnpr_view_cells {
    float min[3], cell;   /* the grid's corner and a cell's side (offset coordinates) */
    float inv;            /* 1 / cell: a point's cell is floor((p - min) x inv), clamped to the grid */
    uint32_t n[3];        /* cells along each axis, their product at most PNPR_VIEW_CELLS_MAX */
    uint32_t count[PNPR_VIEW_CELLS_MAX];
} pnpr_view_cells;
/* The grid over [bmin, bmax]: the smallest cubes (side *r_side) with at most `most` (at most
 * PNPR_VIEW_CELLS_MAX) cells, r_n along each axis; one cell of side 1 for a box too small or too
 * large for float cubes, or empty, or `most` below 8. The cells of a file ordered for drawing too
 * (io/ply_lod.c). */
void pnpr_view_cells_grid(const float bmin[3], const float bmax[3], uint32_t most, float *r_side, uint32_t r_n[3]);
/* Counts the n finite points xyz into cells over [bmin, bmax] (points outside go to the edge
 * cells; non-finite ones are not counted). */
void pnpr_view_cells_build(pnpr_view_cells *c, const float *xyz, size_t n, const float bmin[3], const float bmax[3]);
/* The cells of the grid: n[0] x n[1] x n[2]. */
static inline size_t pnpr_view_cells_size(const pnpr_view_cells *c) { return (size_t)c->n[0] * c->n[1] * c->n[2]; }
/* The cell of point p (offset coordinates): (z n[1] + y) n[0] + x, as the shaders find it. */
uint32_t pnpr_view_cells_index(const pnpr_view_cells *c, const float p[3]);
/* Each cell's weight in this view, r_w[k * stride] for cell k: 0 for a cell without points; else
 * the pixels a unit of surface covers there relative to unit distance: 1 / z^2 at the eye depth z
 * of the box's nearest corner (at least the near plane; orthographic: 1): a surface's screen
 * area per point goes as it; negated for a cell whose box lies wholly outside one plane of the
 * frustum (clip space). */
void pnpr_view_cells_weights(const pnpr_view_cells *c, const pnpr_frame_camera *fc, float *r_w, size_t stride);
/* The lambda (>= 0) for which the cells of weight w[k * stride] > 0, each drawing min(1, lambda x w) of
 * its points, draw `want` points in all (cells that would draw more than theirs are full and
 * give the rest to the others): HUGE_VAL when they hold no more than that; 0 for want <= 0. So
 * near and far keep the same points per pixel among the cells not full (renderer.c). */
double pnpr_view_cells_solve(const pnpr_view_cells *c, const float *w, size_t stride, double want);

#endif
