/* pnpr_scene_frame (include/pointnpr/view.h): the up axis of a generated town (ground + boxes)
 * placed z-up, y-up and as an RGB-D camera frame (y down); robust bounds and the outlier count
 * with a far point at 1e9 and 1e308; the view direction (from above, the front or the scanner's
 * side, the wide axis across); user modes, hints, fall-backs and degenerate input. */
#include "testutil.h"
#include "view_scene.h"

#include <pointnpr/view.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double angle_deg(const double a[3], const double b[3])
{
    double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    double c = d / (la * lb);
    return acos(c > 1 ? 1 : (c < -1 ? -1 : c)) * 180.0 / 3.14159265358979323846;
}

static int finite_info(const pnpr_view_info *v)
{
    int ok = 1;
    for (int a = 0; a < 3; a++)
        ok &= isfinite(v->up[a]) && isfinite(v->view_dir[a]) && isfinite(v->lo[a]) && isfinite(v->hi[a]) &&
              isfinite(v->wide_axis[a]);
    return ok && isfinite(v->elevation_deg);
}

/* The town in frame f: up detected from the ground within 2 degrees, from above. */
static void check_town(const char *name, const view_frame *f, pnpr_azimuth_source az)
{
    view_scene s = view_town();
    pnpr_cloud c = {0};
    CHECK_STATUS(view_make(&c, &s, f, 0, 7), PNPR_OK);
    pnpr_view_info v;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    double a = angle_deg(v.up, f->up);
    printf("%s: up (%.4f %.4f %.4f), %.3f deg from the truth (ground normal %.3f deg), ground %.1f%% of the points, "
           "elevation %.1f deg\n", name, v.up[0], v.up[1], v.up[2], a, angle_deg(v.ground_normal, f->up),
           100 * v.ground_fraction, v.elevation_deg);
    CHECK_MSG(a < 2, "%s: up is %.2f degrees off", name, a);
    CHECK(v.up_source == PNPR_UP_FROM_PLANE);
    CHECK(v.has_ground && angle_deg(v.ground_normal, f->up) < 2);
    CHECK(v.ground_fraction > 0.6 && v.ground_fraction < 0.95);
    CHECK(v.outliers == 0);
    CHECK(v.valid == c.count);
    CHECK_MSG(angle_deg(v.view_dir, f->up) < 90 - 25, "%s: view not from above", name);
    /* elevation: up extent ~20 / horizontal ~100 -> between the tall 30 and the flat 55 */
    CHECK(v.elevation_deg > 40 && v.elevation_deg < 50);
    CHECK(v.azimuth_source == az);
    /* robust bounds hold the scene (ground side 100 x scale, tallest box 20) with a small margin */
    double ext = 0;
    for (int k = 0; k < 3; k++) ext = fmax(ext, (double)v.hi[k] - (double)v.lo[k]);
    CHECK_NEAR(ext, 100 * f->scale * 1.02, 0.6 * f->scale);
    CHECK(finite_info(&v));
    pnpr_cloud_free(&c);
}

static void test_up_detection(void)
{
    view_frame z = view_frame_zup(), y = view_frame_yup(), d = view_frame_rgbd(100);
    check_town("z-up town", &z, PNPR_AZIMUTH_FRONT);
    check_town("y-up town", &y, PNPR_AZIMUTH_FRONT);
    check_town("y-down RGB-D town", &d, PNPR_AZIMUTH_ORIGIN);
    /* tilted 25 degrees about x: no axis to snap to, the plane's own normal */
    view_frame t = view_frame_zup();
    double ct = cos(25 * 3.14159265358979323846 / 180), st = sin(25 * 3.14159265358979323846 / 180);
    t.e1[1] = ct; t.e1[2] = st; t.up[1] = -st; t.up[2] = ct;
    check_town("tilted town", &t, PNPR_AZIMUTH_FRONT);

    /* z up, no anisotropy: the legacy front (0,-1,0.5) direction's azimuth */
    view_scene s = view_town();
    pnpr_cloud c = {0};
    CHECK_STATUS(view_make(&c, &s, &z, 0, 7), PNPR_OK);
    pnpr_view_info v;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK_NEAR(v.view_dir[0], 0, 1e-9);
    CHECK(v.view_dir[1] < -0.5);
    /* y up: the front maps to +z (where an OpenGL camera at the origin looks from) */
    CHECK_STATUS(view_make(&c, &s, &y, 0, 7), PNPR_OK);
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.view_dir[2] > 0.5 && fabs(v.view_dir[0]) < 1e-9);
    /* RGB-D: the horizontal part points back to the camera at the origin (-z), above = -y */
    d = view_frame_rgbd(100);
    CHECK_STATUS(view_make(&c, &s, &d, 0, 7), PNPR_OK);
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.view_dir[2] < -0.5 && v.view_dir[1] < -0.5);
    CHECK(v.up[0] == 0 && v.up[1] == -1 && v.up[2] == 0); /* snapped */
    pnpr_cloud_free(&c);
}

