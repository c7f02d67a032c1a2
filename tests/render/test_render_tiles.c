/* Tiled snapshots (pnpr_renderer_snapshot) with known answers: an image rendered in forced
 * 64-pixel tiles equals the same image rendered as one frame (mean absolute difference per
 * channel < 1/255, i.e. < 1 level; > 99.5 % of the pixels within 2 levels in every channel) for
 * `points` and `sketchy`, with and without a budget; progress once per tile, cancel; images within the limit are exactly one frame; the
 * memory check of pnpr_image_bytes. Exits 77 (skipped) without headless EGL / GL 3.3. */
#include "testutil.h"

#include <pointnpr/features.h>
#include <pointnpr/render.h>

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 240, H = 200 };

typedef struct tile_count { int calls; int cancel_at; } tile_count;
static int count_tiles(void *user, const char *stage, double fraction)
{
    tile_count *t = user;
    (void)fraction;
    CHECK(strncmp(stage, "tile ", 5) == 0);
    t->calls++;
    return t->cancel_at > 0 && t->calls >= t->cancel_at;
}

static void compare(const uint8_t *a, const uint8_t *b, const char *what)
{
    double sum = 0;
    size_t close = 0, n = (size_t)W * H;
    for (size_t i = 0; i < n; i++) {
        int worst = 0;
        for (int c = 0; c < 4; c++) {
            int d = abs((int)a[4 * i + c] - (int)b[4 * i + c]);
            sum += d;
            if (d > worst) worst = d;
        }
        close += worst <= 2;
    }
    double mad = sum / (4.0 * (double)n);
    double frac = (double)close / (double)n;
    fprintf(stderr, "%s: tiled vs one frame: mean abs diff %.4f levels, %.3f %% of pixels within 2 levels\n",
            what, mad, 100 * frac);
    CHECK_MSG(mad < 1.0, "%s: mean abs difference %.4f levels", what, mad);
    CHECK_MSG(frac > 0.995, "%s: %.4f of the pixels within 2 levels", what, frac);
}

