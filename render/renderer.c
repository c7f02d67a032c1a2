/* The PointWorks renderer: two-pass visibility mask (section 4.3), continuous resolution queue
 * (4.4), `points`, `sketchy` (5.1), `lines` (5.2), `stipple` and `cartoon` (5.4) styles, per-segment
 * style maps (intermingled styles, figure 12). See docs/rendering.md. */
#include "renderer_internal.h"
#include "gl_state.h"
#include "pnpr_shaders.h"

#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <pointnpr/outliers.h>

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- stroke textures (paper figure 5 a-c, plus the hatch), generated once ------------------- */

static float hash01(uint32_t x)
{
    x ^= x >> 16; x *= 0x7feb352dU; x ^= x >> 15; x *= 0x846ca68bU; x ^= x >> 16;
    return (float)(x >> 8) * (1.0f / 16777216.0f);
}
static float smooth01(float e0, float e1, float x)
{
    float t = (x - e0) / (e1 - e0);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3 - 2 * t);
}
static float band(float v, float centre, float half_width)
{
    float d = (v - centre) / half_width;
    return d * d >= 1 ? 0 : (1 - d * d) * (1 - d * d);
}

void pnpr_stroke_textures(uint8_t *out)
{
    for (int layer = 0; layer < STROKE_LAYERS; layer++)
        for (int y = 0; y < STROKE_TEX_H; y++)
            for (int x = 0; x < STROKE_TEX_W; x++) {
                float u = (x + 0.5f) / STROKE_TEX_W, v = (y + 0.5f) / STROKE_TEX_H;
                float ends = smooth01(0.0f, 0.18f, u) * smooth01(1.0f, 0.82f, u);
                float grain = hash01((uint32_t)(layer * 7919 + y * 131 + x * 977));
                float a = 0;
                if (layer == 0) {        /* (a) tapered pencil line with graphite grain */
                    float w = 0.22f + 0.2f * ends;
                    a = band(v, 0.5f, w) * ends * (0.65f + 0.35f * grain);
                } else if (layer == 1) { /* (b) two thin strokes crossing at a small angle */
                    float c1 = 0.5f + 0.18f * (u - 0.5f), c2 = 0.5f - 0.18f * (u - 0.5f) + 0.05f;
                    float b = band(v, c1, 0.16f);
                    float b2 = band(v, c2, 0.12f) * 0.8f;
                    a = (b > b2 ? b : b2) * ends * (0.7f + 0.3f * grain);
                } else if (layer == 2) { /* (c) brush: full body, bristle streaks along the stroke */
                    float streak = hash01((uint32_t)(y * 2654435761u + 17u));
                    float body = smooth01(0.0f, 0.1f, u) * smooth01(1.0f, 0.6f, u);
                    a = band(v, 0.5f, 0.5f) * body * (0.55f + 0.45f * streak);
                    if (a > 0) a = a * 1.3f > 1 ? 1 : a * 1.3f;
                } else {                 /* hatch: an even short line */
                    a = band(v, 0.5f, 0.45f) * smooth01(0.0f, 0.1f, u) * smooth01(1.0f, 0.9f, u);
                }
                out[((size_t)layer * STROKE_TEX_H + (size_t)y) * STROKE_TEX_W + (size_t)x] =
                    (uint8_t)(a * 255.0f + 0.5f);
            }
}

/* The painterly brush dab: an ellipse (2:1, the long axis along u) with a soft, slightly ragged
 * edge and bristle streaks along the long axis, mostly opaque. */
static void make_brush_texture(uint8_t *out)
{
    for (int y = 0; y < BRUSH_TEX; y++)
        for (int x = 0; x < BRUSH_TEX; x++) {
            float u = (x + 0.5f) / BRUSH_TEX * 2 - 1, v = (y + 0.5f) / BRUSH_TEX * 2 - 1;
            float rag = 0.08f * (hash01((uint32_t)(y * 31 + 7)) - 0.5f);
            float e = sqrtf(u * u + (v / 0.55f) * (v / 0.55f));
            float edge = smooth01(1.0f + rag, 0.8f + rag, e);
            float streak = hash01((uint32_t)(y * 2654435761u + 101u));
            float a = edge * (0.72f + 0.28f * streak);
            out[(size_t)y * BRUSH_TEX + (size_t)x] = (uint8_t)(a * 255.0f + 0.5f);
        }
}

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
    GLuint vaos[5] = {r->vao_points, r->vao_strokes, r->vao_empty, r->vao_lines, r->vao_flat};
    glDeleteVertexArrays(5, vaos);
    if (r->stroke_tex) glDeleteTextures(1, &r->stroke_tex);
    if (r->color_tex) glDeleteTextures(1, &r->color_tex);
    if (r->depth_rb) glDeleteRenderbuffers(1, &r->depth_rb);
    if (r->info_tex) glDeleteTextures(1, &r->info_tex);
    pnpr_edges_release(&r->edges);
    if (r->fbo) glDeleteFramebuffers(1, &r->fbo);
}

static void set_attribs(GLuint vao, GLuint vbo, GLuint sbo, size_t first, int instanced, int flat)
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
    r->prog_splat = pnpr_gl_link_program(pnpr_shader_splat_vert, pnpr_shader_splat_frag, "splat", err);
    r->prog_stroke = r->prog_splat ? pnpr_gl_link_program(pnpr_shader_stroke_vert, pnpr_shader_stroke_frag, "stroke", err) : 0;
    r->prog_composite = r->prog_stroke ? pnpr_gl_link_program(pnpr_shader_composite_vert, pnpr_shader_composite_frag, "composite", err) : 0;
    r->prog_line = r->prog_composite ? pnpr_gl_link_program(pnpr_shader_line_vert, pnpr_shader_line_frag, "line", err) : 0;
    r->prog_paint = r->prog_line ? pnpr_gl_link_program(pnpr_shader_paint_vert, pnpr_shader_paint_frag, "paint", err) : 0;
    if (!r->prog_paint || pnpr_edges_create(&r->edges, err) != PNPR_OK) { st = PNPR_ERR_UNSUPPORTED; goto done; }
    r->up.view = glGetUniformLocation(r->prog_paint, "u_view");
    r->up.proj = glGetUniformLocation(r->prog_paint, "u_proj");
    r->up.ppu = glGetUniformLocation(r->prog_paint, "u_pixels_per_unit");
    r->up.radius_scale = glGetUniformLocation(r->prog_paint, "u_radius_scale");
    r->up.max_size = glGetUniformLocation(r->prog_paint, "u_max_size");
    r->up.style_filter = glGetUniformLocation(r->prog_paint, "u_style_filter");
    r->up.brush = glGetUniformLocation(r->prog_paint, "u_brush");
    GLuint p = r->prog_splat;
    r->us.view = glGetUniformLocation(p, "u_view");
    r->us.proj = glGetUniformLocation(p, "u_proj");
    r->us.ppu = glGetUniformLocation(p, "u_pixels_per_unit");
    r->us.radius_scale = glGetUniformLocation(p, "u_radius_scale");
    r->us.depth_push = glGetUniformLocation(p, "u_depth_push");
    r->us.max_size = glGetUniformLocation(p, "u_max_size");
    r->us.fade = glGetUniformLocation(p, "u_fade");
    r->us.fade_color = glGetUniformLocation(p, "u_fade_color");
    r->us.fixed_size = glGetUniformLocation(p, "u_fixed_size");
    r->us.levels = glGetUniformLocation(p, "u_levels");
    r->us.ortho = glGetUniformLocation(p, "u_ortho");
    r->us.thin = glGetUniformLocation(p, "u_thin");
    r->us.queue_end = glGetUniformLocation(p, "u_queue_end");
    r->us.queue_fade = glGetUniformLocation(p, "u_queue_fade");
    p = r->prog_line;
    r->ul.view = glGetUniformLocation(p, "u_view");
    r->ul.proj = glGetUniformLocation(p, "u_proj");
    r->ul.viewport = glGetUniformLocation(p, "u_viewport");
    r->ul.width = glGetUniformLocation(p, "u_width");
    r->ul.near_plane = glGetUniformLocation(p, "u_near");
    r->ul.ink = glGetUniformLocation(p, "u_ink");
    r->ul.pull = glGetUniformLocation(p, "u_pull");
    r->ul.ortho = glGetUniformLocation(p, "u_ortho");
    r->ul.ppu = glGetUniformLocation(p, "u_pixels_per_unit");
    r->ul.min_px = glGetUniformLocation(p, "u_min_px");
    p = r->prog_stroke;
    r->ut.view = glGetUniformLocation(p, "u_view");
    r->ut.proj = glGetUniformLocation(p, "u_proj");
    r->ut.viewport = glGetUniformLocation(p, "u_viewport");
    r->ut.ppu = glGetUniformLocation(p, "u_pixels_per_unit");
    r->ut.length = glGetUniformLocation(p, "u_length");
    r->ut.width = glGetUniformLocation(p, "u_width");
    r->ut.radius_scale = glGetUniformLocation(p, "u_radius_scale");
    r->ut.mode = glGetUniformLocation(p, "u_mode");
    r->ut.strokes = glGetUniformLocation(p, "u_strokes");
    r->ut.layer = glGetUniformLocation(p, "u_layer");
    r->ut.ink = glGetUniformLocation(p, "u_ink");
    r->ut.ink_from_points = glGetUniformLocation(p, "u_ink_from_points");
    r->ut.thin = glGetUniformLocation(p, "u_thin");
    r->ut.queue_end = glGetUniformLocation(p, "u_queue_end");
    r->ut.queue_fade = glGetUniformLocation(p, "u_queue_fade");
    r->us_filter = glGetUniformLocation(r->prog_splat, "u_style_filter");
    r->ut_filter = glGetUniformLocation(r->prog_stroke, "u_style_filter");
    /* no style filter unless a style map is drawn (uniforms are program state) */
    glUseProgram(r->prog_splat);
    glUniform1i(r->us_filter, -1);
    glUseProgram(r->prog_stroke);
    glUniform1i(r->ut_filter, -1);
    glUseProgram(r->prog_paint);
    glUniform1i(r->up.style_filter, -1);
    glUseProgram(0);
    r->uc_frame = glGetUniformLocation(r->prog_composite, "u_frame");
    r->uc_origin = glGetUniformLocation(r->prog_composite, "u_origin");

    glGenBuffers(1, &r->vbo);
    glGenVertexArrays(1, &r->vao_points);
    glGenVertexArrays(1, &r->vao_strokes);
    glGenVertexArrays(1, &r->vao_empty);
    glGenVertexArrays(1, &r->vao_flat);
    glGenBuffers(1, &r->style_vbo);
    glGenBuffers(1, &r->paint_style_vbo);
    set_attribs(r->vao_points, r->vbo, r->style_vbo, 0, 0, 0);
    set_attribs(r->vao_strokes, r->vbo, r->style_vbo, 0, 1, 0);
    set_attribs(r->vao_flat, r->vbo, r->style_vbo, 0, 0, 1);
    /* line segments: two ends per instance */
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

    uint8_t *tex = malloc((size_t)STROKE_TEX_W * STROKE_TEX_H * STROKE_LAYERS);
    if (!tex) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    pnpr_stroke_textures(tex);
    glGenTextures(1, &r->stroke_tex);
    glBindTexture(GL_TEXTURE_2D_ARRAY, r->stroke_tex);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R8, STROKE_TEX_W, STROKE_TEX_H, STROKE_LAYERS, 0,
                 GL_RED, GL_UNSIGNED_BYTE, tex);
    free(tex);
    glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

    /* painterly: its vertex buffer, its colour levels (attribute 2 re-pointed per pass), the brush */
    glGenBuffers(1, &r->paint_vbo);
    glGenBuffers(1, &r->paint_col_vbo);
    glGenVertexArrays(1, &r->vao_paint);
    set_attribs(r->vao_paint, r->paint_vbo, r->paint_style_vbo, 0, 0, 0);
    uint8_t *brush = malloc((size_t)BRUSH_TEX * BRUSH_TEX);
    if (!brush) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    make_brush_texture(brush);
    glGenTextures(1, &r->brush_tex);
    glBindTexture(GL_TEXTURE_2D, r->brush_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, BRUSH_TEX, BRUSH_TEX, 0, GL_RED, GL_UNSIGNED_BYTE, brush);
    free(brush);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

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
done:
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
    free(r->paint_src);
    free(r->vstyle);
    /* deleting a bound object unbinds it: put back what the host had (names it still owns) */
    pnpr_gl_state_restore(&saved);
    free(r);
}

