/* Helpers shared by the effects (effects_internal.h): float conversion, luminance, deterministic
 * hash noise, iterated bilateral filtering and DoG edges. No global state. */
#include "effects_internal.h"

#include <math.h>
#include <stdlib.h>

float *pnpr_fx_floats(size_t n, pnpr_error *err)
{
    float *p = n && n <= SIZE_MAX / sizeof(float) ? malloc(n * sizeof(float)) : NULL;
    if (!p) pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "effects: out of memory (%zu floats)", n);
    return p;
}

void pnpr_fx_to_rgb(const pnpr_image *src, float *rgb)
{
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) rgb[3 * i + c] = src->rgba[4 * i + c] * (1.0f / 255.0f);
}

uint8_t pnpr_fx_byte(float v)
{
    if (!(v > 0)) return 0; /* NaN too */
    if (v >= 1) return 255;
    return (uint8_t)(v * 255.0f + 0.5f);
}

void pnpr_fx_from_rgb(const float *rgb, const pnpr_image *src, pnpr_image *dst)
{
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++) dst->rgba[4 * i + c] = pnpr_fx_byte(rgb[3 * i + c]);
        dst->rgba[4 * i + 3] = src->rgba[4 * i + 3];
    }
}

float pnpr_fx_luma(float r, float g, float b)
{
    return 0.2126f * r + 0.7152f * g + 0.0722f * b;
}

void pnpr_fx_luma_of(const float *rgb, float *lum, size_t n)
{
    for (size_t i = 0; i < n; i++) lum[i] = pnpr_fx_luma(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]);
}

/* SplitMix64's finaliser (Steele et al. 2014) over the seed and both coordinates. */
float pnpr_fx_hash(uint64_t seed, int64_t x, int64_t y)
{
    uint64_t z = seed ^ ((uint64_t)x * 0x9E3779B97F4A7C15ull) ^ ((uint64_t)y * 0xC2B2AE3D27D4EB4Full);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (float)(z >> 40) * (1.0f / 16777216.0f);
}

float pnpr_fx_value_noise(uint64_t seed, float x, float y)
{
    float fx = floorf(x), fy = floorf(y);
    int64_t ix = (int64_t)fx, iy = (int64_t)fy;
    float tx = x - fx, ty = y - fy;
    tx = tx * tx * (3 - 2 * tx);
    ty = ty * ty * (3 - 2 * ty);
    float a = pnpr_fx_hash(seed, ix, iy), b = pnpr_fx_hash(seed, ix + 1, iy);
    float c = pnpr_fx_hash(seed, ix, iy + 1), d = pnpr_fx_hash(seed, ix + 1, iy + 1);
    return (a + (b - a) * tx) * (1 - ty) + (c + (d - c) * tx) * ty;
}

pnpr_status pnpr_fx_bilateral_passes(float *buf, float *tmp, int w, int h, int radius, float sigma_color,
                                     int iterations, pnpr_error *err)
{
    float sigma_space = radius * 0.5f > 0.5f ? radius * 0.5f : 0.5f;
    /* OpenCV's colour distance sums the three channels' absolute differences */
    for (int i = 0; i < iterations; i++) {
        pnpr_status st = pnpr_cv_bilateral(buf, tmp, w, h, 3, radius, 3 * sigma_color, sigma_space, err);
        if (st != PNPR_OK) return st;
        for (size_t j = 0, n = (size_t)w * (size_t)h * 3; j < n; j++) buf[j] = tmp[j];
    }
    return PNPR_OK;
}

pnpr_status pnpr_fx_dog(const float *lum, float *r_edge, int w, int h, float sigma, float k, float tau, float phi,
                        pnpr_error *err)
{
    size_t n = (size_t)w * (size_t)h;
    float *wide = pnpr_fx_floats(n, err);
    if (!wide) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_status st = pnpr_cv_gaussian(lum, r_edge, w, h, 1, sigma, err);
    if (st == PNPR_OK) st = pnpr_cv_gaussian(lum, wide, w, h, 1, sigma * k, err);
    if (st == PNPR_OK)
        for (size_t i = 0; i < n; i++) {
            float d = r_edge[i] - tau * wide[i];
            float e = d >= 0 ? 1.0f : 1.0f + tanhf(phi * d);
            r_edge[i] = e > 0 ? (e < 1 ? e : 1) : 0; /* NaN -> 0 cannot happen for finite lum */
        }
    free(wide);
    return st;
}

