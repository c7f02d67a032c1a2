/* The hierarchy style (Chi & Lee, hierarchy.h) with known answers: a georeferenced sphere's strokes
 * cover its projected disk and stop at its outline, where the silhouette strokes draw ink all
 * around; the hatching map puts more ink on the side turned from the light; a slow zoom changes
 * the pixels between frames at most half as much with the smooth level transition as with plain
 * level switching (popping); a style map mixes it with points; a renderer without a tree, bad
 * options and a bad importance map are refused with a message.
 * Exits 77 (skipped) when this machine has no headless EGL / GL 3.3. */
#include "testutil.h"

#include <pointnpr/hierarchy.h>
#include <pointnpr/render.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 200, H = 200 };
static const double kOffset[3] = {4.0e6, -2.5e6, 310};

static pnpr_status render_at(pnpr_renderer *r, const pnpr_draw_options *o, double dist, uint8_t *px, pnpr_error *err)
{
    pnpr_camera cam = {{kOffset[0], kOffset[1] - dist, kOffset[2]}, {kOffset[0], kOffset[1], kOffset[2]}, {0, 0, 1}, 40, 0, 0};
    pnpr_target t = {0, 0, 0, W, H, 1, 0};
    pnpr_status s = pnpr_renderer_draw(r, &cam, o, &t, NULL, err);
    return s == PNPR_OK ? pnpr_renderer_read_frame(r, px, 0) : s;
}

static pnpr_draw_options options(void)
{
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_HIERARCHY;
    for (int c = 0; c < 4; c++) o.background[c] = 1;
    return o;
}

static double luma(const uint8_t *p) { return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]; }
static int is_paper(const uint8_t *p) { return p[0] > 250 && p[1] > 250 && p[2] > 250; }

/* The projected outline's radius in pixels: tan(asin(1/4)) / tan(20 deg) x H / 2 (eye at 4). */
static double outline_px(void) { return tan(asin(0.25)) / tan(20 * 3.14159265358979 / 180) * H / 2; }

/* The read-back frame is top row first: y grows downwards. */
static const uint8_t *pixel(const uint8_t *px, int x, int y) { return px + 4 * ((size_t)y * W + (size_t)x); }

static void test_sphere(pnpr_renderer *r, pnpr_sphere_tree *t, uint8_t *px)
{
    pnpr_draw_options o = options();
    pnpr_error err = {0};
    CHECK_STATUS(render_at(r, &o, 4, px, &err), PNPR_OK);
    double R = outline_px();
    size_t inside = 0, painted = 0, beyond = 0, beyond_ink = 0, interior = 0, interior_dark = 0;
    int bins[36] = {0};
    double paint = 0; /* the interior's mean luma: silhouettes are darker than 0.6 of it */
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double dx = x + 0.5 - W / 2.0, dy = y + 0.5 - H / 2.0;
            if (dx * dx + dy * dy < 0.25 * R * R) { paint += luma(pixel(px, x, y)); interior++; }
        }
    paint /= interior ? (double)interior : 1.0;
    interior = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double dx = x + 0.5 - W / 2.0, dy = y + 0.5 - H / 2.0, d = sqrt(dx * dx + dy * dy);
            const uint8_t *p = pixel(px, x, y);
            if (d < 0.9 * R) { inside++; painted += !is_paper(p); }
            if (d > 1.1 * R) { beyond++; beyond_ink += !is_paper(p); }
            if (d < 0.6 * R) { interior++; interior_dark += luma(p) < 40; }
            if (d > 0.9 * R && d < 1.06 * R && luma(p) < 0.6 * paint) bins[(int)((atan2(dy, dx) + 3.14159265) / 6.2831854 * 36) % 36]++;
        }
    CHECK_MSG(painted >= inside * 97 / 100, "%zu of %zu pixels inside the outline painted", painted, inside);
    CHECK_MSG(beyond_ink * 100 <= beyond, "%zu of %zu pixels beyond the outline not paper", beyond_ink, beyond);
    CHECK_MSG(interior_dark * 50 <= interior, "%zu of %zu interior pixels as dark as ink", interior_dark, interior);
    int empty = 0;
    for (int b = 0; b < 36; b++) empty += bins[b] == 0;
    CHECK_MSG(empty <= 2, "%d of 36 directions without silhouette ink", empty);
    /* without the silhouette band the outline ring has no ink */
    o.hierarchy.silhouette_deg = -1;
    CHECK_STATUS(render_at(r, &o, 4, px, &err), PNPR_OK);
    size_t ring_dark = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double dx = x + 0.5 - W / 2.0, dy = y + 0.5 - H / 2.0, d = sqrt(dx * dx + dy * dy);
            ring_dark += d > 0.9 * R && d < 1.06 * R && luma(pixel(px, x, y)) < 0.6 * paint;
        }
    CHECK_MSG(ring_dark < 20, "%zu ink pixels on the outline without silhouettes", ring_dark);
    /* hatching: more ink away from the light (upper left) than towards it */
    o = options();
    o.hierarchy.tam = PNPR_TAM_HATCH;
    CHECK_STATUS(render_at(r, &o, 4, px, &err), PNPR_OK);
    double lit = 0, dark = 0;
    size_t nl = 0, nd = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double dx = x + 0.5 - W / 2.0, dy = y + 0.5 - H / 2.0;
            if (dx * dx + dy * dy > 0.64 * R * R) continue;
            if (dx < 0 && dy < 0) { lit += luma(pixel(px, x, y)); nl++; }  /* upper left */
            if (dx > 0 && dy > 0) { dark += luma(pixel(px, x, y)); nd++; } /* lower right */
        }
    CHECK_MSG(nl && nd && lit / nl > dark / nd + 15, "hatching: lit quadrant %.1f, shadow quadrant %.1f", lit / nl, dark / nd);
    (void)t;
}

