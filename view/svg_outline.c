/* Outlines for the SVG export (svg_outline.h): the renderer's image-space rules (edge_fill,
 * edge_erode, edge_ink shaders) on a CPU surface buffer, traced into vector polylines.
 *
 * 1. Surface buffer: every point is a disk of the renderer's visibility mask (pnpr_point_spacing
 *    of the default spacing_k times the lines style's mask scale: 1.5 x the distance to the 4th
 *    nearest other point, clamped to [1/8, 4] x the median), splatted with its
 *    perspective size (at most 64 px); each pixel keeps the nearest disk's view depth, depth
 *    extent (radius / max(0.1, |cos(normal, view ray)|), 2.5 radii without normals) and radius.
 * 2. Hole closing: a pixel is a sampling hole when along all 8 directions a march meets a surface
 *    nearer than the pixel by more than `jump` times the smaller depth extent (an empty pixel: any
 *    surface) within 4 of that surface's projected radii (marches of at most 32 px; the renderer
 *    stops at 8 px from a pixel that shows a surface, for speed, and so leaves see-through holes
 *    wider than that open); a hole takes the mean of the 8 surfaces that close it.
 * 3. Crossings: the grid edge between two 4-adjacent pixels is on an outline when one shows a
 *    surface and the other none (silhouette), or when one is farther than the other by more than
 *    `jump` depth extents and the near one sees, along one of 8 rays 2 to 3 px long, a pixel whose
 *    3x3 neighbourhood is all that far (the minimum filter: a contour's far side must be thick).
 * 4. Tracing: marching squares on the crossings (each 2x2 cell joins an edge where the near side
 *    comes first along the cell's boundary to the next edge where it comes last: near corners of
 *    a saddle are joined) give chains of edge midpoints, open at the frame's border or where a
 *    contour fades, closed otherwise.
 * 5. Each chain is smoothed lightly (3 passes of 1/4, 1/2, 1/4), moved towards its near side by
 *    the disks' overhang (0.9 x the 3x3 mean projected radius r + 0.3 px, at most 32 px, at most
 *    half the width of the near surface along the normal; measured on spheres of 2k to 160k
 *    points: the renderer's 1.1 r is for its band, which starts inside the boundary), smoothed
 *    again with a Gaussian of about r (on every (r/3)-th vertex when r >= 6 px), simplified (Douglas-Peucker, 0.5 px);
 *    chains shorter than 4 px are dropped. */
#include "svg_outline.h"

#include <pointnpr/knn.h>
#include <pointnpr/options.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define HOLE_RADII 4.0f   /* holes close within this many projected radii */
#define INSET_RADII 0.9   /* the disks' overhang beyond the outermost points: 0.9 radii */
#define INSET_PX 0.3      /* + 0.3 px (both measured on spheres, docs/lines.md) */
#define SMOOTH_RADII 1.0  /* the chains are smoothed over about one projected disk radius */
#define MAX_SMOOTH_PASSES 128
#define SMOOTH_PASSES 3
#define SIMPLIFY_PX 0.5
#define MIN_LENGTH_PX 4.0

typedef struct px_info {
    float z, ext, r; /* view depth (INFINITY: no surface), depth extent, disk radius (world) */
} px_info;

enum { EDGE_CROSS = 1, EDGE_NEAR_Q = 2, EDGE_PREV = 4, EDGE_SEEN = 8 };

typedef struct outline_ctx {
    const pnpr_frame_camera *fc;
    int w, h;
    float jump;
    px_info *raw, *fill;
    uint32_t *sat;  /* (w+1) x (h+1) summed-area table of the covered raw pixels */
    size_t nh, ne;  /* horizontal grid edges (pixel (x,y) to (x+1,y)), all grid edges */
    uint32_t *next; /* per grid edge: the next crossing along its chain + 1, 0 = none */
    uint8_t *flag;  /* per grid edge: EDGE_* */
} outline_ctx;

/* One chain being traced: vertices (px), where they started, the pixel on their near side. */
typedef struct chain {
    double *xy, *orig, *off, *tmp;
    size_t *near_px;
    uint8_t *keep;
    size_t *stack;
    size_t n, cap;
} chain;

static const int DX[8] = {1, -1, 0, 0, 1, 1, -1, -1}, DY[8] = {0, 0, 1, -1, 1, -1, 1, -1};

