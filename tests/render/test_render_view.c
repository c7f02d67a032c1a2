/* pnpr_camera_default (render.h, docs/view.md), pure CPU: on a generated town placed z-up, y-up
 * and as a y-down RGB-D frame the eye is above the ground and looks down on it, the content fills
 * most of the frame; an aerial-like flat scene fills the frame with its ground; one far outlier
 * (1e9, 1e308) moves the camera by less than 1% of the scene; --up modes; degenerate input.
 * Compared with pnpr_camera_fit (the legacy fixed direction) on the same scenes. */
#include "testutil.h"
#include "view_scene.h"

#include <pointnpr/render.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const float ASPECT = 4.0f / 3.0f, FOV = 45.0f;

typedef struct proj { double s[3], u[3], f[3], tx, ty; } proj;

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void unit(double v[3]) { double l = sqrt(dot(v, v)); for (int a = 0; a < 3; a++) v[a] /= l; }

static proj make_proj(const pnpr_camera *c)
{
    proj p;
    for (int a = 0; a < 3; a++) p.f[a] = c->target[a] - c->eye[a];
    unit(p.f);
    p.s[0] = p.f[1] * c->up[2] - p.f[2] * c->up[1];
    p.s[1] = p.f[2] * c->up[0] - p.f[0] * c->up[2];
    p.s[2] = p.f[0] * c->up[1] - p.f[1] * c->up[0];
    unit(p.s);
    p.u[0] = p.s[1] * p.f[2] - p.s[2] * p.f[1];
    p.u[1] = p.s[2] * p.f[0] - p.s[0] * p.f[2];
    p.u[2] = p.s[0] * p.f[1] - p.s[1] * p.f[0];
    p.ty = tan(0.5 * (c->fov_y_deg > 0 ? c->fov_y_deg : 45) * 3.14159265358979323846 / 180);
    p.tx = p.ty * ASPECT;
    return p;
}

/* NDC of a world point (relative to the eye in double); returns the depth. */
static double project(const proj *p, const pnpr_camera *c, const double w[3], double ndc[2])
{
    double r[3] = {w[0] - c->eye[0], w[1] - c->eye[1], w[2] - c->eye[2]};
    double z = dot(r, p->f);
    ndc[0] = dot(r, p->s) / (z * p->tx);
    ndc[1] = dot(r, p->u) / (z * p->ty);
    return z;
}

/* Share of the frame's width and height covered by the first n points; r_inside: all in frame. */
static void content_fill(const pnpr_camera *c, const pnpr_cloud *cl, size_t n, double r_fill[2], int *r_inside)
{
    proj p = make_proj(c);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    *r_inside = 1;
    for (size_t i = 0; i < n; i++) {
        double w[3], ndc[2];
        for (int a = 0; a < 3; a++) w[a] = cl->origin[a] + cl->xyz[3 * i + a];
        if (!(project(&p, c, w, ndc) > 0)) { *r_inside = 0; continue; }
        for (int k = 0; k < 2; k++) { lo[k] = fmin(lo[k], ndc[k]); hi[k] = fmax(hi[k], ndc[k]); }
    }
    for (int k = 0; k < 2; k++) {
        r_fill[k] = 0.5 * (hi[k] - lo[k]);
        if (lo[k] < -1.0001 || hi[k] > 1.0001) *r_inside = 0;
    }
}

/* Share of the frame covered by the projected ground square of the scene (clipped to the frame
 * by sampling a 200 x 200 grid of the frame against the projected quadrilateral). */
static double footprint(const pnpr_camera *c, const view_scene *s, const view_frame *f)
{
    proj p = make_proj(c);
    double q[4][2];
    for (int k = 0; k < 4; k++) {
        double g[3] = {(k == 1 || k == 2 ? 0.5 : -0.5) * s->side, (k >= 2 ? 0.5 : -0.5) * s->side, 0}, w[3];
        view_to_world(f, g, w);
        project(&p, c, w, q[k]);
    }
    int in = 0;
    for (int j = 0; j < 200; j++)
        for (int i = 0; i < 200; i++) {
            double x = -1 + (i + 0.5) / 100, y = -1 + (j + 0.5) / 100;
            int sgn = 0, ok = 1;
            for (int k = 0; k < 4; k++) { /* inside a convex quad: same side of every edge */
                const double *a = q[k], *b = q[(k + 1) % 4];
                double cr = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
                int sk = cr > 0 ? 1 : -1;
                if (sgn && sk != sgn) ok = 0;
                sgn = sk;
            }
            in += ok;
        }
    return in / 40000.0;
}

