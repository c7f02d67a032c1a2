/* A sample of a cloud for one view (include/pointnpr/crq.h, docs/tiles.md "Drawing a cloud larger
 * than memory"): the cone test, the depth histogram and the solve for c. */
#include <pointnpr/crq.h>

#include <math.h>
#include <string.h>

pnpr_status pnpr_view_sample_init(pnpr_view_sample *v, const double eye[3], const double target[3], double fov_deg,
                                  int width, int height)
{
    if (!v || !eye || !target) return PNPR_ERR_INVALID_ARGUMENT;
    memset(v, 0, sizeof *v);
    double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    double len = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(len > 0) || !isfinite(len) || !isfinite(eye[0] + eye[1] + eye[2]) || !(fov_deg > 0 && fov_deg < 180) ||
        width <= 0 || height <= 0)
        return PNPR_ERR_INVALID_ARGUMENT;
    for (int k = 0; k < 3; k++) {
        v->eye[k] = eye[k];
        v->forward[k] = f[k] / len;
    }
    double ty = tan(0.5 * fov_deg * 3.14159265358979323846 / 180.0), tx = ty * width / height;
    v->tan_cone = PNPR_VIEW_SAMPLE_MARGIN * sqrt(tx * tx + ty * ty);
    return isfinite(v->tan_cone) ? PNPR_OK : PNPR_ERR_INVALID_ARGUMENT;
}

double pnpr_view_sample_depth(const pnpr_view_sample *v, const double p[3])
{
    double d[3] = {p[0] - v->eye[0], p[1] - v->eye[1], p[2] - v->eye[2]};
    double z = d[0] * v->forward[0] + d[1] * v->forward[1] + d[2] * v->forward[2];
    if (!(z > 0) || !isfinite(z)) return 0;
    double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - z * z;
    return r2 <= z * z * v->tan_cone * v->tan_cone ? z : 0;
}

static int depth_bin(double z)
{
    double b = floor((log2(z) + 64.0) * 16.0);
    return b < 0 ? 0 : b >= PNPR_VIEW_SAMPLE_BINS ? PNPR_VIEW_SAMPLE_BINS - 1 : (int)b;
}

void pnpr_view_sample_add(pnpr_view_sample *v, const double p[3])
{
    double z = pnpr_view_sample_depth(v, p);
    if (z == 0) return;
    int b = depth_bin(z);
    if (!v->visible || z < v->z_min) v->z_min = z;
    if (!v->visible || z > v->z_max) v->z_max = z;
    v->count[b]++;
    v->inv_z2[b] += 1.0 / (z * z);
    v->visible++;
}

/* The expected count for c: a bin gives c x its sum of 1/z^2, at most its count (exact unless the
 * share reaches 1 inside the bin). */
static double expected(const pnpr_view_sample *v, double c)
{
    double n = 0;
    for (int b = 0; b < PNPR_VIEW_SAMPLE_BINS; b++) {
        double s = c * v->inv_z2[b];
        n += s < (double)v->count[b] ? s : (double)v->count[b];
    }
    return n;
}

void pnpr_view_sample_solve(pnpr_view_sample *v, double want)
{
    if (!(want > 0)) { v->c = 0; return; } /* nothing (NaN too) */
    if (!((double)v->visible > want)) { v->c = HUGE_VAL; return; }
    /* log2 c between the depths squared: shares from 2^-80 at the nearest to 1 at the farthest */
    double lo = 2.0 * log2(v->z_min) - 80.0, hi = 2.0 * log2(v->z_max) + 1.0;
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (expected(v, exp2(mid)) > want) hi = mid;
        else lo = mid;
    }
    v->c = exp2(lo);
}

double pnpr_view_sample_share(const pnpr_view_sample *v, const double p[3])
{
    double z = pnpr_view_sample_depth(v, p);
    if (z == 0) return 0;
    double s = v->c / (z * z);
    return s < 1 ? s : 1;
}
