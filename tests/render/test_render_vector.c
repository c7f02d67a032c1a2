/* Vector drawings (issue 16, docs/export.md "Vector drawings"):
 * 1. Known answer, a back plane of directional points (strokes along x) seen from above, half of
 *    it under an opaque front plane without features: with nothing in front, one path per stroke
 *    the frame drew; with the occluder, no path reaches into the occluded half and the count lies
 *    between the strokes whose centre is visible and those whose half length reaches past the
 *    occluder's edge. Strokes along the occluder's edge keep the side the frame draws (check_band).
 * 2. The SVG rasterised by rsvg-convert against the PNG of the same view and size: at most 2% of
 *    the pixels differ in ink / no ink (ink: grey below 160 on white) for sketchy (with and
 *    without outlines), stipple, lines (profile lines alone and with outlines); cartoon (colour
 *    areas alone and with outlines): at most 2% of the pixels differ by more than 64 in a
 *    channel; on the generated house scene of `bench quality`.
 * 3. The PDF (cairo) opens in pdfinfo with the page size of the drawing (0.75 pt a px).
 * 4. Degenerate and far input: an empty cloud draws no path (one style or a style map); the
 *    occluded planes 5e6 m from the origin give the paths of the planes at the origin within
 *    0.05 px.
 * 5. Merging collinear hatches keeps the ink length; plotter order shortens the pen-up travel and
 *    keeps every path. Unsupported styles fail with a message.
 * Exits 77 (skipped) without headless GL. */
#include "testutil.h"
#include "quality.h"
#include "png_read.h"

#include <pointnpr/drawing.h>
#include <pointnpr/features.h>
#include <pointnpr/lines.h>
#include <pointnpr/options.h>
#include <pointnpr/props.h>
#include <pointnpr/render.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 320, H = 240, GRID = 60 };

/* The back plane z = 0 (GRID x GRID points over [0,1]^2, directional along x, or along y when
 * `along_y`) and, when `occluder`, a front plane at z = 0.3 over x in [0, 0.5] without features
 * (class none). */
