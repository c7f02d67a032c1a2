/* The renderer's passes over one frame (docs/rendering.md): the visibility mask (pass 1, section
 * 4.3) shared by every style and by style maps, and the style passes: points, cartoon (5.4),
 * sketchy (5.1), stipple (5.4), lines (5.2), painterly (5.3), brush (stroke-based splatting),
 * and style maps (intermingled styles, figure 12). The frame is bound and cleared (renderer.c); each pass sets the GL state it
 * needs and leaves the programs' uniforms as it found them where later frames rely on it. */
#include "renderer_internal.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

void pnpr_renderer_draw_buffers(int info, int color)
{
    GLenum bufs[2] = {color ? GL_COLOR_ATTACHMENT0 : GL_NONE, info ? GL_COLOR_ATTACHMENT1 : GL_NONE};
    glDrawBuffers(2, bufs);
}

float pnpr_queue_fade_length(double drawn, double size, float fraction)
{
    if (fraction < 0 || !(drawn > 0) || drawn >= size) return 0;
    double f = (fraction > 0 ? fraction : pnpr_draw_defaults().queue_fade) * drawn, left = size - drawn + 1;
    if (f > left) f = left;
    return f >= 1 ? (float)f : 1.0f;
}

float pnpr_stroke_half_max(const pnpr_draw_options *o)
{
    if (o->stroke_max < 0) return FLT_MAX;
    return 0.5f * (o->stroke_max > 0 ? o->stroke_max : pnpr_draw_defaults().stroke_max);
}

/* ---- splats and the visibility mask --------------------------------------------------------- */

/* The groups' queue prefixes, from the bound vertex array. */
static void draw_groups(const pnpr_renderer *r, const pnpr_frame_ctx *f)
{
    for (size_t g = 0; g < f->ng; g++)
        if (f->gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)f->gdraw[g]);
}

/* The splat program with the frame's camera, no fade, size or colour levels; blending off. */
static void splat_program(pnpr_renderer *r, const pnpr_frame_ctx *f)
{
    glUseProgram(r->prog_splat);
    glUniformMatrix4fv(r->us.view, 1, GL_FALSE, f->fc.view);
    glUniformMatrix4fv(r->us.proj, 1, GL_FALSE, f->fc.proj);
    glUniform1f(r->us.ppu, f->fc.pixels_per_unit);
    glUniform1i(r->us.ortho, f->fc.ortho);
    glUniform1f(r->us.max_size, r->max_point_size);
    glUniform1f(r->us.fade, 0.0f);
    glUniform1f(r->us.fixed_size, 0.0f);
    glUniform1f(r->us.levels, 0.0f);
    glDisable(GL_BLEND);
}

/* Splats of the regular size (the queue's disk growth), not pushed, from `vao` (the splat
 * program current). */
static void draw_splats(pnpr_renderer *r, const pnpr_frame_ctx *f, GLuint vao)
{
    glUniform1f(r->us.radius_scale, f->point_scale); /* x each cell's disk growth (pnpr_queue) */
    glUniform1f(r->us.depth_push, 0.0f);
    glBindVertexArray(vao);
    draw_groups(r, f);
}

/* One visibility mask (pass 1) drawing. */
typedef struct mask_spec {
    float scale;     /* the disks' growth over the splats: the mask scale (cartoon: its outline scale) */
    int filter;      /* -1: every point; else the points of this style only (a style map) */
    GLint stencil;   /* > 0: written where a disk passes (stencil test on); 0: stencil untouched */
    int painterly;   /* the painterly order's bin prefixes (else the groups') */
    int flat;        /* the groups in their flat (cartoon) colours */
    int info, color; /* the attachments written besides depth: the surface info (outlines), colour */
} mask_spec;

/* The visibility mask (section 4.3): the queue prefixes as disks `m->scale` times the splats,
 * pushed back in depth, into depth (and the stencil, surface info, colour as `m` says), blending
 * off. Used by every style (painterly: with its sky stencil and underpainting colours) and, once
 * per style, by style maps. The splat program must be current (splat_program). */
