/* Profile lines as an SVG drawing, through the renderer's camera, with hidden parts removed by a
 * CPU depth test against the occluder cloud (see pnpr_write_lines_svg in camera.h).
 *
 * - Projection: pnpr_frame_camera_make (the renderer's own view and projection), frame origin =
 *   the lines' origin; occluder points are re-expressed in it in double.
 * - Depth buffer: every occluder point is a disk of point_radius (world), splatted with its
 *   perspective size into a float buffer of the drawing's size, keeping the nearest view depth.
 * - Visibility: a line vertex is visible when in front of the eye, inside the drawing, and no
 *   deeper than the buffer there + depth_tolerance; runs of visible vertices become strokes (a
 *   segment is drawn when both its ends are visible).
 * - Strokes: `<polyline>` with round caps and joins; with taper > 0 each run is a filled outline
 *   whose half-width grows linearly from 0 over the first `taper` fraction of its length and
 *   shrinks likewise at its end. Coordinates in px with 2 decimals.
 * - Outlines (svg_outline.c): the occluders' silhouettes and contours as <path>s in
 *   <g id="outlines">, written before the lines' group <g id="lines">. */
#include "view_internal.h"
#include "svg_outline.h"
#include "../core/internal.h"
#include <pointnpr/output.h>

#include <pointnpr/knn.h>
#include <pointnpr/options.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct proj {
    pnpr_frame_camera fc;
    int w, h;
} proj;

/* Pixel position and view depth of offset point p; returns 0 when behind the eye. */
static int project(const proj *pr, const double p[3], double *r_x, double *r_y, double *r_depth)
{
    const float *V = pr->fc.view, *P = pr->fc.proj;
    double v[4];
    for (int r = 0; r < 4; r++) v[r] = V[0 * 4 + r] * p[0] + V[1 * 4 + r] * p[1] + V[2 * 4 + r] * p[2] + V[3 * 4 + r];
    double depth = -v[2];
    if (!(depth > 1e-12)) return 0;
    double cx = P[0] * v[0] + P[4] * v[1] + P[8] * v[2] + P[12] * v[3];
    double cy = P[1] * v[0] + P[5] * v[1] + P[9] * v[2] + P[13] * v[3];
    double cw = P[3] * v[0] + P[7] * v[1] + P[11] * v[2] + P[15] * v[3];
    if (!(cw > 0)) return 0;
    *r_x = (cx / cw + 1) * 0.5 * pr->w;
    *r_y = (1 - cy / cw) * 0.5 * pr->h;
    *r_depth = depth;
    return 1;
}

static float median_spacing(const pnpr_cloud *c)
{
    pnpr_kdtree *t = NULL;
    if (pnpr_kdtree_build(c->xyz, c->count, 0, &t) != PNPR_OK) return 0;
    float h = pnpr_kdtree_median_spacing(t, 4000);
    pnpr_kdtree_free(t);
    return h;
}

static void splat(float *zb, const proj *pr, const double p[3], double radius)
{
    double x, y, z;
    if (!project(pr, p, &x, &y, &z)) return;
    double r = radius * pr->fc.pixels_per_unit / z;
    if (r < 0.5) r = 0.5;
    if (r > 64) r = 64;
    if (!(x > -r - 1 && y > -r - 1 && x < pr->w + r + 1 && y < pr->h + r + 1)) return; /* off the drawing (or huge) */
    int x0 = (int)floor(x - r), x1 = (int)ceil(x + r), y0 = (int)floor(y - r), y1 = (int)ceil(y + r);
    if (x1 < 0 || y1 < 0 || x0 >= pr->w || y0 >= pr->h) return;
    for (int yy = y0 < 0 ? 0 : y0; yy <= y1 && yy < pr->h; yy++)
        for (int xx = x0 < 0 ? 0 : x0; xx <= x1 && xx < pr->w; xx++) {
            double dx = xx + 0.5 - x, dy = yy + 0.5 - y;
            if (dx * dx + dy * dy > r * r) continue;
            float *q = zb + (size_t)yy * (size_t)pr->w + (size_t)xx;
            if ((float)z < *q) *q = (float)z;
        }
}

