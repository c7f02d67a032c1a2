/* Outlines (silhouettes and occluding contours from the visibility mask), known answers:
 *   - a sphere in `lines` (no profile lines): ink on the projected silhouette circle all around
 *     (on the visibility mask's boundary: at most one mask disk outside it), none inside 0.75 of
 *     its radius, the background outside it; the same at a tenth of the
 *     density (random sampling, so with sampling holes) and with holes cut into the surface;
 *   - a sphere in front of a wall: the contour against the wall is inked, the open wall is not;
 *   - width: a wider outline puts down more ink; outline off: only the background;
 *   - a tiled snapshot gives the same outline as one frame.
 * Exits 77 (skipped) when this machine has no headless EGL / GL 3.3. */
#include "testutil.h"

#include <pointnpr/render.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 320, H = 240 };
static const double PI = 3.14159265358979323846;
static const double off[3] = {4500000.5, 5300000.25, 310.0}; /* georeferenced-like */
static const double R = 1.0, D = 5.0;                        /* sphere radius, eye distance */

static int inked(const uint8_t *p) { return p[0] < 128 && p[1] < 128 && p[2] < 128; }
static int is_bg(const uint8_t *p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }

/* A sphere of n points (uniform random on the surface, normals = positions), centred at off,
 * with `holes` caps of angular radius `hole_rad` removed. */
static void sphere(pnpr_cloud *c, size_t n, int holes, double hole_rad, uint64_t seed)
{
    CHECK_STATUS(pnpr_test_sphere(c, n, R, off, seed), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_normals(c), PNPR_OK);
    pnpr_test_rng rng = {seed + 1};
    double centres[32][3];
    for (int h = 0; h < holes && h < 32; h++) { /* hole centres on the visible half (y < 0) */
        double z = 1.6 * pnpr_test_uniform(&rng) - 0.8, a = PI * (1 + pnpr_test_uniform(&rng));
        double rr = sqrt(1 - z * z);
        centres[h][0] = rr * cos(a); centres[h][1] = rr * sin(a); centres[h][2] = z;
    }
    size_t m = 0;
    for (size_t i = 0; i < c->count; i++) {
        const float *p = c->xyz + 3 * i;
        int keep = 1;
        for (int h = 0; h < holes && h < 32 && keep; h++)
            keep = p[0] * centres[h][0] + p[1] * centres[h][1] + p[2] * centres[h][2] < cos(hole_rad);
        if (!keep) continue;
        memmove(c->xyz + 3 * m, p, 3 * sizeof *p);
        if (c->src_xyz) memmove(c->src_xyz + 3 * m, c->src_xyz + 3 * i, 3 * sizeof(double));
        for (int a = 0; a < 3; a++) c->normal[3 * m + a] = c->xyz[3 * m + a] / (float)R;
        m++;
    }
    c->count = m;
}

static pnpr_camera front_camera(void)
{
    pnpr_camera cam = {{0}, {0}, {0, 0, 1}, 40, 0, 0};
    memcpy(cam.target, off, sizeof cam.target);
    memcpy(cam.eye, off, sizeof cam.eye);
    cam.eye[1] -= D;
    return cam;
}

/* The silhouette circle's radius in pixels (centred in the image). */
static double silhouette_px(void) { return tan(asin(R / D)) / tan(20.0 * PI / 180.0) * 0.5 * H; }

static pnpr_status draw(pnpr_renderer *r, const pnpr_draw_options *o, int max_tile, uint8_t *px)
{
    pnpr_camera cam = front_camera();
    pnpr_snapshot_options so = {0};
    so.max_tile_size = max_tile;
    pnpr_error err = {0};
    pnpr_status st = pnpr_renderer_snapshot(r, &cam, o, W, H, &so, px, NULL, &err);
    if (st != PNPR_OK) fprintf(stderr, "snapshot: %s\n", err.message);
    return st;
}