static void test_aerial_and_wide(void)
{
    view_scene s = view_aerial();
    view_frame z = view_frame_zup();
    pnpr_cloud c = {0};
    CHECK_STATUS(view_make(&c, &s, &z, 0, 11), PNPR_OK);
    pnpr_view_info v;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    printf("aerial: up (%.4f %.4f %.4f), ground %.1f%%, extents up %.2f across %.1f depth %.1f, elevation %.1f deg\n",
           v.up[0], v.up[1], v.up[2], 100 * v.ground_fraction, v.extent_up, v.extent_across, v.extent_depth, v.elevation_deg);
    CHECK(v.up_source == PNPR_UP_FROM_PLANE && v.up[2] == 1);
    CHECK_NEAR(v.elevation_deg, 55, 1e-9); /* 6 / 200 < 0.05: the flat elevation */
    c.up_hint = 3;                          /* as LAS says */
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.up_source == PNPR_UP_FROM_HINT && v.up[2] == 1);
    pnpr_cloud_free(&c);

    /* a long strip (300 along y, 60 across): the wide axis (+y, sign fixed) runs across the
     * screen, so the view comes from the narrow axis up x wide = -x (the front -y is a tie) */
    view_box none[1] = {{0, 0, 0, 0, 0}};
    view_scene strip = {300, 1, 0.01, 0, none, 0};
    CHECK_STATUS(view_make(&c, &strip, &z, 0, 3), PNPR_OK);
    for (size_t i = 0; i < c.count; i++) c.xyz[3 * i] *= 0.2f; /* 300 x 300 -> 60 x 300 */
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK_NEAR(v.wide_axis[1], 1, 1e-6);
    CHECK_NEAR(v.view_dir[1], 0, 1e-6);
    CHECK(v.view_dir[0] < -0.5);
    pnpr_cloud_free(&c);
}

/* One far point at 1e9 (offset) and one at 1e308 (overflows the float offset; src_xyz keeps it):
 * robust bounds unchanged, the outlier counted. */
