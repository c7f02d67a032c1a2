/* Stroke-based splatting's GL side (brush_gl.h; Lopes et al. section 3.3; docs/brush.md). */
#include "renderer_internal.h"
#include "gl_state.h"
#include "pnpr_shaders.h"

#include <pointnpr/brush.h>

#include <stdint.h>
#include <stdlib.h>

enum { BRUSH_TEX_SIZE = 64 };

pnpr_status pnpr_brush_gl_create(pnpr_brush_gl *b, pnpr_error *err)
{
    b->preset = -1;
    b->prog = pnpr_gl_link_program(pnpr_shader_brush_vert, pnpr_shader_brush_frag, "brush", err);
    b->prog_resolve = b->prog ? pnpr_gl_link_program(pnpr_shader_composite_vert, pnpr_shader_brush_resolve_frag,
                                                     "brush_resolve", err)
                              : 0;
    b->prog_blur = b->prog_resolve ? pnpr_gl_link_program(pnpr_shader_composite_vert, pnpr_shader_brush_blur_frag,
                                                          "brush_blur", err)
                                   : 0;
    if (!b->prog_blur) return PNPR_ERR_UNSUPPORTED;
    b->ub_src = glGetUniformLocation(b->prog_blur, "u_src");
    b->ub_dir = glGetUniformLocation(b->prog_blur, "u_dir");
    b->ub_sigma = glGetUniformLocation(b->prog_blur, "u_sigma");
    GLuint p = b->prog;
    b->u_view = glGetUniformLocation(p, "u_view");
    b->u_proj = glGetUniformLocation(p, "u_proj");
    b->u_scale = glGetUniformLocation(p, "u_scale");
    b->u_jitter = glGetUniformLocation(p, "u_jitter");
    b->u_layer = glGetUniformLocation(p, "u_layer");
    b->u_filter = glGetUniformLocation(p, "u_style_filter");
    b->u_brush = glGetUniformLocation(p, "u_brush");
    b->u_oit = glGetUniformLocation(p, "u_oit");
    b->u_weight = glGetUniformLocation(p, "u_weight");
    pnpr_queue_uniforms_find(p, &b->uq);
    b->ur_accum = glGetUniformLocation(b->prog_resolve, "u_accum");
    b->ur_optical = glGetUniformLocation(b->prog_resolve, "u_optical");
    glGenVertexArrays(1, &b->vao);
    glGenVertexArrays(1, &b->vao_empty);
    glGenBuffers(1, &b->vbo);
    glGenTextures(1, &b->tex);
    return PNPR_OK;
}

void pnpr_brush_gl_release(pnpr_brush_gl *b)
{
    if (b->prog) glDeleteProgram(b->prog);
    if (b->prog_resolve) glDeleteProgram(b->prog_resolve);
    if (b->prog_blur) glDeleteProgram(b->prog_blur);
    if (b->blur_fbo) glDeleteFramebuffers(1, &b->blur_fbo);
    if (b->blur_tex) glDeleteTextures(1, &b->blur_tex);
    GLuint vaos[2] = {b->vao, b->vao_empty}, texs[3] = {b->tex, b->accum_tex, b->optical_tex};
    glDeleteVertexArrays(2, vaos);
    glDeleteTextures(3, texs);
    if (b->vbo) glDeleteBuffers(1, &b->vbo);
    if (b->fbo) glDeleteFramebuffers(1, &b->fbo);
}

void pnpr_brush_gl_upload(pnpr_brush_gl *b, const pnpr_brush_vertex *v, size_t n)
{
    glBindBuffer(GL_ARRAY_BUFFER, b->vbo);
    glBufferData(GL_ARRAY_BUFFER, v ? (GLsizeiptr)(n * sizeof *v) : 0, v, GL_STATIC_DRAW);
    b->ready = v != NULL;
}