void pnpr_fx_tone_range(const pnpr_image *src, float *r_lo, float *r_hi)
{
    size_t hist[256] = {0}, n = (size_t)src->width * (size_t)src->height, covered = 0;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *s = src->rgba + 4 * i;
        if (s[3] == 0) continue;
        int y = (int)(pnpr_fx_luma(s[0], s[1], s[2]) + 0.5f);
        hist[y < 0 ? 0 : y > 255 ? 255 : y]++;
        covered++;
    }
    *r_lo = 0;
    *r_hi = 1;
    if (covered == 0) return;
    size_t cut = covered / 50, acc = 0; /* 2nd and 98th percentiles */
    int lo = 0, hi = 255;
    for (lo = 0; lo < 255 && acc + hist[lo] <= cut; lo++) acc += hist[lo];
    acc = 0;
    for (hi = 255; hi > lo && acc + hist[hi] <= cut; hi--) acc += hist[hi];
    *r_lo = (float)lo / 255.0f;
    *r_hi = (float)hi / 255.0f;
}

float pnpr_fx_stretch(float v, float lo, float hi)
{
    float range = hi - lo;
    /* the gain allowed grows from 1 (flat layers keep their tone) to the maximum over 0.04..0.12 */
    float t = (range - 0.04f) / 0.08f;
    float cap = 1.0f + (PNPR_FX_STRETCH_GAIN_MAX - 1.0f) * (t < 0 ? 0 : t > 1 ? 1 : t);
    float gain = range * cap > 0.9f ? 0.9f / range : cap;
    if (gain < 1) gain = 1; /* only stretched, never squeezed */
    /* the stretched range's middle moved (as little as it takes) into 0.05..0.95 */
    float half = 0.5f * gain * range, mid = 0.5f * (lo + hi), lo_m = 0.05f + half, hi_m = 0.95f - half;
    float mid2 = lo_m > hi_m ? 0.5f : mid < lo_m ? lo_m : mid > hi_m ? hi_m : mid;
    float s = mid2 + (v - mid) * gain;
    return s < 0 ? 0 : s > 1 ? 1 : s;
}

pnpr_status pnpr_fx_silhouette(const pnpr_image *src, float *r_ink, float *tmp, pnpr_error *err)
{
    int w = src->width, h = src->height;
    size_t n = (size_t)w * (size_t)h;
    for (size_t i = 0; i < n; i++) tmp[i] = src->rgba[4 * i + 3] ? 1.0f : 0.0f;
    pnpr_status st = pnpr_cv_gaussian(tmp, tmp, w, h, 1, PNPR_FX_SILHOUETTE_GAP, err);
    if (st != PNPR_OK) return st;
    for (size_t i = 0; i < n; i++) tmp[i] = tmp[i] >= 0.5f ? 1.0f : 0.0f; /* coverage, gaps closed */
    st = pnpr_cv_gaussian(tmp, r_ink, w, h, 1, PNPR_FX_SILHOUETTE_WIDTH, err);
    if (st != PNPR_OK) return st;
    for (size_t i = 0; i < n; i++) {
        float s = r_ink[i], ink = 5.0f * s * (1.0f - s); /* 1 across the border's middle */
        r_ink[i] = ink < 0 ? 0 : ink > 1 ? 1 : ink;
    }
    return PNPR_OK;
}

pnpr_status pnpr_fx_fill_gaps(const pnpr_image *src, float *rgb, int radius, float *tmp, pnpr_error *err)
{
    int w = src->width, h = src->height;
    size_t n = (size_t)w * (size_t)h;
    if (radius <= 0) return PNPR_OK;
    float *cov = tmp, *acc = tmp + n;
    for (size_t i = 0; i < n; i++) {
        float c = src->rgba[4 * i + 3] ? 1.0f : 0.0f;
        cov[i] = c;
        for (int k = 0; k < 3; k++) acc[3 * i + k] = c * rgb[3 * i + k];
    }
    pnpr_status st = pnpr_cv_gaussian(cov, cov, w, h, 1, (float)radius, err);
    if (st == PNPR_OK) st = pnpr_cv_gaussian(acc, acc, w, h, 3, (float)radius, err);
    if (st != PNPR_OK) return st;
    for (size_t i = 0; i < n; i++)
        if (src->rgba[4 * i + 3] == 0 && cov[i] >= PNPR_FX_GAP_DENSITY)
            for (int k = 0; k < 3; k++) rgb[3 * i + k] = acc[3 * i + k] / cov[i];
    return PNPR_OK;
}
