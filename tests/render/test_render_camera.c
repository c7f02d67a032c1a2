/* Explicit camera matrices (pnpr_camera_matrices through pnpr_draw_options.matrices): the
 * look-at camera's own matrices give the look-at frame, an off-centre frustum (the left half of
 * the image as its own frustum, like one tile of MeshLab's tiled snapshot) gives that half of the
 * full frame, an orthographic projection renders the cloud (also tiled), a far origin keeps its
 * precision, and bad matrices are refused. Exits 77 (skipped) without headless EGL / GL 3.3. */
#include "testutil.h"

#include <pointnpr/render.h>

#include <epoxy/gl.h>


#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 160, H = 120 };

/* Two grids (a red one at z = 0 and a green one at z = 0.6, smaller) far from the world origin. */
static void make_cloud(pnpr_cloud *c, const double origin[3])
{
    const int n = 40, m = 20;
    CHECK_STATUS(pnpr_cloud_alloc(c, (size_t)(n * n + m * m)), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(c), PNPR_OK);
    memcpy(c->origin, origin, sizeof c->origin);
    size_t k = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++, k++) {
            c->xyz[3 * k] = (float)((i - 0.5 * (n - 1)) * 0.05);
            c->xyz[3 * k + 1] = (float)((j - 0.5 * (n - 1)) * 0.05);
            c->xyz[3 * k + 2] = 0;
            c->rgb[3 * k] = 230; c->rgb[3 * k + 1] = 20; c->rgb[3 * k + 2] = 20;
        }
    for (int j = 0; j < m; j++)
        for (int i = 0; i < m; i++, k++) {
            c->xyz[3 * k] = (float)((i - 0.5 * (m - 1)) * 0.04 + 0.3);
            c->xyz[3 * k + 1] = (float)((j - 0.5 * (m - 1)) * 0.04);
            c->xyz[3 * k + 2] = 0.6f;
            c->rgb[3 * k] = 20; c->rgb[3 * k + 1] = 200; c->rgb[3 * k + 2] = 30;
        }
}

static pnpr_status draw(pnpr_renderer *r, const pnpr_camera *cam, const pnpr_draw_options *o, int w,
                        int h, uint8_t *px)
{
    pnpr_target t = {0, 0, 0, w, h, 1, 0};
    pnpr_error err = {0};
    pnpr_status s = pnpr_renderer_draw(r, cam, o, &t, NULL, &err);
    if (s != PNPR_OK) { fprintf(stderr, "draw: %s\n", err.message); return s; }
    return pnpr_renderer_read_frame(r, px, 0);
}

static int non_background(const uint8_t *px, int w, int h)
{
    int n = 0;
    for (int i = 0; i < w * h; i++)
        if (px[4 * i] < 240 || px[4 * i + 1] < 240 || px[4 * i + 2] < 240) n++;
    return n;
}

/* The host framebuffer fbo (W x H) into px, bottom row first (glReadPixels). */
static void read_host(GLuint fbo, uint8_t *px)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
}

/* The two halves of the frame, each an off-centre frustum drawn into its half of a host
 * framebuffer (MeshLab's tiled snapshot, 2x1), against the whole frame drawn at once: with
 * a guard band (pnpr_target.guard -1) the 16 columns along the cut match as the rest does; without
 * one they do not (GL drops the sprites whose centre lies beyond the cut, and the image-space
 * outlines see the frame's border). Cartoon, whose outlines are found in image space; with every
 * point and with the default screen density (the halves planned as the whole frame:
 * pnpr_draw_options.plan_matrices; the cells beyond a half's edge still draw). Drawn alone,
 * the left half leaves the right half of the framebuffer as it was (the guard is cropped). */
