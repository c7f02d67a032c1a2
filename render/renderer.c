/* The PointWorks renderer: two-pass visibility mask (section 4.3), continuous resolution queue
 * (4.4), `points`, `sketchy` (5.1), `lines` (5.2), `stipple` and `cartoon` (5.4) styles, per-segment
 * style maps (intermingled styles, figure 12). See docs/rendering.md. This file: create / destroy,
 * the draw options check, the frame plan and the draw entry (one frame or one tile); the upload,
 * the passes, snapshots and textures are in renderer_*.c (renderer_internal.h lists them). */
#include "renderer_internal.h"
#include "gl_state.h"
#include "pnpr_shaders.h"

#include <pointnpr/brush.h>
#include <pointnpr/features.h>

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- create / destroy ----------------------------------------------------------------------- */

static void release_gl(pnpr_renderer *r)
{
    if (r->prog_splat) glDeleteProgram(r->prog_splat);
    if (r->prog_stroke) glDeleteProgram(r->prog_stroke);
    if (r->prog_composite) glDeleteProgram(r->prog_composite);
    if (r->prog_line) glDeleteProgram(r->prog_line);
    if (r->prog_paint) glDeleteProgram(r->prog_paint);
    if (r->paint_vbo) glDeleteBuffers(1, &r->paint_vbo);
    if (r->paint_col_vbo) glDeleteBuffers(1, &r->paint_col_vbo);
    if (r->vao_paint) glDeleteVertexArrays(1, &r->vao_paint);
    if (r->brush_tex) glDeleteTextures(1, &r->brush_tex);
    if (r->vbo) glDeleteBuffers(1, &r->vbo);
    if (r->style_vbo) glDeleteBuffers(1, &r->style_vbo);
    if (r->paint_style_vbo) glDeleteBuffers(1, &r->paint_style_vbo);
    if (r->line_vbo) glDeleteBuffers(1, &r->line_vbo);
    if (r->key_vbo) glDeleteBuffers(1, &r->key_vbo);
    if (r->paint_key_vbo) glDeleteBuffers(1, &r->paint_key_vbo);
    if (r->cells_buf) glDeleteBuffers(1, &r->cells_buf);
    if (r->cells_tex) glDeleteTextures(1, &r->cells_tex);
    GLuint vaos[5] = {r->vao_points, r->vao_strokes, r->vao_empty, r->vao_lines, r->vao_flat};
    glDeleteVertexArrays(5, vaos);
    if (r->stroke_tex) glDeleteTextures(1, &r->stroke_tex);
    if (r->color_tex) glDeleteTextures(1, &r->color_tex);
    if (r->depth_rb) glDeleteRenderbuffers(1, &r->depth_rb);
    if (r->info_tex) glDeleteTextures(1, &r->info_tex);
    pnpr_edges_release(&r->edges);
    pnpr_brush_gl_release(&r->brush);
    pnpr_hier_gl_release(&r->hier);
    if (r->fbo) glDeleteFramebuffers(1, &r->fbo);
}

void pnpr_renderer_vertex_attribs(GLuint vao, GLuint vbo, GLuint sbo, GLuint kbo, size_t first, int instanced, int flat)
{
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    /* buffer offsets travel as pointers in GL's API: build them from integers */
#define PNPR_ATTR_OFFSET(field) ((const void *)(uintptr_t)(first * sizeof(pnpr_vertex) + offsetof(pnpr_vertex, field)))
    GLsizei stride = (GLsizei)sizeof(pnpr_vertex);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, PNPR_ATTR_OFFSET(pos));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, stride, PNPR_ATTR_OFFSET(radius));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride, flat ? PNPR_ATTR_OFFSET(flat) : PNPR_ATTR_OFFSET(rgba));
    glEnableVertexAttribArray(5);
    glVertexAttribPointer(5, 4, GL_BYTE, GL_TRUE, stride, PNPR_ATTR_OFFSET(normal));
    if (instanced) {
        glEnableVertexAttribArray(3);
        glVertexAttribPointer(3, 3, GL_FLOAT, GL_FALSE, stride, PNPR_ATTR_OFFSET(dir));
        for (GLuint a = 0; a < 4; a++) glVertexAttribDivisor(a, 1);
        glVertexAttribDivisor(5, 1);
    }
#undef PNPR_ATTR_OFFSET
    /* attribute 4: the style byte of a style map (one byte per vertex in `sbo`) */
    glBindBuffer(GL_ARRAY_BUFFER, sbo);
    glEnableVertexAttribArray(4);
    glVertexAttribIPointer(4, 1, GL_UNSIGNED_BYTE, 1, (const void *)(uintptr_t)first);
    if (instanced) glVertexAttribDivisor(4, 1);
    /* attribute 7: the per-cell queue key (uint16 per vertex in `kbo`) */
    glBindBuffer(GL_ARRAY_BUFFER, kbo);
    glEnableVertexAttribArray(7);
    glVertexAttribIPointer(7, 1, GL_UNSIGNED_SHORT, 2, (const void *)(uintptr_t)(2 * first));
    if (instanced) glVertexAttribDivisor(7, 1);
}

/* The programs, in order; 0 (and the compiler's log in err) at the first that fails. */
static int link_programs(pnpr_renderer *r, pnpr_error *err)
{
    r->prog_splat = pnpr_gl_link_program(pnpr_shader_splat_vert, pnpr_shader_splat_frag, "splat", err);
    r->prog_stroke = r->prog_splat ? pnpr_gl_link_program(pnpr_shader_stroke_vert, pnpr_shader_stroke_frag, "stroke", err) : 0;
    r->prog_composite = r->prog_stroke ? pnpr_gl_link_program(pnpr_shader_composite_vert, pnpr_shader_composite_frag, "composite", err) : 0;
    r->prog_line = r->prog_composite ? pnpr_gl_link_program(pnpr_shader_line_vert, pnpr_shader_line_frag, "line", err) : 0;
    r->prog_paint = r->prog_line ? pnpr_gl_link_program(pnpr_shader_paint_vert, pnpr_shader_paint_frag, "paint", err) : 0;
    return r->prog_paint != 0;
}

