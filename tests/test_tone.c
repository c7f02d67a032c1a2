/* Tone (include/pointnpr/tone.h), known answers: colour darkness, two-sided key light, the
 * product of both, the curve (contrast, gamma), fallbacks when data are missing, the default
 * light from above for z-up and y-up scenes, bad options. */
#include "testutil.h"

#include <pointnpr/tone.h>

#include <math.h>
#include <string.h>

static void test_colour_and_curve(void)
{
    const uint8_t rgb[9] = {255, 255, 255, 0, 0, 0, 128, 128, 128};
    float t[3];
    pnpr_tone_options o = {0};
    o.source = PNPR_TONE_COLOR;
    o.gamma = 1;
    CHECK_STATUS(pnpr_tone(rgb, NULL, 3, &o, t), PNPR_OK);
    CHECK_NEAR(t[0], 0, 1e-6);
    CHECK_NEAR(t[1], 1, 1e-6);
    CHECK_NEAR(t[2], 1 - 128 / 255.0, 1e-5);
    o.gamma = 0; /* default curve: gamma 2.8 */
    CHECK_STATUS(pnpr_tone(rgb, NULL, 3, &o, t), PNPR_OK);
    CHECK_NEAR(t[2], pow(1 - 128 / 255.0, 2.8), 1e-5);
    o.gamma = 1;
    o.contrast = 2; /* (t - 0.5) * 2 + 0.5, clamped */
    CHECK_STATUS(pnpr_tone(rgb, NULL, 3, &o, t), PNPR_OK);
    CHECK_NEAR(t[0], 0, 1e-6);
    CHECK_NEAR(t[1], 1, 1e-6);
    CHECK_NEAR(t[2], (1 - 128 / 255.0 - 0.5) * 2 + 0.5, 1e-5);
    /* auto with colours only = colour */
    o.source = PNPR_TONE_AUTO;
    o.contrast = 0;
    CHECK_STATUS(pnpr_tone(rgb, NULL, 3, &o, t), PNPR_OK);
    CHECK_NEAR(t[1], 1, 1e-6);
}

static void test_light(void)
{
    pnpr_tone_options o = {0};
    o.source = PNPR_TONE_LIGHT;
    o.gamma = 1;
    o.light[2] = 5; /* from +z, any length */
    const float n[15] = {0, 0, 1, 0, 0, -1, 1, 0, 0, 0, 0, 0, 0, 0.6f, 0.8f};
    float t[5];
    CHECK_STATUS(pnpr_tone(NULL, n, 5, &o, t), PNPR_OK);
    CHECK_NEAR(t[0], 0, 1e-6);             /* facing the light */
    CHECK_NEAR(t[1], 0, 1e-6);             /* the other orientation: the same (two-sided) */
    CHECK_NEAR(t[2], 1 - 0.3, 1e-6);       /* edge-on: ambient only */
    CHECK_NEAR(t[3], 1 - (0.3 + 0.35), 1e-6); /* unknown normal: ambient + half */
    CHECK_NEAR(t[4], 1 - (0.3 + 0.7 * 0.8), 1e-6);
    /* both: 1 - shade * (1 - 0.45 * colour darkness) */
    const uint8_t rgb[15] = {0, 0, 0, 255, 255, 255, 0, 0, 0, 255, 255, 255, 0, 0, 0};
    o.source = PNPR_TONE_BOTH;
    CHECK_STATUS(pnpr_tone(rgb, n, 5, &o, t), PNPR_OK);
    CHECK_NEAR(t[0], 1 - 1 * (1 - 0.45), 1e-6);
    CHECK_NEAR(t[1], 0, 1e-6);
    CHECK_NEAR(t[2], 1 - 0.3 * 0.55, 1e-6);
    /* auto with both arrays = both; light without normals falls back to colour */
    o.source = PNPR_TONE_AUTO;
    float t2[5];
    CHECK_STATUS(pnpr_tone(rgb, n, 5, &o, t2), PNPR_OK);
    CHECK(memcmp(t, t2, sizeof t) == 0);
    o.source = PNPR_TONE_LIGHT;
    CHECK_STATUS(pnpr_tone(rgb, NULL, 5, &o, t), PNPR_OK);
    CHECK_NEAR(t[0], 1, 1e-6);
    /* nothing at all: 0.5 ^ gamma */
    o.source = PNPR_TONE_AUTO;
    o.gamma = 2;
    CHECK_STATUS(pnpr_tone(NULL, NULL, 1, &o, t), PNPR_OK);
    CHECK_NEAR(t[0], 0.25, 1e-6);
}

static void test_default_light(void)
{
    pnpr_tone_options o = {0};
    double l[3];
    pnpr_tone_light(&o, l); /* up +z */
    CHECK_NEAR(l[0] * l[0] + l[1] * l[1] + l[2] * l[2], 1, 1e-12);
    CHECK_NEAR(l[2], cos(35 * 3.14159265358979 / 180), 1e-9); /* 35 degrees off the up axis */
    CHECK(l[1] < 0);                                           /* from the -y (front) side */
    o.up[1] = 2; /* y up */
    pnpr_tone_light(&o, l);
    CHECK_NEAR(l[1], cos(35 * 3.14159265358979 / 180), 1e-9);
    /* a flat ground lit from above is light; a wall facing away from it is darker */
    o.gamma = 1;
    o.source = PNPR_TONE_LIGHT;
    const float n[6] = {0, 1, 0, 0, 0, 1};
    float t[2];
    CHECK_STATUS(pnpr_tone(NULL, n, 2, &o, t), PNPR_OK);
    CHECK(t[0] < 0.25f && t[1] > t[0] + 0.2f);
}

static void test_bad_options(void)
{
    float t[1];
    const uint8_t rgb[3] = {1, 2, 3};
    pnpr_tone_options o = {0};
    o.source = PNPR_TONE_SOURCE_COUNT_;
    CHECK_STATUS(pnpr_tone(rgb, NULL, 1, &o, t), PNPR_ERR_INVALID_ARGUMENT);
    memset(&o, 0, sizeof o);
    o.gamma = -1;
    CHECK_STATUS(pnpr_tone(rgb, NULL, 1, &o, t), PNPR_ERR_INVALID_ARGUMENT);
    o.gamma = NAN;
    CHECK_STATUS(pnpr_tone(rgb, NULL, 1, &o, t), PNPR_ERR_INVALID_ARGUMENT);
    memset(&o, 0, sizeof o);
    o.ambient = 1.5f;
    CHECK_STATUS(pnpr_tone(rgb, NULL, 1, &o, t), PNPR_ERR_INVALID_ARGUMENT);
    memset(&o, 0, sizeof o);
    o.light[0] = INFINITY;
    CHECK_STATUS(pnpr_tone(rgb, NULL, 1, &o, t), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_tone(rgb, NULL, 1, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_tone(NULL, NULL, 0, NULL, NULL), PNPR_OK); /* nothing to do */
}

int main(void)
{
    test_colour_and_curve();
    test_light();
    test_default_light();
    test_bad_options();
    return pnpr_test_finish("test_tone");
}