static int covered(const px_info *v) { return v->z < INFINITY; }

static size_t pix(const outline_ctx *c, int x, int y) { return (size_t)y * (size_t)c->w + (size_t)x; }

static float radius_px(const outline_ctx *c, float r, float z)
{
    return r * c->fc->pixels_per_unit / (c->fc->ortho ? 1.0f : fmaxf(z, 1e-6f));
}

/* ---- disk radii ---- */

/* The renderer's disks (render.h): the point spacing of the upload's default spacing_k times the
 * default mask scale of the lines style. */
static pnpr_status disk_radii(const pnpr_cloud *cloud, float *radius)
{
    pnpr_status st = pnpr_point_spacing(cloud->xyz, cloud->count, pnpr_upload_defaults().spacing_k, 0, radius, NULL);
    float scale = pnpr_draw_mask_scale(NULL, PNPR_STYLE_LINES);
    for (size_t i = 0; st == PNPR_OK && i < cloud->count; i++) radius[i] *= scale;
    return st;
}

/* ---- the surface buffer ---- */

static void to_view(const pnpr_frame_camera *fc, const double p[3], double v[3])
{
    const float *V = fc->view;
    for (int r = 0; r < 3; r++) v[r] = V[r] * p[0] + V[4 + r] * p[1] + V[8 + r] * p[2] + V[12 + r];
}

/* Pixel position of view-space v; 0 when behind the eye. */
static int to_pixel(const outline_ctx *c, const double v[3], double *x, double *y)
{
    const float *P = c->fc->proj;
    double cx = P[0] * v[0] + P[4] * v[1] + P[8] * v[2] + P[12];
    double cy = P[1] * v[0] + P[5] * v[1] + P[9] * v[2] + P[13];
    double cw = P[3] * v[0] + P[7] * v[1] + P[11] * v[2] + P[15];
    if (!(-v[2] > 1e-12) || !(cw > 0)) return 0;
    *x = (cx / cw + 1) * 0.5 * c->w;
    *y = (1 - cy / cw) * 0.5 * c->h;
    return isfinite(*x) && isfinite(*y);
}

/* radius / max(0.1, |cos(normal, view ray)|); 2.5 radii without a usable normal. */
static float depth_extent(const pnpr_frame_camera *fc, const double v[3], const float *normal, float r)
{
    double cosv = 0.4;
    if (normal) {
        const float *V = fc->view;
        double ne[3];
        for (int k = 0; k < 3; k++) ne[k] = V[k] * normal[0] + V[4 + k] * normal[1] + V[8 + k] * normal[2];
        double nn = ne[0] * ne[0] + ne[1] * ne[1] + ne[2] * ne[2];
        double vv = fc->ortho ? 1 : sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        double d = fc->ortho ? -ne[2] : ne[0] * v[0] + ne[1] * v[1] + ne[2] * v[2];
        if (nn > 0.25 && vv > 0) cosv = fmax(fabs(d) / (sqrt(nn) * vv), 0.1);
    }
    float e = (float)(r / cosv);
    return e > 1e-30f ? e : 1e-30f;
}

static void splat(outline_ctx *c, double x, double y, px_info info)
{
    double r = radius_px(c, info.r, info.z);
    if (!(r <= PNPR_OUTLINE_MAX_DISK)) r = PNPR_OUTLINE_MAX_DISK;
    if (!(x > -r - 1 && y > -r - 1 && x < c->w + r + 1 && y < c->h + r + 1)) return; /* off the drawing (or huge) */
    int x0 = (int)floor(x - r), x1 = (int)floor(x + r), y0 = (int)floor(y - r), y1 = (int)floor(y + r);
    int cx = (int)floor(x), cy = (int)floor(y);
    if (x1 < 0 || y1 < 0 || x0 >= c->w || y0 >= c->h) return;
    for (int yy = y0 < 0 ? 0 : y0; yy <= y1 && yy < c->h; yy++)
        for (int xx = x0 < 0 ? 0 : x0; xx <= x1 && xx < c->w; xx++) {
            double dx = xx + 0.5 - x, dy = yy + 0.5 - y;
            if (dx * dx + dy * dy > r * r && !(xx == cx && yy == cy)) continue; /* the centre's pixel always */
            px_info *q = c->raw + pix(c, xx, yy);
            if (info.z < q->z) *q = info;
        }
}

