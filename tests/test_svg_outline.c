/* Outlines in the SVG export (pnpr_svg_options.outline), known answers, no GL: the paths of
 * <g id="outlines"> are parsed back from the file and compared with the projected silhouette
 * circle of a sphere (radius R at distance D on the view axis: rs = tan(asin(R/D)) / tan(fov/2)
 * x H/2 px around the drawing's centre):
 *   - a sphere seen from the front (40k points): every path vertex within 1.5 px of the circle,
 *     the paths within 1.5 px of it over >= 90 % of its circumference, on average within 0.5 px;
 *     sparse (4k points, disks of 8 px): within 0.6 disk radii, >= 80 %;
 *   - the sphere with 12 holes cut into it: as the dense one, and no path inside it;
 *   - the sphere in front of a wall: a closed path around it, no path on the open wall;
 *   - a grid-sampled cube without normals: the outline on its projected front edges (1.5 px);
 *   - outline off (or no occluders): no outlines group; the width reaches the group;
 *   - degenerate clouds (empty, one point, NaN points) give a valid drawing; bad options fail.
 * When rsvg-convert is installed, every drawing must also render. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <pointnpr/camera.h>
#include <pointnpr/lines.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { W = 400, H = 300, BINS = 360, MAX_PATHS = 4096, MAX_VERTS = 200000 };
static const double PI = 3.14159265358979323846;
static const double off[3] = {4500000.5, 5300000.25, 310.0}; /* georeferenced-like */
static const double R = 1.0, D = 5.0, FOV = 40.0;

/* Paths parsed from a drawing. */
typedef struct paths {
    size_t count, nv;
    size_t start[MAX_PATHS + 1];
    int closed[MAX_PATHS];
    double xy[2 * MAX_VERTS];
    int has_group;       /* <g id="outlines"> present */
    double stroke_width; /* its stroke-width */
} paths;

static int have_rsvg;

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static char *read_text(const char *path, size_t *r_len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, len = 0;
    char *s = malloc(cap + 1);
    while (s) {
        size_t got = fread(s + len, 1, cap - len, f);
        len += got;
        if (len < cap || cap >= ((size_t)64 << 20)) break; /* end of file, or 64 MB read */
        char *t = realloc(s, 2 * cap + 1);
        if (!t) { free(s); s = NULL; break; }
        s = t;
        cap *= 2;
    }
    fclose(f);
    if (s) s[len] = 0;
    *r_len = len;
    return s;
}

/* Parses "M x,y L x,y ... [Z]" into p (bounded by the attribute's end). */
static int parse_d(const char *d, const char *end, paths *p)
{
    if (p->count >= MAX_PATHS) return 0;
    p->start[p->count] = p->nv;
    p->closed[p->count] = 0;
    const char *s = d;
    while (s < end) {
        if (*s == 'M' || *s == 'L' || *s == ' ' || *s == ',') { s++; continue; }
        if (*s == 'Z') { p->closed[p->count] = 1; s++; continue; }
        char *e1, *e2;
        double x = strtod(s, &e1);
        if (e1 == s || e1 >= end || *e1 != ',') return 0;
        double y = strtod(e1 + 1, &e2);
        if (e2 == e1 + 1 || e2 > end || p->nv >= MAX_VERTS) return 0;
        p->xy[2 * p->nv] = x;
        p->xy[2 * p->nv + 1] = y;
        p->nv++;
        s = e2;
    }
    p->start[++p->count] = p->nv;
    return 1;
}

/* Reads the outlines group of an SVG file; 0 when the file is not a complete drawing. */
static int parse_svg(const char *path, paths *p)
{
    memset(p, 0, sizeof *p);
    size_t len = 0;
    char *s = read_text(path, &len);
    if (!s) return 0;
    int ok = strncmp(s, "<?xml", 5) == 0 && len >= 7 && strcmp(s + len - 7, "</svg>\n") == 0;
    const char *g = strstr(s, "<g id=\"outlines\"");
    if (ok && g) {
        p->has_group = 1;
        const char *gend = strstr(g, "</g>"), *sw = strstr(g, "stroke-width=\"");
        ok = gend != NULL && sw != NULL && sw < gend;
        if (ok) p->stroke_width = strtod(sw + 14, NULL);
        for (const char *q = ok ? strstr(g, "<path d=\"") : NULL; ok && q && q < gend; q = strstr(q + 1, "<path d=\"")) {
            const char *d = q + 9, *e = strchr(d, '"');
            ok = e && e < gend && parse_d(d, e, p);
        }
    }
    free(s);
    if (ok && have_rsvg) {
        char cmd[1400];
        snprintf(cmd, sizeof cmd, "rsvg-convert '%s' -o '%s.png'", path, path);
        ok = system(cmd) == 0;
    }
    return ok;
}

