/* The renderer in a headless EGL context (llvmpipe): background exactness, occlusion through the
 * visibility mask, the continuous resolution queue's prefix, determinism, host GL state kept,
 * compositing, bad input, and two renderers in two contexts.
 * Exits 77 (skipped) when this machine has no headless EGL / GL 3.3. */
#include "testutil.h"

#include <pointnpr/features.h>
#include <pointnpr/render.h>

#include <epoxy/gl.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 160, H = 120 };

static pnpr_camera look(double ex, double ey, double ez, double tx, double ty, double tz)
{
    pnpr_camera c;
    memset(&c, 0, sizeof c);
    c.eye[0] = ex; c.eye[1] = ey; c.eye[2] = ez;
    c.target[0] = tx; c.target[1] = ty; c.target[2] = tz;
    c.up[1] = 1;
    c.fov_y_deg = 40;
    return c;
}

/* A grid of nx*ny points in the plane z, centred at (0,0), spacing h, colour rgb. */
static void add_grid(pnpr_cloud *cl, int nx, int ny, double h, double z, const uint8_t rgb[3],
                     int feature_class)
{
    pnpr_cloud g = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&g, (size_t)nx * ny), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&g), PNPR_OK);
    pnpr_property *pc = NULL, *px = NULL, *py = NULL, *pz = NULL;
    if (feature_class >= 0) {
        CHECK_STATUS(pnpr_cloud_add_property(&g, "feature_class", PNPR_TYPE_UINT8, &pc), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_add_property(&g, "feature_dir_x", PNPR_TYPE_FLOAT32, &px), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_add_property(&g, "feature_dir_y", PNPR_TYPE_FLOAT32, &py), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_add_property(&g, "feature_dir_z", PNPR_TYPE_FLOAT32, &pz), PNPR_OK);
        pz = pnpr_cloud_find_property(&g, "feature_dir_z");
        pc = pnpr_cloud_find_property(&g, "feature_class");
        px = pnpr_cloud_find_property(&g, "feature_dir_x");
    }
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            size_t k = (size_t)j * nx + i;
            g.xyz[3 * k] = (float)((i - 0.5 * (nx - 1)) * h);
            g.xyz[3 * k + 1] = (float)((j - 0.5 * (ny - 1)) * h);
            g.xyz[3 * k + 2] = (float)z;
            memcpy(g.rgb + 3 * k, rgb, 3);
            if (pc) {
                ((uint8_t *)pc->data)[k] = (uint8_t)feature_class;
                ((float *)px->data)[k] = 1;
            }
        }
    CHECK_STATUS(pnpr_cloud_append(cl, &g), PNPR_OK);
    pnpr_cloud_free(&g);
}

static pnpr_status render(pnpr_renderer *r, const pnpr_camera *cam, const pnpr_draw_options *o,
                          uint8_t *px, pnpr_render_stats *st)
{
    pnpr_target t = {0, 0, 0, W, H, 1, 0};
    pnpr_error err = {0};
    pnpr_status s = pnpr_renderer_draw(r, cam, o, &t, st, &err);
    if (s != PNPR_OK) { fprintf(stderr, "draw: %s\n", err.message); return s; }
    return pnpr_renderer_read_frame(r, px, 0);
}

static int is_red(const uint8_t *p) { return p[0] > p[1] + 40 && p[0] > p[2] + 40; }

/* ---- occlusion: red points behind an opaque blue plane ---------------------------------- */
static void test_occlusion(pnpr_renderer *r)
{
    static const uint8_t blue[3] = {20, 40, 230}, red[3] = {240, 10, 10};
    pnpr_camera cam = look(0, 0, 6, 0, 0, 0);
    for (int style = 0; style < 2; style++) {
        for (int with_plane = 0; with_plane < 2; with_plane++) {
            pnpr_cloud cl = {0};
            add_grid(&cl, 41, 41, 0.05, -0.6, red, PNPR_CLASS_DIRECTIONAL);   /* 2 x 2, behind */
            if (with_plane) add_grid(&cl, 81, 81, 0.05, 0.0, blue, PNPR_CLASS_NONDIRECTIONAL); /* 4 x 4 */
            CHECK_STATUS(pnpr_renderer_set_cloud(r, &cl, NULL, NULL), PNPR_OK);
            pnpr_draw_options o;
            memset(&o, 0, sizeof o);
            o.style = (pnpr_style)style;
            o.ink_from_points = 1;
            o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
            uint8_t *px = malloc(W * H * 4);
            CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_OK);
            /* the plane covers the middle of the image (the red square projects inside it) */
            size_t reds = 0;
            for (int y = H / 4; y < 3 * H / 4; y++)
                for (int x = W / 4; x < 3 * W / 4; x++) reds += is_red(px + 4 * ((size_t)y * W + x));
            if (with_plane) CHECK_MSG(reds == 0, "style %d: %zu red pixels show through the plane", style, reds);
            else CHECK_MSG(reds > 100, "style %d: the red cloud alone shows (%zu red pixels)", style, reds);
            free(px);
            pnpr_cloud_free(&cl);
        }
    }
}

