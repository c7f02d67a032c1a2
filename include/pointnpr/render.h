/* pointnpr — render.h: the PointWorks renderer (Xu, Gossett & Chen, sections 4.3-5.1) for an
 * OpenGL 3.3 core context, plus a headless EGL context and PNG output for the CLI and tests.
 * Library target `pointnpr_render` (links libepoxy and libpng; the core `pointnpr` stays GL-free).
 * The pure-CPU parts it builds on are in the core library and have their own headers, included
 * here: the cameras and the SVG line drawings (camera.h), the continuous resolution queue (crq.h).
 *
 * Model:
 *   - A pnpr_renderer is created in the caller's *current* GL 3.3+ core context and owns its GL
 *     objects (programs, buffers, VAOs, textures, its framebuffer). Call every function with that
 *     context current. No global state: two renderers in two contexts are independent.
 *   - pnpr_renderer_set_cloud uploads a cloud: per-point disk radius from the local point spacing,
 *     classes/directions from the feature properties (when present) and the continuous
 *     resolution queue order (a seeded random permutation per group, computed once).
 *   - pnpr_renderer_draw renders one frame into the renderer's own framebuffer (two passes: an
 *     opaque depth-only visibility mask, then the styled primitives depth-tested against it with
 *     blending and no depth writes) and composites it into the target framebuffer. Every piece of
 *     host GL state it touches is saved before and restored after (docs/rendering.md lists it).
 * docs/rendering.md documents every choice the paper leaves open. */
#ifndef POINTNPR_RENDER_H
#define POINTNPR_RENDER_H

#include "camera.h"
#include "cloud.h"
#include "crq.h"
#include "drawing.h"
#include "effects.h"
#include "hierarchy.h"
#include "polylines.h"
#include "style.h"
#include "tone.h"
#include "view.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- renderer ------------------------------------------------------------------------------- */

typedef struct pnpr_renderer pnpr_renderer;

typedef enum pnpr_composite {
    PNPR_COMPOSITE_REPLACE = 0, /* the target's pixels in the viewport become the frame's */
    PNPR_COMPOSITE_OVER,        /* the frame (premultiplied alpha) over the target's pixels */
    PNPR_COMPOSITE_COUNT_
} pnpr_composite;

typedef struct pnpr_renderer_options {
    int reserved; /* nothing yet; zero */
} pnpr_renderer_options;

/* Largest pnpr_upload_options.spacing_k (the upload's kNN lists take count x spacing_k entries:
 * a larger value is refused rather than slow). */
#define PNPR_SPACING_K_MAX 64

/* Largest pnpr_upload_options.painterly_bins. */
#define PNPR_PAINTERLY_BINS_MAX 16

/* The defaults and ranges of pnpr_upload_options and pnpr_draw_options: the tables of options.h
 * (pnpr_upload_defaults, pnpr_draw_defaults; core/options_render.c). */

typedef struct pnpr_upload_options {
    uint32_t spacing_k; /* disk radius of point i = distance to its spacing_k-th nearest other
                         * point (0 = the default, at most PNPR_SPACING_K_MAX), capped at 4x the median;
                         * see docs/rendering.md */
    uint64_t seed;      /* continuous resolution queue seed (0 is a valid seed) */
    int ignore_features; /* treat the cloud as if it had no feature properties */
    int threads;        /* kNN threads; 0 = all cores */
    uint32_t painterly_bins; /* painterly: feature-degree bins = passes (0 = the default, at most
                              * PNPR_PAINTERLY_BINS_MAX); the
                              * painterly data are built when the cloud has feature_degree */
    int skip_painterly;      /* 1: no painterly data, even for a cloud with feature_degree: no
                              * 12-neighbour lists, colour passes or painterly buffers (less time
                              * and memory when no frame will be painterly; a painterly frame is
                              * then refused). 0: built when the cloud has feature_degree */
    pnpr_tone_options tone;  /* clouds without colours are drawn in greys shaded by this tone's
                              * key light on their normals (tone.h; the source is always the
                              * light, the curve is not applied): grey = 240 - 170 * darkness */
    const char *style_key;   /* the per-point key that style maps and segment layers
                              * (pnpr_draw_options.style_map, layer_labels) read: NULL = the
                              * segment labels (cloud->label); else the name of a PNPR_TYPE_UINT32
                              * property, e.g. one value per MeshLab layer for a style per layer,
                              * while cartoon's fills keep following the segment labels. A missing
                              * property: PNPR_ERR_NOT_FOUND; another type: PNPR_ERR_INVALID_ARGUMENT */
    float tone_radius;       /* > 0 (finite): the tone hatches' length in disk radii of this size
                              * instead of the mean disk radius. A sample of a larger cloud gives
                              * the whole cloud's mean spacing: its grown radii would lengthen the
                              * hatches (docs/tiles.md "A sample by the view"). 0 = the mean */
} pnpr_upload_options;