static void draw_mask(pnpr_renderer *r, const pnpr_frame_ctx *f, const mask_spec *m)
{
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glUniform1f(r->us.radius_scale, f->point_scale * m->scale);
    glUniform1f(r->us.depth_push, 1.0f);
    glUniform1i(r->us_filter, m->filter);
    if (m->stencil > 0) {
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_ALWAYS, m->stencil, 0xFF);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        glStencilMask(0xFF);
    }
    pnpr_renderer_draw_buffers(m->info, m->color);
    if (m->painterly) {
        pnpr_renderer_vertex_attribs(r->vao_paint, r->paint_vbo, r->paint_style_vbo, r->paint_key_vbo, 0, 0, 0);
        if (m->color) { /* the coarsest pass's blended colours (level 0) */
            glBindBuffer(GL_ARRAY_BUFFER, r->paint_col_vbo);
            glVertexAttribPointer(2, PAINT_COL_BYTES, GL_UNSIGNED_BYTE, GL_TRUE, PAINT_COL_BYTES, (const void *)0);
        }
        for (size_t b = 0; b < r->paint_bins; b++)
            if (f->pdraw[b]) glDrawArrays(GL_POINTS, (GLint)r->paint_start[b], (GLsizei)f->pdraw[b]);
    } else {
        glBindVertexArray(m->flat ? r->vao_flat : r->vao_points);
        draw_groups(r, f);
    }
    pnpr_renderer_draw_buffers(0, 1);
}

/* The lines' faint point rendering: splats in the point colours mixed (1 - faint) with the
 * background (the splat program current). */
static void draw_faint(pnpr_renderer *r, const pnpr_frame_ctx *f)
{
    const pnpr_draw_options *o = &f->o;
    float bg[4] = {o->background[0], o->background[1], o->background[2], o->background[3]};
    glUniform1f(r->us.fade, 1.0f - o->faint);
    glUniform4fv(r->us.fade_color, 1, bg);
    draw_splats(r, f, r->vao_points);
    glUniform1f(r->us.fade, 0.0f);
}

/* ---- strokes, dots, lines ------------------------------------------------------------------- */

/* The directional strokes of the sketchy style's pass 2 (mode 0), shared with painterly. */
static void stroke_program(pnpr_renderer *r, const pnpr_frame_ctx *f, float stroke_width, const float ink[4],
                           int ink_from_points)
{
    glUseProgram(r->prog_stroke);
    glUniformMatrix4fv(r->ut.view, 1, GL_FALSE, f->fc.view);
    glUniformMatrix4fv(r->ut.proj, 1, GL_FALSE, f->fc.proj);
    glUniform2f(r->ut.viewport, (float)f->fw, (float)f->fh);
    glUniform1f(r->ut.ppu, f->fc.pixels_per_unit);
    glUniform1f(r->ut.width, stroke_width);
    glUniform1f(r->ut.half_max, pnpr_stroke_half_max(&f->o));
    glUniform1f(r->ut.radius_scale, f->point_scale);
    glUniform1i(r->ut.strokes, 0);
    glUniform4fv(r->ut.ink, 1, ink);
    glUniform1i(r->ut.ink_from_points, ink_from_points != 0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, r->stroke_tex);
}

/* Blending of premultiplied colours, no depth writes: the marks of pass 2. */
static void blend_marks(void)
{
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}

/* Pass 2 of `sketchy`: directional strokes and hatches of the groups' queue prefixes, depth-tested
 * against the mask, no depth writes, blended. Returns the strokes drawn. */
