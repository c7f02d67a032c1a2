/* Vector drawings: the strokes, dots, lines and outlines of a rendered frame as paths, for SVG and
 * PDF export (docs/export.md, "Vector drawings"). Pure CPU: the renderer fills a drawing
 * (pnpr_renderer_drawing in render.h, from the frame it drew); this header orders, merges and
 * writes it. */
#ifndef PNPR_DRAWING_H
#define PNPR_DRAWING_H

#include <pointnpr/core.h>

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The layers of a drawing, bottom to top (the order the renderer draws them in). */
typedef enum pnpr_drawing_layer {
    PNPR_LAYER_FILLS = 0,  /* cartoon: the flat colour areas */
    PNPR_LAYER_TONE,       /* sketchy: hatches of the dithering points (tone) */
    PNPR_LAYER_HATCHES,    /* sketchy: hatches of the non-directional feature points */
    PNPR_LAYER_STROKES,    /* sketchy: strokes along the directional feature points */
    PNPR_LAYER_DOTS,       /* stipple: feature and tone dots */
    PNPR_LAYER_LINES,      /* lines: the profile lines */
    PNPR_LAYER_OUTLINES,   /* silhouettes and occluding contours */
    PNPR_LAYER_COUNT_
} pnpr_drawing_layer;

/* Layer names as written in the SVG (inkscape:label) and in messages. */
const char *pnpr_drawing_layer_name(pnpr_drawing_layer layer);

enum {
    PNPR_PATH_CLOSED = 1,  /* the last vertex joins the first */
    PNPR_PATH_DOT = 2,     /* one vertex: a filled disk of diameter `width` */
    PNPR_PATH_FILL = 4,    /* filled (even-odd rule) in its colour, not stroked */
    PNPR_PATH_SUBPATH = 8  /* another subpath of the path before it (the same colour and kind):
                            * holes of a filled area */
};

/* Path i has vertices offset[i] .. offset[i+1]-1 (xy: 2 floats each, pixels, x right, y down,
 * pixel (i, j) covers [i, i+1) x [j, j+1)), is stroked `width[i]` px wide with butt caps and
 * round joins in colour rgba[4 i ..] (straight alpha), and belongs to layer[i]. Paths are in
 * drawing order (the renderer's). Owned by the library: pnpr_drawing_free. */
typedef struct pnpr_drawing {
    int width, height;       /* px; 1 px = 0.75 pt in the PDF (CSS pixels) */
    uint8_t background[4];   /* rgba; alpha 0: no background rectangle */
    size_t count;
    size_t *offset;          /* count + 1 */
    float *xy;
    float *stroke_width;
    uint8_t *rgba;
    uint8_t *layer;
    uint8_t *flags;          /* PNPR_PATH_* */
    size_t cap_paths, cap_vertices;
} pnpr_drawing;

void pnpr_drawing_free(pnpr_drawing *d);

/* Appends a path of n >= 1 vertices. PNPR_ERR_OUT_OF_MEMORY (the drawing unchanged) or
 * PNPR_ERR_INVALID_ARGUMENT (n == 0, a non-finite coordinate or width, an unknown layer). */
PNPR_NODISCARD pnpr_status pnpr_drawing_add(pnpr_drawing *d, const float *xy, size_t n, float width, const uint8_t rgba[4],
                             pnpr_drawing_layer layer, uint8_t flags);

/* Appends the vertex (x, y) to the last path. PNPR_ERR_INVALID_ARGUMENT without paths or for a
 * non-finite vertex; PNPR_ERR_OUT_OF_MEMORY (the drawing unchanged). */
PNPR_NODISCARD pnpr_status pnpr_drawing_extend(pnpr_drawing *d, float x, float y);

/* Appends the centre lines of the ink in a w x h alpha mask (alpha >= threshold; rows top first,
 * or bottom first when bottom_up) as paths in `rgba` on `layer`, each as wide as its band of ink
 * (at least `width` px): the mask thinned to one-pixel curves (Zhang-Suen), traced between ends
 * and junctions (loops closed), centred on the ink and simplified to 0.5 px; a single pixel left
 * is a dot of its blob's area (vector/ink_trace.c). */