/* ---- upload --------------------------------------------------------------------------------- */

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : x > y;
}

/* radius[i] = distance from point i to its k-th nearest other point, capped at 4x the median
 * (isolated points), floored at 1/8 of the median (duplicates). */
/* want_kk > 0: the neighbour lists (want_kk per point, the point itself included, nearest first)
 * are handed over in *r_idx / *r_d2 (kk of them each, *r_kk), for the painterly colours. */
static pnpr_status spacing_radii(const float *xyz, size_t n, uint32_t k, int threads, float *radius,
                                 size_t want_kk, uint32_t **r_idx, float **r_d2, size_t *r_kk)
{
    if (r_idx) { *r_idx = NULL; *r_d2 = NULL; *r_kk = 0; }
    if (n == 1) { radius[0] = 1; return PNPR_OK; }
    size_t kr = (size_t)k + 1 < n ? (size_t)k + 1 : n; /* + the point itself */
    size_t kk = kr > want_kk ? kr : want_kk < n ? want_kk : n;
    pnpr_kdtree *tree = NULL;
    pnpr_status st = pnpr_kdtree_build_threads(xyz, n, 0, threads, &tree);
    if (st != PNPR_OK) return st;
    uint32_t *idx = malloc(n * kk * sizeof *idx);
    float *d2 = malloc(n * kk * sizeof *d2);
    if (!idx || !d2) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    pnpr_knn_options ko;
    memset(&ko, 0, sizeof ko);
    ko.threads = threads;
    st = pnpr_knn_self(tree, n, kk, &ko, idx, d2);
    if (st != PNPR_OK) goto done;
    for (size_t i = 0; i < n; i++) {
        float r = 0;
        for (size_t j = kr; j-- > 0;)
            if (idx[i * kk + j] != PNPR_INDEX_NONE && isfinite(d2[i * kk + j])) { r = sqrtf(d2[i * kk + j]); break; }
        radius[i] = r;
    }
    if (r_idx && want_kk > 0) { /* hand the lists over */
        *r_idx = idx; *r_d2 = d2; *r_kk = kk;
        idx = NULL;
        d2 = NULL;
    }
    /* median of the radii */
    float *sorted = malloc(n * sizeof *sorted);
    if (!sorted) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    memcpy(sorted, radius, n * sizeof *sorted);
    qsort(sorted, n, sizeof *sorted, cmp_float);
    float med = sorted[n / 2];
    if (!(med > 0)) { /* mostly duplicates: the largest distance found, else 1 */
        med = sorted[n - 1] > 0 ? sorted[n - 1] : 1;
    }
    free(sorted);
    for (size_t i = 0; i < n; i++) {
        if (radius[i] > 4 * med) radius[i] = 4 * med;
        if (!(radius[i] >= 0.125f * med)) radius[i] = 0.125f * med;
    }
done:
    free(idx);
    free(d2);
    pnpr_kdtree_free(tree);
    return st;
}

typedef struct label_index { uint32_t label, j; } label_index;

static int cmp_label(const void *a, const void *b)
{
    const label_index *x = a, *y = b;
    if (x->label != y->label) return x->label < y->label ? -1 : 1;
    return x->j < y->j ? -1 : x->j > y->j;
}

/* Mean colour (rounded) of each segment over its finite points: r_flat[3 j] for finite point j
 * (cloud index src[j]). Sorting (label, j) pairs handles any label values, PNPR_LABEL_NONE
 * included (one more segment). Without colours the points' shaded greys grey[j] are averaged
 * (each segment a flat grey by its mean lighting: faceted planes). */
static pnpr_status segment_means(const pnpr_cloud *cloud, const uint32_t *src, const uint8_t *grey, size_t n,
                                 uint8_t *r_flat)
{
    label_index *li = malloc(n * sizeof *li);
    if (!li) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t j = 0; j < n; j++) { li[j].label = cloud->label[src[j]]; li[j].j = (uint32_t)j; }
    qsort(li, n, sizeof *li, cmp_label);
    for (size_t a = 0; a < n;) {
        size_t b = a;
        double sum[3] = {0, 0, 0};
        while (b < n && li[b].label == li[a].label) {
            for (int c = 0; c < 3; c++) sum[c] += cloud->rgb ? cloud->rgb[3 * (size_t)src[li[b].j] + c] : grey[li[b].j];
            b++;
        }
        uint8_t mean[3];
        for (int c = 0; c < 3; c++) mean[c] = (uint8_t)(sum[c] / (double)(b - a) + 0.5);
        for (size_t k = a; k < b; k++) memcpy(r_flat + 3 * (size_t)li[k].j, mean, 3);
        a = b;
    }
    free(li);
    return PNPR_OK;
}

/* Brush size of painterly pass `pass` of `bins`, in disk radii: PNPR_PAINT_MAX_BRUSH for the
 * first (all bins), 1 for the last (the highest-degree bin), geometric in between. */
static float paint_brush(size_t pass, size_t bins)
{
    if (bins <= 1) return 1.0f;
    return (float)pow((double)PNPR_PAINT_MAX_BRUSH, (double)(bins - 1 - pass) / (double)(bins - 1));
}

typedef struct degree_index { float d; uint32_t j; } degree_index;
static int cmp_degree(const void *a, const void *b)
{
    const degree_index *x = a, *y = b;
    if (x->d != y->d) return x->d < y->d ? -1 : 1;
    return x->j < y->j ? -1 : x->j > y->j;
}

/* The painterly data (section 5.3): finite points sorted by feature_degree (non-finite = lowest)
 * and divided evenly into `bins` bins, each shuffled into a queue (pnpr_crq_order); the vertices
 * in that order (*r_pverts, copies of the class-ordered `verts`) and, per pass L and point, the
 * blended colour: the mean colour of the point's neighbours (among its kk nearest, itself
 * included) within the pass's brush radius paint_brush(L) * radius (*r_pcol, level-major RGBA8). */
static pnpr_status paint_data(const pnpr_cloud *cloud, const pnpr_property *pdeg, const uint32_t *src,
                              const float *radius, size_t n, size_t bins, uint64_t seed, const uint32_t *order,
                              const pnpr_vertex *verts, const uint32_t *nidx, const float *nd2, size_t kk,
                              uint32_t **r_porder, uint32_t **r_inv, uint8_t **r_bin, uint8_t **r_col,
                              pnpr_vertex **r_pverts, size_t *r_starts)
{
    degree_index *di = malloc(n * sizeof *di);
    uint8_t *bin = *r_bin = malloc(n);
    uint32_t *porder = *r_porder = malloc(n * sizeof *porder);
    uint32_t *inv = *r_inv = malloc(n * sizeof *inv);
    uint8_t *col = *r_col = malloc(bins * n * 4);
    pnpr_vertex *pv = *r_pverts = malloc(n * sizeof *pv);
    if (!di || !bin || !porder || !inv || !col || !pv) { free(di); return PNPR_ERR_OUT_OF_MEMORY; }
    for (size_t j = 0; j < n; j++) {
        double d = pnpr_type_get(pdeg->type, pdeg->data, src[j]);
        di[j].d = isfinite(d) ? (float)d : -FLT_MAX;
        di[j].j = (uint32_t)j;
    }
    qsort(di, n, sizeof *di, cmp_degree);
    for (size_t rank = 0; rank < n; rank++) bin[di[rank].j] = (uint8_t)(rank * bins / n);
    free(di);
    /* a seed of its own, so that the bins' order is not the class queues' */
    pnpr_status st = pnpr_crq_order(n, bin, (uint32_t)bins, seed ^ 0x9E3779B97F4A7C15ull, porder, r_starts);
    if (st != PNPR_OK) return st;
    for (size_t q = 0; q < n; q++) inv[order[q]] = (uint32_t)q;
    for (size_t q = 0; q < n; q++) {
        uint32_t j = porder[q];
        pv[q] = verts[inv[j]];
        for (size_t L = 0; L < bins; L++) {
            double lim = (double)paint_brush(L, bins) * radius[j];
            double sum[3] = {0, 0, 0};
            size_t cnt = 0;
            for (size_t t = 0; t < kk && nidx; t++) {
                uint32_t m = nidx[j * kk + t];
                if (m == PNPR_INDEX_NONE || !((double)nd2[j * kk + t] <= lim * lim)) continue;
                for (int c = 0; c < 3; c++) sum[c] += verts[inv[m]].rgba[c]; /* colours, or the shaded greys */
                cnt++;
            }
            uint8_t *o = col + 4 * (L * n + q);
            for (int c = 0; c < 3; c++) o[c] = cnt ? (uint8_t)(sum[c] / (double)cnt + 0.5) : pv[q].rgba[c];
            o[3] = 255;
        }
    }
    return PNPR_OK;
}