#define U(S, m, name) {name, offsetof(S, m)}
static const pnpr_gl_uniform splat_table[] = {
    U(splat_uniforms, view, "u_view"), U(splat_uniforms, proj, "u_proj"), U(splat_uniforms, ppu, "u_pixels_per_unit"),
    U(splat_uniforms, radius_scale, "u_radius_scale"), U(splat_uniforms, depth_push, "u_depth_push"),
    U(splat_uniforms, max_size, "u_max_size"), U(splat_uniforms, fade, "u_fade"), U(splat_uniforms, fade_color, "u_fade_color"),
    U(splat_uniforms, fixed_size, "u_fixed_size"), U(splat_uniforms, levels, "u_levels"), U(splat_uniforms, ortho, "u_ortho"),
    U(splat_uniforms, thin, "u_thin"), U(splat_uniforms, fade_in, "u_fade_in"),
};
static const pnpr_gl_uniform stroke_table[] = {
    U(stroke_uniforms, view, "u_view"), U(stroke_uniforms, proj, "u_proj"), U(stroke_uniforms, viewport, "u_viewport"),
    U(stroke_uniforms, ppu, "u_pixels_per_unit"), U(stroke_uniforms, length, "u_length"), U(stroke_uniforms, width, "u_width"),
    U(stroke_uniforms, radius_scale, "u_radius_scale"), U(stroke_uniforms, mode, "u_mode"),
    U(stroke_uniforms, strokes, "u_strokes"), U(stroke_uniforms, layer, "u_layer"), U(stroke_uniforms, ink, "u_ink"),
    U(stroke_uniforms, ink_from_points, "u_ink_from_points"), U(stroke_uniforms, thin, "u_thin"),
    U(stroke_uniforms, fade_in, "u_fade_in"),
    U(stroke_uniforms, tone_radius, "u_tone_radius"), U(stroke_uniforms, half_max, "u_half_max"),
};
static const pnpr_gl_uniform paint_table[] = {
    U(paint_uniforms, view, "u_view"), U(paint_uniforms, proj, "u_proj"), U(paint_uniforms, ppu, "u_pixels_per_unit"),
    U(paint_uniforms, radius_scale, "u_radius_scale"), U(paint_uniforms, max_size, "u_max_size"),
    U(paint_uniforms, style_filter, "u_style_filter"), U(paint_uniforms, brush, "u_brush"),
};
static const pnpr_gl_uniform line_table[] = {
    U(line_uniforms, view, "u_view"), U(line_uniforms, proj, "u_proj"), U(line_uniforms, viewport, "u_viewport"),
    U(line_uniforms, width, "u_width"), U(line_uniforms, near_plane, "u_near"), U(line_uniforms, ink, "u_ink"),
    U(line_uniforms, pull, "u_pull"), U(line_uniforms, ortho, "u_ortho"), U(line_uniforms, ppu, "u_pixels_per_unit"),
    U(line_uniforms, min_px, "u_min_px"),
};
#undef U
#define FIND(prog, table, locations) pnpr_gl_find_uniforms(prog, table, sizeof table / sizeof table[0], locations)

/* The paint, line and composite programs' uniforms, then the splat and stroke programs'; no
 * style filter unless a style map is drawn (uniforms are program state). */
static void find_uniforms(pnpr_renderer *r)
{
    FIND(r->prog_paint, paint_table, &r->up);
    FIND(r->prog_line, line_table, &r->ul);
    r->uc_frame = glGetUniformLocation(r->prog_composite, "u_frame");
    r->uc_origin = glGetUniformLocation(r->prog_composite, "u_origin");
    FIND(r->prog_splat, splat_table, &r->us);
    r->us_filter = glGetUniformLocation(r->prog_splat, "u_style_filter");
    FIND(r->prog_stroke, stroke_table, &r->ut);
    pnpr_queue_uniforms_find(r->prog_splat, &r->uq_splat);
    pnpr_queue_uniforms_find(r->prog_stroke, &r->uq_stroke);
    pnpr_queue_uniforms_find(r->prog_paint, &r->uq_paint);
    r->ut_filter = glGetUniformLocation(r->prog_stroke, "u_style_filter");
    glUseProgram(r->prog_splat);
    glUniform1i(r->us_filter, -1);
    glUseProgram(r->prog_stroke);
    glUniform1i(r->ut_filter, -1);
    glUseProgram(r->prog_paint);
    glUniform1i(r->up.style_filter, -1);
    glUseProgram(0);
}

/* The vertex buffers and the vertex arrays that read them: the points (plain, instanced strokes,
 * flat colours), their style bytes, the line segments (two ends and the polyline's length per
 * instance) and the painterly vertices (attribute 2 re-pointed per pass at their colour levels). */
static void make_vertex_arrays(pnpr_renderer *r)
{
    glGenBuffers(1, &r->vbo);
    glGenVertexArrays(1, &r->vao_points);
    glGenVertexArrays(1, &r->vao_strokes);
    glGenVertexArrays(1, &r->vao_empty);
    glGenVertexArrays(1, &r->vao_flat);
    glGenBuffers(1, &r->style_vbo);
    glGenBuffers(1, &r->paint_style_vbo);
    glGenBuffers(1, &r->key_vbo);
    glGenBuffers(1, &r->paint_key_vbo);
    glGenBuffers(1, &r->cells_buf);
    glGenTextures(1, &r->cells_tex);
    pnpr_renderer_vertex_attribs(r->vao_points, r->vbo, r->style_vbo, r->key_vbo, 0, 0, 0);
    pnpr_renderer_vertex_attribs(r->vao_strokes, r->vbo, r->style_vbo, r->key_vbo, 0, 1, 0);
    pnpr_renderer_vertex_attribs(r->vao_flat, r->vbo, r->style_vbo, r->key_vbo, 0, 0, 1);
    glGenBuffers(1, &r->line_vbo);
    glGenVertexArrays(1, &r->vao_lines);
    glBindVertexArray(r->vao_lines);
    glBindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, LINE_FLOATS * sizeof(float), (const void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, LINE_FLOATS * sizeof(float), (const void *)(uintptr_t)(3 * sizeof(float)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, LINE_FLOATS * sizeof(float), (const void *)(uintptr_t)(6 * sizeof(float)));
    glVertexAttribDivisor(2, 1);
    glVertexAttribDivisor(0, 1);
    glVertexAttribDivisor(1, 1);
    glGenBuffers(1, &r->paint_vbo);
    glGenBuffers(1, &r->paint_col_vbo);
    glGenVertexArrays(1, &r->vao_paint);
    pnpr_renderer_vertex_attribs(r->vao_paint, r->paint_vbo, r->paint_style_vbo, r->paint_key_vbo, 0, 0, 0);
}

/* GL's limits: the largest point size, the largest frame (texture, renderbuffer and viewport). */
static void query_limits(pnpr_renderer *r)
{
    GLfloat range[2] = {1, 1};
    glGetFloatv(GL_POINT_SIZE_RANGE, range);
    r->max_point_size = range[1] >= 1 ? range[1] : 1;
    GLint a = 0, b = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &a);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &b);
    r->max_size = a < b ? a : b;
    GLint vp[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
    if (vp[0] > 0 && vp[0] < r->max_size) r->max_size = vp[0];
    if (vp[1] > 0 && vp[1] < r->max_size) r->max_size = vp[1];
}

