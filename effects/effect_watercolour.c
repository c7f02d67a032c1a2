/* The watercolour effect (effects.h), after Bousseau, Kaplan, Thollot and Sillion 2006,
 * "Interactive watercolor rendering with temporal coherence and abstraction":
 *  1. abstraction: the gaps between splats filled from the coverage (pnpr_fx_fill_gaps, radius
 *     `fill` px: the light holes of a sparse cloud are painted over in their surroundings' colour,
 *     which the depth inpainting then gives the segment's depth), two bilateral passes (OpenCV
 *     bilateralFilter), window `abstraction` px, colour sigma WC_SIGMA_COLOR, then their
 *     morphological smoothing (a closing and an opening, OpenCV morphologyEx) with a disk of
 *     radius `fill` px: dark, then light details narrower than the disk go;
 *  2. pigment density d per pixel (their section 3): d = 1 + density N + edge_darkening E, with
 *     N = 0.4 P + 0.6 T in -1..1 from two deterministic hash value noises of `seed` and the pixel
 *     position: P, the paper grain (cells of paper_scale px, smoothed by a Gaussian of
 *     paper_scale / 2), and T, the turbulence flow (two octaves, turbulence_scale and half of it);
 *     E = the gradient magnitude (OpenCV Sobel / 4) of the abstracted luminance blurred by
 *     edge_width, times edge_width sqrt(2 pi), clamped to 0..1 (1 on a black-white step);
 *  3. their colour modification per channel: C' = C - (C - C^2)(d - 1), clamped to 0..1: d > 1
 *     darkens, d < 1 lightens, white paper and black stay as they are.
 * Alpha is kept. */
#include "effects_internal.h"

#include <math.h>
#include <stdlib.h>

#define WC_SIGMA_COLOR 0.15f

/* P and T (each -1..1) into paper and turb. */
static pnpr_status noises(int w, int h, const float *p, uint64_t seed, float *paper, float *turb, pnpr_error *err)
{
    const float ps = p[2], ts = p[3];
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            paper[i] = 2 * pnpr_fx_value_noise(seed, x / ps, y / ps) - 1;
            float t = 0.67f * pnpr_fx_value_noise(seed ^ 0x5bd1e995u, x / ts, y / ts) +
                      0.33f * pnpr_fx_value_noise(seed ^ 0x1b873593u, 2 * x / ts, 2 * y / ts);
            turb[i] = 2 * t - 1;
        }
    return pnpr_cv_gaussian(paper, paper, w, h, 1, 0.5f * ps, err);
}

/* Edge term E of the abstracted colours into edge (lum, dx, dy: scratch of w * h). */
static pnpr_status edges(const float *rgb, int w, int h, float width, float *lum, float *dx, float *dy, float *edge,
                         pnpr_error *err)
{
    size_t n = (size_t)w * (size_t)h;
    pnpr_fx_luma_of(rgb, lum, n);
    pnpr_status st = pnpr_cv_gaussian(lum, lum, w, h, 1, width, err);
    if (st == PNPR_OK) st = pnpr_cv_sobel(lum, dx, dy, w, h, 1, err);
    if (st != PNPR_OK) return st;
    const float gain = 0.25f * width * 2.5066283f;
    for (size_t i = 0; i < n; i++) {
        float g = gain * sqrtf(dx[i] * dx[i] + dy[i] * dy[i]);
        edge[i] = g < 1 ? g : 1;
    }
    return PNPR_OK;
}

pnpr_status pnpr_fx_watercolour(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed,
                                pnpr_error *err)
{
    int w = src->width, h = src->height;
    size_t n = (size_t)w * (size_t)h;
    float *rgb = pnpr_fx_floats(6 * n, err), *tmp = rgb ? rgb + 3 * n : NULL;
    float *f = rgb ? pnpr_fx_floats(6 * n, err) : NULL; /* paper, turb, edge, lum, dx, dy */
    pnpr_status st = f ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) {
        pnpr_fx_to_rgb(src, rgb);
        st = pnpr_fx_fill_gaps(src, rgb, (int)lroundf(p[6]), f, err);
    }
    if (st == PNPR_OK) {
        st = pnpr_fx_bilateral_passes(rgb, tmp, w, h, (int)lroundf(p[0]), WC_SIGMA_COLOR, 2, err);
    }
    if (st == PNPR_OK) st = pnpr_cv_close_open(rgb, rgb, w, h, 3, (int)lroundf(p[6]), err);
    if (st == PNPR_OK) st = noises(w, h, p, seed, f, f + n, err);
    if (st == PNPR_OK) st = edges(rgb, w, h, p[5], f + 3 * n, f + 4 * n, f + 5 * n, f + 2 * n, err);
    if (st == PNPR_OK) {
        for (size_t i = 0; i < n; i++) {
            float d1 = p[1] * (0.4f * f[i] + 0.6f * f[n + i]) + p[4] * f[2 * n + i]; /* d - 1 */
            for (int c = 0; c < 3; c++) {
                float v = rgb[3 * i + c];
                rgb[3 * i + c] = v - (v - v * v) * d1;
            }
        }
        pnpr_fx_from_rgb(rgb, src, dst);
    }
    free(rgb);
    free(f);
    return st;
}
