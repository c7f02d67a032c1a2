/* Tonal art maps (include/pointnpr/hierarchy.h, filters/tam.c), known answers: the names, bad
 * arguments, the soft round footprint (0 outside the unit circle), determinism, and per kind the
 * tone table 0.08 .. 0.78 of core coverage (hatch within 0.06, 0.12 at 8 x 8; dots within 0.01),
 * pixelwise nesting in tone (hatch, dots), hatching along u up to tone 2 and cross-hatched at
 * tone 5, the 4 x 4 dot grid, and the paint's bristle streaks widening with the tone. */
#include "testutil.h"

#include <pointnpr/hierarchy.h>

#include <math.h>
#include <string.h>

enum { S0 = PNPR_TAM_SIZE, IMAGES = PNPR_TAM_TONES * PNPR_TAM_SIZE * PNPR_TAM_SIZE };

static const double targets[PNPR_TAM_TONES] = {0.08, 0.18, 0.30, 0.44, 0.60, 0.78};

/* Pixel (x, y)'s centre's distance from the centre, the square mapped onto -1..1. */
static double radius_of(int s, int x, int y)
{
    double a = (2.0 * x + 1.0) / s - 1.0, b = (2.0 * y + 1.0) / s - 1.0;
    return sqrt(a * a + b * b);
}

static int is_core(int s, int x, int y) { return radius_of(s, x, y) < 0.7; }

/* Mean coverage (0..1) of the core of image a (side s). */
static double core_mean(const uint8_t *a, int s)
{
    double sum = 0;
    int n = 0;
    for (int y = 0; y < s; y++)
        for (int x = 0; x < s; x++)
            if (is_core(s, x, y)) { sum += a[y * s + x] / 255.0; n++; }
    return n ? sum / n : -1;
}

static void test_names(void)
{
    CHECK(!strcmp(pnpr_tam_name(PNPR_TAM_PAINT), "paint"));
    CHECK(!strcmp(pnpr_tam_name(PNPR_TAM_HATCH), "hatch"));
    CHECK(!strcmp(pnpr_tam_name(PNPR_TAM_DOTS), "dots"));
    CHECK(!strcmp(pnpr_tam_name(PNPR_TAM_COUNT_), ""));
    CHECK(!strcmp(pnpr_tam_name((pnpr_tam_kind)-1), ""));
    for (int k = 0; k < PNPR_TAM_COUNT_; k++) CHECK(pnpr_tam_find(pnpr_tam_name((pnpr_tam_kind)k)) == k);
    CHECK(pnpr_tam_find("HATCH") == PNPR_TAM_HATCH);
    CHECK(pnpr_tam_find("Dots") == PNPR_TAM_DOTS);
    CHECK(pnpr_tam_find("crayon") == -1);
    CHECK(pnpr_tam_find("hatc") == -1);
    CHECK(pnpr_tam_find("") == -1);
    CHECK(pnpr_tam_find(NULL) == -1);
}