/* The PNPR_BRUSH_VARIANTS textures of preset `preset` into the array texture. */
static pnpr_status brush_textures(pnpr_brush_gl *b, int preset, pnpr_error *err)
{
    size_t np;
    const pnpr_brush_preset *ps = pnpr_brush_presets(&np);
    if (preset < 0 || (size_t)preset >= np)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: brush preset %d is not in 0..%zu", preset, np - 1);
    if (b->preset == preset) return PNPR_OK;
    const size_t layer = (size_t)BRUSH_TEX_SIZE * BRUSH_TEX_SIZE;
    uint8_t *a = malloc(layer * PNPR_BRUSH_VARIANTS);
    if (!a) return PNPR_ERR_OUT_OF_MEMORY;
    for (uint32_t v = 0; v < PNPR_BRUSH_VARIANTS; v++)
        if (pnpr_brush_texture(&ps[preset].shape, v, BRUSH_TEX_SIZE, BRUSH_TEX_SIZE, a + v * layer) != PNPR_OK) {
            free(a);
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: brush preset %s is invalid", ps[preset].name);
        }
    glBindTexture(GL_TEXTURE_2D_ARRAY, b->tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R8, BRUSH_TEX_SIZE, BRUSH_TEX_SIZE, PNPR_BRUSH_VARIANTS, 0, GL_RED,
                 GL_UNSIGNED_BYTE, a);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
    free(a);
    b->preset = preset;
    return PNPR_OK;
}

static void target_texture(GLuint tex, GLint format, GLenum channels, int w, int h)
{
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, format, w, h, 0, channels, GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
}

pnpr_status pnpr_brush_gl_targets(pnpr_brush_gl *b, int w, int h, GLuint depth_rb, pnpr_error *err)
{
    if (!b->fbo) {
        glGenFramebuffers(1, &b->fbo);
        glGenTextures(1, &b->accum_tex);
        glGenTextures(1, &b->optical_tex);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, b->fbo);
    if (b->w != w || b->h != h) {
        target_texture(b->accum_tex, GL_RGBA32F, GL_RGBA, w, h);
        target_texture(b->optical_tex, GL_R32F, GL_RED, w, h);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, b->accum_tex, 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, b->optical_tex, 0);
        b->w = w;
        b->h = h;
    }
    /* the frame's depth buffer may have been reallocated: attach it every time */
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
    pnpr_renderer_draw_buffers(1, 1);
    GLenum fs = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (fs != GL_FRAMEBUFFER_COMPLETE) {
        b->w = b->h = 0;
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "renderer: brush targets %dx%d incomplete (0x%x)", w, h,
                              (unsigned)fs);
    }
    return PNPR_OK;
}

pnpr_status pnpr_brush_gl_prepare(pnpr_brush_gl *b, int preset, int w, int h, GLuint depth_rb, pnpr_error *err)
{
    pnpr_status st = brush_textures(b, preset, err);
    return st == PNPR_OK ? pnpr_brush_gl_targets(b, w, h, depth_rb, err) : st;
}

/* The strokes of one layer, group by group (attributes re-pointed at each group's start). */
static size_t draw_layer(pnpr_brush_gl *b, const pnpr_brush_pass *p, int layer)
{
    size_t n = 0;
    glUniform1i(b->u_layer, layer);
    for (size_t g = 0; g < p->groups; g++) {
        if (!p->count[g]) continue;
        pnpr_renderer_vertex_attribs(b->vao, p->main_vbo, p->style_vbo, p->key_vbo, p->first[g], 1, 0);
        glBindBuffer(GL_ARRAY_BUFFER, b->vbo);
        glEnableVertexAttribArray(6);
        glVertexAttribPointer(6, 3, GL_FLOAT, GL_FALSE, sizeof(pnpr_brush_vertex),
                              (const void *)(uintptr_t)(p->first[g] * sizeof(pnpr_brush_vertex)));
        glVertexAttribDivisor(6, 1);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)p->count[g]);
        n += p->count[g];
    }
    return n;
}

