/* The default screen-space budget (pnpr_draw_options.density 0 = the table's 2 points per covered
 * pixel; docs/rendering.md, "Continuous resolution queue"). A dense view no longer drowns in ink:
 * a rough mid-grey plane of 40 000 points seen small (about 44 points per covered pixel) is drawn in
 * sketchy and stipple, and the mean darkness of the pixels the plane covers is measured
 * (covered = not the background in the `points` frame):
 *   - under the default it is below 0.5 (issue 15's first-sight bound), and more than 4x lighter
 *     than with every point (density negative; measured sketchy 0.051 vs 0.536, stipple 0.090 vs
 *     0.696);
 *   - under the default the darkness stays within 25% of that of the same plane seen four times
 *     larger (the screen density holds when zooming; measured 0.051 and 0.049), where drawing every
 *     point changes it by far more (0.536 and 0.222);
 *   - the points drawn are ceil(2 x the covered pixels of the box) within 2% (the per-cell
 *     queues round each cell's share: crq.h);
 *   - with part of the cloud out of view, the points in view keep that count and the others are
 *     not drawn (test_in_view);
 *   - surfaces near and far keep their points per pixel: the cells' shares go as 1 / depth^2
 *     (test_depth, a known answer).
 * Exits 77 (skipped) when this machine has no headless EGL / GL 3.3. */
#include "testutil.h"
#include "../../render/renderer_internal.h" /* the frame's table of the per-cell queues (test_depth) */

#include <pointnpr/features.h>
#include <pointnpr/render.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 160, H = 120, N = 200 };
#ifndef NOISE
#define NOISE 0.02
#endif

static const double plane_off[3] = {500000.25, -300000.5, 120.0};

/* Mean darkness (0 = background white, 1 = black) over the pixels `cover` marks; frame and cover
 * are W x H RGBA. */
static double darkness(const uint8_t *frame, const uint8_t *cover, size_t *r_covered)
{
    double s = 0;
    size_t n = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        const uint8_t *c = cover + 4 * i, *p = frame + 4 * i;
        if (c[0] == 255 && c[1] == 255 && c[2] == 255) continue;
        s += 1.0 - (p[0] + p[1] + p[2]) / (3.0 * 255.0);
        n++;
    }
    *r_covered = n;
    return n ? s / (double)n : 0;
}

static void draw(pnpr_renderer *r, const pnpr_camera *cam, pnpr_style style, float density, uint8_t *px,
                 pnpr_render_stats *st)
{
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = style;
    o.density = density;
    o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_snapshot(r, cam, &o, W, H, NULL, px, st, &err), PNPR_OK);
}

/* The plane from above at distance `dist`: darkness of `style` under the default and with every
 * point, into r_dark[0] and r_dark[1]. */
static void measure(pnpr_renderer *r, const pnpr_cloud *c, double dist, pnpr_style style, uint8_t *px[2],
                    double r_dark[2])
{
    pnpr_camera cam = {{0}, {0}, {0, 1, 0}, 30, 0, 0};
    for (int a = 0; a < 3; a++) cam.target[a] = c->origin[a] + 0.5;
    cam.target[2] = c->origin[2];
    memcpy(cam.eye, cam.target, sizeof cam.eye);
    cam.eye[2] += dist;
    pnpr_render_stats st;
    draw(r, &cam, PNPR_STYLE_POINTS, -1, px[0], &st);
    size_t covered = 0;
    for (int all = 0; all < 2; all++) {
        draw(r, &cam, style, all ? -1.0f : 0.0f, px[1], &st);
        r_dark[all] = darkness(px[1], px[0], &covered);
        size_t want = all ? c->count : (size_t)ceil(2.0 * st.coverage_px);
        if (want > c->count) want = c->count;
        CHECK_MSG(fabs((double)st.points_drawn - (double)want) <= 0.02 * (double)want, "%s at %g: %zu points drawn, expected %zu (box %g px)",
                  pnpr_style_name(style), dist, st.points_drawn, want, st.coverage_px);
    }
    printf("  %-8s distance %.1f: %zu px covered, darkness %.3f under the default, %.3f with every point\n",
           pnpr_style_name(style), dist, covered, r_dark[0], r_dark[1]);
}

