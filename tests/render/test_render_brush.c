/* The brush style (stroke-based splatting, brush.h) with known answers: a sphere's strokes cover
 * its projected disk (radius from the camera's geometry) without a hole and stay within a few
 * pixels of its outline, in the points' colour; the picture does not depend on the order of the
 * points (order-independent blending: a shuffled cloud gives the same pixels within 1/255); every
 * preset draws; a colourless sphere is shaded; a style map mixes brush with points; a cloud
 * without brush data and a preset out of range are refused with a message.
 * Exits 77 (skipped) when this machine has no headless EGL / GL 3.3. */
#include "testutil.h"

#include <pointnpr/brush.h>
#include <pointnpr/render.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 200, H = 200 };
static const double kOffset[3] = {4.0e6, -2.5e6, 310};

static pnpr_status render(pnpr_renderer *r, const pnpr_draw_options *o, uint8_t *px, pnpr_error *err)
{
    /* eye 4 units from the centre: the sphere's outline is at sin a = 1/4 from the axis */
    pnpr_camera cam = {{kOffset[0], kOffset[1] - 4, kOffset[2]}, {kOffset[0], kOffset[1], kOffset[2]}, {0, 0, 1}, 40, 0, 0};
    pnpr_target t = {0, 0, 0, W, H, 1, 0};
    pnpr_status s = pnpr_renderer_draw(r, &cam, o, &t, NULL, err);
    return s == PNPR_OK ? pnpr_renderer_read_frame(r, px, 0) : s;
}

static void sphere(pnpr_cloud *c, int coloured)
{
    CHECK_STATUS(pnpr_test_sphere(c, 20000, 1.0, kOffset, 7), PNPR_OK);
    if (coloured) {
        CHECK_STATUS(pnpr_cloud_alloc_rgb(c), PNPR_OK);
        for (size_t i = 0; i < c->count; i++) { c->rgb[3 * i] = 200; c->rgb[3 * i + 1] = 60; c->rgb[3 * i + 2] = 40; }
    }
    CHECK_STATUS(pnpr_brush_prepare(c, NULL, NULL, NULL), PNPR_OK);
}

/* Swaps points i and j in every per-point array (src_xyz is dropped). */
static void swap_points(pnpr_cloud *c, size_t i, size_t j)
{
    typedef struct array { void *data; size_t size; } array;
    uint8_t t[16];
    array arr[8] = {{c->xyz, 12}, {c->rgb, 3}, {c->normal, 12}};
    size_t n = 3;
    for (size_t k = 0; k < c->prop_count && n < 8; k++) arr[n++] = (array){c->props[k].data, pnpr_type_size(c->props[k].type)};
    for (size_t k = 0; k < n; k++) {
        if (!arr[k].data) continue;
        uint8_t *p = arr[k].data;
        memcpy(t, p + i * arr[k].size, arr[k].size);
        memcpy(p + i * arr[k].size, p + j * arr[k].size, arr[k].size);
        memcpy(p + j * arr[k].size, t, arr[k].size);
    }
}

static void shuffle(pnpr_cloud *c, uint64_t seed)
{
    pnpr_test_rng rng = {seed};
    free(c->src_xyz);
    c->src_xyz = NULL;
    for (size_t i = c->count - 1; i > 0; i--) swap_points(c, i, (size_t)(pnpr_test_uniform(&rng) * (double)(i + 1)));
}

static int is_paper(const uint8_t *p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }

/* The projected outline's radius in pixels: tan(asin(1/4)) / tan(20 deg) x H / 2. */
static double outline_px(void) { return tan(asin(0.25)) / tan(20 * 3.14159265358979 / 180) * H / 2; }

static pnpr_draw_options brush_options(void)
{
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_BRUSH;
    for (int c = 0; c < 4; c++) o.background[c] = 1;
    return o;
}

/* Paper inside the outline (columns below max_x), paint beyond it (all columns), the mean colour. */
static void test_coverage(const uint8_t *px, int max_x, const char *what)
{
    double R = outline_px(), sum[3] = {0, 0, 0};
    size_t inside = 0, holes = 0, outside = 0, ink_out = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double d = hypot(x + 0.5 - W / 2.0, y + 0.5 - H / 2.0);
            const uint8_t *p = px + 4 * (y * W + x);
            if (d < R - 4 && x < max_x) {
                inside++;
                holes += is_paper(p);
                for (int c = 0; c < 3; c++) sum[c] += p[c];
            } else if (d > R + 6) {
                outside++;
                ink_out += !is_paper(p);
            }
        }
    CHECK_MSG(holes == 0, "%s: %zu of %zu pixels inside the outline show paper", what, holes, inside);
    CHECK_MSG(ink_out * 1000 <= outside, "%s: %zu of %zu pixels beyond the outline + 6 px painted", what, ink_out, outside);
    const double want[3] = {200, 60, 40};
    for (int c = 0; c < 3; c++)
        CHECK_MSG(fabs(sum[c] / (double)inside - want[c]) < 8, "%s: mean channel %d %.1f, the points' %g", what, c,
                  sum[c] / (double)inside, want[c]);
}

