/* The picture-quality figures of `pointnpr bench quality` (bench/quality/quality_metrics.c) on
 * images drawn by hand with known answers: projection through pnpr_camera_matrices_from_camera;
 * edge coverage and precision (a line exactly on a projected edge, shifted by 1.5 and 5 px, half
 * drawn, with stray ink, partly hidden by a sphere; a box seen from a corner with its 9 visible
 * edges drawn, then all 12); sphere-silhouette coverage against an outline found independently by
 * casting a ray per pixel (whole, too large, half, half hidden); outline-ink fraction; speckle
 * (checkerboard, flat, isolated dots, 1- and 2-px lines); feature-to-flat ink ratio and the
 * per-pixel kinds (roof, ground, unseen ground, nothing). No GL context is needed (the camera
 * matrices are pure CPU), so this test always runs. */
#include "testutil.h"
#include "quality.h"

#include <pointnpr/render.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 320, H = 240 };

static const double OFF[3] = {500000.5, 4200000.25, 180.0}; /* a georeferenced-like scene origin */
static const double PI = 3.14159265358979323846;

static void empty_scene(pnpr_quality_scene *s)
{
    memset(s, 0, sizeof *s);
    memcpy(s->offset, OFF, sizeof OFF);
}

/* Ground [-10,10]^2 and a 2 x 2 x 2 box at the origin. */
static void box_scene(pnpr_quality_scene *s)
{
    empty_scene(s);
    s->has_ground = 1;
    s->ground_min[0] = s->ground_min[1] = -10;
    s->ground_max[0] = s->ground_max[1] = 10;
    s->building_count = 1;
    s->building[0].half[0] = s->building[0].half[1] = 1;
    s->building[0].wall_height = 2;
    pnpr_quality_scene_edges(s);
}

/* A look-at camera (scene-local eye and target) as the renderer's matrices. */
static void make_view(const double eye[3], const double target[3], float fov, pnpr_quality_view *v)
{
    pnpr_camera c;
    memset(&c, 0, sizeof c);
    for (int a = 0; a < 3; a++) { c.eye[a] = OFF[a] + eye[a]; c.target[a] = OFF[a] + target[a]; }
    c.up[2] = 1;
    c.fov_y_deg = fov;
    c.near_plane = 0.1f;
    c.far_plane = 200;
    pnpr_camera_matrices m;
    CHECK_STATUS(pnpr_camera_matrices_from_camera(&c, NULL, W, H, &m, NULL), PNPR_OK);
    memcpy(v->view, m.view, sizeof v->view);
    memcpy(v->projection, m.projection, sizeof v->projection);
    v->width = W;
    v->height = H;
}

static void proj(const pnpr_quality_view *v, const double p[3], double *x, double *y)
{
    double w[3] = {OFF[0] + p[0], OFF[1] + p[1], OFF[2] + p[2]};
    CHECK(pnpr_quality_project(v, w, x, y));
}

static void fill(uint8_t *px, int r, int g, int b)
{
    for (int i = 0; i < W * H; i++) { px[4 * i] = (uint8_t)r; px[4 * i + 1] = (uint8_t)g; px[4 * i + 2] = (uint8_t)b; px[4 * i + 3] = 255; }
}

static void dot(uint8_t *px, int x, int y, int grey)
{
    if (x < 0 || y < 0 || x >= W || y >= H) return;
    uint8_t *p = px + 4 * ((size_t)y * W + x);
    p[0] = p[1] = p[2] = (uint8_t)grey;
}

/* Inks the pixels under the projected segment a-b (scene-local) between fractions f0 and f1 of
 * its screen length, shifted by (dx, dy) px: 1-px line, 0.25 px steps. */
static void draw(uint8_t *px, const pnpr_quality_view *v, const double a[3], const double b[3], double dx, double dy,
                 double f0, double f1)
{
    double xa, ya, xb, yb;
    proj(v, a, &xa, &ya);
    proj(v, b, &xb, &yb);
    int n = (int)ceil(hypot(xb - xa, yb - ya) / 0.25);
    for (int i = 0; i <= n; i++) {
        double t = n ? (double)i / n : 0;
        if (t < f0 || t > f1) continue;
        dot(px, (int)floor(xa + t * (xb - xa) + dx), (int)floor(ya + t * (yb - ya) + dy), 0);
    }
}