static void splat_all(outline_ctx *c, const pnpr_cloud *cloud, const double shift[3], const float *radius)
{
    for (size_t i = 0; i < (size_t)c->w * (size_t)c->h; i++) c->raw[i] = (px_info){INFINITY, 0, 0};
    for (size_t i = 0; i < cloud->count; i++) {
        const float *q = cloud->xyz + 3 * i;
        double p[3] = {shift[0] + q[0], shift[1] + q[1], shift[2] + q[2]}, v[3], x, y;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        to_view(c->fc, p, v);
        if (!to_pixel(c, v, &x, &y)) continue;
        px_info info = {(float)-v[2], depth_extent(c->fc, v, cloud->normal ? cloud->normal + 3 * i : NULL, radius[i]), radius[i]};
        if (info.z < INFINITY) splat(c, x, y, info);
    }
}

/* ---- hole closing ---- */

static void build_sat(outline_ctx *c)
{
    size_t sw = (size_t)c->w + 1;
    for (size_t x = 0; x < sw; x++) c->sat[x] = 0;
    for (int y = 0; y < c->h; y++) {
        uint32_t row = 0;
        c->sat[(size_t)(y + 1) * sw] = 0;
        for (int x = 0; x < c->w; x++) {
            row += (uint32_t)covered(&c->raw[pix(c, x, y)]);
            c->sat[(size_t)(y + 1) * sw + (size_t)x + 1] = c->sat[(size_t)y * sw + (size_t)x + 1] + row;
        }
    }
}

/* Covered raw pixels in [x0, x1] x [y0, y1] (clamped to the frame). */
static uint32_t covered_in(const outline_ctx *c, int x0, int y0, int x1, int y1)
{
    size_t sw = (size_t)c->w + 1;
    x0 = x0 < 0 ? 0 : x0; y0 = y0 < 0 ? 0 : y0;
    x1 = x1 >= c->w ? c->w - 1 : x1; y1 = y1 >= c->h ? c->h - 1 : y1;
    if (x1 < x0 || y1 < y0) return 0;
    const uint32_t *s = c->sat;
    return s[(size_t)(y1 + 1) * sw + (size_t)x1 + 1] - s[(size_t)y0 * sw + (size_t)x1 + 1] -
           s[(size_t)(y1 + 1) * sw + (size_t)x0] + s[(size_t)y0 * sw + (size_t)x0];
}

/* The surface that closes direction d from (x, y) within the hole limit, or NULL. */
static const px_info *closer(const outline_ctx *c, int x, int y, int d, int reach, float z, float ext)
{
    double unit = d >= 4 ? 1.41421356 : 1.0;
    for (int s = 1; s <= reach; s++) {
        int qx = x + DX[d] * s, qy = y + DY[d] * s;
        if (qx < 0 || qy < 0 || qx >= c->w || qy >= c->h) return NULL;
        const px_info *v = c->raw + pix(c, qx, qy);
        if (covered(v) && v->z < z - c->jump * fminf(v->ext, ext))
            return s * unit <= HOLE_RADII * radius_px(c, v->r, v->z) ? v : NULL;
    }
    return NULL;
}

static px_info close_hole(const outline_ctx *c, int x, int y)
{
    const px_info *me = c->raw + pix(c, x, y);
    int cov = covered(me);
    int reach = PNPR_OUTLINE_REACH;
    if (!cov && covered_in(c, x - reach, y - reach, x + reach, y + reach) == 0) return *me;
    float z = cov ? me->z : INFINITY, ext = cov ? me->ext : INFINITY;
    double sz = 0, se = 0, sr = 0;
    for (int d = 0; d < 8; d++) {
        const px_info *v = closer(c, x, y, d, reach, z, ext);
        if (!v) return *me;
        sz += v->z; se += v->ext; sr += v->r;
    }
    return (px_info){(float)(sz / 8), (float)(se / 8), (float)(sr / 8)};
}

static void fill_holes(outline_ctx *c)
{
    for (int y = 0; y < c->h; y++)
        for (int x = 0; x < c->w; x++) c->fill[pix(c, x, y)] = close_hole(c, x, y);
}

/* ---- crossings ---- */

/* b lies farther than a by more than jump times the smaller depth extent. */
static int is_far(const px_info *a, const px_info *b, float jump)
{
    return covered(a) && covered(b) && b->z > a->z + jump * fminf(a->ext, b->ext);
}

