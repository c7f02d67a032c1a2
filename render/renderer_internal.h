/* The renderer's state and the declarations its sources share. Not installed. The sources:
 *   renderer.c           create / destroy, the draw options check, the frame plan, the draw entry
 *                        (one frame or one tile: clear, style passes, outlines, composite)
 *   renderer_upload.c    pnpr_renderer_set_cloud (spacing radii, queue order, vertices, painterly
 *                        data), pnpr_renderer_set_lines, the style-map bytes
 *   renderer_passes.c    the visibility mask pass and the style passes (points, cartoon, sketchy,
 *                        stipple, lines, painterly, style maps)
 *   renderer_snapshot.c  read back, snapshots in tiles
 *   renderer_textures.c  the stroke and brush textures
 *   brush_gl.c           the brush style (stroke-based splatting): programs, buffer, blending
 *   hierarchy_gl.c       the hierarchy style (Chi & Lee): the traversal's strokes, tonal art maps
 *   vector.c             reads a drawn frame back as paths (pnpr_renderer_drawing) */
#ifndef PNPR_RENDERER_INTERNAL_H
#define PNPR_RENDERER_INTERNAL_H

#include "render_internal.h"
#include "brush_gl.h"
#include "hierarchy_gl.h"
#include "edges.h"

#include <pointnpr/options.h>

#include <epoxy/gl.h>

#include <stddef.h>
#include <stdint.h>

/* Queue groups: with features, one queue per class (as the paper groups them); else one. */
enum { GROUP_DIRECTIONAL = 0, GROUP_NONDIRECTIONAL, GROUP_DITHER, GROUP_NONE, GROUP_MAX };

enum { PNPR_PAINT_MAX_BRUSH = 4 }; /* painterly: the largest brush, in disk radii */
enum { LINE_FLOATS = 7 }; /* a line segment: its two ends and its polyline's length */
enum { STROKE_TEX_W = 128, STROKE_TEX_H = 32, STROKE_LAYERS = 4, STROKE_LAYER_HATCH = 3 };
/* sketchy: the ink alpha of the dithering (tone) hatches, relative to the feature strokes: they
 * cover most of the picture, and how much a mark moving by a fraction of a pixel changes the
 * pixels goes with its darkness (docs/export.md, "Temporal coherence") */
#define SKETCH_TONE_INK 0.8f
/* sketchy: hatches follow the surface: the world direction HATCH_DIR projected onto the point's
 * tangent plane, HATCH_DIR2 where the normal lies within about 18 degrees of HATCH_DIR
 * (stroke.vert.glsl reads them as PNPR_HATCH_DIR / PNPR_HATCH_DIR2, written into every shader by
 * pnpr_shader_prelude from these values; vector.c reads them too) */
#define HATCH_DIR 0.57735027f, 0.57735027f, 0.57735027f
#define HATCH_DIR2 0.70710678f, -0.70710678f, 0.0f

/* painterly: bytes per blended colour (RGB; the shader's attribute takes alpha 1), per pass and
 * point in paint_col_vbo (level-major: vertex i's colour at pass L at (L * count + i) * this) */
#define PAINT_COL_BYTES 3

typedef struct pnpr_vertex {
    float pos[3];
    float radius;
    uint8_t rgba[4];
    float dir[3];
    uint8_t flat[4]; /* cartoon: the segment's mean colour (the point colour without labels) */
    int8_t normal[4]; /* unit normal * 127 (orientation does not matter); all 0 = unknown */
} pnpr_vertex;

typedef struct splat_uniforms { GLint view, proj, ppu, radius_scale, depth_push, max_size, fade, fade_color, fixed_size, levels, ortho, thin, fade_in; } splat_uniforms;
typedef struct line_uniforms { GLint view, proj, viewport, width, near_plane, ink, pull, ortho, ppu, min_px; } line_uniforms;
typedef struct stroke_uniforms {
    GLint view, proj, viewport, ppu, length, width, radius_scale, mode, strokes, layer, ink, ink_from_points, thin, fade_in,
        tone_radius, half_max;
} stroke_uniforms;

typedef struct paint_uniforms { GLint view, proj, ppu, radius_scale, max_size, style_filter, brush; } paint_uniforms;

enum { PAINT_MAX_BINS = PNPR_PAINTERLY_BINS_MAX, PAINT_K = 12, BRUSH_TEX = 64 };

