/* The hierarchy style's GL side (hierarchy_gl.h; Chi & Lee sec. 4; docs/hierarchy.md). */
#include "renderer_internal.h"
#include "gl_state.h"
#include "pnpr_shaders.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

pnpr_status pnpr_hier_gl_create(pnpr_hier_gl *h, pnpr_error *err)
{
    memset(h, 0, sizeof *h);
    h->tam = -1;
    h->prog = pnpr_gl_link_program(pnpr_shader_hierarchy_vert, pnpr_shader_brush_frag, "hierarchy", err);
    if (!h->prog) return PNPR_ERR_UNSUPPORTED;
    h->u_view = glGetUniformLocation(h->prog, "u_view");
    h->u_proj = glGetUniformLocation(h->prog, "u_proj");
    h->u_brush = glGetUniformLocation(h->prog, "u_brush");
    h->u_oit = glGetUniformLocation(h->prog, "u_oit");
    h->u_weight = glGetUniformLocation(h->prog, "u_weight");
    glGenVertexArrays(1, &h->vao);
    glGenBuffers(2, h->vbo);
    glGenTextures(1, &h->tex);
    return PNPR_OK;
}

void pnpr_hier_gl_release(pnpr_hier_gl *h)
{
    if (h->prog) glDeleteProgram(h->prog);
    if (h->vao) glDeleteVertexArrays(1, &h->vao);
    if (h->vbo[0]) glDeleteBuffers(2, h->vbo);
    if (h->tex) glDeleteTextures(1, &h->tex);
    free(h->buf[0]);
    free(h->buf[1]);
    memset(h, 0, sizeof *h);
}

/* The line layer (PNPR_HIER_LINE_LAYER) of side s: full across the middle half of v, fading to
 * the edges; along u, tapered over the last fifth at both ends. */
static void line_layer(int s, uint8_t *a)
{
    for (int y = 0; y < s; y++)
        for (int x = 0; x < s; x++) {
            double u = fabs((x + 0.5) / s * 2 - 1), v = fabs((y + 0.5) / s * 2 - 1);
            double across = v < 0.5 ? 1 : v > 1 ? 0 : 1 - (v - 0.5) / 0.5;
            double along = u < 0.8 ? 1 : (1 - u) / 0.2;
            a[(size_t)y * s + x] = (uint8_t)lrint(255.0 * across * along);
        }
}

/* The tonal art map `kind`: its tones as layers (and the line layer after them), its levels as
 * the mipmaps (Praun et al.: a column of the map is one tone's mipmap chain; view-independent
 * strokes pick the level by GL's mipmapping, view-dependent ones are drawn near the finest
 * level's size). */
static pnpr_status tam_texture(pnpr_hier_gl *h, int kind)
{
    if (h->tam == kind) return PNPR_OK;
    const size_t layer = (size_t)PNPR_TAM_SIZE * PNPR_TAM_SIZE;
    uint8_t *a = malloc(layer * (PNPR_TAM_TONES + 1));
    if (!a) return PNPR_ERR_OUT_OF_MEMORY;
    glBindTexture(GL_TEXTURE_2D_ARRAY, h->tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int l = 0; l < PNPR_TAM_LEVELS; l++) {
        int side = PNPR_TAM_SIZE >> l;
        if (pnpr_tam_level((pnpr_tam_kind)kind, l, a) != PNPR_OK) { free(a); return PNPR_ERR_INVALID_ARGUMENT; }
        line_layer(side, a + (size_t)side * side * PNPR_TAM_TONES);
        glTexImage3D(GL_TEXTURE_2D_ARRAY, l, GL_R8, side, side, PNPR_TAM_TONES + 1, 0, GL_RED, GL_UNSIGNED_BYTE, a);
    }
    free(a);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, PNPR_TAM_LEVELS - 1);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    h->tam = kind;
    return PNPR_OK;
}

/* One traversal into buffer b; when it did not fit, the buffer grows to the counts and the
 * traversal runs again (it is deterministic: the same strokes, now all of them). Uploaded into
 * vbo[b]. */
static pnpr_status traverse(pnpr_hier_gl *h, int b, const pnpr_hier_view *v, const pnpr_hier_params *prm,
                            pnpr_hier_counts *c)
{
    pnpr_status st = pnpr_sphere_tree_traverse(h->tree, v, prm, h->buf[b], h->cap[b], c);
    size_t n = c->strokes[0] + c->strokes[1] + c->strokes[2];
    if (st == PNPR_OK && c->truncated) {
        pnpr_hier_stroke *nb = realloc(h->buf[b], n * sizeof *nb);
        if (!nb) return PNPR_ERR_OUT_OF_MEMORY;
        h->buf[b] = nb;
        h->cap[b] = n;
        st = pnpr_sphere_tree_traverse(h->tree, v, prm, h->buf[b], h->cap[b], c);
        if (st == PNPR_OK && c->truncated) st = PNPR_ERR_NUMERIC; /* never uploads beyond the buffer */
    }
    if (st != PNPR_OK) return st;
    glBindBuffer(GL_ARRAY_BUFFER, h->vbo[b]);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * sizeof(pnpr_hier_stroke)), h->buf[b], GL_STREAM_DRAW);
    return PNPR_OK;
}

