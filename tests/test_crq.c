/* Continuous resolution queue (no GL): the order is a permutation grouped by class and shuffled
 * inside each group, the same for the same seed, different for another seed; the per-group split
 * of a frame's budget is exact; the per-cell queues (test_cells) against brute force. */
#include "testutil.h"

#include <math.h>

#include <pointnpr/crq.h>
#include "../view/view_internal.h" /* the cells' shares (test_solve) */

#include <stdlib.h>
#include <string.h>

static int is_permutation(const uint32_t *o, size_t n)
{
    char *seen = calloc(n ? n : 1, 1);
    int ok = seen != NULL;
    for (size_t i = 0; ok && i < n; i++) {
        if (o[i] >= n || seen[o[i]]) ok = 0;
        else seen[o[i]] = 1;
    }
    free(seen);
    return ok;
}

/* The view's sample against known answers: a camera at the origin looking down +x (fov 90, a
 * square image: the cone's half-angle atan(1.15 x sqrt 2)), 1000 points at depth 10 and 1000 at
 * depth 100 on the axis, 500 behind the eye, 500 beside it out of the cone. Asking 1100 points:
 * c / 10^2 >= 1, so 1000 + 1000 c / 100^2 = 1100, c = 1000: share 1 at depth 10, 0.1 at 100
 * (exact: no bin holds depths on both sides of where the share reaches 1). */
static void test_view_sample(void)
{
    static pnpr_view_sample v; /* 48 KiB of histogram */
    const double eye[3] = {0, 0, 0}, target[3] = {1, 0, 0};
    CHECK_STATUS(pnpr_view_sample_init(&v, eye, target, 90, 100, 100), PNPR_OK);
    const double near[3] = {10, 0.5, 0}, far[3] = {100, -3, 2}, behind[3] = {-5, 0, 0}, beside[3] = {1, 2, 0};
    const double edge_in[3] = {10, 16.2, 0}, edge_out[3] = {10, 16.4, 0}; /* tan 1.15 sqrt 2 = 1.626 */
    const double nan[3] = {NAN, 0, 0}, inf[3] = {INFINITY, 0, 0};
    for (int i = 0; i < 1000; i++) {
        pnpr_view_sample_add(&v, near);
        pnpr_view_sample_add(&v, far);
    }
    for (int i = 0; i < 500; i++) {
        pnpr_view_sample_add(&v, behind);
        pnpr_view_sample_add(&v, beside);
    }
    pnpr_view_sample_add(&v, nan);
    pnpr_view_sample_add(&v, inf);
    CHECK_MSG(v.least.visible == 2000, "%llu points in view", (unsigned long long)v.least.visible);
    CHECK(pnpr_view_sample_depth(&v, near) == 10 && pnpr_view_sample_depth(&v, behind) == 0 &&
          pnpr_view_sample_depth(&v, beside) == 0 && pnpr_view_sample_depth(&v, nan) == 0);
    CHECK(pnpr_view_sample_depth(&v, edge_in) == 10 && pnpr_view_sample_depth(&v, edge_out) == 0);
    pnpr_view_sample_solve(&v, 1100, 0);
    double s_near = pnpr_view_sample_share(&v, near), s_far = pnpr_view_sample_share(&v, far);
    CHECK_MSG(s_near == 1 && fabs(s_far - 0.1) < 1e-9 && fabs(v.c - 1000) < 1e-6, "shares %g %g, c %g", s_near, s_far, v.c);
    CHECK(pnpr_view_sample_share(&v, behind) == 0 && pnpr_view_sample_share(&v, beside) == 0);
    /* asking for more than is in view: every point in view, whole */
    pnpr_view_sample_solve(&v, 2000, 0);
    CHECK(pnpr_view_sample_share(&v, far) == 1 && pnpr_view_sample_share(&v, behind) == 0);
    /* a far-only scene: asking a tenth gives every point a tenth */
    CHECK_STATUS(pnpr_view_sample_init(&v, eye, target, 90, 100, 100), PNPR_OK);
    for (int i = 0; i < 1000; i++) pnpr_view_sample_add(&v, far);
    pnpr_view_sample_solve(&v, 100, 0);
    CHECK(fabs(pnpr_view_sample_share(&v, far) - 0.1) < 1e-9);
    /* nothing asked (0, negative, NaN): nothing kept */
    pnpr_view_sample_solve(&v, 0, 0);
    CHECK(pnpr_view_sample_share(&v, far) == 0);
    pnpr_view_sample_solve(&v, NAN, 0);
    CHECK(pnpr_view_sample_share(&v, far) == 0);
    /* depths far from 1: 1000 points at 1e70 and at 1e-70, a tenth asked of each scene */
    const double deep[3] = {1e70, 0, 0}, shallow[3] = {1e-70, 0, 0};
    for (int s = 0; s < 2; s++) {
        CHECK_STATUS(pnpr_view_sample_init(&v, eye, target, 90, 100, 100), PNPR_OK);
        for (int i = 0; i < 1000; i++) pnpr_view_sample_add(&v, s ? shallow : deep);
        pnpr_view_sample_solve(&v, 100, 0);
        double share = pnpr_view_sample_share(&v, s ? shallow : deep);
        CHECK_MSG(fabs(share - 0.1) < 1e-6, "depth %g: share %g", s ? 1e-70 : 1e70, share);
    }
    /* bad views */
    CHECK_STATUS(pnpr_view_sample_init(&v, eye, eye, 90, 100, 100), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_view_sample_init(&v, eye, target, 0, 100, 100), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_view_sample_init(&v, eye, target, 180, 100, 100), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_view_sample_init(&v, eye, target, 45, 0, 100), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_view_sample_init(&v, nan, target, 45, 100, 100), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_view_sample_init(NULL, eye, target, 45, 100, 100), PNPR_ERR_INVALID_ARGUMENT);
    /* one view's frame cap: 1100 wanted but each frame draws 50 (10.1 c = 50) */
    CHECK_STATUS(pnpr_view_sample_init(&v, eye, target, 90, 100, 100), PNPR_OK);
    for (int i = 0; i < 1000; i++) {
        pnpr_view_sample_add(&v, near);
        pnpr_view_sample_add(&v, far);
    }
    pnpr_view_sample_solve(&v, 1100, 50);
    CHECK_MSG(fabs(v.c - 50 / 10.1) < 1e-6, "c %g", v.c);
    pnpr_view_sample_solve(&v, 1100, 1e6); /* the frame sees fewer than it draws: no cap */
    CHECK_MSG(fabs(v.c - 1000) < 1e-6, "c %g", v.c);
}