static void planes_along(pnpr_cloud *c, int occluder, int along_y)
{
    size_t nb = GRID * GRID, nf = occluder ? (GRID / 2 + 6) * GRID : 0;
    CHECK_STATUS(pnpr_cloud_alloc(c, nb + nf), PNPR_OK);
    /* adding a property may move the others: look them up once all are added */
    CHECK_STATUS(pnpr_cloud_add_property(c, PNPR_PROP_FEATURE_CLASS, PNPR_TYPE_UINT8, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_add_property(c, PNPR_PROP_FEATURE_DIR_X, PNPR_TYPE_FLOAT32, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_add_property(c, PNPR_PROP_FEATURE_DIR_Y, PNPR_TYPE_FLOAT32, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_add_property(c, PNPR_PROP_FEATURE_DIR_Z, PNPR_TYPE_FLOAT32, NULL), PNPR_OK);
    pnpr_property *cls = pnpr_cloud_find_property(c, PNPR_PROP_FEATURE_CLASS);
    pnpr_property *dx = pnpr_cloud_find_property(c, along_y ? PNPR_PROP_FEATURE_DIR_Y : PNPR_PROP_FEATURE_DIR_X);
    if (!cls || !dx) return;
    size_t k = 0;
    for (int j = 0; j < GRID; j++)
        for (int i = 0; i < GRID; i++, k++) {
            c->xyz[3 * k] = (i + 0.5f) / GRID;
            c->xyz[3 * k + 1] = (j + 0.5f) / GRID;
            ((uint8_t *)cls->data)[k] = PNPR_CLASS_DIRECTIONAL;
            ((float *)dx->data)[k] = 1;
        }
    for (int j = 0; j < GRID && occluder; j++) /* the front plane reaches x = 0.5 exactly */
        for (int i = -6; i < GRID / 2; i++, k++) {
            c->xyz[3 * k] = 0.5f - (GRID / 2 - 1 - i + 0.5f) / GRID - 0.5f / GRID;
            c->xyz[3 * k + 1] = (j + 0.5f) / GRID;
            c->xyz[3 * k + 2] = 0.3f;
        }
}

static void planes(pnpr_cloud *c, int occluder) { planes_along(c, occluder, 0); }

/* The planes seen from above (the back plane fills the middle of the frame). */
static const pnpr_camera ABOVE = {{0.5, 0.5, 3}, {0.5, 0.5, 0}, {0, 1, 0}, 40, 0, 0};

/* Sketchy's directional strokes alone, no outlines (stroke width 0: the default). */
static pnpr_draw_options strokes_only(float stroke_width)
{
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_SKETCHY;
    o.sketch_variant = PNPR_SKETCH_DIRECTIONAL;
    o.outline = -1;
    o.stroke_width = stroke_width;
    return o;
}

/* Strokes of the back plane, from above: the known answer of the occluder. */
static void check_occlusion(pnpr_renderer *r)
{
    pnpr_camera cam = ABOVE;
    pnpr_draw_options o = strokes_only(0);
    pnpr_error err = {0};
    pnpr_drawing d = {0};
    for (int occ = 0; occ < 2; occ++) {
        pnpr_cloud c = {0};
        planes(&c, occ);
        CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
        static uint8_t px[W * H * 4];
        pnpr_render_stats st;
        CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, NULL, px, &st, &err), PNPR_OK);
        CHECK_STATUS(pnpr_renderer_drawing(r, &cam, &o, W, H, &d, &err), PNPR_OK);
        /* screen x of world x = 0.5 (the occluder's edge on the back plane): the image centre */
        double edge = 0.5 * W, half_len = 0;
        size_t visible_centre = 0;
        for (size_t i = 0; i < d.count; i++) {
            const float *p = d.xy + 2 * d.offset[i];
            half_len = fmax(half_len, 0.5 * fabs(p[2] - p[0]));
        }
        for (size_t k = 0; k < GRID * GRID; k++) visible_centre += c.xyz[3 * k] > 0.5f;
        if (!occ) {
            printf("no occluder: %zu strokes drawn, %zu paths\n", st.strokes_drawn, d.count);
            CHECK_MSG(d.count == st.strokes_drawn, "%zu paths for %zu strokes", d.count, st.strokes_drawn);
        } else {
            double leftmost = INFINITY;
            for (size_t i = 0; i < d.count; i++)
                for (size_t v = d.offset[i]; v < d.offset[i + 1]; v++) leftmost = fmin(leftmost, d.xy[2 * v]);
            /* strokes whose half length (in world units: px / px-per-unit at depth 3) reaches over the edge */
            double ppu = 0.5 * H / tan(20 * 3.14159265358979 / 180) / 3, reach = half_len / ppu;
            size_t upper = 0;
            for (size_t k = 0; k < GRID * GRID; k++) upper += c.xyz[3 * k] > 0.5 - reach;
            printf("occluder: %zu paths, strokes with a visible centre %zu, reaching past the edge %zu; "
                   "leftmost ink x %.2f, edge %.2f\n", d.count, visible_centre, upper, leftmost, edge);
            CHECK_MSG(leftmost >= edge - 1.0, "ink at x %.2f behind the occluder (edge %.2f)", leftmost, edge);
            CHECK(d.count >= visible_centre && d.count <= upper);
        }
        pnpr_drawing_free(&d);
        pnpr_cloud_free(&c);
    }
}

/* Strokes along the occluder's edge, 6 px wide: the raster tests each of their pixels, so a stroke
 * whose centre line is hidden but whose side is not shows that side. The drawing keeps it as a
 * narrower path on the visible side: no vector ink left of the frame's leftmost ink (half a pixel
 * of slack), paths narrower than the stroke, and the leftmost ink of both within a pixel. (Tested
 * along the centre line only, a stroke was kept whole or dropped: its ink reached 3 px into the
 * hidden side, or the side the frame draws was missing.) */
static void check_band(pnpr_renderer *r)
{
    pnpr_camera cam = ABOVE;
    pnpr_draw_options o = strokes_only(6);
    pnpr_error err = {0};
    pnpr_drawing d = {0};
    pnpr_cloud c = {0};
    planes_along(&c, 1, 1);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
    static uint8_t px[W * H * 4];
    CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, NULL, px, NULL, &err), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_drawing(r, &cam, &o, W, H, &d, &err), PNPR_OK);
    int raster_left = W;
    for (int y = H / 4; y < 3 * H / 4; y++)
        for (int x = 0; x < W; x++)
            if (px[4 * ((size_t)y * W + x) + 3] > 25 && x < raster_left) raster_left = x;
    double full = 0, vector_left = INFINITY;
    for (size_t i = 0; i < d.count; i++) full = fmax(full, d.stroke_width[i]);
    size_t partial = 0;
    for (size_t i = 0; i < d.count; i++) {
        partial += d.stroke_width[i] < 0.9 * full;
        for (size_t v = d.offset[i]; v < d.offset[i + 1]; v++) {
            double y = d.xy[2 * v + 1];
            if (y >= H / 4 && y < 3 * H / 4) vector_left = fmin(vector_left, d.xy[2 * v] - 0.5 * d.stroke_width[i]);
        }
    }
    printf("strokes along the occluder's edge: %zu paths, %zu narrower than the stroke (%.2f px); leftmost ink: "
           "frame x %d, drawing x %.2f\n", d.count, partial, full, raster_left, vector_left);
    CHECK(d.count > 0 && partial >= GRID);
    CHECK_MSG(vector_left >= raster_left - 0.5 && vector_left <= raster_left + 1.0,
              "the drawing's ink starts at x %.2f, the frame's at %d", vector_left, raster_left);
    pnpr_drawing_free(&d);
    pnpr_cloud_free(&c);
}