/* A sphere of n points (uniform random, normals = positions) centred at off, with `holes` caps
 * of angular radius hole_rad removed on the visible half (y < 0). */
static void sphere(pnpr_cloud *c, size_t n, int holes, double hole_rad, uint64_t seed)
{
    CHECK_STATUS(pnpr_test_sphere(c, n, R, off, seed), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_normals(c), PNPR_OK);
    pnpr_test_rng rng = {seed + 1};
    double centres[32][3];
    for (int h = 0; h < holes && h < 32; h++) {
        double z = 1.6 * pnpr_test_uniform(&rng) - 0.8, a = PI * (1 + pnpr_test_uniform(&rng));
        double rr = sqrt(1 - z * z);
        centres[h][0] = rr * cos(a); centres[h][1] = rr * sin(a); centres[h][2] = z;
    }
    size_t m = 0;
    for (size_t i = 0; i < c->count; i++) {
        const float *q = c->xyz + 3 * i;
        int keep = 1;
        for (int h = 0; h < holes && h < 32 && keep; h++)
            keep = q[0] * centres[h][0] + q[1] * centres[h][1] + q[2] * centres[h][2] < cos(hole_rad);
        if (!keep) continue;
        memmove(c->xyz + 3 * m, q, 3 * sizeof *q);
        if (c->src_xyz) memmove(c->src_xyz + 3 * m, c->src_xyz + 3 * i, 3 * sizeof(double));
        for (int a = 0; a < 3; a++) c->normal[3 * m + a] = c->xyz[3 * m + a] / (float)R;
        m++;
    }
    c->count = m;
}

static pnpr_camera front_camera(void)
{
    pnpr_camera cam = {{0}, {0}, {0, 0, 1}, (float)FOV, 0, 0};
    memcpy(cam.target, off, sizeof cam.target);
    memcpy(cam.eye, off, sizeof cam.eye);
    cam.eye[1] -= D;
    return cam;
}

static double silhouette_px(void) { return tan(asin(R / D)) / tan(0.5 * FOV * PI / 180.0) * 0.5 * H; }

/* The expected projected disk radius at the silhouette for n points: 1.5 x the mean distance to
 * the 4th nearest neighbour of a uniform sampling of density rho (Gamma(4.5) / Gamma(4) /
 * sqrt(pi rho)), at the depth of the limb (D^2 - R^2) / D. */
static double disk_px(size_t n)
{
    double rho = (double)n / (4 * PI * R * R), d4 = 1.9386 / sqrt(PI * rho);
    return 1.5 * d4 * (0.5 * H / tan(0.5 * FOV * PI / 180.0)) / ((D * D - R * R) / D);
}

typedef struct ring_fit {
    double max_dev;     /* largest |distance to the centre - rs| of a vertex near the circle */
    double mean_off;    /* mean signed (distance - rs) of those vertices */
    double coverage;    /* fraction of the circumference with a path within tol */
    size_t near, inner, outer; /* vertices within rs +- 6 px, inside it, outside it */
} ring_fit;

/* How the paths fit the circle of radius rs around the drawing's centre. Vertices farther than
 * 6 px from it count as inner / outer; coverage samples every segment at 0.25 px. */
