/* Temporal coherence (issue 16): the mean per-pixel change between consecutive frames of a slow
 * orbit (0.5 degrees a frame, the orbit preset around the preset start of the generated house
 * scene, bench/quality, sparse), for every style, relative to the plain `points` style on the
 * same path. Issue 16 asks sketchy <= 1.5x points: asserted at 160x120 and 320x240 (measured
 * 1.44x and 1.39x since the hatches follow the surface and the tone hatches are lighter,
 * docs/export.md), and that the directional strokes alone (variant a) stay below points. The
 * figures are printed for docs.
 * Per-point stroke randomness is seeded by the point (its queue position, fixed at upload), so
 * a still camera gives identical frames: checked too. Writes the scene (with its features) to
 * SCRATCH/coherence-scene.ply for docs/export.md. Exits 77 (skipped) without headless GL. */
#include "testutil.h"
#include "quality.h"

#include <pointnpr/brush.h>
#include <pointnpr/camera_path.h>
#include <pointnpr/features.h>
#include <pointnpr/io.h>
#include <pointnpr/lines.h>
#include <pointnpr/render.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 160, H = 120, FRAMES = 7 };

/* Mean |a - b| over the RGB channels of n pixels, in 0..1. */
static double mean_change(const uint8_t *a, const uint8_t *b, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) s += abs((int)a[4 * i + c] - (int)b[4 * i + c]);
    return s / (3.0 * 255.0 * n);
}

/* The mean change over FRAMES-1 consecutive pairs of the orbit in `style` at w x h (px holds two
 * frames of that size); -1 on failure. */
static double orbit_change_at(pnpr_renderer *r, const pnpr_camera_path *path, pnpr_style style, pnpr_sketch_variant variant,
                              int w, int h, uint8_t *px[2])
{
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = style;
    o.sketch_variant = variant;
    o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
    pnpr_error err = {0};
    double sum = 0;
    for (int k = 0; k < FRAMES; k++) {
        pnpr_camera cam;
        CHECK_STATUS(pnpr_camera_path_eval(path, (double)k, &cam), PNPR_OK);
        pnpr_status st = pnpr_renderer_snapshot(r, &cam, &o, w, h, NULL, px[k & 1], NULL, &err);
        if (st != PNPR_OK) { fprintf(stderr, "%s: %s\n", pnpr_style_name(style), err.message); return -1; }
        if (k > 0) sum += mean_change(px[0], px[1], w * h);
    }
    return sum / (FRAMES - 1);
}

static double orbit_change(pnpr_renderer *r, const pnpr_camera_path *path, pnpr_style style, pnpr_sketch_variant variant,
                           uint8_t *px[2])
{
    return orbit_change_at(r, path, style, variant, W, H, px);
}

/* Pixels that change between two frames by more than a fading mark changes them in a frame (2/10
 * of the range, check_fade): a pop. */
static size_t pops(const uint8_t *a, const uint8_t *b, int n)
{
    size_t p = 0;
    for (int i = 0; i < n; i++) {
        int d = 0;
        for (int c = 0; c < 3; c++) d = abs((int)a[4 * i + c] - (int)b[4 * i + c]) > d ? abs((int)a[4 * i + c] - (int)b[4 * i + c]) : d;
        p += d > 52;
    }
    return p;
}

/* The queue's fade-in (pnpr_draw_options.queue_fade): a still view whose budget grows by 2% a
 * frame (as an animated --budget does). Strokes and dots that pop in change their pixels at once
 * by the full ink; fading in (the default, over the last 10% of the prefix) they darken by at most
 * 2/10 of it a frame. Pixels still pop where the mask's disks, which grow as fewer points are
 * drawn (the queue's lod), uncover or hide a mark: measured 41 of 52 (sketchy; antialiased
 * strokes ink most pixels in part, so fewer pop at all) and 53 of 77 (stipple) pops remain
 * (with the per-cell queues; one queue for all: 41 of 59 and 55 of 100), asserted below 0.85;
 * a longer fade leaves fewer (sketchy 39 at 0.2, 32 at 0.4). Without a budget the fade changes
 * nothing. */
