/* Helpers shared by the drawing sources in vector/ (not installed). */
#ifndef PNPR_VECTOR_INTERNAL_H
#define PNPR_VECTOR_INTERNAL_H

#include <stddef.h>

/* Douglas-Peucker: simplifies the open polyline xy[0 .. n-1] (2 floats a vertex) in place to
 * within `tol`, keeping its first and last vertex; returns the vertices kept, or 0 when out of
 * memory (xy unchanged). */
size_t pnpr_simplify_polyline(float *xy, size_t n, double tol);

/* The same for a closed polygon: simplified as two open halves between its first vertex and the
 * vertex farthest from it; returns the vertices kept (the first vertex is not repeated). */
size_t pnpr_simplify_polygon(float *xy, size_t n, double tol);

#endif