static void test_sphere(pnpr_renderer *r)
{
    pnpr_cloud c = {0};
    sphere(&c, 1);
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
    uint8_t *a = malloc(W * H * 4), *b = malloc(W * H * 4);
    pnpr_draw_options o = brush_options();
    for (int preset = 0; preset < PNPR_BRUSH_PRESET_COUNT; preset++) {
        o.brush_preset = preset;
        CHECK_STATUS(render(r, &o, a, &err), PNPR_OK);
        test_coverage(a, W, pnpr_brush_presets(NULL)[preset].name);
    }
    /* the same points (with their sizes, clusters and normals) in another order: the same picture
     * (positions seed each stroke's variant and angle; the blending is order-independent) */
    o.brush_preset = 0;
    for (size_t i = 0; i < c.count; i++) /* colours that vary from stroke to stroke: order would show */
        for (int k = 0; k < 3; k++) c.rgb[3 * i + k] = (uint8_t)(128 + 120 * sin((7 + 2 * k) * c.xyz[3 * i + k]));
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
    CHECK_STATUS(render(r, &o, a, &err), PNPR_OK);
    shuffle(&c, 99);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
    CHECK_STATUS(render(r, &o, b, &err), PNPR_OK);
    int worst = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++) {
        int d = abs((int)a[i] - (int)b[i]);
        if (d > worst) worst = d;
    }
    CHECK_MSG(worst <= 1, "shuffled points: a channel differs by %d", worst);
    /* while moving (--brush-blur): alpha blending in draw order, blurred: the shuffled order shows
     * through less than without the blur, and the picture is smoother (a smaller mean difference
     * between horizontal neighbours) than the order-independent one */
    o.brush_blur = 2;
    CHECK_STATUS(render(r, &o, b, &err), PNPR_OK);
    double grad[2] = {0, 0};
    for (int k = 0; k < 2; k++) {
        const uint8_t *img = k ? b : a;
        for (int y = 0; y < H; y++)
            for (int x = 0; x + 1 < W; x++)
                for (int ch = 0; ch < 3 && hypot(x + 0.5 - W / 2.0, y + 0.5 - H / 2.0) < outline_px() - 6; ch++)
                    grad[k] += abs((int)img[4 * (y * W + x) + ch] - (int)img[4 * (y * W + x + 1) + ch]);
    }
    CHECK_MSG(grad[1] < 0.7 * grad[0], "blurred: neighbour differences %.0f, order-independent %.0f", grad[1], grad[0]);
    size_t painted = 0, disk = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (hypot(x + 0.5 - W / 2.0, y + 0.5 - H / 2.0) < outline_px() - 4) { disk++; painted += !is_paper(b + 4 * (y * W + x)); }
    CHECK_MSG(painted == disk, "blurred: %zu of %zu pixels inside the outline painted", painted, disk);
    o.brush_blur = 9; /* beyond its range */
    CHECK_STATUS(render(r, &o, b, &err), PNPR_ERR_INVALID_ARGUMENT);
    o.brush_blur = 0;
    /* bad presets and scales are refused */
    o.brush_preset = PNPR_BRUSH_PRESET_COUNT;
    CHECK_STATUS(render(r, &o, a, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "preset") != NULL, "message: %s", err.message);
    o.brush_preset = 0;
    o.brush_scale = NAN;
    CHECK_STATUS(render(r, &o, a, &err), PNPR_ERR_INVALID_ARGUMENT);
    free(a);
    free(b);
    pnpr_cloud_free(&c);
}

static void test_colourless_and_missing(pnpr_renderer *r)
{
    pnpr_cloud c = {0};
    sphere(&c, 0);
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
    uint8_t *a = malloc(W * H * 4);
    pnpr_draw_options o = brush_options();
    CHECK_STATUS(render(r, &o, a, &err), PNPR_OK);
    /* shaded by the key light: the greys of the disk spread over more than 60 levels */
    int lo = 255, hi = 0;
    double R = outline_px() - 6;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (hypot(x + 0.5 - W / 2.0, y + 0.5 - H / 2.0) < R) {
                int g = a[4 * (y * W + x)];
                if (g < lo) lo = g;
                if (g > hi) hi = g;
            }
    CHECK_MSG(hi - lo > 60, "colourless sphere: greys %d..%d", lo, hi);
    /* without the brush stage's properties: refused, naming them */
    CHECK_STATUS(pnpr_cloud_remove_property(&c, PNPR_PROP_BRUSH_SIZE), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
    memset(&err, 0, sizeof err);
    CHECK_STATUS(render(r, &o, a, &err), PNPR_ERR_NOT_FOUND);
    CHECK_MSG(strstr(err.message, "brush_size") != NULL, "message: %s", err.message);
    free(a);
    pnpr_cloud_free(&c);
}

/* A style map: the left half (label 1, seen on the image's left) in brush, the rest in points. */
static void test_style_map(pnpr_renderer *r)
{
    pnpr_cloud c = {0};
    sphere(&c, 1);
    CHECK_STATUS(pnpr_cloud_alloc_labels(&c), PNPR_OK);
    for (size_t i = 0; i < c.count; i++) c.label[i] = c.xyz[3 * i] < 0;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
    uint8_t *a = malloc(W * H * 4);
    pnpr_draw_options o = brush_options();
    o.style = PNPR_STYLE_POINTS;
    pnpr_style_map_entry map[1] = {{1, PNPR_STYLE_BRUSH}};
    o.style_map = map;
    o.style_map_count = 1;
    CHECK_STATUS(render(r, &o, a, &err), PNPR_OK);
    test_coverage(a, W / 2 - 8, "style map"); /* the points' half (and its seam) has gaps between splats */
    free(a);
    pnpr_cloud_free(&c);
}

int main(void)
{
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_brush: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    if (r) {
        test_sphere(r);
        test_colourless_and_missing(r);
        test_style_map(r);
        pnpr_renderer_destroy(r);
    }
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_brush");
}