/* Degenerate and far input: an empty cloud draws nothing (and no error); the occluded planes at a
 * georeferenced origin (5e6 m away) give the same paths as at the origin, within 0.05 px. */
static void check_degenerate(pnpr_renderer *r)
{
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.sketch_variant = PNPR_SKETCH_DIRECTIONAL;
    o.outline = -1;
    pnpr_error err = {0};
    pnpr_drawing d[2] = {{0}, {0}};
    pnpr_cloud empty = {0};
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &empty, NULL, &err), PNPR_OK);
    const pnpr_style styles[2] = {PNPR_STYLE_SKETCHY, PNPR_STYLE_CARTOON};
    for (int s = 0; s < 2; s++) {
        o.style = styles[s];
        CHECK_STATUS(pnpr_renderer_drawing(r, NULL, &o, W, H, &d[0], &err), PNPR_OK);
        CHECK_MSG(d[0].count == 0, "%zu paths of an empty cloud", d[0].count);
        pnpr_drawing_free(&d[0]);
    }
    /* and under a style map of every vector style: no path either */
    const pnpr_style_map_entry map[3] = {{0, PNPR_STYLE_STIPPLE}, {1, PNPR_STYLE_LINES}, {2, PNPR_STYLE_CARTOON}};
    o.style_map = map;
    o.style_map_count = 3;
    CHECK_STATUS(pnpr_renderer_drawing(r, NULL, &o, W, H, &d[0], &err), PNPR_OK);
    CHECK_MSG(d[0].count == 0, "%zu paths of an empty cloud under a style map", d[0].count);
    pnpr_drawing_free(&d[0]);
    o.style_map = NULL;
    o.style_map_count = 0;
    o.style = PNPR_STYLE_SKETCHY;
    const double far[3] = {5123456.789, 4012345.678, 250.125};
    for (int k = 0; k < 2; k++) {
        pnpr_cloud c = {0};
        planes(&c, 1);
        pnpr_camera cam = ABOVE;
        for (int a = 0; a < 3 && k; a++) {
            c.origin[a] = far[a];
            cam.eye[a] += far[a];
            cam.target[a] += far[a];
        }
        CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
        CHECK_STATUS(pnpr_renderer_drawing(r, &cam, &o, W, H, &d[k], &err), PNPR_OK);
        pnpr_cloud_free(&c);
    }
    double worst = 0;
    int same = d[0].count == d[1].count && d[0].count > 0;
    for (size_t v = 0; same && v < 2 * d[0].offset[d[0].count]; v++) worst = fmax(worst, fabs(d[0].xy[v] - d[1].xy[v]));
    printf("georeferenced origin: %zu and %zu paths, vertices at most %.4f px apart\n", d[0].count, d[1].count, worst);
    CHECK(same && worst <= 0.05);
    pnpr_drawing_free(&d[0]);
    pnpr_drawing_free(&d[1]);
}

static double luma(const uint8_t *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

/* The fraction of pixels where the PNG and the rasterised SVG disagree on ink (grey below 160). */
static double ink_difference(const uint8_t *rgba, const uint8_t *grey)
{
    size_t diff = 0, ink = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        int a = luma(rgba + 4 * i) < 160, b = grey[i] < 160;
        diff += a != b;
        ink += a;
    }
    printf(" (ink %.2f%% of the pixels)", 100.0 * ink / ((double)W * H));
    return (double)diff / ((double)W * H);
}

