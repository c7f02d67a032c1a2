/* Depth inpainting (Wegen et al., listing 1) and layer compositing (effects/composite.c) on
 * small images with known answers. */
#include "testutil.h"

#include <pointnpr/effects.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 40, H = 30 };

static void fill(pnpr_image *im, uint8_t r, uint8_t g, uint8_t b)
{
    for (int i = 0; i < im->width * im->height; i++) {
        im->rgba[4 * i] = r;
        im->rgba[4 * i + 1] = g;
        im->rgba[4 * i + 2] = b;
        im->rgba[4 * i + 3] = 255;
    }
}

static void put(pnpr_image *im, int x, int y, uint8_t v)
{
    uint8_t *p = im->rgba + 4 * ((size_t)y * (size_t)im->width + (size_t)x);
    p[0] = p[1] = p[2] = v;
}

/* A square segment [x0, x1) x [y0, y1) at depth d on a white far background; `filtered` adds a
 * black ring `ring` px wide outside it (an outline a filter drew where the segment has no depth). */
static void square_layer(pnpr_image *raster, pnpr_image *filtered, float *depth, int x0, int x1, int y0, int y1,
                         float d, int ring, uint8_t v)
{
    fill(raster, 255, 255, 255);
    fill(filtered, 255, 255, 255);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int in = x >= x0 && x < x1 && y >= y0 && y < y1;
            int near = x >= x0 - ring && x < x1 + ring && y >= y0 - ring && y < y1 + ring;
            depth[y * W + x] = in ? d : 1.0f;
            if (in) { put(raster, x, y, v); put(filtered, x, y, v); }
            else if (near) put(filtered, x, y, 0);
        }
}

static void test_inpaint_ring(void)
{
    uint8_t a[W * H * 4], b[W * H * 4], mask[W * H];
    pnpr_image raster = {W, H, a}, filtered = {W, H, b};
    float depth[W * H], out[W * H];
    square_layer(&raster, &filtered, depth, 10, 20, 10, 20, 0.3f, 2, 128);
    pnpr_inpaint_options o = {0.05f, 3};
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, depth, &o, out, mask, NULL), PNPR_OK);
    int ring = 0, ring_filled = 0, far_kept = 0, far = 0, inside_kept = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            int in = x >= 10 && x < 20 && y >= 10 && y < 20;
            int near = x >= 8 && x < 22 && y >= 8 && y < 22;
            if (in) inside_kept += out[i] == 0.3f && !mask[i];
            else if (near) { ring++; ring_filled += mask[i] && fabsf(out[i] - 0.3f) < 1e-6f; }
            else { far++; far_kept += out[i] == 1.0f && !mask[i]; }
        }
    CHECK_MSG(inside_kept == 100, "unchanged pixels keep their depth: %d of 100", inside_kept);
    /* every ring pixel is within 3 px of the square (corners: sqrt(2*2*2) < 3): the segment's depth only */
    CHECK_MSG(ring == 14 * 14 - 100 && ring_filled == ring, "ring %d, filled with 0.3: %d", ring, ring_filled);
    CHECK_MSG(far_kept == far, "unmasked far pixels stay far: %d of %d", far_kept, far);
    /* the mask alone (no depth out) is the same mask */
    uint8_t mask_only[W * H];
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, NULL, &o, NULL, mask_only, NULL), PNPR_OK);
    CHECK(!memcmp(mask, mask_only, sizeof mask));
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, depth, &o, NULL, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);

    /* a radius too small to reach the segment: the masked pixel stays far (the listing divides by 0) */
    square_layer(&raster, &filtered, depth, 10, 20, 10, 20, 0.3f, 3, 128);
    o.radius = 1;
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, depth, &o, out, mask, NULL), PNPR_OK);
    CHECK_MSG(mask[7 * W + 15] == 1 && out[7 * W + 15] == 1.0f, "3 px out with radius 1: masked %d depth %g",
              mask[7 * W + 15], (double)out[7 * W + 15]);
    CHECK_MSG(fabsf(out[9 * W + 15] - 0.3f) < 1e-6f, "1 px out with radius 1: %g", (double)out[9 * W + 15]);
    /* the mean is over non-far pixels only: a pixel 1 px out, between depths 0.3 and far */
    o.radius = 2;
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, depth, &o, out, NULL, NULL), PNPR_OK);
    CHECK_MSG(fabsf(out[9 * W + 15] - 0.3f) < 1e-6f, "mean of the segment's depths only: %g", (double)out[9 * W + 15]);
}