/* Writes one visible run [a, b) of projected vertices. */
static int write_run(FILE *f, const double *xy, size_t a, size_t b, const pnpr_svg_options *o, double width,
                     const char *colour)
{
    if (b - a < 2) return 0;
    if (!(o->taper > 0)) {
        if (fprintf(f, "<polyline points=\"") < 0) return -1;
        for (size_t i = a; i < b; i++)
            if (fprintf(f, "%s%.2f,%.2f", i > a ? " " : "", xy[2 * i], xy[2 * i + 1]) < 0) return -1;
        return fprintf(f, "\"/>\n") < 0 ? -1 : 0;
    }
    /* tapered: outline = left side forwards, right side backwards */
    double len = 0, taper = o->taper > 1 ? 1 : o->taper;
    for (size_t i = a + 1; i < b; i++) len += hypot(xy[2 * i] - xy[2 * i - 2], xy[2 * i + 1] - xy[2 * i - 1]);
    if (!(len > 0)) return 0;
    if (fprintf(f, "<path fill=\"%s\" stroke=\"none\" d=\"", colour) < 0) return -1;
    for (int side = 0; side < 2; side++) {
        double s_acc = side ? len : 0;
        for (size_t k = 0; k < b - a; k++) {
            size_t i = side ? b - 1 - k : a + k;
            if (k > 0) {
                size_t prev = side ? i + 1 : i - 1;
                double seg = hypot(xy[2 * i] - xy[2 * prev], xy[2 * i + 1] - xy[2 * prev + 1]);
                s_acc += side ? -seg : seg;
            }
            size_t i0 = i > a ? i - 1 : i, i1 = i + 1 < b ? i + 1 : i;
            double tx = xy[2 * i1] - xy[2 * i0], ty = xy[2 * i1 + 1] - xy[2 * i0 + 1], tl = hypot(tx, ty);
            double nx = tl > 0 ? -ty / tl : 0, ny = tl > 0 ? tx / tl : 0;
            double u = s_acc / len, wf = 1;
            if (u < taper) wf = u / taper;
            if (1 - u < taper && (1 - u) / taper < wf) wf = (1 - u) / taper;
            double hw = 0.5 * width * wf * (side ? -1 : 1);
            if (fprintf(f, "%s%.2f,%.2f", (side == 0 && k == 0) ? "M" : " L", xy[2 * i] + nx * hw, xy[2 * i + 1] + ny * hw) < 0)
                return -1;
        }
    }
    return fprintf(f, " Z\"/>\n") < 0 ? -1 : 0;
}

/* The outlines' group: one <path> per polyline (" Z" when closed). */
static int write_outlines(FILE *f, const pnpr_outline_set *o, double width, const char *colour)
{
    if (fprintf(f, "<g id=\"outlines\" fill=\"none\" stroke=\"%s\" stroke-width=\"%.2f\" stroke-linecap=\"round\" "
                   "stroke-linejoin=\"round\">\n", colour, width) < 0)
        return -1;
    for (size_t k = 0; k < o->count; k++) {
        if (fprintf(f, "<path d=\"") < 0) return -1;
        for (size_t i = o->offset[k]; i < o->offset[k + 1]; i++)
            if (fprintf(f, "%s%.2f,%.2f", i == o->offset[k] ? "M" : " L", o->xy[2 * i], o->xy[2 * i + 1]) < 0) return -1;
        if (fprintf(f, "%s\"/>\n", o->closed[k] ? " Z" : "") < 0) return -1;
    }
    return fprintf(f, "</g>\n") < 0 ? -1 : 0;
}

/* Checks the arguments; r_o: the options with their zeros filled from the table (options.h). */
static pnpr_status check_options(const char *path, const pnpr_polylines *lines, const pnpr_svg_options *opts,
                                 pnpr_svg_options *r_o, int *r_w, int *r_h, pnpr_error *err)
{
    if (!path || !lines || (lines->count && (!lines->offset || !lines->xyz || !lines->closed)))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "svg: invalid arguments");
    int w = opts->width ? opts->width : 1024, h = opts->height ? opts->height : 768;
    if (w < 1 || h < 1 || w > 32768 || h > 32768)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "svg: size %dx%d is not in 1..32768", w, h);
    size_t nt;
    const pnpr_option_desc *table = pnpr_svg_option_table(&nt);
    pnpr_status st = pnpr_option_check(table, nt, opts, err); /* the ranges: options.h */
    if (st != PNPR_OK) return st;
    *r_o = *opts;
    pnpr_option_fill_defaults(table, nt, r_o);
    const pnpr_cloud *occ = opts->occluders;
    if (occ && occ->count && !occ->xyz) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "svg: occluders without points");
    *r_w = w;
    *r_h = h;
    return PNPR_OK;
}