/* Colourless clouds: the key light's darkness of every finite point j (cloud index src[j]) from
 * its normal (tone.h, light source, no curve; unknown normals give 0.5) and its grey,
 * 240 - 170 x darkness. */
static pnpr_status shade_greys(const pnpr_cloud *cloud, const uint32_t *src, size_t n, const pnpr_tone_options *tone,
                               float **r_shade, uint8_t **r_grey)
{
    *r_grey = NULL;
    float *nrm = cloud->normal ? malloc(3 * n * sizeof *nrm) : NULL;
    float *shade = malloc(n * sizeof *shade);
    pnpr_status st = !shade || (cloud->normal && !nrm) ? PNPR_ERR_OUT_OF_MEMORY : PNPR_OK;
    if (st == PNPR_OK && nrm)
        for (size_t j = 0; j < n; j++) memcpy(nrm + 3 * j, cloud->normal + 3 * (size_t)src[j], 3 * sizeof *nrm);
    pnpr_tone_options o = *tone;
    o.source = PNPR_TONE_LIGHT;
    o.contrast = 1;
    o.gamma = 1;
    if (st == PNPR_OK) st = pnpr_tone(NULL, nrm, n, &o, shade);
    free(nrm);
    uint8_t *grey = st == PNPR_OK ? malloc(n) : NULL;
    if (st == PNPR_OK && !grey) st = PNPR_ERR_OUT_OF_MEMORY;
    if (st != PNPR_OK) { free(shade); shade = NULL; }
    else for (size_t j = 0; j < n; j++) grey[j] = (uint8_t)lrintf(240.0f - 170.0f * shade[j]);
    *r_shade = shade;
    *r_grey = grey;
    return st;
}

/* The cartoon's cel bands of a colourless cloud: three greys by the key light's darkness (lit,
 * half-lit, in shadow), all darker than white paper so that no band vanishes into it. */
static uint8_t shade_band(float darkness)
{
    return darkness < 0.3f ? 226 : darkness < 0.55f ? 178 : 128;
}

/* A unit normal as 4 signed bytes (x, y, z * 127, 0); unknown, zero or non-finite: all 0. */
static void pack_normal(const float *n, int8_t r[4])
{
    memset(r, 0, 4);
    if (!n) return;
    double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    if (!(l > 1e-12) || !isfinite(l)) return;
    for (int a = 0; a < 3; a++) r[a] = (int8_t)lrint(127.0 * n[a] / l);
}

static int group_of_class(double c)
{
    switch ((int)c) {
    case PNPR_CLASS_DIRECTIONAL: return GROUP_DIRECTIONAL;
    case PNPR_CLASS_NONDIRECTIONAL: return GROUP_NONDIRECTIONAL;
    case PNPR_CLASS_DITHER: return GROUP_DITHER;
    default: return GROUP_NONE;
    }
}

pnpr_status pnpr_renderer_set_cloud(pnpr_renderer *r, const pnpr_cloud *cloud,
                                    const pnpr_upload_options *opts, pnpr_error *err)
{
    if (!r || !cloud) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: NULL renderer or cloud");
    if (cloud->count > 0 && !cloud->xyz)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: cloud has points but no coordinates");
    if (cloud->count >= 0xFFFFFFFFu)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: too many points (%zu)", cloud->count);
    pnpr_upload_options o;
    memset(&o, 0, sizeof o);
    if (opts) o = *opts;
    if (o.spacing_k > PNPR_SPACING_K_MAX)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: spacing_k %u is more than %d",
                              (unsigned)o.spacing_k, PNPR_SPACING_K_MAX);
    uint32_t k = o.spacing_k ? o.spacing_k : 4;

    const pnpr_property *pc = pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_CLASS);
    const pnpr_property *pd[3] = {pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DIR_X),
                                  pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DIR_Y),
                                  pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DIR_Z)};
    int features = !o.ignore_features && pc && pd[0] && pd[1] && pd[2];
    const pnpr_property *pdeg = features ? pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DEGREE) : NULL;
    if (o.painterly_bins > PAINT_MAX_BINS)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: painterly_bins %u is more than %d",
                              (unsigned)o.painterly_bins, PAINT_MAX_BINS);
    size_t nbins = o.painterly_bins ? o.painterly_bins : 4;
    uint32_t *nidx = NULL, *porder = NULL, *inv = NULL;
    float *nd2 = NULL;
    size_t nkk = 0;
    uint8_t *pbin = NULL, *pcol = NULL;
    pnpr_vertex *pverts = NULL;
    size_t pstarts[PAINT_MAX_BINS + 2];
    uint32_t *vlabel = NULL, *paint_src = NULL;
    uint8_t *zeros = NULL;
    float *shade = NULL;
    uint8_t *grey = NULL;

    /* the finite points */
    size_t n = 0;
    for (size_t i = 0; i < cloud->count; i++) {
        const float *p = cloud->xyz + 3 * i;
        n += isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
    }
    uint32_t *src = malloc((n ? n : 1) * sizeof *src);
    float *xyz = malloc((n ? n : 1) * 3 * sizeof *xyz);
    float *radius = malloc((n ? n : 1) * sizeof *radius);
    uint8_t *group = malloc(n ? n : 1);
    uint32_t *order = malloc((n ? n : 1) * sizeof *order);
    pnpr_vertex *verts = malloc((n ? n : 1) * sizeof *verts);
    uint8_t *flat = cloud->label ? malloc((n ? n : 1) * 3) : NULL;
    pnpr_status st = PNPR_OK;
    if (!src || !xyz || !radius || !group || !order || !verts || (cloud->label && !flat)) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    n = 0;
    for (size_t i = 0; i < cloud->count; i++) {
        const float *p = cloud->xyz + 3 * i;
        if (!(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]))) continue;
        src[n] = (uint32_t)i;
        memcpy(xyz + 3 * n, p, 3 * sizeof *p);
        group[n] = features ? (uint8_t)group_of_class(pnpr_type_get(pc->type, pc->data, i)) : 0;
        n++;
    }
    if (n > 0) {
        st = spacing_radii(xyz, n, k, o.threads, radius, pdeg ? PAINT_K : 0, pdeg ? &nidx : NULL,
                           pdeg ? &nd2 : NULL, pdeg ? &nkk : NULL);
        if (st != PNPR_OK) goto done;
    }
    size_t ngroups = features ? GROUP_MAX : 1;
    size_t starts[GROUP_MAX + 2];
    st = pnpr_crq_order(n, group, (uint32_t)ngroups, o.seed, order, starts);
    if (st != PNPR_OK) goto done;
    if (!cloud->rgb && n > 0 && (st = shade_greys(cloud, src, n, &o.tone, &shade, &grey)) != PNPR_OK) goto done;
    if (cloud->label && n > 0) {
        st = segment_means(cloud, src, grey, n, flat);
        if (st != PNPR_OK) goto done;
    }
    for (size_t q = 0; q < n; q++) {
        uint32_t j = order[q];
        size_t i = src[j];
        pnpr_vertex *v = verts + q;
        memcpy(v->pos, xyz + 3 * (size_t)j, sizeof v->pos);
        v->radius = radius[j];
        if (cloud->rgb) memcpy(v->rgba, cloud->rgb + 3 * i, 3);
        else v->rgba[0] = v->rgba[1] = v->rgba[2] = grey[j];
        v->rgba[3] = 255;
        if (cloud->label) memcpy(v->flat, flat + 3 * (size_t)j, 3);
        else if (!cloud->rgb) v->flat[0] = v->flat[1] = v->flat[2] = shade_band(shade[j]);
        else memcpy(v->flat, v->rgba, 3);
        v->flat[3] = 255;
        pack_normal(cloud->normal ? cloud->normal + 3 * i : NULL, v->normal);
        v->dir[0] = v->dir[1] = v->dir[2] = 0;
        if (features) {
            float d[3];
            double l2 = 0;
            for (int a = 0; a < 3; a++) {
                d[a] = (float)pnpr_type_get(pd[a]->type, pd[a]->data, i);
                if (!isfinite(d[a])) d[a] = 0;
                l2 += (double)d[a] * d[a];
            }
            if (l2 > 0) for (int a = 0; a < 3; a++) v->dir[a] = (float)(d[a] / sqrt(l2));
        }
    }
    if (pdeg && n > 0) {
        st = paint_data(cloud, pdeg, src, radius, n, nbins, o.seed, order, verts, nidx, nd2, nkk,
                        &porder, &inv, &pbin, &pcol, &pverts, pstarts);
        if (st != PNPR_OK) goto done;
    }
    /* style maps: the labels in queue order, the painterly order's main indices, zero bytes */
    int paint = pdeg && n > 0;
    if (cloud->label) {
        vlabel = malloc((n ? n : 1) * sizeof *vlabel);
        if (!vlabel) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
        for (size_t q = 0; q < n; q++) vlabel[q] = cloud->label[src[order[q]]];
    }
    if (paint) {
        paint_src = malloc(n * sizeof *paint_src);
        if (!paint_src) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
        for (size_t q = 0; q < n; q++) paint_src[q] = inv[porder[q]];
    }
    zeros = calloc(n ? n : 1, 1);
    if (!zeros) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    glBindBuffer(GL_ARRAY_BUFFER, r->style_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n ? n : 1), zeros, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, r->paint_style_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(paint ? n : 1), zeros, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * sizeof *verts), n ? verts : NULL, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, r->paint_vbo);
    glBufferData(GL_ARRAY_BUFFER, paint ? (GLsizeiptr)(n * sizeof *pverts) : 0, paint ? pverts : NULL, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, r->paint_col_vbo);
    glBufferData(GL_ARRAY_BUFFER, paint ? (GLsizeiptr)(nbins * n * 4) : 0, paint ? pcol : NULL, GL_STATIC_DRAW);
    pnpr_gl_state_restore(&saved);
    r->paint_bins = paint ? nbins : 0;
    if (paint) for (size_t b = 0; b <= nbins + 1; b++) r->paint_start[b] = pstarts[b];

    free(r->vlabel); free(r->paint_src); free(r->vstyle);
    r->vlabel = vlabel; r->paint_src = paint_src; r->vstyle = zeros;
    vlabel = NULL; paint_src = NULL; zeros = NULL;
    r->count = n;
    r->group_count = ngroups;
    for (size_t g = 0; g <= ngroups + 1; g++) r->group_start[g] = starts[g];
    r->has_features = features;
    r->has_labels = cloud->label != NULL;
    r->has_rgb = cloud->rgb != NULL;
    r->max_radius = 0;
    double rsum = 0;
    for (size_t j = 0; j < n; j++) {
        if (radius[j] > r->max_radius) r->max_radius = radius[j];
        rsum += radius[j];
    }
    r->mean_radius = n ? (float)(rsum / (double)n) : 0;
    memcpy(r->origin, cloud->origin, sizeof r->origin);
    if (pnpr_cloud_inlier_bounds(cloud, r->bmin, r->bmax) == 0) { /* far outliers do not stretch it */
        memset(r->bmin, 0, sizeof r->bmin);
        memset(r->bmax, 0, sizeof r->bmax);
    }
