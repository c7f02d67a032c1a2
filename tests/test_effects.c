/* Image-space effects (include/pointnpr/effects.h), known answers: posterise levels, grey at
 * saturation 0, smoothing and edges leaving a constant image alone, toon and edges lines only along
 * a step, watercolour / oil / pencil keeping the mean colour of a flat image, pencil ink by tone,
 * determinism and seeds, range checks with messages, degenerate sizes, chains = steps. Without
 * OpenCV: the effects that need it report PNPR_ERR_UNSUPPORTED. */
#include "testutil.h"

#include <pointnpr/effects.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static pnpr_image image_new(int w, int h)
{
    pnpr_image im = {w, h, calloc((size_t)w * (size_t)h, 4)};
    if (!im.rgba) abort();
    return im;
}

static void fill(pnpr_image *im, uint8_t r, uint8_t g, uint8_t b, uint8_t a)
{
    for (size_t i = 0, n = (size_t)im->width * (size_t)im->height; i < n; i++) {
        im->rgba[4 * i] = r; im->rgba[4 * i + 1] = g; im->rgba[4 * i + 2] = b; im->rgba[4 * i + 3] = a;
    }
}

/* Deterministic random colours and alphas. */
static void noise(pnpr_image *im, uint64_t seed)
{
    pnpr_test_rng rng = {seed};
    for (size_t i = 0, n = (size_t)im->width * (size_t)im->height * 4; i < n; i++)
        im->rgba[i] = (uint8_t)(pnpr_test_uniform(&rng) * 256);
}

static pnpr_effect effect(pnpr_effect_kind kind)
{
    pnpr_effect e;
    memset(&e, 0, sizeof e);
    e.kind = kind;
    return e;
}

/* Sets the parameter `name` of e (must exist). */
static void set(pnpr_effect *e, const char *name, float v)
{
    int count;
    const pnpr_effect_param_info *p = pnpr_effect_params(e->kind, &count);
    for (int i = 0; i < count; i++)
        if (!strcmp(p[i].name, name)) { e->params[i] = v; e->set |= 1u << i; return; }
    CHECK_MSG(0, "no parameter %s", name);
}

static double luma(const uint8_t *p)
{
    return (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0;
}

static void test_posterise(void)
{
    pnpr_image src = image_new(256, 3), dst = image_new(256, 3);
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 256; x++) {
            uint8_t *p = src.rgba + 4 * (y * 256 + x);
            p[0] = p[1] = p[2] = (uint8_t)x; p[3] = (uint8_t)(255 - x);
        }
    const int levels[] = {2, 4, 7, 64};
    for (int t = 0; t < 4; t++) {
        pnpr_effect e = effect(PNPR_EFFECT_POSTERISE);
        set(&e, "levels", (float)levels[t]);
        set(&e, "normalise", 0); /* each channel as it is */
        CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
        int seen[256] = {0}, distinct = 0;
        for (int i = 0; i < 256 * 3; i++) {
            for (int c = 0; c < 3; c++)
                if (!seen[dst.rgba[4 * i + c]]++) distinct++;
            CHECK(dst.rgba[4 * i + 3] == src.rgba[4 * i + 3]);
        }
        CHECK_MSG(distinct == levels[t], "levels %d gave %d values", levels[t], distinct);
        CHECK(seen[0] && seen[255]); /* black and white are levels */
        CHECK(dst.rgba[0] == 0 && dst.rgba[4 * 255] == 255);
    }
    free(src.rgba);
    free(dst.rgba);
}

/* Tone normalisation on a light, low-contrast layer (a colourless scan shaded 0.67..0.86):
 * posterise keeps several grey levels (one or two without), none of them paper white; pencil
 * hatches the darker half and leaves the lighter light. */
