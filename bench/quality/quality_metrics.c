/* The picture-quality figures of `pointnpr bench quality` (docs/quality.md gives each definition):
 * visible-edge coverage and ink precision, sphere-silhouette coverage, outline-ink fraction,
 * speckle and the feature-to-flat ink ratio, measured on an RGBA8 image against the analytic
 * scene seen through the same camera matrices the renderer used. */
#include "quality.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- options, pixels ------------------------------------------------------------------------ */

static void defaults(const pnpr_quality_options *in, pnpr_quality_options *o)
{
    if (in) *o = *in;
    else memset(o, 0, sizeof *o);
    if (!(o->radius_px > 0)) o->radius_px = 2;
    if (!(o->step_px > 0)) o->step_px = 0.5f;
    if (!(o->ink_luminance > 0)) o->ink_luminance = 0.5f;
    if (!(o->depth_abs > 0)) o->depth_abs = 0.05f;
    if (!(o->depth_rel > 0)) o->depth_rel = 0.002f;
    if (!o->custom_background) o->background[0] = o->background[1] = o->background[2] = 255;
    if (!(o->drawn_tolerance > 0)) o->drawn_tolerance = 0.02f;
    if (!(o->ink_distance > 0)) o->ink_distance = 0.2f;
    if (!(o->speckle_delta > 0)) o->speckle_delta = 0.25f;
    if (o->open_margin_px <= 0) o->open_margin_px = 10;
}

double pnpr_quality_luminance(const uint8_t *px)
{
    return (0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2]) / 255.0;
}

static int image_ok(const pnpr_quality_image *im)
{
    return im && im->rgba && im->width > 0 && im->height > 0;
}

/* ink[i] = 1 where pixel i is darker than ink_luminance x the background's luminance. */
static uint8_t *ink_mask(const pnpr_quality_image *im, const pnpr_quality_options *o, size_t *r_count)
{
    size_t n = (size_t)im->width * (size_t)im->height, count = 0;
    uint8_t *m = malloc(n ? n : 1);
    if (!m) return NULL;
    uint8_t bg[4] = {o->background[0], o->background[1], o->background[2], 255};
    double limit = o->ink_luminance * pnpr_quality_luminance(bg);
    for (size_t i = 0; i < n; i++) count += m[i] = pnpr_quality_luminance(im->rgba + 4 * i) < limit;
    *r_count = count;
    return m;
}

/* ---- matrices and the view in scene-local coordinates --------------------------------------- */

/* r = a * b (column-major 4x4). */
static void mul4(const double a[16], const double b[16], double r[16])
{
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
}

/* General 4x4 inverse by cofactors; 0 when singular or not finite. */
static int inv4(const double m[16], double r[16])
{
    double a[16];
    a[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] + m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    a[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] - m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    a[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] + m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    a[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] - m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    a[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] - m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    a[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] + m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    a[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] - m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    a[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] + m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    a[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] + m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    a[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] - m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    a[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] + m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    a[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] - m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    a[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] - m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    a[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] + m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    a[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] - m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    a[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] + m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    double det = m[0] * a[0] + m[1] * a[4] + m[2] * a[8] + m[3] * a[12];
    if (!(fabs(det) > 1e-300) || !isfinite(det)) return 0;
    for (int i = 0; i < 16; i++) r[i] = a[i] / det;
    return 1;
}

/* The view rebased on the scene's offset (in double, before anything else: world coordinates
 * may be ~5e6), the full transform and its inverse. */
typedef struct qview {
    double pv[16], inv[16], view_local[16];
    int w, h, ortho;
} qview;

static int qview_make(const pnpr_quality_view *v, const double offset[3], qview *q)
{
    if (!v || v->width <= 0 || v->height <= 0) return 0;
    for (int i = 0; i < 16; i++)
        if (!isfinite(v->view[i]) || !isfinite(v->projection[i])) return 0;
    memcpy(q->view_local, v->view, sizeof q->view_local);
    for (int row = 0; row < 4; row++)
        q->view_local[12 + row] = v->view[row] * offset[0] + v->view[4 + row] * offset[1] +
                                  v->view[8 + row] * offset[2] + v->view[12 + row];
    mul4(v->projection, q->view_local, q->pv);
    q->w = v->width;
    q->h = v->height;
    q->ortho = v->projection[11] == 0;
    return inv4(q->pv, q->inv);
}