/* Cartoon (colour areas and outlines): the fraction of pixels whose colour differs by more than a
 * quarter of the range in a channel. */
static double colour_difference(const uint8_t *rgba, const uint8_t *rgb)
{
    size_t diff = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        int d = 0;
        for (int k = 0; k < 3; k++) {
            int e = abs((int)rgba[4 * i + k] - (int)rgb[3 * i + k]);
            d = e > d ? e : d;
        }
        diff += d > 64;
    }
    return (double)diff / ((double)W * H);
}

/* The page size pdfinfo reads, in pt; 0 on failure. */
static int pdf_page(const char *pdf, double *w, double *h)
{
    char cmd[700];
    snprintf(cmd, sizeof cmd, "pdfinfo '%s' 2>/dev/null", pdf);
    FILE *p = popen(cmd, "r");
    if (!p) return 0;
    char line[256];
    int ok = 0;
    while (fgets(line, sizeof line, p))
        if (sscanf(line, "Page size: %lf x %lf pts", w, h) == 2) ok = 1;
    return pclose(p) == 0 && ok;
}

/* The drawing as SVG (SCRATCH/vector-NAME.svg), rasterised by rsvg-convert
 * (SCRATCH/vector-NAME-svg.png) and read back into out (W x H, PNG_FORMAT_GRAY or _RGB). */
static int rasterise(const pnpr_drawing *d, const char *name, int format, uint8_t *out)
{
    char svg[512], png[512], cmd[1100];
    pnpr_error err = {0};
    snprintf(svg, sizeof svg, "%s/vector-%s.svg", PNPR_TEST_SCRATCH, name);
    snprintf(png, sizeof png, "%s/vector-%s-svg.png", PNPR_TEST_SCRATCH, name);
    CHECK_STATUS(pnpr_drawing_write_svg(d, svg, &err), PNPR_OK);
    snprintf(cmd, sizeof cmd, "rsvg-convert '%s' -o '%s'", svg, png);
    return system(cmd) == 0 && pnpr_test_read_png(png, W, H, format, out);
}

/* A close-up (the back plane from 0.3 instead of 3: its strokes would be 6 disk radii = 110 px
 * long): every stroke is at most stroke_max (default 48 px) long, in the drawing (its paths
 * 48/110 of the uncapped ones: measured 37.5 and 85.9 px, the texture's ink spanning 0.78 of a
 * stroke), and the frame draws the same (its ink within 2% of the rasterised drawing's: 0.74%;
 * 10.2% of the pixels inked against 13.3% uncapped). */
static void check_close_up(pnpr_renderer *r)
{
    pnpr_camera cam = {{0.5, 0.5, 0.3}, {0.5, 0.5, 0}, {0, 1, 0}, 40, 0, 0};
    pnpr_cloud c = {0};
    planes(&c, 0);
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
    static uint8_t px[W * H * 4], grey[W * H];
    double longest[2] = {0, 0};
    for (int capped = 1; capped >= 0; capped--) {
        pnpr_draw_options o = strokes_only(0);
        for (int k = 0; k < 4; k++) o.background[k] = 1;
        o.stroke_max = capped ? 0 : -1;
        pnpr_drawing d = {0};
        CHECK_STATUS(pnpr_renderer_drawing(r, &cam, &o, W, H, &d, &err), PNPR_OK);
        for (size_t i = 0; i < d.count; i++) {
            const float *p = d.xy + 2 * d.offset[i], *q = d.xy + 2 * (d.offset[i + 1] - 1);
            longest[capped] = fmax(longest[capped], hypot(q[0] - p[0], q[1] - p[1]));
        }
        CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, NULL, px, NULL, &err), PNPR_OK);
        CHECK(rasterise(&d, "closeup", PNG_FORMAT_GRAY, grey));
        printf("close-up, stroke_max %s: %zu paths, the longest %.1f px", capped ? "default" : "off", d.count, longest[capped]);
        double diff = ink_difference(px, grey);
        printf(", ink differs at %.2f%%\n", 100 * diff);
        CHECK_MSG(diff <= 0.02, "close-up: the frame and the drawing differ at %.2f%%", 100 * diff);
        pnpr_drawing_free(&d);
    }
    /* a path spans the stroke texture's ink, the same share of any stroke's length: the capped and
     * uncapped paths are in the ratio of stroke_max to 6 disk radii (spacing 1/GRID) at depth 0.3 */
    double ppu = 0.5 * H / tan(20 * 3.14159265358979 / 180) / 0.3, full = 6.0 / GRID * ppu;
    double cap = pnpr_draw_defaults().stroke_max, want = full / cap;
    printf("close-up: strokes of %.1f px capped at %g: paths %.1f / %.1f px = %.3f (expected %.3f)\n", full, cap,
           longest[0], longest[1], longest[0] / longest[1], want);
    CHECK_MSG(longest[1] <= cap && longest[1] > 0 && fabs(longest[0] / longest[1] - want) < 0.05 * want,
              "close-up: paths %.1f px capped, %.1f px not (ratio %.3f, expected %.3f)", longest[1], longest[0],
              longest[0] / longest[1], want);
    pnpr_cloud_free(&c);
}