/* ---- background: exactly the background colour where nothing is drawn ------------------ */
static void test_background(pnpr_renderer *r)
{
    static const uint8_t grey[3] = {128, 128, 128};
    pnpr_cloud cl = {0};
    add_grid(&cl, 21, 21, 0.05, 0, grey, PNPR_CLASS_DIRECTIONAL); /* 1 x 1 square */
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &cl, NULL, NULL), PNPR_OK);
    pnpr_camera cam = look(0, 0, 8, 0, 0, 0); /* the square covers the centre only */
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.background[0] = 37 / 255.0f; o.background[1] = 201 / 255.0f; o.background[2] = 99 / 255.0f; o.background[3] = 1;
    uint8_t *px = malloc(W * H * 4);
    for (int style = 0; style < 2; style++) {
        o.style = (pnpr_style)style;
        CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_OK);
        size_t bad = 0, drawn = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                const uint8_t *p = px + 4 * ((size_t)y * W + x);
                int is_bg = p[0] == 37 && p[1] == 201 && p[2] == 99 && p[3] == 255;
                int border = x < W / 4 || x >= 3 * W / 4 || y < H / 8 || y >= 7 * H / 8;
                if (border && !is_bg) bad++;
                drawn += !is_bg;
            }
        CHECK_MSG(bad == 0, "style %d: %zu border pixels differ from the background", style, bad);
        CHECK_MSG(drawn > 50, "style %d: something is drawn (%zu)", style, drawn);
    }
    /* empty cloud: the whole frame is the background, for every style */
    pnpr_cloud empty = {0};
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &empty, NULL, NULL), PNPR_OK);
    for (int style = 0; style < 2; style++) {
        o.style = (pnpr_style)style;
        pnpr_render_stats st;
        CHECK_STATUS(render(r, NULL, &o, px, &st), PNPR_OK);
        size_t bad = 0;
        for (size_t i = 0; i < (size_t)W * H; i++)
            bad += !(px[4 * i] == 37 && px[4 * i + 1] == 201 && px[4 * i + 2] == 99 && px[4 * i + 3] == 255);
        CHECK_MSG(bad == 0, "empty cloud, style %d: %zu non-background pixels", style, bad);
        CHECK(st.points_drawn == 0 && st.points_total == 0);
    }
    free(px);
    pnpr_cloud_free(&cl);
}