/* The per-cell queues' test (pnpr_renderer_queue_alpha is its twin on the CPU): the point's cell
 * from its position, the cell's row of the frame's table (end, fade-in length, disk growth). */
static const char queue_glsl[] =
    "uniform samplerBuffer u_cells;\n"
    "uniform vec3 u_cell_min;\n"
    "uniform float u_cell_inv;\n"
    "uniform ivec3 u_cell_n;\n"
    "uniform float u_queue_scale;\n"
    "float pnpr_queue(vec3 p, uint key, out float grow)\n"
    "{\n"
    "    ivec3 c;\n"
    "    for (int a = 0; a < 3; a++) {\n"
    "        float t = (p[a] - u_cell_min[a]) * u_cell_inv;\n"
    "        c[a] = !(t >= 0.0) ? 0 : t >= float(u_cell_n[a]) ? u_cell_n[a] - 1 : int(t);\n"
    "    }\n"
    "    vec4 q = texelFetch(u_cells, (c.z * u_cell_n.y + c.y) * u_cell_n.x + c.x);\n"
    "    float end = q.x * u_queue_scale, u = float(key) + 0.5;\n"
    "    grow = q.z;\n"
    "    if (!(u < end)) return -1.0;\n"
    "    return q.y > 0.0 ? clamp((end - u) / q.y, 0.0, 1.0) : 1.0;\n"
    "}\n"
    "float pnpr_queue_size(float size, float grow)\n" /* a disk grown, at most to a cell's side */
    "{\n"
    "    return max(size, min(size * grow, 1.0 / u_cell_inv));\n"
    "}\n";

/* with room for the constants' lines before it */
_Static_assert(sizeof queue_glsl + 256 <= PNPR_SHADER_PRELUDE_MAX, "the queue's GLSL fits the shader prelude");

void pnpr_shader_prelude(char *buf, size_t cap)
{
    const float h1[3] = {HATCH_DIR}, h2[3] = {HATCH_DIR2};
    snprintf(buf, cap,
             "#define PNPR_VSTYLE_HIDDEN %uu\n#define PNPR_BRUSH_VARIANTS %uu\n"
             "#define PNPR_HATCH_DIR vec3(%.9g, %.9g, %.9g)\n#define PNPR_HATCH_DIR2 vec3(%.9g, %.9g, %.9g)\n%s",
             (unsigned)PNPR_VSTYLE_HIDDEN, (unsigned)PNPR_BRUSH_VARIANTS, (double)h1[0], (double)h1[1], (double)h1[2],
             (double)h2[0], (double)h2[1], (double)h2[2], queue_glsl);
}

double pnpr_renderer_queue_alpha(const pnpr_renderer *r, const float p[3], uint16_t key)
{
    const float *q = r->cell_table + 4 * (size_t)pnpr_view_cells_index(&r->view_cells, p);
    float end = q[0], u = (float)key + 0.5f;
    if (!(u < end)) return -1;
    if (!(q[1] > 0)) return 1;
    double a = ((double)end - u) / q[1];
    return a < 0 ? 0 : a > 1 ? 1 : a;
}

pnpr_status pnpr_renderer_create(const pnpr_renderer_options *opts, pnpr_renderer **r_renderer,
                                 pnpr_error *err)
{
    (void)opts;
    if (!r_renderer) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: no result pointer");
    *r_renderer = NULL;
    /* glGetString is a GL 1.0 entry point that libepoxy resolves without a context; with no
     * current context the GL dispatch answers NULL. */
    const GLubyte *version = glGetString(GL_VERSION);
    if (!version)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "renderer: no current OpenGL context");
    if (epoxy_is_desktop_gl() == 0 || epoxy_gl_version() < 33)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                              "renderer: needs desktop OpenGL 3.3 core, the context has \"%s\"", (const char *)version);
    pnpr_renderer *r = calloc(1, sizeof *r);
    if (!r) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    pnpr_gl_state_neutral();
    pnpr_status st = PNPR_OK;
    if (!link_programs(r, err) || pnpr_edges_create(&r->edges, err) != PNPR_OK ||
        pnpr_brush_gl_create(&r->brush, err) != PNPR_OK || pnpr_hier_gl_create(&r->hier, err) != PNPR_OK)
        st = PNPR_ERR_UNSUPPORTED;
    if (st == PNPR_OK) {
        find_uniforms(r);
        make_vertex_arrays(r);
        st = pnpr_renderer_make_textures(r);
    }
    if (st == PNPR_OK) query_limits(r);
    if (st != PNPR_OK) {
        release_gl(r);
        free(r);
        r = NULL;
    }
    pnpr_gl_state_restore(&saved);
    *r_renderer = r;
    return st;
}

void pnpr_renderer_destroy(pnpr_renderer *r)
{
    if (!r) return;
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    release_gl(r);
    free(r->vlabel);
    free(r->ulabels);
    free(r->paint_src);
    free(r->vstyle);
    free(r->cell_table);
    pnpr_crq_cells_free(&r->queue);
    pnpr_crq_cells_free(&r->paint_queue);
    /* deleting a bound object unbinds it: put back what the host had (names it still owns) */
    pnpr_gl_state_restore(&saved);
    free(r);
}