static void test_tone_normalise(void)
{
    const int w = 128, h = 64;
    pnpr_image src = image_new(w, h), dst = image_new(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint8_t *p = src.rgba + 4 * (y * w + x);
            p[0] = p[1] = p[2] = (uint8_t)(170 + 50 * x / (w - 1));
            p[3] = 255;
        }
    for (int norm = 0; norm < 2; norm++) {
        pnpr_effect e = effect(PNPR_EFFECT_POSTERISE);
        set(&e, "normalise", (float)norm);
        CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
        int seen[256] = {0}, distinct = 0, grey = 1;
        for (int i = 0; i < w * h; i++) {
            const uint8_t *p = dst.rgba + 4 * i;
            grey &= p[0] == p[1] && p[1] == p[2];
            if (!seen[p[0]]++) distinct++;
        }
        if (norm) CHECK_MSG(distinct >= 3 && grey && !seen[255] && !seen[0], "normalised posterise: %d greys", distinct);
        else CHECK_MSG(distinct <= 2, "posterise per channel: %d values", distinct);
    }
    /* pencil: left half 0.70, right half 0.85 */
    for (int i = 0; i < w * h; i++) {
        uint8_t v = (i % w) < w / 2 ? 179 : 217;
        src.rgba[4 * i] = src.rgba[4 * i + 1] = src.rgba[4 * i + 2] = v;
    }
    double mean[2][2] = {{0}};
    for (int norm = 0; norm < 2; norm++) {
        pnpr_effect e = effect(PNPR_EFFECT_PENCIL);
        set(&e, "normalise", (float)norm);
        set(&e, "outline", 0);
        CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 5, NULL), PNPR_OK);
        for (int y = 8; y < h - 8; y++)
            for (int x = 8; x < w - 8; x++)
                if (x < w / 2 - 8 || x >= w / 2 + 8) mean[norm][x >= w / 2] += dst.rgba[4 * (y * w + x)] / 255.0 / ((w / 2 - 16) * (h - 16));
    }
    CHECK_MSG(mean[1][0] < 0.6 && mean[1][1] > 0.75 && mean[0][0] > mean[1][0] + 0.1,
              "pencil on 0.70 | 0.85: normalised %.3f | %.3f, as is %.3f | %.3f", mean[1][0], mean[1][1], mean[0][0], mean[0][1]);
    free(src.rgba);
    free(dst.rgba);
}

/* The segment's outline from its coverage: a light grey square (230) on paper (alpha 0) gets a dark
 * border from edges, toon and pencil (silhouette 1), not without (silhouette 0: the colour DoG
 * barely sees 230 against 255); edges with paper = 1 leaves the square's inside paper white. */
static void test_silhouette(void)
{
    const int w = 96, h = 96, x0 = 24, x1 = 71;
    pnpr_image src = image_new(w, h), dst = image_new(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint8_t *p = src.rgba + 4 * (y * w + x);
            int in = x >= x0 && x <= x1 && y >= x0 && y <= x1;
            p[0] = p[1] = p[2] = in ? 230 : 255;
            p[3] = in ? 255 : 0;
        }
    const pnpr_effect_kind kinds[] = {PNPR_EFFECT_EDGES, PNPR_EFFECT_TOON, PNPR_EFFECT_PENCIL};
    for (int k = 0; k < 3; k++)
        for (int on = 0; on < 2; on++) {
            pnpr_effect e = effect(kinds[k]);
            set(&e, "silhouette", (float)on);
            CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 1, NULL), PNPR_OK);
            int ring = 0, dark = 0;
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++) {
                    int dx = x < x0 ? x0 - x : x > x1 ? x - x1 : 0, dy = y < x0 ? x0 - y : y > x1 ? y - x1 : 0;
                    int inside = !dx && !dy, edge = inside && (x == x0 || x == x1 || y == x0 || y == x1);
                    if (!edge || (x > x0 + 4 && x < x1 - 4 ? 0 : y > x0 + 4 && y < x1 - 4 ? 0 : 1)) continue;
                    ring++; /* the border away from the corners */
                    dark += dst.rgba[4 * (y * w + x)] < 128;
                }
            if (on) CHECK_MSG(dark >= ring * 9 / 10, "%s: %d of %d border px dark", pnpr_effect_name(kinds[k]), dark, ring);
            else CHECK_MSG(dark <= ring / 10, "%s without silhouette: %d of %d border px dark", pnpr_effect_name(kinds[k]), dark, ring);
        }
    pnpr_effect e = effect(PNPR_EFFECT_EDGES);
    set(&e, "paper", 1);
    CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 1, NULL), PNPR_OK);
    const uint8_t *mid = dst.rgba + 4 * (48 * w + 48);
    CHECK_MSG(mid[0] == 255 && mid[1] == 255 && mid[2] == 255 && mid[3] == 255, "paper inside: %d %d %d %d", mid[0], mid[1], mid[2], mid[3]);
    free(src.rgba);
    free(dst.rgba);
}

/* Watercolour on a yellow surface with 15% black specks (an RGB-D frame's texture noise): the
 * morphological smoothing removes specks instead of merging them into blobs, and the coverage gap
 * fill paints a 1-px hole grid over in the surface's colour. */