void pnpr_brush_gl_oit_begin(pnpr_brush_gl *b, int stencil)
{
    glBindFramebuffer(GL_FRAMEBUFFER, b->fbo);
    pnpr_renderer_draw_buffers(1, 1);
    const float zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfv(GL_COLOR, 1, zero);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    if (stencil > 0) {
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        glStencilFunc(GL_EQUAL, stencil, 0xFF);
    } else {
        glDisable(GL_STENCIL_TEST);
    }
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
}

void pnpr_brush_gl_oit_resolve(pnpr_brush_gl *b, GLuint frame_fbo)
{
    glBindFramebuffer(GL_FRAMEBUFFER, frame_fbo);
    pnpr_renderer_draw_buffers(0, 1);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(b->prog_resolve);
    glUniform1i(b->ur_accum, 0);
    glUniform1i(b->ur_optical, 1);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, b->accum_tex);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, b->optical_tex);
    glBindVertexArray(b->vao_empty);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glActiveTexture(GL_TEXTURE0);
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_DEPTH_TEST);
}

/* The blur's intermediate target at the frame's size (no depth). */
static int blur_target(pnpr_brush_gl *b)
{
    if (!b->blur_fbo) {
        glGenFramebuffers(1, &b->blur_fbo);
        glGenTextures(1, &b->blur_tex);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, b->blur_fbo);
    if (b->blur_w != b->w || b->blur_h != b->h) {
        target_texture(b->blur_tex, GL_RGBA16F, GL_RGBA, b->w, b->h);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, b->blur_tex, 0);
        b->blur_w = b->w;
        b->blur_h = b->h;
    }
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

static void blur_pass(pnpr_brush_gl *b, GLuint src, float dx, float dy, float sigma)
{
    glUseProgram(b->prog_blur);
    glUniform1i(b->ub_src, 0);
    glUniform2f(b->ub_dir, dx, dy);
    glUniform1f(b->ub_sigma, sigma);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, src);
    glBindVertexArray(b->vao_empty);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

/* The fast blend while moving (the paper's), after pnpr_brush_gl_oit_begin (the cleared targets
 * bound, depth and stencil tests set): the strokes alpha-blended in draw order into the
 * accumulation target, blurred horizontally into the intermediate, then vertically over the
 * frame. pnpr_brush_gl_draw falls back to the order-independent blend when the intermediate
 * cannot be made. */
static size_t draw_blurred(pnpr_brush_gl *b, const pnpr_brush_pass *p)
{
    pnpr_renderer_draw_buffers(0, 1);
    glUniform1i(b->u_oit, 0);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    size_t strokes = draw_layer(b, p, 0);
    draw_layer(b, p, 1);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    glBindFramebuffer(GL_FRAMEBUFFER, b->blur_fbo);
    blur_pass(b, b->accum_tex, 1, 0, p->blur);
    glBindFramebuffer(GL_FRAMEBUFFER, p->frame_fbo);
    pnpr_renderer_draw_buffers(0, 1);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    blur_pass(b, b->blur_tex, 0, 1, p->blur);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    return strokes;
}

size_t pnpr_brush_gl_draw(pnpr_brush_gl *b, const pnpr_brush_pass *p)
{
    int blur = p->blur > 0 && blur_target(b);
    pnpr_brush_gl_oit_begin(b, p->stencil);
    glUseProgram(b->prog);
    glUniformMatrix4fv(b->u_view, 1, GL_FALSE, p->view);
    glUniformMatrix4fv(b->u_proj, 1, GL_FALSE, p->proj);
    glUniform1f(b->u_scale, p->scale);
    glUniform1f(b->u_jitter, p->jitter_deg * 3.14159265f / 180.0f);
    glUniform1i(b->u_filter, p->filter);
    glUniform1i(b->u_oit, 1);
    glUniform1f(b->u_weight, PNPR_OIT_WEIGHT);
    glUniform1i(b->u_brush, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, b->tex);
    if (blur) return draw_blurred(b, p);
    size_t strokes = draw_layer(b, p, 0);
    draw_layer(b, p, 1);
    pnpr_brush_gl_oit_resolve(b, p->frame_fbo);
    return strokes;
}