/* pnpr_style_map_entry and its file format: style.h. */

/* Default of pnpr_draw_options.queue_fade. */
#define PNPR_QUEUE_FADE 0.1f

/* Default of pnpr_draw_options.line_min_px. */
#define PNPR_LINE_MIN_PX 8.0f

/* Per-frame options; zero = the default (the defaults and ranges: pnpr_draw_option_table,
 * options.h). Colours are linear 0..1 RGBA. */
typedef struct pnpr_draw_options {
    pnpr_style style;      /* the style; with a style map, the default style of labels not in it */
    /* Intermingled styles (paper figure 12): style_map_count > 0 entries (caller-owned, read
     * during the call only) give segment labels their own styles; labels not listed (and every
     * point of a cloud without labels) take `style`. One visibility mask over all points, then
     * each style over its segments' points (docs/rendering.md). A label listed twice takes its
     * last entry. 0 / NULL = no map. */
    const pnpr_style_map_entry *style_map;
    size_t style_map_count;
    /* A segment layer (image-space effects, effects.h): with layer_label_count > 0 or
     * layer_exclude, only the points in the layer take part in the frame (every pass, the visibility
     * mask included; the queue prefixes stay those of the whole cloud, so a layer shows exactly the
     * points the whole frame would). In the layer: points whose label (cloud->label) is among the
     * layer_label_count labels of layer_labels (caller-owned, read during the call only), or, with
     * layer_exclude, points whose label is not among them and the points of a cloud without labels. */
    const uint32_t *layer_labels;
    size_t layer_label_count;
    int layer_exclude;
    pnpr_sketch_variant sketch_variant;
    float background[4];   /* clear colour of the frame (zero = transparent black) */
    size_t budget;         /* at most this many points sent per frame (the per-cell queues'
                            * prefixes; the near cells thinned first: docs/rendering.md;
                            * 0 = no limit) */
    float density;         /* about density * (screen pixels covered by the cloud's projected
                            * bounding box) points in view per frame, shared among the cells by
                            * depth: the screen-space budget that keeps a dense view from
                            * drowning in ink (0 = the default of the option table, "density";
                            * negative = no limit: every point) */
    float point_scale;     /* multiplies the disk radii */
    float mask_scale;      /* visibility-mask disks = point_scale * mask_scale * radius (cartoon:
                            * the enlarged outline disks, with its own default) */
    float stroke_length;   /* directional stroke length in disk radii; hatches are half */
    float stroke_width;    /* stroke width in pixels */
    float stroke_max;      /* longest stroke or hatch in pixels, whatever its length in disk radii
                            * (0 = the default of the option table, "stroke-max"; negative = none) */
    int stroke_texture;    /* 0, 1, 2: the three directional stroke textures (paper fig. 5 a-c) */
    float ink[4];          /* stroke, line, dot and cartoon outline colour (all zero = the
                            * default, an opaque near-black; painterly strokes: the point colours) */
    int ink_from_points;   /* strokes take the point colour instead of `ink` */
    pnpr_composite composite;
    float line_width;      /* lines: stroke width in pixels */
    float line_min_px;     /* lines: profile lines (whole polylines) shorter than this many pixels
                            * on screen are not drawn: scan noise makes such scribbles
                            * (default PNPR_LINE_MIN_PX) */
    float faint;           /* lines: 0..1, the cloud drawn faintly under the lines (its colours
                            * mixed with the background, this much of the point colour); 0 = none */
    float dot_size;        /* stipple: dot diameter in pixels */
    int levels;            /* cartoon without segment labels: colour levels per channel (>= 2) */
    /* Outlines (silhouettes and occluding contours) found in image space on the visibility mask,
     * sampling holes closed first (docs/rendering.md, "Silhouettes and contours"); drawn in `ink`
     * over the style. Defaults per style: pnpr_style_outline_default. */
    int outline;           /* 0 = the style's default, 1 = on, -1 = off */
    float outline_width;   /* px; 0 = the style's default */
    float outline_jump;    /* a contour is a depth jump of more than this many depth extents (0 = PNPR_OUTLINE_JUMP) */
    float outline_hole;    /* gaps enclosed on all sides within this many projected mask-disk radii
                            * are sampling holes, not outlines (0 = PNPR_OUTLINE_HOLE; at most 32 px) */
    float queue_fade;      /* sketchy, stipple: the last fraction of each group's queue prefix fades
                            * in (alpha ramp), so that strokes and dots appear and vanish over
                            * several frames when the budget (--budget, --density) changes
                            * (0 = PNPR_QUEUE_FADE; negative = none: they pop) */
    int paint_no_sky_mask; /* painterly: no stencil test in the large passes (paper fig. 8 left) */
    int paint_no_strokes;  /* painterly: no directional strokes on top */
    int brush_preset;      /* brush: the brush (pnpr_brush_presets index, brush.h; 0 = bristle) */
    float brush_scale;     /* brush: a splat's half-size in brush_size units (r + eps) */
    float brush_jitter;    /* brush: each stroke turns by a per-point angle of at most this many
                            * degrees (negative = none) */
    float brush_blur;      /* brush: > 0: the paper's blend while the camera moves: strokes alpha-
                            * blended in draw order, then a two-pass Gaussian blur of this sigma in
                            * pixels; 0: order-independent blending (docs/brush.md, "Blending") */
    pnpr_hier_params hierarchy; /* hierarchy: the traversal's and strokes' options (zeros: the
                            * defaults of pnpr_hier_option_table; its ink is the frame's) */
    /* An explicit camera (pnpr_camera_matrices, caller-owned, read during the call only) that
     * replaces the `camera` argument of pnpr_renderer_draw / pnpr_renderer_snapshot; NULL = use
     * `camera` (look-at + symmetric perspective). */
    const struct pnpr_camera_matrices *matrices;
    /* The view the queue is planned for when it is not the frame's own: a tile of a larger
     * picture drawn by the host (MeshLab's snapshot tiles) gives the whole picture's camera and
     * size here, so that every tile draws the points the whole picture draws (the cells' shares,
     * the coverage). NULL = the frame's own view. Read during the call only. */
    const struct pnpr_camera_matrices *plan_matrices;
    int plan_width, plan_height;
} pnpr_draw_options;