typedef struct ring_stats {
    int rays;            /* of 90 rays, those with ink within [rs - 3, rs + 3 + grow] */
    size_t inner_ink;    /* ink pixels inside 0.75 rs */
    size_t inner;        /* pixels inside 0.75 rs */
    size_t outer_non_bg; /* non-background pixels outside rs + 8 + grow */
    size_t ink;          /* all ink pixels */
    double offset;       /* mean over the rays of the ink's centre minus rs (px) */
} ring_stats;

/* The outline lies on the visibility mask's boundary: up to one mask disk (1.5 times the
 * distance to the 4th neighbour, about 1.8 spacings) outside the outermost points. `grow` is
 * that in pixels for n points on the sphere (spacing sqrt(4 pi R^2 / n)), with some slack. */
static double mask_grow_px(size_t n, double rs)
{
    return 2.5 * sqrt(4 * PI * R * R / (double)n) / R * rs;
}

static ring_stats ring(const uint8_t *px, double rs, double grow, int check_outer)
{
    ring_stats s;
    memset(&s, 0, sizeof s);
    double cx = 0.5 * W, cy = 0.5 * H, off_sum = 0;
    for (int k = 0; k < 90; k++) {
        double a = 2 * PI * k / 90, tsum = 0;
        int found = 0;
        for (double t = rs - 3; t <= rs + 3 + grow; t += 0.25) {
            int x = (int)floor(cx + t * cos(a)), y = (int)floor(cy + t * sin(a));
            if (x >= 0 && y >= 0 && x < W && y < H && inked(px + 4 * ((size_t)y * W + x))) { found++; tsum += t; }
        }
        s.rays += found > 0;
        if (found) off_sum += tsum / found - rs;
    }
    s.offset = s.rays ? off_sum / s.rays : 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * W + x);
            double dx = x + 0.5 - cx, dy = y + 0.5 - cy, d = sqrt(dx * dx + dy * dy);
            s.ink += inked(p);
            if (d < 0.75 * rs) { s.inner++; s.inner_ink += inked(p); }
            if (check_outer && d > rs + 8 + grow) s.outer_non_bg += !is_bg(p);
        }
    return s;
}

static void lines_options(pnpr_draw_options *o)
{
    memset(o, 0, sizeof *o);
    o->style = PNPR_STYLE_LINES;
    o->background[0] = o->background[1] = o->background[2] = o->background[3] = 1;
}

static void test_sphere_silhouette(pnpr_renderer *r, uint8_t *px)
{
    static const struct { size_t n; int holes; double rad; const char *what; } cases[] = {
        {40000, 0, 0, "dense"}, {4000, 0, 0, "a tenth of the density"}, {40000, 12, 0.09, "12 holes"}};
    double rs = silhouette_px();
    pnpr_draw_options o;
    lines_options(&o);
    for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
        pnpr_cloud c = {0};
        sphere(&c, cases[t].n, cases[t].holes, cases[t].rad, 11 + t);
        CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
        CHECK_STATUS(draw(r, &o, 0, px), PNPR_OK);
        ring_stats s = ring(px, rs, mask_grow_px(cases[t].n, rs), 1);
        fprintf(stderr, "lines sphere, %s: %d/90 rays inked at r = %.1f px (ink centred %+.2f px from it), %zu of %zu inner px inked, %zu outside\n",
                cases[t].what, s.rays, rs, s.offset, s.inner_ink, s.inner, s.outer_non_bg);
        /* the silhouette where the sphere's outline is, at any density: the band (2.5 px) is
         * centred on it within 1.5 px */
        CHECK_MSG(fabs(s.offset) <= 1.5, "%s: the ink is centred %+.2f px from the silhouette", cases[t].what, s.offset);
        CHECK_MSG(s.rays >= 86, "%s: %d of 90 rays find the silhouette", cases[t].what, s.rays);
        CHECK_MSG(s.inner > 5000 && s.inner_ink * 200 <= s.inner, "%s: %zu ink pixels inside", cases[t].what, s.inner_ink);
        CHECK_MSG(s.outer_non_bg == 0, "%s: %zu pixels outside the silhouette", cases[t].what, s.outer_non_bg);
        char path[600];
        snprintf(path, sizeof path, "%s/outline_sphere_%zu.png", PNPR_TEST_SCRATCH, t);
        CHECK_STATUS(pnpr_write_png(path, px, W, H, 0, NULL), PNPR_OK);
        pnpr_cloud_free(&c);
    }
}

