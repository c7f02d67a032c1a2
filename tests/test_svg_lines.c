/* SVG line drawings: a cube's profile lines seen from a corner, rendered by rsvg-convert; the
 * three edges hidden behind the cube must be absent, the front edges present; with hidden parts
 * kept, the back edges appear. Bad arguments get exact error codes. The rendered drawings are
 * read back with libpng: without it (PNPR_TEST_HAVE_PNG unset) the test is skipped (77). */
#include "testutil.h"
#include "../view/view_internal.h"

#include <pointnpr/camera.h>
#include <pointnpr/features.h>
#include <pointnpr/lines.h>

#include <math.h>
#ifdef PNPR_TEST_HAVE_PNG
#include "png_read.h"
#endif
#include <stdlib.h>
#include <string.h>

#define W 400
#define H 400

/* Reads an 8-bit RGB(A) PNG into grey values; 0 on failure. */
static int read_grey(const char *path, unsigned char *grey)
{
#ifdef PNPR_TEST_HAVE_PNG
    return pnpr_test_read_png(path, W, H, PNG_FORMAT_GRAY, grey);
#else
    (void)path; (void)grey;
    return 0;
#endif
}

/* Darkest pixel within r px of (x, y). */
static int darkest_near(const unsigned char *g, double x, double y, int r)
{
    int best = 255;
    for (int dy = -r; dy <= r; dy++)
        for (int dx = -r; dx <= r; dx++) {
            int px = (int)floor(x) + dx, py = (int)floor(y) + dy;
            if (px < 0 || py < 0 || px >= W || py >= H) continue;
            if (g[py * W + px] < best) best = g[py * W + px];
        }
    return best;
}

static void project(const pnpr_frame_camera *fc, const double p[3], double *x, double *y)
{
    const float *V = fc->view, *P = fc->proj;
    double v[4], c[4];
    for (int r = 0; r < 4; r++) v[r] = V[r] * p[0] + V[4 + r] * p[1] + V[8 + r] * p[2] + V[12 + r];
    for (int r = 0; r < 4; r++) c[r] = P[r] * v[0] + P[4 + r] * v[1] + P[8 + r] * v[2] + P[12 + r] * v[3];
    *x = (c[0] / c[3] + 1) * 0.5 * W;
    *y = (1 - c[1] / c[3]) * 0.5 * H;
}

int main(void)
{
#ifndef PNPR_TEST_HAVE_PNG
    fprintf(stderr, "test_svg_lines: skipped: built without libpng, which reads the rendered drawings back\n");
    return 77;
#endif
    if (system("rsvg-convert --version > /dev/null 2>&1") != 0) {
        fprintf(stderr, "test_svg_lines: rsvg-convert is missing (packaging/deps/lines.txt installs it)\n");
        return 1;
    }
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_cube(&c, 1.0, 0.02, 0.0, NULL, 3), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    pnpr_polylines l = {0};
    CHECK_STATUS(pnpr_profile_lines(&c, NULL, &l, NULL), PNPR_OK);
    CHECK(l.count >= 12);

    pnpr_camera cam = {{2.6, -1.7, 2.1}, {0.5, 0.5, 0.5}, {0, 0, 1}, 40, 0, 0};
    pnpr_svg_options so = {0};
    so.width = W; so.height = H; so.stroke_width = 3; so.occluders = &c;
    so.background = 1; so.background_rgb[0] = so.background_rgb[1] = so.background_rgb[2] = 255;
    char svg[512], png[512], cmd[1400];
    snprintf(svg, sizeof svg, "%s/svg_cube.svg", PNPR_TEST_SCRATCH);
    snprintf(png, sizeof png, "%s/svg_cube.png", PNPR_TEST_SCRATCH);
    pnpr_error err = {0};
    static unsigned char g[W * H];

    /* the camera's projection, for the expected positions (bounds as the writer computes them) */
    pnpr_frame_camera fc;
    float lo[3], hi[3];
    pnpr_cloud_bounds(&c, lo, hi);
    CHECK_STATUS(pnpr_frame_camera_make(&cam, l.origin, lo, hi, 1, W, H, &fc, &err), PNPR_OK);
    /* edge midpoints in offset coordinates: front (on a visible face) and hidden */
    const double front[3][3] = {{1, 0, 0.5}, {0.5, 0, 1}, {1, 0.5, 1}};
    const double hidden[3][3] = {{0, 1, 0.5}, {0.5, 1, 0}, {0, 0.5, 0}};

    for (int show = 0; show < 2; show++) {
        so.occluders = show ? NULL : &c;
        CHECK_STATUS(pnpr_write_lines_svg(svg, &l, &cam, &so, &err), PNPR_OK);
        snprintf(cmd, sizeof cmd, "rsvg-convert '%s' -o '%s'", svg, png);
        CHECK(system(cmd) == 0);
        CHECK(read_grey(png, g));
        for (int e = 0; e < 3; e++) {
            double x, y, p[3];
            for (int k = 0; k < 3; k++) p[k] = front[e][k] - l.origin[k];
            project(&fc, p, &x, &y);
            int d = darkest_near(g, x, y, 3);
            fprintf(stderr, "%s: front edge %d at (%.0f,%.0f): darkest %d\n", show ? "hidden kept" : "hidden removed", e, x, y, d);
            CHECK(d < 100);
            for (int k = 0; k < 3; k++) p[k] = hidden[e][k] - l.origin[k];
            project(&fc, p, &x, &y);
            d = darkest_near(g, x, y, 3);
            fprintf(stderr, "%s: hidden edge %d at (%.0f,%.0f): darkest %d\n", show ? "hidden kept" : "hidden removed", e, x, y, d);
            if (show) CHECK(d < 100);
            else CHECK(d > 200);
        }
    }
    /* tapered strokes are filled outlines and still render */
    so.occluders = &c;
    so.taper = 0.3f;
    CHECK_STATUS(pnpr_write_lines_svg(svg, &l, &cam, &so, &err), PNPR_OK);
    snprintf(cmd, sizeof cmd, "rsvg-convert '%s' -o '%s'", svg, png);
    CHECK(system(cmd) == 0);
    /* bad arguments */
    so.width = -5;
    CHECK_STATUS(pnpr_write_lines_svg(svg, &l, &cam, &so, &err), PNPR_ERR_INVALID_ARGUMENT);
    so.width = W; so.taper = NAN;
    CHECK_STATUS(pnpr_write_lines_svg(svg, &l, &cam, &so, &err), PNPR_ERR_INVALID_ARGUMENT);
    so.taper = 0;
    pnpr_camera bad = cam;
    bad.eye[0] = NAN;
    CHECK_STATUS(pnpr_write_lines_svg(svg, &l, &bad, &so, &err), PNPR_ERR_NUMERIC);
    CHECK_STATUS(pnpr_write_lines_svg("/nonexistent-dir/x.svg", &l, &cam, &so, &err), PNPR_ERR_IO);
    /* no lines and no occluders, no camera: nothing to frame */
    pnpr_polylines none = {0};
    so.occluders = NULL;
    CHECK_STATUS(pnpr_write_lines_svg(svg, &none, NULL, &so, &err), PNPR_ERR_EMPTY);
    /* no lines with a camera: a valid empty drawing */
    CHECK_STATUS(pnpr_write_lines_svg(svg, &none, &cam, &so, &err), PNPR_OK);
    pnpr_lines_free(&l);
    pnpr_cloud_free(&c);
    return pnpr_test_finish("test_svg_lines");
}