done:
    free(src); free(xyz); free(radius); free(group); free(order); free(verts); free(flat);
    free(nidx); free(nd2); free(porder); free(inv); free(pbin); free(pcol); free(pverts);
    free(vlabel); free(paint_src); free(zeros); free(shade); free(grey);
    return st;
}

int pnpr_renderer_has_features(const pnpr_renderer *r) { return r && r->has_features; }
int pnpr_renderer_has_labels(const pnpr_renderer *r) { return r && r->has_labels; }

static int finite3(const float *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

pnpr_status pnpr_renderer_set_lines(pnpr_renderer *r, const pnpr_polylines *lines, pnpr_error *err)
{
    if (!r) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: NULL renderer");
    size_t segs = 0;
    if (lines && lines->count > 0) {
        if (!lines->offset)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: lines without offsets");
        if (lines->offset[0] != 0)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: lines: offset[0] is %zu, not 0", lines->offset[0]);
        for (size_t i = 0; i < lines->count; i++) {
            size_t a = lines->offset[i], b = lines->offset[i + 1];
            if (b < a)
                return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: lines: offsets decrease at polyline %zu", i);
            if (b - a >= 2) segs += (b - a - 1) + (lines->closed && lines->closed[i] && b - a >= 3);
        }
        if (!isfinite(lines->origin[0]) || !isfinite(lines->origin[1]) || !isfinite(lines->origin[2]))
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: lines: non-finite origin");
        if (lines->offset[lines->count] > 0 && !lines->xyz)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: lines have vertices but no coordinates");
        if (segs > (size_t)0x7FFFFFFF / LINE_FLOATS)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: too many line segments (%zu)", segs);
    }
    float *buf = malloc((segs ? segs : 1) * LINE_FLOATS * sizeof *buf);
    if (!buf) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "renderer: lines: out of memory");
    size_t m = 0;
    for (size_t i = 0; segs && i < lines->count; i++) {
        size_t a = lines->offset[i], b = lines->offset[i + 1];
        if (b - a < 2) continue;
        size_t n = b - a, nseg = (n - 1) + (lines->closed && lines->closed[i] && n >= 3), first = m;
        double length = 0;
        for (size_t k = 0; k < nseg; k++) {
            const float *p = lines->xyz + 3 * (a + k), *q = lines->xyz + 3 * (a + (k + 1) % n);
            if (!finite3(p) || !finite3(q)) continue;
            memcpy(buf + LINE_FLOATS * m, p, 3 * sizeof *p);
            memcpy(buf + LINE_FLOATS * m + 3, q, 3 * sizeof *q);
            length += sqrt(((double)q[0] - p[0]) * (q[0] - p[0]) + ((double)q[1] - p[1]) * (q[1] - p[1]) +
                           ((double)q[2] - p[2]) * (q[2] - p[2]));
            m++;
        }
        for (size_t k = first; k < m; k++) buf[LINE_FLOATS * k + 6] = (float)length; /* the polyline's */
    }
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    glBindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m * LINE_FLOATS * sizeof *buf), m ? buf : NULL, GL_STATIC_DRAW);
    pnpr_gl_state_restore(&saved);
    free(buf);
    r->line_segments = m;
    if (m) memcpy(r->line_origin, lines->origin, sizeof r->line_origin);
    return PNPR_OK;
}

/* ---- draw ----------------------------------------------------------------------------------- */

/* Which of the frame's attachments the fragment outputs reach: colour (0) and the mask's surface
 * info (1). Draw-buffer state belongs to the bound framebuffer object (ours), not to the host. */
static void set_draw_buffers(int info, int color)
{
    GLenum bufs[2] = {color ? GL_COLOR_ATTACHMENT0 : GL_NONE, info ? GL_COLOR_ATTACHMENT1 : GL_NONE};
    glDrawBuffers(2, bufs);
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
    set_draw_buffers(0, 1);
    GLenum fs = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (fs != GL_FRAMEBUFFER_COMPLETE) {
        r->fb_w = r->fb_h = 0;
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "renderer: framebuffer %dx%d incomplete (0x%x)", w, h, (unsigned)fs);
    }
    r->fb_w = w;
    r->fb_h = h;
    return PNPR_OK;
}

static int finite4(const float *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]) && isfinite(v[3]); }

/* A tile of a larger image: the frame is the rectangle (x, y, w, h) (GL pixel convention, y up
 * from the bottom row) of a full_w x full_h image; point sizes, queue counts and the camera are
 * those of the full image (pnpr_renderer_snapshot). */
typedef struct tile_rect { int full_w, full_h, x, y, w, h; } tile_rect;

/* The camera, the queue count and the disk growth of a full image (shared by every tile). */
typedef struct frame_plan {
    pnpr_frame_camera fc;
    size_t n_draw;
    double coverage;
    float lod;
} frame_plan;

static pnpr_status check_options(const pnpr_renderer *r, const pnpr_draw_options *opts, pnpr_draw_options *o,
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
    if (!finite4(o->background) || !finite4(o->ink) || !isfinite(o->density) || o->density < 0 ||
        !isfinite(o->point_scale) || o->point_scale < 0 || !isfinite(o->mask_scale) || o->mask_scale < 0 ||
        !isfinite(o->stroke_length) || o->stroke_length < 0 || !isfinite(o->stroke_width) || o->stroke_width < 0 ||
        !isfinite(o->line_width) || o->line_width < 0 || !(o->faint >= 0 && o->faint <= 1) || !isfinite(o->queue_fade) ||
        !isfinite(o->dot_size) || o->dot_size < 0 || o->levels < 0 || o->levels == 1 || o->levels > 256 ||
        !isfinite(o->outline_width) || o->outline_width < 0 || o->outline_width > 64 ||
        !isfinite(o->line_min_px) || o->line_min_px < 0 ||
        !isfinite(o->outline_jump) || o->outline_jump < 0 || !isfinite(o->outline_hole) || o->outline_hole < 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: draw options must be finite and not negative (outline width at most 64 px)");
    if (o->outline < -1 || o->outline > 1)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: outline %d is not -1, 0 or 1", o->outline);
    if (pnpr_style_needs_features(o->style) && o->style != PNPR_STYLE_PAINTERLY && r->count > 0 && !r->has_features)
        return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                              "renderer: style '%s' needs the feature properties feature_class and feature_dir_x/y/z (pnpr_compute_features)",
                              pnpr_style_name(o->style));
    if (o->style == PNPR_STYLE_PAINTERLY && r->count > 0 && !r->paint_bins)
        return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                              "renderer: style 'painterly' needs the feature properties feature_degree, feature_class and feature_dir_x/y/z (pnpr_compute_features)");
    if (o->style_map_count > 0 && !o->style_map)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: style_map_count %zu without a style map", o->style_map_count);
    if (o->style_map_count > 0xFFFFFFFFu)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: style map too large (%zu entries)", o->style_map_count);
    for (size_t i = 0; i < o->style_map_count; i++) {
        pnpr_style s = o->style_map[i].style;
        if ((unsigned)s >= PNPR_STYLE_COUNT_)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: style map entry %zu (label %u): unknown style %d",
                                  i, (unsigned)o->style_map[i].label, (int)s);
        if (r->count == 0) continue;
        if (s == PNPR_STYLE_PAINTERLY && !r->paint_bins)
            return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                                  "renderer: style map: label %u is 'painterly', which needs the feature properties feature_degree, feature_class and feature_dir_x/y/z (pnpr_compute_features)",
                                  (unsigned)o->style_map[i].label);
        if (pnpr_style_needs_features(s) && s != PNPR_STYLE_PAINTERLY && !r->has_features)
            return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                                  "renderer: style map: label %u is '%s', which needs the feature properties feature_class and feature_dir_x/y/z (pnpr_compute_features)",
                                  (unsigned)o->style_map[i].label, pnpr_style_name(s));
    }
    return PNPR_OK;
}

static pnpr_status plan_frame(const pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *o,
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
        pnpr_camera_fit(&box, NULL, 45, (float)w / (float)h, &cam);
    }
    if (!o->matrices) {
        st = pnpr_frame_camera_make(&cam, r->origin, r->bmin, r->bmax, r->count > 0, w, h, &p->fc, err);
        if (st != PNPR_OK) return st;
    }
    /* continuous resolution queue: how many points this frame */
    size_t n_draw = r->count;
    p->coverage = r->count ? pnpr_box_coverage(&p->fc, r->bmin, r->bmax, w, h) : 0;
    if (o->budget > 0 && o->budget < n_draw) n_draw = o->budget;
    if (o->density > 0) {
        double cap = ceil((double)o->density * p->coverage);
        if (cap < (double)n_draw) n_draw = (size_t)cap;
    }
    p->n_draw = n_draw;
    /* a random subset of fraction f has 1/sqrt(f) times the spacing: grow the disks to match */
    p->lod = n_draw > 0 ? (float)sqrt((double)r->count / (double)n_draw) : 1;
    return PNPR_OK;
}

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

/* The directional strokes of the sketchy style's pass 2 (mode 0), shared with painterly. */
static void stroke_program(pnpr_renderer *r, const pnpr_frame_camera *fc, int fw, int fh, float stroke_width,
                           float point_scale, const float ink[4], int ink_from_points)
{
    glUseProgram(r->prog_stroke);
    glUniformMatrix4fv(r->ut.view, 1, GL_FALSE, fc->view);
    glUniformMatrix4fv(r->ut.proj, 1, GL_FALSE, fc->proj);
    glUniform2f(r->ut.viewport, (float)fw, (float)fh);
    glUniform1f(r->ut.ppu, fc->pixels_per_unit);
    glUniform1f(r->ut.width, stroke_width);
    glUniform1f(r->ut.radius_scale, point_scale);
    glUniform1i(r->ut.strokes, 0);
    glUniform4fv(r->ut.ink, 1, ink);
    glUniform1i(r->ut.ink_from_points, ink_from_points != 0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, r->stroke_tex);
}