/* The sphere in front of a wall (the plane y = 3 behind it, normals towards the eye): the
 * contour between two surfaces is inked; the wall away from the sphere and its border is not. */
static void test_contour_on_wall(pnpr_renderer *r, uint8_t *px)
{
    pnpr_cloud s = {0}, wall = {0};
    sphere(&s, 40000, 0, 0, 21);
    const size_t nx = 300, nz = 220;
    const double h = 0.03;
    double woff[3] = {off[0] - 0.5 * h * (nx - 1), off[1] + 3.0, off[2] - 0.5 * h * (nz - 1)};
    CHECK_STATUS(pnpr_test_plane(&wall, nx, nz, h, woff), PNPR_OK); /* z = 0 plane: turn it to y */
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&c, s.count + wall.count), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_normals(&c), PNPR_OK);
    memcpy(c.origin, off, sizeof c.origin);
    for (size_t i = 0; i < s.count; i++)
        for (int a = 0; a < 3; a++) { c.xyz[3 * i + a] = s.xyz[3 * i + a]; c.normal[3 * i + a] = s.normal[3 * i + a]; }
    for (size_t i = 0; i < wall.count; i++) {
        float *p = c.xyz + 3 * (s.count + i);
        double wx = wall.origin[0] + wall.xyz[3 * i], wy = wall.origin[1] + wall.xyz[3 * i + 1];
        p[0] = (float)(wx - off[0]);
        p[1] = 3.0f;
        p[2] = (float)(woff[2] + (wy - woff[1]) - off[2]);
        c.normal[3 * (s.count + i) + 1] = -1;
    }
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    pnpr_draw_options o;
    lines_options(&o);
    CHECK_STATUS(draw(r, &o, 0, px), PNPR_OK);
    double rs = silhouette_px();
    ring_stats st = ring(px, rs, mask_grow_px(40000, rs), 0);
    /* ink on the open wall: farther than 6 px from the circle and inside the frame by 8 px (the
     * wall covers the whole frame) */
    size_t wall_px = 0, wall_ink = 0;
    for (int y = 8; y < H - 8; y++)
        for (int x = 8; x < W - 8; x++) {
            double dx = x + 0.5 - 0.5 * W, dy = y + 0.5 - 0.5 * H;
            if (fabs(sqrt(dx * dx + dy * dy) - rs) < 6 || sqrt(dx * dx + dy * dy) < rs) continue;
            wall_px++;
            wall_ink += inked(px + 4 * ((size_t)y * W + x));
        }
    fprintf(stderr, "sphere before a wall: %d/90 rays inked, %zu of %zu open-wall px inked, %zu inside\n",
            st.rays, wall_ink, wall_px, st.inner_ink);
    CHECK_MSG(st.rays >= 86, "contour on the wall: %d of 90 rays", st.rays);
    CHECK_MSG(wall_px > 20000 && wall_ink * 500 <= wall_px, "open wall: %zu of %zu pixels inked", wall_ink, wall_px);
    CHECK_MSG(st.inner_ink * 200 <= st.inner, "sphere before a wall: %zu ink pixels inside", st.inner_ink);
    char path[600];
    snprintf(path, sizeof path, "%s/outline_wall.png", PNPR_TEST_SCRATCH);
    CHECK_STATUS(pnpr_write_png(path, px, W, H, 0, NULL), PNPR_OK);
    pnpr_cloud_free(&s);
    pnpr_cloud_free(&wall);
    pnpr_cloud_free(&c);
}