static void test_inpaint_threshold_and_errors(void)
{
    uint8_t a[W * H * 4], b[W * H * 4];
    pnpr_image raster = {W, H, a}, filtered = {W, H, b};
    float depth[W * H], out[W * H];
    square_layer(&raster, &filtered, depth, 10, 20, 10, 20, 0.3f, 2, 128);
    for (int i = 0; i < W * H; i++) /* a grey shift of 10/255 = 0.039 everywhere */
        for (int c = 0; c < 3; c++) b[4 * i + c] = a[4 * i + c] > 10 ? (uint8_t)(a[4 * i + c] - 10) : a[4 * i + c];
    pnpr_inpaint_options o = {0.05f, 3};
    uint8_t mask[W * H];
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, depth, &o, out, mask, NULL), PNPR_OK);
    size_t masked = 0;
    for (int i = 0; i < W * H; i++) masked += mask[i];
    CHECK_MSG(masked == 0, "a change of 0.039 under threshold 0.05 masks nothing: %zu", masked);
    o.threshold = 0.03f;
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, depth, &o, out, mask, NULL), PNPR_OK);
    masked = 0;
    for (int i = 0; i < W * H; i++) masked += mask[i];
    CHECK_MSG(masked == W * H, "over threshold 0.03 every pixel: %zu", masked);
    pnpr_error err;
    o.radius = PNPR_INPAINT_RADIUS_MAX + 1;
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, depth, &o, out, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "radius") != NULL);
    o.radius = 3;
    o.threshold = NAN;
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, depth, &o, out, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, depth, NULL, depth, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_image small = {W - 1, H, a};
    CHECK_STATUS(pnpr_depth_inpaint(&small, &filtered, depth, NULL, out, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    /* NaN depths read as far */
    square_layer(&raster, &filtered, depth, 10, 20, 10, 20, 0.3f, 0, 128);
    depth[0] = NAN;
    CHECK_STATUS(pnpr_depth_inpaint(&raster, &filtered, depth, NULL, out, NULL, NULL), PNPR_OK);
    CHECK(out[0] == 1.0f);
}

/* Segment A (grey 100, depth 0.3) in front of segment B (grey 200, depth 0.6, covering the left
 * half); A's filter drew a black ring 2 px wide. */
static void test_composite_modes(void)
{
    uint8_t ra[W * H * 4], fa[W * H * 4], rb[W * H * 4], fb[W * H * 4], out_px[W * H * 4], mask_a[W * H], mask_b[W * H];
    pnpr_image rasA = {W, H, ra}, filA = {W, H, fa}, rasB = {W, H, rb}, filB = {W, H, fb}, out = {W, H, out_px};
    float dA[W * H], dB[W * H], iA[W * H], iB[W * H], zbuf[W * H];
    square_layer(&rasA, &filA, dA, 10, 20, 10, 20, 0.3f, 2, 100);
    square_layer(&rasB, &filB, dB, 0, 20, 0, H, 0.6f, 0, 200);
    pnpr_inpaint_options o = {0.05f, 3};
    CHECK_STATUS(pnpr_depth_inpaint(&rasA, &filA, dA, &o, iA, mask_a, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_depth_inpaint(&rasB, &filB, dB, &o, iB, mask_b, NULL), PNPR_OK);
    const uint8_t bg[4] = {255, 255, 255, 255};
    /* B first, A second and the other way round: the depth test gives the same picture */
    for (int order = 0; order < 2; order++) {
        pnpr_layer L[2] = {{&filB, iB, mask_b}, {&filA, iA, mask_a}};
        if (order) { pnpr_layer t = L[0]; L[0] = L[1]; L[1] = t; }
        CHECK_STATUS(pnpr_layers_composite(L, 2, PNPR_LAYERING_INPAINTED, bg, &out, zbuf, NULL), PNPR_OK);
        CHECK_MSG(out_px[4 * (15 * W + 15)] == 100 && zbuf[15 * W + 15] == 0.3f, "A occludes B (order %d)", order);
        CHECK_MSG(out_px[4 * (15 * W + 9)] == 0, "A's ring over B (order %d): %d", order, out_px[4 * (15 * W + 9)]);
        CHECK_MSG(out_px[4 * (15 * W + 21)] == 0, "A's ring over the background (order %d)", order);
        CHECK_MSG(out_px[4 * (3 * W + 5)] == 200, "B elsewhere (order %d)", order);
        CHECK_MSG(out_px[4 * (3 * W + 30)] == 255 && zbuf[3 * W + 30] == 1.0f, "background (order %d)", order);
    }
    /* per-fragment test on the rasterised depths: the ring has no depth and is lost */
    pnpr_layer F[2] = {{&filB, dB, mask_b}, {&filA, dA, mask_a}};
    CHECK_STATUS(pnpr_layers_composite(F, 2, PNPR_LAYERING_FRAGMENT, bg, &out, NULL, NULL), PNPR_OK);
    CHECK_MSG(out_px[4 * (15 * W + 9)] == 200 && out_px[4 * (15 * W + 21)] == 255, "fragment: ring lost (%d, %d)",
              out_px[4 * (15 * W + 9)], out_px[4 * (15 * W + 21)]);
    CHECK(out_px[4 * (15 * W + 15)] == 100);
    /* no depth test: in order, the later layer on top wherever it has a fragment or changed a pixel */
    pnpr_layer N[2] = {{&filA, dA, mask_a}, {&filB, dB, mask_b}};
    CHECK_STATUS(pnpr_layers_composite(N, 2, PNPR_LAYERING_NONE, bg, &out, NULL, NULL), PNPR_OK);
    CHECK_MSG(out_px[4 * (15 * W + 15)] == 200, "none: B painted over A");
    CHECK_MSG(out_px[4 * (15 * W + 21)] == 0, "none: A's ring where B has nothing");
    /* the incremental form equals the whole */
    uint8_t inc_px[W * H * 4];
    pnpr_image inc = {W, H, inc_px};
    float z2[W * H];
    pnpr_layer I[2] = {{&filB, iB, mask_b}, {&filA, iA, mask_a}};
    CHECK_STATUS(pnpr_layers_composite(I, 2, PNPR_LAYERING_INPAINTED, bg, &out, zbuf, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_layers_clear(bg, &inc, z2, NULL), PNPR_OK);
    for (int l = 0; l < 2; l++) CHECK_STATUS(pnpr_layers_merge(&I[l], PNPR_LAYERING_INPAINTED, &inc, z2, NULL), PNPR_OK);
    CHECK(!memcmp(inc_px, out_px, sizeof inc_px) && !memcmp(z2, zbuf, sizeof z2));
    /* errors */
    pnpr_layer bad = {&filA, NULL, NULL};
    CHECK_STATUS(pnpr_layers_composite(&bad, 1, PNPR_LAYERING_INPAINTED, bg, &out, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_layer nomask = {&filA, dA, NULL};
    CHECK_STATUS(pnpr_layers_composite(&nomask, 1, PNPR_LAYERING_NONE, bg, &out, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_layers_composite(NULL, 0, PNPR_LAYERING_COUNT_, bg, &out, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_layers_composite(NULL, 0, PNPR_LAYERING_NONE, NULL, &out, NULL, NULL), PNPR_OK);
    CHECK(out_px[0] == 0 && out_px[3] == 0);
}

static void test_layering_names(void)
{
    for (int m = 0; m < PNPR_LAYERING_COUNT_; m++) {
        pnpr_layering back;
        CHECK_STATUS(pnpr_layering_from_name(pnpr_layering_name((pnpr_layering)m), &back), PNPR_OK);
        CHECK(back == (pnpr_layering)m);
    }
    pnpr_layering x;
    CHECK_STATUS(pnpr_layering_from_name("Inpainted", &x), PNPR_OK);
    CHECK_STATUS(pnpr_layering_from_name("depth", &x), PNPR_ERR_NOT_FOUND);
    CHECK(!strcmp(pnpr_layering_name(PNPR_LAYERING_COUNT_), ""));
}

int main(void)
{
    test_inpaint_ring();
    test_inpaint_threshold_and_errors();
    test_composite_modes();
    test_layering_names();
    return pnpr_test_finish("test_effects_composite");
}
