/* The styles beyond `points` and `sketchy`, with known answers: `lines` (a cube's edges seen from
 * a corner: the three front edges drawn, the three hidden back edges not; no lines = background;
 * width; faint points; host GL state kept; bad input), `stipple` (darkness across a tone-gradient
 * plane increases with the tone), `cartoon` (a sphere: dark pixels all along the projected
 * silhouette circle, none inside, flat colours: 4 levels per channel or the segment means).
 * Exits 77 (skipped) when this machine has no headless EGL / GL 3.3. */
#include "testutil.h"
#include "../../render/render_internal.h"

#include <pointnpr/features.h>
#include <pointnpr/lines.h>
#include <pointnpr/render.h>

#include <epoxy/gl.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 240, H = 200 };

static const double cube_off[3] = {500000.25, -300000.5, 120.0}; /* georeferenced-like */

static pnpr_status render(pnpr_renderer *r, const pnpr_camera *cam, const pnpr_draw_options *o,
                          uint8_t *px, pnpr_render_stats *st)
{
    pnpr_target t = {0, 0, 0, W, H, 1, 0};
    pnpr_error err = {0};
    pnpr_status s = pnpr_renderer_draw(r, cam, o, &t, st, &err);
    if (s != PNPR_OK) { fprintf(stderr, "draw: %s\n", err.message); return s; }
    return pnpr_renderer_read_frame(r, px, 0);
}

static int grey(const uint8_t *px, int x, int y)
{
    const uint8_t *p = px + 4 * ((size_t)y * W + x);
    return (p[0] + p[1] + p[2]) / 3;
}

/* Darkest / lightest grey within r px of (x, y) (image coordinates, top row first). */
static int darkest_near(const uint8_t *px, double x, double y, int r)
{
    int best = 255;
    for (int dy = -r; dy <= r; dy++)
        for (int dx = -r; dx <= r; dx++) {
            int u = (int)floor(x) + dx, v = (int)floor(y) + dy;
            if (u < 0 || v < 0 || u >= W || v >= H) continue;
            int g = grey(px, u, v);
            if (g < best) best = g;
        }
    return best;
}

/* World point -> pixel (x right, y down), through the renderer's own camera code. */
static void project(const pnpr_frame_camera *fc, const double origin[3], const double world[3],
                    double *x, double *y)
{
    const float *V = fc->view, *P = fc->proj;
    double p[3] = {world[0] - origin[0], world[1] - origin[1], world[2] - origin[2]};
    double v[4], c[4];
    for (int r = 0; r < 4; r++) v[r] = V[r] * p[0] + V[4 + r] * p[1] + V[8 + r] * p[2] + V[12 + r];
    for (int r = 0; r < 4; r++) c[r] = P[r] * v[0] + P[4 + r] * v[1] + P[8 + r] * v[2] + P[12 + r] * v[3];
    *x = (c[0] / c[3] + 1) * 0.5 * W;
    *y = (1 - c[1] / c[3]) * 0.5 * H;
}

/* The 12 edges of the cube [0,1]^3 + cube_off as polylines of 21 vertices each, stored relative
 * to their own origin (cube_off + (0.5, 0.5, 0.5)), unlike the cloud's. */
static void cube_edges(pnpr_polylines *l)
{
    enum { NV = 21 };
    memset(l, 0, sizeof *l);
    l->count = 12;
    l->offset = malloc(13 * sizeof *l->offset);
    l->xyz = malloc(12 * NV * 3 * sizeof *l->xyz);
    l->closed = calloc(12, 1);
    for (int a = 0; a < 3; a++) l->origin[a] = cube_off[a] + 0.5;
    int e = 0;
    for (int axis = 0; axis < 3; axis++)
        for (int c = 0; c < 4; c++) {
            int o1 = (axis + 1) % 3, o2 = (axis + 2) % 3;
            l->offset[e] = (size_t)e * NV;
            for (int k = 0; k < NV; k++) {
                float *p = l->xyz + 3 * ((size_t)e * NV + k);
                p[axis] = (float)k / (NV - 1) - 0.5f;
                p[o1] = (float)(c & 1) - 0.5f;
                p[o2] = (float)((c >> 1) & 1) - 0.5f;
            }
            e++;
        }
    l->offset[12] = 12 * NV;
}

