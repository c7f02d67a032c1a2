/* pointnpr — effects.h: segment-specific image-space effects (Wegen et al., "Segment-based
 * image-space NPR of point clouds"): each segment (or group of segments) is rasterised into its own
 * colour + depth layer, filtered in image space by a chain of effects, its depth inpainted where
 * the filters coloured pixels anew (the paper's listing 1), and the layers are composited with a
 * per-pixel depth test. GL-free (core library): the effects work on caller-owned RGBA8 images;
 * OpenCV (imgproc, photo) provides the building blocks it already implements, through a thin C++
 * adapter (effects/cv_adapter.cpp); a build without OpenCV reports PNPR_ERR_UNSUPPORTED for the
 * effects that need it. The renderer side (one layer per node) is pnpr_renderer_effects (render.h).
 * docs/effects.md documents every effect, every choice the paper leaves open and the file format. */
#ifndef POINTNPR_EFFECTS_H
#define POINTNPR_EFFECTS_H

#include "core.h"
#include "style.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- images ---------------------------------------------------------------------------------- */

/* An RGBA8 image, top row first, straight (not premultiplied) alpha; pixels caller-owned. */
typedef struct pnpr_image {
    int width, height;
    uint8_t *rgba; /* width * height * 4 bytes */
} pnpr_image;

/* ---- effects --------------------------------------------------------------------------------- */

typedef enum pnpr_effect_kind {
    PNPR_EFFECT_SMOOTH = 0,  /* edge-preserving smoothing (bilateral) */
    PNPR_EFFECT_TOON,        /* cartoon (Winnemöller et al. 2006): bilateral abstraction, soft
                              * luminance quantisation, DoG edges */
    PNPR_EFFECT_WATERCOLOUR, /* watercolour (Bousseau et al. 2006): abstraction, pigment density
                              * from paper and turbulence textures, edge darkening */
    PNPR_EFFECT_OIL,         /* oil paint (Semmo et al. 2016): smoothing along the structure
                              * tensor's flow, brush texture, relief lighting */
    PNPR_EFFECT_PENCIL,      /* pencil hatching: hatch layers by tone, outlines */
    PNPR_EFFECT_POSTERISE,   /* colour levels per channel */
    PNPR_EFFECT_GRADE,       /* colour grading: brightness, contrast, saturation, tint, recolour */
    PNPR_EFFECT_EDGES,       /* edge enhancement: XDoG edges darkened into the image */
    PNPR_EFFECT_COUNT_
} pnpr_effect_kind;

/* Most parameters one effect has. */
#define PNPR_EFFECT_PARAMS_MAX 8

/* One parameter of an effect: its name in pipeline files, default, range and meaning. */
typedef struct pnpr_effect_param_info {
    const char *name;
    float def, min, max;
    const char *doc;
} pnpr_effect_param_info;

/* "smooth", "toon", "watercolour", "oil", "pencil", "posterise", "grade", "edges"; "" if invalid. */
const char *pnpr_effect_name(pnpr_effect_kind kind);
/* The effect of a name, ignoring case; PNPR_ERR_NOT_FOUND for others. */
PNPR_NODISCARD pnpr_status pnpr_effect_from_name(const char *name, pnpr_effect_kind *r_kind);
/* The parameter table of an effect (*r_count entries, in the order of pnpr_effect.params);
 * NULL and 0 for an invalid kind. The one source of the defaults and ranges. */
const pnpr_effect_param_info *pnpr_effect_params(pnpr_effect_kind kind, int *r_count);

/* One effect with its parameters. Valid when zeroed (a smooth with the defaults): parameter i takes
 * params[i] when bit i of `set` is on, else its table default. */
typedef struct pnpr_effect {
    pnpr_effect_kind kind;
    uint32_t set;
    float params[PNPR_EFFECT_PARAMS_MAX];
} pnpr_effect;

/* Parameter i of e (its value when set, else the default); NaN for an invalid kind or index. */
float pnpr_effect_param(const pnpr_effect *e, int i);

/* Most effects in one chain. */
#define PNPR_EFFECT_CHAIN_MAX 16

