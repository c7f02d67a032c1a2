/* The painterly style (section 5.3) with known answers: the sky mask (background pixels where the
 * visibility mask has no coverage stay exactly the background colour, while the same frame without
 * the stencil test paints some of them: the test has teeth); the painting covers the surface in
 * the surface's colours without a gap (the mask is the underpainting) and without dark ink; host GL state, the stencil state included, is restored; missing feature
 * degree -> NOT_FOUND naming it; bad bin counts; tiles equal one frame.
 * Exits 77 (skipped) when this machine has no headless EGL / GL 3.3. */
#include "testutil.h"

#include <pointnpr/features.h>
#include <pointnpr/render.h>

#include <epoxy/gl.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 240, H = 200 };

static pnpr_status render(pnpr_renderer *r, const pnpr_camera *cam, const pnpr_draw_options *o,
                          uint8_t *px, pnpr_render_stats *st)
{
    pnpr_target t = {0, 0, 0, W, H, 1, 0};
    pnpr_error err = {0};
    pnpr_status s = pnpr_renderer_draw(r, cam, o, &t, st, &err);
    if (s != PNPR_OK) { fprintf(stderr, "draw: %s\n", err.message); return s; }
    return pnpr_renderer_read_frame(r, px, 0);
}

static int is_bg(const uint8_t *p, const uint8_t bg[4])
{
    return p[0] == bg[0] && p[1] == bg[1] && p[2] == bg[2] && p[3] == bg[3];
}

typedef struct gl_snap { GLint v[16]; GLboolean en[3]; } gl_snap;
static void snap(gl_snap *s)
{
    static const GLenum e[] = {GL_STENCIL_FUNC, GL_STENCIL_REF, GL_STENCIL_VALUE_MASK, GL_STENCIL_FAIL,
                               GL_STENCIL_PASS_DEPTH_FAIL, GL_STENCIL_PASS_DEPTH_PASS, GL_STENCIL_WRITEMASK,
                               GL_STENCIL_BACK_FUNC, GL_STENCIL_BACK_WRITEMASK, GL_STENCIL_CLEAR_VALUE,
                               GL_DEPTH_FUNC, GL_CURRENT_PROGRAM, GL_VERTEX_ARRAY_BINDING, GL_ARRAY_BUFFER_BINDING,
                               GL_TEXTURE_BINDING_2D, GL_VIEWPORT};
    memset(s, 0, sizeof *s);
    for (int i = 0; i < 16; i++) glGetIntegerv(e[i], &s->v[i]);
    s->en[0] = glIsEnabled(GL_STENCIL_TEST);
    s->en[1] = glIsEnabled(GL_BLEND);
    s->en[2] = glIsEnabled(GL_DEPTH_TEST);
}

