/* The hierarchy style's GL side (not installed): Chi & Lee's strokes, chosen on the CPU each frame
 * by pnpr_sphere_tree_traverse (hierarchy.h), streamed as instanced quads with the tonal art map
 * as their texture, blended order-independently with the brush style's targets (brush_gl.h). The
 * renderer owns one (renderer_internal.h); renderer_passes.c draws the style with it.
 * docs/hierarchy.md. */
#ifndef PNPR_HIERARCHY_GL_H
#define PNPR_HIERARCHY_GL_H

#include "brush_gl.h"

#include <pointnpr/hierarchy.h>

typedef struct pnpr_hier_gl {
    GLuint prog, vao, vbo[2], tex;
    GLint u_view, u_proj, u_brush, u_oit, u_weight;
    int tam;                       /* the map in `tex`; -1 = none yet */
    pnpr_hier_stroke *buf[2];      /* the frame's strokes: the first layer (+ ink), the fine layer */
    size_t cap[2];
    const pnpr_sphere_tree *tree;  /* borrowed (pnpr_renderer_set_hierarchy) */
} pnpr_hier_gl;

pnpr_status pnpr_hier_gl_create(pnpr_hier_gl *h, pnpr_error *err);
void pnpr_hier_gl_release(pnpr_hier_gl *h);

/* What one hierarchy pass draws. */
typedef struct pnpr_hier_pass {
    const float *view, *proj;      /* the frame's camera (offsets from the renderer's origin) */
    const float *image_proj;       /* tiles: the whole image's projection */
    const double *origin;          /* the renderer's origin */
    int width, height;
    float pixels_per_unit;
    int ortho;
    const float *lod_view, *lod_proj; /* the camera that chooses the strokes (NULL = view, proj) */
    float lod_pixels_per_unit;
    pnpr_hier_params params;       /* the style's options, ink filled in */
    int stencil;                   /* > 0: only where the stencil equals it (style maps) */
    GLuint frame_fbo;
} pnpr_hier_pass;

/* Traverses the tree, draws the paint strokes (and the fine layer), then the silhouettes and
 * borders, each blended order-independently and resolved over the frame (the OIT targets made
 * with pnpr_brush_gl_targets first). Returns the paint strokes drawn; *r_counts (may be NULL) the
 * traversal's counts. PNPR_ERR_OUT_OF_MEMORY when the stroke buffers cannot grow. */
pnpr_status pnpr_hier_gl_draw(pnpr_hier_gl *h, pnpr_brush_gl *oit, const pnpr_hier_pass *p, pnpr_hier_counts *r_counts);

#endif