/* ---- CRQ: a budget draws at most b points, nested as b grows ---------------------------- */
static void test_crq_prefix(pnpr_renderer *r)
{
    enum { NX = 16, N = NX * NX };
    pnpr_cloud cl = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&cl, N), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&cl), PNPR_OK);
    for (int i = 0; i < N; i++) { /* point i has colour (i, 200, 50) */
        cl.xyz[3 * i] = (float)((i % NX) - 7.5);
        cl.xyz[3 * i + 1] = (float)((i / NX) - 7.5);
        cl.xyz[3 * i + 2] = 0;
        cl.rgb[3 * i] = (uint8_t)i; cl.rgb[3 * i + 1] = 200; cl.rgb[3 * i + 2] = 50;
    }
    pnpr_upload_options uo;
    memset(&uo, 0, sizeof uo);
    uo.seed = 1234;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &cl, &uo, NULL), PNPR_OK);
    pnpr_camera cam = look(0, 0, 30, 0, 0, 0);
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.point_scale = 0.1f;
    uint8_t *px = malloc(W * H * 4);
    /* each point has a cell of its own here (per-cell queues of one point: crq.h): a budget draws
     * at most b and, the queues' offsets spread evenly, within a few of b; the points seen are
     * the points counted, and a larger budget keeps every point of a smaller one */
    static const size_t budgets[] = {1, 17, 64, 200, 256};
    char last[N] = {0};
    for (size_t t = 0; t < sizeof budgets / sizeof budgets[0]; t++) {
        size_t b = budgets[t];
        o.budget = b;
        pnpr_render_stats st;
        CHECK_STATUS(render(r, &cam, &o, px, &st), PNPR_OK);
        CHECK_MSG(st.points_drawn <= st.points_sent && st.points_sent <= b && st.points_drawn + 3 >= b && st.points_total == N,
                  "budget %zu: %zu drawn, %zu sent", b, st.points_drawn, st.points_sent);
        char seen[N] = {0};
        size_t nseen = 0, lost = 0;
        for (size_t i = 0; i < (size_t)W * H; i++)
            if (px[4 * i + 1] == 200 && px[4 * i + 2] == 50) seen[px[4 * i]] = 1;
        for (size_t p = 0; p < N; p++) {
            nseen += seen[p];
            lost += last[p] && !seen[p];
        }
        CHECK_MSG(nseen == st.points_drawn && lost == 0, "budget %zu: %zu points seen, %zu drawn, %zu of the smaller budget's lost",
                  b, nseen, st.points_drawn, lost);
        memcpy(last, seen, N);
    }
    /* density: fewer points when the cloud covers less of the screen */
    o.budget = 0;
    o.density = 0.02f;
    pnpr_render_stats near, far;
    CHECK_STATUS(render(r, &cam, &o, px, &near), PNPR_OK);
    pnpr_camera cam_far = look(0, 0, 60, 0, 0, 0);
    CHECK_STATUS(render(r, &cam_far, &o, px, &far), PNPR_OK);
    CHECK_MSG(far.points_drawn < near.points_drawn && far.points_drawn > 0,
              "density: near %zu, far %zu points", near.points_drawn, far.points_drawn);
    CHECK_NEAR((double)near.points_drawn, ceil(0.02 * near.coverage_px), 0.02 * ceil(0.02 * near.coverage_px) + 2);
    free(px);
    pnpr_cloud_free(&cl);
}

/* A small cube with computed features, for sketchy frames. */
static void feature_cube(pnpr_cloud *cl)
{
    static const double off[3] = {1000.5, -2000.25, 30};
    CHECK_STATUS(pnpr_test_cube(cl, 1.0, 0.025, 0.0, off, 5), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(cl), PNPR_OK);
    memset(cl->rgb, 180, cl->count * 3);
    pnpr_features_options fo;
    memset(&fo, 0, sizeof fo);
    CHECK_STATUS(pnpr_compute_features(cl, &fo, NULL), PNPR_OK);
}

/* ---- determinism: same input and seed, identical images --------------------------------- */
static void test_determinism(pnpr_cloud *cube)
{
    uint8_t *a = malloc(W * H * 4), *b = malloc(W * H * 4);
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_SKETCHY;
    o.budget = cube->count / 3;
    o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
    static const double dir[3] = {1, -2, 1.5};
    pnpr_camera cam;
    CHECK_STATUS(pnpr_camera_fit(cube, dir, 40, (float)W / H, &cam), PNPR_OK);
    pnpr_upload_options uo;
    memset(&uo, 0, sizeof uo);
    uo.seed = 99;
    for (int run = 0; run < 3; run++) {
        pnpr_renderer *r = NULL;
        CHECK_STATUS(pnpr_renderer_create(NULL, &r, NULL), PNPR_OK);
        if (!r) break;
        if (run == 2) uo.seed = 100;
        CHECK_STATUS(pnpr_renderer_set_cloud(r, cube, &uo, NULL), PNPR_OK);
        CHECK(pnpr_renderer_has_features(r));
        CHECK_STATUS(render(r, &cam, &o, run == 0 ? a : b, NULL), PNPR_OK);
        if (run == 1) CHECK_MSG(memcmp(a, b, W * H * 4) == 0, "same seed, different images");
        if (run == 2) CHECK_MSG(memcmp(a, b, W * H * 4) != 0, "another seed, same image under a budget");
        pnpr_renderer_destroy(r);
    }
    /* and something was drawn: dark stroke pixels on the white background */
    size_t dark = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) dark += a[4 * i] < 128;
    CHECK_MSG(dark > 100, "sketchy cube: %zu dark pixels", dark);
    free(a);
    free(b);
}

