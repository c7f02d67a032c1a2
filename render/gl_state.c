#include "gl_state.h"

#include <pointnpr/core.h>

#include <stddef.h>
#include <string.h>

const GLenum pnpr_gl_state_enables[PNPR_GL_STATE_ENABLES] = {
    GL_SCISSOR_TEST, GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_STENCIL_TEST,
    GL_PROGRAM_POINT_SIZE, GL_FRAMEBUFFER_SRGB, GL_POLYGON_OFFSET_FILL,
    GL_SAMPLE_ALPHA_TO_COVERAGE, GL_SAMPLE_COVERAGE, GL_COLOR_LOGIC_OP, GL_DEPTH_CLAMP,
    GL_RASTERIZER_DISCARD, GL_MULTISAMPLE};

void pnpr_gl_state_save(pnpr_gl_state *s)
{
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
    glGetIntegerv(GL_RENDERBUFFER_BINDING, &s->renderbuffer);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    for (int i = 0; i < PNPR_GL_STATE_ENABLES; i++) s->enabled[i] = glIsEnabled(pnpr_gl_state_enables[i]);
    glGetIntegerv(GL_DEPTH_FUNC, &s->depth_func);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    glGetBooleanv(GL_COLOR_WRITEMASK, s->color_mask);
    glGetIntegerv(GL_BLEND_SRC_RGB, &s->blend_src_rgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &s->blend_dst_rgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &s->blend_src_alpha);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &s->blend_dst_alpha);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &s->blend_eq_rgb);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &s->blend_eq_alpha);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, s->clear_color);
    glGetFloatv(GL_DEPTH_CLEAR_VALUE, &s->clear_depth);
    GLint pm[4] = {GL_FILL, GL_FILL, GL_FILL, GL_FILL};
    glGetIntegerv(GL_POLYGON_MODE, pm);
    s->polygon_mode[0] = pm[0];
    s->polygon_mode[1] = pm[1];
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &s->array_buffer);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active_texture);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &s->tex_2d);
    glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &s->tex_2d_array);
    glGetIntegerv(GL_SAMPLER_BINDING, &s->sampler);
    glActiveTexture(GL_TEXTURE1);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &s->tex_2d_unit1);
    glGetIntegerv(GL_SAMPLER_BINDING, &s->sampler_unit1);
    glActiveTexture(GL_TEXTURE0 + PNPR_GL_CELLS_UNIT);
    glGetIntegerv(GL_TEXTURE_BINDING_BUFFER, &s->tex_buffer_cells);
    glGetIntegerv(GL_SAMPLER_BINDING, &s->sampler_cells);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_PACK_ALIGNMENT, &s->pack[0]);
    glGetIntegerv(GL_PACK_ROW_LENGTH, &s->pack[1]);
    glGetIntegerv(GL_PACK_SKIP_PIXELS, &s->pack[2]);
    glGetIntegerv(GL_PACK_SKIP_ROWS, &s->pack[3]);
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &s->pack[4]);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &s->unpack[0]);
    glGetIntegerv(GL_UNPACK_ROW_LENGTH, &s->unpack[1]);
    glGetIntegerv(GL_UNPACK_SKIP_PIXELS, &s->unpack[2]);
    glGetIntegerv(GL_UNPACK_SKIP_ROWS, &s->unpack[3]);
    glGetIntegerv(GL_UNPACK_SKIP_IMAGES, &s->unpack[4]);
    glGetIntegerv(GL_UNPACK_IMAGE_HEIGHT, &s->unpack[5]);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &s->unpack[6]);
    static const GLenum st[2][7] = {
        {GL_STENCIL_FUNC, GL_STENCIL_REF, GL_STENCIL_VALUE_MASK, GL_STENCIL_FAIL, GL_STENCIL_PASS_DEPTH_FAIL,
         GL_STENCIL_PASS_DEPTH_PASS, GL_STENCIL_WRITEMASK},
        {GL_STENCIL_BACK_FUNC, GL_STENCIL_BACK_REF, GL_STENCIL_BACK_VALUE_MASK, GL_STENCIL_BACK_FAIL,
         GL_STENCIL_BACK_PASS_DEPTH_FAIL, GL_STENCIL_BACK_PASS_DEPTH_PASS, GL_STENCIL_BACK_WRITEMASK}};
    for (int f = 0; f < 2; f++)
        for (int i = 0; i < 7; i++) glGetIntegerv(st[f][i], &s->stencil[f][i]);
    glGetIntegerv(GL_STENCIL_CLEAR_VALUE, &s->stencil_clear);
    glActiveTexture((GLenum)s->active_texture);
}

void pnpr_gl_state_neutral(void)
{
    for (int i = 0; i < PNPR_GL_STATE_ENABLES; i++) {
        GLenum cap = pnpr_gl_state_enables[i];
        if (cap == GL_PROGRAM_POINT_SIZE) glEnable(cap);
        else glDisable(cap);
    }
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBlendEquation(GL_FUNC_ADD);
    glActiveTexture(GL_TEXTURE0);
    glBindSampler(0, 0);
    glBindSampler(1, 0);
    glBindSampler(PNPR_GL_CELLS_UNIT, 0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_SKIP_IMAGES, 0);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glStencilMask(0xFF);
    glClearStencil(0);
}