/* The nearest surface of the 3x3 neighbourhood of (x, y) (clamped) lies farther than a. */
static int min_far(const outline_ctx *c, int x, int y, const px_info *a)
{
    const px_info *best = c->fill + pix(c, x, y);
    if (!covered(best)) return 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int qx = x + dx, qy = y + dy;
            qx = qx < 0 ? 0 : qx >= c->w ? c->w - 1 : qx;
            qy = qy < 0 ? 0 : qy >= c->h ? c->h - 1 : qy;
            const px_info *v = c->fill + pix(c, qx, qy);
            if (covered(v) && v->z < best->z) best = v;
        }
    return is_far(a, best, c->jump);
}

/* (x, y) sees a thick farther surface 2 to 3 px away along one of 8 rays (the renderer's
 * contour rays after its minimum filter). */
static int thick_far(const outline_ctx *c, int x, int y)
{
    const px_info *a = c->fill + pix(c, x, y);
    for (int d = 0; d < 8; d++)
        for (int s = 2; s <= (d < 4 ? 3 : 2); s++) {
            int qx = x + DX[d] * s, qy = y + DY[d] * s;
            qx = qx < 0 ? 0 : qx >= c->w ? c->w - 1 : qx;
            qy = qy < 0 ? 0 : qy >= c->h ? c->h - 1 : qy;
            if (min_far(c, qx, qy, a)) return 1;
        }
    return 0;
}

static void edge_pixels(const outline_ctx *c, size_t e, int *px, int *py, int *qx, int *qy)
{
    if (e < c->nh) {
        *py = (int)(e / (size_t)(c->w - 1));
        *px = (int)(e % (size_t)(c->w - 1));
        *qx = *px + 1;
        *qy = *py;
    } else {
        *py = (int)((e - c->nh) / (size_t)c->w);
        *px = (int)((e - c->nh) % (size_t)c->w);
        *qx = *px;
        *qy = *py + 1;
    }
}

/* EDGE_CROSS (| EDGE_NEAR_Q when q is the near side) or 0. */
static uint8_t crossing(const outline_ctx *c, int px, int py, int qx, int qy)
{
    const px_info *a = c->fill + pix(c, px, py), *b = c->fill + pix(c, qx, qy);
    if (covered(a) != covered(b)) return (uint8_t)(EDGE_CROSS | (covered(b) ? EDGE_NEAR_Q : 0));
    if (is_far(a, b, c->jump) && thick_far(c, px, py)) return EDGE_CROSS;
    if (is_far(b, a, c->jump) && thick_far(c, qx, qy)) return EDGE_CROSS | EDGE_NEAR_Q;
    return 0;
}

static void mark_crossings(outline_ctx *c)
{
    for (size_t e = 0; e < c->ne; e++) {
        int px, py, qx, qy;
        edge_pixels(c, e, &px, &py, &qx, &qy);
        c->flag[e] = crossing(c, px, py, qx, qy);
        c->next[e] = 0;
    }
}

/* Joins the crossings of the cell whose corners are pixels (x, y) .. (x+1, y+1): walking its
 * boundary top, right, bottom, left, an edge whose near side comes first is an entry, the other
 * kind an exit; each entry goes to the next free exit (near corners of a saddle stay joined). */
static void link_cell(outline_ctx *c, int x, int y)
{
    size_t w = (size_t)c->w;
    size_t e[4] = {(size_t)y * (w - 1) + (size_t)x, c->nh + (size_t)y * w + (size_t)x + 1,
                   (size_t)(y + 1) * (w - 1) + (size_t)x, c->nh + (size_t)y * w + (size_t)x};
    int kind[4], used[4] = {0, 0, 0, 0}; /* 0 none, 1 entry, 2 exit */
    for (int i = 0; i < 4; i++) {
        uint8_t f = c->flag[e[i]];
        int near_q = (f & EDGE_NEAR_Q) != 0, near_first = i < 2 ? !near_q : near_q;
        kind[i] = !(f & EDGE_CROSS) ? 0 : near_first ? 1 : 2;
    }
    for (int i = 0; i < 4; i++) {
        if (kind[i] != 1) continue;
        for (int k = 1; k < 4; k++) {
            int j = (i + k) % 4;
            if (kind[j] != 2 || used[j]) continue;
            c->next[e[i]] = (uint32_t)(e[j] + 1);
            c->flag[e[j]] |= EDGE_PREV;
            used[j] = 1;
            break;
        }
    }
}

