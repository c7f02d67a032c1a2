/* Host GL state that the renderer touches: saved on entry to every renderer call that issues GL
 * commands, restored on exit (docs/rendering.md lists it). */
#ifndef PNPR_GL_STATE_H
#define PNPR_GL_STATE_H

#include <epoxy/gl.h>

#include <stddef.h>

enum { PNPR_GL_STATE_ENABLES = 14 };
/* The texture unit of the per-cell queues' table (a buffer texture, RGBA32F per cell: renderer.c). */
enum { PNPR_GL_CELLS_UNIT = 5 };

typedef struct pnpr_gl_state {
    GLint draw_fbo, read_fbo, renderbuffer;
    GLint viewport[4];
    GLboolean enabled[PNPR_GL_STATE_ENABLES];
    GLint depth_func;
    GLboolean depth_mask;
    GLboolean color_mask[4];
    GLint blend_src_rgb, blend_dst_rgb, blend_src_alpha, blend_dst_alpha;
    GLint blend_eq_rgb, blend_eq_alpha;
    GLfloat clear_color[4];
    GLfloat clear_depth;
    GLint polygon_mode[2];
    GLint program, vao, array_buffer;
    GLint active_texture, tex_2d, tex_2d_array, sampler;
    GLint tex_2d_unit1, sampler_unit1; /* texture unit 1 (the outline passes read two textures) */
    GLint tex_buffer_cells, sampler_cells; /* unit PNPR_GL_CELLS_UNIT: the per-cell queues' table */
    GLint pack[5];   /* alignment, row length, skip pixels, skip rows, pixel pack buffer */
    GLint unpack[7];
    GLint stencil[2][7]; /* front, back: func, ref, value mask, fail, depth fail, depth pass, write mask */
    GLint stencil_clear; /* alignment, row length, skip pixels, skip rows, skip images, image height, buffer */
} pnpr_gl_state;

/* The capabilities saved (and set to a known value while the renderer works). */
extern const GLenum pnpr_gl_state_enables[PNPR_GL_STATE_ENABLES];

void pnpr_gl_state_save(pnpr_gl_state *s);
void pnpr_gl_state_restore(const pnpr_gl_state *s);
/* Known state for the renderer's own work: no scissor/stencil/cull/etc., fill mode, texture
 * unit 0 without sampler object, client-memory pixel transfers with alignment 1. */
void pnpr_gl_state_neutral(void);

/* Compiles and links a program from GLSL sources; 0 with the compiler's log in err. */
#include <pointnpr/core.h>
/* The #defines every shader gets after its #version line: the constants both C and GLSL use
 * (PNPR_VSTYLE_HIDDEN, PNPR_BRUSH_VARIANTS, PNPR_HATCH_DIR, PNPR_HATCH_DIR2), written from the C
 * values, so no shader restates them (renderer.c). */
#define PNPR_SHADER_PRELUDE_MAX 2048 /* the prelude's bytes at most (the compile's buffer) */
void pnpr_shader_prelude(char *buf, size_t cap);

/* The per-cell queues' uniforms of a program that calls the prelude's pnpr_queue (-1: not used). */
typedef struct pnpr_queue_uniforms { GLint cells, min, inv, n, scale; } pnpr_queue_uniforms;
void pnpr_queue_uniforms_find(GLuint prog, pnpr_queue_uniforms *u);

GLuint pnpr_gl_link_program(const char *vs, const char *fs, const char *name, pnpr_error *err);
/* A uniform of a program and where its location goes: a GLint member of a struct of locations. */
typedef struct pnpr_gl_uniform { const char *name; size_t offset; } pnpr_gl_uniform;
/* Looks up every uniform of the table in prog into the struct at locations (-1: not used). */
void pnpr_gl_find_uniforms(GLuint prog, const pnpr_gl_uniform *table, size_t count, void *locations);

#endif