static void test_outliers(void)
{
    view_scene s = view_town();
    view_frame z = view_frame_zup();
    pnpr_cloud c = {0};
    CHECK_STATUS(view_make(&c, &s, &z, 0, 7), PNPR_OK);
    pnpr_view_info base, v;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &base), PNPR_OK);
    for (int big = 0; big < 2; big++) {
        pnpr_cloud o = {0};
        CHECK_STATUS(view_make(&o, &s, &z, 1, 7), PNPR_OK);
        size_t last = o.count - 1;
        CHECK_STATUS(pnpr_cloud_alloc_src_xyz(&o), PNPR_OK);
        for (size_t i = 0; i < o.count; i++)
            for (int a = 0; a < 3; a++) o.src_xyz[3 * i + a] = o.origin[a] + o.xyz[3 * i + a];
        double w = big ? 1e308 : 1e9;
        for (int a = 0; a < 3; a++) {
            o.src_xyz[3 * last + a] = w;
            o.xyz[3 * last + a] = (float)(w - o.origin[a]); /* inf for 1e308 */
        }
        CHECK_STATUS(pnpr_scene_frame(&o, NULL, &v), PNPR_OK);
        printf("outlier at %g: %zu outlier(s), valid %zu\n", w, v.outliers, v.valid);
        CHECK(v.outliers == 1);
        CHECK(v.valid == (big ? c.count : c.count + 1));
        for (int a = 0; a < 3; a++) {
            CHECK_NEAR(v.lo[a], base.lo[a], 0.01);
            CHECK_NEAR(v.hi[a], base.hi[a], 0.01);
            CHECK_NEAR(v.up[a], base.up[a], 1e-9);
            CHECK_NEAR(v.view_dir[a], base.view_dir[a], 1e-6);
        }
        pnpr_cloud_free(&o);
    }
    /* a few strays just outside (a bird 30 above the town) are outside the robust bounds but not
     * far outliers */
    pnpr_cloud b = {0};
    CHECK_STATUS(view_make(&b, &s, &z, 1, 7), PNPR_OK);
    b.xyz[3 * (b.count - 1) + 2] = 70;
    CHECK_STATUS(pnpr_scene_frame(&b, NULL, &v), PNPR_OK);
    CHECK(v.outliers == 0 && v.hi[2] < 65);
    pnpr_cloud_free(&b);
    pnpr_cloud_free(&c);
}

static void test_modes_and_hints(void)
{
    view_scene s = view_town();
    view_frame z = view_frame_zup();
    pnpr_cloud c = {0};
    CHECK_STATUS(view_make(&c, &s, &z, 0, 7), PNPR_OK);
    pnpr_view_options o = {0};
    pnpr_view_info v;
    o.up_mode = PNPR_UP_POS_Y;
    CHECK_STATUS(pnpr_scene_frame(&c, &o, &v), PNPR_OK);
    CHECK(v.up_source == PNPR_UP_FROM_USER && v.up[0] == 0 && v.up[1] == 1 && v.up[2] == 0);
    CHECK(v.view_dir[1] > 0.4); /* from above along +y */
    CHECK(v.has_ground && v.ground_normal[2] > 0.99); /* the ground is still reported */
    o.up_mode = PNPR_UP_NEG_X;
    CHECK_STATUS(pnpr_scene_frame(&c, &o, &v), PNPR_OK);
    CHECK(v.up[0] == -1 && v.up_source == PNPR_UP_FROM_USER);
    o.up_mode = PNPR_UP_VECTOR;
    o.up[0] = 3; o.up[1] = 4; o.up[2] = 0;
    CHECK_STATUS(pnpr_scene_frame(&c, &o, &v), PNPR_OK);
    CHECK_NEAR(v.up[0], 0.6, 1e-12);
    CHECK_NEAR(v.up[1], 0.8, 1e-12);
    o.up[0] = o.up[1] = 0;
    CHECK_STATUS(pnpr_scene_frame(&c, &o, &v), PNPR_ERR_INVALID_ARGUMENT);
    o.up[2] = NAN;
    CHECK_STATUS(pnpr_scene_frame(&c, &o, &v), PNPR_ERR_INVALID_ARGUMENT);
    o.up_mode = PNPR_UP_MODE_COUNT_;
    CHECK_STATUS(pnpr_scene_frame(&c, &o, &v), PNPR_ERR_INVALID_ARGUMENT);
    o.up_mode = (pnpr_up_mode)-1;
    CHECK_STATUS(pnpr_scene_frame(&c, &o, &v), PNPR_ERR_INVALID_ARGUMENT);
    /* a format hint wins over the plane in AUTO */
    c.up_hint = 2;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.up_source == PNPR_UP_FROM_HINT && v.up[1] == 1);
    c.up_hint = -3;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.up_source == PNPR_UP_FROM_HINT && v.up[2] == -1);
    c.up_hint = 7; /* not a hint: ignored */
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.up_source == PNPR_UP_FROM_PLANE && v.up[2] == 1);
    c.up_hint = 0;
    /* a stored viewpoint sets the azimuth: scanner at +x of the town, 2 m high */
    c.has_viewpoint = 1;
    c.viewpoint[0] = z.at[0] + 80; c.viewpoint[1] = z.at[1]; c.viewpoint[2] = z.at[2] + 2;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.azimuth_source == PNPR_AZIMUTH_VIEWPOINT && v.view_dir[0] > 0.5 && fabs(v.view_dir[1]) < 0.05);
    /* deterministic */
    pnpr_view_info v2;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v2), PNPR_OK);
    CHECK(memcmp(&v, &v2, sizeof v) == 0);
    pnpr_cloud_free(&c);

    /* no ground (a sphere): +z by default */
    double off[3] = {1e7, -1e7, 1e7};
    CHECK_STATUS(pnpr_test_sphere(&c, 20000, 3, off, 5), PNPR_OK);
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.up_source == PNPR_UP_FROM_DEFAULT && v.up[2] == 1 && !v.has_ground);
    CHECK_NEAR(v.elevation_deg, 30, 1e-9); /* as tall as wide */
    pnpr_cloud_free(&c);

    pnpr_up_mode m = PNPR_UP_AUTO;
    CHECK(pnpr_up_mode_parse("y", &m) && m == PNPR_UP_POS_Y);
    CHECK(pnpr_up_mode_parse("+z", &m) && m == PNPR_UP_POS_Z);
    CHECK(pnpr_up_mode_parse("-x", &m) && m == PNPR_UP_NEG_X);
    CHECK(pnpr_up_mode_parse("auto", &m) && m == PNPR_UP_AUTO);
    CHECK(!pnpr_up_mode_parse("w", &m) && !pnpr_up_mode_parse("", &m) && !pnpr_up_mode_parse("++x", &m) &&
          !pnpr_up_mode_parse("+", &m) && !pnpr_up_mode_parse("0,1,0", &m) && !pnpr_up_mode_parse(NULL, &m));
}

