/* Depth inpainting (Wegen et al., listing 1) and the compositing of segment layers with a
 * per-pixel depth test (effects.h; docs/effects.md, "Compositing"). Plain loops: OpenCV has no
 * masked circular mean that skips far-plane pixels, and the listing is a few lines. */
#include "effects_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *const layering_names[PNPR_LAYERING_COUNT_] = {"inpainted", "fragment", "none"};

const char *pnpr_layering_name(pnpr_layering mode)
{
    return (unsigned)mode < PNPR_LAYERING_COUNT_ ? layering_names[mode] : "";
}

pnpr_status pnpr_layering_from_name(const char *name, pnpr_layering *r_mode)
{
    if (!name || !r_mode) return PNPR_ERR_INVALID_ARGUMENT;
    for (int i = 0; i < PNPR_LAYERING_COUNT_; i++)
        if (!strcasecmp(name, layering_names[i])) { *r_mode = (pnpr_layering)i; return PNPR_OK; }
    return PNPR_ERR_NOT_FOUND;
}

/* Grey value 0..1 of an RGBA8 pixel (Rec. 709 luma weights on the stored values). */
static float grey(const uint8_t *p)
{
    return (0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]) / 255.0f;
}

static int same_size(const pnpr_image *a, const pnpr_image *b)
{
    return a && b && a->rgba && b->rgba && a->width == b->width && a->height == b->height && a->width > 0 &&
           a->height > 0 && (size_t)a->width <= ((size_t)1 << 30) / (size_t)a->height;
}

/* The mean of the non-far depths within the circle of radius rad around (x, y); 1 when none. */
static float circle_mean(const float *depth, int w, int h, int x, int y, int rad)
{
    double sum = 0;
    long n = 0;
    int y0 = y - rad < 0 ? 0 : y - rad, y1 = y + rad >= h ? h - 1 : y + rad;
    for (int yy = y0; yy <= y1; yy++) {
        int dy = yy - y, span = (int)floor(sqrt((double)rad * rad - (double)dy * dy));
        int x0 = x - span < 0 ? 0 : x - span, x1 = x + span >= w ? w - 1 : x + span;
        const float *row = depth + (size_t)yy * (size_t)w;
        for (int xx = x0; xx <= x1; xx++)
            if (row[xx] < 1.0f) { sum += row[xx]; n++; } /* the listing's skipFactor: 1 - step(1, d) */
    }
    return n ? (float)(sum / (double)n) : 1.0f;
}

pnpr_status pnpr_depth_inpaint(const pnpr_image *raster, const pnpr_image *filtered, const float *depth,
                               const pnpr_inpaint_options *opts, float *r_depth, uint8_t *r_mask, pnpr_error *err)
{
    if (!same_size(raster, filtered) || (!r_depth && !r_mask) || (r_depth && (!depth || depth == r_depth)))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT,
                              "inpaint: raster and filtered images of one positive size, and a mask or distinct depth buffers needed");
    float thr = opts && opts->threshold != 0 ? opts->threshold : PNPR_INPAINT_THRESHOLD;
    int rad = opts && opts->radius != 0 ? opts->radius : PNPR_INPAINT_RADIUS;
    if (!(thr > 0 && thr <= 1))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "inpaint: threshold %g is outside (0, 1]", (double)thr);
    if (rad < 1 || rad > PNPR_INPAINT_RADIUS_MAX)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "inpaint: radius %d is outside 1..%d", rad,
                              PNPR_INPAINT_RADIUS_MAX);
    int w = raster->width, h = raster->height;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            int masked = fabsf(grey(raster->rgba + 4 * i) - grey(filtered->rgba + 4 * i)) > thr;
            if (r_mask) r_mask[i] = (uint8_t)masked;
            if (!r_depth) continue;
            float d = depth[i];
            if (!(d >= 0.0f && d <= 1.0f)) d = 1.0f; /* NaN or out of range: no fragment */
            r_depth[i] = masked ? circle_mean(depth, w, h, x, y, rad) : d;
        }
    return PNPR_OK;
}

static int out_ok(const pnpr_image *out, const float *depth)
{
    return out && out->rgba && depth && out->width > 0 && out->height > 0 &&
           (size_t)out->width <= ((size_t)1 << 30) / (size_t)out->height;
}

pnpr_status pnpr_layers_clear(const uint8_t background[4], pnpr_image *r_out, float *r_depth, pnpr_error *err)
{
    if (!out_ok(r_out, r_depth)) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "composite: bad output image or depth");
    const uint8_t zero[4] = {0, 0, 0, 0};
    const uint8_t *bg = background ? background : zero;
    size_t n = (size_t)r_out->width * (size_t)r_out->height;
    for (size_t i = 0; i < n; i++) {
        memcpy(r_out->rgba + 4 * i, bg, 4);
        r_depth[i] = 1.0f;
    }
    return PNPR_OK;
}

pnpr_status pnpr_layers_merge(const pnpr_layer *layer, pnpr_layering mode, pnpr_image *r_out, float *r_depth,
                              pnpr_error *err)
{
    if (!out_ok(r_out, r_depth) || !layer || (unsigned)mode >= PNPR_LAYERING_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "composite: bad layer, mode, output image or depth");
    if (!same_size(layer->color, r_out) || !layer->depth || (mode == PNPR_LAYERING_NONE && !layer->changed))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT,
                              "composite: a layer lacks colour, depth or (layering none) its changed mask, or differs in size");
    size_t n = (size_t)r_out->width * (size_t)r_out->height;
    for (size_t i = 0; i < n; i++) {
        float d = layer->depth[i];
        int has = d >= 0.0f && d < 1.0f;
        int take = mode == PNPR_LAYERING_NONE ? has || layer->changed[i] : has && d < r_depth[i];
        if (!take) continue;
        memcpy(r_out->rgba + 4 * i, layer->color->rgba + 4 * i, 3);
        r_out->rgba[4 * i + 3] = 255; /* the layer's alpha is its coverage: what wins is opaque */
        if (has) r_depth[i] = d;
    }
    return PNPR_OK;
}

pnpr_status pnpr_layers_composite(const pnpr_layer *layers, size_t count, pnpr_layering mode,
                                  const uint8_t background[4], pnpr_image *r_out, float *r_depth, pnpr_error *err)
{
    if ((count && !layers) || !r_out || !r_out->rgba || r_out->width <= 0 || r_out->height <= 0 ||
        (size_t)r_out->width > ((size_t)1 << 30) / (size_t)r_out->height || (unsigned)mode >= PNPR_LAYERING_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "composite: bad layers or output image");
    float *depth = r_depth;
    if (!depth && !(depth = malloc((size_t)r_out->width * (size_t)r_out->height * sizeof *depth)))
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "composite: out of memory");
    pnpr_status st = pnpr_layers_clear(background, r_out, depth, err);
    for (size_t l = 0; l < count && st == PNPR_OK; l++) st = pnpr_layers_merge(&layers[l], mode, r_out, depth, err);
    if (depth != r_depth) free(depth);
    return st;
}