/* Painterly (section 5.3). Mask: the bins' queue prefixes (n_draw split over the bins) as enlarged
 * pushed disks into depth, writing stencil 1. Pass L = 0..bins-1 draws bins L..bins-1 as brush
 * dabs of paint_brush(L) disk radii in the pass's blended colours; it needs about 1/brush^2 of
 * the points for the same coverage; the dab fills about half its sprite, so min(q * (points of
 * bins L..), 2 q * count / brush^2) with
 * q = n_draw / count, split over those bins in proportion to their sizes (never more than the
 * mask drew of a bin). Passes whose brush is larger than the mask disk test stencil == 1 (the
 * sky mask); the smaller ones do not. Then the directional strokes, stencil-tested. Returns the
 * number of dabs and strokes. */
static size_t draw_painterly(pnpr_renderer *r, const pnpr_frame_camera *fc, const pnpr_draw_options *o,
                             int fw, int fh, size_t n_draw, float lod, const size_t *gdraw, int filter)
{
    /* filter >= 0 (a style map): only the points of style `filter`; the shared mask (with stencil
     * filter + 1 under the points of this style) is already drawn */
    GLint ref = filter >= 0 ? filter + 1 : 1;
    size_t nb = r->paint_bins, bsize[PAINT_MAX_BINS], mdraw[PAINT_MAX_BINS], d[PAINT_MAX_BINS];
    for (size_t b = 0; b < nb; b++) bsize[b] = r->paint_start[b + 1] - r->paint_start[b];
    pnpr_crq_split(bsize, nb, n_draw, mdraw);
    float point_scale = o->point_scale > 0 ? o->point_scale : 1;
    float mask_scale = o->mask_scale > 0 ? o->mask_scale : 1.5f;
    size_t dabs = 0;
    /* the mask, with the sky stencil */
    if (filter < 0) {
        glUseProgram(r->prog_splat);
        glUniformMatrix4fv(r->us.view, 1, GL_FALSE, fc->view);
        glUniformMatrix4fv(r->us.proj, 1, GL_FALSE, fc->proj);
        glUniform1f(r->us.ppu, fc->pixels_per_unit);
        glUniform1i(r->us.ortho, fc->ortho);
        glUniform1f(r->us.max_size, r->max_point_size);
        glUniform1f(r->us.fade, 0.0f);
        glUniform1f(r->us.fixed_size, 0.0f);
        glUniform1f(r->us.levels, 0.0f);
        glUniform1f(r->us.radius_scale, point_scale * lod * mask_scale);
        glUniform1f(r->us.depth_push, 1.0f);
        glDisable(GL_BLEND);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_ALWAYS, 1, 0xFF);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        glStencilMask(0xFF);
        /* the mask doubles as the underpainting: its disks in the coarsest pass's blended colours,
         * so that no paper shows between the dabs inside the painted area (docs/rendering.md) */
        set_attribs(r->vao_paint, r->paint_vbo, r->paint_style_vbo, 0, 0, 0);
        glBindBuffer(GL_ARRAY_BUFFER, r->paint_col_vbo);
        glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, 4, (const void *)0);
        for (size_t b = 0; b < nb; b++)
            if (mdraw[b]) glDrawArrays(GL_POINTS, (GLint)r->paint_start[b], (GLsizei)mdraw[b]);
    }
    set_attribs(r->vao_paint, r->paint_vbo, r->paint_style_vbo, 0, 0, 0);
    /* the passes, large brushes to small */
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_FALSE);
    glStencilMask(0);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glStencilFunc(GL_EQUAL, ref, 0xFF);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(r->prog_paint);
    glUniformMatrix4fv(r->up.view, 1, GL_FALSE, fc->view);
    glUniformMatrix4fv(r->up.proj, 1, GL_FALSE, fc->proj);
    glUniform1f(r->up.ppu, fc->pixels_per_unit);
    glUniform1f(r->up.max_size, r->max_point_size);
    glUniform1i(r->up.style_filter, filter);
    glUniform1i(r->up.brush, 0);
    glBindTexture(GL_TEXTURE_2D, r->brush_tex);
    double q = r->count ? (double)n_draw / (double)r->count : 0;
    for (size_t L = 0; L < nb; L++) {
        float brush = paint_brush(L, nb);
        size_t avail = 0;
        for (size_t b = L; b < nb; b++) avail += bsize[b];
        double want = q * (double)avail, cap = 2.0 * q * (double)r->count / ((double)brush * brush); /* 2: the dab (a 2:1 ellipse) covers about half its sprite */
        size_t total = (size_t)ceil(want < cap ? want : cap);
        pnpr_crq_split(bsize + L, nb - L, total, d + L);
        if (brush > mask_scale && !o->paint_no_sky_mask) glEnable(GL_STENCIL_TEST);
        else glDisable(GL_STENCIL_TEST);
        glUniform1f(r->up.radius_scale, point_scale * lod * brush);
        /* attribute 2 <- this pass's colour level (vertex i's colour at level L is at L*count + i) */
        glBindBuffer(GL_ARRAY_BUFFER, r->paint_col_vbo);
        glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, 4, (const void *)(uintptr_t)(L * r->count * 4));
        for (size_t b = L; b < nb; b++) {
            size_t m = d[b] < mdraw[b] ? d[b] : mdraw[b];
            if (!m) continue;
            glDrawArrays(GL_POINTS, (GLint)r->paint_start[b], (GLsizei)m);
            dabs += m;
        }
    }
    /* directional strokes on top, inside the sky mask */
    if (!o->paint_no_strokes && gdraw[GROUP_DIRECTIONAL] > 0) {
        if (!o->paint_no_sky_mask) glEnable(GL_STENCIL_TEST);
        else glDisable(GL_STENCIL_TEST);
        float ink[4] = {0.08f, 0.08f, 0.1f, 1};
        int ink_given = o->ink[0] != 0 || o->ink[1] != 0 || o->ink[2] != 0 || o->ink[3] != 0;
        if (ink_given) memcpy(ink, o->ink, sizeof ink);
        /* brush strokes in the points' own colours unless an ink is asked for: no dark scratches */
        stroke_program(r, fc, fw, fh, o->stroke_width > 0 ? o->stroke_width : 2, point_scale, ink,
                       o->ink_from_points || !ink_given);
        glUniform1i(r->ut_filter, filter);
        glUniform1i(r->ut.mode, 0);
        glUniform1f(r->ut.layer, (float)o->stroke_texture);
        glUniform1f(r->ut.length, o->stroke_length > 0 ? o->stroke_length : 6);
        set_attribs(r->vao_strokes, r->vbo, r->style_vbo, r->group_start[GROUP_DIRECTIONAL], 1, 0);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)gdraw[GROUP_DIRECTIONAL]);
        dabs += gdraw[GROUP_DIRECTIONAL];
    }
    glDisable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    return dabs;
}

float pnpr_queue_fade_length(size_t drawn, size_t size, float fraction)
{
    if (fraction < 0 || drawn == 0 || drawn >= size) return 0;
    double f = (fraction > 0 ? fraction : PNPR_QUEUE_FADE) * (double)drawn, left = (double)(size - drawn) + 1;
    if (f > left) f = left;
    return f >= 1 ? (float)f : 1.0f;
}

/* Pass 2 of `sketchy`: directional strokes and hatches of the groups' queue prefixes, depth-tested
 * against the mask, no depth writes, blended. Returns the strokes drawn. */
static size_t draw_sketchy(pnpr_renderer *r, const pnpr_frame_camera *fc, const pnpr_draw_options *o, int fw,
                           int fh, const size_t *gdraw, float point_scale, const float ink[4])
{
    size_t strokes = 0;
    float stroke_length = o->stroke_length > 0 ? o->stroke_length : 6;
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    stroke_program(r, fc, fw, fh, o->stroke_width > 0 ? o->stroke_width : 2, point_scale, ink, o->ink_from_points);
    int draw_group[3] = {1, o->sketch_variant != PNPR_SKETCH_DIRECTIONAL, o->sketch_variant == PNPR_SKETCH_ALL};
    /* the dithering hatches (tone) in a lighter pencil than the strokes and hatches of features */
    float tone_ink[4] = {ink[0], ink[1], ink[2], ink[3] * SKETCH_TONE_INK};
    for (int g = GROUP_DIRECTIONAL; g <= GROUP_DITHER; g++) {
        if (!draw_group[g] || !gdraw[g]) continue;
        int directional = g == GROUP_DIRECTIONAL;
        glUniform1i(r->ut.mode, directional ? 0 : 1);
        glUniform1f(r->ut.layer, directional ? (float)o->stroke_texture : (float)STROKE_LAYER_HATCH);
        glUniform1f(r->ut.length, directional ? stroke_length : 0.5f * stroke_length);
        glUniform1i(r->ut.thin, g == GROUP_DITHER);
        glUniform4fv(r->ut.ink, 1, g == GROUP_DITHER ? tone_ink : ink);
        glUniform1f(r->ut.queue_end, (float)gdraw[g]);
        glUniform1f(r->ut.queue_fade, pnpr_queue_fade_length(gdraw[g], r->group_start[g + 1] - r->group_start[g], o->queue_fade));
        set_attribs(r->vao_strokes, r->vbo, r->style_vbo, r->group_start[g], 1, 0);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)gdraw[g]);
        strokes += gdraw[g];
    }
    glUniform1i(r->ut.thin, 0);
    glUniform1f(r->ut.queue_fade, 0.0f);
    glUniform4fv(r->ut.ink, 1, ink);
    return strokes;
}

/* Pass 2 of `stipple`: the queue prefixes of the feature and dithering groups as dots of a fixed
 * screen size in the ink colour (antialiased edges), depth-tested against the mask, no depth
 * writes, blended. The splat program must be current with the frame's uniforms. */