struct pnpr_renderer {
    GLuint prog_splat, prog_stroke, prog_composite, prog_line, prog_paint;
    paint_uniforms up;
    /* painterly (section 5.3): the points again, sorted by feature degree into bins (each bin a
     * queue), and one blended colour per point and pass (level-major) */
    GLuint paint_vbo, paint_col_vbo, vao_paint, brush_tex;
    size_t paint_bins;                       /* 0: no painterly data (no feature degree) */
    int paint_skipped;                       /* ... or left out (pnpr_upload_options.skip_painterly) */
    size_t paint_start[PAINT_MAX_BINS + 2];
    splat_uniforms us;
    line_uniforms ul;
    stroke_uniforms ut;
    GLint uc_frame, uc_origin;
    GLuint vbo, vao_points, vao_strokes, vao_empty, vao_flat;
    GLuint line_vbo, vao_lines;
    GLuint stroke_tex;
    GLuint fbo, color_tex, depth_rb;
    GLuint info_tex;     /* attachment 1: the mask's surface info (eye distance, depth extent, radius) */
    pnpr_edges edges;    /* outlines from it (edges.c) */
    pnpr_brush_gl brush; /* the brush style (brush_gl.c) */
    pnpr_hier_gl hier;   /* the hierarchy style (hierarchy_gl.c) */
    int fb_w, fb_h;
    float max_point_size;
    GLint max_size;      /* min of GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS */
    float max_radius;    /* largest disk radius of the uploaded cloud (tile guard bands) */
    float mean_radius;   /* mean disk radius (the lines' depth tolerance) */
    float tone_radius;   /* the tone hatches' length in radii: pnpr_upload_options.tone_radius or the mean */
    /* the uploaded cloud */
    size_t count;
    size_t group_start[GROUP_MAX + 2];
    size_t group_count;
    int has_features, has_labels, has_rgb;
    double origin[3];
    float bmin[3], bmax[3];
    pnpr_view_cells view_cells; /* the points per cell: how many a frame's view may show */
    /* per-cell queues (crq.h): the vertices' keys (uint16, main and painterly order), the queues
     * of the groups and of the painterly bins, and the frame's table: per cell its end, fade-in
     * length and disk growth (4 floats; cell_table, in cells_buf as a buffer texture) */
    GLuint key_vbo, paint_key_vbo, cells_buf, cells_tex;
    pnpr_crq_cells queue, paint_queue;
    float *cell_table;
    size_t cells;
    pnpr_queue_uniforms uq_splat, uq_stroke, uq_paint;
    /* style maps (intermingled styles): one style byte per vertex (attribute 4) in the main
     * order (style_vbo) and in the painterly order (paint_style_vbo); the labels and the
     * painterly order's main indices to fill them; the bytes last uploaded */
    GLuint style_vbo, paint_style_vbo;
    GLint us_filter, ut_filter;
    uint32_t *vlabel;    /* label of each vertex (main order); NULL: the cloud has no labels */
    uint32_t *ulabels;   /* the distinct labels, ascending: computed by the first effects frame of
                          * an upload (effects_frame.c), NULL until then and after each upload */
    size_t ulabel_count;
    uint32_t *paint_src; /* main-order index of each painterly vertex */
    uint8_t *vstyle;     /* the style bytes in style_vbo (main order) */
    int vstyle_hidden;   /* some of them are PNPR_VSTYLE_HIDDEN (a segment layer's frame) */
    /* the profile lines: segments as pairs of float offsets from line_origin */
    size_t line_segments;
    double line_origin[3];
};

/* The per-cell queues' test of a point at offset position p with key `key` (pnpr_shader_prelude's
 * pnpr_queue at a scale of 1): -1 when its cell's end leaves it out, else its fade-in alpha. Reads
 * the last frame's table. */
double pnpr_renderer_queue_alpha(const pnpr_renderer *r, const float p[3], uint16_t key);

/* The continuous resolution queue's fade-in (issue 16): of a queue of `size` keys drawn up to
 * `drawn` (a cell's end, in keys: plan_cells), the last ones are drawn with alpha ramping from 1
 * down to 0 over this many keys, so a stroke appears and vanishes gradually as the share moves
 * across it; `fraction` of the drawn keys (pnpr_draw_options.queue_fade), at most the keys left
 * + 1 (a cell drawn whole is drawn at full alpha), 0 = no fade. */
float pnpr_queue_fade_length(double drawn, double size, float fraction);