static void test_painterly(pnpr_renderer *r)
{
    /* a 1.6 x 1.2 plane (spacing 0.02), colour varying over it, features computed; seen from the
     * front at a slant so that it covers the middle of the image, background all around */
    pnpr_cloud c = {0};
    const double off[3] = {-5000.5, 7000.25, 12};
    CHECK_STATUS(pnpr_test_plane(&c, 81, 61, 0.02, off), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    float lo[3], hi[3];
    CHECK(pnpr_cloud_bounds(&c, lo, hi) != 0);
    for (size_t i = 0; i < c.count; i++) {
        double u = (c.xyz[3 * i] - lo[0]) / (hi[0] - lo[0]), v = (c.xyz[3 * i + 1] - lo[1]) / (hi[1] - lo[1]);
        int stripe = ((int)(u * 6) + (int)(v * 4)) & 1;
        c.rgb[3 * i] = (uint8_t)(stripe ? 200 : 40);
        c.rgb[3 * i + 1] = (uint8_t)(60 + 120 * v);
        c.rgb[3 * i + 2] = (uint8_t)(stripe ? 50 : 210);
    }
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    pnpr_camera cam = {{0}, {0}, {0, 0, 1}, 40, 0, 0};
    for (int a = 0; a < 3; a++) cam.target[a] = c.origin[a] + 0.5 * (lo[a] + hi[a]);
    memcpy(cam.eye, cam.target, sizeof cam.eye);
    cam.eye[1] -= 2.6;
    cam.eye[2] += 2.2;
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.background[0] = 0.2f; o.background[1] = 0.4f; o.background[2] = 0.8f; o.background[3] = 1;
    uint8_t *mask = malloc(W * H * 4), *paint = malloc(W * H * 4), *nosky = malloc(W * H * 4);
    /* the mask's coverage: the `points` style with the mask's disk size (point_scale 1.5) */
    o.style = PNPR_STYLE_POINTS;
    o.point_scale = 1.5f;
    CHECK_STATUS(render(r, &cam, &o, mask, NULL), PNPR_OK);
    o.point_scale = 0;
    o.style = PNPR_STYLE_PAINTERLY;
    pnpr_render_stats st;
    CHECK_STATUS(render(r, &cam, &o, paint, &st), PNPR_OK);
    CHECK(st.points_drawn == c.count && st.strokes_drawn > c.count); /* 4 passes of dabs + strokes */
    o.paint_no_sky_mask = 1;
    CHECK_STATUS(render(r, &cam, &o, nosky, NULL), PNPR_OK);
    o.paint_no_sky_mask = 0;
    const uint8_t *bg = mask; /* the top-left corner is background */
    size_t outside = 0, kept = 0, spilled = 0, inside = 0, painted = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        if (is_bg(mask + 4 * i, bg)) {
            outside++;
            kept += is_bg(paint + 4 * i, bg);
            spilled += !is_bg(nosky + 4 * i, bg);
        } else {
            inside++;
            painted += !is_bg(paint + 4 * i, bg);
        }
    }
    fprintf(stderr, "painterly: %zu px outside the mask (%zu kept), %zu spilled without the sky mask; %zu of %zu inside painted\n",
            outside, kept, spilled, painted, inside);
    CHECK(bg[0] == 51 && bg[1] == 102 && bg[2] == 204 && bg[3] == 255);
    CHECK(outside > 10000 && inside > 5000);
    CHECK_MSG(kept == outside, "%zu of %zu background pixels outside the mask were painted", outside - kept, outside);
    CHECK_MSG(spilled > 200, "without the sky mask only %zu pixels spill", spilled);
    /* no paper inside the painted area (the mask is the underpainting), and no dark ink
     * scratches by default (the strokes take the points' colours; the darkest colour channel
     * maximum of the plane's colours is 200) */
    size_t dark = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        const uint8_t *q = paint + 4 * i;
        dark += q[0] < 30 && q[1] < 30 && q[2] < 30;
    }
    fprintf(stderr, "painterly: %zu dark pixels\n", dark);
    CHECK_MSG(painted == inside, "%zu paper pixels inside the painted area", inside - painted);
    CHECK_MSG(dark == 0, "%zu dark (ink) pixels", dark);
    /* colours: at the image centre the painting is one of the plane's colour families, no sky blue */
    const uint8_t *p = paint + 4 * ((size_t)(H / 2) * W + W / 2);
    CHECK(!is_bg(p, bg) && p[3] == 255);
    /* the same frame twice: deterministic */
    CHECK_STATUS(render(r, &cam, &o, nosky, NULL), PNPR_OK);
    CHECK(memcmp(paint, nosky, W * H * 4) == 0);
    /* host GL state, stencil included */
    GLuint vao = 0, buf = 0, tex = 0;
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &buf);
    glGenTextures(1, &tex);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, buf);
    glBindTexture(GL_TEXTURE_2D, tex);
    glEnable(GL_STENCIL_TEST);
    glStencilFuncSeparate(GL_FRONT, GL_NOTEQUAL, 3, 0x0F);
    glStencilFuncSeparate(GL_BACK, GL_LESS, 2, 0x3F);
    glStencilOpSeparate(GL_FRONT, GL_INCR, GL_DECR, GL_INVERT);
    glStencilMaskSeparate(GL_FRONT, 0x5A);
    glStencilMaskSeparate(GL_BACK, 0x33);
    glClearStencil(7);
    glDepthFunc(GL_GEQUAL);
    glViewport(1, 2, 30, 40);
    while (glGetError() != GL_NO_ERROR) {}
    gl_snap before, after;
    snap(&before);
    pnpr_target t = {0, 0, 0, W, H, 1, 0};
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, NULL), PNPR_OK);
    snap(&after);
    CHECK(memcmp(&before, &after, sizeof before) == 0);
    CHECK(glGetError() == GL_NO_ERROR);
    glDisable(GL_STENCIL_TEST);
    glStencilFuncSeparate(GL_FRONT_AND_BACK, GL_ALWAYS, 0, 0xFF);
    glStencilOpSeparate(GL_FRONT_AND_BACK, GL_KEEP, GL_KEEP, GL_KEEP);
    glStencilMask(0xFF);
    glClearStencil(0);
    glDepthFunc(GL_LESS);
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &buf);
    glDeleteTextures(1, &tex);
    /* tiles: forced 64-pixel tiles give the same picture */
    pnpr_snapshot_options so;
    memset(&so, 0, sizeof so);
    so.max_tile_size = 64;
    CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, &so, nosky, NULL, NULL), PNPR_OK);
    double sum = 0;
    size_t close = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        int worst = 0;
        for (int k = 0; k < 4; k++) {
            int d = abs((int)paint[4 * i + k] - (int)nosky[4 * i + k]);
            sum += d;
            if (d > worst) worst = d;
        }
        close += worst <= 2;
    }
    fprintf(stderr, "painterly tiled vs one frame: mean abs diff %.4f, %.3f %% within 2 levels\n",
            sum / (4.0 * W * H), 100.0 * (double)close / (W * H));
    CHECK(sum / (4.0 * W * H) < 1.0 && close > (size_t)W * H * 995 / 1000);
    pnpr_upload_options uo;
    memset(&uo, 0, sizeof uo);
    /* skip_painterly: the frames of the other styles are those of a full upload byte for byte
     * (mask, paint: scratch); a painterly frame is refused, naming the option */
    const pnpr_style others[4] = {PNPR_STYLE_SKETCHY, PNPR_STYLE_STIPPLE, PNPR_STYLE_CARTOON, PNPR_STYLE_POINTS};
    for (int k = 0; k < 4; k++) {
        pnpr_draw_options other = o;
        other.style = others[k];
        uo.skip_painterly = 0;
        CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, &uo, NULL), PNPR_OK);
        CHECK_STATUS(render(r, &cam, &other, mask, NULL), PNPR_OK);
        uo.skip_painterly = 1;
        CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, &uo, NULL), PNPR_OK);
        CHECK_STATUS(render(r, &cam, &other, paint, NULL), PNPR_OK);
        CHECK_MSG(!memcmp(mask, paint, (size_t)W * H * 4), "%s: skip_painterly changed the frame", pnpr_style_name(others[k]));
    }
    pnpr_error skip_err = {0};
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, &skip_err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(strstr(skip_err.message, "skip_painterly") != NULL);
    uo.skip_painterly = 0;
    /* one bin: one pass of the smallest brush; 17 bins: INVALID_ARGUMENT */
    uo.painterly_bins = 1;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, &uo, NULL), PNPR_OK);
    CHECK_STATUS(render(r, &cam, &o, nosky, NULL), PNPR_OK);
    uo.painterly_bins = 17;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, &uo, NULL), PNPR_ERR_INVALID_ARGUMENT);
    /* without features: NOT_FOUND, naming feature_degree */
    uo.painterly_bins = 0;
    uo.ignore_features = 1;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, &uo, NULL), PNPR_OK);
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, &err), PNPR_ERR_NOT_FOUND);
    CHECK(strstr(err.message, "feature_degree") != NULL);
    /* an empty cloud: the background only */
    pnpr_cloud empty = {0};
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &empty, NULL, NULL), PNPR_OK);
    CHECK_STATUS(render(r, &cam, &o, nosky, NULL), PNPR_OK);
    size_t nbg = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) nbg += is_bg(nosky + 4 * i, bg);
    CHECK(nbg == (size_t)W * H);
    free(mask); free(paint); free(nosky);
    pnpr_cloud_free(&c);
}

int main(void)
{
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_painterly: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    if (r) {
        test_painterly(r);
        pnpr_renderer_destroy(r);
    }
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_painterly");
}
