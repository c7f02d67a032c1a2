/* Vector drawings without GL (include/pointnpr/drawing.h): the container, centre lines of ink
 * masks with known answers (a ring, a bar, a cross, a speck), collinear merging, plotter order,
 * the SVG writer's layers, and hostile arguments. */
#include "testutil.h"

#include <pointnpr/drawing.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { S = 128 };
static const uint8_t INK[4] = {20, 20, 25, 255};

/* A ring of radius 40 and width 2.5 px around the centre; one closed centre line on it. */
static void check_ring(void)
{
    static uint8_t a[S * S];
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            double r = hypot(x + 0.5 - 64, y + 0.5 - 64);
            a[y * S + x] = fabs(r - 40) <= 1.25 ? 255 : 0;
        }
    pnpr_drawing d = {0};
    CHECK_STATUS(pnpr_drawing_trace_ink(&d, a, S, S, 0, 128, 2, INK, PNPR_LAYER_OUTLINES), PNPR_OK);
    double worst = 0;
    for (size_t v = 0; v < (d.count ? d.offset[d.count] : 0); v++)
        worst = fmax(worst, fabs(hypot(d.xy[2 * v] - 64, d.xy[2 * v + 1] - 64) - 40));
    double len = pnpr_drawing_ink_length(&d, PNPR_LAYER_OUTLINES);
    printf("ring: %zu paths, length %.1f (circle %.1f), vertices at most %.2f px off the circle\n", d.count, len,
           2 * 3.14159265 * 40, worst);
    CHECK(d.count == 1 && (d.flags[0] & PNPR_PATH_CLOSED));
    CHECK(worst <= 0.8 && fabs(len - 2 * 3.14159265 * 40) < 0.03 * 2 * 3.14159265 * 40);
    pnpr_drawing_free(&d);
}

/* A horizontal bar 3 px thick from x = 20 to 100 (rows bottom-up): one open path along y = 64.5,
 * about 80 px long and 3 px wide; a cross of two 88 px bars: 2 to 4 paths (crossing strokes or arms from a
 * junction) of their length; a 2 x 1 speck: one path over its 2 px; a single pixel: a dot on it. */