/* bound: the largest share of pixels allowed to differ in ink (outline -1: the marks alone). */
static void check_style(pnpr_renderer *r, const pnpr_camera *cam, pnpr_style style, int outline, double bound)
{
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = style;
    o.outline = outline;
    for (int k = 0; k < 4; k++) o.background[k] = 1;
    pnpr_error err = {0};
    static uint8_t px[W * H * 4], grey[W * H], rgb[W * H * 3];
    int areas = style == PNPR_STYLE_CARTOON;
    CHECK_STATUS(pnpr_renderer_snapshot(r, cam, &o, W, H, NULL, px, NULL, &err), PNPR_OK);
    pnpr_drawing d = {0};
    CHECK_STATUS(pnpr_renderer_drawing(r, cam, &o, W, H, &d, &err), PNPR_OK);
    char pdf[512], raster[512];
    snprintf(raster, sizeof raster, "%s/vector-%s.png", PNPR_TEST_SCRATCH, pnpr_style_name(style));
    CHECK_STATUS(pnpr_write_png(raster, px, W, H, 0, &err), PNPR_OK);
    snprintf(pdf, sizeof pdf, "%s/vector-%s.pdf", PNPR_TEST_SCRATCH, pnpr_style_name(style));
    CHECK(rasterise(&d, pnpr_style_name(style), areas ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY, areas ? rgb : grey));
    printf("%-8s outlines %-7s %6zu paths", pnpr_style_name(style), outline < 0 ? "off" : outline > 0 ? "on" : "default", d.count);
    double diff = areas ? colour_difference(px, rgb) : ink_difference(px, grey);
    printf(", %s differs at %.2f%% of the pixels\n", areas ? "colour" : "ink", 100 * diff);
    CHECK_MSG(diff <= bound, "%s: the SVG differs from the PNG at %.2f%% of the pixels", pnpr_style_name(style), 100 * diff);
    CHECK(d.count > 0);
    CHECK_STATUS(pnpr_drawing_write_pdf(&d, pdf, &err), PNPR_OK);
    double pw = 0, ph = 0;
    CHECK_MSG(pdf_page(pdf, &pw, &ph), "pdfinfo cannot read %s", pdf);
    CHECK(fabs(pw - 0.75 * W) < 0.01 && fabs(ph - 0.75 * H) < 0.01);
    pnpr_drawing_free(&d);
}

/* The paths of layer L whose middle (the mean of their ends) lies at x in [x0, x1) (px). */
static size_t layer_paths(const pnpr_drawing *d, pnpr_drawing_layer L, double x0, double x1)
{
    size_t n = 0;
    for (size_t i = 0; i < d->count; i++) {
        double x = 0.5 * (d->xy[2 * d->offset[i]] + d->xy[2 * (d->offset[i + 1] - 1)]);
        n += d->layer[i] == L && x >= x0 && x < x1;
    }
    return n;
}

/* The x range of layer L's vertices; 0 when it has none. */
static int layer_x_range(const pnpr_drawing *d, pnpr_drawing_layer L, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t i = 0; i < d->count; i++)
        for (size_t v = d->offset[i]; v < d->offset[i + 1] && d->layer[i] == L; v++) {
            *lo = fmin(*lo, d->xy[2 * v]);
            *hi = fmax(*hi, d->xy[2 * v]);
        }
    return *lo <= *hi;
}