/* ---- the draw options and the frame plan ---------------------------------------------------- */

static int finite4(const float *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]) && isfinite(v[3]); }

/* Painterly without its data: left out at upload (pnpr_upload_options.skip_painterly), or the
 * cloud has no feature_degree. `what`: the style or map entry, as the message names it. */
static pnpr_status painterly_missing(const pnpr_renderer *r, const char *what, pnpr_error *err)
{
    if (r->paint_skipped)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: %s: the cloud was uploaded without its "
                              "painterly data (pnpr_upload_options.skip_painterly)", what);
    return pnpr_error_set(err, PNPR_ERR_NOT_FOUND, "renderer: %s needs the feature properties feature_degree, "
                          "feature_class and feature_dir_x/y/z (pnpr_compute_features)", what);
}

pnpr_status pnpr_renderer_check_options(const pnpr_renderer *r, const pnpr_draw_options *opts, pnpr_draw_options *o,
                                        pnpr_error *err)
{
    memset(o, 0, sizeof *o);
    if (opts) *o = *opts;
    if ((unsigned)o->style >= PNPR_STYLE_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: unknown style %d", (int)o->style);
    if ((unsigned)o->sketch_variant >= PNPR_SKETCH_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: unknown sketch variant %d", (int)o->sketch_variant);
    if ((unsigned)o->composite >= PNPR_COMPOSITE_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: unknown composite mode %d", (int)o->composite);
    if (o->stroke_texture < 0 || o->stroke_texture > 2)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: stroke texture %d is not 0, 1 or 2", o->stroke_texture);
    if (!finite4(o->background))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: the background colour must be finite");
    pnpr_status cst = pnpr_draw_check(o, err); /* every tabled option against its range (options.h) */
    if (cst != PNPR_OK) return cst;
    if (pnpr_style_needs_features(o->style) && o->style != PNPR_STYLE_PAINTERLY && r->count > 0 && !r->has_features)
        return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                              "renderer: style '%s' needs the feature properties feature_class and feature_dir_x/y/z (pnpr_compute_features)",
                              pnpr_style_name(o->style));
    if (o->style == PNPR_STYLE_PAINTERLY && r->count > 0 && !r->paint_bins)
        return painterly_missing(r, "style 'painterly'", err);
    if (o->style == PNPR_STYLE_BRUSH && r->count > 0 && !r->brush.ready)
        return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                              "renderer: style 'brush' needs the properties brush_size and brush_cluster (pnpr_brush_prepare)");
    if (o->style == PNPR_STYLE_HIERARCHY && r->count > 0 && !r->hier.tree)
        return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                              "renderer: style 'hierarchy' needs a sphere tree (pnpr_sphere_tree_build, pnpr_renderer_set_hierarchy)");
    size_t nh;
    const pnpr_option_desc *ht = pnpr_hier_option_table(&nh);
    pnpr_status hst = pnpr_option_check(ht, nh, &o->hierarchy, err);
    if (hst != PNPR_OK) return hst;
    pnpr_option_fill_defaults(ht, nh, &o->hierarchy);
    if (o->hierarchy.importance && (o->hierarchy.importance_w <= 0 || o->hierarchy.importance_h <= 0))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: hierarchy importance map of size %dx%d",
                              o->hierarchy.importance_w, o->hierarchy.importance_h);
    if (o->style_map_count > 0 && !o->style_map)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: style_map_count %zu without a style map", o->style_map_count);
    if (o->layer_label_count > 0 && !o->layer_labels)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: layer_label_count %zu without labels", o->layer_label_count);
    if (o->style_map_count > 0xFFFFFFFFu)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: style map too large (%zu entries)", o->style_map_count);
    for (size_t i = 0; i < o->style_map_count; i++) {
        pnpr_style s = o->style_map[i].style;
        if ((unsigned)s >= PNPR_STYLE_COUNT_)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: style map entry %zu (label %u): unknown style %d",
                                  i, (unsigned)o->style_map[i].label, (int)s);
        if (r->count == 0) continue;
        if (s == PNPR_STYLE_PAINTERLY && !r->paint_bins) {
            char which[64];
            snprintf(which, sizeof which, "style map: label %u is 'painterly', which", (unsigned)o->style_map[i].label);
            return painterly_missing(r, which, err);
        }
        if (s == PNPR_STYLE_HIERARCHY && !r->hier.tree)
            return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                                  "renderer: style map: label %u is 'hierarchy', which needs a sphere tree (pnpr_renderer_set_hierarchy)",
                                  (unsigned)o->style_map[i].label);
        if (s == PNPR_STYLE_BRUSH && !r->brush.ready)
            return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                                  "renderer: style map: label %u is 'brush', which needs the properties brush_size and brush_cluster (pnpr_brush_prepare)",
                                  (unsigned)o->style_map[i].label);
        if (pnpr_style_needs_features(s) && s != PNPR_STYLE_PAINTERLY && !r->has_features)
            return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                                  "renderer: style map: label %u is '%s', which needs the feature properties feature_class and feature_dir_x/y/z (pnpr_compute_features)",
                                  (unsigned)o->style_map[i].label, pnpr_style_name(s));
    }
    /* the zeros that mean "the default" become the table's defaults (options.h); those of the
     * style (mask scale, ink, outlines) stay 0 and are resolved where the style is known */
    size_t n = 0;
    const pnpr_option_desc *table = pnpr_draw_option_table(&n);
    pnpr_option_fill_defaults(table, n, o);
    return PNPR_OK;
}

/* The vertices a frame sends with every cell's end at most `end`: the groups' prefixes. */
static size_t sent_below(const pnpr_renderer *r, float end)
{
    size_t n = 0;
    for (size_t g = 0; g <= r->group_count; g++) n += pnpr_crq_cells_prefix(&r->queue, g, end);
    return n;
}