static void test_bad_arguments(void)
{
    static uint8_t a[IMAGES];
    CHECK_STATUS(pnpr_tam_level(PNPR_TAM_HATCH, -1, a), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_tam_level(PNPR_TAM_HATCH, PNPR_TAM_LEVELS, a), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_tam_level(PNPR_TAM_COUNT_, 0, a), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_tam_level((pnpr_tam_kind)-1, 0, a), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_tam_level(PNPR_TAM_DOTS, 0, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_tam_level(PNPR_TAM_DOTS, PNPR_TAM_LEVELS - 1, a), PNPR_OK);
}

/* Every kind, level and tone: 0 at and beyond the unit circle (the corners among them); two
 * calls into buffers filled with different bytes give the same images. */
static void test_footprint_and_determinism(void)
{
    static uint8_t a[IMAGES], b[IMAGES];
    for (int k = 0; k < PNPR_TAM_COUNT_; k++)
        for (int level = 0; level < PNPR_TAM_LEVELS; level++) {
            int s = PNPR_TAM_SIZE >> level, outside = 0;
            size_t n = (size_t)PNPR_TAM_TONES * (size_t)s * (size_t)s;
            memset(a, 0xAA, sizeof a);
            memset(b, 0x55, sizeof b);
            CHECK_STATUS(pnpr_tam_level((pnpr_tam_kind)k, level, a), PNPR_OK);
            CHECK_STATUS(pnpr_tam_level((pnpr_tam_kind)k, level, b), PNPR_OK);
            CHECK_MSG(!memcmp(a, b, n), "%s level %d differs between calls", pnpr_tam_name((pnpr_tam_kind)k), level);
            for (int t = 0; t < PNPR_TAM_TONES; t++) {
                const uint8_t *img = a + (size_t)t * (size_t)s * (size_t)s;
                CHECK(img[0] == 0 && img[s - 1] == 0 && img[(s - 1) * s] == 0 && img[s * s - 1] == 0);
                for (int y = 0; y < s; y++)
                    for (int x = 0; x < s; x++) outside += radius_of(s, x, y) >= 1 && img[y * s + x] != 0;
            }
            CHECK_MSG(outside == 0, "%s level %d: %d pixels outside the footprint", pnpr_tam_name((pnpr_tam_kind)k),
                      level, outside);
        }
}

/* Pixelwise nesting in tone: no pixel of tone t is darker than in tone t + 1. */
static void check_nested(const uint8_t *a, int s, const char *what, int level)
{
    int bad = 0;
    for (int t = 0; t + 1 < PNPR_TAM_TONES; t++)
        for (int i = 0; i < s * s; i++) bad += a[(size_t)t * s * s + i] > a[(size_t)(t + 1) * s * s + i];
    CHECK_MSG(bad == 0, "%s level %d: %d pixels lighter in a darker tone", what, level, bad);
}

/* The sum of |differences| along u over the sum along v, in the core. */
static double gradient_ratio(const uint8_t *a, int s)
{
    double gu = 0, gv = 0;
    for (int y = 0; y + 1 < s; y++)
        for (int x = 0; x + 1 < s; x++)
            if (is_core(s, x, y)) {
                gu += fabs((double)a[y * s + x + 1] - a[y * s + x]);
                gv += fabs((double)a[(y + 1) * s + x] - a[y * s + x]);
            }
    return gv > 0 ? gu / gv : -1;
}

static void test_hatch(void)
{
    static uint8_t a[IMAGES];
    for (int level = 0; level < PNPR_TAM_LEVELS; level++) {
        int s = PNPR_TAM_SIZE >> level;
        CHECK_STATUS(pnpr_tam_level(PNPR_TAM_HATCH, level, a), PNPR_OK);
        check_nested(a, s, "hatch", level);
        double tol = level == PNPR_TAM_LEVELS - 1 ? 0.12 : 0.06;
        for (int t = 0; t < PNPR_TAM_TONES; t++) {
            double m = core_mean(a + (size_t)t * s * s, s);
            CHECK_MSG(fabs(m - targets[t]) <= tol, "hatch level %d tone %d: core %.3f, target %.2f", level, t, m,
                      targets[t]);
        }
        if (level == PNPR_TAM_LEVELS - 1) continue; /* 8 x 8: too few strokes for directions */
        /* tones 0-2 hatch along u only (the ink changes across the strokes, along v); tone 5 is
         * cross-hatched (changes along both) */
        for (int t = 0; t < 3; t++) {
            double r = gradient_ratio(a + (size_t)t * s * s, s);
            CHECK_MSG(r >= 0 && r < 0.2, "hatch level %d tone %d: along/across %.3f", level, t, r);
        }
        double r5 = gradient_ratio(a + (size_t)5 * s * s, s);
        CHECK_MSG(r5 > 0.5, "hatch level %d tone 5: along/across %.3f", level, r5);
    }
    /* strokes 1 pixel wide at every level, antialiased: in the light tones the inked pixels are
     * about twice the coverage (a tent straddles two rows); strokes as wide in texture space at
     * every level would ink 4 solid pixels across at level 0 (ratio near 1.25) */
    for (int level = 0; level < PNPR_TAM_LEVELS - 1; level++) {
        int s = PNPR_TAM_SIZE >> level;
        CHECK_STATUS(pnpr_tam_level(PNPR_TAM_HATCH, level, a), PNPR_OK);
        for (int t = 0; t < 2; t++) {
            const uint8_t *img = a + (size_t)t * s * s;
            int inked = 0, core = 0, peak = 0;
            for (int y = 0; y < s; y++)
                for (int x = 0; x < s; x++)
                    if (is_core(s, x, y)) {
                        core++;
                        inked += img[y * s + x] > 0;
                        peak = img[y * s + x] > peak ? img[y * s + x] : peak;
                    }
            double ratio = (double)inked / core / core_mean(img, s);
            CHECK_MSG(ratio > 1.5 && ratio < 2.6 && peak >= 128, "hatch level %d tone %d: inked/coverage %.2f, peak %d",
                      level, t, ratio, peak);
        }
    }
}

static void test_dots(void)
{
    static uint8_t a[IMAGES];
    for (int level = 0; level < PNPR_TAM_LEVELS; level++) {
        int s = PNPR_TAM_SIZE >> level, c = s / 4;
        CHECK_STATUS(pnpr_tam_level(PNPR_TAM_DOTS, level, a), PNPR_OK);
        check_nested(a, s, "dots", level);
        for (int t = 0; t < PNPR_TAM_TONES; t++) {
            const uint8_t *img = a + (size_t)t * s * s;
            double m = core_mean(img, s);
            CHECK_MSG(fabs(m - targets[t]) <= 0.01, "dots level %d tone %d: core %.3f, target %.2f", level, t, m,
                      targets[t]);
            /* 4 x 4 cells of side c: at levels 0 and 1 every tone inks the centre of cell (1, 1)
             * (its dot's) and leaves the corner shared by the four inner cells white */
            if (level <= 1) {
                CHECK_MSG(img[(c + c / 2) * s + c + c / 2] == 255, "dots level %d tone %d: dot centre", level, t);
                CHECK_MSG(img[2 * c * s + 2 * c] == 0, "dots level %d tone %d: between dots", level, t);
            }
        }
    }
}

/* Standard deviation of the row means of the core, and the lowest and highest row mean. */
static double row_spread(const uint8_t *a, int s, double *r_lo, double *r_hi)
{
    double rows[PNPR_TAM_SIZE], sum = 0, var = 0;
    int n = 0;
    *r_lo = 1;
    *r_hi = 0;
    for (int y = 0; y < s; y++) {
        double row = 0;
        int c = 0;
        for (int x = 0; x < s; x++)
            if (is_core(s, x, y)) { row += a[y * s + x] / 255.0; c++; }
        if (!c) continue;
        rows[n] = row / c;
        sum += rows[n];
        *r_lo = fmin(*r_lo, rows[n]);
        *r_hi = fmax(*r_hi, rows[n]);
        n++;
    }
    for (int i = 0; i < n; i++) var += (rows[i] - sum / n) * (rows[i] - sum / n);
    return n ? sqrt(var / n) : -1;
}

static void test_paint(void)
{
    static uint8_t a[IMAGES];
    for (int level = 0; level < PNPR_TAM_LEVELS; level++) {
        int s = PNPR_TAM_SIZE >> level;
        CHECK_STATUS(pnpr_tam_level(PNPR_TAM_PAINT, level, a), PNPR_OK);
        double std[PNPR_TAM_TONES], lo[PNPR_TAM_TONES], hi[PNPR_TAM_TONES];
        for (int t = 0; t < PNPR_TAM_TONES; t++) {
            const uint8_t *img = a + (size_t)t * s * s;
            double m = core_mean(img, s);
            CHECK_MSG(m > 0.5 && m < 0.95, "paint level %d tone %d: core %.3f", level, t, m);
            std[t] = row_spread(img, s, &lo[t], &hi[t]);
            if (t > 0)
                CHECK_MSG(std[t] > std[t - 1], "paint level %d: row std %.4f at tone %d, %.4f before", level, std[t], t,
                          std[t - 1]);
        }
        CHECK_MSG(std[5] > 2 * std[0], "paint level %d: row std %.4f .. %.4f", level, std[0], std[5]);
        /* tone 0 almost uniform (0.85 +- 0.03), tone 5 streaks from 0.45 to 1.0 */
        CHECK_MSG(hi[0] - lo[0] < 0.1 && lo[0] > 0.78 && hi[0] < 0.9, "paint level %d tone 0: rows %.3f .. %.3f", level,
                  lo[0], hi[0]);
        CHECK_MSG(lo[5] < 0.5 && hi[5] > 0.95, "paint level %d tone 5: rows %.3f .. %.3f", level, lo[5], hi[5]);
    }
}

int main(void)
{
    test_names();
    test_bad_arguments();
    test_footprint_and_determinism();
    test_hatch();
    test_dots();
    test_paint();
    return pnpr_test_finish("test_tam");
}