static void free_lines(pnpr_polylines *l)
{
    free(l->offset); free(l->xyz); free(l->closed);
    memset(l, 0, sizeof *l);
}

/* A few GL state items a host may have set (the full list is test_render_gl's). */
typedef struct mini_state { GLint v[12][4]; GLboolean e[4]; } mini_state;
static void take(mini_state *s)
{
    memset(s, 0, sizeof *s);
    static const GLenum ints[] = {GL_DRAW_FRAMEBUFFER_BINDING, GL_VIEWPORT, GL_DEPTH_FUNC, GL_BLEND_SRC_RGB,
                                  GL_BLEND_DST_ALPHA, GL_CURRENT_PROGRAM, GL_VERTEX_ARRAY_BINDING,
                                  GL_ARRAY_BUFFER_BINDING, GL_ACTIVE_TEXTURE, GL_PACK_ALIGNMENT};
    for (int i = 0; i < 10; i++) glGetIntegerv(ints[i], s->v[i]);
    GLboolean b[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, b);
    for (int i = 0; i < 4; i++) s->v[10][i] = b[i];
    glGetBooleanv(GL_DEPTH_WRITEMASK, b);
    s->v[11][0] = b[0];
    static const GLenum en[] = {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST};
    for (int i = 0; i < 4; i++) s->e[i] = glIsEnabled(en[i]);
}
static void odd_state(GLuint vao, GLuint buf)
{
    glViewport(3, 5, 17, 19);
    glDepthFunc(GL_GREATER);
    glBlendFunc(GL_DST_COLOR, GL_SRC_ALPHA);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, buf);
    glActiveTexture(GL_TEXTURE2);
    glPixelStorei(GL_PACK_ALIGNMENT, 2);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glEnable(GL_DEPTH_TEST); glEnable(GL_BLEND); glEnable(GL_CULL_FACE); glEnable(GL_SCISSOR_TEST);
}