/* The frame's table of the per-cell queues (r->cell_table; crq.h, docs/rendering.md "Continuous
 * resolution queue") for the view `fc`: `want` points in view (< 0: every point), shared among the
 * cells in view by their weights (pnpr_view_cells_weights, _solve: a cell at eye depth z draws
 * min(1, c / z^2) of its points). A cell out of view draws by its weight too, at most the largest
 * share in view: no vertex more is sent, and disks and marks beyond the picture's edge still
 * reach into it (guard bands, tiles). The budget caps the vertices sent (the groups' prefixes up
 * to the largest end): over it, every end is cut to the largest that fits (one key level at
 * least), the far cells keeping their smaller shares. Each cell's disks grow by 1 / sqrt(share),
 * at most to the cell's side (pnpr_queue_size). Fills the plan's counts (in view). */
static void plan_cells(pnpr_renderer *r, const pnpr_draw_options *o, const pnpr_frame_camera *fc, double want,
                       frame_plan *p)
{
    float *t = r->cell_table;
    size_t cells = r->count ? r->cells : 0;
    double c = HUGE_VAL;
    for (size_t k = 0; k < cells; k++) t[4 * k + 3] = r->view_cells.count[k] ? 1.0f : 0.0f;
    if (want >= 0 && cells) {
        pnpr_view_cells_weights(&r->view_cells, fc, t + 3, 4); /* the weights in column 3, < 0 out of view */
        c = pnpr_view_cells_solve(&r->view_cells, t + 3, 4, want);
    }
    float end_max = 0;
    for (size_t k = 0; k < cells; k++) {
        double w = t[4 * k + 3];
        t[4 * k] = w > 0 ? (float)(PNPR_CRQ_KEYS * fmin(1.0, c * w)) : 0.0f;
        if (t[4 * k] > end_max) end_max = t[4 * k];
    }
    for (size_t k = 0; k < cells; k++)
        if (t[4 * k + 3] < 0) t[4 * k] = fminf((float)(PNPR_CRQ_KEYS * fmin(1.0, c * -t[4 * k + 3])), end_max);
    if (o->budget > 0 && cells && sent_below(r, end_max) > o->budget) {
        size_t lo = 1, hi = PNPR_CRQ_KEYS; /* the most key levels kv whose prefixes fit (one at least) */
        while (lo < hi) {
            size_t mid = lo + (hi - lo + 1) / 2;
            if (sent_below(r, (float)mid + 0.5f) <= o->budget) lo = mid;
            else hi = mid - 1;
        }
        float cut = (float)lo + 0.5f; /* keeps the keys below lo */
        for (size_t k = 0; k < cells; k++)
            if (t[4 * k] > cut) t[4 * k] = cut;
    }
    /* the points drawn in view: the ends of the cells in view in column 1 (the fade, written below) */
    size_t in_view = 0;
    for (size_t k = 0; k < cells; k++) {
        t[4 * k + 1] = t[4 * k + 3] > 0 ? t[4 * k] : 0.0f;
        if (t[4 * k + 3] > 0) in_view += r->view_cells.count[k];
    }
    p->n_draw = cells ? pnpr_crq_cells_drawn(&r->queue, t + 1, 4) : 0;
    p->lod = p->n_draw > 0 ? (float)sqrt((double)in_view / (double)p->n_draw) : 1;
    p->end_max = 0;
    p->lod_max = 1;
    /* a disk grows at most to a cell's side (pnpr_queue_size): the largest disk is the larger of
     * the largest radius and the side */
    double lod_cap = r->max_radius > 0 ? fmax(1.0, r->view_cells.cell / r->max_radius) : 1.0;
    for (size_t k = 0; k < cells; k++) {
        float e = t[4 * k];
        double share = fmax((double)e / PNPR_CRQ_KEYS, 1.0 / PNPR_CRQ_KEYS);
        t[4 * k + 1] = pnpr_queue_fade_length(e, PNPR_CRQ_KEYS, o->queue_fade);
        t[4 * k + 2] = (float)sqrt(1.0 / share);
        if (e > p->end_max) p->end_max = e;
        if (e > 0.5f && t[4 * k + 2] > p->lod_max) p->lod_max = (float)fmin(t[4 * k + 2], lod_cap);
    }
}

pnpr_status pnpr_renderer_plan_frame(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *o,
                                     int w, int h, frame_plan *p, pnpr_error *err)
{
    pnpr_camera cam;
    memset(&cam, 0, sizeof cam);
    pnpr_status st;
    if (o->matrices) {
        st = pnpr_frame_camera_from_matrices(o->matrices, r->origin, w, h, &p->fc, err);
        if (st != PNPR_OK) return st;
    } else if (camera) cam = *camera;
    else {
        memset(&cam, 0, sizeof cam);
        pnpr_cloud box;
        memset(&box, 0, sizeof box);
        /* a two-point cloud spanning the bounds is enough for the fit */
        float corners[6] = {r->bmin[0], r->bmin[1], r->bmin[2], r->bmax[0], r->bmax[1], r->bmax[2]};
        box.count = 2;
        box.xyz = corners;
        memcpy(box.origin, r->origin, sizeof box.origin);
        if (pnpr_camera_fit(&box, NULL, 45, (float)w / (float)h, &cam) != PNPR_OK)
            memset(&cam, 0, sizeof cam); /* nothing to fit: the zero camera (pnpr_frame_camera_make decides) */
    }
    if (!o->matrices) {
        st = pnpr_frame_camera_make(&cam, r->origin, r->bmin, r->bmax, r->count > 0, w, h, &p->fc, err);
        if (st != PNPR_OK) return st;
    }
    /* continuous resolution queue: how many points this frame, in view (the density x the box's
     * covered pixels), from which cells, and the budget's cap on the vertices sent (plan_cells),
     * for the frame's view or the whole picture's it is a tile of (o->plan_matrices); a random
     * subset of share f has 1/sqrt(f) times the spacing: each cell's disks grow so (the table's
     * column 2), lod is the growth of all the points in view */
    pnpr_frame_camera plan_fc = p->fc;
    int pw = w, ph = h;
    if (o->plan_matrices) {
        if (o->plan_width <= 0 || o->plan_height <= 0)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: plan view of %dx%d pixels", o->plan_width,
                                  o->plan_height);
        pw = o->plan_width;
        ph = o->plan_height;
        st = pnpr_frame_camera_from_matrices(o->plan_matrices, r->origin, pw, ph, &plan_fc, err);
        if (st != PNPR_OK) return st;
    }
    p->coverage = r->count ? pnpr_box_coverage(&plan_fc, r->bmin, r->bmax, pw, ph) : 0;
    double want = o->density > 0 ? ceil((double)o->density * p->coverage) : -1;
    plan_cells(r, o, &plan_fc, want, p);
    return PNPR_OK;
}