/* ---- the disk radii from the feature stage's point_spacing ---------------------------------- */
/* The upload takes the radii from point_spacing (props.h) instead of its own kNN: the frames are
 * byte-identical with and without the property; a property of one constant value for every point
 * is used (every disk that radius: another frame), one with a NaN in it is not (the upload's own
 * kNN: the same frame as without). Sketchy and points (whose disks show their radii); painterly's
 * data left out (skip_painterly), as the CLI does for these styles: painterly needs the kNN's
 * neighbour lists anyway. */
static void test_stored_spacing(pnpr_cloud *cube)
{
    uint8_t *ref = malloc(W * H * 4), *px = malloc(W * H * 4);
    pnpr_property *sp = pnpr_cloud_find_property(cube, PNPR_PROP_POINT_SPACING);
    CHECK(sp != NULL && sp->type == PNPR_TYPE_FLOAT32);
    float *saved = sp ? malloc(cube->count * sizeof *saved) : NULL;
    static const double dir[3] = {1, -2, 1.5};
    pnpr_camera cam;
    CHECK_STATUS(pnpr_camera_fit(cube, dir, 40, (float)W / H, &cam), PNPR_OK);
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, NULL), PNPR_OK);
    pnpr_upload_options uo;
    memset(&uo, 0, sizeof uo);
    uo.skip_painterly = 1;
    for (int s = 0; r && ref && px && saved && s < 2; s++) {
        float *v = sp->data;
        memcpy(saved, v, cube->count * sizeof *saved);
        pnpr_draw_options o;
        memset(&o, 0, sizeof o);
        o.style = s ? PNPR_STYLE_SKETCHY : PNPR_STYLE_POINTS;
        o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
        /* the reference: no property, the upload's own kNN */
        sp->name[0] = 'x';
        CHECK_STATUS(pnpr_renderer_set_cloud(r, cube, &uo, NULL), PNPR_OK);
        CHECK_STATUS(render(r, &cam, &o, ref, NULL), PNPR_OK);
        sp->name[0] = 'p';
        CHECK_STATUS(pnpr_renderer_set_cloud(r, cube, &uo, NULL), PNPR_OK);
        CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_OK);
        CHECK_MSG(!memcmp(ref, px, W * H * 4), "%s: the stored spacing changed the frame", pnpr_style_name(o.style));
        for (size_t i = 0; i < cube->count; i++) v[i] = 0.08f;
        CHECK_STATUS(pnpr_renderer_set_cloud(r, cube, &uo, NULL), PNPR_OK);
        CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_OK);
        CHECK_MSG(memcmp(ref, px, W * H * 4) != 0, "%s: a constant point_spacing was not used", pnpr_style_name(o.style));
        memcpy(v, saved, cube->count * sizeof *saved);
        v[cube->count / 2] = NAN;
        CHECK_STATUS(pnpr_renderer_set_cloud(r, cube, &uo, NULL), PNPR_OK);
        CHECK_STATUS(render(r, &cam, &o, px, NULL), PNPR_OK);
        CHECK_MSG(!memcmp(ref, px, W * H * 4), "%s: a NaN point_spacing was used", pnpr_style_name(o.style));
        memcpy(v, saved, cube->count * sizeof *saved);
    }
    pnpr_renderer_destroy(r);
    free(saved);
    free(ref);
    free(px);
}

/* ---- host GL state: everything the renderer touches is put back ------------------------- */
typedef struct snapshot { GLint v[64][4]; GLboolean e[32]; } snapshot;

static const GLenum snap_ints[] = {
    GL_DRAW_FRAMEBUFFER_BINDING, GL_READ_FRAMEBUFFER_BINDING, GL_RENDERBUFFER_BINDING, GL_VIEWPORT,
    GL_SCISSOR_BOX, GL_DEPTH_FUNC, GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA,
    GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA, GL_CURRENT_PROGRAM,
    GL_VERTEX_ARRAY_BINDING, GL_ARRAY_BUFFER_BINDING, GL_ACTIVE_TEXTURE, GL_PACK_ALIGNMENT,
    GL_UNPACK_ALIGNMENT, GL_PACK_ROW_LENGTH, GL_UNPACK_ROW_LENGTH, GL_PIXEL_PACK_BUFFER_BINDING,
    GL_PIXEL_UNPACK_BUFFER_BINDING, GL_POLYGON_MODE, GL_UNIFORM_BUFFER_BINDING, GL_DRAW_BUFFER,
    GL_READ_BUFFER, GL_ELEMENT_ARRAY_BUFFER_BINDING};
