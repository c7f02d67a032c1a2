/* Segment-specific image-space effects through the renderer (pnpr_renderer_effects), with known
 * answers on a generated scene: a back plane (segment 2, blue) and a square in front of it
 * (segment 1, red), 0.4 apart.
 *   - For every effect: inside the square, the picture equals that of the square alone (the near
 *     segment occludes the far one), and away from the square it equals that of the back plane
 *     alone; two runs give the same bytes.
 *   - A filter that paints around the square (a blur): inpainted layering shows that paint over
 *     the back plane; the per-fragment depth test and plain layering lose it (paper figure 12).
 *   - A sparse square (holes between its splats) smoothed by watercolour: no hole shows the back
 *     plane with inpainting, many do without; nothing bleeds beyond the inpainting radius.
 *   - Filters on the filter thread give the bytes of serial filters; cancelling and a failing
 *     filter end the frame on both paths; preview layers (scale) are smaller and close to the
 *     full picture.
 *   - A layer's frame draws only its points; the next plain frame draws all again; an empty
 *     cloud gives one layer of paper.
 * Exits 77 (skipped) when this machine has no headless EGL / GL 3.3. */
#include "testutil.h"

#include <pointnpr/render.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 200, H = 160 };
static const double SP = 0.025; /* point spacing */

static void put_square(pnpr_cloud *c, size_t *k, double x0, double y0, double z, int n, uint32_t label,
                       const uint8_t rgb[3])
{
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            size_t q = (*k)++;
            c->xyz[3 * q] = (float)(x0 + i * SP);
            c->xyz[3 * q + 1] = (float)(y0 + j * SP);
            c->xyz[3 * q + 2] = (float)z;
            c->label[q] = label;
            memcpy(c->rgb + 3 * q, rgb, 3);
        }
}

enum { BACK = 81, FRONT = 25 };
static const uint8_t blue[3] = {60, 90, 200}, red[3] = {210, 50, 40};

/* The scene: which = 1 front only, 2 back only, 3 both. */
static pnpr_status scene(pnpr_cloud *c, int which)
{
    size_t n = (which & 2 ? BACK * BACK : 0) + (which & 1 ? FRONT * FRONT : 0), k = 0;
    pnpr_status st = pnpr_cloud_alloc(c, n);
    if (st == PNPR_OK) st = pnpr_cloud_alloc_rgb(c);
    if (st == PNPR_OK) st = pnpr_cloud_alloc_labels(c);
    if (st != PNPR_OK) return st;
    if (which & 2) put_square(c, &k, 0, 0, 0, BACK, 2, blue);
    if (which & 1) put_square(c, &k, 0.7, 0.7, 0.4, FRONT, 1, red);
    return PNPR_OK;
}

static pnpr_status effects(pnpr_renderer *r, int which, const char *text, pnpr_layering mode, float point_scale,
                           uint8_t *px)
{
    pnpr_cloud c = {0};
    pnpr_error err = {0};
    pnpr_effect_pipeline p = {0};
    pnpr_status st = scene(&c, which);
    if (st == PNPR_OK) st = pnpr_renderer_set_cloud(r, &c, NULL, &err);
    if (st == PNPR_OK) st = pnpr_effect_pipeline_parse(text, strlen(text), "test.fx", &p, &err);
    if (st == PNPR_OK) {
        p.layering = mode;
        pnpr_camera cam = {{1, 1, 5}, {1, 1, 0}, {0, 1, 0}, 30, 0, 0};
        pnpr_draw_options o;
        memset(&o, 0, sizeof o);
        o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
        o.point_scale = point_scale;
        pnpr_effects_stats es;
        st = pnpr_renderer_effects(r, &cam, &o, &p, W, H, NULL, px, &es, &err);
        if (st == PNPR_OK && es.layers != (size_t)(which == 3 ? 2 : 1)) st = PNPR_ERR_INVALID_ARGUMENT;
    }
    if (st != PNPR_OK) fprintf(stderr, "effects: %s\n", err.message);
    const char *dump = getenv("PNPR_TEST_DUMP"); /* a folder: every picture as a PNG, to look at */
    if (dump && st == PNPR_OK) {
        static int seq;
        char path[512];
        snprintf(path, sizeof path, "%s/effects_%03d.png", dump, seq++);
        if (pnpr_write_png(path, px, W, H, 0, NULL) != PNPR_OK) fprintf(stderr, "cannot write %s\n", path);
    }
    pnpr_effect_pipeline_free(&p);
    pnpr_cloud_free(&c);
    return st;
}