/* A style map in a vector drawing: the back plane in four strips along x (labels 0..3: stipple,
 * sketchy, lines, cartoon) under a profile line across all of them, seen from above. Known
 * answers: the map's dots are the dots of a stipple drawing of the whole plane whose centres lie
 * in strip 0, and its strokes those of a sketchy drawing in strip 1 (the same vertices, visibility
 * and thinning); the line shows over strip 2 only (the lines pass's stencil) and the colour areas
 * over strip 3 only (the mask disks and caps reach a few px further); the SVG and the PNG agree within
 * the 2%. A map with a style that fills areas is refused before drawing. */
static void check_map(pnpr_renderer *r)
{
    pnpr_camera cam = ABOVE;
    pnpr_cloud c = {0};
    planes(&c, 0);
    CHECK_STATUS(pnpr_cloud_alloc_labels(&c), PNPR_OK);
    for (size_t k = 0; k < c.count && c.label; k++) c.label[k] = (uint32_t)(c.xyz[3 * k] * 4);
    float xyz[3 * 50];
    for (int i = 0; i < 50; i++) {
        xyz[3 * i] = 0.02f + 0.96f * i / 49;
        xyz[3 * i + 1] = 0.5f;
        xyz[3 * i + 2] = 0.01f;
    }
    size_t offset[2] = {0, 50};
    uint8_t closed = 0;
    pnpr_polylines lines = {1, offset, xyz, &closed, {0, 0, 0}};
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_lines(r, &lines, &err), PNPR_OK);
    const pnpr_style_map_entry map[4] = {{0, PNPR_STYLE_STIPPLE}, {1, PNPR_STYLE_SKETCHY}, {2, PNPR_STYLE_LINES},
                                         {3, PNPR_STYLE_CARTOON}};
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_SKETCHY;
    for (int k = 0; k < 4; k++) o.background[k] = 1;
    pnpr_drawing d = {0}, one = {0};
    static uint8_t px[W * H * 4], rgb[W * H * 3];
    /* screen x of the strips' edges (world x = i / 4) */
    double ppu = 0.5 * H / tan(20 * 3.14159265358979 / 180) / 3, e[5];
    for (int i = 0; i < 5; i++) e[i] = 0.5 * W + (i / 4.0 - 0.5) * ppu;
    for (int s = 0; s < 2; s++) { /* the single styles first: stipple, sketchy */
        o.style = s ? PNPR_STYLE_SKETCHY : PNPR_STYLE_STIPPLE;
        CHECK_STATUS(pnpr_renderer_drawing(r, &cam, &o, W, H, &one, &err), PNPR_OK);
        pnpr_drawing_layer L = s ? PNPR_LAYER_STROKES : PNPR_LAYER_DOTS;
        size_t want = layer_paths(&one, L, e[s], e[s + 1]);
        pnpr_drawing_free(&one);
        o.style = PNPR_STYLE_SKETCHY;
        o.style_map = map;
        o.style_map_count = 4;
        CHECK_STATUS(pnpr_renderer_drawing(r, &cam, &o, W, H, &d, &err), PNPR_OK);
        size_t got = layer_paths(&d, L, -1, W + 1), in_strip = layer_paths(&d, L, e[s], e[s + 1]);
        printf("style map: %s %zu paths, %zu of them in strip %d; the single style's there %zu\n",
               s ? "strokes" : "dots", got, in_strip, s, want);
        CHECK_MSG(got > 0 && got == in_strip && got == want, "%s: %zu paths, %zu in the strip, %zu in the single style's",
                  s ? "strokes" : "dots", got, in_strip, want);
        o.style_map = NULL;
        o.style_map_count = 0;
        if (s == 0) pnpr_drawing_free(&d);
    }
    double lo, hi;
    CHECK(layer_x_range(&d, PNPR_LAYER_LINES, &lo, &hi));
    printf("style map: line ink x %.1f .. %.1f (strip 2: %.1f .. %.1f)\n", lo, hi, e[2], e[3]);
    /* the stencil of the strip's points reaches past its edges by their mask disks (~2 px), the
     * line's square caps by half its width */
    CHECK(lo >= e[2] - 4 && lo <= e[2] + 2 && hi <= e[3] + 4 && hi >= e[3] - 2);
    CHECK(layer_x_range(&d, PNPR_LAYER_FILLS, &lo, &hi));
    printf("style map: colour areas x %.1f .. %.1f (strip 3: %.1f .. %.1f)\n", lo, hi, e[3], e[4]);
    CHECK(lo >= e[3] - 6 && lo <= e[3] + 2 && hi >= e[4] - 2);
    /* the drawing against the frame */
    o.style_map = map;
    o.style_map_count = 4;
    CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, NULL, px, NULL, &err), PNPR_OK);
    CHECK(rasterise(&d, "map", PNG_FORMAT_RGB, rgb));
    double diff = colour_difference(px, rgb);
    printf("style map: %zu paths, colour differs at %.2f%% of the pixels\n", d.count, 100 * diff);
    CHECK(diff <= 0.02);
    pnpr_drawing_free(&d);
    /* a style that fills areas, in the map or as its default where a label is not listed */
    const pnpr_style_map_entry fill[2] = {{0, PNPR_STYLE_STIPPLE}, {1, PNPR_STYLE_PAINTERLY}};
    o.style_map = fill;
    o.style_map_count = 2;
    CHECK_STATUS(pnpr_renderer_drawing(r, &cam, &o, W, H, &d, &err), PNPR_ERR_UNSUPPORTED);
    CHECK(strstr(err.message, "entry 2 (label 1)") && strstr(err.message, "painterly"));
    o.style_map_count = 1;
    o.style = PNPR_STYLE_POINTS;
    CHECK_STATUS(pnpr_renderer_drawing(r, &cam, &o, W, H, &d, &err), PNPR_ERR_UNSUPPORTED);
    CHECK(strstr(err.message, "default") && strstr(err.message, "points"));
    pnpr_cloud_free(&c);
}