static size_t push(pnpr_cloud *c, size_t n, double x, double y, double z)
{
    c->xyz[3 * n] = (float)x; c->xyz[3 * n + 1] = (float)y; c->xyz[3 * n + 2] = (float)z;
    return n + 1;
}

/* RGB-D frames in camera coordinates (y down, z forward, the camera at the origin). */
static void test_indoor(void)
{
    pnpr_cloud c = {0};
    pnpr_view_info v;
    double down[3] = {0, -1, 0}, towards[3] = {0, 0, -1};
    /* a wall 3 x 2.2 at z = 4 sampled twice as densely as the floor (3 x 3 at y = 1.2) under it,
     * a table top 0.8 x 0.8 at y = 0.5: the wall is the largest plane, all content on one side of
     * it, but it faces the camera, so the floor under it wins */
    CHECK_STATUS(pnpr_cloud_alloc(&c, 40000), PNPR_OK);
    size_t n = 0;
    for (int i = 0; i <= 75; i++) for (int k = 0; k <= 75; k++) n = push(&c, n, -1.5 + 0.04 * i, 1.2, 1 + 0.04 * k);
    for (int i = 0; i <= 150; i++) for (int j = 0; j <= 110; j++) n = push(&c, n, -1.5 + 0.02 * i, -1 + 0.02 * j, 4);
    for (int i = 0; i <= 40; i++) for (int k = 0; k <= 40; k++) n = push(&c, n, -0.4 + 0.02 * i, 0.5, 2 + 0.02 * k);
    c.count = n;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    printf("wall-dominated RGB-D frame: up (%.4f %.4f %.4f), floor %.1f%% of the points\n", v.up[0], v.up[1], v.up[2],
           100 * v.ground_fraction);
    CHECK(angle_deg(v.up, down) < 2 && v.up_source == PNPR_UP_FROM_PLANE);
    CHECK(v.ground_fraction > 0.2 && v.ground_fraction < 0.3);
    /* a table top 1 x 0.6 seen from above (z = 0.8) with two boxes on it: it faces the camera,
     * nothing better is there, it stays the ground: up towards the camera */
    n = 0;
    for (int i = 0; i <= 100; i++) for (int j = 0; j <= 60; j++) n = push(&c, n, -0.5 + 0.01 * i, -0.3 + 0.01 * j, 0.8);
    for (int b = 0; b < 2; b++) {
        double x0 = b ? 0.1 : -0.35, y0 = b ? -0.2 : 0.05;
        for (int i = 0; i <= 15; i++)
            for (int j = 0; j <= 15; j++) {
                n = push(&c, n, x0 + 0.01 * i, y0 + 0.01 * j, 0.65);          /* top */
                n = push(&c, n, x0 + 0.01 * i, y0, 0.65 + 0.01 * j);         /* two sides */
                n = push(&c, n, x0, y0 + 0.01 * i, 0.65 + 0.01 * j);
            }
    }
    c.count = n;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    printf("table top seen from above: up (%.4f %.4f %.4f), table %.1f%% of the points\n", v.up[0], v.up[1], v.up[2],
           100 * v.ground_fraction);
    CHECK(angle_deg(v.up, towards) < 2 && v.up_source == PNPR_UP_FROM_PLANE);
    pnpr_cloud_free(&c);
}