/* The square's screen box: found from the front-only picture (non-white pixels). */
typedef struct box { int x0, y0, x1, y1; } box;
static box ink_box(const uint8_t *px)
{
    box b = {W, H, -1, -1};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *p = px + 4 * (y * W + x);
            if (p[0] > 250 && p[1] > 250 && p[2] > 250) continue;
            if (x < b.x0) b.x0 = x;
            if (x > b.x1) b.x1 = x;
            if (y < b.y0) b.y0 = y;
            if (y > b.y1) b.y1 = y;
        }
    return b;
}

static int inside(box b, int x, int y, int grow)
{
    return x >= b.x0 - grow && x <= b.x1 + grow && y >= b.y0 - grow && y <= b.y1 + grow;
}

/* Pixels of a and b that differ, inside box b grown by `grow` (in = 1) or outside it (in = 0). */
static size_t differ(const uint8_t *a, const uint8_t *b, box bx, int grow, int in)
{
    size_t n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (inside(bx, x, y, grow) == in) n += memcmp(a + 4 * (y * W + x), b + 4 * (y * W + x), 4) != 0;
    return n;
}

/* The box the raster of the square covers (no filter): the square's own pixels. */
static box square_box(pnpr_renderer *r, uint8_t *px)
{
    box none = {0, 0, -1, -1};
    if (effects(r, 1, "", PNPR_LAYERING_INPAINTED, 0, px) != PNPR_OK) return none;
    return ink_box(px);
}

static void test_every_effect_occludes(pnpr_renderer *r)
{
    uint8_t *both = malloc(W * H * 4), *front = malloc(W * H * 4), *back = malloc(W * H * 4), *again = malloc(W * H * 4);
    box sq = square_box(r, front);
    printf("square at %d..%d x %d..%d px\n", sq.x0, sq.x1, sq.y0, sq.y1);
    CHECK(sq.x1 - sq.x0 > 30 && sq.y1 - sq.y0 > 30);
    for (int k = 0; k < PNPR_EFFECT_COUNT_; k++) {
        char text[200];
        snprintf(text, sizeof text, "%s\nnode front labels 1\nnode back labels 2\n", pnpr_effect_name((pnpr_effect_kind)k));
        CHECK_STATUS(effects(r, 3, text, PNPR_LAYERING_INPAINTED, 0, both), PNPR_OK);
        CHECK_STATUS(effects(r, 1, text, PNPR_LAYERING_INPAINTED, 0, front), PNPR_OK);
        CHECK_STATUS(effects(r, 2, text, PNPR_LAYERING_INPAINTED, 0, back), PNPR_OK);
        /* 8 px in from the square's edge: the near segment's pixels, whatever the effect */
        size_t in = differ(both, front, (box){sq.x0 + 8, sq.y0 + 8, sq.x1 - 8, sq.y1 - 8}, 0, 1);
        /* farther than the inpainting radius plus the filters' reach (12 px): the back plane's */
        size_t out = differ(both, back, sq, 12, 0);
        printf("%-12s inside the square %zu px differ from the square alone, outside %zu from the back alone\n",
               pnpr_effect_name((pnpr_effect_kind)k), in, out);
        CHECK_MSG(in == 0 && out == 0, "%s: %zu, %zu", pnpr_effect_name((pnpr_effect_kind)k), in, out);
        CHECK_STATUS(effects(r, 3, text, PNPR_LAYERING_INPAINTED, 0, again), PNPR_OK);
        CHECK_MSG(memcmp(both, again, W * H * 4) == 0, "%s is deterministic", pnpr_effect_name((pnpr_effect_kind)k));
    }
    free(both); free(front); free(back); free(again);
}

