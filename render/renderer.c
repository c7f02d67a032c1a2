/* The PointWorks renderer: two-pass visibility mask (section 4.3), continuous resolution queue
 * (4.4), `points`, `sketchy` (5.1), `lines` (5.2), `stipple` and `cartoon` (5.4) styles. See docs/rendering.md. */
#include "render_internal.h"
#include "gl_state.h"
#include "pnpr_shaders.h"

#include <pointnpr/features.h>
#include <pointnpr/knn.h>

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Queue groups: with features, one queue per class (as the paper groups them); else one. */
enum { GROUP_DIRECTIONAL = 0, GROUP_NONDIRECTIONAL, GROUP_DITHER, GROUP_NONE, GROUP_MAX };

enum { STROKE_TEX_W = 128, STROKE_TEX_H = 32, STROKE_LAYERS = 4, STROKE_LAYER_HATCH = 3 };

typedef struct pnpr_vertex {
    float pos[3];
    float radius;
    uint8_t rgba[4];
    float dir[3];
    uint8_t flat[4]; /* cartoon: the segment's mean colour (the point colour without labels) */
} pnpr_vertex;

typedef struct splat_uniforms { GLint view, proj, ppu, radius_scale, depth_push, max_size, fade, fade_color, fixed_size, levels; } splat_uniforms;
typedef struct line_uniforms { GLint view, proj, viewport, width, near_plane, ink; } line_uniforms;
typedef struct stroke_uniforms {
    GLint view, proj, viewport, ppu, length, width, radius_scale, mode, strokes, layer, ink, ink_from_points;
} stroke_uniforms;

struct pnpr_renderer {
    GLuint prog_splat, prog_stroke, prog_composite, prog_line;
    splat_uniforms us;
    line_uniforms ul;
    stroke_uniforms ut;
    GLint uc_frame, uc_origin;
    GLuint vbo, vao_points, vao_strokes, vao_empty, vao_flat;
    GLuint line_vbo, vao_lines;
    GLuint stroke_tex;
    GLuint fbo, color_tex, depth_rb;
    int fb_w, fb_h;
    float max_point_size;
    GLint max_size;
    /* the uploaded cloud */
    size_t count;
    size_t group_start[GROUP_MAX + 2];
    size_t group_count;
    int has_features, has_labels;
    double origin[3];
    float bmin[3], bmax[3];
    /* the profile lines: segments as pairs of float offsets from line_origin */
    size_t line_segments;
    double line_origin[3];
};

/* ---- shaders -------------------------------------------------------------------------------- */

static GLuint compile(GLenum type, const char *src, const char *name, pnpr_error *err)
{
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, 1, &src, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[400] = {0};
        glGetShaderInfoLog(sh, sizeof log - 1, NULL, log);
        pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "shader %s does not compile: %s", name, log);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

static GLuint link_program(const char *vs, const char *fs, const char *name, pnpr_error *err)
{
    GLuint v = compile(GL_VERTEX_SHADER, vs, name, err);
    if (!v) return 0;
    GLuint f = compile(GL_FRAGMENT_SHADER, fs, name, err);
    if (!f) { glDeleteShader(v); return 0; }
    GLuint p = glCreateProgram();
    glAttachShader(p, v);
    glAttachShader(p, f);
    glLinkProgram(p);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[400] = {0};
        glGetProgramInfoLog(p, sizeof log - 1, NULL, log);
        pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "program %s does not link: %s", name, log);
        glDeleteProgram(p);
        return 0;
    }
    return p;
}

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

static void make_stroke_textures(uint8_t *out)
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

/* ---- create / destroy ----------------------------------------------------------------------- */

static void release_gl(pnpr_renderer *r)
{
    if (r->prog_splat) glDeleteProgram(r->prog_splat);
    if (r->prog_stroke) glDeleteProgram(r->prog_stroke);
    if (r->prog_composite) glDeleteProgram(r->prog_composite);
    if (r->prog_line) glDeleteProgram(r->prog_line);
    if (r->vbo) glDeleteBuffers(1, &r->vbo);
    if (r->line_vbo) glDeleteBuffers(1, &r->line_vbo);
    GLuint vaos[5] = {r->vao_points, r->vao_strokes, r->vao_empty, r->vao_lines, r->vao_flat};
    glDeleteVertexArrays(5, vaos);
    if (r->stroke_tex) glDeleteTextures(1, &r->stroke_tex);
    if (r->color_tex) glDeleteTextures(1, &r->color_tex);
    if (r->depth_rb) glDeleteRenderbuffers(1, &r->depth_rb);
    if (r->fbo) glDeleteFramebuffers(1, &r->fbo);
}

