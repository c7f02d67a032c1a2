/* The headless context's two EGL platforms (render/egl_context.c): PNPR_GL_DEVICE=device takes
 * EGL's device platform (on a machine without a GPU, Mesa's software device), =software Mesa's
 * surfaceless platform. Both render the same frame of a coloured sphere; when both are llvmpipe
 * (the same GL_RENDERER) the frames are byte-identical. A forced device that EGL does not list
 * fails with a message that names it. Unset, llvmpipe comes through the surfaceless platform (the
 * software device is not taken for a GPU). */
#include "testutil.h"

#include <pointnpr/render.h>

#include <epoxy/gl.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 160, H = 120 };

/* Renders the sphere on the platform PNPR_GL_DEVICE=want; 1 when it rendered, 0 when the context
 * could not be had (its message in r_why), -1 on a failed draw. */
static int frame_on(const char *want, const pnpr_cloud *c, uint8_t *px, char *r_renderer, char *r_why,
                    const char **r_platform)
{
    if (want) setenv("PNPR_GL_DEVICE", want, 1);
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        snprintf(r_why, 256, "%.200s", err.message);
        return 0;
    }
    *r_platform = pnpr_gl_context_platform(ctx);
    snprintf(r_renderer, 256, "%.200s", (const char *)glGetString(GL_RENDERER));
    pnpr_renderer *r = NULL;
    int ok = pnpr_renderer_create(NULL, &r, &err) == PNPR_OK && pnpr_renderer_set_cloud(r, c, NULL, &err) == PNPR_OK;
    pnpr_camera cam = {{0, -4, 0}, {0, 0, 0}, {0, 0, 1}, 45, 0, 0};
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    for (int a = 0; a < 4; a++) o.background[a] = 1;
    pnpr_target t = {0, 0, 0, W, H, 1, 0};
    ok = ok && pnpr_renderer_draw(r, &cam, &o, &t, NULL, &err) == PNPR_OK && pnpr_renderer_read_frame(r, px, 0) == PNPR_OK;
    if (!ok) fprintf(stderr, "%s: %s\n", want ? want : "default", err.message);
    pnpr_renderer_destroy(r);
    pnpr_gl_context_destroy(ctx);
    return ok ? 1 : -1;
}

int main(void)
{
    pnpr_cloud c = {0};
    const double off[3] = {0, 0, 0};
    CHECK_STATUS(pnpr_test_sphere(&c, 20000, 1, off, 3), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    for (size_t i = 0; i < c.count; i++)
        for (int a = 0; a < 3; a++) c.rgb[3 * i + a] = (uint8_t)(c.xyz[3 * i + a] > 0 ? 220 : 40);
    uint8_t *a = malloc((size_t)W * H * 4), *b = malloc((size_t)W * H * 4);
    char ra[256] = "", rb[256] = "", why[256] = "";
    const char *pa = NULL, *pb = NULL;
    int got_b = frame_on("software", &c, b, rb, why, &pb);
    if (got_b == 0) {
        fprintf(stderr, "test_render_device: skipped: %s\n", why);
        return 77;
    }
    int got_a = frame_on("device", &c, a, ra, why, &pa);
    printf("software: %s on %s; device: %s\n", rb, pb ? pb : "?", got_a ? ra : why);
    CHECK(got_b == 1 && pb && !strcmp(pb, "surfaceless"));
    if (got_a == 0) { /* EGL lists no device: the message says so */
        CHECK_MSG(strstr(why, "PNPR_GL_DEVICE=device") != NULL, "%s", why);
    } else {
        CHECK(got_a == 1 && pa && !strcmp(pa, "device"));
        size_t differ = 0, ink = 0;
        for (size_t i = 0; i < (size_t)W * H * 4; i++) { differ += a[i] != b[i]; ink += b[i] < 200; }
        printf("frames: %zu of %d bytes differ; %zu dark bytes\n", differ, W * H * 4, ink);
        CHECK(ink > 1000); /* the sphere is drawn */
        if (!strcmp(ra, rb)) CHECK(differ == 0); /* the same rasteriser on both platforms */
    }
    /* unset: a GPU when EGL lists one; Mesa's software device is not taken for one */
    char rd[256] = "";
    const char *pd = NULL;
    unsetenv("PNPR_GL_DEVICE");
    int got_d = frame_on(NULL, &c, a, rd, why, &pd);
    printf("default: %s on %s\n", got_d ? rd : why, pd ? pd : "?");
    CHECK(got_d == 1 && pd && (strstr(rd, "llvmpipe") ? !strcmp(pd, "surfaceless") : 1));
    free(a);
    free(b);
    pnpr_cloud_free(&c);
    return pnpr_test_finish("test_render_device");
}
