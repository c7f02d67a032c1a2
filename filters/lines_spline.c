/* Profile lines, last step: least-squares cubic B-spline per chain, one more smoothing pass,
 * adaptive sampling into a polyline (PointWorks section 5.2, figure 6 e-f).
 *
 * - Parameter: chord length, normalised to [0,1].
 * - Spline: clamped uniform cubic B-spline with C = clamp(round(length / 3h) + 3, 4, L) control
 *   points for a chain of L points of length `length` (one control point per ~3 spacings: enough
 *   for corners of real edges, too few to follow scan noise).
 * - Fit: weighted least squares with a small second-difference penalty on the control points
 *   (lambda = 1e-3 * L / C), so that spans without data stay defined; the chain's two end points
 *   weigh 100x, so that lines meeting at a corner still meet after fitting. Solved as a banded
 *   symmetric system (half-bandwidth 3) by Cholesky in double: O(C).
 * - Extra smoothing (the paper's second pass "to eliminate high-frequency deviations"): every
 *   interior control point moves to 0.5 P_j + 0.25 (P_{j-1} + P_{j+1}).
 * - Sampling: each knot span is split recursively until the spline's midpoint lies within
 *   `tol` of the chord (at most 2^10 pieces per span).
 * Closed chains are fitted as open ones through their points plus the first point again. */
#include "lines_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Cubic B-spline basis functions at t on a clamped uniform knot vector with C control points:
 * returns the span index s (the nonzero functions are s-3 .. s) and fills N[0..3]. */
static int basis(double t, int C, double N[4])
{
    int spans = C - 3; /* number of knot intervals */
    double u = t * spans;
    int s = (int)floor(u);
    if (s < 0) s = 0;
    if (s > spans - 1) s = spans - 1;
    /* knots: k(i) = clamp(i - 3, 0, spans) for i = 0 .. C+3 */
#define KNOT(i) ((double)((i) - 3 < 0 ? 0 : ((i) - 3 > spans ? spans : (i) - 3)))
    int i = s + 3; /* knot interval [k(i), k(i+1)) contains u */
    double left[4], right[4];
    N[0] = 1.0;
    for (int j = 1; j <= 3; j++) {
        left[j] = u - KNOT(i + 1 - j);
        right[j] = KNOT(i + j) - u;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            double den = right[r + 1] + left[j - r];
            double tmp = den != 0.0 ? N[r] / den : 0.0;
            N[r] = saved + right[r + 1] * tmp;
            saved = left[j - r] * tmp;
        }
        N[j] = saved;
    }
#undef KNOT
    return s + 3 - 3; /* first nonzero control point index */
}

static void eval(const double *P, int C, double t, double r[3])
{
    double N[4];
    int f = basis(t, C, N);
    r[0] = r[1] = r[2] = 0.0;
    for (int j = 0; j < 4; j++)
        for (int a = 0; a < 3; a++) r[a] += N[j] * P[3 * (f + j) + a];
}

/* Banded symmetric positive definite solve, half-bandwidth W: A stored as A[i*(W+1) + d] =
 * A(i, i+d). Cholesky in place, then three right-hand sides. Returns 0 if not positive. */
#define W 3
static int band_solve(double *A, double *B, int n)
{
    for (int i = 0; i < n; i++) {
        for (int k = (i - W > 0 ? i - W : 0); k < i; k++) {
            double lki = A[k * (W + 1) + (i - k)];
            A[i * (W + 1)] -= lki * lki;
            for (int d = 1; d <= W && i + d < n; d++)
                if (i + d - k <= W) A[i * (W + 1) + d] -= lki * A[k * (W + 1) + (i + d - k)];
        }
        double dii = A[i * (W + 1)];
        if (!(dii > 0)) return 0;
        dii = sqrt(dii);
        A[i * (W + 1)] = dii;
        for (int d = 1; d <= W && i + d < n; d++) A[i * (W + 1) + d] /= dii;
    }
    for (int c = 0; c < 3; c++) {
        for (int i = 0; i < n; i++) { /* L y = b */
            double s = B[3 * i + c];
            for (int k = (i - W > 0 ? i - W : 0); k < i; k++) s -= A[k * (W + 1) + (i - k)] * B[3 * k + c];
            B[3 * i + c] = s / A[i * (W + 1)];
        }
        for (int i = n - 1; i >= 0; i--) { /* L^T x = y */
            double s = B[3 * i + c];
            for (int d = 1; d <= W && i + d < n; d++) s -= A[i * (W + 1) + d] * B[3 * (i + d) + c];
            B[3 * i + c] = s / A[i * (W + 1)];
        }
    }
    return 1;
}

