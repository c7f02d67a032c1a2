/* The toon effect (effects.h), after Winnemoeller, Olsen and Gooch 2006, "Real-time video
 * abstraction" (as the paper of Wegen et al. uses it):
 *  1. abstraction: `iterations` bilateral passes (OpenCV bilateralFilter) in CIE Lab, window
 *     `radius`, colour sigma `sigma_color` x 100 Lab units;
 *  2. edges from the luminance after the first pass (their n_e < n_b): DoG with sigma_e =
 *     edge_sigma, sigma_r = 1.6 sigma_e, tau = 0.98, E = 1 where D >= 0, else 1 + tanh(phi_e D)
 *     with phi_e = TOON_PHI_E on L / 100;
 *  3. soft luminance quantisation (their eq. 6): Q = q_b + (dq / 2) tanh(phi_q t) / tanh(phi_q),
 *     with `levels` output values 0, 100 / (levels - 1), ..., 100, dq their spacing, q_b the bin
 *     boundary nearest to L and t = (L - q_b) / (dq / 2) in -1..1. Dividing by tanh(phi_q) (our
 *     choice) makes every level, white and black included, an exact output; phi_q = sharpness;
 *  4. back to RGB, multiplied by 1 - edge_strength (1 - E) and by 1 - silhouette S, S the
 *     segment's outline (pnpr_fx_silhouette: the border of its coverage, which the DoG misses
 *     where the segment's colour is close to the paper's; our addition).
 * Alpha is kept. */
#include "effects_internal.h"

#include <math.h>
#include <stdlib.h>

#define TOON_PHI_E 60.0f
#define TOON_TAU 0.98f
#define TOON_K 1.6f

static float quantise(float l, int levels, float phi_q)
{
    float dq = 100.0f / (float)(levels - 1);
    float qb = (floorf(l / dq) + 0.5f) * dq; /* the boundary between the two nearest levels */
    float t = (l - qb) / (0.5f * dq);
    t = t < -1 ? -1 : (t > 1 ? 1 : t);
    return qb + 0.5f * dq * tanhf(phi_q * t) / tanhf(phi_q);
}

pnpr_status pnpr_fx_toon(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err)
{
    (void)seed;
    int w = src->width, h = src->height, iterations = (int)lroundf(p[0]), radius = (int)lroundf(p[2]);
    int levels = (int)lroundf(p[3]);
    size_t n = (size_t)w * (size_t)h;
    float *rgb = pnpr_fx_floats(3 * n, err), *lab = rgb ? pnpr_fx_floats(3 * n, err) : NULL;
    float *lum = lab ? pnpr_fx_floats(3 * n, err) : NULL, *edge = lum ? lum + n : NULL, *sil = lum ? lum + 2 * n : NULL;
    pnpr_status st = lum ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) {
        pnpr_fx_to_rgb(src, rgb);
        st = pnpr_cv_rgb_to_lab(rgb, lab, w, h, err);
    }
    /* rgb serves as the scratch buffer of the bilateral passes */
    if (st == PNPR_OK) st = pnpr_fx_bilateral_passes(lab, rgb, w, h, radius, 100 * p[1], 1, err);
    if (st == PNPR_OK) {
        for (size_t i = 0; i < n; i++) lum[i] = lab[3 * i] * 0.01f;
        st = pnpr_fx_dog(lum, edge, w, h, p[5], TOON_K, TOON_TAU, TOON_PHI_E, err);
    }
    if (st == PNPR_OK) st = pnpr_fx_silhouette(src, sil, lum, err);
    if (st == PNPR_OK && iterations > 1)
        st = pnpr_fx_bilateral_passes(lab, rgb, w, h, radius, 100 * p[1], iterations - 1, err);
    if (st == PNPR_OK) {
        for (size_t i = 0; i < n; i++) lab[3 * i] = quantise(lab[3 * i], levels, p[4]);
        st = pnpr_cv_lab_to_rgb(lab, rgb, w, h, err);
    }
    if (st == PNPR_OK) {
        for (size_t i = 0; i < n; i++) {
            float f = (1.0f - p[6] * (1.0f - edge[i])) * (1.0f - p[7] * sil[i]);
            for (int c = 0; c < 3; c++) rgb[3 * i + c] *= f;
        }
        pnpr_fx_from_rgb(rgb, src, dst);
    }
    free(rgb);
    free(lab);
    free(lum);
    return st;
}