/* Width, off, tiles, bad options. */
static void test_controls(pnpr_renderer *r, uint8_t *px)
{
    pnpr_cloud c = {0};
    sphere(&c, 40000, 0, 0, 31);
    CHECK_STATUS(pnpr_renderer_set_cloud(r, &c, NULL, NULL), PNPR_OK);
    double rs = silhouette_px();
    pnpr_draw_options o;
    lines_options(&o);
    CHECK_STATUS(draw(r, &o, 0, px), PNPR_OK);
    size_t ink_default = ring(px, rs, 0, 0).ink;
    o.outline_width = 6;
    CHECK_STATUS(draw(r, &o, 0, px), PNPR_OK);
    size_t ink_wide = ring(px, rs, 0, 0).ink;
    CHECK_MSG(ink_wide * 10 >= ink_default * 18, "width 6: %zu ink px, default 2.5: %zu", ink_wide, ink_default);
    uint8_t *tiled = malloc((size_t)W * H * 4);
    o.outline_width = 0;
    CHECK_STATUS(draw(r, &o, 0, px), PNPR_OK);
    CHECK_STATUS(draw(r, &o, 120, tiled), PNPR_OK); /* 120 px tiles, guard band inside */
    size_t differ = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) differ += inked(px + 4 * i) != inked(tiled + 4 * i);
    fprintf(stderr, "outline: ink %zu px (width 6: %zu), tiled vs one frame: %zu px differ\n", ink_default, ink_wide, differ);
    CHECK_MSG(differ * 100 <= ink_default, "tiled: %zu of %zu ink pixels differ", differ, ink_default);
    free(tiled);
    o.outline = -1;
    CHECK_STATUS(draw(r, &o, 0, px), PNPR_OK);
    size_t non_bg = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) non_bg += !is_bg(px + 4 * i);
    CHECK_MSG(non_bg == 0, "outline off, no profile lines: %zu pixels drawn", non_bg);
    o.outline = 2;
    CHECK_STATUS(draw(r, &o, 0, px), PNPR_ERR_INVALID_ARGUMENT);
    o.outline = 1;
    o.outline_width = 65;
    CHECK_STATUS(draw(r, &o, 0, px), PNPR_ERR_INVALID_ARGUMENT);
    o.outline_width = NAN;
    CHECK_STATUS(draw(r, &o, 0, px), PNPR_ERR_INVALID_ARGUMENT);
    /* the style defaults: outlines for lines and cartoon, none for the others (their width when asked) */
    float w = -1;
    CHECK(pnpr_style_outline_default(PNPR_STYLE_LINES, &w) == 1 && w == 2.5f);
    CHECK(pnpr_style_outline_default(PNPR_STYLE_CARTOON, &w) == 1 && w == 2.5f);
    CHECK(pnpr_style_outline_default(PNPR_STYLE_SKETCHY, &w) == 0 && w == 1.5f); /* off, 1.5 px when on */
    CHECK(pnpr_style_outline_default(PNPR_STYLE_POINTS, &w) == 0 && w == 2);
    CHECK(pnpr_style_outline_default(PNPR_STYLE_COUNT_, NULL) == 0);
    pnpr_cloud_free(&c);
}

int main(void)
{
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "test_render_outline: skipped: %s\n", err.message);
        return 77;
    }
    pnpr_renderer *r = NULL;
    CHECK_STATUS(pnpr_renderer_create(NULL, &r, &err), PNPR_OK);
    uint8_t *px = malloc((size_t)W * H * 4);
    if (r && px) {
        test_sphere_silhouette(r, px);
        test_contour_on_wall(r, px);
        test_controls(r, px);
    }
    free(px);
    pnpr_renderer_destroy(r);
    pnpr_gl_context_destroy(ctx);
    return pnpr_test_finish("test_render_outline");
}