/* Where the frame goes: framebuffer object `framebuffer` (0 = the default framebuffer) and the
 * rectangle (x, y, width, height) in its pixels. The frame is rendered at width x height.
 * offscreen != 0: render into the renderer's own framebuffer only (no composite; headless
 * snapshots read it back with pnpr_renderer_read_frame); framebuffer, x and y are then unused. */
typedef struct pnpr_target {
    uint32_t framebuffer;
    int x, y, width, height;
    int offscreen;
    /* A guard band (pnpr_renderer_draw): the frame is drawn this many pixels larger on each side
     * (the projection widened to match) and only its width x height middle is composited, so that
     * the marks, disks and outlines of points just outside the target are whole at its border, as
     * when the target is one tile of a larger picture (MeshLab's tiled snapshots). 0 = none; < 0 =
     * the margin the renderer's own tiles take (pnpr_renderer_snapshot); at most what the GL's
     * size limit leaves. Pixels of the framebuffer outside the rectangle are left alone (scissor);
     * offscreen, the renderer's frame is the larger one. */
    int guard;
} pnpr_target;

typedef struct pnpr_render_stats {
    size_t points_total;   /* points uploaded (finite ones) */
    size_t points_drawn;   /* points in view the per-cell queues keep this frame (pass 2 and the
                            * mask alike) */
    size_t points_sent;    /* vertices sent per pass (the groups' prefixes: what `budget` caps;
                            * the vertex shaders drop those beyond their cell's share) */
    size_t strokes_drawn;  /* sketchy, brush, painterly: marks sent in pass 2; lines: line
                            * segments; stipple: dots */
    double coverage_px;    /* screen pixels covered by the projected bounding box */
} pnpr_render_stats;

