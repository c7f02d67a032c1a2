/* The posterise effect (effects.h): each RGB channel rounded to the nearest of `levels` evenly
 * spaced values 0, 255 / (levels - 1), ..., 255 (levels rounded to an integer). Alpha is kept.
 * Needs no OpenCV. */
#include "effects_internal.h"

#include <math.h>

pnpr_status pnpr_fx_posterise(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err)
{
    (void)seed; (void)err;
    int levels = (int)lroundf(p[0]);
    if (levels < 2) levels = 2;
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