static pnpr_quality_edge_figures edges(const pnpr_quality_scene *s, const pnpr_quality_view *v, const uint8_t *px,
                                       const pnpr_quality_segment *seg, size_t n)
{
    pnpr_quality_image im = {px, W, H};
    pnpr_quality_edge_figures r;
    memset(&r, 0, sizeof r);
    CHECK_STATUS(pnpr_quality_edges(s, v, &im, seg, n, NULL, 0, NULL, &r), PNPR_OK);
    return r;
}

static void test_projection(void)
{
    pnpr_quality_view v;
    static const double eye[3] = {0, -5, 0}, target[3] = {0, 0, 0};
    make_view(eye, target, 40, &v);
    double x, y, t = tan(20 * PI / 180);
    double centre[3] = {0, 0, 0}, right[3] = {5 * t * W / H, 0, 0}, top[3] = {0, 0, 5 * t};
    proj(&v, centre, &x, &y);
    CHECK_NEAR(x, W / 2.0, 1e-6);
    CHECK_NEAR(y, H / 2.0, 1e-6);
    proj(&v, right, &x, &y);
    CHECK_NEAR(x, W, 1e-6);
    proj(&v, top, &x, &y);
    CHECK_NEAR(y, 0, 1e-6);
    double behind[3] = {OFF[0], OFF[1] - 10, OFF[2]};
    CHECK(!pnpr_quality_project(&v, behind, &x, &y));
}

/* One segment, nothing in the scene: every sample is visible. */
static void test_segment(void)
{
    pnpr_quality_scene s;
    empty_scene(&s);
    pnpr_quality_view v;
    static const double eye[3] = {0, -5, 0}, target[3] = {0, 0, 0};
    make_view(eye, target, 40, &v);
    pnpr_quality_segment seg;
    memset(&seg, 0, sizeof seg);
    seg.a[0] = -1; seg.b[0] = 1;
    uint8_t *px = malloc(W * H * 4);
    fill(px, 255, 255, 255);
    pnpr_quality_edge_figures r = edges(&s, &v, px, &seg, 1);
    CHECK(r.coverage == 0 && r.precision == 0 && r.ink_pixels == 0);
    double xa, ya, xb, yb;
    proj(&v, seg.a, &xa, &ya);
    proj(&v, seg.b, &xb, &yb);
    CHECK_MSG(r.visible_samples == r.samples && r.samples == (size_t)ceil((xb - xa) / 0.5) + 1,
              "%zu samples over %.1f px", r.samples, xb - xa);
    draw(px, &v, seg.a, seg.b, 0, 0, 0, 1); /* exactly on the edge */
    r = edges(&s, &v, px, &seg, 1);
    CHECK_NEAR(r.coverage, 1, 0);
    CHECK_NEAR(r.precision, 1, 0);
    size_t line_ink = r.ink_pixels;
    for (int y = 10; y < 20; y++) /* 100 stray ink pixels far from the edge */
        for (int x = 10; x < 20; x++) dot(px, x, y, 0);
    r = edges(&s, &v, px, &seg, 1);
    CHECK_NEAR(r.coverage, 1, 0);
    CHECK_NEAR(r.precision, (double)line_ink / (double)(line_ink + 100), 1e-12);
    fill(px, 255, 255, 255);
    draw(px, &v, seg.a, seg.b, 0, 1.5, 0, 1); /* 1.5 px off: still within 2 px */
    r = edges(&s, &v, px, &seg, 1);
    CHECK_NEAR(r.coverage, 1, 0);
    CHECK_NEAR(r.precision, 1, 0);
    fill(px, 255, 255, 255);
    draw(px, &v, seg.a, seg.b, 0, 5, 0, 1); /* 5 px off */
    r = edges(&s, &v, px, &seg, 1);
    CHECK_NEAR(r.coverage, 0, 0);
    CHECK_NEAR(r.precision, 0, 0);
    fill(px, 255, 255, 255);
    draw(px, &v, seg.a, seg.b, 0, 0, 0, 0.5); /* half of it (plus the 2 px reach at its end) */
    r = edges(&s, &v, px, &seg, 1);
    CHECK_NEAR(r.coverage, 0.5 + 2 / (xb - xa), 0.01);
    CHECK_NEAR(r.precision, 1, 0);
    /* a sphere between the eye and the right part: x in [0.332, 1] of the segment is hidden */
    s.sphere_count = 1;
    s.sphere[0].centre[0] = 0.5; s.sphere[0].centre[1] = -2; s.sphere[0].radius = 0.3;
    double a0 = atan2(0.5, 3) - asin(0.3 / hypot(0.5, 3)), hidden_from = 5 * tan(a0);
    fill(px, 255, 255, 255);
    draw(px, &v, seg.a, seg.b, 0, 0, 0, 1);
    r = edges(&s, &v, px, &seg, 1);
    CHECK_NEAR((double)r.visible_samples / (double)r.samples, (hidden_from + 1) / 2, 0.01);
    CHECK_NEAR(r.coverage, 1, 0);
    CHECK_NEAR(r.precision, (hidden_from + 1) / 2, 0.03); /* the ink over the hidden part is not near */
    free(px);
}