/* The density holds among the points in view: two 100 x 100 planes 100 apart, the camera over the
 * first; the second is out of view and none of its points is drawn, so the first keeps
 * ceil(D x covered px) (within 2%; when the queue was one uniform prefix of both, the first got
 * half of that). */
static void test_in_view(pnpr_renderer *r, uint8_t *px)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_plane(&c, 200, 100, 0.01, plane_off), PNPR_OK);
    for (size_t i = 0; i < c.count; i++)
        if (i % 200 >= 100) { /* the second plane: 100 further in x */
            c.xyz[3 * i] += 100.0f;
            if (c.src_xyz) c.src_xyz[3 * i] += 100.0;
        }
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    pnpr_camera cam = {{0}, {0}, {0, 1, 0}, 30, 0, 0};
    for (int a = 0; a < 3; a++) cam.target[a] = c.origin[a] + (a < 2 ? 0.5 : 0);
    memcpy(cam.eye, cam.target, sizeof cam.eye);
    cam.eye[2] += 2;
    pnpr_render_stats st;
    draw(r, &cam, PNPR_STYLE_POINTS, 0.1f, px, &st);
    const double d = 0.1f; /* as the renderer has it */
    double want = ceil(d * st.coverage_px);
    CHECK_MSG(fabs((double)st.points_drawn - want) <= 0.02 * want && want < 10000, "in view: %zu points drawn, expected %.0f (box %g px)",
              st.points_drawn, want, st.coverage_px);
    /* both planes in view (from far above both): the prefix is the density's alone */
    for (int a = 0; a < 3; a++) cam.target[a] = c.origin[a] + (a == 0 ? 50.5 : a == 1 ? 0.5 : 0);
    memcpy(cam.eye, cam.target, sizeof cam.eye);
    cam.eye[2] += 400;
    draw(r, &cam, PNPR_STYLE_POINTS, 0.1f, px, &st);
    want = ceil(d * st.coverage_px);
    CHECK_MSG(fabs((double)st.points_drawn - want) <= 0.02 * want, "all in view: %zu points drawn, expected %.0f (box %g px)",
              st.points_drawn, want, st.coverage_px);
    pnpr_cloud_free(&c);
}

/* Near and far keep their points per pixel (a known answer, read off the frame's table of the
 * per-cell queues): two 1 x 1 planes of 100 x 100 points seen from straight above (fov 60), the
 * near one at height 2, the far one at 0 and 1.5 further in x. The grid of cells (crq.h,
 * view/view_cells.c): the smallest cubes with at most 32 768 of them over the box's 2.5 x 1 x 2
 * are 2.5 / 46 = 0.0543 a side (46 x 19 x 37 = 32 338 cells; the next smaller side needs 46 x
 * 19 x 38 = 33 212); the
 * near plane's cells (the top layer) reach up to 37 x 0.0543 = 2.0109, the far one's to 0.0543,
 * so from an eye at height 4 their nearest corners lie 1.9891 and 3.9457 deep, and each cell
 * draws min(1, c / depth^2) of its points:
 *   - 5 000 points wanted: every near cell draws (3.9457 / 1.9891)^2 = 3.935 times the share
 *     of every far cell, and 5 000 in all: 0.3987 and 0.1013;
 *   - 15 000 wanted: the near cells are full (share 1) and the far ones draw the rest, 0.5;
 *   - and a budget of 6 000 (it caps the vertices sent): every cell 0.3.
 * One share for every cell (the queue before) would give 0.25 and 0.75 everywhere. */
