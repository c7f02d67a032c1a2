/* Dithering points (PointWorks section 4.2, after Ostromoukhov, "A Simple and Efficient
 * Error-Diffusion Algorithm", SIGGRAPH 2001).
 *
 * Error diffusion needs a scan order and, for each pixel, "right", "down-left" and "down"
 * neighbours that are not yet processed. On an unorganised cloud we define:
 *  - scan order: Morton (Z-order) of the points' positions quantised to a 1024^3 grid over the
 *    bounding box (ties by index), a locality-preserving sequence like a raster's rows;
 *  - the candidates of point i: its kNN neighbours that are non-feature points (class NONE) and
 *    come later in the scan order;
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

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ostromoukhov_table.h"

static uint64_t spread10(uint32_t v)
{
    uint64_t x = v & 0x3FFu;
    x = (x | (x << 16)) & 0x030000FFull;
    x = (x | (x << 8)) & 0x0300F00Full;
    x = (x | (x << 4)) & 0x030C30C3ull;
    x = (x | (x << 2)) & 0x09249249ull;
    return x;
}

/* LSD radix sort of 64-bit keys, 16 bits per pass. */
static int radix_sort(uint64_t *keys, size_t n)
{
    uint64_t *tmp = malloc((n ? n : 1) * sizeof *tmp);
    if (!tmp) return 0;
    size_t *cnt = malloc(65536 * sizeof *cnt);
    if (!cnt) { free(tmp); return 0; }
    for (int pass = 0; pass < 4; pass++) {
        int shift = 16 * pass;
        memset(cnt, 0, 65536 * sizeof *cnt);
        for (size_t i = 0; i < n; i++) cnt[(keys[i] >> shift) & 0xFFFF]++;
        size_t sum = 0;
        for (size_t b = 0; b < 65536; b++) { size_t c = cnt[b]; cnt[b] = sum; sum += c; }
        for (size_t i = 0; i < n; i++) tmp[cnt[(keys[i] >> shift) & 0xFFFF]++] = keys[i];
        memcpy(keys, tmp, n * sizeof *keys);
    }
    free(cnt);
    free(tmp);
    return 1;
}

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
    if (tone_scale == 0) tone_scale = 1.0f;
    if (!(tone_scale > 0) || !isfinite(tone_scale)) return PNPR_ERR_INVALID_ARGUMENT;
    if (count == 0) return PNPR_OK;

    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    size_t m = 0;
    for (size_t i = 0; i < count; i++) {
        const float *p = xyz + 3 * i;
        if (io_class[i] != PNPR_CLASS_NONE || !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        for (int a = 0; a < 3; a++) {
            if (p[a] < lo[a]) lo[a] = p[a];
            if (p[a] > hi[a]) hi[a] = p[a];
        }
        m++;
    }
    if (m == 0) return PNPR_OK;
    uint64_t *keys = malloc(m * sizeof *keys);
    uint32_t *rank = malloc(count * sizeof *rank);
    float *err = calloc(count, sizeof *err);
    if (!keys || !rank || !err) { free(keys); free(rank); free(err); return PNPR_ERR_OUT_OF_MEMORY; }
    double ext = 0;
    for (int a = 0; a < 3; a++) if ((double)hi[a] - lo[a] > ext) ext = (double)hi[a] - lo[a];
    double q = ext > 0 ? 1023.0 / ext : 0.0;
    m = 0;
    for (size_t i = 0; i < count; i++) {
        const float *p = xyz + 3 * i;
        rank[i] = UINT32_MAX; /* not a candidate */
        if (io_class[i] != PNPR_CLASS_NONE || !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        uint64_t code = 0;
        for (int a = 0; a < 3; a++) {
            double g = ((double)p[a] - lo[a]) * q;
            uint32_t gi = g > 1023.0 ? 1023u : (uint32_t)(g > 0 ? g : 0);
            code |= spread10(gi) << (2 - a);
        }
        keys[m++] = (code << 32) | (uint64_t)i;
    }
    if (!radix_sort(keys, m)) { free(keys); free(rank); free(err); return PNPR_ERR_OUT_OF_MEMORY; }
    for (size_t s = 0; s < m; s++) rank[(uint32_t)keys[s]] = (uint32_t)s;

    size_t chosen = 0;
    for (size_t s = 0; s < m; s++) {
        uint32_t i = (uint32_t)keys[s];
        double t = point_tone(i, rgb, normals, tone) * tone_scale;
        t = t > 0 ? (t < 1 ? t : 1) : 0;
        double v = t + err[i];
        int out = v >= 0.5;
        if (out) { io_class[i] = PNPR_CLASS_DITHER; chosen++; }
        double e = v - out;
        /* targets: right = smallest later rank; down, down-left = nearest remaining */
        const uint32_t *row = knn + (size_t)i * k;
        uint32_t right = PNPR_INDEX_NONE, near1 = PNPR_INDEX_NONE, near2 = PNPR_INDEX_NONE;
        for (size_t r = 0; r < k; r++) {
            uint32_t j = row[r];
            if (j == PNPR_INDEX_NONE || rank[j] == UINT32_MAX || rank[j] <= s) continue;
            if (right == PNPR_INDEX_NONE || rank[j] < rank[right]) right = j;
        }
        for (size_t r = 0; r < k; r++) { /* rows are sorted nearest first */
            uint32_t j = row[r];
            if (j == PNPR_INDEX_NONE || j == right || rank[j] == UINT32_MAX || rank[j] <= s) continue;
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
    free(keys); free(rank); free(err);
    if (r_chosen) *r_chosen = chosen;
    return PNPR_OK;
}