/* Merging keeps the ink; plotter order keeps the paths and shortens the travel. */
static void check_plot(pnpr_renderer *r, const pnpr_camera *cam)
{
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = PNPR_STYLE_SKETCHY;
    pnpr_error err = {0};
    pnpr_drawing d = {0};
    CHECK_STATUS(pnpr_renderer_drawing(r, cam, &o, W, H, &d, &err), PNPR_OK);
    size_t n = d.count, merged = 9;
    double ink = pnpr_drawing_ink_length(&d, PNPR_LAYER_COUNT_), travel = pnpr_drawing_travel(&d);
    CHECK_STATUS(pnpr_drawing_order_for_plotter(&d), PNPR_OK);
    double after = pnpr_drawing_travel(&d);
    printf("plotter order: %zu paths, pen-up travel %.0f -> %.0f px\n", d.count, travel, after);
    CHECK(d.count == n && fabs(pnpr_drawing_ink_length(&d, PNPR_LAYER_COUNT_) - ink) < 1e-3 * ink && after < 0.5 * travel);
    CHECK_STATUS(pnpr_drawing_merge_collinear(&d, PNPR_LAYER_HATCHES, 1, 0.5f, 1, &merged), PNPR_OK);
    printf("merged %zu hatches\n", merged);
    CHECK(d.count == n - merged);
    /* merging never adds ink, and loses at most the overlaps */
    CHECK(pnpr_drawing_ink_length(&d, PNPR_LAYER_COUNT_) <= ink * (1 + 1e-6));
    pnpr_drawing_free(&d);
    o.style = PNPR_STYLE_POINTS;
    CHECK_STATUS(pnpr_renderer_drawing(r, cam, &o, W, H, &d, &err), PNPR_ERR_UNSUPPORTED);
    CHECK(strstr(err.message, "points") != NULL);
    o.style = PNPR_STYLE_SKETCHY;
    CHECK_STATUS(pnpr_renderer_drawing(r, cam, &o, 0, H, &d, &err), PNPR_ERR_INVALID_ARGUMENT);
}

/* The upload's tone_radius sets the tone hatches' length (a sample of a larger cloud gives the
 * whole cloud's mean spacing, docs/tiles.md): twice the radius, hatches twice as long on the
 * drawing's tone layer, fewer kept, about the same ink. */