/* Homogeneous transform of (p, 1). */
static void xform(const double m[16], const double p[3], double r[4])
{
    for (int row = 0; row < 4; row++) r[row] = m[row] * p[0] + m[4 + row] * p[1] + m[8 + row] * p[2] + m[12 + row];
}

static int clip_to_px(const qview *q, const double c[4], double *x, double *y)
{
    if (!(c[3] > 1e-12)) return 0;
    *x = (c[0] / c[3] + 1) * 0.5 * q->w;
    *y = (1 - c[1] / c[3]) * 0.5 * q->h;
    return isfinite(*x) && isfinite(*y);
}

/* The point of the near plane (NDC z = -1) on the pixel ray through (x, y) px, and the ray's
 * unit direction (scene-local). */
static int pixel_ray(const qview *q, double x, double y, double r_o[3], double r_d[3])
{
    double ndc[2] = {2 * x / q->w - 1, 1 - 2 * y / q->h}, p[2][4];
    for (int k = 0; k < 2; k++) {
        double c[3] = {ndc[0], ndc[1], k ? 1.0 : -1.0};
        xform(q->inv, c, p[k]);
        if (!(fabs(p[k][3]) > 1e-300)) return 0;
    }
    double l = 0;
    for (int a = 0; a < 3; a++) {
        r_o[a] = p[0][a] / p[0][3];
        r_d[a] = p[1][a] / p[1][3] - r_o[a];
        l += r_d[a] * r_d[a];
    }
    l = sqrt(l);
    if (!(l > 0) || !isfinite(l)) return 0;
    for (int a = 0; a < 3; a++) r_d[a] /= l;
    return 1;
}

/* The eye (scene-local) of a perspective view: inverse view applied to the origin. */
static int view_eye(const qview *q, double r_eye[3])
{
    double inv[16], c[4];
    static const double zero[3] = {0, 0, 0};
    if (!inv4(q->view_local, inv)) return 0;
    xform(inv, zero, c);
    for (int a = 0; a < 3; a++) r_eye[a] = c[a];
    return 1;
}

int pnpr_quality_project(const pnpr_quality_view *view, const double world[3], double *r_x, double *r_y)
{
    static const double zero[3] = {0, 0, 0};
    qview q;
    if (!qview_make(view, zero, &q)) return 0;
    double c[4], x, y;
    xform(q.pv, world, c);
    if (!clip_to_px(&q, c, &x, &y)) return 0;
    *r_x = x;
    *r_y = y;
    return 1;
}

/* ---- visibility and edge sampling ----------------------------------------------------------- */

/* Whether scene-local point p, at pixel (x, y), is the first thing its pixel ray meets. */
static int visible(const pnpr_quality_scene *s, const qview *q, const pnpr_quality_options *o, const double p[3],
                   double x, double y)
{
    double org[3], dir[3];
    if (!pixel_ray(q, x, y, org, dir)) return 0;
    double d = 0;
    for (int a = 0; a < 3; a++) d += (p[a] - org[a]) * dir[a];
    double limit = d - (o->depth_abs + o->depth_rel * fabs(d));
    if (!(limit > 0)) return 1;
    return !pnpr_quality_raycast(s, org, dir, limit, NULL);
}

typedef struct sampler {
    const pnpr_quality_scene *scene;
    const qview *q;
    const pnpr_quality_options *o;
    const uint8_t *ink;      /* coverage: ink mask, NULL = do not test */
    uint8_t *stamp;          /* mask of pixels near a visible sample, NULL = none */
    size_t samples, visible_samples, covered;
} sampler;

/* Visits the pixel centres within radius r of (x, y): stamps them, and returns whether one is ink. */
static int near_pixels(sampler *sm, double x, double y)
{
    const double r = sm->o->radius_px;
    int x0 = (int)floor(x - r - 0.5), x1 = (int)ceil(x + r), y0 = (int)floor(y - r - 0.5), y1 = (int)ceil(y + r), hit = 0;
    for (int j = y0 < 0 ? 0 : y0; j <= y1 && j < sm->q->h; j++)
        for (int i = x0 < 0 ? 0 : x0; i <= x1 && i < sm->q->w; i++) {
            double dx = i + 0.5 - x, dy = j + 0.5 - y;
            if (dx * dx + dy * dy > r * r) continue;
            size_t k = (size_t)j * (size_t)sm->q->w + (size_t)i;
            if (sm->stamp) sm->stamp[k] = 1;
            if (sm->ink && sm->ink[k]) hit = 1;
        }
    return hit;
}