static const GLenum snap_enables[] = {
    GL_SCISSOR_TEST, GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_STENCIL_TEST, GL_PROGRAM_POINT_SIZE,
    GL_FRAMEBUFFER_SRGB, GL_POLYGON_OFFSET_FILL, GL_SAMPLE_ALPHA_TO_COVERAGE, GL_DEPTH_CLAMP,
    GL_RASTERIZER_DISCARD, GL_MULTISAMPLE, GL_COLOR_LOGIC_OP};
enum { N_INTS = sizeof snap_ints / sizeof snap_ints[0], N_EN = sizeof snap_enables / sizeof snap_enables[0] };

static void take(snapshot *s)
{
    memset(s, 0, sizeof *s);
    for (int i = 0; i < N_INTS; i++) glGetIntegerv(snap_ints[i], s->v[i]);
    for (int i = 0; i < N_EN; i++) s->e[i] = glIsEnabled(snap_enables[i]);
    int k = N_INTS;
    GLboolean b[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, b);
    for (int i = 0; i < 4; i++) s->v[k][i] = b[i];
    glGetBooleanv(GL_DEPTH_WRITEMASK, b);
    s->v[k + 1][0] = b[0];
    GLfloat f[4];
    glGetFloatv(GL_COLOR_CLEAR_VALUE, f);
    for (int i = 0; i < 4; i++) s->v[k + 2][i] = (GLint)(f[i] * 1000);
    glGetFloatv(GL_DEPTH_CLEAR_VALUE, f);
    s->v[k + 3][0] = (GLint)(f[0] * 1000);
    /* texture unit 0 (the renderer's) and unit 3 (the active one) */
    GLint active;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (int u = 0; u < 2; u++) {
        glActiveTexture(u == 0 ? GL_TEXTURE0 : GL_TEXTURE3);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &s->v[k + 4 + u][0]);
        glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &s->v[k + 4 + u][1]);
        glGetIntegerv(GL_SAMPLER_BINDING, &s->v[k + 4 + u][2]);
    }
    glActiveTexture((GLenum)active);
}