static size_t draw_stipple(pnpr_renderer *r, const pnpr_draw_options *o, const size_t *gdraw, float point_scale,
                           float lod, const float ink[4])
{
    size_t dots = 0;
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUniform1f(r->us.radius_scale, point_scale * lod);
    glUniform1f(r->us.depth_push, 0.0f);
    glUniform1f(r->us.fade, 1.0f);
    glUniform4fv(r->us.fade_color, 1, ink);
    glUniform1f(r->us.fixed_size, o->dot_size > 0 ? o->dot_size : 2.5f);
    glBindVertexArray(r->vao_points);
    for (int g = GROUP_DIRECTIONAL; g <= GROUP_DITHER; g++) {
        if (!gdraw[g]) continue;
        glUniform1i(r->us.thin, g == GROUP_DITHER);
        glUniform1f(r->us.queue_end, (float)(r->group_start[g] + gdraw[g]));
        glUniform1f(r->us.queue_fade, pnpr_queue_fade_length(gdraw[g], r->group_start[g + 1] - r->group_start[g], o->queue_fade));
        glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
        dots += gdraw[g];
    }
    glUniform1i(r->us.thin, 0);
    glUniform1f(r->us.queue_fade, 0.0f);
    glUniform1f(r->us.fade, 0.0f);
    glUniform1f(r->us.fixed_size, 0.0f);
    return dots;
}

/* Pass 2 of `lines`: the segments, depth-tested against the mask (no mask when the cloud is
 * empty: nothing hides them), no depth writes, blended. Returns the segments drawn. */
static size_t draw_lines(pnpr_renderer *r, const pnpr_frame_camera *fc, const pnpr_draw_options *o, int fw, int fh,
                         float lod, const float ink[4])
{
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
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
    glUniform2f(r->ul.viewport, (float)fw, (float)fh);
    glUniform1f(r->ul.width, o->line_width > 0 ? o->line_width : 2);
    /* orthographic: w = 1 everywhere, nothing to move onto the near plane (GL clips) */
    glUniform1f(r->ul.near_plane, fc->ortho ? -1e30f : (float)fc->near_plane);
    glUniform4fv(r->ul.ink, 1, ink);
    /* lines lie on the surface the mask is made of: pulled towards the eye by two mean disk
     * radii so that the mask's disks do not cut them into dashes (docs/rendering.md) */
    float ps = o->point_scale > 0 ? o->point_scale : 1;
    glUniform1f(r->ul.pull, 2.0f * r->mean_radius * ps * lod);
    glUniform1i(r->ul.ortho, fc->ortho);
    glUniform1f(r->ul.ppu, fc->pixels_per_unit);
    glUniform1f(r->ul.min_px, o->line_min_px > 0 ? o->line_min_px : PNPR_LINE_MIN_PX);
    glBindVertexArray(r->vao_lines);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)r->line_segments);
    return r->line_segments;
}

/* ---- style maps (intermingled styles) ---- */

typedef struct map_key { uint32_t label, index; pnpr_style style; } map_key;
static int cmp_map_key(const void *a, const void *b)
{
    const map_key *x = a, *y = b;
    if (x->label != y->label) return x->label < y->label ? -1 : 1;
    return x->index < y->index ? -1 : x->index > y->index;
}

/* The style of every vertex (main order) under o's map: a label's last entry, o->style for labels
 * not in the map; r_used[s] = how many vertices got style s. The cloud has labels. */
static pnpr_status resolve_styles(const pnpr_renderer *r, const pnpr_draw_options *o, uint8_t *r_style, size_t *r_used)
{
    size_t m = o->style_map_count;
    map_key *keys = malloc(m * sizeof *keys);
    if (!keys) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; i < m; i++) {
        keys[i].label = o->style_map[i].label;
        keys[i].index = (uint32_t)i;
        keys[i].style = o->style_map[i].style;
    }
    qsort(keys, m, sizeof *keys, cmp_map_key);
    for (int s = 0; s < PNPR_STYLE_COUNT_; s++) r_used[s] = 0;
    for (size_t q = 0; q < r->count; q++) {
        uint32_t label = r->vlabel[q];
        size_t lo = 0, hi = m; /* first key with a larger label */
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (keys[mid].label <= label) lo = mid + 1;
            else hi = mid;
        }
        pnpr_style s = lo > 0 && keys[lo - 1].label == label ? keys[lo - 1].style : o->style;
        r_style[q] = (uint8_t)s;
        r_used[s]++;
    }
    free(keys);
    return PNPR_OK;
}

/* Uploads the per-vertex style bytes (main and painterly order) when they changed. */
static pnpr_status upload_styles(pnpr_renderer *r, const uint8_t *vstyle)
{
    if (!memcmp(vstyle, r->vstyle, r->count)) return PNPR_OK;
    glBindBuffer(GL_ARRAY_BUFFER, r->style_vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)r->count, vstyle);
    if (r->paint_bins && r->paint_src) {
        uint8_t *ps = malloc(r->count);
        if (!ps) return PNPR_ERR_OUT_OF_MEMORY;
        for (size_t q = 0; q < r->count; q++) ps[q] = vstyle[r->paint_src[q]];
        glBindBuffer(GL_ARRAY_BUFFER, r->paint_style_vbo);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)r->count, ps);
        free(ps);
    }
    memcpy(r->vstyle, vstyle, r->count);
    return PNPR_OK;
}

/* A frame with several styles (a style map). Pass 1, the one visibility mask: every style's
 * points of the queue prefixes (painterly's from its bin queues) as enlarged pushed disks into
 * depth, each writing stencil = its style + 1 where it passes (the front-most surface's style);
 * cartoon's disks are its outline disks (outline scale, ink colour), drawn after the others.
 * Pass 2, each style over its own points (a vertex-shader filter on the style byte), in the
 * order points (opaque, depth writes), cartoon fills, painterly (sky stencil = its style),
 * stipple, sketchy, lines (stencil = the lines style: the lines show over those segments only).
 * Returns the primitives of pass 2 other than plain splats. */