/* A box seen from above its corner (1, -1): 4 top edges, 3 vertical edges and the 2 foot edges of
 * the two faces towards the eye are visible; the vertical edge (-1, 1) and 2 foot edges are not. */
static void test_box(void)
{
    pnpr_quality_scene s;
    box_scene(&s);
    CHECK(s.edge_count == 12);
    pnpr_quality_view v;
    static const double eye[3] = {6, -5, 7}, target[3] = {0, 0, 1};
    make_view(eye, target, 40, &v);
    uint8_t *px = malloc(W * H * 4);
    fill(px, 255, 255, 255);
    size_t expected = 0, nvis = 0;
    for (size_t i = 0; i < s.edge_count; i++) {
        const pnpr_quality_segment *e = &s.edge[i];
        int hidden = (e->kind == PNPR_QUALITY_EDGE_CORNER && e->a[0] < 0 && e->a[1] > 0) ||
                     (e->kind == PNPR_QUALITY_EDGE_FOOT && ((e->a[0] < 0 && e->b[0] < 0) || (e->a[1] > 0 && e->b[1] > 0)));
        if (hidden) continue;
        double xa, ya, xb, yb;
        proj(&v, e->a, &xa, &ya);
        proj(&v, e->b, &xb, &yb);
        expected += (size_t)ceil(hypot(xb - xa, yb - ya) / 0.5) + 1;
        draw(px, &v, e->a, e->b, 0, 0, 0, 1);
        nvis++;
    }
    CHECK(nvis == 9);
    pnpr_quality_image im = {px, W, H};
    pnpr_quality_edge_figures r, all;
    CHECK_STATUS(pnpr_quality_line_figures(&s, &v, &im, NULL, &r, &all), PNPR_OK);
    CHECK_NEAR(r.coverage, 1, 0);
    CHECK_NEAR(r.precision, 1, 0);
    CHECK_MSG(fabs((double)r.visible_samples - (double)expected) <= 0.03 * (double)expected,
              "visible samples %zu, expected about %zu (of %zu)", r.visible_samples, expected, r.samples);
    CHECK(r.samples > r.visible_samples + 100);
    CHECK(all.coverage < 0.8 && all.visible_samples > r.visible_samples); /* the ground border is not inked */
    for (size_t i = 0; i < s.edge_count; i++) draw(px, &v, s.edge[i].a, s.edge[i].b, 0, 0, 0, 1); /* hidden ones too */
    CHECK_STATUS(pnpr_quality_line_figures(&s, &v, &im, NULL, &r, NULL), PNPR_OK);
    CHECK_NEAR(r.coverage, 1, 0);
    CHECK_MSG(r.precision < 0.9 && r.precision > 0.5, "precision with hidden edges drawn: %g", r.precision);
    free(px);
}