static void set_attribs(GLuint vao, GLuint vbo, size_t first, int instanced, int flat)
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
    if (instanced) {
        glEnableVertexAttribArray(3);
        glVertexAttribPointer(3, 3, GL_FLOAT, GL_FALSE, stride, PNPR_ATTR_OFFSET(dir));
        for (GLuint a = 0; a < 4; a++) glVertexAttribDivisor(a, 1);
    }
#undef PNPR_ATTR_OFFSET
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
    r->prog_splat = link_program(pnpr_shader_splat_vert, pnpr_shader_splat_frag, "splat", err);
    r->prog_stroke = r->prog_splat ? link_program(pnpr_shader_stroke_vert, pnpr_shader_stroke_frag, "stroke", err) : 0;
    r->prog_composite = r->prog_stroke ? link_program(pnpr_shader_composite_vert, pnpr_shader_composite_frag, "composite", err) : 0;
    r->prog_line = r->prog_composite ? link_program(pnpr_shader_line_vert, pnpr_shader_line_frag, "line", err) : 0;
    if (!r->prog_line) { st = PNPR_ERR_UNSUPPORTED; goto done; }
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
    p = r->prog_line;
    r->ul.view = glGetUniformLocation(p, "u_view");
    r->ul.proj = glGetUniformLocation(p, "u_proj");
    r->ul.viewport = glGetUniformLocation(p, "u_viewport");
    r->ul.width = glGetUniformLocation(p, "u_width");
    r->ul.near_plane = glGetUniformLocation(p, "u_near");
    r->ul.ink = glGetUniformLocation(p, "u_ink");
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
    r->uc_frame = glGetUniformLocation(r->prog_composite, "u_frame");
    r->uc_origin = glGetUniformLocation(r->prog_composite, "u_origin");

    glGenBuffers(1, &r->vbo);
    glGenVertexArrays(1, &r->vao_points);
    glGenVertexArrays(1, &r->vao_strokes);
    glGenVertexArrays(1, &r->vao_empty);
    glGenVertexArrays(1, &r->vao_flat);
    set_attribs(r->vao_points, r->vbo, 0, 0, 0);
    set_attribs(r->vao_strokes, r->vbo, 0, 1, 0);
    set_attribs(r->vao_flat, r->vbo, 0, 0, 1);
    /* line segments: two ends per instance */
    glGenBuffers(1, &r->line_vbo);
    glGenVertexArrays(1, &r->vao_lines);
    glBindVertexArray(r->vao_lines);
    glBindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)(uintptr_t)(3 * sizeof(float)));
    glVertexAttribDivisor(0, 1);
    glVertexAttribDivisor(1, 1);

    uint8_t *tex = malloc((size_t)STROKE_TEX_W * STROKE_TEX_H * STROKE_LAYERS);
    if (!tex) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    make_stroke_textures(tex);
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

    GLfloat range[2] = {1, 1};
    glGetFloatv(GL_POINT_SIZE_RANGE, range);
    r->max_point_size = range[1] >= 1 ? range[1] : 1;
    GLint a = 0, b = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &a);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &b);
    r->max_size = a < b ? a : b;
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
static pnpr_status spacing_radii(const float *xyz, size_t n, uint32_t k, int threads, float *radius)
{
    if (n == 1) { radius[0] = 1; return PNPR_OK; }
    size_t kk = (size_t)k + 1 < n ? (size_t)k + 1 : n; /* + the point itself */
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
        for (size_t j = kk; j-- > 0;)
            if (idx[i * kk + j] != PNPR_INDEX_NONE && isfinite(d2[i * kk + j])) { r = sqrtf(d2[i * kk + j]); break; }
        radius[i] = r;
    }
    /* median of the radii (copy into d2, no longer needed) */
    memcpy(d2, radius, n * sizeof *d2);
    qsort(d2, n, sizeof *d2, cmp_float);
    float med = d2[n / 2];
    if (!(med > 0)) { /* mostly duplicates: the largest distance found, else 1 */
        med = d2[n - 1] > 0 ? d2[n - 1] : 1;
    }
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
 * included (one more segment). Without colours every point is grey 160. */