static pnpr_camera zoom_camera(int f, int frames)
{
    double d = 5.0 * pow(0.7, f / (double)frames);
    pnpr_camera cam = {{kOffset[0], kOffset[1] - d, kOffset[2]}, {kOffset[0], kOffset[1], kOffset[2]}, {0, 0, 1}, 40, 0, 0};
    return cam;
}

/* The mean squared per-pixel change (0..255 units): a transition spread over several frames makes
 * the same total absolute change as a pop in one, but a much smaller squared one (docs/hierarchy.md). */
static double mean_change(const uint8_t *a, const uint8_t *b)
{
    double d = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++)
        if (i % 4 != 3) d += (double)((int)a[i] - (int)b[i]) * ((int)a[i] - (int)b[i]);
    return d / (W * H * 3.0);
}

/* Popping along a slow zoom onto the sphere: at every frame, the mean per-pixel change that the
 * change of stroke selection alone makes: the frame against the same camera drawing the strokes
 * that the previous frame's camera chose (pnpr_hier_params.lod_camera; the motion is the same in
 * both). The strokes take their nodes' colours (of a checker finer than the strokes: a node's
 * mean colour differs from its children's), so a parent replaced by its children shows. */
static double zoom_popping(pnpr_renderer *r, const pnpr_cloud *c, int plain, uint8_t *a, uint8_t *b)
{
    pnpr_draw_options o = options();
    o.hierarchy.no_smooth = plain;
    o.hierarchy.node_colour = 1;
    o.hierarchy.silhouette_deg = -1;
    o.hierarchy.noise_angle = -1;
    o.hierarchy.stroke_px = 24;
    pnpr_error err = {0};
    pnpr_target t = {0, 0, 0, W, H, 1, 0};
    double sum = 0;
    const int frames = 40;
    for (int f = 1; f <= frames; f++) {
        pnpr_camera cam = zoom_camera(f, frames), prev = zoom_camera(f - 1, frames);
        pnpr_camera_matrices pm;
        CHECK_STATUS(pnpr_camera_matrices_from_camera(&prev, c, W, H, &pm, &err), PNPR_OK);
        o.hierarchy.lod_camera = NULL;
        CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, &err), PNPR_OK);
        CHECK_STATUS(pnpr_renderer_read_frame(r, a, 0), PNPR_OK);
        o.hierarchy.lod_camera = &pm;
        CHECK_STATUS(pnpr_renderer_draw(r, &cam, &o, &t, NULL, &err), PNPR_OK);
        CHECK_STATUS(pnpr_renderer_read_frame(r, b, 0), PNPR_OK);
        sum += mean_change(a, b);
    }
    return sum / frames;
}