/* Random frames: a path of 65 frames has 64 views, frame 32 the one without its own (views 31 and
 * 32 are frames 31 and 33, both standing for it). Frames 31 and 33 at the origin looking down +x,
 * the others 1e6 away; frame 32 turned by up to 20 degrees and moved by up to about 1, fovs 30..60.
 * 200 random points in frame 32's cone (its own cone test) each seen by the path's views at most
 * at frame 32's depth. Without the cosine of the frames' half-angle (the depth from the view's eye
 * less the reach) 1019 of these 4053 points, near the edge of frame 32's cone on the side it turns
 * from, came out deeper than frame 32 sees them. */
static void check_widened_holds(void)
{
    enum { F = 65, M = 32 };
    static pnpr_view_sample v, one;
    static double eyes[3 * F], targets[3 * F], fovs[F];
    pnpr_test_rng rng = {12345};
    int missed = 0, deeper = 0, tried = 0;
    for (int trial = 0; trial < 50; trial++) {
        for (int f = 0; f < F; f++) {
            double x = f == M - 1 || f == M + 1 ? 0 : 1e6 * (f - M);
            eyes[3 * f] = x;
            eyes[3 * f + 1] = eyes[3 * f + 2] = 0;
            targets[3 * f] = x + 1;
            targets[3 * f + 1] = targets[3 * f + 2] = 0;
            fovs[f] = 30 + 30 * pnpr_test_uniform(&rng);
        }
        double turn = 20 * 3.14159265358979323846 / 180 * pnpr_test_uniform(&rng), az = 6.2831853 * pnpr_test_uniform(&rng);
        double f1[3] = {cos(turn), sin(turn) * cos(az), sin(turn) * sin(az)};
        for (int i = 0; i < 3; i++) eyes[3 * M + i] = 0.5 * pnpr_test_normal(&rng) / sqrt(3.0);
        for (int i = 0; i < 3; i++) targets[3 * M + i] = eyes[3 * M + i] + f1[i];
        CHECK_STATUS(pnpr_view_sample_init_frames(&v, eyes, targets, fovs, F, 100, 100), PNPR_OK);
        CHECK_STATUS(pnpr_view_sample_init(&one, eyes + 3 * M, targets + 3 * M, fovs[M], 100, 100), PNPR_OK);
        for (int k = 0; k < 200; k++) {
            double p[3];
            for (int i = 0; i < 3; i++) p[i] = eyes[3 * M + i] + 20 * (pnpr_test_uniform(&rng) - 0.5) + (i == 0 ? 10 : 0);
            double z1 = pnpr_view_sample_depth(&one, p);
            if (z1 <= 0) continue;
            double z = pnpr_view_sample_depth(&v, p);
            tried++;
            missed += z <= 0;
            deeper += z > z1 * (1 + 1e-9);
        }
    }
    CHECK_MSG(tried > 1000 && missed == 0 && deeper == 0, "widened views: of %d points of frame %d, %d missed, %d deeper",
              tried, M, missed, deeper);
}

