/* The oil paint effect (effects.h), a simplified version of Semmo, Limberger, Kyprianidis and
 * Doellner 2016, "Image stylization by interactive oil paint filtering":
 *  1. optional colour levels (`levels` >= 2: each channel rounded to the nearest of `levels`);
 *  2. flow: the structure tensor (E, F, G) = sum over RGB of (fx^2, fx fy, fy^2), derivatives by
 *     OpenCV Sobel of the image blurred by 1 px, tensor smoothed by a Gaussian of tensor_sigma;
 *     the flow is its minor eigenvector t = (l1 - E, -F), l1 the major eigenvalue; where the
 *     anisotropy A = (l1 - l2) / (l1 + l2) is low the flow blends towards a smooth random
 *     direction (value noise of `seed`, cells of 64 px), so that flat areas get strokes too;
 *  3. paint: line integral convolution along the flow (Cabral and Leedom 1993): unit steps both
 *     ways for `length` px, Gaussian weights of sigma length / 2, bilinear samples;
 *  4. brush: value noise of cells brush_scale / 2 px smeared by the same integration is a height
 *     field H; its Sobel gradient lights the paint from the upper left: C' = C (1 + relief b),
 *     b = clamp(-(Hx + Hy) / sqrt(2) x OIL_BUMP_GAIN, -1, 1) (Semmo's Phong shading reduced to its
 *     diffuse term; no specular), faded out where the paint is lighter than luminance 0.85 so
 *     that a white background stays white.
 * Alpha is kept. */
#include "effects_internal.h"

#include <math.h>
#include <stdlib.h>

#define OIL_BUMP_GAIN 0.35f

/* Flow field (fx, fy per pixel, unit length) of rgb into flow; s: scratch of 9 n floats. */
static pnpr_status flow_field(const float *rgb, int w, int h, float tsigma, uint64_t seed, float *s, float *flow,
                              pnpr_error *err)
{
    size_t n = (size_t)w * (size_t)h;
    float *blur = s, *dx = s + 3 * n, *dy = s + 6 * n, *tensor = s; /* tensor reuses blur */
    pnpr_status st = pnpr_cv_gaussian(rgb, blur, w, h, 3, 1.0f, err);
    if (st == PNPR_OK) st = pnpr_cv_sobel(blur, dx, dy, w, h, 3, err);
    if (st != PNPR_OK) return st;
    for (size_t i = 0; i < n; i++) {
        float e = 0, f = 0, g = 0;
        for (int c = 0; c < 3; c++) {
            float a = dx[3 * i + c], b = dy[3 * i + c];
            e += a * a; f += a * b; g += b * b;
        }
        tensor[3 * i] = e; tensor[3 * i + 1] = f; tensor[3 * i + 2] = g;
    }
    st = pnpr_cv_gaussian(tensor, tensor, w, h, 3, tsigma, err);
    if (st != PNPR_OK) return st;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            float e = tensor[3 * i], f = tensor[3 * i + 1], g = tensor[3 * i + 2];
            float root = sqrtf((e - g) * (e - g) + 4 * f * f), l1 = 0.5f * (e + g + root);
            float tx = l1 - e, ty = -f, len = sqrtf(tx * tx + ty * ty);
            float aniso = e + g > 1e-8f ? root / (e + g) : 0;
            float ang = 6.2831853f * pnpr_fx_value_noise(seed ^ 0xF10Bu, x / 64.0f, y / 64.0f);
            float nx = cosf(ang), ny = sinf(ang);
            if (len > 1e-12f) {
                tx /= len; ty /= len;
                if (tx * nx + ty * ny < 0) { tx = -tx; ty = -ty; }
            } else { tx = nx; ty = ny; aniso = 0; }
            float bx = aniso * tx + (1 - aniso) * nx, by = aniso * ty + (1 - aniso) * ny;
            float bl = sqrtf(bx * bx + by * by);
            flow[2 * i] = bl > 1e-6f ? bx / bl : tx;
            flow[2 * i + 1] = bl > 1e-6f ? by / bl : ty;
        }
    return PNPR_OK;
}

