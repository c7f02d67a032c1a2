/* Dithering points (PointWorks section 4.2, after Ostromoukhov, "A Simple and Efficient
 * Error-Diffusion Algorithm", SIGGRAPH 2001).
 *
 * Error diffusion needs a scan order and, for each pixel, "right", "down-left" and "down"
 * neighbours that are not yet processed. On an unorganised cloud we define:
 *  - scan order: the order of the arrays, which must be spatially coherent, as a raster's rows
 *    are. pnpr_compute_features passes kd-tree order (median splits on the widest axis: a
 *    locality-preserving k-d curve, like a Morton order, at no extra cost);
 *  - the candidates of point i: its kNN neighbours that are non-feature points (class NONE, a
 *    dithering point chosen earlier is no longer one) and come later in the scan order;
 *  - "right" = the candidate that comes next in the scan order (the scan continues there);
 *    "down" = the nearest remaining candidate; "down-left" = the next-nearest remaining one;
 *  - the coefficients (r, dl, d)/sum come from Ostromoukhov's table, indexed by the point's input
 *    level round(255 * tone); missing targets have their weight shared out over the present
 *    ones; with no candidate at all the error is dropped.
 * Input tone (darkness, 0 = white, 1 = black): caller-given, else 1 - Rec.601 luma of the
 * colour, else from the normal lit from +z: 0.5 * (1 - n_z) (unknown normal: 0.5); multiplied by
 * tone_scale and clamped to [0,1]. A point becomes a dithering point when tone + diffused error
 * >= 0.5; the error left is (tone + error) - output. The density of dithering points per surface
 * sample therefore follows the tone. */
#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <pointnpr/options.h>

#include <math.h>
#include <stdlib.h>

#include "ostromoukhov_table.h"

static float point_tone(size_t i, const uint8_t *rgb, const float *normals, const float *tone)
{
    if (tone) return tone[i];
    if (rgb) {
        const uint8_t *c = rgb + 3 * i;
        return 1.0f - (0.299f * c[0] + 0.587f * c[1] + 0.114f * c[2]) / 255.0f;
    }
    if (normals) {
        const float *n = normals + 3 * i;
        if (n[0] != 0.0f || n[1] != 0.0f || n[2] != 0.0f) return 0.5f * (1.0f - n[2]);
    }
    return 0.5f;
}

pnpr_status pnpr_dither(const float *xyz, const uint8_t *rgb, const float *normals,
                        const float *tone, size_t count, const uint32_t *knn, size_t k,
                        float tone_scale, uint8_t *io_class, size_t *r_chosen)
{
    if (r_chosen) *r_chosen = 0;
    if (count && (!xyz || !knn || !io_class || k == 0)) return PNPR_ERR_INVALID_ARGUMENT;
    if (tone_scale == 0) tone_scale = pnpr_features_defaults().dither_scale; /* options.h */
    if (!(tone_scale > 0) || !isfinite(tone_scale)) return PNPR_ERR_INVALID_ARGUMENT;
    if (count == 0) return PNPR_OK;
    float *err = calloc(count, sizeof *err);
    if (!err) return PNPR_ERR_OUT_OF_MEMORY;

    size_t chosen = 0;
    for (size_t i = 0; i < count; i++) {
        const float *p = xyz + 3 * i;
        if (io_class[i] != PNPR_CLASS_NONE || !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        double t = point_tone(i, rgb, normals, tone) * tone_scale;
        t = t > 0 ? (t < 1 ? t : 1) : 0;
        double v = t + err[i];
        int out = v >= 0.5;
        if (out) { io_class[i] = PNPR_CLASS_DITHER; chosen++; }
        double e = v - out;
        /* targets among later non-feature neighbours: right = the one the scan reaches first,
         * down and down-left = the nearest remaining ones (rows are sorted nearest first) */
        const uint32_t *row = knn + i * k;
        uint32_t right = PNPR_INDEX_NONE, near1 = PNPR_INDEX_NONE, near2 = PNPR_INDEX_NONE;
        for (size_t r = 0; r < k; r++) {
            uint32_t j = row[r];
            if (j == PNPR_INDEX_NONE || j <= i || io_class[j] != PNPR_CLASS_NONE) continue;
            if (right == PNPR_INDEX_NONE || j < right) right = j;
        }
        for (size_t r = 0; r < k; r++) {
            uint32_t j = row[r];
            if (j == PNPR_INDEX_NONE || j <= i || j == right || io_class[j] != PNPR_CLASS_NONE) continue;
            if (near1 == PNPR_INDEX_NONE) near1 = j;
            else { near2 = j; break; }
        }
        int level = (int)(t * 255.0 + 0.5);
        const int *c = pnpr_ostromoukhov[level];
        double wr = right != PNPR_INDEX_NONE ? c[0] : 0, wd = near1 != PNPR_INDEX_NONE ? c[2] : 0,
               wdl = near2 != PNPR_INDEX_NONE ? c[1] : 0;
        double ws = wr + wd + wdl;
        if (!(ws > 0)) continue; /* no later neighbour: the error is dropped */
        if (right != PNPR_INDEX_NONE) err[right] += (float)(e * wr / ws);
        if (near1 != PNPR_INDEX_NONE) err[near1] += (float)(e * wd / ws);
        if (near2 != PNPR_INDEX_NONE) err[near2] += (float)(e * wdl / ws);
    }
    free(err);
    if (r_chosen) *r_chosen = chosen;
    return PNPR_OK;
}