/* Samples segment a-b every step_px on screen (perspective-correct), in front of the eye only. */
static void sample_segment(sampler *sm, const double a[3], const double b[3])
{
    double ca[4], cb[4];
    xform(sm->q->pv, a, ca);
    xform(sm->q->pv, b, cb);
    /* keep the part with w > eps (in front of the eye) */
    const double eps = 1e-9;
    double t0 = 0, t1 = 1;
    if (ca[3] <= eps && cb[3] <= eps) return;
    if (ca[3] <= eps) t0 = (eps - ca[3]) / (cb[3] - ca[3]);
    if (cb[3] <= eps) t1 = (eps - ca[3]) / (cb[3] - ca[3]);
    double pa[3], pb[3], xa, ya, xb, yb;
    for (int k = 0; k < 3; k++) { pa[k] = a[k] + t0 * (b[k] - a[k]); pb[k] = a[k] + t1 * (b[k] - a[k]); }
    xform(sm->q->pv, pa, ca);
    xform(sm->q->pv, pb, cb);
    if (!clip_to_px(sm->q, ca, &xa, &ya) || !clip_to_px(sm->q, cb, &xb, &yb)) return;
    double len = hypot(xb - xa, yb - ya);
    long n = (long)ceil(len / sm->o->step_px);
    if (n > 10000000) n = 10000000;
    for (long i = 0; i <= n; i++) {
        double s = n ? (double)i / (double)n : 0;
        double x = xa + s * (xb - xa), y = ya + s * (yb - ya);
        if (!(x >= 0 && y >= 0 && x < sm->q->w && y < sm->q->h)) continue;
        double den = s * ca[3] + (1 - s) * cb[3], t = den > 0 ? s * ca[3] / den : s; /* screen -> 3D */
        double p[3];
        for (int k = 0; k < 3; k++) p[k] = pa[k] + t * (pb[k] - pa[k]);
        sm->samples++;
        if (!visible(sm->scene, sm->q, sm->o, p, x, y)) continue;
        sm->visible_samples++;
        sm->covered += near_pixels(sm, x, y);
    }
}

static void sample_all(sampler *sm, const pnpr_quality_segment *seg, size_t n)
{
    for (size_t i = 0; i < n; i++) sample_segment(sm, seg[i].a, seg[i].b);
}

/* ---- silhouettes ---------------------------------------------------------------------------- */

static void perp_basis(const double v[3], double u1[3], double u2[3])
{
    double a[3] = {0, 0, 1};
    if (fabs(v[2]) > 0.9) { a[0] = 1; a[2] = 0; }
    u1[0] = v[1] * a[2] - v[2] * a[1]; u1[1] = v[2] * a[0] - v[0] * a[2]; u1[2] = v[0] * a[1] - v[1] * a[0];
    double l = sqrt(u1[0] * u1[0] + u1[1] * u1[1] + u1[2] * u1[2]);
    for (int k = 0; k < 3; k++) u1[k] /= l;
    u2[0] = v[1] * u1[2] - v[2] * u1[1]; u2[1] = v[2] * u1[0] - v[0] * u1[2]; u2[2] = v[0] * u1[1] - v[1] * u1[0];
}

/* The silhouette circle (tangent points from the eye; orthographic: the great circle across the
 * view direction) of a sphere as n chords. */
static int circle_chords(const qview *q, const double c[3], double r, int n, pnpr_quality_segment *seg)
{
    double v[3], m[3], rho;
    if (q->ortho) {
        for (int k = 0; k < 3; k++) v[k] = q->view_local[4 * k + 2]; /* row 2 of the view = -forward */
        double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (!(l > 0)) return 0;
        for (int k = 0; k < 3; k++) { v[k] /= l; m[k] = c[k]; }
        rho = r;
    } else {
        double eye[3];
        if (!view_eye(q, eye)) return 0;
        for (int k = 0; k < 3; k++) v[k] = eye[k] - c[k];
        double d2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2], d = sqrt(d2);
        if (!(d > r) || !(r > 0)) return 0;
        for (int k = 0; k < 3; k++) { m[k] = c[k] + v[k] * (r * r / d2); v[k] /= d; }
        rho = r * sqrt(1 - r * r / d2);
    }
    double u1[3], u2[3];
    perp_basis(v, u1, u2);
    for (int i = 0; i < n; i++) {
        double a0 = 2 * 3.14159265358979323846 * i / n, a1 = 2 * 3.14159265358979323846 * (i + 1) / n;
        for (int k = 0; k < 3; k++) {
            seg[i].a[k] = m[k] + rho * (cos(a0) * u1[k] + sin(a0) * u2[k]);
            seg[i].b[k] = m[k] + rho * (cos(a1) * u1[k] + sin(a1) * u2[k]);
        }
        seg[i].kind = PNPR_QUALITY_EDGE_OUTLINE;
        seg[i].angle_deg = 0;
    }
    return 1;
}