static size_t draw_sketchy(pnpr_renderer *r, const pnpr_frame_ctx *f)
{
    const pnpr_draw_options *o = &f->o;
    const float *ink = f->ink;
    size_t strokes = 0;
    float stroke_length = o->stroke_length;
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    blend_marks();
    stroke_program(r, f, o->stroke_width, ink, o->ink_from_points);
    int draw_group[3] = {1, o->sketch_variant != PNPR_SKETCH_DIRECTIONAL, o->sketch_variant == PNPR_SKETCH_ALL};
    /* the dithering hatches (tone) in a lighter pencil than the strokes and hatches of features */
    float tone_ink[4] = {ink[0], ink[1], ink[2], ink[3] * SKETCH_TONE_INK};
    for (int g = GROUP_DIRECTIONAL; g <= GROUP_DITHER; g++) {
        if (!draw_group[g] || !f->gdraw[g]) continue;
        int directional = g == GROUP_DIRECTIONAL;
        glUniform1i(r->ut.mode, directional ? 0 : 1);
        glUniform1f(r->ut.layer, directional ? (float)o->stroke_texture : (float)STROKE_LAYER_HATCH);
        glUniform1f(r->ut.length, directional ? stroke_length : 0.5f * stroke_length);
        glUniform1i(r->ut.thin, g == GROUP_DITHER);
        glUniform1f(r->ut.tone_radius, g == GROUP_DITHER ? r->tone_radius : 0.0f);
        glUniform4fv(r->ut.ink, 1, g == GROUP_DITHER ? tone_ink : ink);
        glUniform1i(r->ut.fade_in, 1);
        pnpr_renderer_vertex_attribs(r->vao_strokes, r->vbo, r->style_vbo, r->key_vbo, r->group_start[g], 1, 0);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)f->gdraw[g]);
        strokes += f->gdraw[g];
    }
    glUniform1i(r->ut.thin, 0);
    glUniform1f(r->ut.tone_radius, 0.0f);
    glUniform1i(r->ut.fade_in, 0);
    glUniform4fv(r->ut.ink, 1, ink);
    return strokes;
}

/* Pass 2 of `stipple`: the queue prefixes of the feature and dithering groups as dots of a fixed
 * screen size in the ink colour (antialiased edges), depth-tested against the mask, no depth
 * writes, blended. The splat program must be current with the frame's uniforms. */
static size_t draw_stipple(pnpr_renderer *r, const pnpr_frame_ctx *f)
{
    const pnpr_draw_options *o = &f->o;
    size_t dots = 0;
    blend_marks();
    glUniform1f(r->us.radius_scale, f->point_scale);
    glUniform1f(r->us.depth_push, 0.0f);
    glUniform1f(r->us.fade, 1.0f);
    glUniform4fv(r->us.fade_color, 1, f->ink);
    glUniform1f(r->us.fixed_size, o->dot_size);
    glBindVertexArray(r->vao_points);
    for (int g = GROUP_DIRECTIONAL; g <= GROUP_DITHER; g++) {
        if (!f->gdraw[g]) continue;
        glUniform1i(r->us.thin, g == GROUP_DITHER);
        glUniform1i(r->us.fade_in, 1);
        glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)f->gdraw[g]);
        dots += f->gdraw[g];
    }
    glUniform1i(r->us.thin, 0);
    glUniform1i(r->us.fade_in, 0);
    glUniform1f(r->us.fade, 0.0f);
    glUniform1f(r->us.fixed_size, 0.0f);
    return dots;
}

/* Pass 2 of `lines`: the segments, depth-tested against the mask (no mask when the cloud is
 * empty: nothing hides them), no depth writes, blended. Returns the segments drawn. */
static size_t draw_lines(pnpr_renderer *r, const pnpr_frame_ctx *f)
{
    const pnpr_draw_options *o = &f->o;
    const pnpr_frame_camera *fc = &f->fc;
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    blend_marks();
    /* the lines' offsets are relative to their own origin: view * translate(line - cloud origin) */
    double d[3] = {r->line_origin[0] - r->origin[0], r->line_origin[1] - r->origin[1],
                   r->line_origin[2] - r->origin[2]};
    float lview[16];
    memcpy(lview, fc->view, sizeof lview);
    for (int row = 0; row < 4; row++)
        lview[12 + row] = (float)((double)fc->view[row] * d[0] + (double)fc->view[4 + row] * d[1] +
                                  (double)fc->view[8 + row] * d[2] + (double)fc->view[12 + row]);
    glUseProgram(r->prog_line);
    glUniformMatrix4fv(r->ul.view, 1, GL_FALSE, lview);
    glUniformMatrix4fv(r->ul.proj, 1, GL_FALSE, fc->proj);
    glUniform2f(r->ul.viewport, (float)f->fw, (float)f->fh);
    glUniform1f(r->ul.width, o->line_width);
    /* orthographic: w = 1 everywhere, nothing to move onto the near plane (GL clips) */
    glUniform1f(r->ul.near_plane, fc->ortho ? -1e30f : (float)fc->near_plane);
    glUniform4fv(r->ul.ink, 1, f->ink);
    /* lines lie on the surface the mask is made of: pulled towards the eye by two mean disk
     * radii so that the mask's disks do not cut them into dashes (docs/rendering.md) */
    glUniform1f(r->ul.pull, 2.0f * r->mean_radius * f->point_scale * f->lod);
    glUniform1i(r->ul.ortho, fc->ortho);
    glUniform1f(r->ul.ppu, fc->pixels_per_unit);
    glUniform1f(r->ul.min_px, o->line_min_px);
    glBindVertexArray(r->vao_lines);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)r->line_segments);
    return r->line_segments;
}

