/* Polylines of the tracers (vector_internal.h): the growing buffer, and Douglas-Peucker
 * simplification of polylines and polygons with an explicit stack (no recursion however long the
 * line). */
#include "vector_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int pnpr_polybuf_push(pnpr_polybuf *b, float x, float y)
{
    if (b->n == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 64;
        float *q = cap > SIZE_MAX / (2 * sizeof *q) ? NULL : realloc(b->xy, 2 * cap * sizeof *q);
        if (!q) return 0;
        b->xy = q;
        b->cap = cap;
    }
    b->xy[2 * b->n] = x;
    b->xy[2 * b->n + 1] = y;
    b->n++;
    return 1;
}

static double seg_dist(const float *p, const float *a, const float *b)
{
    double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy));
}

/* Marks the vertices to keep between a and b (both kept). */
static int mark(const float *xy, size_t a, size_t b, double tol, uint8_t *keep, size_t *stack)
{
    size_t top = 0;
    stack[top++] = a;
    stack[top++] = b;
    while (top) {
        size_t hi = stack[--top], lo = stack[--top], best = 0;
        double dmax = tol;
        for (size_t i = lo + 1; i < hi; i++) {
            double d = seg_dist(xy + 2 * i, xy + 2 * lo, xy + 2 * hi);
            if (d > dmax) { dmax = d; best = i; }
        }
        if (!best) continue;
        keep[best] = 1;
        stack[top++] = lo; stack[top++] = best;
        stack[top++] = best; stack[top++] = hi;
    }
    return 1;
}

static size_t compact(float *xy, size_t n, const uint8_t *keep)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (keep[i]) { xy[2 * m] = xy[2 * i]; xy[2 * m + 1] = xy[2 * i + 1]; m++; }
    return m;
}

size_t pnpr_simplify_polyline(float *xy, size_t n, double tol)
{
    if (n < 3) return n;
    uint8_t *keep = calloc(n, 1);
    size_t *stack = malloc(2 * n * sizeof *stack);
    if (!keep || !stack) { free(keep); free(stack); return 0; }
    keep[0] = keep[n - 1] = 1;
    mark(xy, 0, n - 1, tol, keep, stack);
    size_t m = compact(xy, n, keep);
    free(keep);
    free(stack);
    return m;
}

size_t pnpr_simplify_polygon(float *xy, size_t n, double tol)
{
    if (n < 4) return n;
    /* the polygon with its first vertex repeated at the end, split at the farthest vertex */
    float *p = malloc(2 * (n + 1) * sizeof *p);
    uint8_t *keep = calloc(n + 1, 1);
    size_t *stack = malloc(2 * (n + 1) * sizeof *stack);
    if (!p || !keep || !stack) { free(p); free(keep); free(stack); return 0; }
    memcpy(p, xy, 2 * n * sizeof *p);
    p[2 * n] = xy[0];
    p[2 * n + 1] = xy[1];
    size_t far = 1;
    double dmax = -1;
    for (size_t i = 1; i < n; i++) {
        double d = hypot(p[2 * i] - p[0], p[2 * i + 1] - p[1]);
        if (d > dmax) { dmax = d; far = i; }
    }
    keep[0] = keep[far] = keep[n] = 1;
    mark(p, 0, far, tol, keep, stack);
    mark(p, far, n, tol, keep, stack);
    keep[n] = 0; /* not repeated */
    size_t m = compact(p, n, keep);
    memcpy(xy, p, 2 * m * sizeof *p);
    free(p);
    free(keep);
    free(stack);
    return m;
}