/* ---- lines: a cube's edges from a corner ------------------------------------------------- */
static void test_lines_cube(pnpr_renderer *r)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_cube(&c, 1.0, 0.02, 0.0, cube_off, 3), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    pnpr_polylines l;
    cube_edges(&l);
    pnpr_camera cam = {{0}, {0}, {0, 0, 1}, 40, 0, 0};
    static const double eye[3] = {2.6, -1.7, 2.1};
    for (int a = 0; a < 3; a++) { cam.eye[a] = cube_off[a] + eye[a]; cam.target[a] = cube_off[a] + 0.5; }
    pnpr_frame_camera fc;
    float lo[3], hi[3];
    CHECK(pnpr_cloud_bounds(&c, lo, hi) != 0);
    CHECK_STATUS(pnpr_frame_camera_make(&cam, c.origin, lo, hi, 1, W, H, &fc, NULL), PNPR_OK);
    /* nearest corner (1,0,1): its three edges are in front; the farthest (0,1,0) is hidden */
    static const double front[3][3] = {{0.5, 0, 1}, {1, 0.5, 1}, {1, 0, 0.5}};
    static const double back[3][3] = {{0.5, 1, 0}, {0, 0.5, 0}, {0, 1, 0.5}};

    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_LINES;
    o.outline = -1; /* the profile lines alone (outlines: test_render_outline) */
    o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
    uint8_t *px = malloc(W * H * 4), *px2 = malloc(W * H * 4);
    pnpr_render_stats st;

    /* no lines: exactly the background */
    CHECK_STATUS(render(r, &cam, &o, px, &st), PNPR_OK);
    size_t bad = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) bad += !(px[4 * i] == 255 && px[4 * i + 1] == 255 && px[4 * i + 2] == 255 && px[4 * i + 3] == 255);
    CHECK_MSG(bad == 0, "no lines: %zu pixels are not the background", bad);
    CHECK(st.strokes_drawn == 0);

    CHECK_STATUS(pnpr_renderer_set_lines(r, &l, NULL), PNPR_OK);
    CHECK_STATUS(render(r, &cam, &o, px, &st), PNPR_OK);
    CHECK_MSG(st.strokes_drawn == 12 * 20, "segments drawn: %zu", st.strokes_drawn);
    for (int e = 0; e < 3; e++) {
        double wf[3], wb[3], x, y;
        for (int a = 0; a < 3; a++) { wf[a] = cube_off[a] + front[e][a]; wb[a] = cube_off[a] + back[e][a]; }
        project(&fc, c.origin, wf, &x, &y);
        int d = darkest_near(px, x, y, 2);
        CHECK_MSG(d < 80, "front edge %d at (%.1f, %.1f): darkest grey %d, expected a dark line", e, x, y, d);
        project(&fc, c.origin, wb, &x, &y);
        d = darkest_near(px, x, y, 3);
        CHECK_MSG(d == 255, "hidden back edge %d at (%.1f, %.1f): darkest grey %d, expected background", e, x, y, d);
    }
    /* wider lines: more ink */
    size_t dark2 = 0, dark6 = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) dark2 += grey(px, x, y) < 128;
    o.line_width = 6;
    CHECK_STATUS(render(r, &cam, &o, px2, NULL), PNPR_OK);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) dark6 += grey(px2, x, y) < 128;
    CHECK_MSG(dark6 > 2 * dark2 && dark2 > 100, "width 6: %zu dark pixels, width 2: %zu", dark6, dark2);
    o.line_width = 0;

    /* without occluders nothing hides the back edges */
    pnpr_cloud empty = {0};
    pnpr_camera cam_nf = cam;
    cam_nf.near_plane = 0.5f; cam_nf.far_plane = 10;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &empty, NULL, NULL), PNPR_OK);
    CHECK_STATUS(render(r, &cam_nf, &o, px2, NULL), PNPR_OK);
    for (int e = 0; e < 3; e++) {
        double wb[3], x, y;
        for (int a = 0; a < 3; a++) wb[a] = cube_off[a] + back[e][a];
        project(&fc, c.origin, wb, &x, &y);
        int d = darkest_near(px2, x, y, 2);
        CHECK_MSG(d < 80, "no occluders: back edge %d at (%.1f, %.1f): darkest grey %d", e, x, y, d);
    }
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);

    /* faint points: the faces show lightly (not background, lighter than the lines) */
    o.faint = 0.3f;
    CHECK_STATUS(render(r, &cam, &o, px2, NULL), PNPR_OK);
    {
        double centre[3] = {cube_off[0] + 0.5, cube_off[1] + 0.0, cube_off[2] + 0.5}, x, y; /* front face y=0 */
        project(&fc, c.origin, centre, &x, &y);
        int g = grey(px2, (int)x, (int)y);
        CHECK_MSG(g < 255 && g > 150, "faint face centre grey %d (expected light grey)", g);
        for (int e = 0; e < 3; e++) {
            double wf[3];
            for (int a = 0; a < 3; a++) wf[a] = cube_off[a] + front[e][a];
            project(&fc, c.origin, wf, &x, &y);
            CHECK_MSG(darkest_near(px2, x, y, 2) < 80, "faint: front edge %d still dark", e);
        }
    }
    o.faint = 0;

    /* host GL state: odd values before, the same after set_lines, draw (composited) */
    {
        GLuint vao, buf, fbo, tex;
        glGenVertexArrays(1, &vao);
        glGenBuffers(1, &buf);
        glGenFramebuffers(1, &fbo);
        glGenTextures(1, &tex);
        glBindTexture(GL_TEXTURE_2D, tex);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W + 10, H + 10, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
        odd_state(vao, buf);
        mini_state before, after;
        take(&before);
        CHECK_STATUS(pnpr_renderer_set_lines(r, &l, NULL), PNPR_OK);
        pnpr_target t = {fbo, 4, 6, W, H, 0, 0};
        o.faint = 0.5f;
        CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, NULL), PNPR_OK);
        o.faint = 0;
        take(&after);
        CHECK_MSG(memcmp(&before, &after, sizeof before) == 0, "lines: host GL state changed");
        CHECK_MSG(glGetError() == GL_NO_ERROR, "lines: GL error");
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBindVertexArray(0);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        glActiveTexture(GL_TEXTURE0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_TRUE);
        glDisable(GL_DEPTH_TEST); glDisable(GL_BLEND); glDisable(GL_CULL_FACE); glDisable(GL_SCISSOR_TEST);
        glViewport(0, 0, W, H);
        glDepthFunc(GL_LESS);
        glBlendFunc(GL_ONE, GL_ZERO);
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &tex);
        glDeleteBuffers(1, &buf);
        glDeleteVertexArrays(1, &vao);
    }

    /* bad input */
    pnpr_error err = {0};
    l.offset[3] = l.offset[2] - 1;
    CHECK_STATUS(pnpr_renderer_set_lines(r, &l, &err), PNPR_ERR_INVALID_ARGUMENT);
    l.offset[3] = 3 * 21;
    l.xyz[5] = NAN; /* one vertex of the first edge: its two segments are dropped */
    CHECK_STATUS(pnpr_renderer_set_lines(r, &l, NULL), PNPR_OK);
    CHECK_STATUS(render(r, &cam, &o, px, &st), PNPR_OK);
    CHECK_MSG(st.strokes_drawn == 12 * 20 - 2, "NaN vertex: %zu segments", st.strokes_drawn);
    o.faint = 1.5f;
    CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_ERR_INVALID_ARGUMENT);
    o.faint = 0; o.line_width = NAN;
    CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_ERR_INVALID_ARGUMENT);
    o.line_width = 0;
    /* clearing the lines */
    CHECK_STATUS(pnpr_renderer_set_lines(r, NULL, NULL), PNPR_OK);
    CHECK_STATUS(render(r, &cam, &o, px, &st), PNPR_OK);
    CHECK(st.strokes_drawn == 0);

    free(px); free(px2);
    free_lines(&l);
    pnpr_cloud_free(&c);
}

