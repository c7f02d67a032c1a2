/* pointnpr — style.h: the drawing styles, their names and what each needs by default (GL-free,
 * core library: the stage planner (plan.h), the renderer, the CLI and MeshLab read them here). */
#ifndef POINTNPR_STYLE_H
#define POINTNPR_STYLE_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pnpr_style {
    PNPR_STYLE_POINTS = 0, /* plain round splats in the point colour (baseline, single pass) */
    PNPR_STYLE_SKETCHY,    /* PointWorks sketch: strokes along feature directions + hatches */
    PNPR_STYLE_LINES,      /* profile lines (pnpr_renderer_set_lines) as dark strokes, hidden parts
                            * removed by the visibility mask of the cloud (section 5.2) */
    PNPR_STYLE_STIPPLE,    /* small dark round dots on the feature and dithering points */
    PNPR_STYLE_CARTOON,    /* flat colours per segment (cloud->label) or quantised, dark silhouettes
                            * from enlarged pass-1 disks (section 5.4) */
    PNPR_STYLE_PAINTERLY,  /* brush dabs in blended colours, large to small over feature-degree bins,
                            * a stencil sky mask, directional strokes on top (section 5.3) */
    PNPR_STYLE_BRUSH,      /* stroke-based splatting (Lopes et al.): Gaussian-sum brush strokes on
                            * surface-aligned splats oriented by Householder frames, blended order-
                            * independently (brush.h, docs/brush.md) */
    PNPR_STYLE_HIERARCHY,  /* Chi & Lee's painterly hierarchy: strokes of sphere-tree nodes chosen by
                            * region abstraction and screen size, smooth level transitions, tonal
                            * art maps, silhouettes, region borders (hierarchy.h, docs/hierarchy.md) */
    PNPR_STYLE_COUNT_
} pnpr_style;

/* The sketchy variants of the paper's figure 9. */
typedef enum pnpr_sketch_variant {
    PNPR_SKETCH_ALL = 0,            /* (c) directional strokes + non-directional + dithering hatches */
    PNPR_SKETCH_DIRECTIONAL,        /* (a) directional strokes only */
    PNPR_SKETCH_NONDIRECTIONAL,     /* (b) directional strokes + non-directional hatches */
    PNPR_SKETCH_COUNT_
} pnpr_sketch_variant;

const char *pnpr_style_name(pnpr_style style);          /* "points", "sketchy", "lines", "stipple", "cartoon", "painterly", "brush", "hierarchy"; "" if invalid */
/* The style of a name, ignoring case ("Sketchy" is sketchy); PNPR_ERR_NOT_FOUND for others. */
PNPR_NODISCARD pnpr_status pnpr_style_from_name(const char *name, pnpr_style *r_style);
/* The style names in order, joined by `sep` (", ", " | "), into buf (cap > 0 bytes, NUL-terminated,
 * truncated to fit); styles whose bit (1u << style) is set in `skip` are left out. Returns buf.
 * Messages and usage texts list the styles with it. */
const char *pnpr_style_list(char *buf, size_t cap, const char *sep, uint32_t skip);
/* Styles drawn from the feature classes (sketchy, stipple, painterly). */
int pnpr_style_needs_features(pnpr_style style);
/* Outline defaults shared by the renderer and the SVG export (docs/rendering.md, "Silhouettes and
 * contours"): a contour is a depth jump of more than PNPR_OUTLINE_JUMP depth extents (3: chosen
 * on the quality scene, where 2 let 8 mm range noise near a scanner ink the ground); sampling
 * holes are closed within PNPR_OUTLINE_HOLE projected disk radii. */
#define PNPR_OUTLINE_JUMP 3.0f
#define PNPR_OUTLINE_HOLE 4.0f
/* The SVG export's outline width in px (pnpr_svg_options.outline_width 0). */
#define PNPR_SVG_OUTLINE_WIDTH 2.0f

/* Whether a style draws outlines by default (1 on / 0 off; lines and cartoon), and the width in px
 * it draws them with, also when they are asked for (r_width may be NULL; 0 for an invalid style). */
int pnpr_style_outline_default(pnpr_style style, float *r_width);

/* One entry of a per-segment style map: points whose segment label (cloud->label) is `label`
 * are drawn in `style`. */
typedef struct pnpr_style_map_entry {
    uint32_t label;
    pnpr_style style;
} pnpr_style_map_entry;

/* A parsed style map file (`pointnpr render --style-map`). */
typedef struct pnpr_style_map {
    pnpr_style_map_entry *entries; /* owned (pnpr_style_map_free), in file order */
    size_t count;
    int have_default;              /* a "* STYLE" line was given: */
    pnpr_style default_style;      /* the style of labels not listed (the last such line) */
} pnpr_style_map;

void pnpr_style_map_free(pnpr_style_map *map); /* frees the entries, leaves a zeroed map; NULL ok */

/* Largest style map file the CLI loads (pnpr_text_file_load). */
#define PNPR_STYLE_MAP_FILE_MAX ((size_t)64 << 20)

/* Parses a style map from memory (`size` bytes; NUL bytes end a line's content): lines
 * "LABEL STYLE" (LABEL in 0..4294967295, STYLE a name of pnpr_style_from_name) and "* STYLE"
 * (the default), '#' comments, blank lines; a line holds at most 1023 characters. `name` names
 * the text in messages (a file name). PNPR_ERR_FORMAT with "NAME:LINE: what is wrong" (err->line
 * set) on a bad line; r_map is zeroed on failure. */
PNPR_NODISCARD pnpr_status pnpr_style_map_parse(const char *text, size_t size, const char *name, pnpr_style_map *r_map,
                                 pnpr_error *err);

#ifdef __cplusplus
}
#endif
#endif
