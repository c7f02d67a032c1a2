/* Outlines in image space (not installed): silhouettes and occluding contours from the visibility
 * mask's per-pixel surface info, with sampling holes closed first. See docs/rendering.md,
 * "Silhouettes and contours". */
#ifndef PNPR_EDGES_H
#define PNPR_EDGES_H

#include <pointnpr/core.h>

#include <epoxy/gl.h>

typedef struct pnpr_edges {
    GLuint prog_fill, prog_erode, prog_ink, prog_cover, vao;
    GLint uc_src, uc_block, uf_cover, ue_cover;
    GLuint cover_fbo[2], cover_tex[2]; /* coarse coverage: 32-px blocks of the info, 16-px of tex[0] */
    GLint uf_info, uf_reach, uf_jump, uf_hole, uf_ppu, uf_ortho, uf_surface_reach, uf_skip_level;
    GLint ue_filled, ue_ppu, ue_ortho, ue_inset, ue_inset_max, ue_limit, ue_width, ue_skip_level;
    GLint ui_filled, ui_eroded, ui_width, ui_jump, ui_ink, ui_erase, ui_background;
    GLuint fbo[2], tex[2]; /* the hole-closed info and its minimum filter, frame-sized */
    int w, h;
} pnpr_edges;

/* What one outline pass draws. */
typedef struct pnpr_edge_params {
    float width;         /* outline width in px (> 0) */
    float jump;          /* a contour: depth jump of more than this many mask-disk radii */
    float hole;          /* holes: closed within this many projected mask-disk radii */
    int reach;           /* longest hole march in px */
    float ppu;           /* pixels per world unit at eye distance 1 */
    int ortho;
    float ink[4];        /* straight alpha */
    float inset;         /* silhouettes lie this fraction of the projected mask-disk radius inside
                          * the mask's boundary; the overhang is painted in `background` */
    float background[4]; /* premultiplied */
} pnpr_edge_params;

/* Largest inset in px (the overhang of very large disks is not erased beyond it). */
enum { PNPR_EDGE_MAX_INSET = 8 };

/* Longest march of the hole closing, in pixels (tiles add it to their guard band). */
enum { PNPR_EDGE_MAX_REACH = 32 };
/* Longest hole march from a pixel that shows a surface (holes through which a farther surface is
 * seen), and the block sizes (log2) of the shortcuts' coarse coverage: 2^5 = 32 px (the reach),
 * 2^4 = 16 px (the distance to no surface). */
enum { PNPR_EDGE_SURFACE_REACH = 8, PNPR_EDGE_SKIP_FILL = 5, PNPR_EDGE_SKIP_ERODE = 4 };

/* Programs and the fullscreen VAO; PNPR_ERR_UNSUPPORTED (message in err) when a shader fails. */
pnpr_status pnpr_edges_create(pnpr_edges *e, pnpr_error *err);
void pnpr_edges_release(pnpr_edges *e);

/* Reads `info_tex` (RGBA32F: eye distance, depth extent (0 = no surface), disk radius) of a w x h
 * frame, closes its holes into the edge module's own texture, filters it, then blends the ink into
 * framebuffer `frame_fbo` (its draw buffer 0, premultiplied alpha). Leaves blending enabled,
 * depth test disabled and the frame FBO bound. */
pnpr_status pnpr_edges_draw(pnpr_edges *e, GLuint info_tex, GLuint frame_fbo, int w, int h,
                            const pnpr_edge_params *p, pnpr_error *err);

#endif