static void check_fade(pnpr_renderer *r, const pnpr_camera_path *path, uint8_t *px[2])
{
    pnpr_camera start;
    CHECK_STATUS(pnpr_camera_path_eval(path, 0, &start), PNPR_OK);
    const pnpr_style styles[2] = {PNPR_STYLE_SKETCHY, PNPR_STYLE_STIPPLE};
    for (int s = 0; s < 2; s++) {
        size_t popped[2] = {0, 0};
        for (int fade = 0; fade < 2; fade++) {
            pnpr_draw_options o;
            memset(&o, 0, sizeof o);
            o.style = styles[s];
            o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
            o.queue_fade = fade ? 0 : -1; /* 0: the default fade; -1: none */
            o.density = -1;               /* the budget alone sets the prefix */
            for (int k = 0; k < FRAMES; k++) {
                o.budget = (size_t)(10000 * (1 + 0.02 * k));
                CHECK_STATUS(pnpr_renderer_snapshot(r, &start, &o, W, H, NULL, px[k & 1], NULL, NULL), PNPR_OK);
                if (k > 0) popped[fade] += pops(px[0], px[1], W * H);
            }
        }
        printf("  budget growing 2%% a frame, %s: %zu pixels pop without the fade, %zu with it\n", pnpr_style_name(styles[s]),
               popped[0], popped[1]);
        CHECK_MSG(popped[0] > 50 && popped[1] < 0.85 * popped[0], "%s: %zu pixels pop with the fade, %zu without",
                  pnpr_style_name(styles[s]), popped[1], popped[0]);
    }
    /* everything drawn: no fade at all, the same pixels */
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_SKETCHY;
    o.density = -1;
    CHECK_STATUS(pnpr_renderer_snapshot(r, &start, &o, W, H, NULL, px[0], NULL, NULL), PNPR_OK);
    o.queue_fade = -1;
    CHECK_STATUS(pnpr_renderer_snapshot(r, &start, &o, W, H, NULL, px[1], NULL, NULL), PNPR_OK);
    CHECK_MSG(!memcmp(px[0], px[1], (size_t)W * H * 4), "the fade changed a frame that draws every point");
    o.queue_fade = NAN;
    CHECK_STATUS(pnpr_renderer_snapshot(r, &start, &o, W, H, NULL, px[1], NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
}

/* Sketchy against points at twice the size (320 x 240): the bound holds there too. */
static void check_larger(pnpr_renderer *r, const pnpr_camera_path *path)
{
    uint8_t *big[2] = {malloc((size_t)4 * W * H * 4), malloc((size_t)4 * W * H * 4)};
    if (big[0] && big[1]) {
        double base = orbit_change_at(r, path, PNPR_STYLE_POINTS, PNPR_SKETCH_ALL, 2 * W, 2 * H, big);
        double v = orbit_change_at(r, path, PNPR_STYLE_SKETCHY, PNPR_SKETCH_ALL, 2 * W, 2 * H, big);
        printf("  %dx%d: points %.4f, sketchy %.4f (%.2fx)\n", 2 * W, 2 * H, base, v, v / base);
        CHECK_MSG(base > 0 && v >= 0 && v <= 1.5 * base, "sketchy changes %.2fx as much as points at %dx%d", v / base, 2 * W, 2 * H);
    }
    free(big[0]);
    free(big[1]);
}

/* A still camera: two frames of the same view are the same pixels (nothing depends on the frame). */
static void check_still(pnpr_renderer *r, const pnpr_camera_path *path, uint8_t *px[2])
{
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_SKETCHY;
    pnpr_camera cam;
    CHECK_STATUS(pnpr_camera_path_eval(path, 0, &cam), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, NULL, px[0], NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_camera_path_eval(path, 3, &cam), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, NULL, px[1], NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_camera_path_eval(path, 0, &cam), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, NULL, px[1], NULL, NULL), PNPR_OK);
    CHECK_MSG(!memcmp(px[0], px[1], (size_t)W * H * 4), "the same view drawn again differs");
}

/* The scene with features and profile lines uploaded; the slow orbit around its preset start. */
static int prepare(pnpr_renderer *r, pnpr_cloud *c, pnpr_sphere_tree *tree, pnpr_camera_path *path)
{
    pnpr_quality_scene scene;
    pnpr_quality_scene_init(&scene, PNPR_QUALITY_PRESET_SPARSE);
    CHECK_STATUS(pnpr_quality_scan(&scene, 0, c, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(c, NULL, NULL), PNPR_OK);
    pnpr_error err = {0};
    /* the scene as a file, for the pictures of docs/export.md (pointnpr animate) */
    CHECK_STATUS(pnpr_write_file(PNPR_TEST_SCRATCH "/coherence-scene.ply", c, NULL, &err), PNPR_OK);
    CHECK_STATUS(pnpr_brush_prepare(c, NULL, NULL, NULL), PNPR_OK); /* the brush style's data */
    CHECK_STATUS(pnpr_sphere_tree_build(c, NULL, tree, NULL, NULL), PNPR_OK); /* the hierarchy style's */
    CHECK_STATUS(pnpr_renderer_set_cloud(r, c, NULL, &err), PNPR_OK);
    pnpr_renderer_set_hierarchy(r, tree);
    pnpr_polylines lines = {0};
    CHECK_STATUS(pnpr_profile_lines(c, NULL, &lines, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_lines(r, &lines, &err), PNPR_OK);
    pnpr_lines_free(&lines);
    pnpr_camera start;
    double up[3];
    CHECK_STATUS(pnpr_camera_preset_start(c, NULL, 45, (float)W / H, &start, up), PNPR_OK);
    pnpr_camera_preset_options po = {720, 360}; /* 0.5 degrees a second, one frame a second */
    CHECK_STATUS(pnpr_camera_path_preset(PNPR_PRESET_ORBIT, &start, up, &po, path, &err), PNPR_OK);
    return pnpr_test_failures == 0;
}

int main(void)
{
    pnpr_error err = {0};
    pnpr_gl_context *ctx = NULL;
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_coherence: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    pnpr_cloud c = {0};
    pnpr_camera_path path = {0};
    uint8_t *px[2] = {malloc((size_t)W * H * 4), malloc((size_t)W * H * 4)};
    pnpr_sphere_tree tree = {0};
    if (r && px[0] && px[1] && prepare(r, &c, &tree, &path)) {
        check_still(r, &path, px);
        double base = orbit_change(r, &path, PNPR_STYLE_POINTS, PNPR_SKETCH_ALL, px);
        CHECK(base > 0);
        printf("coherence, %zu points, %dx%d, orbit 0.5 deg/frame, mean per-pixel change (x points):\n", c.count, W, H);
        for (int s = 0; s < PNPR_STYLE_COUNT_; s++) {
            double v = s == PNPR_STYLE_POINTS ? base : orbit_change(r, &path, (pnpr_style)s, PNPR_SKETCH_ALL, px);
            CHECK(v >= 0);
            printf("  %-10s %.4f (%.2fx)\n", pnpr_style_name((pnpr_style)s), v, v / base);
            if (s == PNPR_STYLE_SKETCHY) CHECK_MSG(v <= 1.5 * base, "sketchy changes %.2fx as much as points", v / base);
        }
        double va = orbit_change(r, &path, PNPR_STYLE_SKETCHY, PNPR_SKETCH_DIRECTIONAL, px);
        double vb = orbit_change(r, &path, PNPR_STYLE_SKETCHY, PNPR_SKETCH_NONDIRECTIONAL, px);
        printf("  sketchy a  %.4f (%.2fx)\n  sketchy b  %.4f (%.2fx)\n", va, va / base, vb, vb / base);
        CHECK_MSG(va >= 0 && va < base, "directional strokes alone change %.2fx as much as points", va / base);
        check_larger(r, &path);
        check_fade(r, &path, px);
    }
    free(px[0]);
    free(px[1]);
    pnpr_camera_path_free(&path);
    pnpr_cloud_free(&c);
    pnpr_renderer_destroy(r);
    pnpr_sphere_tree_free(&tree);
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_coherence");
}