typedef struct pnpr_effect_chain {
    pnpr_effect effects[PNPR_EFFECT_CHAIN_MAX];
    int count;
} pnpr_effect_chain;

/* Applies one effect: src -> dst (same size, distinct buffers). The alpha channel is kept; it
 * tells fragments (alpha > 0) from paper (alpha 0, where the layer has no point: its colour is the
 * paper's): the per-pixel effects (posterise, grade) leave paper as it is, so that a recoloured
 * segment gets no tinted halo; the neighbourhood effects read the paper's colour as it is.
 * Noise (paper texture, brush texture) comes from `seed` and the pixel position only: the same
 * input and seed give the same bytes. PNPR_ERR_INVALID_ARGUMENT for a bad size, kind or a set
 * parameter outside its range (message names the effect and parameter); PNPR_ERR_UNSUPPORTED when
 * the effect needs OpenCV and this build has none. */
PNPR_NODISCARD pnpr_status pnpr_effect_apply(const pnpr_effect *e, const pnpr_image *src, pnpr_image *dst,
                                             uint64_t seed, pnpr_error *err);
/* Applies the chain in order: src -> dst (count 0 copies). */
PNPR_NODISCARD pnpr_status pnpr_effect_chain_apply(const pnpr_effect_chain *chain, const pnpr_image *src,
                                                   pnpr_image *dst, uint64_t seed, pnpr_error *err);

/* Named presets: effect chains with parameters (the MeshLab dialog and `preset NAME` lines in
 * pipeline files read them here). */
typedef struct pnpr_effect_preset {
    const char *name;
    const char *doc;
    pnpr_effect_chain chain;
} pnpr_effect_preset;

const pnpr_effect_preset *pnpr_effect_presets(int *r_count);
/* The preset of a name (ignoring case); NULL when none. */
const pnpr_effect_preset *pnpr_effect_preset_find(const char *name);

/* ---- depth inpainting and compositing -------------------------------------------------------- */

/* Defaults of pnpr_inpaint_options (docs/effects.md says how they were chosen). */
#define PNPR_INPAINT_THRESHOLD 0.05f
#define PNPR_INPAINT_RADIUS 3
#define PNPR_INPAINT_RADIUS_MAX 64

typedef struct pnpr_inpaint_options {
    float threshold; /* grey difference (0..1) between rasterised and filtered pixel above which the
                      * pixel's depth is inpainted (0 = PNPR_INPAINT_THRESHOLD) */
    int radius;      /* circular neighbourhood radius in px (0 = PNPR_INPAINT_RADIUS, at most
                      * PNPR_INPAINT_RADIUS_MAX) */
} pnpr_inpaint_options;

/* The paper's listing 1: where the grey values of `raster` and `filtered` differ by more than the
 * threshold, the depth becomes the mean of the non-far depths (< 1) within the circle of `radius`
 * px around the pixel (the pixel included); elsewhere it is kept. A masked pixel without any non-far
 * neighbour stays far (1): the listing divides by zero there. depth and r_depth: width * height
 * window depths in 0..1, top row first, 1 = far plane (no fragment); they may not alias.
 * r_mask: 1 where the pixel was masked, else 0. One of r_depth and r_mask may be NULL (r_depth
 * NULL: only the mask, the circle means are not computed; depth may then be NULL too). */
PNPR_NODISCARD pnpr_status pnpr_depth_inpaint(const pnpr_image *raster, const pnpr_image *filtered,
                                              const float *depth, const pnpr_inpaint_options *opts,
                                              float *r_depth, uint8_t *r_mask, pnpr_error *err);

/* How layers are composited (paper figure 12). */
typedef enum pnpr_layering {
    PNPR_LAYERING_INPAINTED = 0, /* per-pixel depth test on the inpainted depths (the default) */
    PNPR_LAYERING_FRAGMENT,      /* per-pixel depth test on the rasterised depths: pixels a filter
                                  * coloured outside the segment have no depth and are lost */
    PNPR_LAYERING_NONE,          /* no depth test: layers painted in order, later ones on top, each
                                  * where it has a fragment or its filters changed the pixel */
    PNPR_LAYERING_COUNT_
} pnpr_layering;

