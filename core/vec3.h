/* Small 3-vector helpers (not installed), shared by the library's sources. */
#ifndef PNPR_VEC3_H
#define PNPR_VEC3_H

#include <math.h>

static inline double pnpr_dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static inline void pnpr_cross3(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

/* Whether all three components are finite (float and double points). */
static inline int pnpr_finite3f(const float p[3]) { return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]); }
static inline int pnpr_finite3d(const double p[3]) { return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]); }

/* The squared distance between float points x and q as the kd-tree computes it ((x - q) per axis,
 * summed x, y, z in float): the spacing and painterly's brush test use it too, so that their
 * distances equal the kNN's bit for bit. */
static inline float pnpr_dist2f(const float x[3], const float q[3])
{
    float dx = x[0] - q[0], dy = x[1] - q[1], dz = x[2] - q[2];
    return dx * dx + dy * dy + dz * dz;
}

/* Scales v to unit length when its length is positive and finite; returns the length. */
static inline double pnpr_normalize3(double v[3])
{
    double l = sqrt(pnpr_dot3(v, v));
    if (l > 0 && isfinite(l)) { v[0] /= l; v[1] /= l; v[2] /= l; }
    return l;
}

#endif