/* ---- stipple: darkness follows the tone --------------------------------------------------- */
static void test_stipple_tone(pnpr_renderer *r)
{
    /* a plane 2 x 1 (spacing 0.025), grey from light (x = 0) to dark (x = 2), features computed:
     * the dithering points' density follows the tone, and so must the image's darkness */
    enum { NX = 81, NY = 41 };
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_plane(&c, NX, NY, 0.025, cube_off), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    float lo[3], hi[3];
    CHECK(pnpr_cloud_bounds(&c, lo, hi) != 0);
    for (size_t i = 0; i < c.count; i++) {
        double t = (c.xyz[3 * i] - lo[0]) / (hi[0] - lo[0]); /* 0 .. 1 */
        uint8_t g = (uint8_t)(250 - 230 * t);
        c.rgb[3 * i] = c.rgb[3 * i + 1] = c.rgb[3 * i + 2] = g;
    }
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    CHECK(pnpr_renderer_has_features(r));
    pnpr_camera cam = {{0}, {0}, {0, 1, 0}, 30, 0, 0};
    for (int a = 0; a < 3; a++) cam.target[a] = c.origin[a] + 0.5 * (lo[a] + hi[a]);
    memcpy(cam.eye, cam.target, sizeof cam.eye);
    cam.eye[2] += 4.0;
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_STIPPLE;
    o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
    uint8_t *px = malloc(W * H * 4);
    pnpr_render_stats st;
    CHECK_STATUS(render(r, &cam, &o, px, &st), PNPR_OK);
    CHECK(st.strokes_drawn > 0 && st.strokes_drawn < c.count);
    /* mean darkness in 5 bands across x, inside the plane's image */
    pnpr_frame_camera fc;
    CHECK_STATUS(pnpr_frame_camera_make(&cam, c.origin, lo, hi, 1, W, H, &fc, NULL), PNPR_OK);
    double x0, y0, x1, y1;
    double wlo[3] = {c.origin[0] + lo[0], c.origin[1] + lo[1], c.origin[2]};
    double whi[3] = {c.origin[0] + hi[0], c.origin[1] + hi[1], c.origin[2]};
    project(&fc, c.origin, wlo, &x0, &y0);
    project(&fc, c.origin, whi, &x1, &y1);
    if (y0 > y1) { double t = y0; y0 = y1; y1 = t; }
    double dark[5] = {0};
    for (int b = 0; b < 5; b++) {
        int xa = (int)(x0 + (x1 - x0) * (b + 0.1) / 5), xb = (int)(x0 + (x1 - x0) * (b + 0.9) / 5);
        size_t n = 0;
        for (int y = (int)y0 + 3; y < (int)y1 - 3; y++)
            for (int x = xa; x < xb; x++) { dark[b] += 255 - grey(px, x, y); n++; }
        dark[b] /= n ? (double)n : 1;
    }
    for (int b = 1; b < 5; b++)
        CHECK_MSG(dark[b] > dark[b - 1], "stipple band %d darkness %.2f not above band %d's %.2f", b, dark[b], b - 1, dark[b - 1]);
    CHECK_MSG(dark[4] > 3 * dark[0] + 5, "darkest band %.2f vs lightest %.2f", dark[4], dark[0]);
    fprintf(stderr, "stipple band darkness: %.1f %.1f %.1f %.1f %.1f (%zu dots)\n", dark[0], dark[1], dark[2], dark[3], dark[4], st.strokes_drawn);
    /* dots are only dark ink on white: no pixel is coloured */
    size_t coloured = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        int mx = px[4 * i], mn = px[4 * i];
        for (int k = 1; k < 3; k++) { if (px[4 * i + k] > mx) mx = px[4 * i + k]; if (px[4 * i + k] < mn) mn = px[4 * i + k]; }
        coloured += mx - mn > 8;
    }
    CHECK_MSG(coloured == 0, "%zu coloured pixels in a stipple image", coloured);
    /* a budget draws fewer dots; without features: NOT_FOUND */
    o.budget = c.count / 4;
    CHECK_STATUS(render(r, &cam, &o, px, &st), PNPR_OK);
    CHECK_MSG(st.points_drawn <= c.count / 4 && st.points_drawn >= 0.97 * (double)(c.count / 4), "budget %zu: %zu drawn",
              c.count / 4, st.points_drawn);
    o.budget = 0;
    pnpr_upload_options uo;
    memset(&uo, 0, sizeof uo);
    uo.ignore_features = 1;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, &uo, NULL), PNPR_OK);
    CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_ERR_NOT_FOUND);
    o.dot_size = -1;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_ERR_INVALID_ARGUMENT);
    free(px);
    pnpr_cloud_free(&c);
}