/* ---- painterly ------------------------------------------------------------------------------ */

/* Painterly's dabs: pass L = 0..bins-1 draws bins L..bins-1 as brush dabs of pnpr_paint_brush(L)
 * disk radii in the pass's blended colours; it needs about 1/brush^2 of the points for the same
 * coverage; the dab fills about half its sprite, so of what the mask drew of each cell, the share
 * min(1, 2 count / (brush^2 x points of bins L..)) (the queues' scale: each cell's end times it).
 * Passes whose brush is larger than the mask disk test stencil == ref (the sky mask); the
 * smaller ones do not. */
static size_t draw_dabs(pnpr_renderer *r, const pnpr_frame_ctx *f, int filter, GLint ref, float mask_scale)
{
    size_t nb = r->paint_bins, dabs = 0;
    pnpr_renderer_vertex_attribs(r->vao_paint, r->paint_vbo, r->paint_style_vbo, r->paint_key_vbo, 0, 0, 0);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_FALSE);
    glStencilMask(0);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glStencilFunc(GL_EQUAL, ref, 0xFF);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(r->prog_paint);
    glUniformMatrix4fv(r->up.view, 1, GL_FALSE, f->fc.view);
    glUniformMatrix4fv(r->up.proj, 1, GL_FALSE, f->fc.proj);
    glUniform1f(r->up.ppu, f->fc.pixels_per_unit);
    glUniform1f(r->up.max_size, r->max_point_size);
    glUniform1i(r->up.style_filter, filter);
    glUniform1i(r->up.brush, 0);
    glBindTexture(GL_TEXTURE_2D, r->brush_tex);
    for (size_t L = 0; L < nb; L++) {
        float brush = pnpr_paint_brush(L, nb);
        size_t avail = r->paint_start[nb] - r->paint_start[L];
        /* 2: the dab (a 2:1 ellipse) covers about half its sprite */
        double share = fmin(1.0, 2.0 * (double)r->count / ((double)brush * brush * (double)(avail ? avail : 1)));
        glUniform1f(r->uq_paint.scale, (float)share);
        if (brush > mask_scale && !f->o.paint_no_sky_mask) glEnable(GL_STENCIL_TEST);
        else glDisable(GL_STENCIL_TEST);
        glUniform1f(r->up.radius_scale, f->point_scale * brush);
        /* attribute 2 <- this pass's colour level (vertex i's colour at level L is at L*count + i) */
        glBindBuffer(GL_ARRAY_BUFFER, r->paint_col_vbo);
        glVertexAttribPointer(2, PAINT_COL_BYTES, GL_UNSIGNED_BYTE, GL_TRUE, PAINT_COL_BYTES,
                              (const void *)(uintptr_t)(L * r->count * PAINT_COL_BYTES));
        for (size_t b = L; b < nb; b++) { /* + 1: the shader's product may round up */
            size_t m = pnpr_crq_cells_prefix(&r->paint_queue, b, f->end_max * (float)share + 1.0f);
            if (m > f->pdraw[b]) m = f->pdraw[b];
            if (!m) continue;
            glDrawArrays(GL_POINTS, (GLint)r->paint_start[b], (GLsizei)m);
            dabs += m;
        }
    }
    glUniform1f(r->uq_paint.scale, 1.0f);
    return dabs;
}

/* Painterly's directional strokes on top, inside the sky mask, in the points' own colours unless
 * an ink is asked for (no dark scratches). */