static void test_depth(pnpr_renderer *r, uint8_t *px)
{
    enum { SIDE = 100, PLANE = SIDE * SIDE };
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&c, 2 * PLANE), PNPR_OK);
    if (!c.xyz) return;
    c.origin[0] = 1000; c.origin[1] = 2000;
    for (size_t i = 0; i < 2 * PLANE; i++) {
        size_t k = i % PLANE;
        int far = i >= PLANE;
        c.xyz[3 * i] = (float)(k % SIDE) / (SIDE - 1) + (far ? 1.5f : 0.0f);
        c.xyz[3 * i + 1] = (float)(k / SIDE) / (SIDE - 1);
        c.xyz[3 * i + 2] = far ? 0.0f : 2.0f;
    }
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    pnpr_camera cam = {{1001.25, 2000.5, 4}, {1001.25, 2000.5, 0}, {0, 1, 0}, 60, 0, 0};
    pnpr_render_stats st;
    draw(r, &cam, PNPR_STYLE_POINTS, 1.0f, px, &st);
    const pnpr_view_cells *vc = &r->view_cells;
    CHECK_MSG(vc->n[0] == 46 && vc->n[1] == 19 && vc->n[2] == 37 && fabs(vc->cell - 2.5 / 46) < 1e-6,
              "grid %u x %u x %u of side %.9g", vc->n[0], vc->n[1], vc->n[2], (double)vc->cell);
    const double near_depth = 4.0 - 37.0 * vc->cell, far_depth = 4.0 - vc->cell; /* the side to float precision */
    const double ratio = (far_depth / near_depth) * (far_depth / near_depth);
    const double wants[2] = {5000, 15000};
    for (int t = 0; t < 2; t++) {
        float d = (float)(wants[t] / st.coverage_px);
        draw(r, &cam, PNPR_STYLE_POINTS, d, px, &st);
        double want = ceil((double)d * st.coverage_px);
        double near_want = t == 0 ? want * ratio / (PLANE * (ratio + 1)) : 1, far_want = t == 0 ? near_want / ratio : (want - PLANE) / PLANE;
        /* every cell with points: its share (end / keys), by plane (layer 36 near, 0 far) */
        double lo[2] = {2, 2}, hi[2] = {-1, -1};
        size_t counted[2] = {0, 0};
        for (size_t k = 0; k < r->cells; k++) {
            if (!vc->count[k]) continue;
            int layer = (int)(k / ((size_t)vc->n[0] * vc->n[1])), near = layer == 36;
            CHECK(layer == 36 || layer == 0);
            double share = r->cell_table[4 * k] / PNPR_CRQ_KEYS;
            lo[near] = fmin(lo[near], share);
            hi[near] = fmax(hi[near], share);
            counted[near] += vc->count[k];
        }
        printf("near and far planes, %.0f wanted: near cells' share %.4f..%.4f (expected %.4f), far %.4f..%.4f (%.4f); %zu drawn\n",
               want, lo[1], hi[1], near_want, lo[0], hi[0], far_want, st.points_drawn);
        CHECK(counted[0] == PLANE && counted[1] == PLANE);
        CHECK_MSG(fabs(lo[1] - near_want) < 1e-4 && fabs(hi[1] - near_want) < 1e-4 && fabs(lo[0] - far_want) < 1e-4 &&
                      fabs(hi[0] - far_want) < 1e-4,
                  "%.0f wanted: near %.5f..%.5f, expected %.5f; far %.5f..%.5f, expected %.5f", want, lo[1], hi[1], near_want,
                  lo[0], hi[0], far_want);
        CHECK_MSG(fabs((double)st.points_drawn - want) <= 0.02 * want, "%.0f wanted, %zu drawn", want, st.points_drawn);
    }
    /* a budget caps the vertices sent, the groups' prefixes up to the largest end: 6 000 of the
     * 15 000 wanted cuts every cell to one end, 0.3 of its points (the near ones would send all) */
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.density = (float)(15000.0 / st.coverage_px);
    o.budget = 6000;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_renderer_snapshot(r, &cam, &o, W, H, NULL, px, &st, &err), PNPR_OK);
    float end_max = 0, end_min = PNPR_CRQ_KEYS;
    for (size_t k = 0; k < r->cells; k++)
        if (r->view_cells.count[k]) {
            end_max = fmaxf(end_max, r->cell_table[4 * k]);
            end_min = fminf(end_min, r->cell_table[4 * k]);
        }
    size_t sent = 0;
    for (size_t g = 0; g <= r->group_count; g++) sent += pnpr_crq_cells_prefix(&r->queue, g, end_max);
    CHECK_MSG(sent <= 6000 && sent > 5990 && st.points_drawn == sent && end_min == end_max &&
                  fabs(end_max / PNPR_CRQ_KEYS - 0.3) < 1e-3,
              "budget 6000: %zu sent, %zu drawn, ends %.1f..%.1f", sent, st.points_drawn, (double)end_min, (double)end_max);
    /* 50 points wanted: every cell draws 1/400 of its points or less, and its disks would grow 20
     * times or more; a disk grows at most to a cell's side, so the largest growth the frame plans
     * for (the guard bands) is the side over the largest radius */
    o.budget = 0;
    o.density = (float)(50.0 / st.coverage_px);
    frame_plan plan;
    CHECK_STATUS(pnpr_renderer_plan_frame(r, &cam, &o, W, H, &plan, &err), PNPR_OK);
    float grow_max = 0;
    for (size_t k = 0; k < r->cells; k++)
        if (r->view_cells.count[k] && r->cell_table[4 * k] > 0.5f) grow_max = fmaxf(grow_max, r->cell_table[4 * k + 2]);
    double cap = fmax(1.0, (double)vc->cell / r->max_radius);
    CHECK_MSG(grow_max > 20 && cap < grow_max && fabs(plan.lod_max - cap) < 1e-5 * cap,
              "50 wanted: growth up to %.1f, planned %.3f, the cell's side over the largest radius %.3f", (double)grow_max,
              (double)plan.lod_max, cap);
    pnpr_cloud_free(&c);
}