static void check_guard(pnpr_renderer *r, const pnpr_draw_options *o, const pnpr_camera_matrices *m)
{
    uint8_t *a = malloc((size_t)W * H * 4);
    pnpr_draw_options of = *o;
    of.matrices = m;
    CHECK(a && draw(r, NULL, &of, W, H, a) == PNPR_OK);
    GLuint fbo, tex;
    glGenFramebuffers(1, &fbo);
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    pnpr_camera_matrices half[2] = {*m, *m};
    for (int col = 0; col < 4; col++) {
        half[0].projection[col * 4] = 2 * m->projection[col * 4] + m->projection[col * 4 + 3];
        half[1].projection[col * 4] = 2 * m->projection[col * 4] - m->projection[col * 4 + 3];
    }
    uint8_t *px = malloc((size_t)W * H * 4);
    int bad[2] = {0, 0}, compared = 0;
    for (int guarded = 0; px && guarded < 2; guarded++) {
        for (int side = 0; side < 2; side++) {
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            if (side == 0) { glClearColor(1, 0, 1, 1); glClear(GL_COLOR_BUFFER_BIT); }
            pnpr_draw_options oh = *o;
            oh.matrices = &half[side];
            oh.plan_matrices = m; /* the queue planned for the whole frame */
            oh.plan_width = W;
            oh.plan_height = H;
            pnpr_target t = {fbo, side * (W / 2), 0, W / 2, H, 0, guarded ? -1 : 0};
            pnpr_error err = {0};
            CHECK_STATUS(pnpr_renderer_draw(r, NULL, &oh, &t, NULL, &err), PNPR_OK);
            if (side == 1 || !guarded) continue;
            read_host(fbo, px);
            int untouched = 1;
            for (int y = 0; y < H; y++)
                for (int x = W / 2; x < W; x++) {
                    const uint8_t *p = px + 4 * ((size_t)y * W + x);
                    untouched &= p[0] == 255 && p[1] == 0 && p[2] == 255;
                }
            CHECK_MSG(untouched, "guard band: the left half's frame reached into the right half");
        }
        read_host(fbo, px);
        compared = 0;
        for (int y = 16; y < H - 16; y++) /* not the image's own top and bottom borders, where the
                                           * guard band sees beyond the image and the frame does not */
            for (int x = W / 2 - 8; x < W / 2 + 8; x++) {
                compared++;
                int d = 0;
                for (int c = 0; c < 3; c++) {
                    int dc = abs((int)px[((size_t)(H - 1 - y) * W + x) * 4 + c] - (int)a[((size_t)y * W + x) * 4 + c]);
                    d = dc > d ? dc : d;
                }
                bad[guarded] += d > 16;
            }
    }
    fprintf(stderr, "two halves, the 16 columns along the cut: %d of %d pixels differ by > 16 without a guard band, %d with\n",
            bad[0], compared, bad[1]);
    CHECK_MSG(bad[1] * 100 <= compared, "with a guard band: %d of %d pixels along the cut differ", bad[1], compared);
    CHECK_MSG(bad[0] > 4 * bad[1] + 10, "without a guard band the cut shows nothing to fix: %d vs %d", bad[0], bad[1]);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    free(px);
    free(a);
}