static ring_fit fit_ring(const paths *p, double rs, double tol)
{
    ring_fit f;
    memset(&f, 0, sizeof f);
    static unsigned char bin[BINS];
    memset(bin, 0, sizeof bin);
    double cx = 0.5 * W, cy = 0.5 * H, sum = 0;
    for (size_t k = 0; k < p->count; k++) {
        size_t a = p->start[k], n = p->start[k + 1] - a;
        for (size_t i = 0; i < n; i++) {
            const double *u = p->xy + 2 * (a + i);
            double dev = hypot(u[0] - cx, u[1] - cy) - rs;
            if (fabs(dev) > 6) { f.inner += dev < 0; f.outer += dev > 0; continue; }
            f.near++;
            sum += dev;
            if (fabs(dev) > f.max_dev) f.max_dev = fabs(dev);
            if (i + 1 == n && !p->closed[k]) continue;
            const double *v = p->xy + 2 * (a + (i + 1) % n);
            double len = hypot(v[0] - u[0], v[1] - u[1]);
            for (double t = 0; t <= len && len < 1e4; t += 0.25) {
                double x = u[0] + (v[0] - u[0]) * t / len, y = u[1] + (v[1] - u[1]) * t / len;
                if (fabs(hypot(x - cx, y - cy) - rs) > tol) continue;
                int b = (int)floor((atan2(y - cy, x - cx) + PI) / (2 * PI) * BINS);
                bin[b < 0 ? 0 : b >= BINS ? BINS - 1 : b] = 1;
            }
        }
    }
    size_t covered = 0;
    for (int b = 0; b < BINS; b++) covered += bin[b];
    f.coverage = (double)covered / BINS;
    f.mean_off = f.near ? sum / (double)f.near : 0;
    return f;
}

static const char *scratch(const char *name)
{
    static char path[600];
    snprintf(path, sizeof path, "%s/%s", PNPR_TEST_SCRATCH, name);
    return path;
}

static pnpr_svg_options svg_options(const pnpr_cloud *occ)
{
    pnpr_svg_options so;
    memset(&so, 0, sizeof so);
    so.width = W;
    so.height = H;
    so.occluders = occ;
    so.background = 1;
    so.background_rgb[0] = so.background_rgb[1] = so.background_rgb[2] = 255;
    return so;
}

static paths P;

static void test_sphere(void)
{
    static const struct { size_t n; int holes; double rad; const char *what; } cases[] = {
        {40000, 0, 0, "dense"}, {4000, 0, 0, "sparse"}, {40000, 12, 0.09, "12 holes"}};
    pnpr_camera cam = front_camera();
    pnpr_polylines none = {0};
    double rs = silhouette_px();
    for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
        pnpr_cloud c = {0};
        sphere(&c, cases[t].n, cases[t].holes, cases[t].rad, 11 + t);
        pnpr_svg_options so = svg_options(&c);
        pnpr_error err = {0};
        const char *path = scratch(t == 0 ? "outline_sphere.svg" : t == 1 ? "outline_sphere_sparse.svg" : "outline_sphere_holes.svg");
        double t0 = now_seconds();
        CHECK_STATUS(pnpr_write_lines_svg(path, &none, &cam, &so, &err), PNPR_OK);
        double secs = now_seconds() - t0;
        CHECK(parse_svg(path, &P));
        /* 1.5 px, >= 90 %; with 4k points (disks of 8 px) the sampling's own gaps dent the mask's
         * boundary by up to about half a disk radius: 0.6 radii, >= 80 % within 1.5 px */
        int sparse = cases[t].n < 10000;
        double rd = disk_px(cases[t].n), tol = sparse ? 0.6 * rd : 1.5, min_cov = sparse ? 0.8 : 0.9;
        ring_fit f = fit_ring(&P, rs, 1.5);
        fprintf(stderr, "sphere, %s (%zu points, disks %.1f px): %zu paths, %zu vertices; rs %.1f px; vertices off the circle by "
                        "%+.2f px on average, at most %.2f px; %.1f %% of it within 1.5 px; %zu inside, %zu outside; %.3f s\n",
                cases[t].what, c.count, rd, P.count, P.nv, rs, f.mean_off, f.max_dev, 100 * f.coverage, f.inner, f.outer, secs);
        CHECK_MSG(P.has_group && P.count >= 1, "%s: no outline paths", cases[t].what);
        CHECK_MSG(fabs(f.mean_off) <= 0.5, "%s: the outline lies %+.2f px off the silhouette", cases[t].what, f.mean_off);
        CHECK_MSG(f.max_dev <= tol, "%s: a vertex %.2f px off the silhouette", cases[t].what, f.max_dev);
        CHECK_MSG(f.coverage >= min_cov, "%s: %.1f %% of the silhouette covered", cases[t].what, 100 * f.coverage);
        CHECK_MSG(f.inner == 0 && f.outer == 0, "%s: %zu vertices inside, %zu outside", cases[t].what, f.inner, f.outer);
        CHECK(fabs(P.stroke_width - 2.0) < 1e-9);
        pnpr_cloud_free(&c);
    }
}