/* ---- one frame ------------------------------------------------------------------------------ */

/* The projection of a sub-rectangle of the image: clip x' = x * W/tw + w * (W - 2 x0 - tw)/tw
 * (and y alike) maps the tile's pixels onto its own normalised device coordinates. */
static void tile_projection(float proj[16], const tile_rect *t)
{
    double sx = (double)t->full_w / t->w, tx = ((double)t->full_w - 2.0 * t->x - t->w) / t->w;
    double sy = (double)t->full_h / t->h, ty = ((double)t->full_h - 2.0 * t->y - t->h) / t->h;
    for (int col = 0; col < 4; col++) {
        double wv = proj[col * 4 + 3];
        proj[col * 4 + 0] = (float)(sx * proj[col * 4 + 0] + tx * wv);
        proj[col * 4 + 1] = (float)(sy * proj[col * 4 + 1] + ty * wv);
    }
}

static pnpr_status ensure_framebuffer(pnpr_renderer *r, int w, int h, pnpr_error *err)
{
    if (r->fbo && r->fb_w == w && r->fb_h == h) return PNPR_OK;
    if (!r->fbo) {
        glGenFramebuffers(1, &r->fbo);
        glGenTextures(1, &r->color_tex);
        glGenRenderbuffers(1, &r->depth_rb);
        glGenTextures(1, &r->info_tex);
    }
    glBindTexture(GL_TEXTURE_2D, r->info_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glBindTexture(GL_TEXTURE_2D, r->color_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glBindRenderbuffer(GL_RENDERBUFFER, r->depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->color_tex, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, r->depth_rb);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, r->info_tex, 0);
    pnpr_renderer_draw_buffers(0, 1);
    GLenum fs = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (fs != GL_FRAMEBUFFER_COMPLETE) {
        r->fb_w = r->fb_h = 0;
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "renderer: framebuffer %dx%d incomplete (0x%x)", w, h, (unsigned)fs);
    }
    r->fb_w = w;
    r->fb_h = h;
    return PNPR_OK;
}

/* The style map of o (a style per vertex, *r_vstyle, and f->used) when the cloud has labels;
 * when every point ends up in one style, no map: that style's own path (the same frame as
 * without a map). */
static pnpr_status resolve_map(const pnpr_renderer *r, pnpr_frame_ctx *f, uint8_t **r_vstyle, pnpr_error *err)
{
    *r_vstyle = NULL;
    int layer = pnpr_draw_has_layer(&f->o);
    if (!((f->o.style_map_count > 0 && r->vlabel) || layer) || r->count == 0) {
        if (!r->vstyle_hidden) return PNPR_OK;
        /* the last frame was a layer's: show every vertex again */
        if (!(*r_vstyle = calloc(r->count ? r->count : 1, 1)))
            return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "renderer: out of memory");
        return PNPR_OK;
    }
    uint8_t *vstyle = malloc(r->count);
    if (!vstyle) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "renderer: style map: out of memory");
    pnpr_status st = pnpr_renderer_resolve_styles(r, &f->o, vstyle, f->used);
    if (st != PNPR_OK) { free(vstyle); return pnpr_error_set(err, st, "renderer: style map: out of memory"); }
    int nused = 0;
    pnpr_style only = f->o.style;
    for (int s = 0; s < PNPR_STYLE_COUNT_; s++)
        if (f->used[s]) { nused++; only = (pnpr_style)s; }
    if (nused <= 1) f->o.style = only;
    if (nused <= 1 && !layer) { free(vstyle); vstyle = NULL; }
    f->mapped = nused > 1;
    *r_vstyle = vstyle;
    return PNPR_OK;
}

/* Everything a frame (or tile) of a w x h image needs before GL: the checked options, the style
 * map (*r_vstyle), the scales and ink, the camera, the queue prefixes, whether outlines follow. */
static pnpr_status prepare_frame(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                 int w, int h, const tile_rect *tile, pnpr_frame_ctx *f, uint8_t **r_vstyle,
                                 pnpr_error *err)
{
    *r_vstyle = NULL;
    pnpr_status st = pnpr_renderer_check_options(r, opts, &f->o, err);
    if (st == PNPR_OK) st = resolve_map(r, f, r_vstyle, err);
    if (st != PNPR_OK) return st;
    const pnpr_draw_options *o = &f->o;
    f->point_scale = o->point_scale;
    f->mask_scale = pnpr_draw_mask_scale(o, o->style);
    pnpr_draw_ink(o, f->ink);

    frame_plan plan;
    st = pnpr_renderer_plan_frame(r, camera, o, w, h, &plan, err);
    if (st != PNPR_OK) { free(*r_vstyle); *r_vstyle = NULL; return st; }
    f->fc = plan.fc;
    memcpy(f->image_proj, f->fc.proj, sizeof f->image_proj);
    if (tile) tile_projection(f->fc.proj, tile);
    f->n_draw = plan.n_draw;
    f->coverage = plan.coverage;
    f->lod = plan.lod;
    f->end_max = plan.end_max;
    /* the vertex prefixes that hold every cell's points drawn (the shaders drop the others) */
    f->ng = r->group_count + 1; /* + "other" (empty by construction) */
    for (size_t g = 0; g < f->ng; g++) f->gdraw[g] = f->n_draw ? pnpr_crq_cells_prefix(&r->queue, g, f->end_max) : 0;
    for (size_t b = 0; b < r->paint_bins; b++)
        f->pdraw[b] = f->n_draw ? pnpr_crq_cells_prefix(&r->paint_queue, b, f->end_max) : 0;

    /* outlines: after the style's passes, from the mask's surface info (written only then) */
    f->outline_width = 0;
    int outline = pnpr_style_outline_default(o->style, &f->outline_width);
    if (o->outline) outline = o->outline > 0;
    if (o->outline_width > 0) f->outline_width = o->outline_width;
    f->outline = outline && !f->mapped && o->style != PNPR_STYLE_PAINTERLY && o->style != PNPR_STYLE_POINTS &&
                 f->n_draw > 0;
    return PNPR_OK;
}

