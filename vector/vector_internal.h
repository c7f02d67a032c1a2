/* Helpers shared by the drawing sources in vector/ (not installed). */
#ifndef PNPR_VECTOR_INTERNAL_H
#define PNPR_VECTOR_INTERNAL_H

#include <stddef.h>

/* A growing polyline of float vertices (2 a vertex); zero-initialised = empty; free(xy). */
typedef struct pnpr_polybuf {
    float *xy;
    size_t n, cap;
} pnpr_polybuf;

/* Appends (x, y); 0 when out of memory (the buffer unchanged). */
int pnpr_polybuf_push(pnpr_polybuf *b, float x, float y);

/* Douglas-Peucker: simplifies the open polyline xy[0 .. n-1] (2 floats a vertex) in place to
 * within `tol`, keeping its first and last vertex; returns the vertices kept, or 0 when out of
 * memory (xy unchanged). */
size_t pnpr_simplify_polyline(float *xy, size_t n, double tol);

/* The same for a closed polygon: simplified as two open halves between its first vertex and the
 * vertex farthest from it; returns the vertices kept (the first vertex is not repeated). */
size_t pnpr_simplify_polygon(float *xy, size_t n, double tol);

#endif