/* Bounds of the line vertices and the finite occluder points (shifted into the frame). */
static void frame_bounds(const pnpr_polylines *lines, const pnpr_cloud *occ, const double shift[3], float bmin[3],
                         float bmax[3])
{
    size_t nv = lines->count ? lines->offset[lines->count] : 0;
    for (int a = 0; a < 3; a++) { bmin[a] = INFINITY; bmax[a] = -INFINITY; }
    for (size_t i = 0; i < nv; i++)
        for (int a = 0; a < 3; a++) {
            float v = lines->xyz[3 * i + a];
            if (v < bmin[a]) bmin[a] = v;
            if (v > bmax[a]) bmax[a] = v;
        }
    for (size_t i = 0; occ && i < occ->count; i++) {
        float v[3];
        for (int a = 0; a < 3; a++) v[a] = (float)(shift[a] + occ->xyz[3 * i + a]);
        if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) continue;
        for (int a = 0; a < 3; a++) {
            if (v[a] < bmin[a]) bmin[a] = v[a];
            if (v[a] > bmax[a]) bmax[a] = v[a];
        }
    }
}

/* The drawing's projection: `camera`, or pnpr_camera_fit of the bounds. */
static pnpr_status make_projection(const pnpr_camera *camera, const double org[3], const float bmin[3],
                                   const float bmax[3], int w, int h, proj *pr, pnpr_error *err)
{
    int have_box = bmin[0] <= bmax[0];
    pnpr_camera cam;
    if (camera) cam = *camera;
    else {
        pnpr_cloud box = {0}; /* a two-point cloud spanning the bounds, for pnpr_camera_fit */
        float corners[6] = {bmin[0], bmin[1], bmin[2], bmax[0], bmax[1], bmax[2]};
        if (!have_box) return pnpr_error_set(err, PNPR_ERR_EMPTY, "svg: nothing to draw and no camera given");
        box.count = 2;
        box.xyz = corners;
        memcpy(box.origin, org, sizeof box.origin);
        pnpr_status st = pnpr_camera_fit(&box, NULL, 0, (float)w / (float)h, &cam);
        if (st != PNPR_OK) return pnpr_error_set(err, st, "svg: cannot frame the drawing");
    }
    pr->w = w;
    pr->h = h;
    return pnpr_frame_camera_make(&cam, org, bmin, bmax, have_box, w, h, &pr->fc, err);
}

/* The occluders' depth buffer (disks of point_radius) and the lines' depth tolerance; *r_zb stays
 * NULL without occluders. */
static pnpr_status depth_buffer(const pnpr_cloud *occ, const double shift[3], const proj *pr, const pnpr_svg_options *o,
                                const float bmin[3], const float bmax[3], float **r_zb, double *r_tol, pnpr_error *err)
{
    *r_zb = NULL;
    *r_tol = 0;
    if (!occ || !occ->count) return PNPR_OK;
    size_t npx = (size_t)pr->w * (size_t)pr->h;
    float *zb = malloc(npx * sizeof *zb);
    if (!zb) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "svg: no memory for a %dx%d depth buffer", pr->w, pr->h);
    for (size_t i = 0; i < npx; i++) zb[i] = INFINITY;
    double radius = o->point_radius > 0 ? o->point_radius : median_spacing(occ);
    if (!(radius > 0)) radius = 1e-3 * sqrt((double)(bmax[0] - bmin[0]) * (bmax[0] - bmin[0]) + (double)(bmax[1] - bmin[1]) * (bmax[1] - bmin[1]));
    *r_tol = o->depth_tolerance > 0 ? o->depth_tolerance : 3 * radius;
    for (size_t i = 0; i < occ->count; i++) {
        double p[3] = {shift[0] + occ->xyz[3 * i], shift[1] + occ->xyz[3 * i + 1], shift[2] + occ->xyz[3 * i + 2]};
        if (isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2])) splat(zb, pr, p, radius);
    }
    *r_zb = zb;
    return PNPR_OK;
}

/* The profile lines' group: the visible runs of every polyline. */
static int write_lines(FILE *f, const pnpr_polylines *lines, const proj *pr, const float *zb, double tol,
                       const pnpr_svg_options *o, double width, const char *colour)
{
    int bad = fprintf(f, "<g id=\"lines\" fill=\"none\" stroke=\"%s\" stroke-width=\"%.2f\" stroke-linecap=\"round\" "
                         "stroke-linejoin=\"round\">\n", colour, width) < 0;
    size_t maxv = 0;
    for (size_t p = 0; p < lines->count; p++)
        if (lines->offset[p + 1] - lines->offset[p] > maxv) maxv = lines->offset[p + 1] - lines->offset[p];
    double *xy = malloc((maxv + 2) * 2 * sizeof *xy);
    uint8_t *vis = malloc(maxv + 2);
    if (!xy || !vis) bad = 1;
    for (size_t p = 0; p < lines->count && !bad; p++) {
        size_t a = lines->offset[p], n = lines->offset[p + 1] - a, m = n + (lines->closed[p] && n > 2);
        for (size_t k = 0; k < m; k++) {
            size_t i = a + k % n;
            double q[3] = {lines->xyz[3 * i], lines->xyz[3 * i + 1], lines->xyz[3 * i + 2]}, z;
            vis[k] = (uint8_t)project(pr, q, &xy[2 * k], &xy[2 * k + 1], &z);
            if (vis[k] && zb && xy[2 * k] >= 0 && xy[2 * k + 1] >= 0 && xy[2 * k] < pr->w && xy[2 * k + 1] < pr->h) {
                int px = (int)xy[2 * k], py = (int)xy[2 * k + 1];
                vis[k] = z <= zb[(size_t)py * (size_t)pr->w + (size_t)px] + tol;
            }
        }
        for (size_t k = 0; k < m && !bad;) {
            while (k < m && !vis[k]) k++;
            size_t start = k;
            while (k < m && vis[k]) k++;
            bad |= write_run(f, xy, start, k, o, width, colour) < 0;
        }
    }
    free(xy);
    free(vis);
    return bad ? -1 : fprintf(f, "</g>\n") < 0 ? -1 : 0;
}