int main(void)
{
    pnpr_error err = {0};
    pnpr_gl_context *ctx = NULL;
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_camera: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    if (!r) { pnpr_gl_context_destroy(ctx); return pnpr_test_finish("test_render_camera"); }

    const double origin[3] = {4.5e5, -2.25e6, 1.25e3}; /* UTM-like: matrices must be rebased */
    pnpr_cloud cloud = {0};
    make_cloud(&cloud, origin);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &cloud, NULL, &err), PNPR_OK);

    pnpr_camera cam;
    memset(&cam, 0, sizeof cam);
    cam.eye[0] = origin[0] + 0.4; cam.eye[1] = origin[1] - 2.2; cam.eye[2] = origin[2] + 2.0;
    cam.target[0] = origin[0]; cam.target[1] = origin[1]; cam.target[2] = origin[2] + 0.2;
    cam.up[2] = 1;
    cam.fov_y_deg = 40;

    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_POINTS;
    o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;

    uint8_t *a = malloc((size_t)W * H * 4), *b = malloc((size_t)W * H * 4), *half = malloc((size_t)W * H * 4);
    CHECK(a && b && half);
    if (!a || !b || !half) return pnpr_test_finish("test_render_camera");

    /* 1. the look-at camera's own matrices: the same frame */
    CHECK_STATUS(draw(r, &cam, &o, W, H, a), PNPR_OK);
    int covered = non_background(a, W, H);
    CHECK_MSG(covered > W * H / 10, "look-at frame covers %d pixels", covered);
    pnpr_camera_matrices m;
    CHECK_STATUS(pnpr_camera_matrices_from_camera(&cam, &cloud, W, H, &m, &err), PNPR_OK);
    pnpr_draw_options om = o;
    om.matrices = &m;
    pnpr_camera bogus; /* ignored when matrices are given */
    memset(&bogus, 0, sizeof bogus);
    CHECK_STATUS(draw(r, &bogus, &om, W, H, b), PNPR_OK);
    int maxd = 0, ndiff = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++) {
        int d = abs((int)a[i] - (int)b[i]);
        if (d > maxd) maxd = d;
        if (d) ndiff++;
    }
    CHECK_MSG(maxd <= 1, "matrices of the look-at camera: max difference %d (%d bytes differ)", maxd, ndiff);

    /* 2. off-centre: the left half of the image as its own frustum (as MeshLab's tiled snapshot
     * does): clip x' = 2 x + w, a W/2 x H frame, equal to the left half of the full frame except
     * next to the cut (GL drops point sprites whose centre lies outside the viewport) */
    pnpr_camera_matrices mh = m;
    for (int col = 0; col < 4; col++) mh.projection[col * 4 + 0] = 2 * m.projection[col * 4 + 0] + m.projection[col * 4 + 3];
    CHECK(mh.projection[8] != 0); /* really off-centre */
    om.matrices = &mh;
    CHECK_STATUS(draw(r, NULL, &om, W / 2, H, half), PNPR_OK);
    int bad = 0, compared = 0, maxh = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W / 2 - 8; x++) {
            compared++;
            int d = 0;
            for (int c = 0; c < 4; c++) {
                int dc = abs((int)half[((size_t)y * (W / 2) + x) * 4 + c] - (int)a[((size_t)y * W + x) * 4 + c]);
                if (dc > d) d = dc;
            }
            if (d > maxh) maxh = d;
            if (d > 16) bad++;
        }
    CHECK_MSG(bad * 200 <= compared, "off-centre half frame: %d of %d pixels differ by > 16 (max %d)", bad, compared, maxh);
    int covered_half = non_background(half, W / 2, H);
    CHECK_MSG(covered_half > 0, "off-centre half frame is empty");
    fprintf(stderr, "off-centre half: %d/%d pixels differ by > 16, max %d\n", bad, compared, maxh);

    pnpr_draw_options oc = o; /* cartoon: its outlines are found in image space, up to the frame's border */
    oc.style = PNPR_STYLE_CARTOON;
    oc.density = -1; /* every point in the whole frame and in each half */
    check_guard(r, &oc, &m);
    oc.density = 0; /* the default screen density: each half planned as the whole frame
                     * (plan_matrices), as the decorator's tiles are */
    check_guard(r, &oc, &m);
    /* a plan view without a size: refused */
    pnpr_draw_options op = oc;
    op.matrices = &m;
    op.plan_matrices = &m;
    uint8_t *tmp = malloc((size_t)W * H * 4);
    CHECK(tmp && draw(r, NULL, &op, W, H, tmp) == PNPR_ERR_INVALID_ARGUMENT);
    free(tmp);

    /* the right half too, through the tiled snapshot path (guard bands on top of the frustum) */
    pnpr_camera_matrices mr = m;
    for (int col = 0; col < 4; col++) mr.projection[col * 4 + 0] = 2 * m.projection[col * 4 + 0] - m.projection[col * 4 + 3];
    om.matrices = &mr;
    pnpr_snapshot_options so;
    memset(&so, 0, sizeof so);
    so.max_tile_size = 48;
    CHECK_STATUS(pnpr_renderer_snapshot(r, NULL, &om, W / 2, H, &so, half, NULL, &err), PNPR_OK);
    bad = 0; compared = 0;
    for (int y = 0; y < H; y++)
        for (int x = 8; x < W / 2; x++) {
            compared++;
            int d = 0;
            for (int c = 0; c < 4; c++) {
                int dc = abs((int)half[((size_t)y * (W / 2) + x) * 4 + c] - (int)a[((size_t)y * W + W / 2 + x) * 4 + c]);
                if (dc > d) d = dc;
            }
            if (d > 16) bad++;
        }
    CHECK_MSG(bad * 100 <= compared, "off-centre right half (tiled): %d of %d pixels differ by > 16", bad, compared);

    /* 3. orthographic: the same view, glOrtho around the cloud */
    pnpr_camera_matrices mo = m;
    memset(mo.projection, 0, sizeof mo.projection);
    {
        double top = 1.3, right = top * W / H, n = 0.5, f = 6.0;
        mo.projection[0] = 1 / right;
        mo.projection[5] = 1 / top;
        mo.projection[10] = -2 / (f - n);
        mo.projection[14] = -(f + n) / (f - n);
        mo.projection[15] = 1;
    }
    om.matrices = &mo;
    CHECK_STATUS(draw(r, NULL, &om, W, H, b), PNPR_OK);
    int covered_o = non_background(b, W, H);
    CHECK_MSG(covered_o > W * H / 20, "orthographic frame covers %d pixels", covered_o);
    /* the red grid's centre projects to the image centre region: red there */
    {
        int reds = 0;
        for (int y = H / 2 - 10; y < H / 2 + 10; y++)
            for (int x = W / 2 - 40; x < W / 2 - 20; x++) {
                const uint8_t *p = b + ((size_t)y * W + x) * 4;
                if (p[0] > p[1] + 40 && p[0] > p[2] + 40) reds++;
            }
        CHECK_MSG(reds > 0, "orthographic frame: no red near the centre");
    }
    /* orthographic disks do not depend on depth: the same frame with the eye moved back along
     * the view direction (only the view's translation changes) */
    pnpr_camera_matrices mo2 = mo;
    mo2.view[14] -= 1.5;
    mo2.projection[14] = -(6.0 + 1.5 + 0.5 + 1.5) / (6.0 - 0.5);
    om.matrices = &mo2;
    CHECK_STATUS(draw(r, NULL, &om, W, H, half), PNPR_OK);
    maxd = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++) {
        int d = abs((int)b[i] - (int)half[i]);
        if (d > maxd) maxd = d;
    }
    CHECK_MSG(maxd <= 1, "orthographic frame moved back along the view: max difference %d", maxd);
    /* orthographic through the tiled snapshot */
    om.matrices = &mo;
    CHECK_STATUS(pnpr_renderer_snapshot(r, NULL, &om, W, H, &so, half, NULL, &err), PNPR_OK);
    int covered_ot = non_background(half, W, H);
    CHECK_MSG(abs(covered_ot - covered_o) * 50 <= covered_o, "orthographic tiled snapshot covers %d vs %d", covered_ot, covered_o);

    /* 4. a view with a uniform scale (MeshLab's trackball): scale 2 in the view, the eye twice as
     * far in eye units -> the same image */
    {
        pnpr_camera_matrices ms = m;
        for (int i = 0; i < 12; i++) ms.view[i] *= 2; /* scale(2) applied after the view: 2 * V */
        ms.view[12] *= 2; ms.view[13] *= 2; ms.view[14] *= 2;
        /* eye space is twice as large: near and far twice as far */
        double n = m.projection[14] / (m.projection[10] - 1), f = m.projection[14] / (m.projection[10] + 1);
        n *= 2; f *= 2;
        ms.projection[10] = -(f + n) / (f - n);
        ms.projection[14] = -2 * f * n / (f - n);
        om.matrices = &ms;
        CHECK_STATUS(draw(r, NULL, &om, W, H, b), PNPR_OK);
        bad = 0;
        for (int i = 0; i < W * H; i++) {
            int d = 0;
            for (int c = 0; c < 4; c++) {
                int dc = abs((int)a[4 * i + c] - (int)b[4 * i + c]);
                if (dc > d) d = dc;
            }
            if (d > 16) bad++;
        }
        CHECK_MSG(bad * 200 <= W * H, "scaled view: %d pixels differ by > 16", bad);
    }

    /* 5. bad matrices */
    {
        pnpr_camera_matrices x = m;
        x.view[13] = NAN;
        om.matrices = &x;
        CHECK_STATUS(draw(r, NULL, &om, W, H, b), PNPR_ERR_NUMERIC);
        x = m;
        x.view[3] = 0.5; /* not affine */
        CHECK_STATUS(draw(r, NULL, &om, W, H, b), PNPR_ERR_NUMERIC);
        x = m;
        memset(x.view, 0, sizeof x.view);
        x.view[15] = 1; /* singular */
        CHECK_STATUS(draw(r, NULL, &om, W, H, b), PNPR_ERR_NUMERIC);
        x = m;
        x.projection[15] = 0; x.projection[11] = 0; /* neither kind */
        CHECK_STATUS(draw(r, NULL, &om, W, H, b), PNPR_ERR_NUMERIC);
        x = m;
        x.projection[14] = -x.projection[14]; /* near plane behind the eye */
        CHECK_STATUS(draw(r, NULL, &om, W, H, b), PNPR_ERR_NUMERIC);
        CHECK_STATUS(pnpr_camera_matrices_from_camera(NULL, &cloud, W, H, &m, &err), PNPR_ERR_INVALID_ARGUMENT);
        CHECK_STATUS(pnpr_camera_matrices_from_camera(&cam, &cloud, 0, H, &m, &err), PNPR_ERR_INVALID_ARGUMENT);
    }

    free(a); free(b); free(half);
    pnpr_cloud_free(&cloud);
    pnpr_renderer_destroy(r);
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_camera");
}