/* Pixels of a and b that differ in the band 1..3 px outside box bx. */
static size_t band_differ(const uint8_t *a, const uint8_t *b, box bx)
{
    size_t n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (inside(bx, x, y, 3) && !inside(bx, x, y, 0)) n += memcmp(a + 4 * (y * W + x), b + 4 * (y * W + x), 4) != 0;
    return n;
}

/* A filter that paints outside the square (a smoothing that is not edge-preserving blurs its red
 * into the paper around it): over the back plane only the inpainted depth lets those pixels
 * through (paper figure 12). */
static void test_outlines_need_inpainting(pnpr_renderer *r)
{
    uint8_t *px = malloc(W * H * 4), *back = malloc(W * H * 4);
    box sq = square_box(r, px);
    const char *text = "node front labels 1\nsmooth sigma_color=1 radius=4\nnode back labels 2\n";
    CHECK_STATUS(effects(r, 2, text, PNPR_LAYERING_INPAINTED, 0, back), PNPR_OK);
    CHECK_STATUS(effects(r, 3, text, PNPR_LAYERING_INPAINTED, 0, px), PNPR_OK);
    size_t inpainted = band_differ(px, back, sq);
    CHECK_STATUS(effects(r, 3, text, PNPR_LAYERING_FRAGMENT, 0, px), PNPR_OK);
    size_t fragment = band_differ(px, back, sq);
    CHECK_STATUS(effects(r, 3, text, PNPR_LAYERING_NONE, 0, px), PNPR_OK);
    size_t none = band_differ(px, back, sq);
    size_t band = (size_t)((sq.x1 - sq.x0 + 7) * (sq.y1 - sq.y0 + 7) - (sq.x1 - sq.x0 + 1) * (sq.y1 - sq.y0 + 1));
    printf("the square's blurred edge over the back plane, in the 3 px band around it (%zu px): inpainted %zu px, "
           "fragment test %zu, no depth test %zu\n", band, inpainted, fragment, none);
    CHECK(inpainted > band / 2);
    /* no depth there: the back plane's own pixels; without depth test the back layer (drawn after
     * the square) paints over the band */
    CHECK(fragment == 0);
    CHECK(none == 0);
    free(px); free(back);
}

/* Pixels of the back plane's blue inside box b. */
static size_t blue_in(const uint8_t *px, box b)
{
    size_t n = 0;
    for (int y = b.y0; y <= b.y1; y++)
        for (int x = b.x0; x <= b.x1; x++) {
            const uint8_t *p = px + 4 * (y * W + x);
            n += p[2] > p[0] + 40;
        }
    return n;
}