/* Needs a current GL 3.3+ core context (else PNPR_ERR_UNSUPPORTED with the reason in err).
 * opts may be NULL. */
PNPR_NODISCARD pnpr_status pnpr_renderer_create(const pnpr_renderer_options *opts, pnpr_renderer **r_renderer,
                                 pnpr_error *err);
/* Deletes the GL objects (its context must be current) and frees the renderer. NULL ok. */
void pnpr_renderer_destroy(pnpr_renderer *renderer);

/* Uploads a cloud (replacing the previous one). Points with NaN/Inf coordinates are dropped.
 * An empty (or all-NaN) cloud is valid: frames then show only the background.
 * Features are taken from feature_class (+ feature_dir_x/y/z) when present. */
PNPR_NODISCARD pnpr_status pnpr_renderer_set_cloud(pnpr_renderer *renderer, const pnpr_cloud *cloud,
                                    const pnpr_upload_options *opts, pnpr_error *err);

/* Profile lines for the `lines` style (include/pointnpr/lines.h), replacing earlier ones; the data
 * are copied (the caller keeps ownership). NULL or zero lines: none (the style then draws only
 * the background, and the faint points when asked). Line vertices are world positions
 * (origin + offset) like the cloud's, so lines and cloud may have different origins. Segments
 * with a non-finite end are dropped. PNPR_ERR_INVALID_ARGUMENT for inconsistent offsets. */
PNPR_NODISCARD pnpr_status pnpr_renderer_set_lines(pnpr_renderer *renderer, const pnpr_polylines *lines,
                                    pnpr_error *err);

/* The sphere tree the hierarchy style draws (hierarchy.h): borrowed, not copied: it must stay
 * valid until it is replaced, set to NULL or the renderer is destroyed. Its origin may differ
 * from the cloud's. */
void pnpr_renderer_set_hierarchy(pnpr_renderer *renderer, const pnpr_sphere_tree *tree);

/* Renders one frame. camera NULL = pnpr_camera_fit of the uploaded cloud for the target's
 * aspect. PNPR_ERR_NOT_FOUND when the style needs features the cloud does not carry;
 * PNPR_ERR_INVALID_ARGUMENT for a zero/negative size or bad option; PNPR_ERR_NUMERIC for a
 * non-finite or degenerate camera. stats may be NULL. */
PNPR_NODISCARD pnpr_status pnpr_renderer_draw(pnpr_renderer *renderer, const pnpr_camera *camera,
                               const pnpr_draw_options *opts, const pnpr_target *target,
                               pnpr_render_stats *r_stats, pnpr_error *err);

/* ---- snapshots of any size (tiled) ---- */

/* Default limit of pnpr_image_bytes: 4 GiB (a 32768 x 32768 RGBA image). */
#define PNPR_IMAGE_BYTES_DEFAULT_LIMIT ((size_t)4 << 30)

/* The bytes of a width x height RGBA8 image, checked before allocating: PNPR_ERR_OUT_OF_MEMORY
 * with a message when it overflows size_t or exceeds `limit` (0 = PNPR_IMAGE_BYTES_DEFAULT_LIMIT);
 * PNPR_ERR_INVALID_ARGUMENT for a zero or negative size. */
PNPR_NODISCARD pnpr_status pnpr_image_bytes(int width, int height, size_t limit, size_t *r_bytes, pnpr_error *err);

/* The largest frame edge this GL allows: min(GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE,
 * GL_MAX_VIEWPORT_DIMS), queried at creation. */
int pnpr_renderer_max_size(const pnpr_renderer *renderer);

/* Most tiles a snapshot may take (each tile draws the whole cloud): a max_tile_size too small for
 * the image is refused rather than slow. */
#define PNPR_SNAPSHOT_TILES_MAX 4096