static size_t draw_paint_strokes(pnpr_renderer *r, const pnpr_frame_ctx *f, int filter)
{
    const pnpr_draw_options *o = &f->o;
    size_t n = f->gdraw[GROUP_DIRECTIONAL];
    if (o->paint_no_strokes || n == 0) return 0;
    if (!o->paint_no_sky_mask) glEnable(GL_STENCIL_TEST);
    else glDisable(GL_STENCIL_TEST);
    float ink[4];
    int ink_given = pnpr_draw_ink(o, ink);
    stroke_program(r, f, o->stroke_width, ink, o->ink_from_points || !ink_given);
    glUniform1i(r->ut_filter, filter);
    glUniform1i(r->ut.mode, 0);
    glUniform1f(r->ut.layer, (float)o->stroke_texture);
    glUniform1f(r->ut.length, o->stroke_length);
    pnpr_renderer_vertex_attribs(r->vao_strokes, r->vbo, r->style_vbo, r->key_vbo, r->group_start[GROUP_DIRECTIONAL], 1, 0);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)n);
    return n;
}

/* Painterly (section 5.3). Mask: the bins' queue prefixes (n_draw split over the bins) as enlarged
 * pushed disks into depth, writing stencil 1; it doubles as the underpainting: its disks in the
 * coarsest pass's blended colours, so that no paper shows between the dabs inside the painted
 * area (docs/rendering.md). Then the dabs (draw_dabs) and the directional strokes, stencil-tested.
 * filter >= 0 (a style map): only the points of style `filter`; the shared mask (with stencil
 * filter + 1 under the points of this style) is already drawn. Returns the dabs and strokes. */
static size_t draw_painterly(pnpr_renderer *r, const pnpr_frame_ctx *f, int filter)
{
    float mask_scale = pnpr_draw_mask_scale(&f->o, PNPR_STYLE_PAINTERLY);
    if (filter < 0) {
        splat_program(r, f);
        mask_spec m = {mask_scale, -1, 1, 1, 0, 0, 1};
        draw_mask(r, f, &m);
    }
    size_t dabs = draw_dabs(r, f, filter, filter >= 0 ? filter + 1 : 1, mask_scale);
    dabs += draw_paint_strokes(r, f, filter);
    glDisable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    return dabs;
}

/* ---- brush (stroke-based splatting) --------------------------------------------------------- */

/* The brush style (Lopes et al.; brush_gl.c): the visibility mask into depth and colour (the
 * point colours: an underpainting, so that no paper shows where the strokes' soft rims leave a
 * pixel partly covered, e.g. along the near side of a depth jump) and the surface info when
 * outlines follow, then the strokes of the queue prefixes depth-tested against it and
 * blended order-independently over the frame. filter >= 0 (a style map): only the points of style
 * `filter`; the shared mask is already drawn. Returns the strokes. */
static size_t draw_brush(pnpr_renderer *r, const pnpr_frame_ctx *f, int filter)
{
    if (filter < 0) {
        splat_program(r, f);
        mask_spec m = {f->mask_scale, -1, 0, 0, 0, f->outline, 1};
        draw_mask(r, f, &m);
    }
    size_t first[GROUP_MAX + 1];
    for (size_t g = 0; g < f->ng; g++) first[g] = r->group_start[g];
    float jitter = f->o.brush_jitter < 0 ? 0.0f : f->o.brush_jitter;
    pnpr_brush_pass p = {f->fc.view, f->fc.proj, f->o.brush_scale * f->point_scale, jitter, f->o.brush_blur, filter,
                         filter >= 0 ? filter + 1 : 0, r->fbo,
                         r->vbo, r->style_vbo, r->key_vbo, first, f->gdraw, f->ng};
    size_t n = pnpr_brush_gl_draw(&r->brush, &p);
    glUseProgram(r->prog_splat);
    return n;
}

/* Chi & Lee's hierarchy (hierarchy_gl.c): the visibility mask (for the paint map with the point
 * colours as underpainting, as brush; hatching and dots on the paper), then the strokes the
 * traversal chose, within the style's stencil in a style map. */
