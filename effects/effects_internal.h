/* Internal interface of the image-space effects (effects/): one function per effect, each in its
 * own file, called by pnpr_effect_apply (effects/effect.c) with checked arguments; the OpenCV
 * building blocks (effects/cv_adapter.cpp). */
#ifndef PNPR_EFFECTS_INTERNAL_H
#define PNPR_EFFECTS_INTERNAL_H

#include <pointnpr/effects.h>

/* An effect: src -> dst (same size, distinct, checked), parameters resolved to values in range
 * (p[i] = pnpr_effect_param(e, i)). */
typedef pnpr_status (*pnpr_effect_fn)(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed,
                                      pnpr_error *err);

pnpr_status pnpr_fx_smooth(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_toon(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_watercolour(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_oil(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_pencil(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_posterise(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_grade(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_edges(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);

/* Whether this build has OpenCV (0: the pnpr_cv_* functions return PNPR_ERR_UNSUPPORTED). */
int pnpr_cv_available(void);

/* ---- OpenCV building blocks (effects/cv_adapter.cpp) ----
 * Caller-owned float buffers: w * h pixels of `ch` interleaved channels (1 or 3), top row first;
 * borders replicate the edge pixels. Exceptions become PNPR_ERR_OUT_OF_MEMORY (allocation) or
 * PNPR_ERR_UNSUPPORTED (other OpenCV errors) with a message; without OpenCV every one returns
 * PNPR_ERR_UNSUPPORTED "effects: this build has no OpenCV". */

/* cv::bilateralFilter, window (2 radius + 1)^2; sigma_color in the buffer's units (OpenCV measures
 * the colour distance as the sum of the channels' absolute differences). src != dst. */
pnpr_status pnpr_cv_bilateral(const float *src, float *dst, int w, int h, int ch, int radius, float sigma_color,
                              float sigma_space, pnpr_error *err);
/* cv::GaussianBlur with a +-3 sigma kernel; src == dst allowed. */
pnpr_status pnpr_cv_gaussian(const float *src, float *dst, int w, int h, int ch, float sigma, pnpr_error *err);
/* Morphological smoothing: cv::morphologyEx closing, then opening, with an elliptical element of
 * the given radius (px): dark, then bright details narrower than the element go (Bousseau et al.'s
 * abstraction). Closing first, so that dense dark specks (texture noise of RGB-D frames) vanish
 * instead of merging into blobs; the light gaps between splats are filled before, from the
 * coverage (pnpr_fx_fill_gaps). src == dst allowed. */
pnpr_status pnpr_cv_close_open(const float *src, float *dst, int w, int h, int ch, int radius, pnpr_error *err);
/* cv::Sobel 3x3 first derivatives in x and y of every channel (a unit step gives 4). */
pnpr_status pnpr_cv_sobel(const float *src, float *dx, float *dy, int w, int h, int ch, pnpr_error *err);
/* cv::cvtColor sRGB (0..1) <-> CIE Lab (L 0..100, a and b about -128..127). */
pnpr_status pnpr_cv_rgb_to_lab(const float *rgb, float *lab, int w, int h, pnpr_error *err);
pnpr_status pnpr_cv_lab_to_rgb(const float *lab, float *rgb, int w, int h, pnpr_error *err);
/* cv::resize (bilinear) of an RGBA8 image sw x sh into dst, dw x dh (the preview layers of
 * pnpr_renderer_effects grown to the image size). src != dst. */
pnpr_status pnpr_cv_resize_rgba8(const uint8_t *src, int sw, int sh, uint8_t *dst, int dw, int dh, pnpr_error *err);

/* ---- shared helpers of the effects (effects/effect_common.c) ---- */

/* malloc of n floats; NULL with PNPR_ERR_OUT_OF_MEMORY in err on failure or overflow. */
float *pnpr_fx_floats(size_t n, pnpr_error *err);
/* RGB of src as floats 0..1 (3 per pixel). */
void pnpr_fx_to_rgb(const pnpr_image *src, float *rgb);
/* Writes rgb (3 floats per pixel, 0..1) to dst's RGB, rounded and clamped (NaN -> 0); alpha from src. */
void pnpr_fx_from_rgb(const float *rgb, const pnpr_image *src, pnpr_image *dst);
/* Byte of a 0..1 value: rounded, clamped, NaN -> 0. */
uint8_t pnpr_fx_byte(float v);
/* Rec. 709 luminance of linear-weighted RGB values. */
float pnpr_fx_luma(float r, float g, float b);
/* Luminance (0..1) of every pixel of rgb (3 floats per pixel) into lum (n floats). */
void pnpr_fx_luma_of(const float *rgb, float *lum, size_t n);
/* Uniform 0..1 hash of (seed, x, y): white noise on the integer lattice. */
float pnpr_fx_hash(uint64_t seed, int64_t x, int64_t y);
/* Value noise 0..1 at (x, y) in cells of the lattice: bilinear with a smoothstep, C1-continuous. */
float pnpr_fx_value_noise(uint64_t seed, float x, float y);
/* `iterations` bilateral passes over a 3-channel buffer in place (tmp: the same size);
 * sigma_color on the scale of the mean absolute channel difference, spatial sigma radius / 2. */
pnpr_status pnpr_fx_bilateral_passes(float *buf, float *tmp, int w, int h, int radius, float sigma_color,
                                     int iterations, pnpr_error *err);
/* Difference of Gaussians edges of lum (0..1; Winnemoeller et al. 2006 / 2012 XDoG):
 * D = G_sigma - tau G_(k sigma); edge = 1 where D >= 0, else 1 + tanh(phi D) (0 = black line).
 * r_edge: w * h values 0..1; lum is kept. */
pnpr_status pnpr_fx_dog(const float *lum, float *r_edge, int w, int h, float sigma, float k, float tau, float phi,
                        pnpr_error *err);

/* Tone normalisation (pencil, posterise): the 2nd and 98th percentiles (0..1) of the luminance of
 * src's covered pixels (alpha > 0), from a 256-bin histogram; 0 and 1 when none is covered. */
void pnpr_fx_tone_range(const pnpr_image *src, float *r_lo, float *r_hi);
/* v (0..1) stretched about the middle of lo..hi so that the range spans 0.9, with a gain never
 * below 1 and at most PNPR_FX_STRETCH_GAIN_MAX, a cap that falls to 1 as the range
 * shrinks from 0.12 to 0.04 (a flat layer keeps its tone: white paper stays unhatched); clamped
 * to 0..1; the stretched range is then moved as little as it takes to lie within 0.05..0.95 (a
 * layer whose range already spans that is unchanged). Light, low-contrast scans (colourless clouds shaded 0.65..0.85) then use the
 * whole tone scale. */
#define PNPR_FX_STRETCH_GAIN_MAX 4.0f
float pnpr_fx_stretch(float v, float lo, float hi);

/* Fills the gaps of a layer: every uncovered pixel (alpha 0) whose coverage density (a Gaussian of
 * `radius` px over alpha > 0) is at least PNPR_FX_GAP_DENSITY takes the coverage-weighted mean
 * colour of its neighbourhood (normalised convolution); rgb: 3 floats per pixel, changed in place.
 * Unlike a morphological fill it never grows a dark speck. tmp: 4 * w * h floats of scratch. */
#define PNPR_FX_GAP_DENSITY 0.3f
pnpr_status pnpr_fx_fill_gaps(const pnpr_image *src, float *rgb, int radius, float *tmp, pnpr_error *err);

/* Silhouette ink (0..1) of a layer into r_ink (w * h): the layer's coverage (alpha > 0) with the
 * gaps between splats closed (a Gaussian of PNPR_FX_SILHOUETTE_GAP px thresholded at 1/2),
 * blurred by PNPR_FX_SILHOUETTE_WIDTH px; the ink is 5 s (1 - s) clamped (1 along the border, a
 * band about 2 px wide). The outline of a segment whose colour is close to the paper's, which the
 * colour edges (DoG) miss. tmp: w * h floats of scratch. */
#define PNPR_FX_SILHOUETTE_GAP 2.0f
#define PNPR_FX_SILHOUETTE_WIDTH 0.8f
pnpr_status pnpr_fx_silhouette(const pnpr_image *src, float *r_ink, float *tmp, pnpr_error *err);

#endif