void pnpr_gl_state_restore(const pnpr_gl_state *s)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fbo);
    glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)s->renderbuffer);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    for (int i = 0; i < PNPR_GL_STATE_ENABLES; i++) {
        if (s->enabled[i]) glEnable(pnpr_gl_state_enables[i]);
        else glDisable(pnpr_gl_state_enables[i]);
    }
    glDepthFunc((GLenum)s->depth_func);
    glDepthMask(s->depth_mask);
    glColorMask(s->color_mask[0], s->color_mask[1], s->color_mask[2], s->color_mask[3]);
    glBlendFuncSeparate((GLenum)s->blend_src_rgb, (GLenum)s->blend_dst_rgb,
                        (GLenum)s->blend_src_alpha, (GLenum)s->blend_dst_alpha);
    glBlendEquationSeparate((GLenum)s->blend_eq_rgb, (GLenum)s->blend_eq_alpha);
    glClearColor(s->clear_color[0], s->clear_color[1], s->clear_color[2], s->clear_color[3]);
    glClearDepth(s->clear_depth);
    /* core profiles have one polygon mode for both faces */
    glPolygonMode(GL_FRONT_AND_BACK, (GLenum)s->polygon_mode[0]);
    glUseProgram((GLuint)s->program);
    glBindVertexArray((GLuint)s->vao);
    glBindBuffer(GL_ARRAY_BUFFER, (GLuint)s->array_buffer);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, (GLuint)s->tex_2d);
    glBindTexture(GL_TEXTURE_2D_ARRAY, (GLuint)s->tex_2d_array);
    glBindSampler(0, (GLuint)s->sampler);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, (GLuint)s->tex_2d_unit1);
    glBindSampler(1, (GLuint)s->sampler_unit1);
    glActiveTexture(GL_TEXTURE0 + PNPR_GL_CELLS_UNIT);
    glBindTexture(GL_TEXTURE_BUFFER, (GLuint)s->tex_buffer_cells);
    glBindSampler(PNPR_GL_CELLS_UNIT, (GLuint)s->sampler_cells);
    glActiveTexture((GLenum)s->active_texture);
    glPixelStorei(GL_PACK_ALIGNMENT, s->pack[0]);
    glPixelStorei(GL_PACK_ROW_LENGTH, s->pack[1]);
    glPixelStorei(GL_PACK_SKIP_PIXELS, s->pack[2]);
    glPixelStorei(GL_PACK_SKIP_ROWS, s->pack[3]);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, (GLuint)s->pack[4]);
    glPixelStorei(GL_UNPACK_ALIGNMENT, s->unpack[0]);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, s->unpack[1]);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, s->unpack[2]);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, s->unpack[3]);
    glPixelStorei(GL_UNPACK_SKIP_IMAGES, s->unpack[4]);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, s->unpack[5]);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, (GLuint)s->unpack[6]);
    for (int f = 0; f < 2; f++) {
        GLenum face = f ? GL_BACK : GL_FRONT;
        const GLint *v = s->stencil[f];
        glStencilFuncSeparate(face, (GLenum)v[0], v[1], (GLuint)v[2]);
        glStencilOpSeparate(face, (GLenum)v[3], (GLenum)v[4], (GLenum)v[5]);
        glStencilMaskSeparate(face, (GLuint)v[6]);
    }
    glClearStencil(s->stencil_clear);
}

/* ---- shader programs ---- */

void pnpr_queue_uniforms_find(GLuint prog, pnpr_queue_uniforms *u)
{
    u->cells = glGetUniformLocation(prog, "u_cells");
    u->min = glGetUniformLocation(prog, "u_cell_min");
    u->inv = glGetUniformLocation(prog, "u_cell_inv");
    u->n = glGetUniformLocation(prog, "u_cell_n");
    u->scale = glGetUniformLocation(prog, "u_queue_scale");
}

static GLuint compile(GLenum type, const char *src, const char *name, pnpr_error *err)
{
    /* the #version line, then the constants the C side defines (pnpr_shader_prelude), then the rest */
    char prelude[PNPR_SHADER_PRELUDE_MAX];
    pnpr_shader_prelude(prelude, sizeof prelude);
    const char *nl = strchr(src, '\n');
    const char *parts[3] = {src, prelude, nl ? nl + 1 : ""};
    GLint lens[3] = {nl ? (GLint)(nl + 1 - src) : (GLint)strlen(src), -1, -1};
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, 3, parts, lens);
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

GLuint pnpr_gl_link_program(const char *vs, const char *fs, const char *name, pnpr_error *err)
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

void pnpr_gl_find_uniforms(GLuint prog, const pnpr_gl_uniform *table, size_t count, void *locations)
{
    for (size_t i = 0; i < count; i++)
        *(GLint *)((char *)locations + table[i].offset) = glGetUniformLocation(prog, table[i].name);
}
