/* The posterise effect (effects.h). normalise = 0: each RGB channel rounded to the nearest of
 * `levels` evenly spaced values 0, 255 / (levels - 1), ..., 255 (levels rounded to an integer).
 * normalise = 1 (the default): tone posterisation, see posterise_tone (a light grey scan keeps
 * several levels instead of one grey). Alpha is kept. Needs no OpenCV. */
#include "effects_internal.h"

#include <math.h>

/* normalise = 1: the luminance Y stretched over the layer's range and quantised to the centre of
 * its bin, (k + 1/2) / levels (neither paper white nor black), the colour scaled by Q / Y so that
 * its hue stays (a grey stays grey: no colour fringes from channels rounded apart). */
static void posterise_tone(const pnpr_image *src, pnpr_image *dst, int levels)
{
    float lo, hi;
    pnpr_fx_tone_range(src, &lo, &hi);
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *s = src->rgba + 4 * i;
        uint8_t *d = dst->rgba + 4 * i;
        d[3] = s[3];
        if (s[3] == 0) { d[0] = s[0]; d[1] = s[1]; d[2] = s[2]; continue; } /* paper: copied */
        float y = pnpr_fx_luma(s[0], s[1], s[2]) / 255.0f;
        float t = pnpr_fx_stretch(y, lo, hi);
        int k = (int)(t * (float)levels);
        float q = ((float)(k < levels ? k : levels - 1) + 0.5f) / (float)levels;
        for (int c = 0; c < 3; c++)
            d[c] = pnpr_fx_byte(y > 0.02f ? (float)s[c] / 255.0f * q / y : q);
    }
}

pnpr_status pnpr_fx_posterise(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err)
{
    (void)seed; (void)err;
    int levels = (int)lroundf(p[0]);
    if (levels < 2) levels = 2;
    if (p[1] > 0.5f) { posterise_tone(src, dst, levels); return PNPR_OK; }
    uint8_t table[256];
    for (int v = 0; v < 256; v++) {
        long k = lround(v * (levels - 1) / 255.0); /* nearest level index */
        table[v] = (uint8_t)lround(k * 255.0 / (levels - 1));
    }
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t i = 0; i < n; i++) {
        int paper = src->rgba[4 * i + 3] == 0; /* no fragment: copied (effects.h) */
        for (int c = 0; c < 3; c++) dst->rgba[4 * i + c] = paper ? src->rgba[4 * i + c] : table[src->rgba[4 * i + c]];
        dst->rgba[4 * i + 3] = src->rgba[4 * i + 3];
    }
    return PNPR_OK;
}