/* Pixels whose ray (computed here from eye, target, fov) meets sphere (c, rad): an outline found
 * independently of the library. */
static void disk(const double eye[3], const double target[3], double fov, const double c[3], double rad, uint8_t *in)
{
    double f[3], l = 0, r[3], u[3];
    for (int a = 0; a < 3; a++) { f[a] = target[a] - eye[a]; l += f[a] * f[a]; }
    for (int a = 0; a < 3; a++) f[a] /= sqrt(l);
    r[0] = f[1]; r[1] = -f[0]; r[2] = 0; /* f x (0, 0, 1) */
    l = hypot(r[0], r[1]);
    r[0] /= l; r[1] /= l;
    u[0] = r[1] * f[2] - r[2] * f[1]; u[1] = r[2] * f[0] - r[0] * f[2]; u[2] = r[0] * f[1] - r[1] * f[0];
    double t = tan(0.5 * fov * PI / 180);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double x = (2 * (i + 0.5) / W - 1) * t * W / H, y = (1 - 2 * (j + 0.5) / H) * t, d[3], oc[3], dd = 0, b = 0, cc = 0;
            for (int a = 0; a < 3; a++) { d[a] = f[a] + x * r[a] + y * u[a]; oc[a] = eye[a] - c[a]; dd += d[a] * d[a]; b += d[a] * oc[a]; cc += oc[a] * oc[a]; }
            in[j * W + i] = b * b - dd * (cc - rad * rad) >= 0;
        }
}

/* Inks the disk's boundary pixels (inside, with a 4-neighbour outside) with y in [y0, y1). */
static void ink_boundary(uint8_t *px, const uint8_t *in, int y0, int y1)
{
    for (int j = y0; j < y1; j++)
        for (int i = 0; i < W; i++) {
            if (!in[j * W + i]) continue;
            int edge = i == 0 || j == 0 || i == W - 1 || j == H - 1 || !in[j * W + i - 1] || !in[j * W + i + 1] ||
                       !in[(j - 1) * W + i] || !in[(j + 1) * W + i];
            if (edge) dot(px, i, j, 0);
        }
}

static pnpr_quality_edge_figures silhouette(const pnpr_quality_scene *s, const pnpr_quality_view *v, const uint8_t *px)
{
    pnpr_quality_image im = {px, W, H};
    pnpr_quality_edge_figures r;
    memset(&r, 0, sizeof r);
    CHECK_STATUS(pnpr_quality_sphere_silhouette(s, 0, v, &im, NULL, &r), PNPR_OK);
    return r;
}

static void test_sphere(void)
{
    pnpr_quality_scene s;
    empty_scene(&s);
    s.sphere_count = 1;
    s.sphere[0].centre[2] = 1;
    s.sphere[0].radius = 1;
    static const double eye[3] = {0, -6, 1}, target[3] = {0, 0, 1};
    pnpr_quality_view v;
    make_view(eye, target, 40, &v);
    uint8_t *px = malloc(W * H * 4), *in = malloc(W * H);
    disk(eye, target, 40, s.sphere[0].centre, 1, in);
    fill(px, 255, 255, 255);
    ink_boundary(px, in, 0, H);
    pnpr_quality_edge_figures r = silhouette(&s, &v, px);
    CHECK_NEAR(r.coverage, 1, 0);
    CHECK_NEAR(r.precision, 1, 0);
    CHECK(r.visible_samples == r.samples && r.samples > 1000);
    fill(px, 255, 255, 255);
    ink_boundary(px, in, 0, H / 2); /* the upper half */
    r = silhouette(&s, &v, px);
    CHECK_NEAR(r.coverage, 0.5, 0.02);
    disk(eye, target, 40, s.sphere[0].centre, 1.15, in); /* an outline about 9 px too large */
    fill(px, 255, 255, 255);
    ink_boundary(px, in, 0, H);
    r = silhouette(&s, &v, px);
    CHECK_NEAR(r.coverage, 0, 0);
    /* a wall in front whose top is at the eye's height hides exactly the lower half */
    s.building_count = 1;
    s.building[0].centre[1] = -2.5;
    s.building[0].half[0] = 3; s.building[0].half[1] = 0.3;
    s.building[0].wall_height = 1;
    disk(eye, target, 40, s.sphere[0].centre, 1, in);
    fill(px, 255, 255, 255);
    ink_boundary(px, in, 0, H);
    r = silhouette(&s, &v, px);
    CHECK_NEAR((double)r.visible_samples / (double)r.samples, 0.5, 0.01);
    CHECK_NEAR(r.coverage, 1, 0);
    s.sphere[0].centre[1] = -6; /* the eye inside the sphere: no silhouette */
    pnpr_quality_image im = {px, W, H};
    CHECK_STATUS(pnpr_quality_sphere_silhouette(&s, 0, &v, &im, NULL, &r), PNPR_ERR_NUMERIC);
    CHECK_STATUS(pnpr_quality_sphere_silhouette(&s, 1, &v, &im, NULL, &r), PNPR_ERR_INVALID_ARGUMENT);
    free(in);
    free(px);
}