/* The sphere in front of a wall (the plane y = 3 behind it, 9 x 6.6, normals towards the eye,
 * filling the drawing): its contour is a closed path around it; the open wall has none. */
static void test_contour_on_wall(void)
{
    pnpr_cloud s = {0}, wall = {0}, c = {0};
    sphere(&s, 40000, 0, 0, 21);
    const size_t nx = 300, nz = 220;
    const double h = 0.03;
    double woff[3] = {off[0] - 0.5 * h * (nx - 1), off[1] + 3.0, off[2] - 0.5 * h * (nz - 1)};
    CHECK_STATUS(pnpr_test_plane(&wall, nx, nz, h, woff), PNPR_OK); /* z = 0 plane: turned to y */
    CHECK_STATUS(pnpr_cloud_alloc(&c, s.count + wall.count), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_normals(&c), PNPR_OK);
    memcpy(c.origin, off, sizeof c.origin);
    memcpy(c.xyz, s.xyz, 3 * s.count * sizeof *c.xyz);
    memcpy(c.normal, s.normal, 3 * s.count * sizeof *c.normal);
    for (size_t i = 0; i < wall.count; i++) {
        float *q = c.xyz + 3 * (s.count + i);
        double wx = wall.origin[0] + wall.xyz[3 * i], wy = wall.origin[1] + wall.xyz[3 * i + 1];
        q[0] = (float)(wx - off[0]);
        q[1] = 3.0f;
        q[2] = (float)(woff[2] + (wy - woff[1]) - off[2]);
        c.normal[3 * (s.count + i) + 1] = -1;
    }
    pnpr_camera cam = front_camera();
    pnpr_polylines none = {0};
    pnpr_svg_options so = svg_options(&c);
    pnpr_error err = {0};
    const char *path = scratch("outline_wall.svg");
    CHECK_STATUS(pnpr_write_lines_svg(path, &none, &cam, &so, &err), PNPR_OK);
    CHECK(parse_svg(path, &P));
    double rs = silhouette_px();
    ring_fit f = fit_ring(&P, rs, 1.5);
    /* a closed path whose every vertex is near the circle, going all around it */
    int closed_around = 0;
    static paths one;
    for (size_t k = 0; k < P.count; k++) {
        if (!P.closed[k]) continue;
        one.count = 1;
        one.start[0] = 0;
        one.start[1] = P.start[k + 1] - P.start[k];
        one.closed[0] = 1;
        memcpy(one.xy, P.xy + 2 * P.start[k], 2 * one.start[1] * sizeof *one.xy);
        ring_fit g = fit_ring(&one, rs, 1.5);
        closed_around |= g.inner == 0 && g.outer == 0 && g.coverage >= 0.9;
    }
    /* vertices on the open wall: farther than 6 px from the circle, 8 px inside the border */
    size_t on_wall = 0;
    for (size_t i = 0; i < P.nv; i++) {
        double x = P.xy[2 * i], y = P.xy[2 * i + 1];
        if (x > 8 && y > 8 && x < W - 8 && y < H - 8 && hypot(x - 0.5 * W, y - 0.5 * H) > rs + 6) on_wall++;
    }
    fprintf(stderr, "sphere before a wall: %zu paths; vertices off the circle by %+.2f px on average, at most %.2f px; "
                    "%.1f %% covered; a closed path around it: %s; %zu vertices inside, %zu on the open wall\n",
            P.count, f.mean_off, f.max_dev, 100 * f.coverage, closed_around ? "yes" : "no", f.inner, on_wall);
    CHECK_MSG(closed_around, "no closed contour around the sphere");
    CHECK_MSG(on_wall == 0, "%zu outline vertices on the open wall", on_wall);
    CHECK_MSG(f.inner == 0, "%zu outline vertices inside the sphere", f.inner);
    CHECK(f.max_dev <= 1.5);
    pnpr_cloud_free(&s);
    pnpr_cloud_free(&wall);
    pnpr_cloud_free(&c);
}