static void test_watercolour_specks(void)
{
    const int w = 96, h = 96;
    pnpr_image src = image_new(w, h), dst = image_new(w, h);
    pnpr_test_rng rng = {11};
    size_t dark_in = 0, dark_out = 0, holes = 0, hole_yellow = 0;
    for (int i = 0; i < w * h; i++) {
        uint8_t *p = src.rgba + 4 * i;
        int speck = pnpr_test_uniform(&rng) < 0.15, hole = (i % w) % 4 == 0 && (i / w) % 4 == 0;
        p[0] = hole ? 255 : speck ? 0 : 235;
        p[1] = hole ? 255 : speck ? 0 : 220;
        p[2] = hole ? 255 : speck ? 0 : 60;
        p[3] = hole ? 0 : 255;
        dark_in += speck && !hole;
    }
    pnpr_effect e = effect(PNPR_EFFECT_WATERCOLOUR);
    CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 3, NULL), PNPR_OK);
    for (int i = 0; i < w * h; i++) {
        const uint8_t *p = dst.rgba + 4 * i;
        dark_out += luma(p) < 0.2;
        if (src.rgba[4 * i + 3] == 0) { holes++; hole_yellow += p[2] < 150; }
    }
    CHECK_MSG(dark_out * 10 <= dark_in, "watercolour: %zu dark px of %zu black specks", dark_out, dark_in);
    CHECK_MSG(hole_yellow >= holes * 9 / 10, "watercolour: %zu of %zu holes painted yellow", hole_yellow, holes);
    free(src.rgba);
    free(dst.rgba);
}

static void test_grade(void)
{
    pnpr_image src = image_new(32, 32), dst = image_new(32, 32);
    noise(&src, 7);
    /* every 17th pixel paper (alpha 0: no fragment), the others fragments */
    for (int i = 0; i < 32 * 32; i++)
        src.rgba[4 * i + 3] = i % 17 == 0 ? 0 : src.rgba[4 * i + 3] ? src.rgba[4 * i + 3] : 1;
    pnpr_effect e = effect(PNPR_EFFECT_GRADE);
    set(&e, "saturation", 0);
    CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
    int grey = 1, paper_kept = 1;
    for (int i = 0; i < 32 * 32; i++) {
        const uint8_t *p = dst.rgba + 4 * i;
        if (i % 17 == 0) { paper_kept &= !memcmp(p, src.rgba + 4 * i, 4); continue; }
        grey &= p[0] == p[1] && p[1] == p[2] && p[3] == src.rgba[4 * i + 3];
        if (!grey) break;
        CHECK_NEAR(p[0], luma(src.rgba + 4 * i) * 255, 0.51);
    }
    CHECK(grey);
    CHECK_MSG(paper_kept, "grade leaves paper (alpha 0) as it is");
    /* the defaults change nothing */
    e = effect(PNPR_EFFECT_GRADE);
    CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
    CHECK(!memcmp(src.rgba, dst.rgba, 32 * 32 * 4));
    /* brightness +0.2 on mid grey 100: 100 + 51; recolour 1 with a red tint: (Y, 0, 0) */
    fill(&src, 100, 100, 100, 9);
    set(&e, "brightness", 0.2f);
    CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
    CHECK(dst.rgba[0] == 151 && dst.rgba[1] == 151 && dst.rgba[3] == 9);
    e = effect(PNPR_EFFECT_GRADE);
    set(&e, "tint_g", 0);
    set(&e, "tint_b", 0);
    set(&e, "recolour", 1);
    CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
    CHECK(dst.rgba[0] == 100 && dst.rgba[1] == 0 && dst.rgba[2] == 0);
    free(src.rgba);
    free(dst.rgba);
}

/* Set parameters outside their range are refused with a message naming effect and parameter. */
static void test_ranges(void)
{
    pnpr_image src = image_new(4, 4), dst = image_new(4, 4);
    for (int k = 0; k < PNPR_EFFECT_COUNT_; k++) {
        int count;
        const pnpr_effect_param_info *p = pnpr_effect_params((pnpr_effect_kind)k, &count);
        CHECK(p && count >= 1 && count <= PNPR_EFFECT_PARAMS_MAX);
        for (int i = 0; i < count; i++) {
            CHECK(p[i].def >= p[i].min && p[i].def <= p[i].max);
            const float bad[3] = {p[i].max + 1, p[i].min - 1, NAN};
            for (int t = 0; t < 3; t++) {
                pnpr_effect e = effect((pnpr_effect_kind)k);
                e.params[i] = bad[t];
                e.set = 1u << i;
                pnpr_error err;
                memset(&err, 0, sizeof err);
                CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, &err), PNPR_ERR_INVALID_ARGUMENT);
                CHECK_MSG(strstr(err.message, pnpr_effect_name(e.kind)) && strstr(err.message, p[i].name),
                          "message '%s'", err.message);
            }
        }
    }
    free(src.rgba);
    free(dst.rgba);
}