/* The longest half length of a stroke or hatch in pixels: half of o->stroke_max (its default when
 * 0), no limit (FLT_MAX) when negative. The stroke shader's u_half_max and the vector export's
 * strokes both take it from here. */
float pnpr_stroke_half_max(const pnpr_draw_options *o);

/* The stroke textures (STROKE_LAYERS layers of STROKE_TEX_W x STROKE_TEX_H alpha bytes, u along
 * the stroke), generated once (paper figure 5 a-c, plus the hatch). */
void pnpr_stroke_textures(uint8_t *out);

/* What the outline pass of a recorded frame puts in the colour attachment (vector.c). */
enum {
    PNPR_OUTLINES_DRAWN = 0, /* as in any frame */
    PNPR_OUTLINES_INK_ONLY,  /* only the outlines' ink: the attachment is cleared to transparent first */
    PNPR_OUTLINES_NO_INK     /* no ink: the pass still paints the mask disks' overhang beyond the
                              * silhouettes in the background, as any frame does */
};

/* What a drawn frame was made of: the resolved options, the camera and the queue prefixes, so that
 * its strokes, dots and lines can be computed again on the CPU (vector.c). */
typedef struct pnpr_frame_record {
    int outline_pass;           /* in: PNPR_OUTLINES_* (zero: as drawn) */
    int pass_only;              /* in: a style map's frame draws pass 2 of style pass_only - 1 only
                                 * (its mask is every style's); zero: every style */
    pnpr_draw_options o;        /* options with the style map resolved (o.style_map stays NULL) */
    pnpr_frame_camera fc;
    int width, height;
    size_t n_draw;
    size_t gdraw[GROUP_MAX + 1];
    float point_scale, lod, ink[4];
    int outline;                /* the frame drew outlines (the info attachment holds the mask's surface) */
    float outline_width;
    int mapped;                 /* several styles (a style map) */
    size_t used[PNPR_STYLE_COUNT_]; /* style map: the vertices of each style (the per-vertex styles:
                                     * pnpr_renderer.vstyle) */
} pnpr_frame_record;

/* Draws one offscreen frame of width x height (within the GL limit) like pnpr_renderer_draw and
 * fills *rec. */
pnpr_status pnpr_renderer_draw_recorded(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                        int width, int height, pnpr_frame_record *rec, pnpr_error *err);

/* ---- shared by renderer*.c ------------------------------------------------------------------ */

/* Points `vao` at the vertices of `vbo` from vertex `first` on (attributes 0 position, 1 radius,
 * 2 colour (the flat colour with `flat`), 5 normal; 3 the feature direction and per-instance
 * attributes with `instanced`) and attribute 4 at the style bytes of `sbo` (renderer.c). */
void pnpr_renderer_vertex_attribs(GLuint vao, GLuint vbo, GLuint sbo, GLuint kbo, size_t first, int instanced, int flat);

/* Generates and uploads the stroke texture array and the painterly brush (renderer_textures.c). */
pnpr_status pnpr_renderer_make_textures(pnpr_renderer *r);

/* Brush size of painterly pass `pass` of `bins`, in disk radii: PNPR_PAINT_MAX_BRUSH for the
 * first (all bins), 1 for the last (the highest-degree bin), geometric in between
 * (renderer_upload.c). */
float pnpr_paint_brush(size_t pass, size_t bins);

/* Style maps (renderer_upload.c): the style of every vertex (main order) under o's map, a label's
 * last entry, o->style for labels not in the map; r_used[s] = how many vertices got style s (the
 * cloud has labels). Then the upload of those bytes (main and painterly order) when they changed. */
pnpr_status pnpr_renderer_resolve_styles(const pnpr_renderer *r, const pnpr_draw_options *o, uint8_t *r_style,
                                         size_t *r_used);
/* The style byte of a vertex outside the frame's segment layer (pnpr_draw_options.layer_labels):
 * every vertex shader drops it (PNPR_VSTYLE_HIDDEN there too: pnpr_shader_prelude). Style maps and
 * layers are counted in r_used only for the vertices in the layer. */
#define PNPR_VSTYLE_HIDDEN 255u
/* Whether o asks for a segment layer. */
int pnpr_draw_has_layer(const pnpr_draw_options *o);
pnpr_status pnpr_renderer_upload_styles(pnpr_renderer *r, const uint8_t *vstyle);