int main(void)
{
    pnpr_error err = {0};
    pnpr_gl_context *ctx = NULL;
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_density: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    /* a 1 x 1 plane of N x N points (spacing 0.005), mid grey, with scanner noise of 0.4 spacings
     * (sigma 0.002): most points are directional, as on a real scan's rough surfaces */
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_plane(&c, N, N, 1.0 / (N - 1), plane_off), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    memset(c.rgb, 110, 3 * c.count);
    pnpr_test_rng rng = {7};
    for (size_t i = 0; i < c.count; i++) c.xyz[3 * i + 2] += (float)(0.002 * pnpr_test_normal(&rng));
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    uint8_t *px[2] = {malloc((size_t)W * H * 4), malloc((size_t)W * H * 4)};
    if (r && px[0] && px[1]) {
        printf("a mid-grey plane of %zu points from above, %dx%d:\n", c.count, W, H);
        const pnpr_style styles[2] = {PNPR_STYLE_SKETCHY, PNPR_STYLE_STIPPLE};
        for (int s = 0; s < 2; s++) {
            double far[2], near[2];
            measure(r, &c, 7.5, styles[s], px, far);  /* about 30 x 30 px */
            measure(r, &c, 3.75, styles[s], px, near); /* about 60 x 60 px */
            const char *name = pnpr_style_name(styles[s]);
            CHECK_MSG(far[0] < 0.5, "%s: the default drawn small is a dark mass (%.3f)", name, far[0]);
            CHECK_MSG(far[1] > 4 * far[0], "%s: every point drawn small (%.3f) is not much darker than the default (%.3f)",
                      name, far[1], far[0]);
            CHECK_MSG(fabs(far[0] - near[0]) < 0.25 * near[0], "%s: darkness %.3f small, %.3f four times larger", name,
                      far[0], near[0]);
            CHECK_MSG(far[1] - near[1] > 2 * fabs(far[0] - near[0]),
                      "%s: every point changes by %.3f when zooming, the default by %.3f", name, far[1] - near[1],
                      fabs(far[0] - near[0]));
        }
    }
    if (r && px[0]) test_in_view(r, px[0]);
    if (r && px[0]) test_depth(r, px[0]);
    free(px[0]);
    free(px[1]);
    pnpr_cloud_free(&c);
    pnpr_renderer_destroy(r);
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_density");
}
