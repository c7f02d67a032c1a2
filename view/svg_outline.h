/* Outlines (silhouettes and occluding contours) of a point cloud as vector polylines, for the SVG
 * export (not installed). The rules are those of the renderer's image-space outlines
 * (docs/rendering.md, "Silhouettes and contours"), run on a CPU surface buffer; the tracing is
 * described in docs/lines.md ("Outlines in the SVG"). */
#ifndef PNPR_SVG_OUTLINE_H
#define PNPR_SVG_OUTLINE_H

#include "view_internal.h"

/* Polylines in pixel coordinates of the drawing (x right, y down, pixel (i, j) covers
 * [i, i+1) x [j, j+1)). Polyline k has vertices offset[k] .. offset[k+1]-1. */
typedef struct pnpr_outline_set {
    size_t count;
    size_t *offset;    /* count + 1 entries (NULL when count is 0) */
    double *xy;        /* 2 per vertex */
    uint8_t *closed;   /* 1: the last vertex joins the first */
    size_t cap_lines, cap_vertices;
} pnpr_outline_set;

/* The fixed parameters of the rules (the renderer's defaults). */
enum {
    PNPR_OUTLINE_REACH = 32,        /* longest hole march in px (from any pixel: the renderer
                                     * marches 8 px from a pixel that shows a surface, for speed) */
    PNPR_OUTLINE_MAX_INSET = 32,    /* largest silhouette / contour inset in px */
    PNPR_OUTLINE_MAX_DISK = 64      /* largest disk radius in px */
};

/* Outlines of `cloud` (offsets shifted by `shift` into the camera's frame) seen through `fc` in
 * a w x h drawing: a depth jump of more than `jump` (> 0) depth extents is a contour. The result
 * replaces *r (free it with pnpr_outline_set_free). PNPR_ERR_OUT_OF_MEMORY when the buffers do
 * not fit; an empty or all-NaN cloud gives no polylines. */
pnpr_status pnpr_svg_outlines(const pnpr_cloud *cloud, const double shift[3], const pnpr_frame_camera *fc,
                              int w, int h, float jump, pnpr_outline_set *r, pnpr_error *err);
void pnpr_outline_set_free(pnpr_outline_set *s);

#endif