#ifdef PNPR_HAVE_OPENCV
/* Left half (x < w / 2) colour a, right half colour b. */
static void step(pnpr_image *im, const uint8_t a[3], const uint8_t b[3])
{
    for (int y = 0; y < im->height; y++)
        for (int x = 0; x < im->width; x++) {
            uint8_t *p = im->rgba + 4 * ((size_t)y * im->width + x);
            memcpy(p, x < im->width / 2 ? a : b, 3);
            p[3] = 255;
        }
}

static void test_smooth_constant(void)
{
    pnpr_image src = image_new(40, 30), dst = image_new(40, 30);
    fill(&src, 100, 150, 200, 77);
    pnpr_effect e = effect(PNPR_EFFECT_SMOOTH);
    set(&e, "radius", 6);
    CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
    CHECK(!memcmp(src.rgba, dst.rgba, 40 * 30 * 4));
    free(src.rgba);
    free(dst.rgba);
}

/* Toon on a light | dark step (64x64, step at x = 32): dark line pixels (luminance below 60% of
 * the flat colour's) exist in every row within 4 px of the step and nowhere further than 8 px;
 * each side far from the step is one flat colour. */
static void test_toon_step(void)
{
    const int w = 64, h = 64;
    pnpr_image src = image_new(w, h), dst = image_new(w, h);
    const uint8_t light[3] = {230, 220, 120}, dark[3] = {40, 60, 140};
    step(&src, light, dark);
    pnpr_effect e = effect(PNPR_EFFECT_TOON);
    CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
    const uint8_t *fl = dst.rgba, *fr = dst.rgba + 4 * (w - 1); /* flat colours: the row's ends */
    int near_rows = 0, far_lines = 0, flat = 1;
    for (int y = 0; y < h; y++) {
        int found = 0;
        for (int x = 0; x < w; x++) {
            const uint8_t *p = dst.rgba + 4 * (y * w + x);
            double ref = luma(x < w / 2 ? fl : fr);
            int line = luma(p) < 0.6 * ref;
            if (abs(x - w / 2) <= 4) found |= line;
            if (abs(x - w / 2) > 8) {
                far_lines += line;
                flat &= !memcmp(p, x < w / 2 ? fl : fr, 4);
            }
        }
        near_rows += found;
    }
    CHECK_MSG(near_rows == h, "%d of %d rows have a line at the step", near_rows, h);
    CHECK_MSG(far_lines == 0, "%d line pixels far from the step", far_lines);
    CHECK(flat);
    CHECK(luma(fl) > luma(fr) + 0.3); /* the sides keep their order */
    /* a constant image stays constant */
    fill(&src, 90, 140, 60, 255);
    CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
    int same = 1;
    for (int i = 1; i < w * h; i++) same &= !memcmp(dst.rgba + 4 * i, dst.rgba, 4);
    CHECK(same);
    free(src.rgba);
    free(dst.rgba);
}

/* Edges: a constant image is unchanged to the byte; on a step only pixels within 3 k sigma of it
 * change, and some darken. */
static void test_edges(void)
{
    const int w = 64, h = 16;
    pnpr_image src = image_new(w, h), dst = image_new(w, h);
    pnpr_effect e = effect(PNPR_EFFECT_EDGES);
    const uint8_t c[3][4] = {{0, 0, 0, 255}, {255, 255, 255, 0}, {37, 180, 99, 128}};
    for (int t = 0; t < 3; t++) {
        fill(&src, c[t][0], c[t][1], c[t][2], c[t][3]);
        CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
        CHECK(!memcmp(src.rgba, dst.rgba, (size_t)w * h * 4));
    }
    const uint8_t light[3] = {220, 220, 220}, darkc[3] = {60, 60, 60};
    step(&src, light, darkc);
    CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 0, NULL), PNPR_OK);
    int far_changed = 0, near_dark = 0;
    double reach = 3 * 1.6 * 1.0 + 1; /* 3 k sigma of the defaults, + the step's own pixel */
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = 4 * ((size_t)y * w + x);
            int changed = memcmp(src.rgba + i, dst.rgba + i, 4) != 0;
            if (fabs(x - (w / 2 - 0.5)) > reach) far_changed += changed;
            else near_dark += dst.rgba[i] < src.rgba[i] - 40;
        }
    CHECK_MSG(far_changed == 0, "%d pixels changed far from the step", far_changed);
    CHECK_MSG(near_dark >= h, "%d darkened pixels near the step", near_dark);
    free(src.rgba);
    free(dst.rgba);
}