static void link_cells(outline_ctx *c)
{
    for (int y = 0; y + 1 < c->h; y++)
        for (int x = 0; x + 1 < c->w; x++) link_cell(c, x, y);
}

/* ---- chains ---- */

static int chain_reserve(chain *ch, size_t n)
{
    if (n <= ch->cap) return 1;
    size_t cap = ch->cap ? ch->cap : 256;
    while (cap < n) cap *= 2;
    double *xy = realloc(ch->xy, 2 * cap * sizeof *xy);
    if (xy) ch->xy = xy;
    double *orig = realloc(ch->orig, 2 * cap * sizeof *orig);
    if (orig) ch->orig = orig;
    double *off = realloc(ch->off, cap * sizeof *off);
    if (off) ch->off = off;
    double *tmp = realloc(ch->tmp, 2 * (cap + 1) * sizeof *tmp);
    if (tmp) ch->tmp = tmp;
    size_t *np = realloc(ch->near_px, cap * sizeof *np);
    if (np) ch->near_px = np;
    uint8_t *keep = realloc(ch->keep, cap + 1);
    if (keep) ch->keep = keep;
    size_t *stack = realloc(ch->stack, 4 * (cap + 1) * sizeof *stack);
    if (stack) ch->stack = stack;
    if (!xy || !orig || !off || !tmp || !np || !keep || !stack) return 0;
    ch->cap = cap;
    return 1;
}

static void chain_free(chain *ch)
{
    free(ch->xy); free(ch->orig); free(ch->off); free(ch->tmp); free(ch->near_px); free(ch->keep); free(ch->stack);
}

/* Appends the midpoint of crossing e (pixel centres are at + 0.5). */
static int chain_add(const outline_ctx *c, chain *ch, size_t e)
{
    if (!chain_reserve(ch, ch->n + 1)) return 0;
    int px, py, qx, qy;
    edge_pixels(c, e, &px, &py, &qx, &qy);
    size_t i = ch->n++;
    ch->xy[2 * i] = ch->orig[2 * i] = 0.5 * (px + qx) + 0.5;
    ch->xy[2 * i + 1] = ch->orig[2 * i + 1] = 0.5 * (py + qy) + 0.5;
    ch->near_px[i] = (c->flag[e] & EDGE_NEAR_Q) ? pix(c, qx, qy) : pix(c, px, py);
    return 1;
}

static size_t wrap(size_t i, ptrdiff_t d, size_t n, int closed)
{
    ptrdiff_t j = (ptrdiff_t)i + d;
    if (closed) return (size_t)((j % (ptrdiff_t)n + (ptrdiff_t)n) % (ptrdiff_t)n);
    return j < 0 ? 0 : j >= (ptrdiff_t)n ? n - 1 : (size_t)j;
}

/* One pass of x += f ((x[i-1] + x[i+1]) / 2 - x[i]); the ends of open chains stay. */
static void smooth_pass(chain *ch, int closed, double f)
{
    size_t n = ch->n;
    memcpy(ch->tmp, ch->xy, 2 * n * sizeof *ch->xy);
    for (size_t i = 0; i < n; i++) {
        if (!closed && (i == 0 || i == n - 1)) continue;
        size_t a = wrap(i, -1, n, closed), b = wrap(i, 1, n, closed);
        for (int k = 0; k < 2; k++) ch->xy[2 * i + k] += f * (0.5 * (ch->tmp[2 * a + k] + ch->tmp[2 * b + k]) - ch->tmp[2 * i + k]);
    }
}

/* Passes of (1/4, 1/2, 1/4): n passes are a Gaussian of variance n / 2 vertices^2. */
static void smooth(chain *ch, int closed, int passes)
{
    for (int pass = 0; pass < passes; pass++) smooth_pass(ch, closed, 0.5);
}