static size_t draw_hierarchy(pnpr_renderer *r, const pnpr_frame_ctx *f, int filter)
{
    int paint = f->o.hierarchy.tam == PNPR_TAM_PAINT;
    if (filter < 0) {
        splat_program(r, f);
        mask_spec m = {f->mask_scale, -1, 0, 0, 0, f->outline, paint};
        draw_mask(r, f, &m);
    }
    pnpr_frame_camera lod;
    int frozen = f->o.hierarchy.lod_camera &&
                 pnpr_frame_camera_from_matrices(f->o.hierarchy.lod_camera, r->origin, f->fw, f->fh, &lod, NULL) == PNPR_OK;
    pnpr_hier_pass p = {f->fc.view, f->fc.proj, f->image_proj, r->origin, f->fw, f->fh, f->fc.pixels_per_unit,
                        f->fc.ortho, frozen ? lod.view : NULL, frozen ? lod.proj : NULL, frozen ? lod.pixels_per_unit : 0,
                        f->o.hierarchy, filter >= 0 ? filter + 1 : 0, r->fbo};
    for (int k = 0; k < 3; k++) p.params.ink[k] = f->ink[k];
    pnpr_hier_counts c;
    size_t n = pnpr_hier_gl_draw(&r->hier, &r->brush, &p, &c) == PNPR_OK ? c.strokes[PNPR_HIER_PAINT] : 0;
    glUseProgram(r->prog_splat);
    return n;
}

/* ---- one style ------------------------------------------------------------------------------ */

size_t pnpr_renderer_draw_single(pnpr_renderer *r, const pnpr_frame_ctx *f)
{
    const pnpr_draw_options *o = &f->o;
    pnpr_style s = o->style;
    int cartoon = s == PNPR_STYLE_CARTOON;
    size_t strokes = 0;
    if (f->n_draw > 0 && s == PNPR_STYLE_PAINTERLY) return draw_painterly(r, f, -1);
    if (f->n_draw > 0 && s == PNPR_STYLE_BRUSH) return draw_brush(r, f, -1);
    if (f->n_draw > 0 && s == PNPR_STYLE_HIERARCHY) return draw_hierarchy(r, f, -1);
    if (f->n_draw > 0) {
        splat_program(r, f);
        if (s == PNPR_STYLE_LINES && o->faint > 0) {
            /* lines over a faint point rendering, then a fresh depth buffer for the mask */
            draw_faint(r, f);
            glClear(GL_DEPTH_BUFFER_BIT);
        }
        float levels = r->has_labels || !r->has_rgb ? 0.0f : (float)o->levels;
        if (s == PNPR_STYLE_POINTS) {
            draw_splats(r, f, r->vao_points); /* the only pass */
        } else {
            /* pass 1: the mask, writing the surface info for the outlines. Cartoon: the enlarged
             * disks go into depth AND colour, in the flat colours (they close the gaps between the
             * splats) */
            if (cartoon) glUniform1f(r->us.levels, levels);
            mask_spec m = {f->mask_scale, -1, 0, 0, cartoon, f->outline, cartoon};
            draw_mask(r, f, &m);
        }
        if (cartoon) {
            /* pass 2: the same points as regular-size opaque splats in flat colours, depth-tested
             * against the enlarged disks, no depth writes, the frame not cleared */
            glDepthMask(GL_FALSE);
            glUniform1f(r->us.levels, levels);
            draw_splats(r, f, r->vao_flat);
            glUniform1f(r->us.levels, 0.0f);
        }
        if (s == PNPR_STYLE_SKETCHY) strokes += draw_sketchy(r, f);
        if (s == PNPR_STYLE_STIPPLE) strokes += draw_stipple(r, f);
    }
    if (s == PNPR_STYLE_LINES && r->line_segments > 0) strokes = draw_lines(r, f);
    return strokes;
}

/* ---- style maps (intermingled styles) ------------------------------------------------------- */

/* Pass 1 of a style map, the one visibility mask: every style's points of the queue prefixes
 * (painterly's from its bin queues) as enlarged pushed disks into depth, each writing stencil =
 * its style + 1 where it passes (the front-most surface's style); cartoon's disks are its outline
 * disks (outline scale, ink colour), drawn after the others. */