/* Bilinear sample of the 4 channels of buf at (x, y), clamped to the image, added with weight wt. */
static void sample_add(const float *buf, int w, int h, float x, float y, float wt, float acc[4])
{
    x = x < 0 ? 0 : (x > w - 1 ? (float)(w - 1) : x);
    y = y < 0 ? 0 : (y > h - 1 ? (float)(h - 1) : y);
    int x0 = (int)x, y0 = (int)y, x1 = x0 + 1 < w ? x0 + 1 : x0, y1 = y0 + 1 < h ? y0 + 1 : y0;
    float ax = x - x0, ay = y - y0;
    const float *p00 = buf + 4 * ((size_t)y0 * w + x0), *p10 = buf + 4 * ((size_t)y0 * w + x1);
    const float *p01 = buf + 4 * ((size_t)y1 * w + x0), *p11 = buf + 4 * ((size_t)y1 * w + x1);
    for (int c = 0; c < 4; c++)
        acc[c] += wt * ((p00[c] * (1 - ax) + p10[c] * ax) * (1 - ay) + (p01[c] * (1 - ax) + p11[c] * ax) * ay);
}

/* Line integral convolution of the 4-channel buf along flow into out. */
static void lic(const float *buf, const float *flow, int w, int h, int length, float *out)
{
    float sigma = 0.5f * (float)length, inv = 1.0f / (2 * sigma * sigma);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float acc[4] = {0, 0, 0, 0}, total = 1;
            sample_add(buf, w, h, (float)x, (float)y, 1, acc);
            for (int dir = -1; dir <= 1; dir += 2) {
                float px = (float)x, py = (float)y;
                const float *f0 = flow + 2 * ((size_t)y * w + x);
                float vx = dir * f0[0], vy = dir * f0[1];
                for (int k = 1; k <= length; k++) {
                    px += vx; py += vy;
                    if (px < 0 || py < 0 || px > w - 1 || py > h - 1) break;
                    const float *f = flow + 2 * ((size_t)lroundf(py) * w + lroundf(px));
                    float nx = f[0], ny = f[1];
                    if (nx * vx + ny * vy < 0) { nx = -nx; ny = -ny; }
                    vx = nx; vy = ny;
                    float wt = expf(-(float)(k * k) * inv);
                    sample_add(buf, w, h, px, py, wt, acc);
                    total += wt;
                }
            }
            for (int c = 0; c < 4; c++) out[4 * ((size_t)y * w + x) + c] = acc[c] / total;
        }
}

pnpr_status pnpr_fx_oil(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err)
{
    int w = src->width, h = src->height, length = (int)lroundf(p[0]), levels = (int)lroundf(p[4]);
    size_t n = (size_t)w * (size_t)h;
    float *rgb = pnpr_fx_floats(20 * n, err); /* rgb 3, scratch 9, flow 2, paint 4 (+ brush) 4... */
    if (!rgb) return PNPR_ERR_OUT_OF_MEMORY;
    float *scratch = rgb + 3 * n, *flow = rgb + 12 * n, *paint = rgb + 14 * n, *lit = scratch;
    pnpr_fx_to_rgb(src, rgb);
    if (levels >= 2)
        for (size_t i = 0; i < 3 * n; i++) rgb[i] = roundf(rgb[i] * (float)(levels - 1)) / (float)(levels - 1);
    pnpr_status st = flow_field(rgb, w, h, p[1], seed, scratch, flow, err);
    if (st == PNPR_OK) {
        float *in4 = scratch; /* r, g, b, brush noise */
        const float bs = 0.5f * p[2];
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                size_t i = (size_t)y * (size_t)w + (size_t)x;
                for (int c = 0; c < 3; c++) in4[4 * i + c] = rgb[3 * i + c];
                in4[4 * i + 3] = pnpr_fx_value_noise(seed, x / bs, y / bs);
            }
        lic(in4, flow, w, h, length, paint);
        for (size_t i = 0; i < n; i++) rgb[i] = paint[4 * i + 3]; /* height field */
        st = pnpr_cv_sobel(rgb, lit, lit + n, w, h, 1, err);
    }
    if (st == PNPR_OK) {
        for (size_t i = 0; i < n; i++) {
            float b = -(lit[i] + lit[n + i]) * 0.70710678f * OIL_BUMP_GAIN;
            b = b < -1 ? -1 : (b > 1 ? 1 : b);
            float y = pnpr_fx_luma(paint[4 * i], paint[4 * i + 1], paint[4 * i + 2]);
            float k = (1 - y) * (1.0f / 0.15f); /* no relief on white: the background stays clean */
            b *= k < 1 ? (k > 0 ? k : 0) : 1;
            for (int c = 0; c < 3; c++) rgb[3 * i + c] = paint[4 * i + c] * (1 + p[3] * b);
        }
        pnpr_fx_from_rgb(rgb, src, dst);
    }
    free(rgb);
    return st;
}
