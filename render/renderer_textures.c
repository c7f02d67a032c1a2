/* The renderer's textures: the stroke textures (paper figure 5 a-c, plus the hatch; a texture
 * array, one layer each) and the painterly brush dab, generated once at pnpr_renderer_create. */
#include "renderer_internal.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

/* ---- the texels ----------------------------------------------------------------------------- */

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

/* ---- upload --------------------------------------------------------------------------------- */

/* Mipmapped, linearly filtered, clamped to the edge: the texture bound to `target`. */
static void texture_params(GLenum target)
{
    glGenerateMipmap(target);
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

pnpr_status pnpr_renderer_make_textures(pnpr_renderer *r)
{
    uint8_t *tex = malloc((size_t)STROKE_TEX_W * STROKE_TEX_H * STROKE_LAYERS);
    if (!tex) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_stroke_textures(tex);
    glGenTextures(1, &r->stroke_tex);
    glBindTexture(GL_TEXTURE_2D_ARRAY, r->stroke_tex);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R8, STROKE_TEX_W, STROKE_TEX_H, STROKE_LAYERS, 0,
                 GL_RED, GL_UNSIGNED_BYTE, tex);
    free(tex);
    texture_params(GL_TEXTURE_2D_ARRAY);

    uint8_t *brush = malloc((size_t)BRUSH_TEX * BRUSH_TEX);
    if (!brush) return PNPR_ERR_OUT_OF_MEMORY;
    make_brush_texture(brush);
    glGenTextures(1, &r->brush_tex);
    glBindTexture(GL_TEXTURE_2D, r->brush_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, BRUSH_TEX, BRUSH_TEX, 0, GL_RED, GL_UNSIGNED_BYTE, brush);
    free(brush);
    texture_params(GL_TEXTURE_2D);
    return PNPR_OK;
}