/* A path's frames, more than views (pnpr_view_sample_init_frames): 127 frames, every second one a
 * view (frame f = 126 j / 63 = 2 j), each view standing for its neighbours.
 *   - Turning: eyes at the origin, frame f looking 2.5 f degrees about z, fov 2 (the cone's
 *     half-angle atan(1.15 sqrt 2 tan 1 deg) = 1.63 deg). A point at 2.5 degrees, 10 away, lies in
 *     frame 1's cone only (on its axis, at depth 10); the views of frames 0 and 2 stand for it
 *     (half-angles 1.63 + 2.5) and give it their own depth, 10 cos 2.5 deg, less than 10 (the
 *     least depth the frames between may see it at, its distance x the cosine of their
 *     half-angle, is 10 cos 1.63 deg, more). The views without widening would not see it.
 *   - Moving: frame f's eye at x = f / 2, all looking down +x, fov 90 (half-angle atan(1.15 sqrt
 *     2) = 58.4 deg). A point at x = 70 lies 7 ahead of the last eye; the last view stands for
 *     frame 125, 0.5 behind: the least depth a point 6.5 from an eye has in a cone of 58.4 deg is
 *     6.5 cos 58.4 deg. A point 0.2 ahead of frame 1's eye (x = 0.7) gets at most 0.2.
 *   - Random frames around a view (turned up to 20 degrees, eyes up to 1 away) and random points
 *     in their cones: the widened view sees every point, at most at that frame's depth. */
static void test_frames(void)
{
    enum { F = 127 };
    static pnpr_view_sample v;
    static double eyes[3 * F], targets[3 * F], fovs[F];
    for (int f = 0; f < F; f++) {
        double a = 2.5 * f * 3.14159265358979323846 / 180.0;
        eyes[3 * f] = eyes[3 * f + 1] = eyes[3 * f + 2] = 0;
        targets[3 * f] = cos(a);
        targets[3 * f + 1] = sin(a);
        targets[3 * f + 2] = 0;
        fovs[f] = 2;
    }
    CHECK_STATUS(pnpr_view_sample_init_frames(&v, eyes, targets, fovs, F, 100, 100), PNPR_OK);
    CHECK(v.views == PNPR_VIEW_SAMPLE_VIEWS);
    const double half = 2.5 * 3.14159265358979323846 / 180.0, p[3] = {10 * cos(half), 10 * sin(half), 0};
    double z = pnpr_view_sample_depth(&v, p);
    CHECK_MSG(fabs(z - 10 * cos(half)) < 1e-9, "turning: depth %.12g, expected %.12g", z, 10 * cos(half));
    static pnpr_view_sample bare; /* the same views without widening */
    CHECK_STATUS(pnpr_view_sample_init(&bare, eyes, targets, 2, 100, 100), PNPR_OK);
    CHECK_STATUS(pnpr_view_sample_add_view(&bare, eyes + 6, targets + 6, 2, 100, 100), PNPR_OK);
    CHECK(pnpr_view_sample_depth(&bare, p) == 0);
    for (int f = 0; f < F; f++) {
        eyes[3 * f] = 0.5 * f;
        targets[3 * f] = 0.5 * f + 1;
        targets[3 * f + 1] = 0;
        fovs[f] = 90;
    }
    CHECK_STATUS(pnpr_view_sample_init_frames(&v, eyes, targets, fovs, F, 100, 100), PNPR_OK);
    const double ahead[3] = {70, 0, 0}, close[3] = {0.7, 0, 0};
    z = pnpr_view_sample_depth(&v, ahead);
    const double cos_half = 1 / sqrt(1 + 1.15 * 1.15 * 2);
    CHECK_MSG(fabs(z - 6.5 * cos_half) < 1e-9, "moving: depth %.12g, expected %.12g", z, 6.5 * cos_half);
    z = pnpr_view_sample_depth(&v, close);
    CHECK_MSG(z > 0 && z <= 0.2 + 1e-12, "moving: depth %g near frame 1's eye", z);
    /* each view's own histogram is its frame's (the frame's cap): x = 62.8 lies 0.2 behind the last
     * frame's eye, inside the last view's widened cone (its apex 0.59 behind) but not its frame's */
    static pnpr_view_depths each[PNPR_VIEW_SAMPLE_VIEWS];
    v.each = each;
    const double behind_last[3] = {62.8, 0, 0};
    pnpr_view_sample_add(&v, ahead);
    pnpr_view_sample_add(&v, behind_last);
    CHECK_MSG(each[63].visible == 1 && fabs(each[63].z_min - 7) < 1e-9 && v.least.visible == 2,
              "the last view's own histogram: %llu depths from %g; %llu in view", (unsigned long long)each[63].visible, each[63].z_min, (unsigned long long)v.least.visible);
    check_widened_holds();
    /* as many frames as views: no widening, the plain views' depths */
    CHECK_STATUS(pnpr_view_sample_init_frames(&v, eyes, targets, fovs, 3, 100, 100), PNPR_OK);
    CHECK(v.views == 3 && pnpr_view_sample_depth(&v, ahead) == 69);
    /* a frame that is not a view */
    targets[3 * 5] = eyes[3 * 5];
    CHECK_STATUS(pnpr_view_sample_init_frames(&v, eyes, targets, fovs, F, 100, 100), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_view_sample_init_frames(&v, eyes, targets, fovs, 0, 100, 100), PNPR_ERR_INVALID_ARGUMENT);
}