/* Pixel position of offset point p seen by a look-at camera (vertical fov, aspect W / H). */
static void look_at_px(const double eye[3], const double target[3], double fov, const double p[3], double *x, double *y)
{
    double f[3], s[3], u[3], d[3], up[3] = {0, 0, 1};
    for (int a = 0; a < 3; a++) { f[a] = target[a] - eye[a]; d[a] = p[a] - eye[a]; }
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int a = 0; a < 3; a++) f[a] /= fl;
    s[0] = f[1] * up[2] - f[2] * up[1]; s[1] = f[2] * up[0] - f[0] * up[2]; s[2] = f[0] * up[1] - f[1] * up[0];
    double sl = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int a = 0; a < 3; a++) s[a] /= sl;
    u[0] = s[1] * f[2] - s[2] * f[1]; u[1] = s[2] * f[0] - s[0] * f[2]; u[2] = s[0] * f[1] - s[1] * f[0];
    double vx = s[0] * d[0] + s[1] * d[1] + s[2] * d[2], vy = u[0] * d[0] + u[1] * d[1] + u[2] * d[2];
    double vz = f[0] * d[0] + f[1] * d[1] + f[2] * d[2], fy = 1 / tan(0.5 * fov * PI / 180.0);
    *x = (vx / vz * fy / ((double)W / H) + 1) * 0.5 * W;
    *y = (1 - vy / vz * fy) * 0.5 * H;
}

/* A cube [0,1]^3 sampled on a regular grid (spacing 0.025, no normals: depth extents of 2.5
 * radii) seen from the front and above: its two front vertical edges are silhouettes; on every
 * other row between 20 % and 80 % of their height the outline crosses the row within 1.5 px of
 * the edge's projection. */
static void test_cube_edges(void)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_cube(&c, 1.0, 0.025, 0.0, off, 1), PNPR_OK);
    double eye[3] = {0.5, -2.0, 1.5}, target[3] = {0.5, 0.5, 0.5};
    pnpr_camera cam = {{0}, {0}, {0, 0, 1}, 45, 0, 0};
    for (int a = 0; a < 3; a++) { cam.eye[a] = off[a] + eye[a]; cam.target[a] = off[a] + target[a]; }
    pnpr_polylines none = {0};
    pnpr_svg_options so = svg_options(&c);
    pnpr_error err = {0};
    const char *path = scratch("outline_cube.svg");
    CHECK_STATUS(pnpr_write_lines_svg(path, &none, &cam, &so, &err), PNPR_OK);
    CHECK(parse_svg(path, &P));
    int rows = 0, hits = 0;
    double worst = 0, sum = 0;
    for (int side = 0; side < 2; side++) {
        double lo[3] = {side, 0, 0.2}, hi[3] = {side, 0, 0.8}, x0, y0, x1, y1;
        look_at_px(eye, target, 45, lo, &x0, &y0);
        look_at_px(eye, target, 45, hi, &x1, &y1);
        for (double y = ceil(y1); y <= y0; y += 2) {
            double ex = x1 + (x0 - x1) * (y - y1) / (y0 - y1), best = 1e9;
            for (size_t k = 0; k < P.count; k++)
                for (size_t i = P.start[k]; i + 1 < P.start[k + 1] + (P.closed[k] ? 1 : 0); i++) {
                    size_t j = i + 1 < P.start[k + 1] ? i + 1 : P.start[k];
                    const double *a = P.xy + 2 * i, *b = P.xy + 2 * j;
                    if ((a[1] - y) * (b[1] - y) > 0 || a[1] == b[1]) continue;
                    double x = a[0] + (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]);
                    if (fabs(x - ex) < fabs(best)) best = x - ex;
                }
            rows++;
            hits += fabs(best) <= 1.5;
            if (fabs(best) < 1e8) { sum += best * (side ? 1 : -1); if (fabs(best) > worst) worst = fabs(best); }
        }
    }
    fprintf(stderr, "cube edges: %d of %d rows crossed within 1.5 px of the true edge, at most %.2f px off, "
                    "%+.2f px outside on average\n", hits, rows, worst, rows ? sum / rows : 0);
    CHECK_MSG(rows > 60 && hits == rows, "cube: %d of %d rows", hits, rows);
    pnpr_cloud_free(&c);
}