/* The frame's table of the per-cell queues to its buffer texture on PNPR_GL_CELLS_UNIT, and the
 * grid and a scale of 1 to the programs that test it (pnpr_shader_prelude). */
static void bind_queue(pnpr_renderer *r)
{
    glBindBuffer(GL_ARRAY_BUFFER, r->cells_buf); /* (the host's texture-buffer binding untouched) */
    int any = r->cells && r->count;
    const float none[4] = {0, 0, 1, 0};
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(4 * (any ? r->cells : 1) * sizeof(float)), any ? r->cell_table : none,
                 GL_STREAM_DRAW);
    glActiveTexture(GL_TEXTURE0 + PNPR_GL_CELLS_UNIT);
    glBindTexture(GL_TEXTURE_BUFFER, r->cells_tex);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, r->cells_buf);
    glActiveTexture(GL_TEXTURE0);
    const pnpr_view_cells *c = &r->view_cells;
    const struct { GLuint prog; const pnpr_queue_uniforms *u; } progs[4] = {
        {r->prog_splat, &r->uq_splat}, {r->prog_stroke, &r->uq_stroke}, {r->prog_paint, &r->uq_paint},
        {r->brush.prog, &r->brush.uq}};
    for (int i = 0; i < 4; i++) {
        glUseProgram(progs[i].prog);
        glUniform1i(progs[i].u->cells, PNPR_GL_CELLS_UNIT);
        glUniform3f(progs[i].u->min, c->min[0], c->min[1], c->min[2]);
        glUniform1f(progs[i].u->inv, c->inv);
        glUniform3i(progs[i].u->n, (GLint)c->n[0], (GLint)c->n[1], (GLint)c->n[2]);
        glUniform1f(progs[i].u->scale, 1.0f);
    }
    glUseProgram(0);
}

/* Binds the frame, clears colour (to the premultiplied background), depth, stencil and the
 * surface info; depth test on. */
static void clear_frame(pnpr_renderer *r, const pnpr_frame_ctx *f)
{
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glViewport(0, 0, f->fw, f->fh);
    float a = f->o.background[3];
    glClearColor(f->o.background[0] * a, f->o.background[1] * a, f->o.background[2] * a, a); /* premultiplied */
    glClearDepth(1.0);
    glDepthMask(GL_TRUE);
    glClearStencil(0);
    pnpr_renderer_draw_buffers(1, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    const float no_surface[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 1, no_surface);
    pnpr_renderer_draw_buffers(0, 1);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
}

static void record_frame(pnpr_frame_record *rec, const pnpr_frame_ctx *f)
{
    int pass = rec->outline_pass, only = rec->pass_only;
    memset(rec, 0, sizeof *rec);
    rec->outline_pass = pass;
    rec->pass_only = only;
    rec->o = f->o;
    rec->o.style_map = NULL;
    rec->o.style_map_count = 0;
    rec->fc = f->fc;
    rec->width = f->fw;
    rec->height = f->fh;
    rec->n_draw = f->n_draw;
    memcpy(rec->gdraw, f->gdraw, sizeof f->gdraw);
    rec->point_scale = f->point_scale;
    rec->lod = f->lod;
    memcpy(rec->ink, f->ink, sizeof f->ink);
    rec->outline = f->outline;
    rec->outline_width = f->outline_width;
    rec->mapped = f->mapped;
    memcpy(rec->used, f->used, sizeof rec->used);
}

/* The outlines from the mask's surface info (edges.c); `pass` (PNPR_OUTLINES_*): as drawn, their
 * ink alone in the colour attachment, or no ink (vector drawings, vector.c). */
static pnpr_status draw_outlines(pnpr_renderer *r, const pnpr_frame_ctx *f, int pass, pnpr_error *err)
{
    const pnpr_draw_options *o = &f->o;
    float a = o->background[3];
    /* the mask's boundary is drawn by the largest disks of the outermost points: about 1.1
     * mean mask radii beyond them (measured on random samplings, docs/rendering.md); the
     * silhouette is drawn that far inside it */
    float inset = 1.1f;
    pnpr_edge_params ep = {f->outline_width, o->outline_jump, o->outline_hole, PNPR_EDGE_MAX_REACH, f->fc.pixels_per_unit,
                           f->fc.ortho, {f->ink[0], f->ink[1], f->ink[2], f->ink[3]}, inset,
                           {o->background[0] * a, o->background[1] * a, o->background[2] * a, a}};
    if (pass == PNPR_OUTLINES_INK_ONLY) {
        const float clear[4] = {0, 0, 0, 0};
        glClearBufferfv(GL_COLOR, 0, clear);
        memset(ep.background, 0, sizeof ep.background);
    }
    if (pass == PNPR_OUTLINES_NO_INK) ep.ink[3] = 0; /* edge_ink discards pixels of no ink */
    return pnpr_edges_draw(&r->edges, r->info_tex, r->fbo, f->fw, f->fh, &ep, err);
}

/* The frame onto the host's framebuffer at (target->x, target->y), over it or replacing it. */
static void composite(pnpr_renderer *r, const pnpr_frame_ctx *f, const pnpr_target *target)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)target->framebuffer);
    glViewport(target->x, target->y, f->fw, f->fh);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (f->o.composite == PNPR_COMPOSITE_OVER) {
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    } else {
        glDisable(GL_BLEND);
    }
    glUseProgram(r->prog_composite);
    glUniform1i(r->uc_frame, 0);
    glUniform2i(r->uc_origin, target->x, target->y);
    glBindTexture(GL_TEXTURE_2D, r->color_tex);
    glBindVertexArray(r->vao_empty);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

