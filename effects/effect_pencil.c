/* The pencil effect (effects.h): hatching by tone with outlines.
 *  tone t = Rec. 709 luminance blurred by a Gaussian of 1 px (OpenCV GaussianBlur), with
 *  normalise = 1 stretched over the layer's tone range (pnpr_fx_stretch: a light, low-contrast
 *  colourless scan is hatched like a drawing of its shading instead of vanishing into the paper);
 *  hatch layer i < layers at angle + {0, 90, 45, -45} degrees is drawn where t < {0.8, 0.6, 0.4,
 *  0.2}[i], with pressure s = clamp((threshold - t) / 0.2, 0, 1): parallel lines `spacing` px
 *  apart whose centres wobble by up to PENCIL_WOBBLE px (value noise of `seed` along the line) and
 *  whose darkness varies along them (hash of the line and position); the line profile is a
 *  triangle of half-width 0.6 + 1.6 s px, the ink PENCIL_INK s; layers multiply (1 - ink);
 *  outlines: the DoG of the luminance (sigma 1.5, k 1.6, tau 0.98, phi 60; effects/effect_common.c)
 *  multiplied in with `outline` darkness, and the segment's outline (pnpr_fx_silhouette) with
 *  `silhouette` darkness;
 *  colour: the grey value v becomes v mix(1, C / Y, color) per channel (C the source colour, Y its
 *  luminance, the ratio at most 4): with color = 1 the hatching keeps the source's hue.
 * The constants make the mean grey of a flat area follow its tone roughly (test_effects checks
 * within 0.15). Alpha is kept. */
#include "effects_internal.h"

#include <math.h>
#include <stdlib.h>

#define PENCIL_INK 0.9f
#define PENCIL_WOBBLE 0.8f

/* Ink (0..1) of hatch layer `layer` at pixel (x, y) for pressure s. */
static float hatch(float x, float y, float angle_deg, float spacing, float s, int layer, uint64_t seed)
{
    float a = angle_deg * 0.017453293f, c = cosf(a), sn = sinf(a);
    float u = -x * sn + y * c, v = x * c + y * sn; /* across and along the lines */
    float k = floorf(u / spacing);
    uint64_t ls = seed + 0x632BE59BD9B4E019ull * (uint64_t)(layer + 1);
    float wob = PENCIL_WOBBLE * (2 * pnpr_fx_value_noise(ls, v / 24.0f, k * 3.7f) - 1);
    float d = fabsf(u - (k + 0.5f) * spacing - wob);
    float hw = 0.6f + 1.6f * s;
    float profile = d < hw ? 1 - d / hw : 0;
    float press = 0.7f + 0.3f * pnpr_fx_value_noise(ls ^ 0xA5A5u, v / 40.0f, k * 5.3f);
    return PENCIL_INK * s * profile * press;
}

pnpr_status pnpr_fx_pencil(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err)
{
    static const float offsets[4] = {0, 90, 45, -45}, thresholds[4] = {0.8f, 0.6f, 0.4f, 0.2f};
    int w = src->width, h = src->height, layers = (int)lroundf(p[2]);
    size_t n = (size_t)w * (size_t)h;
    float *lum = pnpr_fx_floats(5 * n, err), *tone = lum ? lum + n : NULL, *edge = lum ? lum + 2 * n : NULL;
    float *sil = lum ? lum + 3 * n : NULL, *tmp = lum ? lum + 4 * n : NULL;
    pnpr_status st = lum ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) {
        for (size_t i = 0; i < n; i++) {
            const uint8_t *s = src->rgba + 4 * i;
            lum[i] = pnpr_fx_luma(s[0], s[1], s[2]) * (1.0f / 255.0f);
        }
        st = pnpr_cv_gaussian(lum, tone, w, h, 1, 1.0f, err);
    }
    if (st == PNPR_OK) st = pnpr_fx_dog(lum, edge, w, h, 1.5f, 1.6f, 0.98f, 60.0f, err);
    if (st == PNPR_OK) st = pnpr_fx_silhouette(src, sil, tmp, err);
    if (st != PNPR_OK) { free(lum); return st; }
    if (p[6] > 0.5f) {
        float lo, hi;
        pnpr_fx_tone_range(src, &lo, &hi);
        for (size_t i = 0; i < n; i++) tone[i] = pnpr_fx_stretch(tone[i], lo, hi);
    }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            float v = 1;
            for (int l = 0; l < layers && l < 4; l++) {
                float s = (thresholds[l] - tone[i]) / 0.2f;
                if (s <= 0) continue;
                v *= 1 - hatch((float)x, (float)y, p[1] + offsets[l], p[0], s < 1 ? s : 1, l, seed);
            }
            v *= (1 - p[3] * (1 - edge[i])) * (1 - p[5] * sil[i]);
            const uint8_t *s = src->rgba + 4 * i;
            float y709 = lum[i] > 0.02f ? lum[i] : 0.02f;
            for (int c = 0; c < 3; c++) {
                float ratio = s[c] * (1.0f / 255.0f) / y709;
                ratio = ratio < 4 ? ratio : 4;
                dst->rgba[4 * i + c] = pnpr_fx_byte(v * (1 + p[4] * (ratio - 1)));
            }
            dst->rgba[4 * i + 3] = s[3];
        }
    free(lum);
    return PNPR_OK;
}