typedef struct pnpr_snapshot_options {
    int max_tile_size;      /* largest tile edge in px, guard band included (0 = the GL limit); a
                             * smaller value forces tiling (tests) */
    int unpremultiply;      /* as pnpr_renderer_read_frame */
    pnpr_progress progress; /* called after each tile with stage "tile i/n"; non-zero cancels */
} pnpr_snapshot_options;

/* Renders a width x height image of any size into r_rgba (width*height*4 bytes, RGBA8, top row
 * first; size it with pnpr_image_bytes). Images within the GL limit (or max_tile_size) are one
 * frame, exactly pnpr_renderer_draw + pnpr_renderer_read_frame. Larger ones are rendered as tiles:
 * sub-frusta of the same camera, each with a guard band, with the point sizes, stroke sizes and
 * queue counts of the full image, and stitched (docs/rendering.md). The renderer's frame afterwards
 * holds the last tile. r_stats: those of the first tile (points drawn are the same for all). */
PNPR_NODISCARD pnpr_status pnpr_renderer_snapshot(pnpr_renderer *renderer, const pnpr_camera *camera,
                                   const pnpr_draw_options *opts, int width, int height,
                                   const pnpr_snapshot_options *sopts, uint8_t *r_rgba,
                                   pnpr_render_stats *r_stats, pnpr_error *err);

/* ---- vector drawings ---- */

/* The frame of `opts` at width x height (within the GL limit) as a vector drawing (drawing.h):
 * the strokes and hatches of `sketchy`, the dots of `stipple`, the profile lines of `lines`, the
 * flat colour areas of `cartoon` (filled paths) and the outlines of every one of them,
 * each placed as the shaders place it, the hidden ones removed with the frame's own visibility
 * mask (docs/export.md, "Vector drawings"). The renderer's frame afterwards holds this frame.
 * *r_drawing is replaced (release it with pnpr_drawing_free). PNPR_ERR_UNSUPPORTED for the
 * other styles and for style maps, with a message. */
/* Whether pnpr_renderer_drawing draws `opts` (a check before any work): PNPR_OK or
 * PNPR_ERR_UNSUPPORTED with the reason. */
PNPR_NODISCARD pnpr_status pnpr_drawing_supported(const pnpr_draw_options *opts, pnpr_error *err);
PNPR_NODISCARD pnpr_status pnpr_renderer_drawing(pnpr_renderer *renderer, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                  int width, int height, pnpr_drawing *r_drawing, pnpr_error *err);

/* Copies the last frame (width*height*4 bytes, RGBA8, top row first). unpremultiply: colours of
 * partly transparent pixels divided by alpha (for PNGs with alpha). */
PNPR_NODISCARD pnpr_status pnpr_renderer_read_frame(pnpr_renderer *renderer, uint8_t *r_rgba, int unpremultiply);
/* Copies the last frame's depth (width*height floats, top row first): window depth 0..1 of the
 * visibility mask, the nearest visible surface; 1 = far plane (no fragment). */
PNPR_NODISCARD pnpr_status pnpr_renderer_read_depth(pnpr_renderer *renderer, float *r_depth);
/* Size of the last frame (0 x 0 before the first draw). */
void pnpr_renderer_frame_size(const pnpr_renderer *renderer, int *r_width, int *r_height);

/* Whether the uploaded cloud carries the feature properties (class and direction). The painterly
 * style also needs feature_degree (PNPR_ERR_NOT_FOUND otherwise). */
int pnpr_renderer_has_features(const pnpr_renderer *renderer);
/* Whether it carried segment labels (cloud->label): cartoon then paints each segment in its mean
 * colour (computed at upload over the segment's finite points). */
int pnpr_renderer_has_labels(const pnpr_renderer *renderer);

/* Styles by name, their needs and defaults: style.h. */

/* ---- segment-specific image-space effects (Wegen et al.; effects.h) -------------------------- */

/* Smallest pnpr_effects_options.scale. */
#define PNPR_EFFECTS_SCALE_MIN 0.0625f