static void test_tiles(pnpr_renderer *r)
{
    /* a coloured noisy cube (features for sketchy) seen from a corner, filling the image */
    pnpr_cloud c = {0};
    const double off[3] = {1000.5, -2000.25, 30};
    CHECK_STATUS(pnpr_test_cube(&c, 1.0, 0.02, 0.002, off, 7), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    float lo[3], hi[3];
    CHECK(pnpr_cloud_bounds(&c, lo, hi) != 0);
    for (size_t i = 0; i < c.count; i++)
        for (int a = 0; a < 3; a++) {
            double t = (c.xyz[3 * i + a] - lo[a]) / (hi[a] - lo[a]); /* 0..1 across the cube */
            c.rgb[3 * i + a] = (uint8_t)(40 + 200 * (t < 0 ? 0 : t > 1 ? 1 : t));
        }
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    pnpr_camera cam = {{0}, {0}, {0, 0, 1}, 40, 0, 0};
    for (int a = 0; a < 3; a++) {
        cam.target[a] = off[a] + 0.5;
        cam.eye[a] = off[a] + 0.5 + (a == 0 ? 1.7 : a == 1 ? -2.1 : 1.4);
    }
    uint8_t *one = malloc(W * H * 4), *tiled = malloc(W * H * 4);
    pnpr_style styles[2] = {PNPR_STYLE_POINTS, PNPR_STYLE_SKETCHY};
    for (int s = 0; s < 2; s++) {
        pnpr_draw_options o;
        memset(&o, 0, sizeof o);
        o.style = styles[s];
        o.background[0] = 0.9f; o.background[1] = 0.95f; o.background[2] = 1; o.background[3] = 1;
        pnpr_target t = {0, 0, 0, W, H, 1, 0};
        pnpr_error err = {0};
        pnpr_render_stats st1, st2;
        CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, &st1, &err), PNPR_OK);
        CHECK_STATUS(pnpr_renderer_read_frame(r, one, 0), PNPR_OK);
        pnpr_snapshot_options so;
        memset(&so, 0, sizeof so);
        so.max_tile_size = 64;
        tile_count tc = {0, 0};
        so.progress.fn = count_tiles;
        so.progress.user = &tc;
        memset(tiled, 0, W * H * 4);
        CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, &so, tiled, &st2, &err), PNPR_OK);
        CHECK_MSG(tc.calls >= 20, "%d tiles of 64 px for %dx%d", tc.calls, W, H);
        CHECK(st2.points_drawn == st1.points_drawn);
        compare(one, tiled, pnpr_style_name(styles[s]));
        /* the same with a budget: the queue counts are the full image's in every tile */
        o.budget = c.count / 3;
        CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, &st1, &err), PNPR_OK);
        CHECK_STATUS(pnpr_renderer_read_frame(r, one, 0), PNPR_OK);
        CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, &so, tiled, &st2, &err), PNPR_OK);
        /* the budget caps the vertices sent; the cells' shares differ with depth, so fewer are
         * drawn (measured 4491 of 5000) */
        CHECK_MSG(st2.points_drawn == st1.points_drawn && st1.points_drawn <= c.count / 3 &&
                      st1.points_drawn >= 0.85 * (double)(c.count / 3), "budget %zu: %zu drawn, tiled %zu", c.count / 3,
                  st1.points_drawn, st2.points_drawn);
        compare(one, tiled, "budget");
        /* within the limit: one frame, byte-identical to draw + read_frame */
        so.max_tile_size = 0;
        tc.calls = 0;
        CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, &so, tiled, NULL, &err), PNPR_OK);
        CHECK(tc.calls == 1);
        CHECK(memcmp(one, tiled, W * H * 4) == 0);
        /* cancel after the 3rd tile */
        so.max_tile_size = 64;
        tc.calls = 0;
        tc.cancel_at = 3;
        CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, &so, tiled, NULL, &err), PNPR_ERR_CANCELLED);
        CHECK(tc.calls == 3);
    }
    /* bad arguments */
    pnpr_snapshot_options so;
    memset(&so, 0, sizeof so);
    so.max_tile_size = -1;
    CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, NULL, W, H, &so, tiled, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, NULL, 0, H, NULL, tiled, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, NULL, W, H, NULL, NULL, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    /* over the GL limit, pnpr_renderer_draw refuses and names the snapshot */
    pnpr_target big = {0, 0, 0, pnpr_renderer_max_size(r) + 1, 8, 1, 0};
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, NULL, &big, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "snapshot") != NULL);
    free(one);
    free(tiled);
    pnpr_cloud_free(&c);
}

static void test_image_bytes(void)
{
    size_t b = 1;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_image_bytes(7680, 4320, 0, &b, &err), PNPR_OK);
    CHECK(b == (size_t)7680 * 4320 * 4);
    CHECK_STATUS(pnpr_image_bytes(100000, 100000, 0, &b, &err), PNPR_ERR_OUT_OF_MEMORY);
    CHECK(b == 0 && strstr(err.message, "GiB") != NULL);
    CHECK_STATUS(pnpr_image_bytes(INT_MAX, INT_MAX, SIZE_MAX, &b, &err), sizeof(size_t) > 4 ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY);
    CHECK_STATUS(pnpr_image_bytes(1000, 1000, 1000, &b, &err), PNPR_ERR_OUT_OF_MEMORY);
    CHECK_STATUS(pnpr_image_bytes(0, 10, 0, &b, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_image_bytes(10, -1, 0, &b, &err), PNPR_ERR_INVALID_ARGUMENT);
}

int main(void)
{
    test_image_bytes();
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_tiles: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    if (r) {
        test_tiles(r);
        pnpr_renderer_destroy(r);
    }
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_tiles");
}
