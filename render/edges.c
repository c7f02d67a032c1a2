/* Outlines in image space: silhouettes and occluding contours from the visibility mask (see
 * edges.h and docs/rendering.md). Fullscreen passes: hole closing, then a minimum filter with the
 * distance to no surface, into textures of their own; then the mask disks' overhang beyond the
 * silhouettes erased and the ink band drawn on the near side of every depth discontinuity. */
#include "edges.h"
#include "gl_state.h"
#include "pnpr_shaders.h"

#include <stddef.h>

static void edge_uniforms(pnpr_edges *e)
{
    e->uf_info = glGetUniformLocation(e->prog_fill, "u_info");
    e->uf_reach = glGetUniformLocation(e->prog_fill, "u_reach");
    e->uf_jump = glGetUniformLocation(e->prog_fill, "u_jump");
    e->uf_hole = glGetUniformLocation(e->prog_fill, "u_hole");
    e->uf_ppu = glGetUniformLocation(e->prog_fill, "u_ppu");
    e->uf_ortho = glGetUniformLocation(e->prog_fill, "u_ortho");
    e->uf_surface_reach = glGetUniformLocation(e->prog_fill, "u_surface_reach");
    e->uf_skip_level = glGetUniformLocation(e->prog_fill, "u_skip_level");
    e->ue_skip_level = glGetUniformLocation(e->prog_erode, "u_skip_level");
    e->ue_filled = glGetUniformLocation(e->prog_erode, "u_filled");
    e->ue_ppu = glGetUniformLocation(e->prog_erode, "u_ppu");
    e->ue_ortho = glGetUniformLocation(e->prog_erode, "u_ortho");
    e->ue_inset = glGetUniformLocation(e->prog_erode, "u_inset");
    e->ue_inset_max = glGetUniformLocation(e->prog_erode, "u_inset_max");
    e->ue_limit = glGetUniformLocation(e->prog_erode, "u_limit");
    e->ue_width = glGetUniformLocation(e->prog_erode, "u_width");
    e->ui_filled = glGetUniformLocation(e->prog_ink, "u_filled");
    e->ui_eroded = glGetUniformLocation(e->prog_ink, "u_eroded");
    e->ui_width = glGetUniformLocation(e->prog_ink, "u_width");
    e->ui_jump = glGetUniformLocation(e->prog_ink, "u_jump");
    e->ui_ink = glGetUniformLocation(e->prog_ink, "u_ink");
    e->uc_src = glGetUniformLocation(e->prog_cover, "u_src");
    e->uc_block = glGetUniformLocation(e->prog_cover, "u_block");
    e->uf_cover = glGetUniformLocation(e->prog_fill, "u_cover");
    e->ue_cover = glGetUniformLocation(e->prog_erode, "u_cover");
    e->ui_erase = glGetUniformLocation(e->prog_ink, "u_erase");
    e->ui_background = glGetUniformLocation(e->prog_ink, "u_background");
}

pnpr_status pnpr_edges_create(pnpr_edges *e, pnpr_error *err)
{
    const char *vs = pnpr_shader_composite_vert;
    e->prog_fill = pnpr_gl_link_program(vs, pnpr_shader_edge_fill_frag, "edge_fill", err);
    e->prog_erode = e->prog_fill ? pnpr_gl_link_program(vs, pnpr_shader_edge_erode_frag, "edge_erode", err) : 0;
    e->prog_ink = e->prog_erode ? pnpr_gl_link_program(vs, pnpr_shader_edge_ink_frag, "edge_ink", err) : 0;
    e->prog_cover = e->prog_ink ? pnpr_gl_link_program(vs, pnpr_shader_edge_cover_frag, "edge_cover", err) : 0;
    if (!e->prog_cover) return PNPR_ERR_UNSUPPORTED;
    edge_uniforms(e);
    glGenVertexArrays(1, &e->vao);
    return PNPR_OK;
}

void pnpr_edges_release(pnpr_edges *e)
{
    if (e->prog_fill) glDeleteProgram(e->prog_fill);
    if (e->prog_erode) glDeleteProgram(e->prog_erode);
    if (e->prog_ink) glDeleteProgram(e->prog_ink);
    if (e->prog_cover) glDeleteProgram(e->prog_cover);
    if (e->cover_tex[0]) glDeleteTextures(2, e->cover_tex);
    if (e->cover_fbo[0]) glDeleteFramebuffers(2, e->cover_fbo);
    e->prog_cover = e->cover_tex[0] = e->cover_tex[1] = e->cover_fbo[0] = e->cover_fbo[1] = 0;
    if (e->vao) glDeleteVertexArrays(1, &e->vao);
    if (e->tex[0]) glDeleteTextures(2, e->tex);
    if (e->fbo[0]) glDeleteFramebuffers(2, e->fbo);
    e->prog_fill = e->prog_erode = e->prog_ink = e->vao = 0;
    e->tex[0] = e->tex[1] = e->fbo[0] = e->fbo[1] = 0;
}