static void test_silhouette_count(void)
{
    pnpr_quality_scene s;
    box_scene(&s);
    s.tree_count = 2;
    for (int i = 0; i < 2; i++) {
        s.tree[i].base[0] = 4 * i - 2; s.tree[i].base[1] = 5;
        s.tree[i].trunk_radius = 0.2; s.tree[i].trunk_height = 2; s.tree[i].crown_centre_z = 3; s.tree[i].crown_radius = 1.2;
    }
    s.sphere_count = 1;
    s.sphere[0].centre[0] = 4; s.sphere[0].radius = 0.8;
    pnpr_quality_view v;
    static const double eye[3] = {6, -5, 7}, target[3] = {0, 0, 1};
    make_view(eye, target, 40, &v);
    CHECK(pnpr_quality_silhouettes(&s, &v, 0, NULL, 0) == 4 + 2 * 2 + 3 * 256);
    pnpr_quality_segment seg[60];
    CHECK(pnpr_quality_silhouettes(&s, &v, 16, seg, 10) == 4 + 4 + 48); /* too small: the size it needs */
    CHECK(pnpr_quality_silhouettes(&s, &v, 16, seg, 60) == 56);
    /* trunk lines: tangent to the trunk as seen from the eye */
    for (int k = 4; k < 8; k++) {
        const pnpr_quality_tree *t = &s.tree[(k - 4) / 2];
        double rx = seg[k].a[0] - t->base[0], ry = seg[k].a[1] - t->base[1];
        CHECK_NEAR(hypot(rx, ry), t->trunk_radius, 1e-12);
        CHECK_NEAR(rx * (eye[0] - seg[k].a[0]) + ry * (eye[1] - seg[k].a[1]), 0, 1e-9);
        CHECK_NEAR(seg[k].b[2] - seg[k].a[2], t->trunk_height, 1e-12);
    }
    /* circle chords: their ends on the sphere, tangent to the eye ray */
    const pnpr_quality_segment *c = &seg[8 + 32];
    double n[3], e[3], dn = 0, de = 0;
    for (int a = 0; a < 3; a++) { n[a] = c->a[a] - s.sphere[0].centre[a]; e[a] = eye[a] - c->a[a]; dn += n[a] * n[a]; de += n[a] * e[a]; }
    CHECK_NEAR(sqrt(dn), 0.8, 1e-12);
    CHECK_NEAR(de, 0, 1e-9);
}