/* Balls (the cells of a file ordered for drawing): known answers for one view, and every point
 * of a random ball no more likely kept than the ball says, for plain and widened views. */
static void test_balls(void)
{
    static pnpr_view_sample v;
    const double eye[3] = {0, 0, 0}, target[3] = {1, 0, 0};
    CHECK_STATUS(pnpr_view_sample_init(&v, eye, target, 60, 100, 100), PNPR_OK);
    /* the cone's half-angle: atan(1.15 sqrt 2 tan 30 deg) = 43.2 deg */
    const double t = 1.15 * sqrt(2.0) * tan(30 * 3.14159265358979323846 / 180);
    const double ahead[3] = {10, 0, 0}, behind[3] = {-5, 0, 0}, around[3] = {0.5, 0, 0};
    const double beside[3] = {10, 10 * t + 1.2, 0}, off[3] = {10, 10 * t + 1.6, 0};
    pnpr_view_sample_add_ball(&v, ahead, 1, 40);
    pnpr_view_sample_add_ball(&v, behind, 1, 7);
    CHECK(v.least.visible == 40 && v.least.z_min == 9 && v.least.z_max == 9);
    v.c = 0.5 * 81; /* a point at depth 9: share 0.5 */
    CHECK_NEAR(pnpr_view_sample_ball_share(&v, ahead, 1), 0.5, 1e-12);
    const double front[3] = {9, 0, 0};
    CHECK_NEAR(pnpr_view_sample_share(&v, front), 0.5, 1e-12);
    CHECK(pnpr_view_sample_ball_share(&v, behind, 1) == 0);
    CHECK(pnpr_view_sample_ball_share(&v, around, 1) == 1); /* it holds the eye */
    /* 1.2 beside the cone's edge (1.2 cos 43.2 deg = 0.87 from it): a ball of 1 reaches in, of 0.8 not */
    CHECK(pnpr_view_sample_ball_share(&v, beside, 1) > 0);
    CHECK(pnpr_view_sample_ball_share(&v, beside, 0.8) == 0);
    CHECK(pnpr_view_sample_ball_share(&v, off, 1) == 0);
    const double nan_c[3] = {NAN, 0, 0};
    CHECK(pnpr_view_sample_ball_share(&v, nan_c, 1) == 0);

    enum { F = 65 };
    static pnpr_view_sample w;
    static double eyes[3 * F], targets[3 * F], fovs[F];
    pnpr_test_rng rng = {99};
    int tried = 0, above = 0;
    for (int trial = 0; trial < 40; trial++) {
        for (int f = 0; f < F; f++) { /* a wandering, turning path */
            double a = 0.05 * f + 0.3 * pnpr_test_uniform(&rng);
            eyes[3 * f] = 0.3 * f;
            eyes[3 * f + 1] = 2 * sin(0.1 * f);
            eyes[3 * f + 2] = pnpr_test_uniform(&rng);
            targets[3 * f] = eyes[3 * f] + cos(a);
            targets[3 * f + 1] = eyes[3 * f + 1] + sin(a);
            targets[3 * f + 2] = eyes[3 * f + 2] - 0.2;
            fovs[f] = 20 + 40 * pnpr_test_uniform(&rng);
        }
        int frames = trial % 2 ? F : 20; /* widened views, or plain ones */
        CHECK_STATUS(pnpr_view_sample_init_frames(&w, eyes, targets, fovs, (size_t)frames, 160, 90), PNPR_OK);
        w.c = pow(10, 3 * pnpr_test_uniform(&rng) - 1);
        for (int b = 0; b < 100; b++) {
            double c[3], rho = 3 * pnpr_test_uniform(&rng);
            for (int i = 0; i < 3; i++) c[i] = 40 * (pnpr_test_uniform(&rng) - 0.3);
            double bs = pnpr_view_sample_ball_share(&w, c, rho);
            for (int k = 0; k < 30; k++) {
                double p[3], d[3], len = 0;
                for (int i = 0; i < 3; i++) {
                    d[i] = pnpr_test_normal(&rng);
                    len += d[i] * d[i];
                }
                double r = rho * cbrt(pnpr_test_uniform(&rng)) / sqrt(len);
                for (int i = 0; i < 3; i++) p[i] = c[i] + r * d[i];
                double ps = pnpr_view_sample_share(&w, p);
                tried += ps > 0;
                above += ps > bs * (1 + 1e-9);
            }
        }
    }
    CHECK_MSG(tried > 3000 && above == 0, "of %d points in view, %d more likely kept than their ball", tried, above);
}