static pnpr_status ensure_targets(pnpr_edges *e, int w, int h, pnpr_error *err)
{
    if (e->fbo[0] && e->w == w && e->h == h) return PNPR_OK;
    if (!e->fbo[0]) {
        glGenFramebuffers(2, e->fbo);
        glGenTextures(2, e->tex);
    }
    for (int i = 0; i < 2; i++) {
        glBindTexture(GL_TEXTURE_2D, e->tex[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, e->fbo[i]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, e->tex[i], 0);
        GLenum fs = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (fs != GL_FRAMEBUFFER_COMPLETE) {
            e->w = e->h = 0;
            return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "renderer: outline buffer %dx%d incomplete (0x%x)", w, h, (unsigned)fs);
        }
    }
    if (!e->cover_fbo[0]) {
        glGenFramebuffers(2, e->cover_fbo);
        glGenTextures(2, e->cover_tex);
    }
    for (int i = 0; i < 2; i++) {
        int shift = i == 0 ? PNPR_EDGE_SKIP_FILL : PNPR_EDGE_SKIP_ERODE;
        glBindTexture(GL_TEXTURE_2D, e->cover_tex[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RG8, (w + (1 << shift) - 1) >> shift, (h + (1 << shift) - 1) >> shift, 0,
                     GL_RG, GL_UNSIGNED_BYTE, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, e->cover_fbo[i]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, e->cover_tex[i], 0);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            e->w = e->h = 0;
            return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "renderer: outline coverage buffer incomplete");
        }
    }
    e->w = w;
    e->h = h;
    return PNPR_OK;
}

/* The coarse coverage of `src` (w x h) in blocks of 2^shift px into cover target i, read through
 * texture unit 1 by the next pass. */
static void coarse_cover(pnpr_edges *e, GLuint src, int i, int shift, int w, int h)
{
    glBindFramebuffer(GL_FRAMEBUFFER, e->cover_fbo[i]);
    glViewport(0, 0, (w + (1 << shift) - 1) >> shift, (h + (1 << shift) - 1) >> shift);
    glUseProgram(e->prog_cover);
    glUniform1i(e->uc_src, 0);
    glUniform1i(e->uc_block, 1 << shift);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, src);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glViewport(0, 0, w, h);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, e->cover_tex[i]);
    glActiveTexture(GL_TEXTURE0);
}

pnpr_status pnpr_edges_draw(pnpr_edges *e, GLuint info_tex, GLuint frame_fbo, int w, int h,
                            const pnpr_edge_params *p, pnpr_error *err)
{
    pnpr_status st = ensure_targets(e, w, h, err);
    if (st != PNPR_OK) return st;
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glViewport(0, 0, w, h);
    glBindVertexArray(e->vao);
    glActiveTexture(GL_TEXTURE0);
    /* pass 1: hole closing, info -> tex[0] */
    int fill_skip = p->reach <= (1 << PNPR_EDGE_SKIP_FILL);
    if (fill_skip) coarse_cover(e, info_tex, 0, PNPR_EDGE_SKIP_FILL, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, e->fbo[0]);
    glUseProgram(e->prog_fill);
    glUniform1i(e->uf_cover, 1);
    glUniform1i(e->uf_info, 0);
    glUniform1i(e->uf_reach, p->reach);
    glUniform1f(e->uf_jump, p->jump);
    glUniform1f(e->uf_hole, p->hole);
    glUniform1f(e->uf_ppu, p->ppu);
    glUniform1i(e->uf_ortho, p->ortho != 0);
    glUniform1i(e->uf_skip_level, fill_skip ? PNPR_EDGE_SKIP_FILL : 0);
    glUniform1i(e->uf_surface_reach, PNPR_EDGE_SURFACE_REACH);
    glBindTexture(GL_TEXTURE_2D, info_tex);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    /* pass 2: minimum filter, tex[0] -> tex[1] */
    float limit = (float)PNPR_EDGE_MAX_INSET + p->width + 2.0f;
    int erode_skip = limit <= (float)(1 << PNPR_EDGE_SKIP_ERODE);
    if (erode_skip) coarse_cover(e, e->tex[0], 1, PNPR_EDGE_SKIP_ERODE, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, e->fbo[1]);
    glUseProgram(e->prog_erode);
    glUniform1i(e->ue_cover, 1);
    glUniform1i(e->ue_filled, 0);
    glUniform1f(e->ue_ppu, p->ppu);
    glUniform1i(e->ue_ortho, p->ortho != 0);
    glUniform1f(e->ue_inset, p->inset);
    glUniform1f(e->ue_inset_max, (float)PNPR_EDGE_MAX_INSET);
    glUniform1f(e->ue_limit, limit);
    glUniform1f(e->ue_width, p->width);
    glUniform1i(e->ue_skip_level, erode_skip ? PNPR_EDGE_SKIP_ERODE : 0);
    glBindTexture(GL_TEXTURE_2D, e->tex[0]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    /* pass 3: the overhang erased (replaced), then the ink band blended into the frame
     * (texture units 0 and 1) */
    glBindFramebuffer(GL_FRAMEBUFFER, frame_fbo);
    glUseProgram(e->prog_ink);
    glUniform1i(e->ui_filled, 0);
    glUniform1i(e->ui_eroded, 1);
    glUniform1f(e->ui_width, p->width);
    glUniform1f(e->ui_jump, p->jump);
    glUniform4fv(e->ui_ink, 1, p->ink);
    glUniform4fv(e->ui_background, 1, p->background);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, e->tex[1]);
    glActiveTexture(GL_TEXTURE0);
    if (p->inset > 0) {
        glUniform1i(e->ui_erase, 1);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUniform1i(e->ui_erase, 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    return PNPR_OK;
}