static void test_sparse_holes(pnpr_renderer *r)
{
    uint8_t *px = malloc(W * H * 4), *back = malloc(W * H * 4), *plain = malloc(W * H * 4);
    box sq = square_box(r, plain);
    box core = {sq.x0 + 4, sq.y0 + 4, sq.x1 - 4, sq.y1 - 4};
    /* point scale 0.35: splats far apart, the back plane shows through the square */
    const char *raw = "node front labels 1\nnode back labels 2\n";
    CHECK_STATUS(effects(r, 3, raw, PNPR_LAYERING_INPAINTED, 0.35f, px), PNPR_OK);
    size_t holes_raw = blue_in(px, core);
    const char *wc = "node front labels 1\nwatercolour\nnode back labels 2\n";
    CHECK_STATUS(effects(r, 3, wc, PNPR_LAYERING_FRAGMENT, 0.35f, px), PNPR_OK);
    size_t holes_fragment = blue_in(px, core);
    CHECK_STATUS(effects(r, 3, wc, PNPR_LAYERING_INPAINTED, 0.35f, px), PNPR_OK);
    size_t holes = blue_in(px, core);
    CHECK_STATUS(effects(r, 2, wc, PNPR_LAYERING_INPAINTED, 0.35f, back), PNPR_OK);
    size_t bleed = differ(px, back, sq, PNPR_INPAINT_RADIUS + 12, 0);
    size_t n = (size_t)(core.x1 - core.x0 + 1) * (size_t)(core.y1 - core.y0 + 1);
    printf("sparse square (%zu px): back plane seen through %zu px raw, %zu with watercolour + fragment test, "
           "%zu with inpainting; %zu px differ from the back plane beyond the square\n",
           n, holes_raw, holes_fragment, holes, bleed);
    CHECK(holes_raw > n / 10);
    CHECK(holes_fragment > n / 10);
    CHECK(holes == 0);
    CHECK(bleed == 0);
    free(px); free(back); free(plain);
}