pnpr_status pnpr_renderer_draw_frame(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                     const pnpr_target *target, const tile_rect *tile, pnpr_render_stats *r_stats,
                                     pnpr_frame_record *rec, pnpr_error *err)
{
    if (!r || !target) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: NULL renderer or target");
    if (r_stats) memset(r_stats, 0, sizeof *r_stats);
    pnpr_frame_ctx f;
    memset(&f, 0, sizeof f);
    f.fw = target->width;
    f.fh = target->height;
    int w = tile ? tile->full_w : f.fw, h = tile ? tile->full_h : f.fh; /* the image */
    if (w <= 0 || h <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: image size %dx%d must be positive", w, h);
    if (f.fw > r->max_size || f.fh > r->max_size)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT,
                              "renderer: image size %dx%d exceeds this GL's limit %d (pnpr_renderer_snapshot renders larger images in tiles)",
                              f.fw, f.fh, (int)r->max_size);
    uint8_t *vstyle = NULL;
    pnpr_status st = prepare_frame(r, camera, opts, w, h, tile, &f, &vstyle, err);
    if (st != PNPR_OK) return st;

    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    pnpr_gl_state_neutral();
    st = ensure_framebuffer(r, f.fw, f.fh, err);
    if (st == PNPR_OK && vstyle) {
        st = pnpr_renderer_upload_styles(r, vstyle);
        if (st != PNPR_OK) pnpr_error_set(err, st, "renderer: style map: out of memory");
    }
    free(vstyle);
    int brush = f.n_draw > 0 && (f.mapped ? f.used[PNPR_STYLE_BRUSH] > 0 : f.o.style == PNPR_STYLE_BRUSH);
    if (st == PNPR_OK && brush) st = pnpr_brush_gl_prepare(&r->brush, f.o.brush_preset, f.fw, f.fh, r->depth_rb, err);
    int hier = f.n_draw > 0 && (f.mapped ? f.used[PNPR_STYLE_HIERARCHY] > 0 : f.o.style == PNPR_STYLE_HIERARCHY);
    if (st == PNPR_OK && hier) st = pnpr_brush_gl_targets(&r->brush, f.fw, f.fh, r->depth_rb, err);
    if (st != PNPR_OK) { pnpr_gl_state_restore(&saved); return st; }
    clear_frame(r, &f);
    bind_queue(r);
    if (rec) record_frame(rec, &f);
    if (rec) f.pass_only = rec->pass_only;
    size_t strokes = 0;
    if (!f.mapped) strokes = pnpr_renderer_draw_single(r, &f);
    else if (f.n_draw > 0) strokes = pnpr_renderer_draw_mapped(r, &f);
    if (f.outline) st = draw_outlines(r, &f, rec ? rec->outline_pass : PNPR_OUTLINES_DRAWN, err);
    if (st != PNPR_OK) { pnpr_gl_state_restore(&saved); return st; }
    if (!target->offscreen && !tile) composite(r, &f, target);
    pnpr_gl_state_restore(&saved);
    if (r_stats) {
        r_stats->points_total = r->count;
        r_stats->points_drawn = f.n_draw;
        for (size_t g = 0; g < f.ng; g++) r_stats->points_sent += f.gdraw[g];
        r_stats->strokes_drawn = strokes;
        r_stats->coverage_px = f.coverage;
    }
    return PNPR_OK;
}

/* The guard band of target (pnpr_target.guard; < 0: the renderer's own tile margin), at most what
 * the GL's size limit leaves; 0 when none. */
static pnpr_status guard_of(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                            const pnpr_target *t, int *r_guard, pnpr_error *err)
{
    *r_guard = 0;
    int room = ((int)r->max_size - (t->width > t->height ? t->width : t->height)) / 2, g = t->guard;
    if (g == 0 || t->width <= 0 || t->height <= 0 || room <= 0) return PNPR_OK;
    if (g < 0) {
        pnpr_draw_options o;
        frame_plan plan;
        pnpr_status st = pnpr_renderer_check_options(r, opts, &o, err);
        if (st == PNPR_OK) st = pnpr_renderer_plan_frame(r, camera, &o, t->width, t->height, &plan, err);
        if (st != PNPR_OK) return st;
        g = pnpr_renderer_tile_margin(r, &o, &plan, 4 * room);
    }
    *r_guard = g < room ? g : room;
    return PNPR_OK;
}

pnpr_status pnpr_renderer_draw(pnpr_renderer *r, const pnpr_camera *camera,
                               const pnpr_draw_options *opts, const pnpr_target *target,
                               pnpr_render_stats *r_stats, pnpr_error *err)
{
    int g = 0;
    if (r && target) {
        pnpr_status st = guard_of(r, camera, opts, target, &g, err);
        if (st != PNPR_OK) return st;
    }
    if (g == 0) return pnpr_renderer_draw_frame(r, camera, opts, target, NULL, r_stats, NULL, err);
    /* the target as the middle of a frame g px larger all round: drawn as that tile of the
     * target's image (the plan, budget and coverage of the target's own size), then cropped */
    tile_rect t = {target->width, target->height, -g, -g, target->width + 2 * g, target->height + 2 * g};
    pnpr_target big = *target;
    big.x -= g;
    big.y -= g;
    big.width = t.w;
    big.height = t.h;
    pnpr_status st = pnpr_renderer_draw_frame(r, camera, opts, &big, &t, r_stats, NULL, err);
    if (st != PNPR_OK || target->offscreen) return st;
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    GLint box[4];
    glGetIntegerv(GL_SCISSOR_BOX, box);
    pnpr_gl_state_neutral();
    glEnable(GL_SCISSOR_TEST);
    glScissor(target->x, target->y, target->width, target->height);
    pnpr_frame_ctx f;
    memset(&f, 0, sizeof f);
    f.fw = big.width;
    f.fh = big.height;
    f.o.composite = opts ? opts->composite : PNPR_COMPOSITE_REPLACE;
    composite(r, &f, &big);
    glScissor(box[0], box[1], box[2], box[3]);
    pnpr_gl_state_restore(&saved);
    return PNPR_OK;
}

pnpr_status pnpr_renderer_draw_recorded(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                        int width, int height, pnpr_frame_record *rec, pnpr_error *err)
{
    pnpr_target tgt = {0, 0, 0, width, height, 1, 0};
    return pnpr_renderer_draw_frame(r, camera, opts, &tgt, NULL, NULL, rec, err);
}

int pnpr_renderer_max_size(const pnpr_renderer *r) { return r ? (int)r->max_size : 0; }

void pnpr_renderer_frame_size(const pnpr_renderer *r, int *w, int *h)
{
    if (w) *w = r ? r->fb_w : 0;
    if (h) *h = r ? r->fb_h : 0;
}