/* Eye height above the ground (along the true up) and the view's dot with up. */
static void above(const pnpr_camera *c, const view_frame *f, double *r_height, double *r_down)
{
    double e[3], d[3];
    for (int a = 0; a < 3; a++) { e[a] = c->eye[a] - f->at[a]; d[a] = c->target[a] - c->eye[a]; }
    unit(d);
    *r_height = dot(e, f->up);
    *r_down = dot(d, f->up);
}

static void check_scene(const char *name, const view_frame *f, int legacy_below)
{
    view_scene s = view_town();
    pnpr_cloud c = {0};
    CHECK_STATUS(view_make(&c, &s, f, 0, 7), PNPR_OK);
    pnpr_camera cam, old;
    pnpr_view_info v;
    CHECK_STATUS(pnpr_camera_default(&c, NULL, FOV, ASPECT, &cam, &v), PNPR_OK);
    CHECK_STATUS(pnpr_camera_fit(&c, NULL, FOV, ASPECT, &old), PNPR_OK);
    double h, down, fill[2], hold, dold, fold[2];
    int inside, iold;
    above(&cam, f, &h, &down);
    above(&old, f, &hold, &dold);
    content_fill(&cam, &c, c.count, fill, &inside);
    content_fill(&old, &c, c.count, fold, &iold);
    printf("%s: eye %.3g above the ground (scene %.3g), view . up %.3f, fills %.0f%% x %.0f%% of the frame; "
           "legacy fit: eye %.3g above, fills %.0f%% x %.0f%%\n",
           name, h, s.side * f->scale, down, 100 * fill[0], 100 * fill[1], hold, 100 * fold[0], 100 * fold[1]);
    CHECK_MSG(h > 0.2 * s.side * f->scale, "%s: eye %.3g above the ground", name, h);
    CHECK(down < -0.5); /* looks down onto it (46.6 degrees) */
    CHECK(inside);
    CHECK(fmax(fill[0], fill[1]) >= 0.9 && fmax(fill[0], fill[1]) <= 0.96); /* 5% margin */
    CHECK(legacy_below ? hold < 0 : hold > 0);
    CHECK(cam.near_plane == 0 && cam.far_plane == 0); /* no outlier: automatic */
    pnpr_cloud_free(&c);
}

static void test_scenes(void)
{
    view_frame z = view_frame_zup(), y = view_frame_yup(), d = view_frame_rgbd(100);
    check_scene("z-up town", &z, 0);
    check_scene("y-up town", &y, 1);
    check_scene("y-down RGB-D town", &d, 0);
}

static void test_aerial(void)
{
    view_scene s = view_aerial();
    view_frame z = view_frame_zup();
    pnpr_cloud c = {0};
    CHECK_STATUS(view_make(&c, &s, &z, 0, 11), PNPR_OK);
    pnpr_camera cam, old;
    CHECK_STATUS(pnpr_camera_default(&c, NULL, FOV, ASPECT, &cam, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_camera_fit(&c, NULL, FOV, ASPECT, &old), PNPR_OK);
    double a = footprint(&cam, &s, &z), b = footprint(&old, &s, &z), fill[2];
    int inside;
    content_fill(&cam, &c, c.count, fill, &inside);
    printf("aerial 200 x 200 x 5: the ground covers %.0f%% of the frame (legacy fit: %.0f%%), content %.0f%% x %.0f%%\n",
           100 * a, 100 * b, 100 * fill[0], 100 * fill[1]);
    CHECK(a >= 0.5);
    CHECK(b < 0.35);
    CHECK(inside);
    /* the tighter axis holds the content with the 5% margin: 1 / 1.05 of the frame */
    CHECK_NEAR(fmax(fill[0], fill[1]), 1 / 1.05, 0.005);
    pnpr_cloud_free(&c);
}

static double dist3(const double a[3], const double b[3])
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(dot(d, d));
}