static void sample_span(const double *P, int C, double a, double b, const double pa[3],
                        const double pb[3], double tol, int depth, pnpr_lines_buf *out)
{
    double m = 0.5 * (a + b), pm[3], e[3];
    eval(P, C, m, pm);
    for (int k = 0; k < 3; k++) e[k] = pm[k] - 0.5 * (pa[k] + pb[k]);
    if (depth < 10 && e[0] * e[0] + e[1] * e[1] + e[2] * e[2] > tol * tol) {
        sample_span(P, C, a, m, pa, pm, tol, depth + 1, out);
        sample_span(P, C, m, b, pm, pb, tol, depth + 1, out);
        return;
    }
    pnpr_lines_buf_push(out, pa);
}

int pnpr_lines_fit_chain(const double *q, size_t L, int closed, double h, double tol,
                         pnpr_lines_buf *out)
{
    size_t n = L + (closed ? 1 : 0);
    if (L < 4) { /* too short for a cubic: keep the points */
        for (size_t i = 0; i < L; i++) if (!pnpr_lines_buf_push(out, q + 3 * i)) return 0;
        return 1;
    }
    double *t = malloc(n * sizeof *t);
    if (!t) return 0;
    double len = 0;
    t[0] = 0;
    for (size_t i = 1; i < n; i++) {
        const double *a = q + 3 * (i - 1), *b = q + 3 * (i % L);
        double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        len += sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        t[i] = len;
    }
    if (!(len > 0)) { /* all points coincide */
        free(t);
        return pnpr_lines_buf_push(out, q);
    }
    for (size_t i = 1; i < n; i++) t[i] /= len;
    double cc = floor(len / (3.0 * h) + 0.5) + 3;
    int C = cc < 4 ? 4 : (cc > (double)n ? (int)n : (int)cc);
    if (C < 4) C = 4;
    double *A = calloc((size_t)C * (W + 1), sizeof *A), *P = calloc(3 * (size_t)C, sizeof *P);
    if (!A || !P) { free(t); free(A); free(P); return 0; }
    for (size_t i = 0; i < n; i++) {
        double N[4];
        int f = basis(t[i], C, N);
        double w = (i == 0 || i + 1 == n) ? 100.0 : 1.0;
        const double *qi = q + 3 * (i % L);
        for (int j = 0; j < 4; j++) {
            for (int k = j; k < 4; k++) A[(f + j) * (W + 1) + (k - j)] += w * N[j] * N[k];
            for (int a = 0; a < 3; a++) P[3 * (f + j) + a] += w * N[j] * qi[a];
        }
    }
    /* second-difference penalty: lambda * sum |P_{j-1} - 2 P_j + P_{j+1}|^2 */
    double lambda = 1e-3 * (double)n / (double)C;
    for (int j = 1; j + 1 < C; j++) {
        const int idx[3] = {j - 1, j, j + 1};
        const double c[3] = {1, -2, 1};
        for (int x = 0; x < 3; x++)
            for (int y = x; y < 3; y++) A[idx[x] * (W + 1) + (idx[y] - idx[x])] += lambda * c[x] * c[y];
    }
    int ok = band_solve(A, P, C);
    if (ok) {
        /* the paper's extra smoothing pass, ends fixed */
        double prev[3] = {P[0], P[1], P[2]};
        for (int j = 1; j + 1 < C; j++) {
            double cur[3] = {P[3 * j], P[3 * j + 1], P[3 * j + 2]};
            for (int a = 0; a < 3; a++) P[3 * j + a] = 0.5 * cur[a] + 0.25 * (prev[a] + P[3 * (j + 1) + a]);
            memcpy(prev, cur, sizeof prev);
        }
        int spans = C - 3;
        for (int s = 0; s < spans; s++) {
            double a = (double)s / spans, b = (double)(s + 1) / spans, pa[3], pb[3];
            eval(P, C, a, pa);
            eval(P, C, b, pb);
            sample_span(P, C, a, b, pa, pb, tol, 0, out);
        }
        if (!closed) {
            double pe[3];
            eval(P, C, 1.0, pe);
            pnpr_lines_buf_push(out, pe);
        }
    } else { /* singular (cannot happen with the penalty, but defined): the points themselves */
        for (size_t i = 0; i < L; i++) pnpr_lines_buf_push(out, q + 3 * i);
    }
    free(t); free(A); free(P);
    return out->ok;
}
