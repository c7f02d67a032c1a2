/* The renderer's options whose cost would grow without bound are refused with a message naming
 * them: spacing_k above PNPR_SPACING_K_MAX (kNN lists of count x k entries), and a snapshot that
 * would take more than PNPR_SNAPSHOT_TILES_MAX tiles (each draws the whole cloud); the largest
 * accepted spacing_k uploads. The automatic depth range of an explicit camera ignores a far
 * outlier (GL-free). Exits 77 (skipped) without headless EGL / GL 3.3. */
#include "testutil.h"

#include <pointnpr/render.h>

#include <stdlib.h>
#include <string.h>

static void test_spacing_k(pnpr_renderer *r, const pnpr_cloud *c)
{
    pnpr_upload_options uo = {0};
    pnpr_error err = {0};
    uo.spacing_k = PNPR_SPACING_K_MAX + 1;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, c, &uo, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "spacing_k 65") != NULL, "message: %s", err.message);
    uo.spacing_k = PNPR_SPACING_K_MAX;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, c, &uo, &err), PNPR_OK);
}

static void test_tiles(pnpr_renderer *r)
{
    enum { S = 2048 };
    uint8_t *rgba = malloc((size_t)S * S * 4);
    pnpr_snapshot_options so = {0};
    pnpr_draw_options o = {0};
    pnpr_error err = {0};
    so.max_tile_size = 16; /* at least (2048 / 16)^2 = 16384 tiles */
    CHECK_STATUS(pnpr_renderer_snapshot(r, NULL, &o, S, S, &so, rgba, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "max_tile_size") != NULL, "message: %s", err.message);
    so.max_tile_size = 256; /* 8 x 8 plus guard bands: accepted */
    CHECK_STATUS(pnpr_renderer_snapshot(r, NULL, &o, S / 4, S / 4, &so, rgba, NULL, &err), PNPR_OK);
    free(rgba);
}

/* An explicit camera 5 units from a unit sphere, with a far point at 1e9 in the cloud: the
 * automatic depth range stays around the sphere (it reached the far point: near plane 1e5, the
 * sphere clipped away). GL-free. */
static void test_depth_range(void)
{
    pnpr_cloud c = {0};
    const double off[3] = {0, 0, 0};
    CHECK_STATUS(pnpr_test_sphere(&c, 2000, 1, off, 5), PNPR_OK);
    c.xyz[3 * (c.count - 1)] = 1e9f;
    pnpr_camera cam = {{0, -5, 0}, {0, 0, 0}, {0, 0, 1}, 45, 0, 0};
    pnpr_camera_matrices m;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_camera_matrices_from_camera(&cam, &c, 400, 300, &m, &err), PNPR_OK);
    const double *P = m.projection, n = P[14] / (P[10] - 1), f = P[14] / (P[10] + 1);
    printf("explicit camera, far point at 1e9: near %g, far %g\n", n, f);
    CHECK(n > 0 && n < 4 && f > 6 && f < 10);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_depth_range();
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_bounds: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    pnpr_cloud c = {0};
    const double off[3] = {0, 0, 0};
    CHECK_STATUS(pnpr_test_sphere(&c, 2000, 1, off, 5), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    if (r) {
        test_spacing_k(r, &c);
        test_tiles(r);
        pnpr_renderer_destroy(r);
    }
    pnpr_cloud_free(&c);
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_bounds");
}
