/* The edges effect (effects.h): XDoG of the Rec. 709 luminance L (0..1) in the tau form of
 * Winnemoeller, Kyprianidis and Olsen 2012 ("XDoG: an eXtended difference-of-Gaussians compendium"),
 * eqs. 2-5 with epsilon = 0: D = G_sigma(L) - tau G_(k sigma)(L); T = 1 where D >= 0, else
 * 1 + tanh(phi D). Each RGB byte is multiplied by 1 - strength (1 - T). Flat regions have D =
 * (1 - tau) L >= 0 and stay exactly unchanged. Gaussians: OpenCV GaussianBlur. The segment's
 * outline (pnpr_fx_silhouette: its coverage border) is multiplied in with `silhouette` darkness.
 * With paper = 1 the lines are drawn on the paper colour (that of the first uncovered pixel, white
 * when every pixel is covered) instead of the image: a line drawing. Alpha is kept. */
#include "effects_internal.h"

#include <stdlib.h>

pnpr_status pnpr_fx_edges(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err)
{
    (void)seed;
    int w = src->width, h = src->height;
    size_t n = (size_t)w * (size_t)h;
    float *lum = pnpr_fx_floats(n, err), *edge = lum ? pnpr_fx_floats(2 * n, err) : NULL, *sil = edge ? edge + n : NULL;
    pnpr_status st = edge ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) {
        for (size_t i = 0; i < n; i++) {
            const uint8_t *s = src->rgba + 4 * i;
            lum[i] = pnpr_fx_luma(s[0], s[1], s[2]) * (1.0f / 255.0f);
        }
        st = pnpr_fx_dog(lum, edge, w, h, p[0], p[1], p[2], p[3], err);
    }
    if (st == PNPR_OK) st = pnpr_fx_silhouette(src, sil, lum, err);
    if (st == PNPR_OK) {
        uint8_t paper[3] = {255, 255, 255};
        for (size_t i = 0; i < n; i++)
            if (src->rgba[4 * i + 3] == 0) { for (int c = 0; c < 3; c++) paper[c] = src->rgba[4 * i + c]; break; }
        for (size_t i = 0; i < n; i++) {
            float f = (1.0f - p[4] * (1.0f - edge[i])) * (1.0f - p[5] * sil[i]);
            for (int c = 0; c < 3; c++) {
                float base = src->rgba[4 * i + c] + p[6] * (float)(paper[c] - src->rgba[4 * i + c]);
                dst->rgba[4 * i + c] = pnpr_fx_byte(base * (1.0f / 255.0f) * f);
            }
            dst->rgba[4 * i + 3] = src->rgba[4 * i + 3];
        }
    }
    free(lum);
    free(edge);
    return st;
}