static void mean_rgb(const pnpr_image *im, double m[3])
{
    size_t n = (size_t)im->width * (size_t)im->height;
    m[0] = m[1] = m[2] = 0;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) m[c] += im->rgba[4 * i + c];
    for (int c = 0; c < 3; c++) m[c] /= (double)n * 255.0;
}

/* Watercolour, oil and pencil (colour 1) on a flat 256x256 image keep its mean colour (the noise
 * has mean 0.5; pencil hatching reproduces the tone roughly, hence its wider tolerance). */
static void test_constant_mean(void)
{
    const int w = 256, h = 256;
    pnpr_image src = image_new(w, h), dst = image_new(w, h);
    const uint8_t col[3] = {150, 110, 70};
    fill(&src, col[0], col[1], col[2], 200);
    const struct { pnpr_effect_kind kind; double tol; } cases[] = {
        {PNPR_EFFECT_WATERCOLOUR, 0.03}, {PNPR_EFFECT_OIL, 0.02}, {PNPR_EFFECT_PENCIL, 0.15}};
    for (int t = 0; t < 3; t++) {
        pnpr_effect e = effect(cases[t].kind);
        if (cases[t].kind == PNPR_EFFECT_PENCIL) set(&e, "color", 1);
        CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 42, NULL), PNPR_OK);
        double m[3];
        mean_rgb(&dst, m);
        for (int c = 0; c < 3; c++)
            CHECK_MSG(fabs(m[c] - col[c] / 255.0) <= cases[t].tol, "%s channel %d: mean %.4f, source %.4f",
                      pnpr_effect_name(cases[t].kind), c, m[c], col[c] / 255.0);
        CHECK(dst.rgba[3] == 200);
    }
    /* pencil: black draws far more ink than white; white paper stays white */
    pnpr_effect e = effect(PNPR_EFFECT_PENCIL);
    double ink[2];
    for (int t = 0; t < 2; t++) {
        fill(&src, t ? 255 : 0, t ? 255 : 0, t ? 255 : 0, 255);
        CHECK_STATUS(pnpr_effect_apply(&e, &src, &dst, 3, NULL), PNPR_OK);
        double m[3];
        mean_rgb(&dst, m);
        ink[t] = 1 - (m[0] + m[1] + m[2]) / 3;
    }
    CHECK_MSG(ink[0] > 0.2 && ink[1] < 0.01, "pencil ink on black %.3f, on white %.3f", ink[0], ink[1]);
    free(src.rgba);
    free(dst.rgba);
}

/* Every effect: two runs give the same bytes and keep alpha; the noisy ones differ by seed. */
static void test_determinism(void)
{
    const int w = 96, h = 64;
    pnpr_image src = image_new(w, h), a = image_new(w, h), b = image_new(w, h);
    noise(&src, 11);
    size_t bytes = (size_t)w * h * 4;
    for (int k = 0; k < PNPR_EFFECT_COUNT_; k++) {
        pnpr_effect e = effect((pnpr_effect_kind)k);
        CHECK_STATUS(pnpr_effect_apply(&e, &src, &a, 5, NULL), PNPR_OK);
        CHECK_STATUS(pnpr_effect_apply(&e, &src, &b, 5, NULL), PNPR_OK);
        CHECK_MSG(!memcmp(a.rgba, b.rgba, bytes), "%s is not deterministic", pnpr_effect_name(e.kind));
        int alpha = 1;
        for (size_t i = 3; i < bytes; i += 4) alpha &= a.rgba[i] == src.rgba[i];
        CHECK_MSG(alpha, "%s changed alpha", pnpr_effect_name(e.kind));
        CHECK_STATUS(pnpr_effect_apply(&e, &src, &b, 6, NULL), PNPR_OK);
        int noisy = k == PNPR_EFFECT_WATERCOLOUR || k == PNPR_EFFECT_OIL || k == PNPR_EFFECT_PENCIL;
        CHECK_MSG(noisy == (memcmp(a.rgba, b.rgba, bytes) != 0), "%s: seed dependence %d expected",
                  pnpr_effect_name(e.kind), noisy);
    }
    free(src.rgba);
    free(a.rgba);
    free(b.rgba);
}