static void check_bar_cross_speck(void)
{
    static uint8_t a[S * S];
    memset(a, 0, sizeof a);
    for (int y = 63; y <= 65; y++)
        for (int x = 20; x < 100; x++) a[(S - 1 - y) * S + x] = 200;
    pnpr_drawing d = {0};
    CHECK_STATUS(pnpr_drawing_trace_ink(&d, a, S, S, 1, 128, 2, INK, PNPR_LAYER_LINES), PNPR_OK);
    double len = pnpr_drawing_ink_length(&d, PNPR_LAYER_LINES);
    printf("bar: %zu paths, length %.1f, width %.1f\n", d.count, len, d.count ? d.stroke_width[0] : 0);
    CHECK(d.count == 1 && !(d.flags[0] & PNPR_PATH_CLOSED) && len > 74 && len <= 80);
    CHECK(d.count == 1 && fabs(d.stroke_width[0] - 3) < 0.2); /* as wide as the 3 px bar */
    for (size_t v = 0; d.count && v < d.offset[1]; v++) CHECK(fabs(d.xy[2 * v + 1] - 64.5) < 0.6);
    pnpr_drawing_free(&d);
    memset(a, 0, sizeof a);
    for (int k = 20; k < 108; k++)
        for (int t = -1; t <= 1; t++) { a[(64 + t) * S + k] = 255; a[k * S + 64 + t] = 255; }
    CHECK_STATUS(pnpr_drawing_trace_ink(&d, a, S, S, 0, 128, 2, INK, PNPR_LAYER_LINES), PNPR_OK);
    len = pnpr_drawing_ink_length(&d, PNPR_LAYER_LINES);
    printf("cross: %zu paths, length %.1f\n", d.count, len);
    CHECK(d.count >= 2 && d.count <= 4 && len > 160 && len <= 176); /* two crossing strokes, or four arms */
    pnpr_drawing_free(&d);
    memset(a, 0, sizeof a);
    a[10 * S + 10] = a[10 * S + 11] = 255;
    CHECK_STATUS(pnpr_drawing_trace_ink(&d, a, S, S, 0, 128, 1, INK, PNPR_LAYER_LINES), PNPR_OK);
    len = pnpr_drawing_ink_length(&d, PNPR_LAYER_LINES);
    printf("speck: %zu paths, length %.2f, width %.2f\n", d.count, len, d.count ? d.stroke_width[0] : 0);
    CHECK(d.count == 1 && fabs(len - 2) < 0.01 && fabs(d.stroke_width[0] - 1) < 0.01); /* the 2 x 1 px it inks */
    pnpr_drawing_free(&d);
    a[10 * S + 11] = 0;
    CHECK_STATUS(pnpr_drawing_trace_ink(&d, a, S, S, 0, 128, 1, INK, PNPR_LAYER_LINES), PNPR_OK);
    CHECK(d.count == 1 && (d.flags[0] & PNPR_PATH_DOT) && fabs(d.xy[0] - 10.5) < 0.01 && fabs(d.xy[1] - 10.5) < 0.01);
    pnpr_drawing_free(&d);
    a[10 * S + 10] = 0;
    memset(a, 0, sizeof a);
    CHECK_STATUS(pnpr_drawing_trace_ink(&d, a, S, S, 0, 128, 2, INK, PNPR_LAYER_LINES), PNPR_OK);
    CHECK(d.count == 0);
    CHECK_STATUS(pnpr_drawing_trace_ink(&d, a, 0, S, 0, 128, 2, INK, PNPR_LAYER_LINES), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_drawing_trace_ink(&d, a, S, S, 0, 128, NAN, INK, PNPR_LAYER_LINES), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_drawing_free(&d);
}

/* Hatches on one line merge into one path spanning them; paths on other lines, in other colours
 * or of other widths stay; the ink never grows. */
static void check_merge(void)
{
    pnpr_drawing d = {0};
    const float h[][4] = {{0, 0, 10, 10}, {9, 9, 20, 20}, {21, 21, 30, 30}, {40, 40, 50, 50}, /* 3 merge; the 4th: gap 14 px */
                          {0, 5, 10, 15}};                                                  /* another line */
    for (int i = 0; i < 5; i++) CHECK_STATUS(pnpr_drawing_add(&d, h[i], 2, 1, INK, PNPR_LAYER_HATCHES, 0), PNPR_OK);
    const uint8_t red[4] = {255, 0, 0, 255};
    const float other[4] = {30.5f, 30.5f, 35, 35};
    CHECK_STATUS(pnpr_drawing_add(&d, other, 2, 1, red, PNPR_LAYER_HATCHES, 0), PNPR_OK); /* other colour */
    double ink = pnpr_drawing_ink_length(&d, PNPR_LAYER_HATCHES);
    size_t merged = 0;
    CHECK_STATUS(pnpr_drawing_merge_collinear(&d, PNPR_LAYER_HATCHES, 1, 0.5f, 1.5f, &merged), PNPR_OK);
    printf("merge: %zu merged, %zu paths left\n", merged, d.count);
    CHECK(merged == 2 && d.count == 4);
    CHECK(fabs(d.xy[0]) < 1e-4 && fabs(d.xy[2] - 30) < 1e-4 && fabs(d.xy[3] - 30) < 1e-4);
    CHECK(pnpr_drawing_ink_length(&d, PNPR_LAYER_HATCHES) <= ink);
    CHECK_STATUS(pnpr_drawing_merge_collinear(&d, PNPR_LAYER_HATCHES, NAN, 0.5f, 1, NULL), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_drawing_free(&d);
}

/* A grid of short strokes in a scrambled order: the plotter order keeps every path and its
 * ink, keeps layers in order, and travels far less. */
static void check_order(void)
{
    pnpr_drawing d = {0};
    uint32_t s = 12345;
    for (int i = 0; i < 400; i++) {
        s = s * 1664525u + 1013904223u;
        int k = (int)(s >> 8) % 400;
        float x = (float)(k % 20) * 10, y = (float)(k / 20) * 10;
        float xy[4] = {x, y, x + 5, y};
        CHECK_STATUS(pnpr_drawing_add(&d, xy, 2, 1, INK, i % 7 == 0 ? PNPR_LAYER_OUTLINES : PNPR_LAYER_STROKES, 0), PNPR_OK);
    }
    double ink = pnpr_drawing_ink_length(&d, PNPR_LAYER_COUNT_), before = pnpr_drawing_travel(&d);
    CHECK_STATUS(pnpr_drawing_order_for_plotter(&d), PNPR_OK);
    double after = pnpr_drawing_travel(&d);
    printf("plotter order: travel %.0f -> %.0f px\n", before, after);
    CHECK(d.count == 400 && fabs(pnpr_drawing_ink_length(&d, PNPR_LAYER_COUNT_) - ink) < 1e-3 && after < 0.25 * before);
    for (size_t i = 1; i < d.count; i++) CHECK(d.layer[i] >= d.layer[i - 1]);
    pnpr_drawing_free(&d);
}

/* Colour areas: a red square 20 x 20 at (10,10) with a blue 6 x 6 square in its middle, and two
 * green pixels touching at a corner, on white: the red path has two loops (its outline and the
 * hole, the second a subpath), each the 4 corners of its square exactly; blue one loop; green two
 * separate loops (pixels that touch at a corner stay apart); white left out. An image of 90000
 * colours is refused. */
static void check_regions(void)
{
    enum { R = 48 };
    static uint8_t img[R * R * 4];
    memset(img, 255, sizeof img);
    for (int y = 10; y < 30; y++)
        for (int x = 10; x < 30; x++) {
            uint8_t *p = img + 4 * (y * R + x);
            int hole = x >= 17 && x < 23 && y >= 17 && y < 23;
            p[0] = hole ? 0 : 255; p[1] = 0; p[2] = hole ? 255 : 0;
        }
    const int gx[2] = {40, 41}, gy[2] = {40, 41};
    for (int k = 0; k < 2; k++) { uint8_t *p = img + 4 * (gy[k] * R + gx[k]); p[0] = 0; p[1] = 200; p[2] = 0; }
    const uint8_t white[4] = {255, 255, 255, 255};
    pnpr_drawing d = {0};
    CHECK_STATUS(pnpr_drawing_trace_regions(&d, img, R, R, 0, white, PNPR_LAYER_FILLS), PNPR_OK);
    printf("regions: %zu loops\n", d.count);
    CHECK(d.count == 5);
    size_t red = 0, blue = 0, green = 0;
    for (size_t i = 0; i < d.count; i++) {
        CHECK(d.flags[i] & PNPR_PATH_FILL);
        CHECK(d.offset[i + 1] - d.offset[i] == 4);
        red += d.rgba[4 * i] == 255;
        blue += d.rgba[4 * i + 2] == 255;
        green += d.rgba[4 * i + 1] == 200;
    }
    CHECK(red == 2 && blue == 1 && green == 2);
    /* the red outline's corners are the square's, exactly; the hole follows as a subpath */
    CHECK(d.count >= 2 && d.rgba[0] == 255 && !(d.flags[0] & PNPR_PATH_SUBPATH) && (d.flags[1] & PNPR_PATH_SUBPATH));
    float lo = 1e9f, hi = -1e9f;
    for (size_t v = d.offset[0]; d.count && v < d.offset[1]; v++) { lo = fminf(lo, d.xy[2 * v]); hi = fmaxf(hi, d.xy[2 * v]); }
    CHECK(lo == 10 && hi == 30);
    pnpr_drawing_free(&d);
    static uint8_t many[300 * 300 * 4];
    for (int i = 0; i < 300 * 300; i++) { many[4 * i] = (uint8_t)i; many[4 * i + 1] = (uint8_t)(i >> 8); many[4 * i + 2] = (uint8_t)(i >> 16); many[4 * i + 3] = 255; }
    CHECK_STATUS(pnpr_drawing_trace_regions(&d, many, 300, 300, 0, white, PNPR_LAYER_FILLS), PNPR_ERR_UNSUPPORTED);
    CHECK_STATUS(pnpr_drawing_trace_regions(&d, img, 0, R, 0, white, PNPR_LAYER_FILLS), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_drawing_free(&d);
}

/* Repeated marks: the same stroke twice (once reversed, once a tenth of a pixel off) and a dot
 * twice leave one of each; another colour or layer stays. */
static void check_dedupe(void)
{
    pnpr_drawing d = {0};
    const float a[4] = {1, 1, 9, 5}, rev[4] = {9, 5, 1, 1}, off[4] = {1.02f, 1.05f, 9.04f, 4.98f}, dot[2] = {3, 3};
    const uint8_t red[4] = {255, 0, 0, 255};
    CHECK_STATUS(pnpr_drawing_add(&d, a, 2, 1, INK, PNPR_LAYER_STROKES, 0), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, rev, 2, 1, INK, PNPR_LAYER_STROKES, 0), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, off, 2, 1, INK, PNPR_LAYER_STROKES, 0), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, a, 2, 1, red, PNPR_LAYER_STROKES, 0), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, a, 2, 1, INK, PNPR_LAYER_HATCHES, 0), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, dot, 1, 2, INK, PNPR_LAYER_DOTS, PNPR_PATH_DOT), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, dot, 1, 2, INK, PNPR_LAYER_DOTS, PNPR_PATH_DOT), PNPR_OK);
    size_t removed = 0;
    CHECK_STATUS(pnpr_drawing_dedupe(&d, 0.25f, &removed), PNPR_OK);
    printf("dedupe: %zu removed, %zu left\n", removed, d.count);
    CHECK(removed == 3 && d.count == 4 && d.xy[0] == 1 && d.xy[2] == 9);
    CHECK_STATUS(pnpr_drawing_dedupe(&d, 0, NULL), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_drawing_free(&d);
}