typedef struct pnpr_effects_options {
    uint64_t seed;          /* noise of the effects (paper, brushes): the same seed, the same image */
    pnpr_progress progress; /* called on the calling thread as each layer is rasterised, with stage
                             * "layer i/n"; non-zero cancels */
    float scale;            /* layers at this fraction of the image size (PNPR_EFFECTS_SCALE_MIN..1;
                             * 0 = 1), the composite grown to the image bilinearly: a preview while
                             * the camera moves (the filters' radii stay in layer pixels, so the
                             * preview is coarser as well as faster) */
    int serial;             /* 1: the filters run on the calling (GL) thread; 0: on a filter thread,
                             * layer i filtered while layer i+1 is rasterised (the same pixels) */
} pnpr_effects_options;

typedef struct pnpr_effects_stats {
    size_t layers;          /* layers rasterised, filtered and composited */
    double raster_s, filter_s, inpaint_s, composite_s; /* seconds spent in each step, all layers
                             * (with the filter thread, raster_s overlaps the other three) */
    int layer_width, layer_height; /* the size the layers had (scale) */
} pnpr_effects_stats;

/* Renders a width x height image (within the GL limit) of the uploaded cloud through an effects
 * pipeline: one layer per pipeline node that draws labels present in the cloud (one per label
 * with per_label), each rasterised with the node's style and point scale on top of `opts` (its
 * background made opaque: the effects see the paper colour), filtered by the node's chain, its
 * depth inpainted (unless the node turns it off), merged in node order with the pipeline's
 * layering; pixels no layer covers take opts->background. A cloud without labels is one layer,
 * the root's. r_rgba: width*height*4 bytes (RGBA8, top row first). Style maps and layers in
 * `opts` are refused (the pipeline chooses them). The renderer's frame afterwards holds the last
 * layer. */
PNPR_NODISCARD pnpr_status pnpr_renderer_effects(pnpr_renderer *renderer, const pnpr_camera *camera,
                                                 const pnpr_draw_options *opts, const pnpr_effect_pipeline *pipeline,
                                                 int width, int height, const pnpr_effects_options *eopts,
                                                 uint8_t *r_rgba, pnpr_effects_stats *r_stats, pnpr_error *err);

/* ---- headless context and PNG (CLI, tests, snapshots) --------------------------------------- */

typedef struct pnpr_gl_context pnpr_gl_context;

/* An OpenGL 3.3+ core context without window system, made current on the calling thread: on a GPU
 * when EGL lists one (EGL_EXT_platform_device), else on Mesa's llvmpipe
 * (EGL_MESA_platform_surfaceless). The environment variable PNPR_GL_DEVICE=software skips the
 * GPUs; PNPR_GL_DEVICE=device takes the first device EGL lists even when it is a software one.
 * It has no default framebuffer: render into a pnpr_renderer (whose frame is read back) or an FBO.
 * PNPR_ERR_UNSUPPORTED with the reason when libEGL, the platform or GL 3.3 is not available. */
PNPR_NODISCARD pnpr_status pnpr_gl_context_create(pnpr_gl_context **r_context, pnpr_error *err);
PNPR_NODISCARD pnpr_status pnpr_gl_context_make_current(pnpr_gl_context *context);
void pnpr_gl_context_destroy(pnpr_gl_context *context); /* releases it if current; NULL ok */
/* "device" (EGL's device platform) or "surfaceless" (Mesa's); NULL for NULL. */
const char *pnpr_gl_context_platform(const pnpr_gl_context *context);

/* Writes RGBA8 pixels (top row first) as an 8-bit PNG, RGB or RGBA (alpha != 0). */
/* Reads a PNG as grey bytes (any colour type, converted by libpng; row 0 at the top) into *r_grey
 * (malloc'd, width x height bytes; free with free). At most 16384 x 16384. PNPR_ERR_FORMAT with
 * the file and libpng's reason for anything it cannot read. */
PNPR_NODISCARD pnpr_status pnpr_read_png_grey(const char *path, uint8_t **r_grey, int *r_width, int *r_height,
                                              pnpr_error *err);

PNPR_NODISCARD pnpr_status pnpr_write_png(const char *path, const uint8_t *rgba, int width, int height,
                           int alpha, pnpr_error *err);

#ifdef __cplusplus
}
#endif
#endif