static void test_outliers(void)
{
    view_scene s = view_town();
    view_frame z = view_frame_zup();
    pnpr_cloud c = {0};
    CHECK_STATUS(view_make(&c, &s, &z, 0, 7), PNPR_OK);
    pnpr_camera base, cam, old;
    CHECK_STATUS(pnpr_camera_default(&c, NULL, FOV, ASPECT, &base, NULL), PNPR_OK);
    double size = s.side * sqrt(2.0), fill[2];
    int inside;
    for (int big = 0; big < 2; big++) {
        pnpr_cloud o = {0};
        CHECK_STATUS(view_make(&o, &s, &z, 1, 7), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_alloc_src_xyz(&o), PNPR_OK);
        for (size_t i = 0; i < o.count; i++)
            for (int a = 0; a < 3; a++) o.src_xyz[3 * i + a] = o.origin[a] + o.xyz[3 * i + a];
        double w = big ? 1e308 : 1e9;
        for (int a = 0; a < 3; a++) {
            o.src_xyz[3 * (o.count - 1) + a] = w;
            o.xyz[3 * (o.count - 1) + a] = (float)(w - o.origin[a]);
        }
        pnpr_view_info v;
        CHECK_STATUS(pnpr_camera_default(&o, NULL, FOV, ASPECT, &cam, &v), PNPR_OK);
        double de = dist3(cam.eye, base.eye), dt = dist3(cam.target, base.target);
        printf("outlier at %g: eye moved %.3g, target %.3g (scene %.3g), %zu outlier, near %.4g far %.4g\n",
               w, de, dt, size, v.outliers, (double)cam.near_plane, (double)cam.far_plane);
        CHECK(de < 0.01 * size && dt < 0.01 * size);
        if (!big) { /* the legacy fit ignores the far outlier too (it used to frame it: the town
                     * shrank to a dot, 7e-6 % of the frame): the same camera as without it */
            pnpr_camera clean_fit;
            CHECK_STATUS(pnpr_camera_fit(&o, NULL, FOV, ASPECT, &old), PNPR_OK);
            CHECK_STATUS(pnpr_camera_fit(&c, NULL, FOV, ASPECT, &clean_fit), PNPR_OK);
            content_fill(&old, &o, o.count - 1, fill, &inside);
            printf("  legacy fit with it: the town fills %.2g%% x %.2g%% of the frame\n", 100 * fill[0], 100 * fill[1]);
            CHECK(dist3(old.eye, clean_fit.eye) < 1e-6 * size && dist3(old.target, clean_fit.target) < 1e-6 * size);
            CHECK(fmax(fill[0], fill[1]) > 0.5);
        }
        CHECK(v.outliers == 1);
        CHECK(memcmp(cam.up, base.up, sizeof cam.up) == 0);
        /* explicit depth range around the content (the automatic one would reach the outlier) */
        proj p = make_proj(&cam);
        double zmin = INFINITY, zmax = -INFINITY, ndc[2];
        for (size_t i = 0; i + 1 < o.count; i++) {
            double q[3];
            for (int a = 0; a < 3; a++) q[a] = o.origin[a] + o.xyz[3 * i + a];
            double zz = project(&p, &cam, q, ndc);
            zmin = fmin(zmin, zz);
            zmax = fmax(zmax, zz);
        }
        CHECK(cam.near_plane > 0 && cam.near_plane < zmin && cam.far_plane > zmax && cam.far_plane < 3 * zmax);
        pnpr_cloud_free(&o);
    }
    pnpr_cloud_free(&c);
}

static int finite_camera(const pnpr_camera *c)
{
    int ok = 1;
    for (int a = 0; a < 3; a++) ok &= isfinite(c->eye[a]) && isfinite(c->target[a]) && isfinite(c->up[a]);
    return ok && dist3(c->eye, c->target) > 0;
}