pnpr_status pnpr_quality_circle(const pnpr_quality_view *view, const double offset[3], const double centre[3],
                                double radius, int n, pnpr_quality_segment *r_seg)
{
    qview q;
    if (!view || !offset || !centre || !r_seg || n < 3) return PNPR_ERR_INVALID_ARGUMENT;
    if (!qview_make(view, offset, &q)) return PNPR_ERR_NUMERIC;
    return circle_chords(&q, centre, radius, n, r_seg) ? PNPR_OK : PNPR_ERR_NUMERIC;
}

/* Whether circle_chords can draw the sphere's outline (the eye is outside it). */
static int circle_possible(const qview *q, const double c[3], double r)
{
    double eye[3];
    if (!(r > 0)) return 0;
    if (q->ortho) return 1;
    if (!view_eye(q, eye)) return 0;
    double d2 = (eye[0] - c[0]) * (eye[0] - c[0]) + (eye[1] - c[1]) * (eye[1] - c[1]) + (eye[2] - c[2]) * (eye[2] - c[2]);
    return d2 > r * r;
}

static void put(pnpr_quality_segment *seg, size_t cap, size_t *n, const double a[3], const double b[3])
{
    if (seg && *n < cap) {
        memcpy(seg[*n].a, a, 3 * sizeof *a);
        memcpy(seg[*n].b, b, 3 * sizeof *b);
        seg[*n].kind = PNPR_QUALITY_EDGE_OUTLINE;
        seg[*n].angle_deg = 0;
    }
    (*n)++;
}

/* A vertical trunk's two silhouette lines: tangent generators seen from the eye. */
static void trunk_lines(const pnpr_quality_tree *t, const double eye[3], pnpr_quality_segment *seg, size_t cap, size_t *n)
{
    double ux = eye[0] - t->base[0], uy = eye[1] - t->base[1], d = hypot(ux, uy), r = t->trunk_radius;
    if (!(d > r) || !(r > 0)) return;
    ux /= d; uy /= d;
    double ca = r / d, sa = sqrt(1 - ca * ca);
    for (int side = -1; side <= 1; side += 2) {
        double dx = ca * ux - side * sa * uy, dy = ca * uy + side * sa * ux;
        double a[3] = {t->base[0] + r * dx, t->base[1] + r * dy, 0}, b[3] = {a[0], a[1], t->trunk_height};
        put(seg, cap, n, a, b);
    }
}

size_t pnpr_quality_silhouettes(const pnpr_quality_scene *s, const pnpr_quality_view *view, int circle_segments,
                                pnpr_quality_segment *seg, size_t cap)
{
    qview q;
    size_t n = 0;
    if (!s || !qview_make(view, s->offset, &q)) return 0;
    if (circle_segments < 3) circle_segments = 256;
    if (s->has_ground) {
        const double *lo = s->ground_min, *hi = s->ground_max;
        double c[4][3] = {{lo[0], lo[1], 0}, {hi[0], lo[1], 0}, {hi[0], hi[1], 0}, {lo[0], hi[1], 0}};
        for (int k = 0; k < 4; k++) put(seg, cap, &n, c[k], c[(k + 1) % 4]);
    }
    double eye[3];
    if (!q.ortho && view_eye(&q, eye))
        for (int i = 0; i < s->tree_count; i++) trunk_lines(&s->tree[i], eye, seg, cap, &n);
    for (int i = 0; i < s->tree_count + s->sphere_count; i++) {
        const pnpr_quality_tree *t = i < s->tree_count ? &s->tree[i] : NULL;
        double c[3] = {t ? t->base[0] : 0, t ? t->base[1] : 0, t ? t->crown_centre_z : 0};
        if (!t) memcpy(c, s->sphere[i - s->tree_count].centre, sizeof c);
        double r = t ? t->crown_radius : s->sphere[i - s->tree_count].radius;
        if (!circle_possible(&q, c, r)) continue;
        if (seg && n + (size_t)circle_segments <= cap) circle_chords(&q, c, r, circle_segments, seg + n);
        n += (size_t)circle_segments;
    }
    return n;
}