static void test_outline_ink(void)
{
    uint8_t *px = malloc(W * H * 4);
    static const uint8_t ink[3] = {20, 20, 26};
    double f;
    size_t drawn;
    fill(px, 255, 255, 255);
    CHECK_STATUS(pnpr_quality_outline_ink(&(pnpr_quality_image){px, W, H}, ink, NULL, &f, &drawn), PNPR_OK);
    CHECK(f == 0 && drawn == 0);
    for (int y = 0; y < 40; y++)
        for (int x = 0; x < 50; x++) {
            uint8_t *p = px + 4 * (y * W + x);
            int k = y < 20 && x < 25 ? 0 : (y >= 20 && x < 10 ? 1 : 2); /* 500 ink, 200 near-ink, the rest colour */
            static const uint8_t c[3][3] = {{20, 20, 26}, {35, 30, 50}, {200, 100, 50}};
            memcpy(p, c[k], 3);
        }
    CHECK_STATUS(pnpr_quality_outline_ink(&(pnpr_quality_image){px, W, H}, ink, NULL, &f, &drawn), PNPR_OK);
    CHECK(drawn == 2000);
    CHECK_NEAR(f, 700.0 / 2000.0, 1e-12);
    pnpr_quality_options o;
    memset(&o, 0, sizeof o);
    o.ink_distance = 0.05f; /* 12.75 levels: the near-ink (distance 29) no longer counts */
    CHECK_STATUS(pnpr_quality_outline_ink(&(pnpr_quality_image){px, W, H}, ink, &o, &f, NULL), PNPR_OK);
    CHECK_NEAR(f, 0.25, 1e-12);
    CHECK_STATUS(pnpr_quality_outline_ink(&(pnpr_quality_image){NULL, W, H}, ink, NULL, &f, NULL), PNPR_ERR_INVALID_ARGUMENT);
    free(px);
}

static double speckle(const uint8_t *px)
{
    double f = -1;
    CHECK_STATUS(pnpr_quality_speckle(&(pnpr_quality_image){px, W, H}, NULL, &f), PNPR_OK);
    return f;
}

static void test_speckle(void)
{
    uint8_t *px = malloc(W * H * 4);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) dot(px, x, y, (x + y) % 2 ? 255 : 0);
    CHECK_NEAR(speckle(px), 1, 0); /* 1-px checkerboard: every drawn pixel */
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) dot(px, x, y, ((x / 2) + (y / 2)) % 2 ? 255 : 0);
    CHECK_NEAR(speckle(px), 0, 0); /* 2-px checkerboard: each pixel has an equal neighbour on both axes */
    fill(px, 255, 255, 255);
    CHECK_NEAR(speckle(px), 0, 0); /* nothing drawn */
    fill(px, 180, 40, 40);
    CHECK_NEAR(speckle(px), 0, 0); /* flat colour */
    for (int k = 0; k < 10; k++) dot(px, 20 + 25 * k, 30 + 15 * k, 0);
    CHECK_NEAR(speckle(px), 10.0 / (W * H), 1e-15);
    fill(px, 255, 255, 255);
    for (int x = 0; x < W; x++) dot(px, x, 100, 0);
    CHECK_NEAR(speckle(px), 1, 0); /* a 1-px line differs from both pixels across it */
    for (int x = 0; x < W; x++) dot(px, x, 101, 0);
    CHECK_NEAR(speckle(px), 0, 0); /* a 2-px line does not */
    fill(px, 200, 200, 200);
    for (int x = 0; x < W; x++) dot(px, x, 0, 0); /* top row: its one neighbour stands for both */
    CHECK_NEAR(speckle(px), (double)W / (W * H), 1e-15);
    free(px);
}

/* Feature-to-flat ratio on the box scene, scanned from (0, -8, 2): object pixels (and 3 px around
 * them) darkness 0.8, the rest 0.2, so every pixel near a crease is 0.8 and open ground 0.2. */