static pnpr_status segment_means(const pnpr_cloud *cloud, const uint32_t *src, size_t n, uint8_t *r_flat)
{
    label_index *li = malloc(n * sizeof *li);
    if (!li) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t j = 0; j < n; j++) { li[j].label = cloud->label[src[j]]; li[j].j = (uint32_t)j; }
    qsort(li, n, sizeof *li, cmp_label);
    for (size_t a = 0; a < n;) {
        size_t b = a;
        double sum[3] = {0, 0, 0};
        while (b < n && li[b].label == li[a].label) {
            for (int c = 0; c < 3; c++) sum[c] += cloud->rgb ? cloud->rgb[3 * (size_t)src[li[b].j] + c] : 160;
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
    uint32_t k = o.spacing_k ? o.spacing_k : 4;

    const pnpr_property *pc = pnpr_cloud_find_property(cloud, "feature_class");
    const pnpr_property *pd[3] = {pnpr_cloud_find_property(cloud, "feature_dir_x"),
                                  pnpr_cloud_find_property(cloud, "feature_dir_y"),
                                  pnpr_cloud_find_property(cloud, "feature_dir_z")};
    int features = !o.ignore_features && pc && pd[0] && pd[1] && pd[2];

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
        st = spacing_radii(xyz, n, k, o.threads, radius);
        if (st != PNPR_OK) goto done;
    }
    size_t ngroups = features ? GROUP_MAX : 1;
    size_t starts[GROUP_MAX + 2];
    st = pnpr_crq_order(n, group, (uint32_t)ngroups, o.seed, order, starts);
    if (st != PNPR_OK) goto done;
    if (cloud->label && n > 0) {
        st = segment_means(cloud, src, n, flat);
        if (st != PNPR_OK) goto done;
    }
    for (size_t q = 0; q < n; q++) {
        uint32_t j = order[q];
        size_t i = src[j];
        pnpr_vertex *v = verts + q;
        memcpy(v->pos, xyz + 3 * (size_t)j, sizeof v->pos);
        v->radius = radius[j];
        if (cloud->rgb) memcpy(v->rgba, cloud->rgb + 3 * i, 3);
        else v->rgba[0] = v->rgba[1] = v->rgba[2] = 160;
        v->rgba[3] = 255;
        if (cloud->label) memcpy(v->flat, flat + 3 * (size_t)j, 3);
        else memcpy(v->flat, v->rgba, 3);
        v->flat[3] = 255;
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
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * sizeof *verts), n ? verts : NULL, GL_STATIC_DRAW);
    pnpr_gl_state_restore(&saved);

    r->count = n;
    r->group_count = ngroups;
    for (size_t g = 0; g <= ngroups + 1; g++) r->group_start[g] = starts[g];
    r->has_features = features;
    r->has_labels = cloud->label != NULL;
    memcpy(r->origin, cloud->origin, sizeof r->origin);
    if (pnpr_cloud_bounds(cloud, r->bmin, r->bmax) == 0) {
        memset(r->bmin, 0, sizeof r->bmin);
        memset(r->bmax, 0, sizeof r->bmax);
    }
done:
    free(src); free(xyz); free(radius); free(group); free(order); free(verts); free(flat);
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
        if (segs > (size_t)0x7FFFFFFF / 6)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: too many line segments (%zu)", segs);
    }
    float *buf = malloc((segs ? segs : 1) * 6 * sizeof *buf);
    if (!buf) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "renderer: lines: out of memory");
    size_t m = 0;
    for (size_t i = 0; segs && i < lines->count; i++) {
        size_t a = lines->offset[i], b = lines->offset[i + 1];
        if (b - a < 2) continue;
        size_t n = b - a, nseg = (n - 1) + (lines->closed && lines->closed[i] && n >= 3);
        for (size_t k = 0; k < nseg; k++) {
            const float *p = lines->xyz + 3 * (a + k), *q = lines->xyz + 3 * (a + (k + 1) % n);
            if (!finite3(p) || !finite3(q)) continue;
            memcpy(buf + 6 * m, p, 3 * sizeof *p);
            memcpy(buf + 6 * m + 3, q, 3 * sizeof *q);
            m++;
        }
    }
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    glBindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m * 6 * sizeof *buf), m ? buf : NULL, GL_STATIC_DRAW);
    pnpr_gl_state_restore(&saved);
    free(buf);
    r->line_segments = m;
    if (m) memcpy(r->line_origin, lines->origin, sizeof r->line_origin);
    return PNPR_OK;
}

/* ---- draw ----------------------------------------------------------------------------------- */

