/* Zeroed draw and upload options render exactly what pnpr_draw_defaults() / pnpr_upload_defaults()
 * passed explicitly render (options.h: the renderer's defaults come from its tables), for every
 * style: snapshots compared bytewise. Exits 77 (skipped) without headless EGL / GL 3.3. */
#include "testutil.h"

#include <pointnpr/brush.h>
#include <pointnpr/features.h>
#include <pointnpr/options.h>
#include <pointnpr/render.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 160, H = 120 };

static void snapshot(pnpr_renderer *r, const pnpr_draw_options *o, uint8_t *px)
{
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_snapshot(r, NULL, o, W, H, NULL, px, NULL, &err), PNPR_OK);
}

int main(void)
{
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_defaults: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    pnpr_cloud c = {0};
    const double off[3] = {0, 0, 0};
    CHECK_STATUS(pnpr_test_plane(&c, 60, 40, 0.025, off), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    for (size_t i = 0; i < c.count; i++)
        for (int k = 0; k < 3; k++) c.rgb[3 * i + k] = (uint8_t)((i * (k + 3) * 37) % 230);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_brush_prepare(&c, NULL, NULL, NULL), PNPR_OK); /* the brush style's data */
    pnpr_sphere_tree tree = {0};
    CHECK_STATUS(pnpr_sphere_tree_build(&c, NULL, &tree, NULL, NULL), PNPR_OK); /* the hierarchy style's */
    uint8_t *a = malloc(W * H * 4), *b = malloc(W * H * 4);
    const pnpr_upload_options uz = {0}, ud = pnpr_upload_defaults();
    for (int u = 0; r && u < 2; u++) {
        /* the upload: zeroed, then the defaults written out; each frame the same either way */
        CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, u ? &ud : &uz, NULL), PNPR_OK);
        pnpr_renderer_set_hierarchy(r, &tree);
        for (int s = 0; s < PNPR_STYLE_COUNT_; s++) {
            pnpr_draw_options z = {0}, d = pnpr_draw_defaults();
            z.style = d.style = (pnpr_style)s;
            z.budget = d.budget = c.count / 2; /* the queue fade too */
            snapshot(r, &z, a);
            snapshot(r, &d, b);
            CHECK_MSG(memcmp(a, b, W * H * 4) == 0, "style %s, upload %s: zeroed options and pnpr_draw_defaults() differ",
                      pnpr_style_name((pnpr_style)s), u ? "defaults" : "zeroed");
        }
    }
    free(a);
    free(b);
    pnpr_cloud_free(&c);
    pnpr_sphere_tree_free(&tree);
    pnpr_renderer_destroy(r);
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_defaults");
}