/* Reads the last frame's colour (GL_RGBA, GL_UNSIGNED_BYTE: premultiplied as drawn) or depth
 * (GL_DEPTH_COMPONENT, GL_FLOAT) whole into buf, bottom row first, host GL state kept
 * (renderer_snapshot.c). PNPR_ERR_EMPTY before the first frame. */
pnpr_status pnpr_renderer_read_raw(pnpr_renderer *r, unsigned format, unsigned type, void *buf);

/* A tile of a larger image: the frame is the rectangle (x, y, w, h) (GL pixel convention, y up
 * from the bottom row) of a full_w x full_h image; point sizes, queue counts and the camera are
 * those of the full image (pnpr_renderer_snapshot). */
typedef struct tile_rect { int full_w, full_h, x, y, w, h; } tile_rect;

/* The camera, the queue count and the disk growth of a full image (shared by every tile). */
typedef struct frame_plan {
    pnpr_frame_camera fc;
    size_t n_draw;       /* the points drawn (every cell's keys below its end) */
    double coverage;
    float lod;           /* sqrt(points in view / drawn): their disks' growth (the lines' pull) */
    float lod_max;       /* the largest growth of a cell drawn (tile guard bands) */
    float end_max;       /* the largest end of a cell: the vertex prefixes drawn reach it */
} frame_plan;

/* The margin of a tile of at most tmax px (guard band, in px) that keeps the sprites, marks and
 * outlines of the points beyond its border whole: half the largest sprite, the longest stroke's
 * half length or the dots, lines and outline reach (o checked and filled); at most tmax / 4. */
int pnpr_renderer_tile_margin(const pnpr_renderer *r, const pnpr_draw_options *o, const frame_plan *plan, int tmax);

/* The draw (renderer.c): *o = the checked options (zeros where opts is NULL), their zeros
 * replaced by the defaults of pnpr_draw_option_table (options.h) except those of the style
 * (pnpr_draw_mask_scale, pnpr_draw_ink, pnpr_style_outline_default); the plan of a
 * w x h image; one frame or one tile of it into the renderer's framebuffer (composited into the
 * target unless it is offscreen or a tile), *rec filled when given. */
pnpr_status pnpr_renderer_check_options(const pnpr_renderer *r, const pnpr_draw_options *opts, pnpr_draw_options *o,
                                        pnpr_error *err);
pnpr_status pnpr_renderer_plan_frame(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *o,
                                     int w, int h, frame_plan *p, pnpr_error *err);
pnpr_status pnpr_renderer_draw_frame(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                     const pnpr_target *target, const tile_rect *tile, pnpr_render_stats *r_stats,
                                     pnpr_frame_record *rec, pnpr_error *err);

/* One frame's resolved values, read by the passes. */
typedef struct pnpr_frame_ctx {
    pnpr_draw_options o;             /* checked; o.style: the style (the only one a map left) */
    pnpr_frame_camera fc;            /* with the tile's projection when tiled */
    float image_proj[16];            /* the whole image's projection */
    int fw, fh;                      /* the frame (framebuffer) */
    size_t n_draw;                   /* the queue prefix, all groups together */
    size_t ng;                       /* the groups drawn (group_count + "other", empty) */
    size_t gdraw[GROUP_MAX + 1];     /* the prefix of each group */
    size_t pdraw[PAINT_MAX_BINS];    /* painterly: the prefix of each bin (the mask's) */
    float end_max;                   /* the largest end of a cell (the prefixes reach it) */
    double coverage;
    float lod, point_scale, mask_scale, ink[4];
    int outline;                     /* outlines after the passes (from the mask's surface info) */
    float outline_width;
    int mapped;                      /* several styles (a style map): pnpr_renderer_draw_mapped */
    size_t used[PNPR_STYLE_COUNT_];  /* style map: the vertices of each style */
    int pass_only;                   /* style map: pass 2 of this style + 1 only (pnpr_frame_record) */
} pnpr_frame_ctx;

/* The passes (renderer_passes.c). Which of the frame's attachments the fragment outputs reach:
 * colour (0) and the mask's surface info (1); draw-buffer state belongs to the bound framebuffer
 * object (ours), not to the host. The passes of one style, or of a style map; each returns the
 * primitives drawn other than plain splats (strokes, dots, dabs, line segments). */
void pnpr_renderer_draw_buffers(int info, int color);
size_t pnpr_renderer_draw_single(pnpr_renderer *r, const pnpr_frame_ctx *f);
size_t pnpr_renderer_draw_mapped(pnpr_renderer *r, const pnpr_frame_ctx *f);

#endif
