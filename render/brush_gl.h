/* Stroke-based splatting's GL side (not installed): the brush programs, the per-point brush
 * buffer, the brush textures and the order-independent blending targets. The renderer owns one
 * (renderer_internal.h); renderer_passes.c draws the style with it. See docs/brush.md. */
#ifndef PNPR_BRUSH_GL_H
#define PNPR_BRUSH_GL_H

#include <pointnpr/core.h>

#include "gl_state.h"

#include <epoxy/gl.h>

#include <stddef.h>

typedef struct pnpr_brush_gl {
    GLuint prog, prog_resolve, prog_blur, vao, vao_empty, vbo, tex, fbo, accum_tex, optical_tex;
    GLuint blur_fbo, blur_tex;   /* the blur's intermediate (made at the first blurred frame) */
    GLint ub_src, ub_dir, ub_sigma;
    int blur_w, blur_h;
    GLint u_view, u_proj, u_scale, u_jitter, u_layer, u_filter, u_brush, u_oit, u_weight;
    GLint ur_accum, ur_optical;
    pnpr_queue_uniforms uq; /* the per-cell queues (the renderer sets them each frame) */
    int preset;      /* the preset in `tex`; -1 = none yet */
    int w, h;        /* the blending targets' size */
    int ready;       /* the uploaded cloud carries brush data (vbo filled) */
} pnpr_brush_gl;

/* One vertex's brush attributes (attribute 6), in the renderer's queue order. */
typedef struct pnpr_brush_vertex { float size, stretch, layers; } pnpr_brush_vertex;

/* Programs and buffers; PNPR_ERR_UNSUPPORTED (message in err) when a shader fails. */
pnpr_status pnpr_brush_gl_create(pnpr_brush_gl *b, pnpr_error *err);
void pnpr_brush_gl_release(pnpr_brush_gl *b);

/* Uploads n brush vertices (NULL / 0: the cloud has no brush data: ready = 0). */
void pnpr_brush_gl_upload(pnpr_brush_gl *b, const pnpr_brush_vertex *v, size_t n);

/* What one brush pass draws. */
typedef struct pnpr_brush_pass {
    const float *view, *proj;    /* the frame's camera */
    float scale;                 /* brush scale x point scale (x each cell's disk growth in the shader) */
    float jitter_deg;
    float blur;                  /* > 0: alpha blending + a Gaussian blur of this sigma (px) */
    int filter;                  /* style-map filter (-1 = all) */
    int stencil;                 /* > 0: strokes only where the stencil equals it (a style map's
                                  * surfaces of this style); 0: no stencil test */
    GLuint frame_fbo;            /* the frame (colour attachment 0) */
    GLuint main_vbo, style_vbo, key_vbo; /* the renderer's vertices, style bytes and queue keys */
    const size_t *first, *count; /* the groups' starts and queue prefixes */
    size_t groups;
} pnpr_brush_pass;

/* Before a frame that draws brushes: the preset's textures (made when it changes) and the blending
 * targets at the frame's size w x h, sharing its depth-stencil renderbuffer. Leaves the brush FBO
 * bound. PNPR_ERR_INVALID_ARGUMENT for a preset out of range, PNPR_ERR_UNSUPPORTED when the
 * targets cannot be made (message in err). */
pnpr_status pnpr_brush_gl_prepare(pnpr_brush_gl *b, int preset, int w, int h, GLuint depth_rb, pnpr_error *err);

/* The blending targets at the frame's size w x h, sharing its depth-stencil renderbuffer (also for
 * the hierarchy style's strokes); PNPR_ERR_UNSUPPORTED when they cannot be made. */
pnpr_status pnpr_brush_gl_targets(pnpr_brush_gl *b, int w, int h, GLuint depth_rb, pnpr_error *err);

/* the OIT weight a^PNPR_OIT_WEIGHT: 2 keeps the strokes' dense cores over their neighbours' rims
 * (1 = a plain alpha-weighted mean, which blurs the strokes together; docs/brush.md) */
#define PNPR_OIT_WEIGHT 2.0f

/* Order-independent blending of strokes whose fragment shader is brush.frag.glsl (u_oit 1): begin
 * clears the targets and sets the state (depth test against the frame's depth without writes,
 * stencil test for stencil > 0, additive blending); resolve composites them over the frame
 * `frame_fbo` and leaves blending and stencil off, the depth test on. */
void pnpr_brush_gl_oit_begin(pnpr_brush_gl *b, int stencil);
void pnpr_brush_gl_oit_resolve(pnpr_brush_gl *b, GLuint frame_fbo);

/* Draws the strokes of the queue prefixes (both layers), depth-tested against the frame's depth
 * (the visibility mask), blended order-independently and resolved over the frame's colour
 * (pnpr_brush_gl_prepare first). Leaves the frame FBO bound with draw buffer 0, blending off,
 * depth writes off. Returns the strokes drawn (first layer). */
size_t pnpr_brush_gl_draw(pnpr_brush_gl *b, const pnpr_brush_pass *p);

#endif