/* What write_drawing prints. */
typedef struct drawing {
    const pnpr_polylines *lines;
    const proj *pr;
    const float *zb;
    double tol;
    const pnpr_outline_set *outl;
    const pnpr_svg_options *o;
} drawing;

/* The whole drawing: header, background, outlines (when `outl`), lines; 0 when all was written. */
static int print_drawing(FILE *f, const void *ctx)
{
    const drawing *d = ctx;
    const pnpr_svg_options *o = d->o;
    const uint8_t *sc = o->stroke_rgb;
    char colour[16];
    snprintf(colour, sizeof colour, "#%02x%02x%02x", sc[0], sc[1], sc[2]);
    int bad = fprintf(f,
                      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                      "<!-- profile lines by pointnpr %s -->\n"
                      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\">\n",
                      PNPR_VERSION_STRING, d->pr->w, d->pr->h, d->pr->w, d->pr->h) < 0;
    if (o->background)
        bad |= fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"#%02x%02x%02x\"/>\n", o->background_rgb[0],
                       o->background_rgb[1], o->background_rgb[2]) < 0;
    if (d->outl)
        bad |= write_outlines(f, d->outl, o->outline_width, colour) < 0;
    bad |= write_lines(f, d->lines, d->pr, d->zb, d->tol, o, o->stroke_width, colour) < 0;
    bad |= fprintf(f, "</svg>\n") < 0;
    return bad;
}

static pnpr_status write_drawing(const char *path, const pnpr_polylines *lines, const proj *pr, const float *zb,
                                 double tol, const pnpr_outline_set *outl, const pnpr_svg_options *o, pnpr_error *err)
{
    drawing d = {lines, pr, zb, tol, outl, o};
    return pnpr_output_write(path, print_drawing, &d, err);
}

pnpr_status pnpr_write_lines_svg(const char *path, const pnpr_polylines *lines,
                                 const pnpr_camera *camera, const pnpr_svg_options *opts,
                                 pnpr_error *err)
{
    static const pnpr_svg_options defaults;
    if (!opts) opts = &defaults;
    int w = 0, h = 0;
    pnpr_svg_options filled;
    pnpr_status st = check_options(path, lines, opts, &filled, &w, &h, err);
    if (st != PNPR_OK) return st;
    opts = &filled;
    /* the lines' frame (the occluders' when there are no line vertices: georeferenced origins
     * stay out of the float matrices) */
    const pnpr_cloud *occ = opts->occluders;
    size_t nv = lines->count ? lines->offset[lines->count] : 0;
    const double *org = nv == 0 && occ ? occ->origin : lines->origin;
    double shift[3] = {0, 0, 0};
    if (occ) for (int a = 0; a < 3; a++) shift[a] = occ->origin[a] - org[a];
    float bmin[3], bmax[3];
    frame_bounds(lines, occ, shift, bmin, bmax);
    proj pr;
    if ((st = make_projection(camera, org, bmin, bmax, w, h, &pr, err)) != PNPR_OK) return st;
    float *zb;
    double tol;
    if ((st = depth_buffer(occ, shift, &pr, opts, bmin, bmax, &zb, &tol, err)) != PNPR_OK) return st;
    pnpr_outline_set outl = {0};
    int outlines = occ && occ->count && opts->outline >= 0;
    if (outlines) st = pnpr_svg_outlines(occ, shift, &pr.fc, w, h, opts->outline_jump, &outl, err);
    if (st == PNPR_OK) st = write_drawing(path, lines, &pr, zb, tol, outlines ? &outl : NULL, opts, err);
    pnpr_outline_set_free(&outl);
    free(zb);
    return st;
}
