/* The points of a cloud on a grid of cells, and how many of them a view may show
 * (view/view_internal.h). PointWorks draws each object's queue by the screen space the object
 * occupies and culls the objects out of view (sections 3 and 4.4); with one queue per cloud, the
 * cells stand in for its objects in the count of what is in view. */
#include "view_internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint32_t axis_index(float v, float min, float inv, uint32_t n)
{
    float c = (v - min) * inv; /* as the shaders compute it (pnpr_shader_prelude) */
    if (!(c >= 0)) return 0;
    return c >= (float)n ? n - 1 : (uint32_t)c;
}

/* Cells of side e along an extent (1 at least; the grid's product bounds each axis). */
static uint32_t axis_cells(float extent, float e)
{
    float k = ceilf(extent / e);
    return k >= (float)PNPR_VIEW_CELLS_MAX ? PNPR_VIEW_CELLS_MAX : k >= 1 ? (uint32_t)k : 1;
}

static double grid_cells(const float bmin[3], const float bmax[3], float e)
{
    double n = 1;
    for (int a = 0; a < 3; a++) n *= axis_cells(bmax[a] - bmin[a], e);
    return n;
}

/* The smallest side (to float precision, by bisection) whose grid has at most `most` (8 to
 * PNPR_VIEW_CELLS_MAX) cells; `longest` (the box's longest side, finite, > 0) / (k - 1), k the
 * cube root of `most` rounded down, fits (k cubes a side at most, with rounding: 32768 cells,
 * longest / 31) unless it is subnormal: the caller checks. */
static float grid_side(const float bmin[3], const float bmax[3], float longest, double most)
{
    float lo = longest / (float)most, hi = longest / (float)(floor(cbrt(most) + 1e-9) - 1);
    if (grid_cells(bmin, bmax, lo) <= most) return lo; /* a line */
    for (int it = 0; it < 64 && hi - lo > hi * 1e-6f; it++) {
        float mid = 0.5f * (lo + hi);
        if (grid_cells(bmin, bmax, mid) <= most) hi = mid;
        else lo = mid;
    }
    return hi;
}

void pnpr_view_cells_grid(const float bmin[3], const float bmax[3], uint32_t most, float *r_side, uint32_t r_n[3])
{
    float side = 0;
    const double m = most > PNPR_VIEW_CELLS_MAX ? PNPR_VIEW_CELLS_MAX : most;
    for (int a = 0; a < 3; a++) side = fmaxf(side, bmax[a] - bmin[a]);
    float cell = side > 0 && isfinite(side) && m >= 8 ? grid_side(bmin, bmax, side, m) : 0;
    /* a box too small or too large for float cubes (a side below the normal floats, an extent
     * that overflows), empty, or fewer than 8 cells asked: one cell, every point clamped into it */
    const int one = !(cell >= FLT_MIN) || !isfinite(1.0f / cell) || grid_cells(bmin, bmax, cell) > m;
    *r_side = one ? 1 : cell;
    for (int a = 0; a < 3; a++) r_n[a] = one ? 1 : axis_cells(bmax[a] - bmin[a], cell);
}

void pnpr_view_cells_build(pnpr_view_cells *c, const float *xyz, size_t n, const float bmin[3], const float bmax[3])
{
    memset(c, 0, sizeof *c);
    pnpr_view_cells_grid(bmin, bmax, PNPR_VIEW_CELLS_MAX, &c->cell, c->n);
    c->inv = 1.0f / c->cell;
    for (int a = 0; a < 3; a++) c->min[a] = bmin[a];
    for (size_t i = 0; i < n; i++) {
        const float *p = xyz + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        c->count[pnpr_view_cells_index(c, p)]++;
    }
}

uint32_t pnpr_view_cells_index(const pnpr_view_cells *c, const float p[3])
{
    uint32_t x = axis_index(p[0], c->min[0], c->inv, c->n[0]), y = axis_index(p[1], c->min[1], c->inv, c->n[1]),
             z = axis_index(p[2], c->min[2], c->inv, c->n[2]);
    return (z * c->n[1] + y) * c->n[0] + x;
}