static void test_layer_then_plain(pnpr_renderer *r)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(scene(&c, 3), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    pnpr_camera cam = {{1, 1, 5}, {1, 1, 0}, {0, 1, 0}, 30, 0, 0};
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
    pnpr_target t = {0, 0, 0, W, H, 1, 0};
    uint8_t *a = malloc(W * H * 4), *b = malloc(W * H * 4);
    pnpr_render_stats s;
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, &s, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_read_frame(r, a, 0), PNPR_OK);
    uint32_t only = 2;
    pnpr_draw_options lo = o;
    lo.layer_labels = &only;
    lo.layer_label_count = 1;
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &lo, &t, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_read_frame(r, b, 0), PNPR_OK);
    size_t red_px = 0;
    for (int i = 0; i < W * H; i++) red_px += b[4 * i] > 150 && b[4 * i + 2] < 100;
    CHECK_MSG(red_px == 0, "the back plane's layer shows no red: %zu", red_px);
    lo.layer_exclude = 1; /* everything but label 2: the square */
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &lo, &t, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_read_frame(r, b, 0), PNPR_OK);
    size_t blue_px = 0;
    for (int i = 0; i < W * H; i++) blue_px += b[4 * i + 2] > b[4 * i] + 40;
    CHECK_MSG(blue_px == 0, "the layer without label 2 shows no blue: %zu", blue_px);
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_read_frame(r, b, 0), PNPR_OK);
    CHECK_MSG(memcmp(a, b, W * H * 4) == 0, "a plain frame after layers draws every point again");
    lo.layer_labels = NULL;
    lo.layer_label_count = 3;
    CHECK_STATUS(pnpr_renderer_draw(r, &cam, &lo, &t, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    /* the effects refuse layers and style maps in the base options */
    pnpr_effect_pipeline p = {0};
    CHECK_STATUS(pnpr_effect_pipeline_parse("", 0, "x", &p, NULL), PNPR_OK);
    lo.layer_labels = &only;
    lo.layer_label_count = 1;
    CHECK_STATUS(pnpr_renderer_effects(r, &cam, &lo, &p, W, H, NULL, a, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_renderer_effects(r, &cam, &o, &p, 0, H, NULL, a, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    /* an empty cloud: one layer (the root's) of paper, the background everywhere */
    pnpr_cloud empty = {0};
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &empty, NULL, NULL), PNPR_OK);
    pnpr_effect_pipeline_free(&p);
    const char *text = "toon\nnode a labels 1\nwatercolour\n";
    CHECK_STATUS(pnpr_effect_pipeline_parse(text, strlen(text), "x", &p, NULL), PNPR_OK);
    pnpr_effects_stats es;
    CHECK_STATUS(pnpr_renderer_effects(r, &cam, &o, &p, W, H, NULL, a, &es, NULL), PNPR_OK);
    size_t paper = 0;
    for (int i = 0; i < W * H; i++) paper += a[4 * i] == 255 && a[4 * i + 1] == 255 && a[4 * i + 2] == 255 && a[4 * i + 3] == 255;
    CHECK_MSG(es.layers == 1 && paper == (size_t)W * H, "empty cloud: %zu layers, %zu of %d px paper", es.layers, paper, W * H);
    pnpr_effect_pipeline_free(&p);
    free(a); free(b);
    pnpr_cloud_free(&c);
}

/* The scene with the back plane cut into 4 stripes (labels 2..5): 5 segments. */
static pnpr_status striped(pnpr_renderer *r)
{
    pnpr_cloud c = {0};
    pnpr_status st = scene(&c, 3);
    for (size_t q = 0; st == PNPR_OK && q < (size_t)BACK * BACK; q++) c.label[q] = 2 + (uint32_t)(q / BACK) * 4 / BACK;
    if (st == PNPR_OK) st = pnpr_renderer_set_cloud(r, &c, NULL, NULL);
    pnpr_cloud_free(&c);
    return st;
}

static int cancel_at_2(void *user, const char *stage, double fraction)
{
    (void)stage; (void)fraction;
    return ++*(int *)user >= 2;
}

/* Runs the pipeline `p` on the striped scene with the given options. */
static pnpr_status striped_effects(pnpr_renderer *r, const pnpr_effect_pipeline *p, const pnpr_effects_options *eo,
                                   uint8_t *px, pnpr_effects_stats *es)
{
    pnpr_camera cam = {{1, 1, 5}, {1, 1, 0}, {0, 1, 0}, 30, 0, 0};
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
    pnpr_error err = {0};
    pnpr_status st = pnpr_renderer_effects(r, &cam, &o, p, W, H, eo, px, es, &err);
    if (st != PNPR_OK && st != PNPR_ERR_CANCELLED) fprintf(stderr, "effects (expected or not): %s\n", err.message);
    return st;
}

/* The filter thread: the same bytes as filtering on the GL thread, over more layers than it has
 * slots; cancelling and a failing filter end the frame on either path (no hang, the status). */
static void test_filter_thread(pnpr_renderer *r)
{
    CHECK_STATUS(striped(r), PNPR_OK);
    const char *text = "per_label on\nwatercolour\nnode a labels 1 3\nper_label off\ntoon\n";
    pnpr_effect_pipeline p = {0};
    CHECK_STATUS(pnpr_effect_pipeline_parse(text, strlen(text), "x", &p, NULL), PNPR_OK);
    uint8_t *a = malloc(W * H * 4), *b = malloc(W * H * 4);
    pnpr_effects_options eo;
    memset(&eo, 0, sizeof eo);
    pnpr_effects_stats sa, sb;
    CHECK_STATUS(striped_effects(r, &p, &eo, a, &sa), PNPR_OK);
    eo.serial = 1;
    CHECK_STATUS(striped_effects(r, &p, &eo, b, &sb), PNPR_OK);
    CHECK_MSG(sa.layers == 4 && sb.layers == 4, "layers: threaded %zu, serial %zu (want 4: labels 2, 4, 5, then 1+3)",
              sa.layers, sb.layers);
    CHECK_MSG(memcmp(a, b, W * H * 4) == 0, "the filter thread gives the bytes of the serial filters");
    for (int serial = 0; serial < 2; serial++) {
        int calls = 0;
        eo.serial = serial;
        eo.progress.fn = cancel_at_2;
        eo.progress.user = &calls;
        CHECK_STATUS(striped_effects(r, &p, &eo, b, &sb), PNPR_ERR_CANCELLED);
        CHECK_MSG(calls == 2 && sb.layers <= 2, "cancelled at layer 2 (serial %d): %d reports, %zu layers merged", serial,
                  calls, sb.layers);
        eo.progress.fn = NULL;
        pnpr_effect_pipeline bad = p; /* a filter that fails on the filter side: a parameter out of range */
        pnpr_effect_node nodes[2];
        memcpy(nodes, p.nodes, sizeof nodes);
        bad.nodes = nodes;
        nodes[1].chain.effects[0].set = 1;
        nodes[1].chain.effects[0].params[0] = 1e9f;
        CHECK_STATUS(striped_effects(r, &bad, &eo, b, &sb), PNPR_ERR_INVALID_ARGUMENT);
        CHECK_MSG(sb.layers < 4, "a failing filter ends the frame (serial %d): %zu layers", serial, sb.layers);
    }
    eo.serial = 0;
    CHECK_STATUS(striped_effects(r, &p, &eo, b, &sb), PNPR_OK);
    CHECK_MSG(memcmp(a, b, W * H * 4) == 0, "after a cancelled and a failed frame the next is whole");
    pnpr_effect_pipeline_free(&p);
    free(a); free(b);
}

/* Preview layers (scale): the layers at half size, the picture close to the full one (the square
 * where it was within 2 px, few pixels far off); scales outside 1/16..1 are refused. */
static void test_preview_scale(pnpr_renderer *r)
{
    uint8_t *full = malloc(W * H * 4), *half = malloc(W * H * 4);
    pnpr_effect_pipeline p = {0};
    CHECK_STATUS(pnpr_effect_pipeline_parse("toon\n", 5, "x", &p, NULL), PNPR_OK);
    pnpr_cloud c = {0};
    CHECK_STATUS(scene(&c, 1), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    pnpr_effects_options eo;
    memset(&eo, 0, sizeof eo);
    pnpr_effects_stats es;
    CHECK_STATUS(striped_effects(r, &p, &eo, full, &es), PNPR_OK);
    CHECK(es.layer_width == W && es.layer_height == H);
    eo.scale = 0.5f;
    CHECK_STATUS(striped_effects(r, &p, &eo, half, &es), PNPR_OK);
    CHECK_MSG(es.layer_width == W / 2 && es.layer_height == H / 2, "preview layers %dx%d", es.layer_width, es.layer_height);
    box bf = ink_box(full), bh = ink_box(half);
    /* within 4 px: the outline band is 2 layer px wide, 4 px once grown */
    CHECK_MSG(abs(bf.x0 - bh.x0) <= 4 && abs(bf.x1 - bh.x1) <= 4 && abs(bf.y0 - bh.y0) <= 4 && abs(bf.y1 - bh.y1) <= 4,
              "square at (%d..%d, %d..%d) full, (%d..%d, %d..%d) preview", bf.x0, bf.x1, bf.y0, bf.y1, bh.x0, bh.x1, bh.y0,
              bh.y1);
    size_t far = 0;
    for (int i = 0; i < W * H * 4; i++) far += abs((int)full[i] - (int)half[i]) > 64;
    CHECK_MSG(far < (size_t)W * H * 4 / 20, "preview: %zu of %d channel values more than 64 off", far, W * H * 4);
    eo.scale = 1.0f;
    CHECK_STATUS(striped_effects(r, &p, &eo, half, &es), PNPR_OK);
    CHECK_MSG(memcmp(full, half, W * H * 4) == 0, "scale 1 is the full image");
    const float bad[] = {0.01f, -0.5f, 1.5f, NAN, INFINITY};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        eo.scale = bad[k];
        CHECK_STATUS(striped_effects(r, &p, &eo, half, &es), PNPR_ERR_INVALID_ARGUMENT);
    }
    pnpr_effect_pipeline_free(&p);
    pnpr_cloud_free(&c);
    free(full); free(half);
}

int main(void)
{
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_effects: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    if (r) {
        test_layer_then_plain(r);
        test_every_effect_occludes(r);
        test_outlines_need_inpainting(r);
        test_sparse_holes(r);
        test_filter_thread(r);
        test_preview_scale(r);
    }
    pnpr_renderer_destroy(r);
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_effects");
}