/* Strokes first .. first + n - 1 of vbo[b], blended order-independently and resolved. */
static void draw_range(pnpr_hier_gl *h, pnpr_brush_gl *oit, const pnpr_hier_pass *p, const float *view, int b,
                       size_t first, size_t n)
{
    if (!n) return;
    pnpr_brush_gl_oit_begin(oit, p->stencil);
    glUseProgram(h->prog);
    glUniformMatrix4fv(h->u_view, 1, GL_FALSE, view);
    glUniformMatrix4fv(h->u_proj, 1, GL_FALSE, p->proj);
    glUniform1i(h->u_brush, 0);
    glUniform1i(h->u_oit, 1);
    glUniform1f(h->u_weight, PNPR_OIT_WEIGHT);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, h->tex);
    glBindVertexArray(h->vao);
    glBindBuffer(GL_ARRAY_BUFFER, h->vbo[b]);
    const size_t st = sizeof(pnpr_hier_stroke), base = first * st;
    const struct { GLint n; GLenum type; GLboolean norm; size_t off; } at[5] = {
        {3, GL_FLOAT, GL_FALSE, offsetof(pnpr_hier_stroke, pos)}, {3, GL_FLOAT, GL_FALSE, offsetof(pnpr_hier_stroke, u)},
        {3, GL_FLOAT, GL_FALSE, offsetof(pnpr_hier_stroke, v)}, {4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(pnpr_hier_stroke, rgba)},
        {1, GL_FLOAT, GL_FALSE, offsetof(pnpr_hier_stroke, tone)}};
    for (GLuint a = 0; a < 5; a++) {
        glEnableVertexAttribArray(a);
        glVertexAttribPointer(a, at[a].n, at[a].type, at[a].norm, (GLsizei)st, (const void *)(uintptr_t)(base + at[a].off));
        glVertexAttribDivisor(a, 1);
    }
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)n);
    pnpr_brush_gl_oit_resolve(oit, p->frame_fbo);
}

static void tree_view(const float *view, const double *tree_origin, const double *origin, float *r_view)
{
    memcpy(r_view, view, 16 * sizeof *r_view);
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) r_view[12 + i] += view[4 * k + i] * (float)(tree_origin[k] - origin[k]);
}

pnpr_status pnpr_hier_gl_draw(pnpr_hier_gl *h, pnpr_brush_gl *oit, const pnpr_hier_pass *p, pnpr_hier_counts *r_counts)
{
    pnpr_hier_counts c1 = {0}, c2 = {0};
    if (r_counts) *r_counts = c1;
    if (!h->tree || h->tree->root == PNPR_INDEX_NONE) return PNPR_OK;
    /* the tree's frame: the views translated by the origins' difference */
    float view[16], lview[16];
    tree_view(p->view, h->tree->origin, p->origin, view);
    tree_view(p->lod_view ? p->lod_view : p->view, h->tree->origin, p->origin, lview);
    pnpr_hier_view v = {lview, p->lod_proj ? p->lod_proj : p->proj, p->width, p->height,
                        p->lod_view ? p->lod_pixels_per_unit : p->pixels_per_unit, p->ortho,
                        p->lod_view ? NULL : p->image_proj};
    pnpr_status st = tam_texture(h, p->params.tam);
    if (st == PNPR_OK) st = traverse(h, 0, &v, &p->params, &c1);
    if (st != PNPR_OK) return st;
    size_t np = c1.strokes[PNPR_HIER_PAINT];
    draw_range(h, oit, p, view, 0, 0, np);
    if (p->params.layers == 2) {
        pnpr_hier_params fine = p->params;
        fine.fine_layer = 1;
        if ((st = traverse(h, 1, &v, &fine, &c2)) != PNPR_OK) return st;
        draw_range(h, oit, p, view, 1, 0, c2.strokes[PNPR_HIER_PAINT]);
    }
    draw_range(h, oit, p, view, 0, np, c1.strokes[PNPR_HIER_SILHOUETTE] + c1.strokes[PNPR_HIER_BORDER]);
    if (r_counts) {
        *r_counts = c1;
        r_counts->strokes[PNPR_HIER_PAINT] += c2.strokes[PNPR_HIER_PAINT];
        r_counts->weighted += c2.weighted;
    }
    return PNPR_OK;
}
