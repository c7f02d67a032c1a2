/* Internal pieces of the profile-line stage shared by filters/lines.c and lines_spline.c. */
#ifndef PNPR_LINES_INTERNAL_H
#define PNPR_LINES_INTERNAL_H

#include <pointnpr/lines.h>

/* A growable array of 3D points (double). ok = 0 after an allocation failure. */
typedef struct pnpr_lines_buf {
    double *p;
    size_t n, cap;
    int ok;
} pnpr_lines_buf;

int pnpr_lines_buf_push(pnpr_lines_buf *b, const double p[3]);

/* Fits chain q[0..L-1] (closed: q[L-1] connects back to q[0]) with a cubic B-spline and appends
 * the sampled polyline to out (closed chains: without repeating the first point). h = spacing,
 * tol = max chord deviation. Returns 0 on allocation failure. */
int pnpr_lines_fit_chain(const double *q, size_t L, int closed, double h, double tol,
                         pnpr_lines_buf *out);

#endif