/* Unit normal at vertex i pointing to its near side. */
static void near_normal(const outline_ctx *c, const chain *ch, size_t i, int closed, double nrm[2])
{
    size_t a = wrap(i, -1, ch->n, closed), b = wrap(i, 1, ch->n, closed);
    double tx = ch->xy[2 * b] - ch->xy[2 * a], ty = ch->xy[2 * b + 1] - ch->xy[2 * a + 1], tl = hypot(tx, ty);
    nrm[0] = tl > 0 ? -ty / tl : 0;
    nrm[1] = tl > 0 ? tx / tl : 0;
    size_t p = ch->near_px[i];
    double vx = (double)(p % (size_t)c->w) + 0.5 - ch->orig[2 * i], vy = (double)(p / (size_t)c->w) + 0.5 - ch->orig[2 * i + 1];
    if (nrm[0] * vx + nrm[1] * vy < 0) { nrm[0] = -nrm[0]; nrm[1] = -nrm[1]; }
}

/* The mean projected radius of the disks around pixel p (3x3). */
static double disk_px(const outline_ctx *c, size_t p)
{
    int x = (int)(p % (size_t)c->w), y = (int)(p / (size_t)c->w);
    double sum = 0, n = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= c->w || qy >= c->h) continue;
            const px_info *v = c->fill + pix(c, qx, qy);
            if (covered(v)) { sum += v->r; n++; }
        }
    if (!(n > 0)) return 0;
    return radius_px(c, (float)(sum / n), c->fill[p].z);
}

/* How far the near surface of vertex i reaches along nrm (px, from the vertex), up to `limit`:
 * the march ends at a pixel without a surface or one that jumps in depth from the previous. */
static double near_width(const outline_ctx *c, const chain *ch, size_t i, const double nrm[2], double limit)
{
    const px_info *prev = c->fill + ch->near_px[i];
    for (double s = 1.0; s <= limit; s += 0.5) {
        int x = (int)floor(ch->xy[2 * i] + s * nrm[0]), y = (int)floor(ch->xy[2 * i + 1] + s * nrm[1]);
        if (x < 0 || y < 0 || x >= c->w || y >= c->h) return limit;
        const px_info *v = c->fill + pix(c, x, y);
        if (!covered(v) || is_far(prev, v, c->jump) || is_far(v, prev, c->jump)) return s;
        prev = v;
    }
    return limit;
}

/* Moves every vertex to its near side by the disks' overhang (INSET_RADII x their radius +
 * INSET_PX, at most PNPR_OUTLINE_MAX_INSET px and half the near surface's width), the offsets
 * smoothed along the chain (mean over 5 vertices). Returns the mean projected disk radius. */
static double inset(const outline_ctx *c, chain *ch, int closed)
{
    size_t n = ch->n;
    double rsum = 0;
    for (size_t i = 0; i < n; i++) {
        double nrm[2], r = disk_px(c, ch->near_px[i]), o = INSET_RADII * r + INSET_PX;
        if (o > PNPR_OUTLINE_MAX_INSET) o = PNPR_OUTLINE_MAX_INSET;
        rsum += r;
        near_normal(c, ch, i, closed, nrm);
        double wdt = near_width(c, ch, i, nrm, 2 * o + 1);
        ch->off[i] = o < 0.5 * wdt ? o : 0.5 * wdt;
    }
    for (size_t i = 0; i < n; i++) {
        double s = 0;
        for (ptrdiff_t d = -2; d <= 2; d++) s += ch->off[wrap(i, d, n, closed)];
        ch->tmp[i] = s / 5;
    }
    memcpy(ch->off, ch->tmp, n * sizeof *ch->off);
    for (size_t i = 0; i < n; i++) {
        double nrm[2];
        near_normal(c, ch, i, closed, nrm);
        ch->tmp[2 * i] = ch->xy[2 * i] + ch->off[i] * nrm[0];
        ch->tmp[2 * i + 1] = ch->xy[2 * i + 1] + ch->off[i] * nrm[1];
    }
    memcpy(ch->xy, ch->tmp, 2 * n * sizeof *ch->xy);
    return rsum / (double)n;
}