static pnpr_status ensure_framebuffer(pnpr_renderer *r, int w, int h, pnpr_error *err)
{
    if (r->fbo && r->fb_w == w && r->fb_h == h) return PNPR_OK;
    if (!r->fbo) {
        glGenFramebuffers(1, &r->fbo);
        glGenTextures(1, &r->color_tex);
        glGenRenderbuffers(1, &r->depth_rb);
    }
    glBindTexture(GL_TEXTURE_2D, r->color_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glBindRenderbuffer(GL_RENDERBUFFER, r->depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->color_tex, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->depth_rb);
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

pnpr_status pnpr_renderer_draw(pnpr_renderer *r, const pnpr_camera *camera,
                               const pnpr_draw_options *opts, const pnpr_target *target,
                               pnpr_render_stats *r_stats, pnpr_error *err)
{
    if (!r || !target) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: NULL renderer or target");
    if (r_stats) memset(r_stats, 0, sizeof *r_stats);
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    if (opts) o = *opts;
    int w = target->width, h = target->height;
    if (w <= 0 || h <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: image size %dx%d must be positive", w, h);
    if (w > r->max_size || h > r->max_size)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: image size %dx%d exceeds this GL's limit %d", w, h, (int)r->max_size);
    if ((unsigned)o.style >= PNPR_STYLE_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: unknown style %d", (int)o.style);
    if ((unsigned)o.sketch_variant >= PNPR_SKETCH_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: unknown sketch variant %d", (int)o.sketch_variant);
    if ((unsigned)o.composite >= PNPR_COMPOSITE_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: unknown composite mode %d", (int)o.composite);
    if (o.stroke_texture < 0 || o.stroke_texture > 2)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: stroke texture %d is not 0, 1 or 2", o.stroke_texture);
    if (!finite4(o.background) || !finite4(o.ink) || !isfinite(o.density) || o.density < 0 ||
        !isfinite(o.point_scale) || o.point_scale < 0 || !isfinite(o.mask_scale) || o.mask_scale < 0 ||
        !isfinite(o.stroke_length) || o.stroke_length < 0 || !isfinite(o.stroke_width) || o.stroke_width < 0 ||
        !isfinite(o.line_width) || o.line_width < 0 || !(o.faint >= 0 && o.faint <= 1) ||
        !isfinite(o.dot_size) || o.dot_size < 0 || o.levels < 0 || o.levels == 1 || o.levels > 256)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: draw options must be finite and not negative");
    if (pnpr_style_needs_features(o.style) && r->count > 0 && !r->has_features)
        return pnpr_error_set(err, PNPR_ERR_NOT_FOUND,
                              "renderer: style '%s' needs the feature properties feature_class and feature_dir_x/y/z (pnpr_compute_features)",
                              pnpr_style_name(o.style));
    float point_scale = o.point_scale > 0 ? o.point_scale : 1;
    float mask_scale = o.mask_scale > 0 ? o.mask_scale : o.style == PNPR_STYLE_CARTOON ? 2.0f : 1.5f;
    float stroke_length = o.stroke_length > 0 ? o.stroke_length : 6;
    float stroke_width = o.stroke_width > 0 ? o.stroke_width : 2;
    float line_width = o.line_width > 0 ? o.line_width : 2;
    float dot_size = o.dot_size > 0 ? o.dot_size : 2.5f;
    float ink[4] = {0.08f, 0.08f, 0.1f, 1};
    if (o.ink[0] != 0 || o.ink[1] != 0 || o.ink[2] != 0 || o.ink[3] != 0) memcpy(ink, o.ink, sizeof ink);

    pnpr_camera cam;
    if (camera) cam = *camera;
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
    pnpr_frame_camera fc;
    pnpr_status st = pnpr_frame_camera_make(&cam, r->origin, r->bmin, r->bmax, r->count > 0, w, h, &fc, err);
    if (st != PNPR_OK) return st;

    /* continuous resolution queue: how many points this frame */
    size_t n_draw = r->count;
    double coverage = r->count ? pnpr_box_coverage(&fc, r->bmin, r->bmax, w, h) : 0;
    if (o.budget > 0 && o.budget < n_draw) n_draw = o.budget;
    if (o.density > 0) {
        double cap = ceil((double)o.density * coverage);
        if (cap < (double)n_draw) n_draw = (size_t)cap;
    }
    size_t gsize[GROUP_MAX + 1], gdraw[GROUP_MAX + 1];
    size_t ng = r->group_count + 1; /* + "other" (empty by construction) */
    for (size_t g = 0; g < ng; g++) gsize[g] = r->group_start[g + 1] - r->group_start[g];
    pnpr_crq_split(gsize, ng, n_draw, gdraw);
    /* a random subset of fraction f has 1/sqrt(f) times the spacing: grow the disks to match */
    float lod = n_draw > 0 ? (float)sqrt((double)r->count / (double)n_draw) : 1;

    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    pnpr_gl_state_neutral();
    st = ensure_framebuffer(r, w, h, err);
    if (st != PNPR_OK) { pnpr_gl_state_restore(&saved); return st; }
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glViewport(0, 0, w, h);
    float a = o.background[3];
    glClearColor(o.background[0] * a, o.background[1] * a, o.background[2] * a, a); /* premultiplied */
    glClearDepth(1.0);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);

    size_t strokes = 0;
    int sketchy = o.style == PNPR_STYLE_SKETCHY, lines = o.style == PNPR_STYLE_LINES;
    int stipple = o.style == PNPR_STYLE_STIPPLE, cartoon = o.style == PNPR_STYLE_CARTOON;
    int masked = sketchy || lines || stipple; /* pass 1 is a depth-only visibility mask */
    if (n_draw > 0) {
        glUseProgram(r->prog_splat);
        glUniformMatrix4fv(r->us.view, 1, GL_FALSE, fc.view);
        glUniformMatrix4fv(r->us.proj, 1, GL_FALSE, fc.proj);
        glUniform1f(r->us.ppu, fc.pixels_per_unit);
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
        /* pass 1 (mask) / the only pass (points): round disks of the prefixes. Cartoon: the
         * enlarged disks go into depth AND colour, in the outline colour */
        glUniform1f(r->us.radius_scale, point_scale * lod * (masked || cartoon ? mask_scale : 1));
        glUniform1f(r->us.depth_push, masked || cartoon ? 1.0f : 0.0f);
        if (masked) glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        if (cartoon) {
            glUniform1f(r->us.fade, 1.0f);
            glUniform4f(r->us.fade_color, ink[0], ink[1], ink[2], 1.0f);
        }
        for (size_t g = 0; g < ng; g++)
            if (gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        if (cartoon) {
            /* pass 2: the same points as regular-size opaque splats in flat colours, depth-tested
             * against the enlarged disks, no depth writes, the frame not cleared: the outline
             * colour stays where no splat covers an enlarged disk (silhouettes) */
            glDepthMask(GL_FALSE);
            glUniform1f(r->us.fade, 0.0f);
            glUniform1f(r->us.radius_scale, point_scale * lod);
            glUniform1f(r->us.depth_push, 0.0f);
            glUniform1f(r->us.levels, r->has_labels ? 0.0f : (float)(o.levels ? o.levels : 4));
            glBindVertexArray(r->vao_flat);
            for (size_t g = 0; g < ng; g++)
                if (gdraw[g]) glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
            glUniform1f(r->us.levels, 0.0f);
        }

        if (sketchy) {
            /* pass 2: strokes, depth-tested against the mask, no depth writes, blended */
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glDepthMask(GL_FALSE);
            glEnable(GL_BLEND);
            glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
            glUseProgram(r->prog_stroke);
            glUniformMatrix4fv(r->ut.view, 1, GL_FALSE, fc.view);
            glUniformMatrix4fv(r->ut.proj, 1, GL_FALSE, fc.proj);
            glUniform2f(r->ut.viewport, (float)w, (float)h);
            glUniform1f(r->ut.ppu, fc.pixels_per_unit);
            glUniform1f(r->ut.width, stroke_width);
            glUniform1f(r->ut.radius_scale, point_scale);
            glUniform1i(r->ut.strokes, 0);
            glUniform4fv(r->ut.ink, 1, ink);
            glUniform1i(r->ut.ink_from_points, o.ink_from_points != 0);
            glBindTexture(GL_TEXTURE_2D_ARRAY, r->stroke_tex);
            int draw_group[3] = {1, o.sketch_variant != PNPR_SKETCH_DIRECTIONAL,
                                 o.sketch_variant == PNPR_SKETCH_ALL};
            for (int g = GROUP_DIRECTIONAL; g <= GROUP_DITHER; g++) {
                if (!draw_group[g] || !gdraw[g]) continue;
                int directional = g == GROUP_DIRECTIONAL;
                glUniform1i(r->ut.mode, directional ? 0 : 1);
                glUniform1f(r->ut.layer, directional ? (float)o.stroke_texture : (float)STROKE_LAYER_HATCH);
                glUniform1f(r->ut.length, directional ? stroke_length : 0.5f * stroke_length);
                set_attribs(r->vao_strokes, r->vbo, r->group_start[g], 1, 0);
                glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)gdraw[g]);
                strokes += gdraw[g];
            }
        }
    }
    if (stipple && n_draw > 0) {
        /* pass 2 of `stipple`: the queue prefixes of the feature and dithering groups as dots of
         * a fixed screen size in the ink colour (antialiased edges), depth-tested against the
         * mask, no depth writes, blended */
        glDepthMask(GL_FALSE);
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        glUniform1f(r->us.radius_scale, point_scale * lod);
        glUniform1f(r->us.depth_push, 0.0f);
        glUniform1f(r->us.fade, 1.0f);
        glUniform4fv(r->us.fade_color, 1, ink);
        glUniform1f(r->us.fixed_size, dot_size);
        for (int g = GROUP_DIRECTIONAL; g <= GROUP_DITHER; g++) {
            if (!gdraw[g]) continue;
            glDrawArrays(GL_POINTS, (GLint)r->group_start[g], (GLsizei)gdraw[g]);
            strokes += gdraw[g];
        }
    }
    if (lines && r->line_segments > 0) {
        /* pass 2 of `lines`: the segments, depth-tested against the mask (no mask when the
         * cloud is empty: nothing hides them), no depth writes, blended */
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_FALSE);
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        /* the lines' offsets are relative to their own origin: view * translate(line - cloud origin) */
        double d[3] = {r->line_origin[0] - r->origin[0], r->line_origin[1] - r->origin[1],
                       r->line_origin[2] - r->origin[2]};
        float lview[16];
        memcpy(lview, fc.view, sizeof lview);
        for (int row = 0; row < 4; row++)
            lview[12 + row] = (float)((double)fc.view[row] * d[0] + (double)fc.view[4 + row] * d[1] +
                                      (double)fc.view[8 + row] * d[2] + (double)fc.view[12 + row]);
        glUseProgram(r->prog_line);
        glUniformMatrix4fv(r->ul.view, 1, GL_FALSE, lview);
        glUniformMatrix4fv(r->ul.proj, 1, GL_FALSE, fc.proj);
        glUniform2f(r->ul.viewport, (float)w, (float)h);
        glUniform1f(r->ul.width, line_width);
        glUniform1f(r->ul.near_plane, (float)fc.near_plane);
        glUniform4fv(r->ul.ink, 1, ink);
        glBindVertexArray(r->vao_lines);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)r->line_segments);
        strokes = r->line_segments;
    }

    if (!target->offscreen) {
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
    /* GL's rows go bottom-up: flip in place */
    size_t row = (size_t)w * 4;
    for (int y = 0; y < h / 2; y++) {
        uint8_t *p = rgba + (size_t)y * row, *q = rgba + (size_t)(h - 1 - y) * row;
        for (size_t i = 0; i < row; i++) { uint8_t t = p[i]; p[i] = q[i]; q[i] = t; }
    }
    if (unpremultiply) {
        for (size_t i = 0; i < (size_t)w * h; i++) {
            uint8_t *p = rgba + 4 * i;
            if (p[3] == 0 || p[3] == 255) continue;
            for (int c = 0; c < 3; c++) {
                unsigned v = (p[c] * 255u + p[3] / 2u) / p[3];
                p[c] = (uint8_t)(v > 255 ? 255 : v);
            }
        }
    }
    return PNPR_OK;
}

void pnpr_renderer_frame_size(const pnpr_renderer *r, int *w, int *h)
{
    if (w) *w = r ? r->fb_w : 0;
    if (h) *h = r ? r->fb_h : 0;
}

/* ---- styles --------------------------------------------------------------------------------- */

static const char *const style_names[PNPR_STYLE_COUNT_] = {"points", "sketchy", "lines", "stipple", "cartoon"};

const char *pnpr_style_name(pnpr_style s)
{
    return (unsigned)s < PNPR_STYLE_COUNT_ ? style_names[s] : "";
}

pnpr_status pnpr_style_from_name(const char *name, pnpr_style *r_style)
{
    if (!name || !r_style) return PNPR_ERR_INVALID_ARGUMENT;
    for (int i = 0; i < PNPR_STYLE_COUNT_; i++)
        if (!strcmp(name, style_names[i])) { *r_style = (pnpr_style)i; return PNPR_OK; }
    return PNPR_ERR_NOT_FOUND;
}

int pnpr_style_needs_features(pnpr_style s) { return s == PNPR_STYLE_SKETCHY || s == PNPR_STYLE_STIPPLE; }