static void test_gl_state(pnpr_cloud *cube)
{
    /* a host with a framebuffer, a program, a VAO, textures, a sampler and odd settings */
    GLuint fbo, tex, tex_arr, tex3, rb, vao, buf, ubo, sampler;
    glGenFramebuffers(1, &fbo);
    glGenTextures(1, &tex);
    glGenTextures(1, &tex_arr);
    glGenTextures(1, &tex3);
    glGenRenderbuffers(1, &rb);
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &buf);
    glGenBuffers(1, &ubo);
    glGenSamplers(1, &sampler);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 300, 200, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    CHECK(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    glClearColor(1, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    const char *vs = "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n";
    const char *fs = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
    GLuint sv = glCreateShader(GL_VERTEX_SHADER), sf = glCreateShader(GL_FRAGMENT_SHADER);
    glShaderSource(sv, 1, &vs, NULL); glCompileShader(sv);
    glShaderSource(sf, 1, &fs, NULL); glCompileShader(sf);
    GLuint prog = glCreateProgram();
    glAttachShader(prog, sv); glAttachShader(prog, sf); glLinkProgram(prog);
    glUseProgram(prog);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, buf);
    glBindBuffer(GL_UNIFORM_BUFFER, ubo);
    glBindTexture(GL_TEXTURE_2D_ARRAY, tex_arr);
    glBindSampler(0, sampler);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, tex3);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glViewport(3, 5, 17, 19);
    glScissor(1, 2, 30, 40);
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_COLOR, GL_DST_ALPHA, GL_ONE_MINUS_DST_COLOR, GL_CONSTANT_ALPHA);
    glBlendEquationSeparate(GL_MAX, GL_FUNC_REVERSE_SUBTRACT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_FALSE);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glEnable(GL_CULL_FACE);
    glEnable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glClearColor(0.25f, 0.5f, 0.75f, 0.125f);
    glClearDepth(0.5);
    glPixelStorei(GL_PACK_ALIGNMENT, 2);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
    CHECK(glGetError() == GL_NO_ERROR);

    snapshot before, after;
    take(&before);
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, NULL), PNPR_OK);
    if (r) {
        CHECK_STATUS(pnpr_renderer_set_cloud(r, cube, NULL, NULL), PNPR_OK);
        uint8_t *px = malloc(W * H * 4);
        for (int style = 0; style < 2; style++) {
            pnpr_draw_options o;
            memset(&o, 0, sizeof o);
            o.style = (pnpr_style)style;
            o.background[0] = o.background[3] = 1; /* opaque red, as the host's clear */
            pnpr_target t = {fbo, 40, 30, W, H, 0, 0}; /* composite into the host's framebuffer */
            CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t, NULL, NULL), PNPR_OK);
            CHECK_STATUS(pnpr_renderer_read_frame(r, px, 0), PNPR_OK);
            t.offscreen = 1;
            CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t, NULL, NULL), PNPR_OK);
        }
        take(&after);
        CHECK(glGetError() == GL_NO_ERROR);
        for (int i = 0; i < N_INTS + 8; i++)
            CHECK_MSG(memcmp(before.v[i], after.v[i], sizeof before.v[i]) == 0,
                      "state %d (0x%x) changed: %d %d %d %d -> %d %d %d %d", i, i < N_INTS ? snap_ints[i] : 0,
                      before.v[i][0], before.v[i][1], before.v[i][2], before.v[i][3],
                      after.v[i][0], after.v[i][1], after.v[i][2], after.v[i][3]);
        for (int i = 0; i < N_EN; i++)
            CHECK_MSG(before.e[i] == after.e[i], "enable 0x%x changed", snap_enables[i]);

        /* the composite (REPLACE) put the frame at (40, 30) of the host framebuffer, exactly */
        uint8_t *host = malloc(W * H * 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        glReadPixels(40, 30, W, H, GL_RGBA, GL_UNSIGNED_BYTE, host);
        size_t diff = 0;
        for (int y = 0; y < H; y++) /* host rows bottom-up, frame rows top-down */
            diff += memcmp(host + (size_t)y * W * 4, px + (size_t)(H - 1 - y) * W * 4, W * 4) != 0;
        CHECK_MSG(diff == 0, "%zu composited rows differ from the frame", diff);
        /* outside the rectangle the host's pixels are untouched (its red clear) */
        uint8_t corner[4];
        glReadPixels(5, 5, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, corner);
        CHECK(corner[0] == 255 && corner[1] == 0 && corner[2] == 0);

        /* OVER: a transparent background leaves the host's pixels */
        glDisable(GL_FRAMEBUFFER_SRGB);
        glClearColor(0, 0, 1, 1);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDisable(GL_SCISSOR_TEST);
        glClear(GL_COLOR_BUFFER_BIT);
        pnpr_draw_options o;
        memset(&o, 0, sizeof o);
        o.composite = PNPR_COMPOSITE_OVER;
        pnpr_target t = {fbo, 0, 0, W, H, 0, 0};
        static const double dir[3] = {0, -1, 0.5};
        pnpr_camera cam;
        CHECK_STATUS(pnpr_camera_fit(cube, dir, 45, (float)W / H, &cam), PNPR_OK);
        cam.target[0] += 3; /* look beside the cube: nothing drawn */
        cam.eye[0] += 3;
        CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, NULL), PNPR_OK);
        glReadPixels(W / 2, H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, corner);
        CHECK_MSG(corner[0] == 0 && corner[1] == 0 && corner[2] == 255, "OVER: %d %d %d", corner[0], corner[1], corner[2]);

        snapshot s1, s2;
        take(&s1);
        pnpr_renderer_destroy(r);
        take(&s2);
        CHECK(memcmp(&s1, &s2, sizeof s1) == 0);
        CHECK(glGetError() == GL_NO_ERROR);
        free(px);
        free(host);
    }
    glDeleteProgram(prog); glDeleteShader(sv); glDeleteShader(sf);
    glDeleteFramebuffers(1, &fbo);
    GLuint texs[3] = {tex, tex_arr, tex3};
    glDeleteTextures(3, texs);
    glDeleteRenderbuffers(1, &rb);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &buf);
    glDeleteBuffers(1, &ubo);
    glDeleteSamplers(1, &sampler);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_CULL_FACE);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glActiveTexture(GL_TEXTURE0);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