static double seg_dist(const double *p, const double *a, const double *b)
{
    double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

/* Douglas-Peucker over tmp[0..m-1] (explicit stack of at most 2m entries): keep[i] marks the
 * vertices kept. */
static void simplify(chain *ch, size_t m)
{
    memset(ch->keep, 0, m);
    ch->keep[0] = ch->keep[m - 1] = 1;
    size_t top = 0;
    ch->stack[top++] = 0;
    ch->stack[top++] = m - 1;
    while (top >= 2) {
        size_t b = ch->stack[--top], a = ch->stack[--top], far = a;
        double dmax = SIMPLIFY_PX;
        for (size_t i = a + 1; i < b; i++) {
            double d = seg_dist(ch->tmp + 2 * i, ch->tmp + 2 * a, ch->tmp + 2 * b);
            if (d > dmax) { dmax = d; far = i; }
        }
        if (far == a) continue;
        ch->keep[far] = 1;
        ch->stack[top++] = a; ch->stack[top++] = far;
        ch->stack[top++] = far; ch->stack[top++] = b;
    }
}

static int set_reserve(pnpr_outline_set *s, size_t lines, size_t vertices)
{
    if (lines + 1 > s->cap_lines) {
        size_t cap = s->cap_lines ? 2 * s->cap_lines : 64;
        while (cap < lines + 1) cap *= 2;
        size_t *off = realloc(s->offset, cap * sizeof *off);
        if (off) s->offset = off;
        uint8_t *cl = realloc(s->closed, cap);
        if (cl) s->closed = cl;
        if (!off || !cl) return 0;
        s->cap_lines = cap;
    }
    if (vertices > s->cap_vertices) {
        size_t cap = s->cap_vertices ? 2 * s->cap_vertices : 1024;
        while (cap < vertices) cap *= 2;
        double *xy = realloc(s->xy, 2 * cap * sizeof *xy);
        if (!xy) return 0;
        s->xy = xy;
        s->cap_vertices = cap;
    }
    return 1;
}

static double chain_length(const chain *ch, int closed)
{
    double len = 0;
    for (size_t i = 1; i < ch->n + (closed ? 1 : 0); i++) {
        size_t a = i - 1, b = i % ch->n;
        len += hypot(ch->xy[2 * b] - ch->xy[2 * a], ch->xy[2 * b + 1] - ch->xy[2 * a + 1]);
    }
    return len;
}

/* Keeps every k-th vertex (and the last of an open chain). */
static void decimate(chain *ch, size_t k, int closed)
{
    size_t m = 0;
    for (size_t i = 0; i < ch->n; i += k, m++) {
        ch->xy[2 * m] = ch->xy[2 * i];
        ch->xy[2 * m + 1] = ch->xy[2 * i + 1];
    }
    if (!closed && (ch->n - 1) % k) {
        ch->xy[2 * m] = ch->xy[2 * (ch->n - 1)];
        ch->xy[2 * m + 1] = ch->xy[2 * (ch->n - 1) + 1];
        m++;
    }
    ch->n = m;
}

/* A Gaussian of sigma px along the chain (vertices about 1 px apart): on every k-th vertex,
 * k = sigma / 3, so that at most 72 passes run whatever sigma. */
static void smooth_gaussian(chain *ch, int closed, double sigma)
{
    size_t k = sigma >= 6 ? (size_t)(sigma / 3) : 1;
    if (k > 1 && ch->n / k >= 3) decimate(ch, k, closed);
    else k = 1;
    double s = sigma / (double)k, passes = 2 * s * s;
    smooth(ch, closed, passes < SMOOTH_PASSES ? SMOOTH_PASSES : passes > MAX_SMOOTH_PASSES ? MAX_SMOOTH_PASSES : (int)passes);
}

/* Smooths, insets and simplifies the traced chain and appends it to out (0: out of memory). */
static int finish_chain(const outline_ctx *c, chain *ch, int closed, pnpr_outline_set *out)
{
    if (ch->n < 3) return 1;
    smooth(ch, closed, SMOOTH_PASSES);
    smooth_gaussian(ch, closed, SMOOTH_RADII * inset(c, ch, closed));
    if (chain_length(ch, closed) < MIN_LENGTH_PX) return 1;
    size_t m = ch->n + (closed ? 1 : 0); /* a closed chain repeats its first vertex */
    memcpy(ch->tmp, ch->xy, 2 * ch->n * sizeof *ch->xy);
    if (closed) { ch->tmp[2 * ch->n] = ch->xy[0]; ch->tmp[2 * ch->n + 1] = ch->xy[1]; }
    simplify(ch, m);
    size_t kept = 0, base = out->count ? out->offset[out->count] : 0;
    for (size_t i = 0; i < ch->n; i++) kept += ch->keep[i];
    if (!set_reserve(out, out->count + 1, base + kept)) return 0;
    if (out->count == 0) out->offset[0] = 0;
    size_t k = base;
    for (size_t i = 0; i < ch->n; i++)
        if (ch->keep[i]) { out->xy[2 * k] = ch->xy[2 * i]; out->xy[2 * k + 1] = ch->xy[2 * i + 1]; k++; }
    out->closed[out->count] = (uint8_t)(closed != 0);
    out->offset[++out->count] = k;
    return 1;
}

/* Follows the crossings from edge e; returns 0 when out of memory. */
static int trace_from(outline_ctx *c, chain *ch, size_t e, pnpr_outline_set *out)
{
    size_t cur = e;
    int closed = 0;
    ch->n = 0;
    for (;;) {
        c->flag[cur] |= EDGE_SEEN;
        if (!chain_add(c, ch, cur)) return 0;
        if (!c->next[cur]) break;
        cur = c->next[cur] - 1;
        if (c->flag[cur] & EDGE_SEEN) { closed = cur == e; break; }
    }
    return finish_chain(c, ch, closed, out);
}

/* Open chains first (from crossings nobody leads to), then the cycles that remain. */
static pnpr_status trace_all(outline_ctx *c, pnpr_outline_set *out)
{
    chain ch;
    memset(&ch, 0, sizeof ch);
    int ok = 1;
    for (int pass = 0; pass < 2 && ok; pass++)
        for (size_t e = 0; e < c->ne && ok; e++) {
            uint8_t f = c->flag[e];
            if (!(f & EDGE_CROSS) || (f & EDGE_SEEN) || (pass == 0 && (f & EDGE_PREV))) continue;
            ok = trace_from(c, &ch, e, out);
        }
    chain_free(&ch);
    return ok ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
}

void pnpr_outline_set_free(pnpr_outline_set *s)
{
    if (!s) return;
    free(s->offset);
    free(s->xy);
    free(s->closed);
    memset(s, 0, sizeof *s);
}

/* Steps 1 and 2: the hole-closed surface buffer c->fill (the raw buffer and its summed-area table
 * are released before the crossings' arrays are allocated: at most 28 bytes a pixel at a time). */
static pnpr_status surface(outline_ctx *c, const pnpr_cloud *cloud, const double shift[3])
{
    size_t npx = (size_t)c->w * (size_t)c->h;
    float *radius = malloc(cloud->count * sizeof *radius);
    c->raw = malloc(npx * sizeof *c->raw);
    c->fill = malloc(npx * sizeof *c->fill);
    c->sat = malloc(((size_t)c->w + 1) * ((size_t)c->h + 1) * sizeof *c->sat);
    pnpr_status st = radius && c->raw && c->fill && c->sat ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) st = disk_radii(cloud, radius);
    if (st == PNPR_OK) {
        splat_all(c, cloud, shift, radius);
        build_sat(c);
        fill_holes(c);
    }
    free(radius);
    free(c->raw);
    free(c->sat);
    c->raw = NULL;
    c->sat = NULL;
    return st;
}