static size_t draw_mapped(pnpr_renderer *r, const pnpr_frame_camera *fc, const pnpr_draw_options *o, int fw,
                          int fh, size_t n_draw, float lod, const size_t *gdraw, size_t ng, const size_t *used,
                          const float ink[4])
{
    float ps = o->point_scale > 0 ? o->point_scale : 1;
    float mask_scale = o->mask_scale > 0 ? o->mask_scale : 1.5f;
    float outline_scale = o->mask_scale > 0 ? o->mask_scale : 2.0f;
    size_t strokes = 0;
    size_t nb = r->paint_bins, bsize[PAINT_MAX_BINS], mdraw[PAINT_MAX_BINS];
    for (size_t b = 0; b < nb; b++) bsize[b] = r->paint_start[b + 1] - r->paint_start[b];
    if (nb) pnpr_crq_split(bsize, nb, n_draw, mdraw);

    glUseProgram(r->prog_splat);
    glUniformMatrix4fv(r->us.view, 1, GL_FALSE, fc->view);
    glUniformMatrix4fv(r->us.proj, 1, GL_FALSE, fc->proj);
    glUniform1f(r->us.ppu, fc->pixels_per_unit);
    glUniform1i(r->us.ortho, fc->ortho);
    glUniform1f(r->us.max_size, r->max_point_size);
    glUniform1f(r->us.fade, 0.0f);
    glUniform1f(r->us.fixed_size, 0.0f);
    glUniform1f(r->us.levels, 0.0f);
    glUniform1f(r->us.depth_push, 1.0f);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glEnable(GL_STENCIL_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glStencilMask(0xFF);
    /* pass 1: the shared mask */
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glUniform1f(r->us.radius_scale, ps * lod * mask_scale);
    for (int s = 0; s < PNPR_STYLE_COUNT_; s++) {
        if (!used[s] || s == PNPR_STYLE_CARTOON) continue;
        glStencilFunc(GL_ALWAYS, s + 1, 0xFF);
        glUniform1i(r->us_filter, s);
        if (s == PNPR_STYLE_PAINTERLY) {
            set_attribs(r->vao_paint, r->paint_vbo, r->paint_style_vbo, 0, 0, 0);
            for (size_t b = 0; b < nb; b++)
                if (mdraw[b]) glDrawArrays(GL_POINTS, (GLint)r->paint_start[b], (GLsizei)mdraw[b]);
        } else {
            glBindVertexArray(r->vao_points);
            for (size_t g = 0; g < ng; g++)
                if (gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
        }
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (used[PNPR_STYLE_CARTOON]) { /* outline disks: depth and colour (ink) */
        glStencilFunc(GL_ALWAYS, PNPR_STYLE_CARTOON + 1, 0xFF);
        glUniform1i(r->us_filter, PNPR_STYLE_CARTOON);
        glUniform1f(r->us.radius_scale, ps * lod * outline_scale);
        glUniform1f(r->us.fade, 1.0f);
        glUniform4f(r->us.fade_color, ink[0], ink[1], ink[2], 1.0f);
        glBindVertexArray(r->vao_points);
        for (size_t g = 0; g < ng; g++)
            if (gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
        glUniform1f(r->us.fade, 0.0f);
    }
    glStencilMask(0);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glDisable(GL_STENCIL_TEST);
    /* pass 2 */
    glUniform1f(r->us.depth_push, 0.0f);
    glUniform1f(r->us.radius_scale, ps * lod);
    if (used[PNPR_STYLE_POINTS]) { /* opaque splats, depth writes (the nearest wins) */
        glUniform1i(r->us_filter, PNPR_STYLE_POINTS);
        glBindVertexArray(r->vao_points);
        for (size_t g = 0; g < ng; g++)
            if (gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
    }
    glDepthMask(GL_FALSE);
    if (used[PNPR_STYLE_CARTOON]) { /* flat colours over the outline disks */
        glUniform1i(r->us_filter, PNPR_STYLE_CARTOON);
        glBindVertexArray(r->vao_flat);
        for (size_t g = 0; g < ng; g++)
            if (gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
    }
    if (used[PNPR_STYLE_LINES] && o->faint > 0) { /* the faint points under the lines segments */
        float bg[4] = {o->background[0], o->background[1], o->background[2], o->background[3]};
        glUniform1i(r->us_filter, PNPR_STYLE_LINES);
        glUniform1f(r->us.fade, 1.0f - o->faint);
        glUniform4fv(r->us.fade_color, 1, bg);
        glBindVertexArray(r->vao_points);
        for (size_t g = 0; g < ng; g++)
            if (gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
        glUniform1f(r->us.fade, 0.0f);
    }
    if (used[PNPR_STYLE_PAINTERLY] && nb) {
        strokes += draw_painterly(r, fc, o, fw, fh, n_draw, lod, gdraw, PNPR_STYLE_PAINTERLY);
        glUniform1i(r->ut_filter, -1);
        glUseProgram(r->prog_paint);
        glUniform1i(r->up.style_filter, -1);
        glUseProgram(r->prog_splat);
    }
    if (used[PNPR_STYLE_STIPPLE]) {
        glUniform1i(r->us_filter, PNPR_STYLE_STIPPLE);
        strokes += draw_stipple(r, o, gdraw, ps, lod, ink);
    }
    glUniform1i(r->us_filter, -1);
    if (used[PNPR_STYLE_SKETCHY]) {
        glUseProgram(r->prog_stroke);
        glUniform1i(r->ut_filter, PNPR_STYLE_SKETCHY);
        strokes += draw_sketchy(r, fc, o, fw, fh, gdraw, ps, ink);
        glUniform1i(r->ut_filter, -1);
    }
    if (used[PNPR_STYLE_LINES] && r->line_segments > 0) {
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_EQUAL, PNPR_STYLE_LINES + 1, 0xFF);
        strokes += draw_lines(r, fc, o, fw, fh, lod, ink);
        glDisable(GL_STENCIL_TEST);
    }
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    return strokes;
}

static pnpr_status draw_impl(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                             const pnpr_target *target, const tile_rect *tile, pnpr_render_stats *r_stats,
                             pnpr_frame_record *rec, pnpr_error *err)
{
    if (!r || !target) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: NULL renderer or target");
    if (r_stats) memset(r_stats, 0, sizeof *r_stats);
    pnpr_draw_options o;
    int fw = target->width, fh = target->height; /* the frame (framebuffer) */
    int w = tile ? tile->full_w : fw, h = tile ? tile->full_h : fh; /* the image */
    if (w <= 0 || h <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: image size %dx%d must be positive", w, h);
    if (fw > r->max_size || fh > r->max_size)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT,
                              "renderer: image size %dx%d exceeds this GL's limit %d (pnpr_renderer_snapshot renders larger images in tiles)",
                              fw, fh, (int)r->max_size);
    pnpr_status st = check_options(r, opts, &o, err);
    if (st != PNPR_OK) return st;
    /* a style map: the style of every point; when they all end up in one style, that style's
     * own path (the same frame as without a map) */
    uint8_t *vstyle = NULL;
    size_t used[PNPR_STYLE_COUNT_] = {0};
    if (o.style_map_count > 0 && r->count > 0 && r->vlabel) {
        vstyle = malloc(r->count);
        if (!vstyle) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "renderer: style map: out of memory");
        st = resolve_styles(r, &o, vstyle, used);
        if (st != PNPR_OK) { free(vstyle); return pnpr_error_set(err, st, "renderer: style map: out of memory"); }
        int nused = 0;
        pnpr_style only = o.style;
        for (int s = 0; s < PNPR_STYLE_COUNT_; s++)
            if (used[s]) { nused++; only = (pnpr_style)s; }
        if (nused <= 1) { o.style = only; free(vstyle); vstyle = NULL; }
    }
    float point_scale = o.point_scale > 0 ? o.point_scale : 1;
    float mask_scale = o.mask_scale > 0 ? o.mask_scale : o.style == PNPR_STYLE_CARTOON ? 2.0f : 1.5f;
    float ink[4] = {0.08f, 0.08f, 0.1f, 1};
    if (o.ink[0] != 0 || o.ink[1] != 0 || o.ink[2] != 0 || o.ink[3] != 0) memcpy(ink, o.ink, sizeof ink);

    frame_plan plan;
    st = plan_frame(r, camera, &o, w, h, &plan, err);
    if (st != PNPR_OK) { free(vstyle); return st; }
    pnpr_frame_camera fc = plan.fc;
    if (tile) tile_projection(fc.proj, tile);
    size_t n_draw = plan.n_draw;
    double coverage = plan.coverage;
    float lod = plan.lod;
    size_t gsize[GROUP_MAX + 1], gdraw[GROUP_MAX + 1];
    size_t ng = r->group_count + 1; /* + "other" (empty by construction) */
    for (size_t g = 0; g < ng; g++) gsize[g] = r->group_start[g + 1] - r->group_start[g];
    pnpr_crq_split(gsize, ng, n_draw, gdraw);

    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    pnpr_gl_state_neutral();
    st = ensure_framebuffer(r, fw, fh, err);
    if (st == PNPR_OK && vstyle) {
        st = upload_styles(r, vstyle);
        if (st != PNPR_OK) pnpr_error_set(err, st, "renderer: style map: out of memory");
    }
    if (st != PNPR_OK) { pnpr_gl_state_restore(&saved); free(vstyle); return st; }
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glViewport(0, 0, fw, fh);
    float a = o.background[3];
    glClearColor(o.background[0] * a, o.background[1] * a, o.background[2] * a, a); /* premultiplied */
    glClearDepth(1.0);
    glDepthMask(GL_TRUE);
    glClearStencil(0);
    set_draw_buffers(1, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    const float no_surface[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 1, no_surface);
    set_draw_buffers(0, 1);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);

    size_t strokes = 0;
    int mapped = vstyle != NULL;
    /* outlines: after the style's passes, from the mask's surface info (written only then) */
    float outline_width = 0;
    int outline = pnpr_style_outline_default(o.style, &outline_width);
    if (o.outline) outline = o.outline > 0;
    if (o.outline_width > 0) outline_width = o.outline_width;
    outline = outline && !mapped && o.style != PNPR_STYLE_PAINTERLY && o.style != PNPR_STYLE_POINTS && n_draw > 0;
    int ink_only = rec && rec->outline_ink_only;
    if (rec) {
        memset(rec, 0, sizeof *rec);
        rec->outline_ink_only = ink_only;
        rec->o = o;
        rec->o.style_map = NULL;
        rec->o.style_map_count = 0;
        rec->fc = fc;
        rec->width = fw;
        rec->height = fh;
        rec->n_draw = n_draw;
        memcpy(rec->gdraw, gdraw, sizeof gdraw);
        rec->point_scale = point_scale;
        rec->lod = lod;
        memcpy(rec->ink, ink, sizeof ink);
        rec->outline = outline;
        rec->outline_width = outline_width > 0 ? outline_width : 2;
        rec->mapped = mapped;
    }
    int sketchy = o.style == PNPR_STYLE_SKETCHY, lines = o.style == PNPR_STYLE_LINES;
    int stipple = o.style == PNPR_STYLE_STIPPLE, cartoon = o.style == PNPR_STYLE_CARTOON;
    int masked = sketchy || lines || stipple; /* pass 1 is a depth-only visibility mask */
    int painterly = o.style == PNPR_STYLE_PAINTERLY;
    if (vstyle) { /* several styles: none of the single-style paths below */
        if (n_draw > 0) strokes = draw_mapped(r, &fc, &o, fw, fh, n_draw, lod, gdraw, ng, used, ink);
        sketchy = lines = stipple = cartoon = masked = painterly = 0;
        free(vstyle);
        vstyle = NULL;
    }
    if (painterly && n_draw > 0) strokes = draw_painterly(r, &fc, &o, fw, fh, n_draw, lod, gdraw, -1);
    if (n_draw > 0 && !painterly && !mapped) {
        glUseProgram(r->prog_splat);
        glUniformMatrix4fv(r->us.view, 1, GL_FALSE, fc.view);
        glUniformMatrix4fv(r->us.proj, 1, GL_FALSE, fc.proj);
        glUniform1f(r->us.ppu, fc.pixels_per_unit);
        glUniform1i(r->us.ortho, fc.ortho);
        glUniform1f(r->us.max_size, r->max_point_size);
        glUniform1f(r->us.fade, 0.0f);
        glUniform1f(r->us.fixed_size, 0.0f);
        glUniform1f(r->us.levels, 0.0f);
        glDisable(GL_BLEND);
        glBindVertexArray(r->vao_points);
        if (lines && o.faint > 0) {
            /* lines over a faint point rendering: regular splats, colours mixed with the
             * (opaque) background, then a fresh depth buffer for the mask */
            float bg[4] = {o.background[0], o.background[1], o.background[2], o.background[3]};
            glUniform1f(r->us.fade, 1.0f - o.faint);
            glUniform4fv(r->us.fade_color, 1, bg);
            glUniform1f(r->us.radius_scale, point_scale * lod);
            glUniform1f(r->us.depth_push, 0.0f);
            for (size_t g = 0; g < ng; g++)
                if (gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
            glClear(GL_DEPTH_BUFFER_BIT);
            glUniform1f(r->us.fade, 0.0f);
        }
        /* pass 1 (mask) / the only pass (points): round disks of the prefixes; the mask writes
         * the surface info (attachment 1) for the outlines. Cartoon: the enlarged disks go into
         * depth AND colour, in the flat colours (they close the gaps between the splats) */
        glUniform1f(r->us.radius_scale, point_scale * lod * (masked || cartoon ? mask_scale : 1));
        glUniform1f(r->us.depth_push, masked || cartoon ? 1.0f : 0.0f);
        if (masked || cartoon) set_draw_buffers(outline, cartoon);
        if (cartoon) glUniform1f(r->us.levels, r->has_labels || !r->has_rgb ? 0.0f : (float)(o.levels ? o.levels : 4));
        glBindVertexArray(cartoon ? r->vao_flat : r->vao_points);
        for (size_t g = 0; g < ng; g++)
            if (gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
        set_draw_buffers(0, 1);
        if (cartoon) {
            /* pass 2: the same points as regular-size opaque splats in flat colours, depth-tested
             * against the enlarged disks, no depth writes, the frame not cleared */
            glDepthMask(GL_FALSE);
            glUniform1f(r->us.radius_scale, point_scale * lod);
            glUniform1f(r->us.depth_push, 0.0f);
            glUniform1f(r->us.levels, r->has_labels || !r->has_rgb ? 0.0f : (float)(o.levels ? o.levels : 4));
            glBindVertexArray(r->vao_flat);
            for (size_t g = 0; g < ng; g++)
                if (gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
            glUniform1f(r->us.levels, 0.0f);
        }

        if (sketchy) strokes += draw_sketchy(r, &fc, &o, fw, fh, gdraw, point_scale, ink);
    }
    if (stipple && n_draw > 0) strokes += draw_stipple(r, &o, gdraw, point_scale, lod, ink);
    if (lines && r->line_segments > 0) strokes = draw_lines(r, &fc, &o, fw, fh, lod, ink);
    if (outline) {
        /* the mask's boundary is drawn by the largest disks of the outermost points: about 1.1
         * mean mask radii beyond them (measured on random samplings, docs/rendering.md); the
         * silhouette is drawn that far inside it */
        float inset = 1.1f;
        pnpr_edge_params ep = {outline_width > 0 ? outline_width : 2, o.outline_jump > 0 ? o.outline_jump : PNPR_OUTLINE_JUMP,
                               o.outline_hole > 0 ? o.outline_hole : PNPR_OUTLINE_HOLE, PNPR_EDGE_MAX_REACH, fc.pixels_per_unit,
                               fc.ortho, {ink[0], ink[1], ink[2], ink[3]}, inset,
                               {o.background[0] * a, o.background[1] * a, o.background[2] * a, a}};
        if (ink_only) { /* vector drawings: the outlines' ink alone (vector.c) */
            const float clear[4] = {0, 0, 0, 0};
            glClearBufferfv(GL_COLOR, 0, clear);
            memset(ep.background, 0, sizeof ep.background);
        }
        st = pnpr_edges_draw(&r->edges, r->info_tex, r->fbo, fw, fh, &ep, err);
        if (st != PNPR_OK) { pnpr_gl_state_restore(&saved); return st; }
    }

    if (!target->offscreen && !tile) {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)target->framebuffer);
        glViewport(target->x, target->y, w, h);
        glDisable(GL_DEPTH_TEST);
        glDepthMask(GL_FALSE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        if (o.composite == PNPR_COMPOSITE_OVER) {
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
    pnpr_gl_state_restore(&saved);
    if (r_stats) {
        r_stats->points_total = r->count;
        r_stats->points_drawn = n_draw;
        r_stats->strokes_drawn = strokes;
        r_stats->coverage_px = coverage;
    }
    return PNPR_OK;
}

pnpr_status pnpr_renderer_draw(pnpr_renderer *r, const pnpr_camera *camera,
                               const pnpr_draw_options *opts, const pnpr_target *target,
                               pnpr_render_stats *r_stats, pnpr_error *err)
{
    return draw_impl(r, camera, opts, target, NULL, r_stats, NULL, err);
}

pnpr_status pnpr_renderer_draw_recorded(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                        int width, int height, pnpr_frame_record *rec, pnpr_error *err)
{
    pnpr_target tgt = {0, 0, 0, width, height, 1};
    return draw_impl(r, camera, opts, &tgt, NULL, NULL, rec, err);
}

/* GL's rows go bottom-up: flip in place; then optionally un-premultiply. */
static void finish_pixels(uint8_t *rgba, int w, int h, int unpremultiply)
{
    size_t row = (size_t)w * 4;
    for (int y = 0; y < h / 2; y++) {
        uint8_t *p = rgba + (size_t)y * row, *q = rgba + (size_t)(h - 1 - y) * row;
        for (size_t i = 0; i < row; i++) { uint8_t t = p[i]; p[i] = q[i]; q[i] = t; }
    }
    if (unpremultiply) {
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
            uint8_t *p = rgba + 4 * i;
            if (p[3] == 0 || p[3] == 255) continue;
            for (int c = 0; c < 3; c++) {
                unsigned v = (p[c] * 255u + p[3] / 2u) / p[3];
                p[c] = (uint8_t)(v > 255 ? 255 : v);
            }
        }
    }
}

pnpr_status pnpr_renderer_read_frame(pnpr_renderer *r, uint8_t *rgba, int unpremultiply)
{
    if (!r || !rgba) return PNPR_ERR_INVALID_ARGUMENT;
    if (!r->fbo || r->fb_w <= 0) return PNPR_ERR_EMPTY;
    int w = r->fb_w, h = r->fb_h;
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    pnpr_gl_state_neutral();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    pnpr_gl_state_restore(&saved);
    finish_pixels(rgba, w, h, unpremultiply);
    return PNPR_OK;
}

int pnpr_renderer_max_size(const pnpr_renderer *r) { return r ? (int)r->max_size : 0; }

pnpr_status pnpr_image_bytes(int width, int height, size_t limit, size_t *r_bytes, pnpr_error *err)
{
    if (r_bytes) *r_bytes = 0;
    if (width <= 0 || height <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "image size %dx%d must be positive", width, height);
    if (limit == 0) limit = PNPR_IMAGE_BYTES_DEFAULT_LIMIT;
    if ((size_t)width > SIZE_MAX / 4 / (size_t)height || (size_t)width * (size_t)height * 4 > limit)
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY,
                              "image %dx%d needs %.3g GiB of RGBA memory, more than the limit of %.3g GiB",
                              width, height, (double)width * (double)height * 4.0 / 1073741824.0,
                              (double)limit / 1073741824.0);
    if (r_bytes) *r_bytes = (size_t)width * (size_t)height * 4;
    return PNPR_OK;
}

pnpr_status pnpr_renderer_snapshot(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                   int width, int height, const pnpr_snapshot_options *sopts,
                                   uint8_t *r_rgba, pnpr_render_stats *r_stats, pnpr_error *err)
{
    if (!r || !r_rgba) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "snapshot: NULL renderer or pixels");
    if (r_stats) memset(r_stats, 0, sizeof *r_stats);
    pnpr_snapshot_options so;
    memset(&so, 0, sizeof so);
    if (sopts) so = *sopts;
    if (width <= 0 || height <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "snapshot: image size %dx%d must be positive", width, height);
    if (so.max_tile_size < 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "snapshot: max_tile_size %d is negative", so.max_tile_size);
    int tmax = (int)r->max_size;
    if (so.max_tile_size > 0 && so.max_tile_size < tmax) tmax = so.max_tile_size;
    pnpr_target tgt = {0, 0, 0, width, height, 1};
    if (width <= tmax && height <= tmax) { /* one frame: exactly pnpr_renderer_draw */
        pnpr_status st = draw_impl(r, camera, opts, &tgt, NULL, r_stats, NULL, err);
        if (st != PNPR_OK) return st;
        pnpr_progress_report(&so.progress, "tile 1/1", 1.0);
        return pnpr_renderer_read_frame(r, r_rgba, so.unpremultiply);
    }
    if (tmax < 16)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "snapshot: tiles of at most %d px are too small", tmax);
    pnpr_draw_options o;
    pnpr_status st = check_options(r, opts, &o, err);
    if (st != PNPR_OK) return st;
    frame_plan plan;
    st = plan_frame(r, camera, &o, width, height, &plan, err);
    if (st != PNPR_OK) return st;
    /* Guard band: GL drops a point sprite whose centre leaves the viewport, so every tile is
     * rendered with a margin of the largest sprite's half size (estimated from the largest disk
     * at the box's nearest depth, clamped to GL's point size range and to a quarter tile). */
    double dmin = INFINITY;
    for (int k = 0; k < 8; k++) {
        double p[3] = {(k & 1) ? r->bmax[0] : r->bmin[0], (k & 2) ? r->bmax[1] : r->bmin[1],
                       (k & 4) ? r->bmax[2] : r->bmin[2]};
        double d = -((double)plan.fc.view[2] * p[0] + (double)plan.fc.view[6] * p[1] +
                     (double)plan.fc.view[10] * p[2] + (double)plan.fc.view[14]);
        if (d < dmin) dmin = d;
    }
    if (!(dmin > plan.fc.near_plane)) dmin = plan.fc.near_plane;
    if (plan.fc.ortho) dmin = 1; /* orthographic: clip w = 1, sprite sizes do not depend on depth */
    float ps = o.point_scale > 0 ? o.point_scale : 1, ms = o.mask_scale > 0 ? o.mask_scale : 2.0f;
    double grow = ps * plan.lod * (ms > PNPR_PAINT_MAX_BRUSH ? ms : PNPR_PAINT_MAX_BRUSH);
    double sprite = r->count ? 2.0 * r->max_radius * grow * plan.fc.pixels_per_unit / dmin : 0;
    if (!(sprite <= r->max_point_size)) sprite = r->max_point_size;
    double extra = (o.dot_size > 0 ? o.dot_size : 2.5) + (o.line_width > 0 ? o.line_width : 2) +
                   PNPR_EDGE_MAX_REACH + PNPR_EDGE_MAX_INSET + 3 + (o.outline_width > 0 ? o.outline_width : 4);
    int margin = (int)ceil(0.5 * sprite + extra) + 1;
    if (margin > tmax / 4) margin = tmax / 4;
    int inner = tmax - 2 * margin;
    int nx = (width + inner - 1) / inner, ny = (height + inner - 1) / inner;
    if ((double)nx * ny > PNPR_SNAPSHOT_TILES_MAX)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT,
                              "snapshot: %dx%d in tiles of %d px takes %.0f tiles, more than %d (raise max_tile_size)",
                              width, height, tmax, (double)nx * ny, PNPR_SNAPSHOT_TILES_MAX);
    int ntiles = nx * ny, done = 0;
    tgt.width = tgt.height = tmax;
    for (int ty = 0; ty < ny; ty++)
        for (int tx = 0; tx < nx; tx++) {
            int x0 = tx * inner, y0 = ty * inner;
            int iw = width - x0 < inner ? width - x0 : inner, ih = height - y0 < inner ? height - y0 : inner;
            tile_rect t = {width, height, x0 - margin, y0 - margin, tmax, tmax};
            pnpr_render_stats ts;
            st = draw_impl(r, camera, &o, &tgt, &t, &ts, NULL, err);
            if (st != PNPR_OK) return st;
            if (r_stats && done == 0) *r_stats = ts;
            pnpr_gl_state saved;
            pnpr_gl_state_save(&saved);
            pnpr_gl_state_neutral();
            glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
            glReadBuffer(GL_COLOR_ATTACHMENT0);
            glPixelStorei(GL_PACK_ROW_LENGTH, width);
            glReadPixels(margin, margin, iw, ih, GL_RGBA, GL_UNSIGNED_BYTE,
                         r_rgba + ((size_t)y0 * (size_t)width + (size_t)x0) * 4);
            pnpr_gl_state_restore(&saved);
            done++;
            char stage[48];
            snprintf(stage, sizeof stage, "tile %d/%d", done, ntiles);
            if (pnpr_progress_report(&so.progress, stage, (double)done / ntiles))
                return pnpr_error_set(err, PNPR_ERR_CANCELLED, "snapshot: cancelled after %s", stage);
        }
    finish_pixels(r_rgba, width, height, so.unpremultiply);
    return PNPR_OK;
}

void pnpr_renderer_frame_size(const pnpr_renderer *r, int *w, int *h)
{
    if (w) *w = r ? r->fb_w : 0;
    if (h) *h = r ? r->fb_h : 0;
}