/* Short marks: open paths under the length go; dots, areas and loops stay. */
static void check_drop_short(void)
{
    pnpr_drawing d = {0};
    const float s3[4] = {0, 0, 3, 0}, s5[4] = {0, 0, 3, 4}, dot[2] = {1, 1}, sq[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    CHECK_STATUS(pnpr_drawing_add(&d, s3, 2, 1, INK, PNPR_LAYER_HATCHES, 0), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, s5, 2, 1, INK, PNPR_LAYER_HATCHES, 0), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, dot, 1, 2, INK, PNPR_LAYER_DOTS, PNPR_PATH_DOT), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, sq, 4, 1, INK, PNPR_LAYER_OUTLINES, PNPR_PATH_CLOSED), PNPR_OK);
    size_t removed = 9;
    CHECK_STATUS(pnpr_drawing_drop_short(&d, 4.5f, &removed), PNPR_OK);
    CHECK(removed == 1 && d.count == 3 && d.xy[2] == 3 && d.xy[3] == 4);
    CHECK_STATUS(pnpr_drawing_drop_short(&d, NAN, NULL), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_drawing_free(&d);
}

/* The SVG: one Inkscape layer per non-empty class, dots as circles; paths of one colour in one
 * group, a path of another width saying its own; bad paths refused. */