/* ---- line figures --------------------------------------------------------------------------- */

pnpr_status pnpr_quality_edges(const pnpr_quality_scene *s, const pnpr_quality_view *view,
                               const pnpr_quality_image *im, const pnpr_quality_segment *truth, size_t truth_count,
                               const pnpr_quality_segment *extra, size_t extra_count,
                               const pnpr_quality_options *opts, pnpr_quality_edge_figures *r)
{
    if (!s || !view || !image_ok(im) || !r || (truth_count && !truth) || (extra_count && !extra))
        return PNPR_ERR_INVALID_ARGUMENT;
    if (im->width != view->width || im->height != view->height) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_quality_options o;
    defaults(opts, &o);
    qview q;
    if (!qview_make(view, s->offset, &q)) return PNPR_ERR_NUMERIC;
    size_t ink_count = 0, npx = (size_t)im->width * (size_t)im->height;
    uint8_t *ink = ink_mask(im, &o, &ink_count), *stamp = calloc(npx, 1);
    if (!ink || !stamp) { free(ink); free(stamp); return PNPR_ERR_OUT_OF_MEMORY; }
    sampler sm = {s, &q, &o, ink, stamp, 0, 0, 0};
    sample_all(&sm, truth, truth_count);
    memset(r, 0, sizeof *r);
    r->samples = sm.samples;
    r->visible_samples = sm.visible_samples;
    r->covered_samples = sm.covered;
    sm.ink = NULL; /* the extra outlines only widen what counts as near */
    sample_all(&sm, extra, extra_count);
    for (size_t i = 0; i < npx; i++) r->ink_near += ink[i] && stamp[i];
    r->ink_pixels = ink_count;
    r->coverage = r->visible_samples ? (double)r->covered_samples / (double)r->visible_samples : 0;
    r->precision = ink_count ? (double)r->ink_near / (double)ink_count : 0;
    free(ink);
    free(stamp);
    return PNPR_OK;
}

size_t pnpr_quality_visible_mask(const pnpr_quality_scene *s, const pnpr_quality_view *view,
                                 const pnpr_quality_segment *seg, size_t count, const pnpr_quality_options *opts,
                                 uint8_t value, uint8_t *r_mask)
{
    pnpr_quality_options o;
    defaults(opts, &o);
    qview q;
    if (!s || !r_mask || (count && !seg) || !qview_make(view, s->offset, &q)) return 0;
    size_t npx = (size_t)q.w * (size_t)q.h;
    uint8_t *stamp = calloc(npx, 1);
    if (!stamp) return 0;
    sampler sm = {s, &q, &o, NULL, stamp, 0, 0, 0};
    sample_all(&sm, seg, count);
    for (size_t i = 0; i < npx; i++)
        if (stamp[i]) r_mask[i] = value;
    free(stamp);
    return sm.visible_samples;
}

pnpr_status pnpr_quality_line_figures(const pnpr_quality_scene *s, const pnpr_quality_view *view,
                                      const pnpr_quality_image *im, const pnpr_quality_options *opts,
                                      pnpr_quality_edge_figures *r_lines, pnpr_quality_edge_figures *r_all)
{
    if (!s || !r_lines) return PNPR_ERR_INVALID_ARGUMENT;
    size_t ns = pnpr_quality_silhouettes(s, view, 0, NULL, 0);
    pnpr_quality_segment *all = malloc((s->edge_count + ns + 1) * sizeof *all);
    if (!all) return PNPR_ERR_OUT_OF_MEMORY;
    memcpy(all, s->edge, s->edge_count * sizeof *all);
    ns = pnpr_quality_silhouettes(s, view, 0, all + s->edge_count, ns);
    pnpr_status st = pnpr_quality_edges(s, view, im, all, s->edge_count, all + s->edge_count, ns, opts, r_lines);
    if (st == PNPR_OK && r_all) st = pnpr_quality_edges(s, view, im, all, s->edge_count + ns, NULL, 0, opts, r_all);
    free(all);
    return st;
}

