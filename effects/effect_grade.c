/* The grade effect (effects.h), on RGB 0..1, in this order:
 *   brightness:  c += brightness
 *   contrast:    c = (c - 0.5) * contrast + 0.5
 *   saturation:  c = Y + (c - Y) * saturation, Y the Rec. 709 luminance of the pixel
 *   tint:        recolour > 0: c = mix(c, tint * Y, recolour) (the pixel recoloured in the tint's
 *                hue at its luminance); recolour = 0: c *= tint (white tint: unchanged)
 * then clamped to 0..1. Alpha is kept; pixels of alpha 0 (paper, no fragment) are copied as they
 * are (effects.h). Needs no OpenCV. */
#include "effects_internal.h"

pnpr_status pnpr_fx_grade(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err)
{
    (void)seed; (void)err;
    const float bright = p[0], contrast = p[1], sat = p[2], tint[3] = {p[3], p[4], p[5]}, recolour = p[6];
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t i = 0; i < n; i++) {
        float c[3];
        if (src->rgba[4 * i + 3] == 0) { for (int k = 0; k < 4; k++) dst->rgba[4 * i + k] = src->rgba[4 * i + k]; continue; }
        for (int k = 0; k < 3; k++) c[k] = (src->rgba[4 * i + k] * (1.0f / 255.0f) + bright - 0.5f) * contrast + 0.5f;
        float y = pnpr_fx_luma(c[0], c[1], c[2]);
        for (int k = 0; k < 3; k++) {
            float v = y + (c[k] - y) * sat;
            if (recolour > 0) v += (tint[k] * y - v) * recolour;
            else v *= tint[k];
            dst->rgba[4 * i + k] = pnpr_fx_byte(v);
        }
        dst->rgba[4 * i + 3] = src->rgba[4 * i + 3];
    }
    return PNPR_OK;
}
