/* Symmetric 3x3 eigen-decomposition by cyclic Jacobi rotations in double precision.
 * The matrix is scaled by its largest absolute entry first, so covariances of clouds at scale
 * 1e-6 or 1e6 converge alike; Jacobi is slower than the closed-form cubic but accurate for
 * nearly repeated eigenvalues (planar and linear neighbourhoods), which is what matters here. */
#include <pointnpr/features.h>

#include <math.h>
#include <string.h>

void pnpr_eigen_sym3(const double a_in[3][3], double w[3], double vec[3][3])
{
    double a[3][3], v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    double scale = 0.0;
    int finite = 1;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double x = 0.5 * (a_in[i][j] + a_in[j][i]); /* symmetrise */
            a[i][j] = x;
            if (!isfinite(x)) finite = 0;
            else if (fabs(x) > scale) scale = fabs(x);
        }
    if (!finite || scale == 0.0) {
        w[0] = w[1] = w[2] = 0.0;
        memcpy(vec, v, sizeof v);
        return;
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) a[i][j] /= scale;

    static const int P[3] = {0, 0, 1}, Q[3] = {1, 2, 2};
    for (int sweep = 0; sweep < 50; sweep++) {
        double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        if (off < 1e-36) break;
        for (int r = 0; r < 3; r++) {
            int p = P[r], q = Q[r];
            double apq = a[p][q];
            if (fabs(apq) < 1e-300) continue;
            double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            double t = fabs(theta) > 1e150 ? 0.5 / theta
                                           : (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
            double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
            a[p][p] -= t * apq;
            a[q][q] += t * apq;
            a[p][q] = a[q][p] = 0.0;
            int o = 3 - p - q; /* the remaining index */
            double aop = a[o][p], aoq = a[o][q];
            a[o][p] = a[p][o] = c * aop - s * aoq;
            a[o][q] = a[q][o] = s * aop + c * aoq;
            for (int k = 0; k < 3; k++) {
                double vkp = v[k][p], vkq = v[k][q];
                v[k][p] = c * vkp - s * vkq;
                v[k][q] = s * vkp + c * vkq;
            }
        }
    }
    /* sort ascending; eigenvectors are the columns of v */
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 2; i++)
        for (int j = i + 1; j < 3; j++)
            if (a[order[j]][order[j]] < a[order[i]][order[i]]) { int t = order[i]; order[i] = order[j]; order[j] = t; }
    for (int i = 0; i < 3; i++) {
        w[i] = a[order[i]][order[i]] * scale;
        double len = 0.0;
        for (int k = 0; k < 3; k++) len += v[k][order[i]] * v[k][order[i]];
        len = len > 0 ? 1.0 / sqrt(len) : 1.0;
        for (int k = 0; k < 3; k++) vec[i][k] = v[k][order[i]] * len;
    }
    /* right-handed: third = first x second */
    vec[2][0] = vec[0][1] * vec[1][2] - vec[0][2] * vec[1][1];
    vec[2][1] = vec[0][2] * vec[1][0] - vec[0][0] * vec[1][2];
    vec[2][2] = vec[0][0] * vec[1][1] - vec[0][1] * vec[1][0];
}