pnpr_status pnpr_quality_sphere_silhouette(const pnpr_quality_scene *s, int index, const pnpr_quality_view *view,
                                           const pnpr_quality_image *im, const pnpr_quality_options *opts,
                                           pnpr_quality_edge_figures *r)
{
    enum { N = 512 };
    if (!s || index < 0 || index >= s->sphere_count) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_quality_segment *seg = malloc(N * sizeof *seg);
    if (!seg) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_status st = pnpr_quality_circle(view, s->offset, s->sphere[index].centre, s->sphere[index].radius, N, seg);
    if (st == PNPR_OK) st = pnpr_quality_edges(s, view, im, seg, N, NULL, 0, opts, r);
    free(seg);
    return st;
}

/* ---- image-only figures --------------------------------------------------------------------- */

static int drawn(const uint8_t *px, const pnpr_quality_options *o)
{
    for (int c = 0; c < 3; c++)
        if (fabs((double)px[c] - o->background[c]) > o->drawn_tolerance * 255.0) return 1;
    return 0;
}

pnpr_status pnpr_quality_outline_ink(const pnpr_quality_image *im, const uint8_t ink_rgb[3],
                                     const pnpr_quality_options *opts, double *r_fraction, size_t *r_drawn)
{
    if (!image_ok(im) || !ink_rgb || !r_fraction) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_quality_options o;
    defaults(opts, &o);
    size_t n = (size_t)im->width * (size_t)im->height, nd = 0, ni = 0;
    const double lim = o.ink_distance * 255.0;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *p = im->rgba + 4 * i;
        if (!drawn(p, &o)) continue;
        nd++;
        double d2 = 0;
        for (int c = 0; c < 3; c++) d2 += ((double)p[c] - ink_rgb[c]) * ((double)p[c] - ink_rgb[c]);
        ni += d2 <= lim * lim;
    }
    *r_fraction = nd ? (double)ni / (double)nd : 0;
    if (r_drawn) *r_drawn = nd;
    return PNPR_OK;
}

static int differs(const uint8_t *a, const uint8_t *b, double lim)
{
    for (int c = 0; c < 3; c++)
        if (fabs((double)a[c] - b[c]) > lim) return 1;
    return 0;
}

pnpr_status pnpr_quality_speckle(const pnpr_quality_image *im, const pnpr_quality_options *opts, double *r_fraction)
{
    if (!image_ok(im) || !r_fraction) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_quality_options o;
    defaults(opts, &o);
    const int w = im->width, h = im->height;
    const double lim = o.speckle_delta * 255.0;
    size_t nd = 0, ns = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const uint8_t *p = im->rgba + 4 * ((size_t)y * w + x);
            if (!drawn(p, &o)) continue;
            nd++;
            int xl = x > 0 ? x - 1 : x + 1, xr = x + 1 < w ? x + 1 : x - 1; /* the one neighbour stands for both */
            int yu = y > 0 ? y - 1 : y + 1, yd = y + 1 < h ? y + 1 : y - 1;
            int along_x = w > 1 && differs(p, im->rgba + 4 * ((size_t)y * w + xl), lim) &&
                          differs(p, im->rgba + 4 * ((size_t)y * w + xr), lim);
            int along_y = h > 1 && differs(p, im->rgba + 4 * ((size_t)yu * w + x), lim) &&
                          differs(p, im->rgba + 4 * ((size_t)yd * w + x), lim);
            ns += along_x || along_y;
        }
    *r_fraction = nd ? (double)ns / (double)nd : 0;
    return PNPR_OK;
}

/* ---- tone: feature-to-flat ink ratio --------------------------------------------------------- */

/* Whether some scanner sees scene-local point p (in range, in its elevation window, unobstructed). */
static int scanned(const pnpr_quality_scene *s, const double p[3])
{
    for (int k = 0; k < s->scanner_count; k++) {
        const double *o = s->scanner[k];
        double v[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]}, d = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (!(d > 0) || d > s->max_range) continue;
        double el = asin(v[2] / d) * 180 / 3.14159265358979323846;
        if (el < s->elevation_min_deg || el > s->elevation_max_deg) continue;
        if (!pnpr_quality_raycast(s, o, v, d - 0.02, NULL)) return 1;
    }
    return 0;
}