const char *pnpr_layering_name(pnpr_layering mode); /* "inpainted", "fragment", "none"; "" if invalid */
PNPR_NODISCARD pnpr_status pnpr_layering_from_name(const char *name, pnpr_layering *r_mode);

/* One segment layer: its filtered colours and its depth (inpainted for PNPR_LAYERING_INPAINTED,
 * else as rasterised); `changed` (may be NULL) marks the pixels whose colour the filters changed
 * (pnpr_depth_inpaint's mask), used by PNPR_LAYERING_NONE. */
typedef struct pnpr_layer {
    const pnpr_image *color;
    const float *depth;
    const uint8_t *changed;
} pnpr_layer;

/* Composites `count` layers of the same size into r_out: each pixel takes the colour of the layer
 * with the nearest depth < 1 (ties: the earlier layer) with alpha 255 (a layer's alpha is its
 * coverage, not a transparency), or `background` (RGBA8; NULL = transparent black) where no layer
 * has one; PNPR_LAYERING_NONE paints in order instead. r_depth (may be
 * NULL): the winning depth, 1 where none. */
PNPR_NODISCARD pnpr_status pnpr_layers_composite(const pnpr_layer *layers, size_t count, pnpr_layering mode,
                                                 const uint8_t background[4], pnpr_image *r_out,
                                                 float *r_depth, pnpr_error *err);
/* The same one layer at a time (so that layers need not all be kept): pnpr_layers_clear fills
 * r_out with `background` and r_depth (width * height) with 1, then pnpr_layers_merge adds the
 * layers in order; the result equals pnpr_layers_composite's. */
PNPR_NODISCARD pnpr_status pnpr_layers_clear(const uint8_t background[4], pnpr_image *r_out, float *r_depth,
                                             pnpr_error *err);
PNPR_NODISCARD pnpr_status pnpr_layers_merge(const pnpr_layer *layer, pnpr_layering mode, pnpr_image *r_out,
                                             float *r_depth, pnpr_error *err);

/* ---- pipeline files -------------------------------------------------------------------------- */

/* A node of the pipeline tree (paper section 4.2): the resolved configuration after inheritance
 * (a child starts from its parent's and overrides what it names). */
typedef struct pnpr_effect_node {
    char name[64];
    int parent;            /* index of the parent node; -1 for the root (node 0) */
    uint32_t *labels;      /* labels this node lists itself (owned; none for the root) */
    size_t label_count;
    pnpr_style style;      /* how the layer is rasterised (points by default) */
    float point_scale;     /* disk radius factor of the raster (0 = the renderer's default) */
    int per_label;         /* 1: one layer per label instead of one for the node */
    int inpaint;           /* 1 (default): depth inpainting; 0: off */
    pnpr_inpaint_options inpaint_opts;
    pnpr_effect_chain chain;
} pnpr_effect_node;

typedef struct pnpr_effect_pipeline {
    pnpr_effect_node *nodes; /* owned; nodes[0] is the root, which draws every label no node lists */
    size_t count;
    pnpr_layering layering;
} pnpr_effect_pipeline;

/* Largest pipeline file the CLI loads. */
#define PNPR_EFFECT_PIPELINE_FILE_MAX ((size_t)1 << 20)

/* Parses a pipeline description (docs/effects.md, "Pipeline files"); `name` names the text in
 * messages. PNPR_ERR_FORMAT with "NAME:LINE: what is wrong" (err->line set) on a bad line;
 * r_pipeline is zeroed on failure. */
PNPR_NODISCARD pnpr_status pnpr_effect_pipeline_parse(const char *text, size_t size, const char *name,
                                                      pnpr_effect_pipeline *r_pipeline, pnpr_error *err);
void pnpr_effect_pipeline_free(pnpr_effect_pipeline *pipeline); /* leaves it zeroed; NULL ok */
/* The node that draws `label`: the last node listing it, else the root (0). */
size_t pnpr_effect_pipeline_node_of(const pnpr_effect_pipeline *pipeline, uint32_t label);

#ifdef __cplusplus
}
#endif
#endif