static void check_tone_radius(pnpr_renderer *r, const pnpr_cloud *c, const pnpr_camera *cam)
{
    const pnpr_property *sp = pnpr_cloud_find_property(c, PNPR_PROP_POINT_SPACING);
    CHECK(sp != NULL);
    if (!sp) return;
    double mean = 0;
    for (size_t i = 0; i < c->count; i++) mean += ((const float *)sp->data)[i];
    mean /= (double)c->count;
    double count[2], ink[2];
    for (int k = 0; k < 2; k++) {
        pnpr_upload_options uo = pnpr_upload_defaults();
        uo.tone_radius = (float)(mean * (k + 1));
        pnpr_error err = {0};
        CHECK_STATUS(pnpr_renderer_set_cloud(r, c, &uo, &err), PNPR_OK);
        pnpr_draw_options o;
        memset(&o, 0, sizeof o);
        o.style = PNPR_STYLE_SKETCHY;
        pnpr_drawing d = {0};
        CHECK_STATUS(pnpr_renderer_drawing(r, cam, &o, W, H, &d, &err), PNPR_OK);
        count[k] = 0;
        for (size_t i = 0; i < d.count; i++) count[k] += d.layer[i] == PNPR_LAYER_TONE;
        ink[k] = pnpr_drawing_ink_length(&d, PNPR_LAYER_TONE);
        pnpr_drawing_free(&d);
    }
    double len_ratio = count[0] > 0 && count[1] > 0 ? (ink[1] / count[1]) / (ink[0] / count[0]) : 0;
    printf("tone radius x2: %.0f -> %.0f tone hatches, mean length x%.2f, ink x%.2f\n", count[0], count[1], len_ratio,
           ink[0] > 0 ? ink[1] / ink[0] : 0);
    /* below 2: a hatch is 3 px long at least, and which ones are kept is a hash of the vertex's
     * place (the cells' order sets it: x1.73 with cells of 1/32 the longest side, x1.64 with the
     * finer grid, the same cloud drawn whole) */
    CHECK_MSG(count[0] > 100 && len_ratio > 1.5 && len_ratio < 2.3, "tone hatches %.0f, length x%.2f", count[0], len_ratio);
    /* fewer kept (a hatch whose point's sample area exceeds its quad is kept whatever its length,
     * so not half), the ink within a third (683 -> 460 hatches, ink x1.19 when written) */
    CHECK_MSG(count[1] > 0.4 * count[0] && count[1] < 0.8 * count[0] && ink[1] > 0.75 * ink[0] && ink[1] < 1.33 * ink[0],
              "tone hatches %.0f -> %.0f, ink %.0f -> %.0f px", count[0], count[1], ink[0], ink[1]);
}

int main(void)
{
    if (system("rsvg-convert --version > /dev/null 2>&1") != 0 || system("pdfinfo -v > /dev/null 2>&1") != 0) {
        fprintf(stderr, "test_render_vector: rsvg-convert or pdfinfo is missing (packaging/deps/vector.txt installs them)\n");
        return 1;
    }
    pnpr_error err = {0};
    pnpr_gl_context *ctx = NULL;
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_vector: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    if (r) check_occlusion(r);
    if (r) check_band(r);
    if (r) check_close_up(r);
    if (r) check_map(r);
    if (r) check_degenerate(r);
    pnpr_quality_scene scene;
    pnpr_quality_scene_init(&scene, PNPR_QUALITY_PRESET_SPARSE);
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_quality_scan(&scene, 0, &c, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    pnpr_polylines lines = {0};
    CHECK_STATUS(pnpr_profile_lines(&c, NULL, &lines, NULL), PNPR_OK);
    if (r && pnpr_test_failures == 0) {
        CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, &err), PNPR_OK);
        CHECK_STATUS(pnpr_renderer_set_lines(r, &lines, &err), PNPR_OK);
        pnpr_camera cam;
        CHECK_STATUS(pnpr_camera_fit(&c, NULL, 45, (float)W / H, &cam), PNPR_OK);
        /* every style at most 2% (the bound), as drawn by default and with outlines */
        check_style(r, &cam, PNPR_STYLE_SKETCHY, 0, 0.02);
        check_style(r, &cam, PNPR_STYLE_SKETCHY, 1, 0.02);
        check_style(r, &cam, PNPR_STYLE_STIPPLE, 0, 0.02);
        check_style(r, &cam, PNPR_STYLE_LINES, -1, 0.02);
        check_style(r, &cam, PNPR_STYLE_LINES, 0, 0.02);
        /* cartoon by colour: the areas alone, and with the outlines */
        check_style(r, &cam, PNPR_STYLE_CARTOON, -1, 0.02);
        check_style(r, &cam, PNPR_STYLE_CARTOON, 0, 0.02);
        check_plot(r, &cam);
        check_tone_radius(r, &c, &cam);
    }
    pnpr_lines_free(&lines);
    pnpr_cloud_free(&c);
    pnpr_renderer_destroy(r);
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_vector");
}