pnpr_status pnpr_quality_kind_image(const pnpr_quality_scene *s, const pnpr_quality_view *view, int scanned_only,
                                    uint8_t *r_kind)
{
    if (!s || !view || !r_kind) return PNPR_ERR_INVALID_ARGUMENT;
    qview q;
    if (!qview_make(view, s->offset, &q)) return PNPR_ERR_NUMERIC;
    for (int y = 0; y < q.h; y++)
        for (int x = 0; x < q.w; x++) {
            double o[3], d[3];
            pnpr_quality_hit hit;
            uint8_t kind = PNPR_QUALITY_NOTHING;
            if (pixel_ray(&q, x + 0.5, y + 0.5, o, d) && pnpr_quality_raycast(s, o, d, 0, &hit)) {
                kind = (uint8_t)hit.kind;
                double p[3] = {o[0] + hit.t * d[0], o[1] + hit.t * d[1], o[2] + hit.t * d[2]};
                if (scanned_only && kind == PNPR_QUALITY_GROUND && !scanned(s, p)) kind = PNPR_QUALITY_UNSEEN;
            }
            r_kind[(size_t)y * q.w + x] = kind;
        }
    return PNPR_OK;
}

/* In-place Chebyshev dilation of a 0/1 mask by m px: separable running-window maxima. */
static int dilate(uint8_t *mask, int w, int h, int m)
{
    int n = w > h ? w : h;
    int *pre = malloc(((size_t)n + 1) * sizeof *pre);
    uint8_t *line = malloc((size_t)n);
    if (!pre || !line) { free(pre); free(line); return 0; }
    for (int pass = 0; pass < 2; pass++) {
        int len = pass ? h : w, lines = pass ? w : h;
        for (int l = 0; l < lines; l++) {
            pre[0] = 0;
            for (int i = 0; i < len; i++) {
                size_t k = pass ? (size_t)i * w + l : (size_t)l * w + i;
                line[i] = mask[k];
                pre[i + 1] = pre[i] + line[i];
            }
            for (int i = 0; i < len; i++) {
                int a = i - m < 0 ? 0 : i - m, b = i + m + 1 > len ? len : i + m + 1;
                size_t k = pass ? (size_t)i * w + l : (size_t)l * w + i;
                mask[k] = pre[b] - pre[a] > 0;
            }
        }
    }
    free(pre);
    free(line);
    return 1;
}

pnpr_status pnpr_quality_tone(const pnpr_quality_scene *s, const pnpr_quality_view *view,
                              const pnpr_quality_image *im, const pnpr_quality_options *opts,
                              pnpr_quality_tone_figures *r)
{
    if (!s || !view || !image_ok(im) || !r) return PNPR_ERR_INVALID_ARGUMENT;
    if (im->width != view->width || im->height != view->height) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_quality_options o;
    defaults(opts, &o);
    qview q;
    if (!qview_make(view, s->offset, &q)) return PNPR_ERR_NUMERIC;
    size_t npx = (size_t)im->width * (size_t)im->height;
    uint8_t *kind = malloc(npx), *objects = malloc(npx), *feature = calloc(npx, 1);
    pnpr_status st = PNPR_ERR_OUT_OF_MEMORY;
    if (!kind || !objects || !feature) goto done;
    if ((st = pnpr_quality_kind_image(s, view, 1, kind)) != PNPR_OK) goto done;
    for (size_t i = 0; i < npx; i++) objects[i] = kind[i] != PNPR_QUALITY_GROUND && kind[i] != PNPR_QUALITY_UNSEEN;
    st = PNPR_ERR_OUT_OF_MEMORY;
    if (!dilate(objects, im->width, im->height, o.open_margin_px)) goto done;
    sampler sm = {s, &q, &o, NULL, feature, 0, 0, 0};
    sample_all(&sm, s->edge, s->edge_count);
    double sf = 0, so = 0;
    memset(r, 0, sizeof *r);
    for (size_t i = 0; i < npx; i++) {
        double dark = 1 - pnpr_quality_luminance(im->rgba + 4 * i);
        if (feature[i]) { sf += dark; r->feature_pixels++; }
        if (kind[i] == PNPR_QUALITY_GROUND && !objects[i]) { so += dark; r->flat_pixels++; }
    }
    st = PNPR_ERR_EMPTY;
    if (!r->feature_pixels || !r->flat_pixels) goto done;
    r->feature_darkness = sf / (double)r->feature_pixels;
    r->flat_darkness = so / (double)r->flat_pixels;
    r->ratio = r->feature_darkness / (r->flat_darkness > 1.0 / 255 ? r->flat_darkness : 1.0 / 255);
    st = PNPR_OK;
done:
    free(kind);
    free(objects);
    free(feature);
    return st;
}