pnpr_status pnpr_svg_outlines(const pnpr_cloud *cloud, const double shift[3], const pnpr_frame_camera *fc,
                              int w, int h, float jump, pnpr_outline_set *r, pnpr_error *err)
{
    memset(r, 0, sizeof *r);
    if (!cloud || !cloud->count || !cloud->xyz || w < 2 || h < 2) return PNPR_OK;
    outline_ctx c;
    memset(&c, 0, sizeof c);
    c.fc = fc;
    c.w = w;
    c.h = h;
    c.jump = jump;
    c.nh = (size_t)(w - 1) * (size_t)h;
    c.ne = c.nh + (size_t)w * (size_t)(h - 1);
    pnpr_status st = surface(&c, cloud, shift);
    if (st == PNPR_OK) {
        c.next = malloc(c.ne * sizeof *c.next);
        c.flag = malloc(c.ne);
        if (!c.next || !c.flag) st = PNPR_ERR_OUT_OF_MEMORY;
    }
    if (st == PNPR_OK) {
        mark_crossings(&c);
        link_cells(&c);
        st = trace_all(&c, r);
    }
    free(c.fill); free(c.next); free(c.flag);
    if (st != PNPR_OK) {
        pnpr_outline_set_free(r);
        return pnpr_error_set(err, st, "svg: outlines of a %dx%d drawing: %s", w, h, pnpr_status_string(st));
    }
    return PNPR_OK;
}