/* ---- bad input: clear errors or defined images, never a crash --------------------------- */
static void test_bad_input(pnpr_renderer *r)
{
    pnpr_error err;
    uint8_t *px = malloc(W * H * 4);
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    pnpr_target t = {0, 0, 0, W, H, 1, 0};
    static const uint8_t grey[3] = {100, 100, 100};
    pnpr_cloud cl = {0};
    add_grid(&cl, 10, 10, 0.1, 0, grey, -1); /* no features */
    /* NaN positions: dropped */
    cl.xyz[0] = NAN;
    cl.xyz[3 * 7 + 2] = INFINITY;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &cl, NULL, NULL), PNPR_OK);
    pnpr_render_stats st;
    CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t, &st, NULL), PNPR_OK);
    CHECK(st.points_total == 98 && st.points_drawn == 98);
    /* sketchy without features: NOT_FOUND with a message */
    o.style = PNPR_STYLE_SKETCHY;
    memset(&err, 0, sizeof err);
    CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t, NULL, &err), PNPR_ERR_NOT_FOUND);
    CHECK(strstr(err.message, "feature_class") != NULL);
    o.style = PNPR_STYLE_POINTS;
    /* zero / negative size */
    pnpr_target t0 = {0, 0, 0, 0, H, 1, 0};
    memset(&err, 0, sizeof err);
    CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t0, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(err.message[0] != 0);
    t0.width = W; t0.height = -3;
    CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t0, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    t0.height = 1 << 30;
    CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t0, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, NULL, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    /* bad options */
    o.style = (pnpr_style)17;
    CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    o.style = PNPR_STYLE_POINTS;
    o.point_scale = NAN;
    CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    o.point_scale = 0;
    o.background[1] = INFINITY;
    CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    o.background[1] = 0;
    /* bad cameras */
    pnpr_camera cam = look(0, 0, 5, 0, 0, 0);
    cam.eye[1] = NAN;
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, NULL), PNPR_ERR_NUMERIC);
    cam = look(1, 2, 3, 1, 2, 3);
    memset(&err, 0, sizeof err);
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, &err), PNPR_ERR_INVALID_ARGUMENT); /* finite, but no direction */
    CHECK(strstr(err.message, "same point") != NULL);
    cam = look(0, 5, 0, 0, 0, 0); /* up (0,1,0) parallel to the view direction */
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "parallel") != NULL);
    cam = look(0, 0, 5, 0, 0, 0);
    cam.fov_y_deg = 200;
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    /* camera looking away: only background */
    cam = look(0, 0, 5, 0, 0, 10);
    o.background[2] = o.background[3] = 1;
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, &st, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_read_frame(r, px, 0), PNPR_OK);
    CHECK(px[0] == 0 && px[1] == 0 && px[2] == 255 && px[3] == 255);
    /* all points NaN: like an empty cloud */
    for (size_t i = 0; i < cl.count * 3; i++) cl.xyz[i] = NAN;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &cl, NULL, NULL), PNPR_OK);
    o.style = PNPR_STYLE_SKETCHY; /* no points: nothing needs features */
    CHECK_STATUS(pnpr_renderer_draw(r, NULL, &o, &t, &st, NULL), PNPR_OK);
    CHECK(st.points_total == 0);
    /* one point, and duplicates only */
    pnpr_cloud one = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&one, 5), PNPR_OK); /* five points at the origin */
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &one, NULL, NULL), PNPR_OK);
    o.style = PNPR_STYLE_POINTS;
    /* the box is a point: it covers its one pixel, so the default screen density (2 per covered
     * pixel) draws 2 of the 5; every point without the limit */
    CHECK_STATUS(render(r, NULL, &o, px, &st), PNPR_OK);
    CHECK_MSG(st.coverage_px == 1 && st.points_drawn == 2, "duplicates: %g px covered, %zu drawn", st.coverage_px,
              st.points_drawn);
    o.density = -1;
    CHECK_STATUS(render(r, NULL, &o, px, &st), PNPR_OK);
    CHECK(st.points_drawn == 5);
    o.density = 0;
    one.count = 1;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &one, NULL, NULL), PNPR_OK);
    CHECK_STATUS(render(r, NULL, &o, px, &st), PNPR_OK);
    CHECK(st.coverage_px == 1 && st.points_drawn == 1);
    one.count = 5;
    pnpr_cloud_free(&one);
    /* a cloud with points but no coordinates */
    pnpr_cloud broken = {0};
    broken.count = 3;
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &broken, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_renderer_set_cloud(NULL, &cl, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_renderer_read_frame(r, NULL, 0), PNPR_ERR_INVALID_ARGUMENT);
    /* styles by name */
    pnpr_style s;
    CHECK_STATUS(pnpr_style_from_name("sketchy", &s), PNPR_OK);
    CHECK(s == PNPR_STYLE_SKETCHY);
    CHECK_STATUS(pnpr_style_from_name("oil", &s), PNPR_ERR_NOT_FOUND);
    CHECK(strcmp(pnpr_style_name((pnpr_style)99), "") == 0);
    /* PNG: bad arguments and an unwritable path */
    CHECK_STATUS(pnpr_write_png("/nonexistent-dir/x.png", px, W, H, 0, NULL), PNPR_ERR_IO);
    CHECK_STATUS(pnpr_write_png(PNPR_TEST_SCRATCH "/x.png", px, 0, H, 0, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_write_png(PNPR_TEST_SCRATCH "/x.png", px, W, H, 1, NULL), PNPR_OK);
    free(px);
    pnpr_cloud_free(&cl);
}