static void test_modes_and_degenerate(void)
{
    view_scene s = view_town();
    view_frame z = view_frame_zup();
    pnpr_cloud c = {0};
    CHECK_STATUS(view_make(&c, &s, &z, 0, 7), PNPR_OK);
    pnpr_view_options o = {0};
    pnpr_camera cam;
    o.up_mode = PNPR_UP_POS_Y;
    CHECK_STATUS(pnpr_camera_default(&c, &o, FOV, ASPECT, &cam, NULL), PNPR_OK);
    CHECK(cam.up[0] == 0 && cam.up[1] == 1 && cam.up[2] == 0 && cam.eye[1] > cam.target[1]);
    o.up_mode = PNPR_UP_MODE_COUNT_;
    CHECK_STATUS(pnpr_camera_default(&c, &o, FOV, ASPECT, &cam, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_camera_default(NULL, NULL, FOV, ASPECT, &cam, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_camera_default(&c, NULL, FOV, ASPECT, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    /* bad fov / aspect fall back to 45 / 1 */
    CHECK_STATUS(pnpr_camera_default(&c, NULL, NAN, -1, &cam, NULL), PNPR_OK);
    CHECK(cam.fov_y_deg == 45 && finite_camera(&cam));
    pnpr_cloud_free(&c);

    CHECK_STATUS(pnpr_camera_default(&c, NULL, FOV, ASPECT, &cam, NULL), PNPR_ERR_EMPTY);
    CHECK_STATUS(pnpr_cloud_alloc(&c, 4), PNPR_OK);
    for (int i = 0; i < 12; i++) c.xyz[i] = NAN;
    CHECK_STATUS(pnpr_camera_default(&c, NULL, FOV, ASPECT, &cam, NULL), PNPR_ERR_EMPTY);
    /* one point at 1e7: a finite camera looking at it from above */
    c.origin[0] = 1e7; c.origin[1] = 1e7; c.origin[2] = -1e7;
    c.xyz[3] = 1; c.xyz[4] = 2; c.xyz[5] = 3;
    CHECK_STATUS(pnpr_camera_default(&c, NULL, FOV, ASPECT, &cam, NULL), PNPR_OK);
    CHECK(finite_camera(&cam) && cam.eye[2] > cam.target[2]);
    CHECK_NEAR(cam.target[0], 1e7 + 1, 1e-6);
    CHECK_NEAR(cam.target[2], -1e7 + 3, 1e-6);
    /* duplicates */
    for (int i = 0; i < 12; i++) c.xyz[i] = (float)(i % 3);
    CHECK_STATUS(pnpr_camera_default(&c, NULL, FOV, ASPECT, &cam, NULL), PNPR_OK);
    CHECK(finite_camera(&cam));
    /* collinear: the line across the frame, filling 95% of it */
    CHECK_STATUS(pnpr_cloud_alloc(&c, 500), PNPR_OK);
    for (size_t i = 0; i < 500; i++) { c.xyz[3 * i] = (float)i; c.xyz[3 * i + 1] = 1; c.xyz[3 * i + 2] = 1; }
    CHECK_STATUS(pnpr_camera_default(&c, NULL, FOV, ASPECT, &cam, NULL), PNPR_OK);
    double fill[2];
    int inside;
    content_fill(&cam, &c, c.count, fill, &inside);
    CHECK(finite_camera(&cam) && inside);
    CHECK_NEAR(fill[0], 1 / 1.05, 0.005);
    /* a sphere at 1e7: all of it in the frame */
    double off[3] = {1e7, -1e7, 1e7};
    CHECK_STATUS(pnpr_test_sphere(&c, 5000, 2, off, 3), PNPR_OK);
    CHECK_STATUS(pnpr_camera_default(&c, NULL, FOV, ASPECT, &cam, NULL), PNPR_OK);
    content_fill(&cam, &c, c.count, fill, &inside);
    CHECK(inside && fmax(fill[0], fill[1]) > 0.85);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_scenes();
    test_aerial();
    test_outliers();
    test_modes_and_degenerate();
    return pnpr_test_finish("test_render_view");
}