static void check_svg(void)
{
    pnpr_drawing d = {0};
    d.width = 50;
    d.height = 40;
    const float p[4] = {1, 2, 30, 20}, dot[2] = {10, 10}, bad[2] = {NAN, 1};
    CHECK_STATUS(pnpr_drawing_add(&d, p, 2, 2, INK, PNPR_LAYER_STROKES, 0), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, dot, 1, 2.5f, INK, PNPR_LAYER_DOTS, PNPR_PATH_DOT), PNPR_OK);
    const float q[4] = {5, 6, 7, 8};
    CHECK_STATUS(pnpr_drawing_add(&d, q, 2, 1.5f, INK, PNPR_LAYER_STROKES, 0), PNPR_OK);
    CHECK_STATUS(pnpr_drawing_add(&d, bad, 1, 1, INK, PNPR_LAYER_DOTS, 0), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_drawing_add(&d, p, 0, 1, INK, PNPR_LAYER_DOTS, 0), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_drawing_add(&d, p, 2, 1, INK, PNPR_LAYER_COUNT_, 0), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(d.count == 3);
    char path[512];
    snprintf(path, sizeof path, "%s/drawing.svg", PNPR_TEST_SCRATCH);
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_drawing_write_svg(&d, path, &err), PNPR_OK);
    FILE *f = fopen(path, "r");
    char text[4096] = {0};
    size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f) fclose(f);
    CHECK(n > 0 && strstr(text, "inkscape:label=\"strokes\"") && strstr(text, "inkscape:label=\"dots\"") &&
          !strstr(text, "inkscape:label=\"hatches\"") && strstr(text, "<circle cx=\"10.00\" cy=\"10.00\" r=\"1.25\"/>") &&
          strstr(text, "M1.00 2.00L30.00 20.00") && strstr(text, "width=\"50px\" height=\"40px\""));
    /* the two strokes: one group at the first's width, the second's own */
    const char *g = strstr(text, "stroke-width=\"2.00\">\n<path d=\"M1.00 2.00L30.00 20.00\"/>\n"
                                 "<path stroke-width=\"1.50\" d=\"M5.00 6.00L7.00 8.00\"/>\n</g>");
    CHECK_MSG(g != NULL, "strokes of one colour and two widths:\n%s", text);
    d.width = 0;
    CHECK_STATUS(pnpr_drawing_write_svg(&d, path, &err), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_drawing_free(&d);
}

int main(void)
{
    check_ring();
    check_bar_cross_speck();
    check_merge();
    check_order();
    check_regions();
    check_dedupe();
    check_drop_short();
    check_svg();
    return pnpr_test_finish("test_drawing");
}