/* Off, no occluders, width; bad options. */
static void test_options(void)
{
    pnpr_cloud c = {0};
    sphere(&c, 4000, 0, 0, 31);
    pnpr_camera cam = front_camera();
    pnpr_polylines none = {0};
    memcpy(none.origin, off, sizeof none.origin);
    pnpr_svg_options so = svg_options(&c);
    pnpr_error err = {0};
    const char *path = scratch("outline_options.svg");
    so.outline = -1;
    CHECK_STATUS(pnpr_write_lines_svg(path, &none, &cam, &so, &err), PNPR_OK);
    CHECK(parse_svg(path, &P) && !P.has_group);
    so.outline = 1;
    so.occluders = NULL;
    CHECK_STATUS(pnpr_write_lines_svg(path, &none, &cam, &so, &err), PNPR_OK);
    CHECK(parse_svg(path, &P) && !P.has_group);
    so.occluders = &c;
    so.outline_width = 3.5f;
    CHECK_STATUS(pnpr_write_lines_svg(path, &none, &cam, &so, &err), PNPR_OK);
    CHECK(parse_svg(path, &P) && P.has_group && P.count >= 1 && fabs(P.stroke_width - 3.5) < 1e-9);
    so.outline_width = NAN;
    CHECK_STATUS(pnpr_write_lines_svg(path, &none, &cam, &so, &err), PNPR_ERR_INVALID_ARGUMENT);
    so.outline_width = 0;
    so.outline_jump = -1;
    CHECK_STATUS(pnpr_write_lines_svg(path, &none, &cam, &so, &err), PNPR_ERR_INVALID_ARGUMENT);
    so.outline_jump = INFINITY;
    CHECK_STATUS(pnpr_write_lines_svg(path, &none, &cam, &so, &err), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_cloud_free(&c);
}

/* Empty, one point, some and all points NaN, all points coincident, points around the eye (behind
 * it, on its plane, just in front): valid drawings. */
static void test_degenerate(void)
{
    pnpr_camera cam = front_camera();
    pnpr_polylines none = {0};
    const char *path = scratch("outline_degenerate.svg");
    for (int t = 0; t < 6; t++) {
        pnpr_cloud c = {0};
        size_t n = t == 0 ? 0 : t == 1 ? 1 : 500;
        if (n) CHECK_STATUS(pnpr_cloud_alloc(&c, n), PNPR_OK);
        memcpy(c.origin, off, sizeof c.origin);
        pnpr_test_rng rng = {77};
        for (size_t i = 0; i < n; i++)
            for (int a = 0; a < 3; a++) {
                float v = t == 4 ? 0.25f : (float)(pnpr_test_uniform(&rng) - 0.5);
                if (t == 5) v = (float)(0.2 * (pnpr_test_uniform(&rng) - 0.5) - (a == 1 ? D : 0)); /* eye at -D y */
                if ((t == 2 && i % 3 == 0) || t == 3) v = a == 1 ? NAN : v;
                c.xyz[3 * i + a] = v;
            }
        pnpr_svg_options so = svg_options(&c);
        pnpr_error err = {0};
        CHECK_STATUS(pnpr_write_lines_svg(path, &none, &cam, &so, &err), PNPR_OK);
        CHECK_MSG(parse_svg(path, &P), "degenerate case %d: not a valid drawing", t);
        for (size_t i = 0; i < 2 * P.nv; i++) CHECK(isfinite(P.xy[i]));
        fprintf(stderr, "degenerate case %d (%zu points): %zu outline paths\n", t, n, P.count);
        pnpr_cloud_free(&c);
    }
}

int main(void)
{
    have_rsvg = system("rsvg-convert --version > /dev/null 2>&1") == 0;
    if (!have_rsvg) fprintf(stderr, "test_svg_outline: rsvg-convert is missing: drawings are parsed, not rendered\n");
    test_sphere();
    test_contour_on_wall();
    test_cube_edges();
    test_options();
    test_degenerate();
    return pnpr_test_finish("test_svg_outline");
}