static void test_degenerate(void)
{
    pnpr_cloud c = {0};
    pnpr_view_info v;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_ERR_EMPTY);
    CHECK_STATUS(pnpr_scene_frame(NULL, NULL, &v), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_cloud_alloc(&c, 5), PNPR_OK);
    for (size_t i = 0; i < 15; i++) c.xyz[i] = (i % 2) ? NAN : INFINITY;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_ERR_EMPTY);
    /* one finite point among NaNs, far from the world origin */
    c.origin[0] = 1e7; c.origin[1] = -1e7; c.origin[2] = 1e7;
    c.xyz[6] = 1; c.xyz[7] = 2; c.xyz[8] = 3;
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.valid == 1 && v.outliers == 0 && finite_info(&v));
    CHECK(v.lo[0] == 1 && v.hi[0] == 1 && v.up[2] == 1 && v.up_source == PNPR_UP_FROM_DEFAULT);
    CHECK(v.view_dir[2] > 0.4);
    /* all duplicates */
    for (size_t i = 0; i < 15; i++) c.xyz[i] = (float)(i % 3);
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.valid == 5 && v.outliers == 0 && finite_info(&v) && v.up_source == PNPR_UP_FROM_DEFAULT);
    /* collinear (a line along x): no plane, +z */
    CHECK_STATUS(pnpr_cloud_alloc(&c, 1000), PNPR_OK);
    for (size_t i = 0; i < 1000; i++) { c.xyz[3 * i] = (float)i * 0.01f; c.xyz[3 * i + 1] = 2; c.xyz[3 * i + 2] = -1; }
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(finite_info(&v) && v.up_source == PNPR_UP_FROM_DEFAULT && !v.has_ground);
    CHECK_NEAR(v.wide_axis[0] * v.wide_axis[0], 1, 1e-9);
    CHECK_NEAR(v.view_dir[0], 0, 1e-9); /* the line runs across the screen */
    /* a single plane without anything on it (flat, no side information): up +z by the prior */
    for (size_t i = 0; i < 1000; i++) { c.xyz[3 * i] = (float)(i % 40); c.xyz[3 * i + 1] = (float)(i / 40); c.xyz[3 * i + 2] = 0; }
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.up_source == PNPR_UP_FROM_PLANE && v.up[2] == 1 && v.ground_fraction == 1);
    /* the same plane seen by a stored scanner below it: up -z */
    c.has_viewpoint = 1;
    c.viewpoint[0] = 20; c.viewpoint[1] = 12; c.viewpoint[2] = -5; /* (the origin is 0 again) */
    CHECK_STATUS(pnpr_scene_frame(&c, NULL, &v), PNPR_OK);
    CHECK(v.up[2] == -1);
    /* a tiny sample budget still works */
    pnpr_view_options o = {0};
    o.max_samples = 2;
    CHECK_STATUS(pnpr_scene_frame(&c, &o, &v), PNPR_OK);
    CHECK(finite_info(&v));
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_up_detection();
    test_aerial_and_wide();
    test_outliers();
    test_modes_and_hints();
    test_indoor();
    test_degenerate();
    return pnpr_test_finish("test_view");
}