/* 1x1, 1x2000 and 2000x1 images with every effect and the edge parameters at their extremes. */
static void test_sizes(void)
{
    const int sz[3][2] = {{1, 1}, {1, 2000}, {2000, 1}};
    for (int s = 0; s < 3; s++) {
        pnpr_image src = image_new(sz[s][0], sz[s][1]), dst = image_new(sz[s][0], sz[s][1]);
        noise(&src, 3);
        for (int k = 0; k < PNPR_EFFECT_COUNT_; k++)
            for (int extreme = 0; extreme < 2; extreme++) {
                pnpr_effect e = effect((pnpr_effect_kind)k);
                int count;
                const pnpr_effect_param_info *p = pnpr_effect_params(e.kind, &count);
                if (extreme) {
                    for (int i = 0; i < count; i++) e.params[i] = p[i].max;
                    e.set = (1u << count) - 1;
                }
                pnpr_error err;
                memset(&err, 0, sizeof err);
                pnpr_status st = pnpr_effect_apply(&e, &src, &dst, 1, &err);
                CHECK_MSG(st == PNPR_OK, "%s on %dx%d: %s", pnpr_effect_name(e.kind), sz[s][0], sz[s][1], err.message);
            }
        free(src.rgba);
        free(dst.rgba);
    }
}

/* A chain of three equals the three applied one by one (with the chain's per-step seeds). */
static void test_chain(void)
{
    const int w = 50, h = 40;
    pnpr_image src = image_new(w, h), a = image_new(w, h), b = image_new(w, h), c = image_new(w, h);
    noise(&src, 21);
    pnpr_effect_chain chain;
    memset(&chain, 0, sizeof chain);
    chain.count = 3;
    chain.effects[0] = effect(PNPR_EFFECT_WATERCOLOUR);
    chain.effects[1] = effect(PNPR_EFFECT_POSTERISE);
    set(&chain.effects[1], "levels", 5);
    chain.effects[2] = effect(PNPR_EFFECT_EDGES);
    const uint64_t seed = 99, step_seed = 0x9E3779B97F4A7C15ull;
    CHECK_STATUS(pnpr_effect_chain_apply(&chain, &src, &c, seed, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_effect_apply(&chain.effects[0], &src, &a, seed, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_effect_apply(&chain.effects[1], &a, &b, seed + step_seed, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_effect_apply(&chain.effects[2], &b, &a, seed + 2 * step_seed, NULL), PNPR_OK);
    CHECK(!memcmp(a.rgba, c.rgba, (size_t)w * h * 4));
    /* every preset runs */
    int np;
    const pnpr_effect_preset *presets = pnpr_effect_presets(&np);
    for (int i = 0; i < np; i++)
        CHECK_STATUS(pnpr_effect_chain_apply(&presets[i].chain, &src, &c, seed, NULL), PNPR_OK);
    free(src.rgba);
    free(a.rgba);
    free(b.rgba);
    free(c.rgba);
}

#else
/* Without OpenCV: the effects that need it say so; posterise and grade still work. */
static void test_no_opencv(void)
{
    pnpr_image src = image_new(8, 8), dst = image_new(8, 8);
    for (int k = 0; k < PNPR_EFFECT_COUNT_; k++) {
        pnpr_effect e = effect((pnpr_effect_kind)k);
        pnpr_error err;
        memset(&err, 0, sizeof err);
        pnpr_status st = pnpr_effect_apply(&e, &src, &dst, 0, &err);
        if (e.kind != PNPR_EFFECT_POSTERISE && e.kind != PNPR_EFFECT_GRADE) {
            CHECK_STATUS(st, PNPR_ERR_UNSUPPORTED);
            CHECK(strstr(err.message, "OpenCV") != NULL);
        } else {
            CHECK_STATUS(st, PNPR_OK);
        }
    }
    free(src.rgba);
    free(dst.rgba);
}
#endif

int main(void)
{
    test_posterise();
    test_tone_normalise();
    test_silhouette();
    test_watercolour_specks();
    test_grade();
    test_ranges();
#ifdef PNPR_HAVE_OPENCV
    test_smooth_constant();
    test_toon_step();
    test_edges();
    test_constant_mean();
    test_determinism();
    test_sizes();
    test_chain();
#else
    test_no_opencv();
#endif
    return pnpr_test_finish("test_effects");
}