/* The grid over degenerate boxes: never more than PNPR_VIEW_CELLS_MAX cells, every finite point
 * counted once. A box of subnormal size and one whose extent overflows a float get one cell (they
 * had made 32768^3 and 32768^2 cells, written past the counts); a single point one; an ordinary
 * flat box the smallest cubes. */
static void test_grid_degenerate(void)
{
    static pnpr_view_cells vc;
    const float boxes[][6] = {
        {0, 0, 0, 1e-44f, 1e-44f, 1e-44f},  {-3e38f, -3e38f, 0, 3e38f, 3e38f, 0}, {5, 5, 5, 5, 5, 5},
        {0, 0, 0, 2000, 40, 0},            {0, 0, 0, 1e-38f, 2e-38f, 0},        {NAN, 0, 0, 1, 1, 1},
    };
    const uint32_t cells[] = {1, 1, 1, 0, 0, 0}; /* 0: not a known count, at most the limit */
    for (size_t b = 0; b < sizeof boxes / sizeof *boxes; b++) {
        const float *lo = boxes[b], *hi = boxes[b] + 3;
        float pts[5 * 3] = {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], 0.5f * (lo[0] + hi[0]), lo[1], hi[2],
                            NAN, 0, 0, INFINITY, 1, 1};
        pnpr_view_cells_build(&vc, pts, 5, lo, hi);
        size_t size = pnpr_view_cells_size(&vc), total = 0;
        for (size_t k = 0; k < size && size <= PNPR_VIEW_CELLS_MAX; k++) total += vc.count[k];
        size_t finite = 0;
        for (int i = 0; i < 5; i++) finite += isfinite(pts[3 * i]) && isfinite(pts[3 * i + 1]) && isfinite(pts[3 * i + 2]);
        CHECK_MSG(size >= 1 && size <= PNPR_VIEW_CELLS_MAX && (!cells[b] || size == cells[b]) && total == finite &&
                      vc.cell > 0 && isfinite(vc.inv),
                  "box %zu: %u x %u x %u cells of side %g, %zu of %zu points counted", b, vc.n[0], vc.n[1], vc.n[2],
                  (double)vc.cell, total, finite);
    }
    /* the flat road: cubes of 2000 / 1000 x 40 / 20 -> the smallest side with at most 32768 */
    pnpr_view_cells_build(&vc, NULL, 0, boxes[3], boxes[3] + 3);
    CHECK_MSG(vc.n[2] == 1 && (double)vc.n[0] * vc.n[1] <= PNPR_VIEW_CELLS_MAX &&
                  (double)ceil(2000 / (vc.cell * 0.999)) * ceil(40 / (vc.cell * 0.999)) > PNPR_VIEW_CELLS_MAX,
              "road: %u x %u of side %g", vc.n[0], vc.n[1], (double)vc.cell);
}

/* A camera path's sample, known answers: view A at the origin looking down +x sees `near` at depth
 * 10 and `far` at 100, view B at x = 110 looking back sees them at 100 and 10, and `past` (x =
 * 120, behind B) only A sees, at 120. The least depths: 10, 10, 120. 1100 wanted of 2000 + 100:
 * 2000 c / 10^2 + 100 c / 120^2 = 1100, c = 54.98 (shares 0.5498 near and far). Each frame to
 * draw 50 of its own: A's 1000 c / 100 + 1000 c / 10^4 + 100 c / 120^2 = 50 (c = 4.9472), B's
 * 10.1 c = 50 (4.9505): the cap is the larger, B's, the first view (view C, looking away, sees
 * nothing and counts for nothing). Without the views' own histograms, no cap. Every point wanted
 * and each frame drawing more than it sees: the cap is the square of the farthest depth a frame
 * sees (A's 120), every point whole. */