static void test_popping(pnpr_renderer *r, const pnpr_cloud *c)
{
    uint8_t *a = malloc((size_t)W * H * 4), *b = malloc((size_t)W * H * 4);
    double smooth = zoom_popping(r, c, 0, a, b), plain = zoom_popping(r, c, 1, a, b);
    CHECK_MSG(plain > 0.05 && smooth <= 0.5 * plain, "popping per frame: smooth %.4f, plain %.4f", smooth, plain);
    fprintf(stderr, "zoom: mean per-pixel change per frame from the stroke selection: %.4f smooth, %.4f plain level switching\n",
            smooth, plain);
    free(a); free(b);
}

static void test_refusals(pnpr_renderer *r, pnpr_sphere_tree *t, uint8_t *px)
{
    pnpr_draw_options o = options();
    pnpr_error err = {0};
    pnpr_renderer_set_hierarchy(r, NULL);
    CHECK_STATUS(render_at(r, &o, 4, px, &err), PNPR_ERR_NOT_FOUND);
    CHECK(strstr(err.message, "sphere tree") != NULL);
    pnpr_renderer_set_hierarchy(r, t);
    o.hierarchy.stroke_px = 1000;
    memset(&err, 0, sizeof err);
    CHECK_STATUS(render_at(r, &o, 4, px, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "stroke_px") != NULL);
    o = options();
    o.hierarchy.importance = px;
    CHECK_STATUS(render_at(r, &o, 4, px, &err), PNPR_ERR_INVALID_ARGUMENT);
    /* an importance map of the frame's size: accepted */
    uint8_t *map = malloc(64 * 64);
    memset(map, 255, 64 * 64);
    o.hierarchy.importance = map;
    o.hierarchy.importance_w = o.hierarchy.importance_h = 64;
    CHECK_STATUS(render_at(r, &o, 4, px, &err), PNPR_OK);
    free(map);
}

/* Style map: the upper half (label 0) painted by the hierarchy, the lower half plain points. */
static void test_style_map(pnpr_renderer *r, pnpr_cloud *c, pnpr_sphere_tree *t, uint8_t *px)
{
    CHECK_STATUS(pnpr_cloud_alloc_labels(c), PNPR_OK);
    for (size_t i = 0; i < c->count; i++) c->label[i] = c->xyz[3 * i + 2] < 0;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_set_cloud(r, c, NULL, &err), PNPR_OK);
    pnpr_renderer_set_hierarchy(r, t);
    pnpr_style_map_entry map[2] = {{0, PNPR_STYLE_HIERARCHY}, {1, PNPR_STYLE_POINTS}};
    pnpr_draw_options o = options();
    o.style_map = map;
    o.style_map_count = 2;
    CHECK_STATUS(render_at(r, &o, 4, px, &err), PNPR_OK);
    size_t up = 0, down = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            if (is_paper(pixel(px, x, y))) continue;
            if (y < H / 2 - 10) up++;
            if (y > H / 2 + 10) down++;
        }
    CHECK_MSG(up > 3000 && down > 3000, "style map: %zu pixels drawn above, %zu below", up, down);
}

int main(void)
{
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_hierarchy: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    pnpr_cloud c = {0};
    pnpr_sphere_tree t = {0};
    uint8_t *px = malloc((size_t)W * H * 4);
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    CHECK_STATUS(pnpr_test_sphere(&c, 20000, 1.0, kOffset, 7), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    for (size_t i = 0; i < c.count; i++) { /* a checker of 48 x 24 cells in longitude and latitude */
        const float *p = c.xyz + 3 * i;
        int u = (int)floor((atan2(p[1], p[0]) + 3.14159265) / 6.2831854 * 48), v = (int)floor((p[2] + 1) * 12);
        int odd = (u + v) & 1;
        c.rgb[3 * i] = odd ? 220 : 60;
        c.rgb[3 * i + 1] = odd ? 170 : 90;
        c.rgb[3 * i + 2] = odd ? 60 : 200;
    }
    CHECK_STATUS(pnpr_sphere_tree_build(&c, NULL, &t, NULL, NULL), PNPR_OK);
    if (r) {
        CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
        test_refusals(r, &t, px);
        pnpr_renderer_set_hierarchy(r, &t);
        test_sphere(r, &t, px);
        test_popping(r, &c);
        test_style_map(r, &c, &t, px);
        pnpr_renderer_destroy(r);
    }
    free(px);
    pnpr_sphere_tree_free(&t);
    pnpr_cloud_free(&c);
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_hierarchy");
}