/* ---- two renderers in two contexts -------------------------------------------------------- */
static void test_two_contexts(pnpr_gl_context *ctx_a, pnpr_cloud *cube)
{
    pnpr_gl_context *ctx_b = NULL;
    CHECK_STATUS(pnpr_gl_context_create(&ctx_b, NULL), PNPR_OK); /* now current */
    if (!ctx_b) return;
    static const uint8_t green[3] = {0, 200, 0};
    pnpr_cloud grid = {0};
    add_grid(&grid, 30, 30, 0.05, 0, green, -1);
    pnpr_renderer *rb = NULL, *ra = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &rb, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_cloud(rb, &grid, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_gl_context_make_current(ctx_a), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_create(NULL, &ra, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_cloud(ra, cube, NULL, NULL), PNPR_OK);
    if (!ra || !rb) return;
    uint8_t *a1 = malloc(W * H * 4), *a2 = malloc(W * H * 4), *b1 = malloc(W * H * 4), *b2 = malloc(W * H * 4);
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_SKETCHY;
    o.background[3] = 1;
    pnpr_draw_options ob;
    memset(&ob, 0, sizeof ob);
    ob.background[3] = 1;
    CHECK_STATUS(render(ra, NULL, &o, a1, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_gl_context_make_current(ctx_b), PNPR_OK);
    CHECK_STATUS(render(rb, NULL, &ob, b1, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_gl_context_make_current(ctx_a), PNPR_OK);
    CHECK_STATUS(render(ra, NULL, &o, a2, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_gl_context_make_current(ctx_b), PNPR_OK);
    CHECK_STATUS(render(rb, NULL, &ob, b2, NULL), PNPR_OK);
    CHECK(memcmp(a1, a2, W * H * 4) == 0);
    CHECK(memcmp(b1, b2, W * H * 4) == 0);
    CHECK(memcmp(a1, b1, W * H * 4) != 0);
    size_t green_px = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) green_px += b1[4 * i + 1] == 200 && b1[4 * i] == 0;
    CHECK_MSG(green_px > 1000, "context B draws its own cloud (%zu green pixels)", green_px);
    pnpr_renderer_destroy(rb);
    CHECK_STATUS(pnpr_gl_context_make_current(ctx_a), PNPR_OK);
    pnpr_renderer_destroy(ra);
    pnpr_gl_context_destroy(ctx_b);
    CHECK_STATUS(pnpr_gl_context_make_current(ctx_a), PNPR_OK);
    free(a1); free(a2); free(b1); free(b2);
    pnpr_cloud_free(&grid);
}

int main(void)
{
    /* No context current yet: a clear error. */
    pnpr_renderer *r = NULL;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_ERR_UNSUPPORTED);
    CHECK(r == NULL && strstr(err.message, "context") != NULL);

    pnpr_gl_context *ctx = NULL;
    pnpr_status st = pnpr_gl_context_create(&ctx, &err);
    if (st != PNPR_OK) {
        fprintf(stderr, "test_render_gl: skipped: %s\n", err.message);
        return 77;
    }
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    if (r) {
        test_occlusion(r);
        test_background(r);
        test_crq_prefix(r);
        test_bad_input(r);
        pnpr_renderer_destroy(r);
    }
    pnpr_cloud cube = {0};
    feature_cube(&cube);
    test_determinism(&cube);
    test_stored_spacing(&cube);
    test_gl_state(&cube);
    test_two_contexts(ctx, &cube);
    pnpr_cloud_free(&cube);
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_gl");
}