/* ---- cartoon: a sphere's silhouette is dark, its inside flat-coloured -------------------- */
static int is_dark(const uint8_t *p) { return p[0] < 70 && p[1] < 70 && p[2] < 70; }

static void test_cartoon_sphere(pnpr_renderer *r)
{
    const double R = 1.0, D = 5.0;
    /* an evenly sampled sphere (Fibonacci lattice, spacing ~0.02): the splats cover it without
     * holes (gaps in a sampling would show the outline colour, as the paper's method does) */
    enum { NS = 30000 };
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&c, NS), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    memcpy(c.origin, cube_off, sizeof c.origin);
    pnpr_test_rng rng = {5};
    for (size_t i = 0; i < NS; i++) {
        double z = 1 - (2.0 * i + 1) / NS, rr = sqrt(1 - z * z), phi = 2.39996322972865332 * (double)i;
        c.xyz[3 * i] = (float)(R * rr * cos(phi));
        c.xyz[3 * i + 1] = (float)(R * rr * sin(phi));
        c.xyz[3 * i + 2] = (float)(R * z);
        int upper = z > 0;
        c.rgb[3 * i] = (uint8_t)(upper ? 60 + 40 * pnpr_test_uniform(&rng) : 190 + 20 * pnpr_test_uniform(&rng));
        c.rgb[3 * i + 1] = (uint8_t)(110 + 30 * pnpr_test_uniform(&rng));
        c.rgb[3 * i + 2] = (uint8_t)(upper ? 200 + 40 * pnpr_test_uniform(&rng) : 40 + 40 * pnpr_test_uniform(&rng));
    }
    pnpr_camera cam = {{0}, {0}, {0, 0, 1}, 40, 0, 0};
    memcpy(cam.target, cube_off, sizeof cam.target);
    memcpy(cam.eye, cube_off, sizeof cam.eye);
    cam.eye[1] -= D;
    /* the silhouette circle's radius in pixels, centred in the image */
    double rs = tan(asin(R / D)) / tan(20.0 * 3.14159265358979 / 180.0) * 0.5 * H;
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_CARTOON;
    o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
    uint8_t *px = malloc(W * H * 4);
    for (int labelled = 0; labelled < 2; labelled++) {
        if (labelled) { /* two segments: upper and lower hemisphere */
            CHECK_STATUS(pnpr_cloud_alloc_labels(&c), PNPR_OK);
            for (size_t i = 0; i < c.count; i++) c.label[i] = c.xyz[3 * i + 2] > 0 ? 7 : 3;
        }
        CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
        CHECK(pnpr_renderer_has_labels(r) == labelled);
        CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_OK);
        /* along 90 rays from the centre: a dark pixel near the silhouette radius */
        int rays_dark = 0;
        for (int k = 0; k < 90; k++) {
            double a = 2 * 3.14159265358979 * k / 90, cx = 0.5 * W, cy = 0.5 * H;
            int found = 0;
            for (double t = rs - 2.5; t <= rs + 3.5 && !found; t += 0.5) {
                int x = (int)floor(cx + t * cos(a)), y = (int)floor(cy + t * sin(a));
                if (x >= 0 && y >= 0 && x < W && y < H) found = is_dark(px + 4 * ((size_t)y * W + x));
            }
            rays_dark += found;
        }
        CHECK_MSG(rays_dark >= 88, "labels %d: %d of 90 rays find a dark silhouette pixel at r = %.1f px", labelled, rays_dark, rs);
        /* the inner disk (0.75 of the radius): no dark pixel, only flat colours */
        size_t dark = 0, off_level = 0, inner = 0;
        uint8_t seen[2][3];
        int nseen = 0, extra_colours = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double dx = x + 0.5 - 0.5 * W, dy = y + 0.5 - 0.5 * H;
                if (dx * dx + dy * dy > (0.75 * rs) * (0.75 * rs)) continue;
                const uint8_t *p = px + 4 * ((size_t)y * W + x);
                inner++;
                dark += is_dark(p);
                if (!labelled) {
                    for (int ch = 0; ch < 3; ch++) off_level += p[ch] % 85 != 0; /* 4 levels: 0, 85, 170, 255 */
                } else if (!is_dark(p)) {
                    int known = 0;
                    for (int s = 0; s < nseen; s++) known |= !memcmp(seen[s], p, 3);
                    if (!known && nseen < 2) memcpy(seen[nseen++], p, 3);
                    else if (!known) extra_colours++;
                }
            }
        CHECK_MSG(inner > 1000 && dark == 0, "labels %d: %zu dark pixels inside the silhouette (of %zu)", labelled, dark, inner);
        if (!labelled) CHECK_MSG(off_level == 0, "%zu channel values off the 4 levels", off_level);
        else CHECK_MSG(nseen == 2 && extra_colours == 0, "labelled: %d colours + %d more inside (expected the 2 segment means)", nseen, extra_colours);
        {
            char path[600];
            snprintf(path, sizeof path, "%s/cartoon_sphere_%d.png", PNPR_TEST_SCRATCH, labelled);
            CHECK_STATUS(pnpr_write_png(path, px, W, H, 0, NULL), PNPR_OK);
        }
        fprintf(stderr, "cartoon labels %d: silhouette r = %.1f px, %d/90 rays dark, inner %zu px\n", labelled, rs, rays_dark, inner);
    }
    /* outside the enlarged silhouette: exactly the background */
    size_t bad = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double dx = x + 0.5 - 0.5 * W, dy = y + 0.5 - 0.5 * H;
            if (dx * dx + dy * dy < (rs + 8) * (rs + 8)) continue;
            const uint8_t *p = px + 4 * ((size_t)y * W + x);
            bad += !(p[0] == 255 && p[1] == 255 && p[2] == 255);
        }
    CHECK_MSG(bad == 0, "cartoon: %zu pixels outside the sphere are not background", bad);
    o.levels = 1;
    CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_ERR_INVALID_ARGUMENT);
    free(px);
    pnpr_cloud_free(&c);
}

int main(void)
{
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_styles: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    if (r) {
        test_lines_cube(r);
        test_stipple_tone(r);
        test_cartoon_sphere(r);
        pnpr_renderer_destroy(r);
    }
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_styles");
}