static void test_path_sample(void)
{
    static pnpr_view_sample v;
    static pnpr_view_depths each[PNPR_VIEW_SAMPLE_VIEWS];
    const double a[3] = {0, 0, 0}, a_to[3] = {1, 0, 0}, b[3] = {110, 0, 0}, b_to[3] = {0, 0, 0};
    const double near[3] = {10, 0.5, 0}, far[3] = {100, -3, 2}, past[3] = {120, 1, 0}, side[3] = {55, 500, 0};
    const double c_to[3] = {0, 0, 1}; /* view C looks up, away from every point */
    for (int pass = 0; pass < 2; pass++) { /* B (the neediest) first, C last */
        CHECK_STATUS(pnpr_view_sample_init(&v, b, b_to, 90, 100, 100), PNPR_OK);
        CHECK_STATUS(pnpr_view_sample_add_view(&v, a, a_to, 90, 100, 100), PNPR_OK);
        CHECK_STATUS(pnpr_view_sample_add_view(&v, a, c_to, 10, 100, 100), PNPR_OK);
        memset(each, 0, sizeof each);
        v.each = pass ? each : NULL;
        for (int i = 0; i < 1000; i++) {
            pnpr_view_sample_add(&v, near);
            pnpr_view_sample_add(&v, far);
            if (i < 100) pnpr_view_sample_add(&v, past);
            pnpr_view_sample_add(&v, side); /* neither sees it */
        }
        CHECK(pnpr_view_sample_depth(&v, near) == 10 && pnpr_view_sample_depth(&v, far) == 10 &&
              pnpr_view_sample_depth(&v, past) == 120 && pnpr_view_sample_depth(&v, side) == 0);
        CHECK_MSG(v.least.visible == 2100, "%llu in view", (unsigned long long)v.least.visible);
        const double c = 1100 / (2000 / 100.0 + 100 / 14400.0);
        pnpr_view_sample_solve(&v, 1100, 0);
        CHECK_MSG(fabs(v.c - c) < 1e-6, "c %g, want %g", v.c, c);
        CHECK(fabs(pnpr_view_sample_share(&v, far) - c / 100) < 1e-9 && pnpr_view_sample_share(&v, side) == 0);
        pnpr_view_sample_solve(&v, 1100, 50);
        const double cap = pass ? 50 / 10.1 : c;
        CHECK_MSG(fabs(v.c - cap) < 1e-6, "pass %d: c %g, want %g", pass, v.c, cap);
        if (pass) CHECK(each[0].visible == 2000 && each[1].visible == 2100 && each[2].visible == 0);
        /* every point wanted, each frame drawing more than it sees: all whole, c the square of the
         * farthest depth a frame sees (A's 120) */
        pnpr_view_sample_solve(&v, 1e6, 1e6);
        CHECK_MSG(pass ? v.c == 120.0 * 120.0 : v.c == HUGE_VAL, "pass %d: c %g", pass, v.c);
        CHECK(pnpr_view_sample_share(&v, past) == 1 && pnpr_view_sample_share(&v, near) == 1);
    }
    /* at most PNPR_VIEW_SAMPLE_VIEWS views */
    CHECK_STATUS(pnpr_view_sample_init(&v, a, a_to, 90, 100, 100), PNPR_OK);
    for (int k = 1; k < PNPR_VIEW_SAMPLE_VIEWS; k++) CHECK_STATUS(pnpr_view_sample_add_view(&v, b, b_to, 90, 100, 100), PNPR_OK);
    CHECK_STATUS(pnpr_view_sample_add_view(&v, b, b_to, 90, 100, 100), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(v.views == PNPR_VIEW_SAMPLE_VIEWS);
    CHECK_STATUS(pnpr_view_sample_add_view(NULL, b, b_to, 90, 100, 100), PNPR_ERR_INVALID_ARGUMENT);
}

/* Per-cell queues: two groups over 1203 cells (one of 5000 points, one of 200, 1200 of one point,
 * one empty) against brute force: each group sorted by key, stable (a cell's points keep the
 * group's queue order), the keys of a cell's queue its ranks as (rank + offset) / count, the
 * prefixes and the drawn counts exactly those of the keys; a share f of every cell draws f x all
 * within a few points (the offsets' golden-ratio sequence), and the shares nest. */
/* The cells' shares (view/view_cells.c, pnpr_view_cells_solve), known answers: three cells of 100
 * points with weights 4, 1 and 0 (out of view). 50 wanted: lambda 50 / 500 = 0.1 (shares 0.4 and
 * 0.1); 150: the first would take 1.2, so it is full and the second draws the other 50 (lambda
 * 0.5); 200 or more: every cell in view whole (HUGE_VAL); 0: none. */
static void test_solve(void)
{
    pnpr_view_cells *c = calloc(1, sizeof *c);
    CHECK(c != NULL);
    if (!c) return;
    c->n[0] = 3; c->n[1] = c->n[2] = 1;
    c->count[0] = c->count[1] = c->count[2] = 100;
    const float w[6] = {4, -1, 1, -1, 0, -1}; /* stride 2 */
    CHECK_NEAR(pnpr_view_cells_solve(c, w, 2, 50), 0.1, 1e-12);
    CHECK_NEAR(pnpr_view_cells_solve(c, w, 2, 150), 0.5, 1e-12);
    CHECK(pnpr_view_cells_solve(c, w, 2, 200) == HUGE_VAL && pnpr_view_cells_solve(c, w, 2, 1e9) == HUGE_VAL);
    CHECK(pnpr_view_cells_solve(c, w, 2, 0) == 0);
    free(c);
}

static uint32_t cell_of_array(const void *user, uint32_t point) { return ((const uint32_t *)user)[point]; }

static void test_cells(void)
{
    enum { CELLS = 1204, N = 5000 + 200 + 1200 };
    uint32_t *cell = malloc(N * sizeof *cell), *order = malloc(N * sizeof *order), *before = malloc(N * sizeof *before);
    uint16_t *key = malloc(N * sizeof *key);
    uint8_t *group = malloc(N);
    float *end = malloc(CELLS * sizeof *end);
    CHECK(cell && order && before && key && group && end);
    if (!cell || !order || !before || !key || !group || !end) return;
    for (size_t i = 0; i < N; i++) {
        cell[i] = i < 5000 ? 0 : i < 5200 ? 1 : (uint32_t)(i - 5200 + 2); /* cell 1203: empty */
        group[i] = (uint8_t)(i % 3 == 0);
    }
    size_t starts[4];
    CHECK_STATUS(pnpr_crq_order(N, group, 2, 7, order, starts), PNPR_OK);
    memcpy(before, order, N * sizeof *order);
    pnpr_crq_cells q;
    CHECK_STATUS(pnpr_crq_cells_make(order, starts, 3, cell_of_array, cell, CELLS, 7, key, &q), PNPR_OK);
    CHECK(is_permutation(order, N));
    size_t bad_sort = 0, bad_stable = 0, bad_key = 0, bad_group = 0;
    for (size_t g = 0; g < 2; g++) {
        size_t rank[CELLS] = {0};
        for (size_t i = starts[g]; i < starts[g + 1]; i++) { /* the queue order: ranks */
            uint32_t p = before[i], k = cell[p];
            size_t r = rank[k]++;
            /* where p went: its key is its rank's */
            size_t at = starts[g];
            while (at < starts[g + 1] && order[at] != p) at++;
            bad_group += at == starts[g + 1];
            if (at < starts[g + 1]) bad_key += key[at] != pnpr_crq_key(r, q.count[g * CELLS + k], q.offset[g * CELLS + k]);
        }
        for (size_t i = starts[g] + 1; i < starts[g + 1]; i++) {
            bad_sort += key[i] < key[i - 1];
            /* stable: two points of one cell with one key keep the queue order */
        }
        for (size_t i = starts[g]; i < starts[g + 1]; i++)
            for (size_t j = i + 1; j < starts[g + 1] && j < i + 64; j++)
                if (cell[order[i]] == cell[order[j]]) {
                    size_t pi = starts[g], pj = starts[g];
                    while (before[pi] != order[i]) pi++;
                    while (before[pj] != order[j]) pj++;
                    bad_stable += pi > pj;
                }
    }
    CHECK_MSG(!bad_sort && !bad_stable && !bad_key && !bad_group, "sorted %zu, stable %zu, keys %zu, groups %zu", bad_sort,
              bad_stable, bad_key, bad_group);
    const float fracs[] = {0.0f, 0.013f, 0.3f, 0.5f, 0.77f, 1.0f};
    size_t last = 0;
    for (size_t t = 0; t < sizeof fracs / sizeof fracs[0]; t++) {
        for (size_t k = 0; k < CELLS; k++) end[k] = fracs[t] * PNPR_CRQ_KEYS;
        size_t drawn = 0, prefix_ok = 1;
        for (size_t g = 0; g < 2; g++) {
            size_t kept = 0;
            for (size_t i = starts[g]; i < starts[g + 1]; i++) kept += (float)key[i] + 0.5f < end[cell[order[i]]];
            drawn += kept;
            prefix_ok &= pnpr_crq_cells_prefix(&q, g, end[0]) == kept; /* one end: the prefix is what it keeps */
        }
        CHECK_MSG(pnpr_crq_cells_drawn(&q, end, 1) == drawn && prefix_ok, "share %g: %zu drawn, brute force %zu",
                  (double)fracs[t], pnpr_crq_cells_drawn(&q, end, 1), drawn);
        CHECK_MSG(fabs((double)drawn - fracs[t] * N) <= 4, "share %g: %zu of %d drawn", (double)fracs[t], drawn, N);
        CHECK(drawn >= last);
        last = drawn;
    }
    /* cells of their own ends: the counts follow each cell's */
    for (size_t k = 0; k < CELLS; k++) end[k] = k == 0 ? 0.25f * PNPR_CRQ_KEYS : 0;
    size_t c0 = q.count[0] + q.count[CELLS];
    CHECK_MSG(fabs((double)pnpr_crq_cells_drawn(&q, end, 1) - 0.25 * (double)c0) <= 2, "cell 0 at 1/4: %zu of %zu",
              pnpr_crq_cells_drawn(&q, end, 1), c0);
    /* a cell out of range: refused, nothing left allocated */
    cell[5] = CELLS;
    pnpr_crq_cells bad;
    CHECK_STATUS(pnpr_crq_cells_make(order, starts, 3, cell_of_array, cell, CELLS, 7, key, &bad), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(bad.count == NULL && bad.cum == NULL && bad.offset == NULL);
    pnpr_crq_cells_free(&q);
    free(cell); free(order); free(before); free(key); free(group); free(end);
}

int main(void)
{
    enum { N = 10000 };
    uint32_t *a = malloc(N * sizeof *a), *b = malloc(N * sizeof *b), *c = malloc(N * sizeof *c);
    uint8_t *group = malloc(N);
    CHECK(a && b && c && group);
    if (!a || !b || !c || !group) return pnpr_test_finish("test_crq");
    test_cells();
    test_solve();
    test_balls();

    /* one group: a permutation, deterministic, seed-dependent, not the identity */
    size_t starts[8];
    CHECK_STATUS(pnpr_crq_order(N, NULL, 1, 42, a, starts), PNPR_OK);
    CHECK_STATUS(pnpr_crq_order(N, NULL, 1, 42, b, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_crq_order(N, NULL, 1, 43, c, NULL), PNPR_OK);
    CHECK(is_permutation(a, N));
    CHECK(is_permutation(c, N));
    CHECK(memcmp(a, b, N * sizeof *a) == 0);
    CHECK(memcmp(a, c, N * sizeof *a) != 0);
    size_t fixed = 0, first_half = 0;
    for (size_t i = 0; i < N; i++) {
        fixed += a[i] == i;
        first_half += i < N / 10 && a[i] < N / 2;
    }
    CHECK_MSG(fixed < 20, "%zu fixed points", fixed);
    /* a random prefix is spread over the input: ~half of the first 10% come from the first half */
    CHECK_MSG(first_half > N / 20 - 150 && first_half < N / 20 + 150, "%zu", first_half);
    CHECK(starts[0] == 0 && starts[1] == N && starts[2] == N);

    /* groups: contiguous, each a shuffle of its members, unknown groups last */
    for (size_t i = 0; i < N; i++) group[i] = (uint8_t)(i % 7 == 0 ? 2 : i % 3 == 0 ? 0 : i % 11 == 0 ? 9 : 1);
    CHECK_STATUS(pnpr_crq_order(N, group, 4, 7, a, starts), PNPR_OK);
    CHECK(is_permutation(a, N));
    for (size_t g = 0; g <= 4; g++) {
        for (size_t q = starts[g]; q < starts[g + 1]; q++) {
            size_t gg = group[a[q]] > 4 ? 4 : group[a[q]];
            if (gg != g) { CHECK_MSG(0, "point %u of group %zu at queue position %zu of group %zu", a[q], gg, q, g); break; }
        }
    }
    CHECK(starts[5] == N);
    CHECK(starts[4] - starts[3] == 0); /* group 3 has no members */
    CHECK(starts[5] - starts[4] > 0);  /* value 9 went to the "other" group */
    /* a group's order does not depend on the other groups' members */
    uint8_t *g2 = malloc(N);
    CHECK(g2 != NULL);
    if (g2) {
        memcpy(g2, group, N);
        CHECK_STATUS(pnpr_crq_order(N, g2, 4, 7, b, NULL), PNPR_OK);
        CHECK(memcmp(a, b, N * sizeof *a) == 0);
        free(g2);
    }

    /* split: exact totals, proportional, never more than a group holds */
    size_t sizes[4] = {10, 0, 333, 7}, draw[4];
    for (size_t total = 0; total <= 360; total++) {
        pnpr_crq_split(sizes, 4, total, draw);
        size_t sum = 0;
        for (int g = 0; g < 4; g++) { sum += draw[g]; CHECK(draw[g] <= sizes[g]); }
        CHECK_MSG(sum == (total < 350 ? total : 350), "total %zu sum %zu", total, sum);
        CHECK(draw[1] == 0);
    }
    pnpr_crq_split(sizes, 4, 35, draw);
    CHECK(draw[0] == 1 && draw[2] == 33 && draw[3] == 1);

    /* degenerate */
    CHECK_STATUS(pnpr_crq_order(0, NULL, 1, 1, NULL, starts), PNPR_OK);
    CHECK(starts[0] == 0 && starts[1] == 0);
    CHECK_STATUS(pnpr_crq_order(5, NULL, 1, 1, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_crq_order(1, NULL, 1, 1, a, NULL), PNPR_OK);
    CHECK(a[0] == 0);

    free(a); free(b); free(c); free(group);
    test_view_sample();
    test_path_sample();
    test_grid_degenerate();
    test_frames();
    return pnpr_test_finish("test_crq");
}