PNPR_NODISCARD pnpr_status pnpr_drawing_trace_ink(pnpr_drawing *d, const uint8_t *alpha, int w, int h, int bottom_up, uint8_t threshold,
                                   float width, const uint8_t rgba[4], pnpr_drawing_layer layer);

/* Appends the flat colour areas of a w x h RGBA image (rows top first, or bottom first when
 * bottom_up) as filled paths on `layer`: one path per colour (its first loop, then the others as
 * PNPR_PATH_SUBPATH), traced along the pixel borders and simplified to 0.7 px; pixels of the
 * `background` colour or with alpha 0 are left out (vector/region_trace.c). PNPR_ERR_UNSUPPORTED
 * for an image of more than 65536 colours (not flat areas). */
PNPR_NODISCARD pnpr_status pnpr_drawing_trace_regions(pnpr_drawing *d, const uint8_t *rgba, int w, int h, int bottom_up,
                                       const uint8_t background[4], pnpr_drawing_layer layer);

/* Total length of the paths of `layer` (PNPR_LAYER_COUNT_: all), px. */
double pnpr_drawing_ink_length(const pnpr_drawing *d, pnpr_drawing_layer layer);

/* Pen-up travel: the sum of the distances from each path's last vertex to the next path's first
 * (starting at (0, 0)), px. */
double pnpr_drawing_travel(const pnpr_drawing *d);

/* Merges the straight two-vertex paths of `layer` (hatches) that lie on one line: the same
 * direction within `angle_deg`, the same offset across it within `offset_px`, the same width and
 * colour, and overlapping or separated by at most `gap_px` along it, become one path spanning
 * them. Returns PNPR_OK (the drawing keeps its order: a merged path takes the place of its first
 * part) or PNPR_ERR_OUT_OF_MEMORY (the drawing unchanged). r_merged (may be NULL): paths removed. */
PNPR_NODISCARD pnpr_status pnpr_drawing_merge_collinear(pnpr_drawing *d, pnpr_drawing_layer layer, float angle_deg, float offset_px,
                                         float gap_px, size_t *r_merged);

/* Removes repeated marks: paths of at most two vertices (strokes, hatches, dots) of the same
 * layer, kind, width and colour whose ends (in either order) round to the same points of a grid
 * of `tol` px; the first of them stays, with the opacity of all of them drawn over each other
 * (1 - (1 - a)^k: the ink a frame blends). Duplicate points in a scan draw the same stroke
 * twice, which a pen plotter would draw twice. r_removed (may be NULL): paths removed. */
PNPR_NODISCARD pnpr_status pnpr_drawing_dedupe(pnpr_drawing *d, float tol, size_t *r_removed);

/* Removes the open paths shorter than min_px (a pen plotter draws a mark of a pen's width as a
 * dot); dots, filled areas and closed paths stay. r_removed (may be NULL): paths removed. */
PNPR_NODISCARD pnpr_status pnpr_drawing_drop_short(pnpr_drawing *d, float min_px, size_t *r_removed);

/* Orders the paths of each layer for a pen plotter: greedy nearest neighbour from the previous
 * pen position over the ends of the remaining paths (an open path may be drawn backwards),
 * layers kept in order. PNPR_ERR_OUT_OF_MEMORY leaves the drawing unchanged. */
PNPR_NODISCARD pnpr_status pnpr_drawing_order_for_plotter(pnpr_drawing *d);

/* SVG 1.1: one <g> per non-empty layer, in layer order, marked as an Inkscape layer with its name;
 * paths with their widths and colours; coordinates with 2 decimals; width and height in px.
 * Written through pnpr_output (output.h): a temporary beside `path` renamed over it, "-" =
 * standard output. */
PNPR_NODISCARD pnpr_status pnpr_drawing_write_svg(const pnpr_drawing *d, const char *path, pnpr_error *err);

/* PDF 1.5 through cairo, one page of width x height px at 0.75 pt a px, the same paths (PDF has no
 * named layers in cairo 1.16: the layers are drawn in order). PNPR_ERR_UNSUPPORTED when the
 * library was built without cairo. */
PNPR_NODISCARD pnpr_status pnpr_drawing_write_pdf(const pnpr_drawing *d, const char *path, pnpr_error *err);

#ifdef __cplusplus
}
#endif

#endif