static void test_tone(void)
{
    pnpr_quality_scene s;
    box_scene(&s);
    s.scanner_count = 1;
    s.scanner[0][1] = -8; s.scanner[0][2] = 2;
    s.elevation_min_deg = -90; s.elevation_max_deg = 90; s.max_range = 100;
    pnpr_quality_view v;
    static const double eye[3] = {0, -14, 10}, target[3] = {0, 0, 0};
    make_view(eye, target, 50, &v);
    uint8_t *kind = malloc(W * H), *all = malloc(W * H), *px = malloc(W * H * 4);
    CHECK_STATUS(pnpr_quality_kind_image(&s, &v, 1, kind), PNPR_OK);
    CHECK_STATUS(pnpr_quality_kind_image(&s, &v, 0, all), PNPR_OK);
    double x, y;
    static const double roof[3] = {0, 0, 2}, front[3] = {0, -6, 0}, shadow[3] = {0, 6, 0};
    proj(&v, roof, &x, &y);
    CHECK(kind[(int)y * W + (int)x] == PNPR_QUALITY_ROOF);
    proj(&v, front, &x, &y);
    CHECK(kind[(int)y * W + (int)x] == PNPR_QUALITY_GROUND);
    proj(&v, shadow, &x, &y); /* seen by the camera over the box, hidden from the scanner by it */
    CHECK(kind[(int)y * W + (int)x] == PNPR_QUALITY_UNSEEN && all[(int)y * W + (int)x] == PNPR_QUALITY_GROUND);
    CHECK(kind[0] == PNPR_QUALITY_NOTHING); /* top left: beyond the ground */
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            int near = 0;
            for (int dj = -3; dj <= 3; dj++)
                for (int di = -3; di <= 3; di++) {
                    int u = i + di, w = j + dj;
                    if (u < 0 || w < 0 || u >= W || w >= H) continue;
                    uint8_t k = kind[w * W + u];
                    near |= k != PNPR_QUALITY_GROUND && k != PNPR_QUALITY_UNSEEN;
                }
            dot(px, i, j, near ? 51 : 204);
        }
    pnpr_quality_tone_figures t;
    CHECK_STATUS(pnpr_quality_tone(&s, &v, &(pnpr_quality_image){px, W, H}, NULL, &t), PNPR_OK);
    CHECK_NEAR(t.feature_darkness, 0.8, 1e-12);
    CHECK_NEAR(t.flat_darkness, 0.2, 1e-12);
    CHECK_NEAR(t.ratio, 4, 1e-9);
    CHECK(t.feature_pixels > 500 && t.flat_pixels > 5000);
    fill(px, 128, 128, 128);
    CHECK_STATUS(pnpr_quality_tone(&s, &v, &(pnpr_quality_image){px, W, H}, NULL, &t), PNPR_OK);
    CHECK_NEAR(t.ratio, 1, 1e-12);
    fill(px, 255, 255, 255); /* a blank page: no ink anywhere; the ratio's floor keeps it finite */
    CHECK_STATUS(pnpr_quality_tone(&s, &v, &(pnpr_quality_image){px, W, H}, NULL, &t), PNPR_OK);
    CHECK_NEAR(t.ratio, 0, 1e-12);
    s.scanner_count = 0; /* nothing scanned: no open ground */
    CHECK_STATUS(pnpr_quality_tone(&s, &v, &(pnpr_quality_image){px, W, H}, NULL, &t), PNPR_ERR_EMPTY);
    free(kind);
    free(all);
    free(px);
}

static void test_bad_input(void)
{
    pnpr_quality_scene s;
    box_scene(&s);
    pnpr_quality_view v;
    static const double eye[3] = {6, -5, 7}, target[3] = {0, 0, 1};
    make_view(eye, target, 40, &v);
    uint8_t *px = calloc(W * H * 4, 1);
    pnpr_quality_edge_figures r;
    pnpr_quality_image im = {px, W, H}, small = {px, W / 2, H};
    CHECK_STATUS(pnpr_quality_line_figures(&s, &v, &small, NULL, &r, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_quality_edges(&s, &v, &im, NULL, 3, NULL, 0, NULL, &r), PNPR_ERR_INVALID_ARGUMENT);
    v.view[0] = NAN;
    CHECK_STATUS(pnpr_quality_line_figures(&s, &v, &im, NULL, &r, NULL), PNPR_ERR_NUMERIC);
    double f;
    CHECK_STATUS(pnpr_quality_speckle(&small, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    small.width = 0;
    CHECK_STATUS(pnpr_quality_speckle(&small, NULL, &f), PNPR_ERR_INVALID_ARGUMENT);
    free(px);
}

int main(void)
{
    test_projection();
    test_segment();
    test_box();
    test_sphere();
    test_silhouette_count();
    test_outline_ink();
    test_speckle();
    test_tone();
    test_bad_input();
    return pnpr_test_finish("test_quality_metrics");
}