static void draw_mapped_mask(pnpr_renderer *r, const pnpr_frame_ctx *f)
{
    const pnpr_draw_options *o = &f->o;
    float mask_scale = pnpr_draw_mask_scale(o, PNPR_STYLE_POINTS); /* every style's but cartoon's */
    float outline_scale = pnpr_draw_mask_scale(o, PNPR_STYLE_CARTOON);
    splat_program(r, f);
    for (int s = 0; s < PNPR_STYLE_COUNT_; s++) {
        if (!f->used[s] || s == PNPR_STYLE_CARTOON) continue;
        /* brush: its underpainting (the point colours), as without a map */
        int under = s == PNPR_STYLE_BRUSH || (s == PNPR_STYLE_HIERARCHY && f->o.hierarchy.tam == PNPR_TAM_PAINT);
        mask_spec m = {mask_scale, s, s + 1, s == PNPR_STYLE_PAINTERLY, 0, 0, under};
        draw_mask(r, f, &m);
    }
    if (f->used[PNPR_STYLE_CARTOON]) { /* outline disks: depth and colour (ink) */
        glUniform1f(r->us.fade, 1.0f);
        glUniform4f(r->us.fade_color, f->ink[0], f->ink[1], f->ink[2], 1.0f);
        mask_spec m = {outline_scale, PNPR_STYLE_CARTOON, PNPR_STYLE_CARTOON + 1, 0, 0, 0, 1};
        draw_mask(r, f, &m);
        glUniform1f(r->us.fade, 0.0f);
    }
    glStencilMask(0);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glDisable(GL_STENCIL_TEST);
}

/* A frame with several styles (a style map): the shared mask (draw_mapped_mask), then pass 2,
 * each style over its own points (a vertex-shader filter on the style byte), in the order points
 * (opaque, depth writes), cartoon fills, painterly (sky stencil = its style), stipple, sketchy,
 * lines (stencil = the lines style: the lines show over those segments only). With f->pass_only,
 * pass 2 of that style alone (vector drawings, vector.c). */
size_t pnpr_renderer_draw_mapped(pnpr_renderer *r, const pnpr_frame_ctx *f)
{
    size_t used[PNPR_STYLE_COUNT_], strokes = 0;
    for (int s = 0; s < PNPR_STYLE_COUNT_; s++) used[s] = f->pass_only && s != f->pass_only - 1 ? 0 : f->used[s];
    draw_mapped_mask(r, f);
    if (used[PNPR_STYLE_POINTS]) { /* opaque splats, depth writes (the nearest wins) */
        glUniform1i(r->us_filter, PNPR_STYLE_POINTS);
        draw_splats(r, f, r->vao_points);
    }
    glDepthMask(GL_FALSE);
    if (used[PNPR_STYLE_CARTOON]) { /* flat colours over the outline disks */
        glUniform1i(r->us_filter, PNPR_STYLE_CARTOON);
        draw_splats(r, f, r->vao_flat);
    }
    if (used[PNPR_STYLE_LINES] && f->o.faint > 0) { /* the faint points under the lines segments */
        glUniform1i(r->us_filter, PNPR_STYLE_LINES);
        draw_faint(r, f);
    }
    if (used[PNPR_STYLE_PAINTERLY] && r->paint_bins) {
        strokes += draw_painterly(r, f, PNPR_STYLE_PAINTERLY);
        glUniform1i(r->ut_filter, -1);
        glUseProgram(r->prog_paint);
        glUniform1i(r->up.style_filter, -1);
        glUseProgram(r->prog_splat);
    }
    if (used[PNPR_STYLE_BRUSH]) {
        strokes += draw_brush(r, f, PNPR_STYLE_BRUSH);
        glEnable(GL_DEPTH_TEST);
    }
    if (used[PNPR_STYLE_HIERARCHY]) {
        strokes += draw_hierarchy(r, f, PNPR_STYLE_HIERARCHY);
        glEnable(GL_DEPTH_TEST);
    }
    if (used[PNPR_STYLE_STIPPLE]) {
        glUniform1i(r->us_filter, PNPR_STYLE_STIPPLE);
        strokes += draw_stipple(r, f);
    }
    glUniform1i(r->us_filter, -1);
    if (used[PNPR_STYLE_SKETCHY]) {
        glUseProgram(r->prog_stroke);
        glUniform1i(r->ut_filter, PNPR_STYLE_SKETCHY);
        strokes += draw_sketchy(r, f);
        glUniform1i(r->ut_filter, -1);
    }
    if (used[PNPR_STYLE_LINES] && r->line_segments > 0) {
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_EQUAL, PNPR_STYLE_LINES + 1, 0xFF);
        strokes += draw_lines(r, f);
        glDisable(GL_STENCIL_TEST);
    }
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    return strokes;
}