/* Whether the box [lo, hi] lies wholly outside one plane of the frustum (m: projection x view). */
static int box_outside(const float m[16], const float lo[3], const float hi[3])
{
    int out[6] = {0};
    for (int k = 0; k < 8; k++) {
        float p[4] = {(k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2], 1}, q[4] = {0};
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) q[i] += m[j * 4 + i] * p[j];
        for (int a = 0; a < 3; a++) {
            out[2 * a] += q[a] < -q[3];
            out[2 * a + 1] += q[a] > q[3];
        }
    }
    for (int f = 0; f < 6; f++)
        if (out[f] == 8) return 1;
    return 0;
}

void pnpr_view_cells_weights(const pnpr_view_cells *c, const pnpr_frame_camera *fc, float *r_w, size_t stride)
{
    float m[16] = {0}; /* column-major, as the camera's */
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++)
            for (int k = 0; k < 4; k++) m[col * 4 + row] += fc->proj[k * 4 + row] * fc->view[col * 4 + k];
    double zmin = fc->near_plane > 1e-30 ? fc->near_plane : 1e-30;
    for (uint32_t z = 0; z < c->n[2]; z++)
        for (uint32_t y = 0; y < c->n[1]; y++)
            for (uint32_t x = 0; x < c->n[0]; x++) {
                size_t k = ((size_t)z * c->n[1] + y) * c->n[0] + x;
                float lo[3] = {c->min[0] + (float)x * c->cell, c->min[1] + (float)y * c->cell, c->min[2] + (float)z * c->cell};
                float hi[3] = {lo[0] + c->cell, lo[1] + c->cell, lo[2] + c->cell};
                r_w[k * stride] = 0;
                if (!c->count[k]) continue;
                int out = box_outside(m, lo, hi);
                double depth = HUGE_VAL; /* the nearest corner's eye depth (the camera looks down -z) */
                for (int q = 0; q < 8; q++) {
                    const float p[3] = {(q & 1) ? hi[0] : lo[0], (q & 2) ? hi[1] : lo[1], (q & 4) ? hi[2] : lo[2]};
                    double e = -((double)fc->view[2] * p[0] + (double)fc->view[6] * p[1] + (double)fc->view[10] * p[2] +
                                 (double)fc->view[14]);
                    if (e < depth) depth = e;
                }
                double w = fc->ortho ? 1.0 : 1.0 / (fmax(depth, zmin) * fmax(depth, zmin));
                r_w[k * stride] = out ? -(float)w : (float)w;
            }
}

typedef struct cell_weight { float w; uint32_t count; } cell_weight;
static int cmp_weight_desc(const void *a, const void *b)
{
    float x = ((const cell_weight *)a)->w, y = ((const cell_weight *)b)->w;
    return x > y ? -1 : x < y;
}

double pnpr_view_cells_solve(const pnpr_view_cells *c, const float *w, size_t stride, double want)
{
    size_t cells = pnpr_view_cells_size(c), m = 0;
    double all = 0, sum = 0;
    cell_weight *a = malloc((cells ? cells : 1) * sizeof *a);
    for (size_t k = 0; k < cells; k++) {
        if (!(w[k * stride] > 0) || !c->count[k]) continue;
        all += c->count[k];
        sum += (double)c->count[k] * w[k * stride];
        if (a) a[m++] = (cell_weight){w[k * stride], c->count[k]};
    }
    if (want >= all) { free(a); return HUGE_VAL; }
    double *rest = a ? malloc((m + 1) * sizeof *rest) : NULL;
    if (!rest || !(want > 0)) { /* (no memory: none full) */
        free(a); free(rest);
        return want > 0 && sum > 0 ? want / sum : 0;
    }
    qsort(a, m, sizeof *a, cmp_weight_desc);
    rest[m] = 0; /* rest[j]: count x weight of the cells from j on, summed from the smallest (no
                  * cancellation when the weights span many orders of magnitude) */
    for (size_t j = m; j > 0; j--) rest[j - 1] = rest[j] + (double)a[j - 1].count * a[j - 1].w;
    double full = 0, lambda = HUGE_VAL;
    for (size_t j = 0; j < m; j++) { /* the cells before j are full; is cell j? */
        double l = (want - full) / rest[j];
        if (l * a[j].w < 1) { lambda = l > 0 ? l : 0; break; }
        full += a[j].count;
    }
    free(a);
    free(rest);
    return lambda;
}
