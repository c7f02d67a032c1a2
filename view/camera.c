/* Camera: auto-fit and the look-at / perspective matrices (in double, relative to the cloud's
 * origin, then converted to float). */
#include "view_internal.h"
#include <pointnpr/outliers.h>
#include "../core/vec3.h"

#include <math.h>
#include <string.h>

static const double PNPR_PI = 3.14159265358979323846;

pnpr_status pnpr_camera_fit(const pnpr_cloud *cloud, const double dir[3], float fov_y_deg,
                            float aspect, pnpr_camera *r_camera)
{
    if (!cloud || !r_camera) return PNPR_ERR_INVALID_ARGUMENT;
    float bmin[3], bmax[3];
    if (pnpr_cloud_inlier_bounds(cloud, bmin, bmax) == 0) return PNPR_ERR_EMPTY;
    if (!(fov_y_deg > 0 && fov_y_deg < 179)) fov_y_deg = 45;
    if (!(aspect > 0) || !isfinite(aspect)) aspect = 1;
    double d[3] = {0, -1, 0.5};
    if (dir) { d[0] = dir[0]; d[1] = dir[1]; d[2] = dir[2]; }
    if (!(pnpr_normalize3(d) > 0)) { d[0] = 0; d[1] = -1; d[2] = 0.5; pnpr_normalize3(d); }
    double c[3];
    for (int a = 0; a < 3; a++) c[a] = 0.5 * ((double)bmin[a] + (double)bmax[a]);
    /* camera basis: right s, up u, towards the eye d */
    double up0[3] = {0, 0, 1};
    if (fabs(d[2]) > 0.999) { up0[0] = 0; up0[1] = 1; up0[2] = 0; }
    double s[3], u[3], f[3] = {-d[0], -d[1], -d[2]};
    pnpr_cross3(f, up0, s);
    pnpr_normalize3(s);
    pnpr_cross3(s, f, u);
    /* the nearest distance (along d, from the box centre) at which all 8 corners are inside
     * the frustum: corner at (x, y) across and z towards the eye needs
     * dist >= z + |x| / tan(half_x) and dist >= z + |y| / tan(half_y) */
    double tan_y = tan(0.5 * fov_y_deg * PNPR_PI / 180.0), tan_x = tan_y * aspect;
    double dist = 0, extent = 0;
    for (int k = 0; k < 8; k++) {
        double p[3] = {((k & 1) ? bmax[0] : bmin[0]) - c[0], ((k & 2) ? bmax[1] : bmin[1]) - c[1],
                       ((k & 4) ? bmax[2] : bmin[2]) - c[2]};
        double x = fabs(pnpr_dot3(p, s)), y = fabs(pnpr_dot3(p, u)), z = pnpr_dot3(p, d);
        double need = z + (x / tan_x > y / tan_y ? x / tan_x : y / tan_y);
        if (need > dist) dist = need;
        double e = sqrt(pnpr_dot3(p, p));
        if (e > extent) extent = e;
    }
    if (!(extent > 0)) { extent = 1; dist = 1 / tan_y; } /* a single point */
    dist *= 1.04; /* a small margin */
    if (dist < extent * 1.01) dist = extent * 1.01; /* keep the eye outside the box */
    memset(r_camera, 0, sizeof *r_camera);
    for (int a = 0; a < 3; a++) {
        r_camera->target[a] = cloud->origin[a] + c[a];
        r_camera->eye[a] = r_camera->target[a] + d[a] * dist;
    }
    memcpy(r_camera->up, up0, sizeof up0);
    r_camera->fov_y_deg = fov_y_deg;
    return PNPR_OK;
}

/* The tightest symmetric frustum along the fixed basis (s right, u up, d towards the eye) around
 * every point inside the robust bounds: a point at
 * (x, y, z) relative to the centre is inside when |x - dx| <= (dist - z) tan_x (and alike in y),
 * which gives dist and the lateral shift (dx, dy) in closed form. r_zmax: the largest z. */
static void fit_frustum(const pnpr_cloud *cloud, const pnpr_view_info *info, const double c[3],
                        const double s[3], const double u[3], const double d[3], double tan_x,
                        double tan_y, double r_fit[3], double *r_zmax)
{
    double px = -INFINITY, mx = INFINITY, py = -INFINITY, my = INFINITY, zmax = -INFINITY;
    for (size_t i = 0; i < cloud->count; i++) {
        const float *q = cloud->xyz + 3 * i;
        int in = 1;
        for (int a = 0; a < 3; a++) in &= q[a] >= info->lo[a] && q[a] <= info->hi[a]; /* NaN: out */
        if (!in) continue;
        double p[3] = {q[0] - c[0], q[1] - c[1], q[2] - c[2]};
        double x = pnpr_dot3(p, s), y = pnpr_dot3(p, u), z = pnpr_dot3(p, d);
        if (x + z * tan_x > px) px = x + z * tan_x;
        if (x - z * tan_x < mx) mx = x - z * tan_x;
        if (y + z * tan_y > py) py = y + z * tan_y;
        if (y - z * tan_y < my) my = y - z * tan_y;
        if (z > zmax) zmax = z;
    }
    if (!(zmax > -INFINITY)) { px = mx = py = my = zmax = 0; } /* no point inside (not reached) */
    double dist_x = (px - mx) / (2 * tan_x), dist_y = (py - my) / (2 * tan_y);
    r_fit[0] = 0.5 * (px + mx);
    r_fit[1] = 0.5 * (py + my);
    r_fit[2] = dist_x > dist_y ? dist_x : dist_y;
    *r_zmax = zmax;
}

/* near/far around the robust bounds (widened by a quarter diagonal), for clouds with far outliers. */
static void robust_depth_range(const pnpr_view_info *info, const double eye[3], const double f[3],
                               pnpr_camera *cam)
{
    double dmin = INFINITY, dmax = -INFINITY, e[3];
    for (int a = 0; a < 3; a++) e[a] = (double)info->hi[a] - (double)info->lo[a];
    double diag = sqrt(pnpr_dot3(e, e));
    for (int k = 0; k < 8; k++) {
        double p[3] = {((k & 1) ? info->hi[0] : info->lo[0]) - eye[0], ((k & 2) ? info->hi[1] : info->lo[1]) - eye[1],
                       ((k & 4) ? info->hi[2] : info->lo[2]) - eye[2]};
        dmin = fmin(dmin, pnpr_dot3(p, f));
        dmax = fmax(dmax, pnpr_dot3(p, f));
    }
    double fa = dmax + 0.25 * diag, n = dmin - 0.25 * diag;
    if (n < fa * 1e-3) n = fa * 1e-3;
    if (!(fa > 0) || !isfinite(fa) || !(n > 0)) return; /* leave them automatic */
    cam->near_plane = (float)n;
    cam->far_plane = (float)fa;
}

pnpr_status pnpr_camera_default(const pnpr_cloud *cloud, const pnpr_view_options *opts,
                                float fov_y_deg, float aspect, pnpr_camera *r_camera,
                                pnpr_view_info *r_info)
{
    if (!cloud || !r_camera) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_view_info info;
    pnpr_status st = pnpr_scene_frame(cloud, opts, &info);
    if (st != PNPR_OK) return st;
    if (!(fov_y_deg > 0 && fov_y_deg < 179)) fov_y_deg = 45;
    if (!(aspect > 0) || !isfinite(aspect)) aspect = 1;
    const double *d = info.view_dir;
    double f[3] = {-d[0], -d[1], -d[2]}, s[3], u[3], c[3], fit[3], zmax, e[3];
    pnpr_cross3(f, info.up, s);
    pnpr_normalize3(s);
    pnpr_cross3(s, f, u);
    for (int a = 0; a < 3; a++) {
        c[a] = 0.5 * ((double)info.lo[a] + (double)info.hi[a]);
        e[a] = (double)info.hi[a] - (double)info.lo[a];
    }
    double tan_y = tan(0.5 * fov_y_deg * PNPR_PI / 180.0), diag = sqrt(pnpr_dot3(e, e));
    fit_frustum(cloud, &info, c, s, u, d, tan_y * aspect / 1.05, tan_y / 1.05, fit, &zmax); /* 5% margin */
    double dist = fit[2], min_dist = diag > 0 ? zmax + 0.02 * diag : 1 / tan_y; /* eye outside the content */
    if (!(dist >= min_dist)) dist = min_dist;
    memset(r_camera, 0, sizeof *r_camera);
    double eye[3];
    for (int a = 0; a < 3; a++) {
        double t = c[a] + s[a] * fit[0] + u[a] * fit[1];
        eye[a] = t + d[a] * dist;
        r_camera->target[a] = cloud->origin[a] + t;
        r_camera->eye[a] = cloud->origin[a] + eye[a];
        r_camera->up[a] = info.up[a];
    }
    r_camera->fov_y_deg = fov_y_deg;
    if (info.outliers > 0) robust_depth_range(&info, eye, f, r_camera);
    if (r_info) *r_info = info;
    return PNPR_OK;
}

/* The look-at camera's view (relative to origin) and projection in double. */
static pnpr_status lookat_matrices(const pnpr_camera *cam, const double origin[3], const float bmin[3],
                                   const float bmax[3], int have_box, int width, int height,
                                   double view_out[16], double proj_out[16], double *r_near,
                                   double *r_far, pnpr_error *err)
{
    double eye[3], f[3], up[3];
    for (int a = 0; a < 3; a++) {
        if (!isfinite(cam->eye[a]) || !isfinite(cam->target[a]) || !isfinite(cam->up[a]))
            return pnpr_error_set(err, PNPR_ERR_NUMERIC, "camera: eye, target and up must be finite");
        eye[a] = cam->eye[a] - origin[a]; /* in double: origins may be ~1e6 */
        f[a] = (cam->target[a] - origin[a]) - eye[a];
        up[a] = cam->up[a];
    }
    if (!(pnpr_normalize3(f) > 0))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "camera: eye and target are the same point");
    double s[3], u[3];
    pnpr_cross3(f, up, s);
    if (!(pnpr_normalize3(s) > 1e-12))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "camera: up is zero or parallel to the view direction");
    pnpr_cross3(s, f, u);
    float fov = cam->fov_y_deg;
    if (fov == 0) fov = 45;
    if (!(fov > 0 && fov < 179))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "camera: fov %g is not in (0, 179) degrees", (double)fov);
    double view[16] = {
        s[0], u[0], -f[0], 0,
        s[1], u[1], -f[1], 0,
        s[2], u[2], -f[2], 0,
        -pnpr_dot3(s, eye), -pnpr_dot3(u, eye), pnpr_dot3(f, eye), 1};
    double n = cam->near_plane, fa = cam->far_plane;
    if (!(n > 0) || !(fa > n)) {
        /* automatic: the depth range of the box corners along the view direction */
        double dmin = INFINITY, dmax = -INFINITY;
        if (have_box) {
            for (int k = 0; k < 8; k++) {
                double p[3] = {(k & 1) ? bmax[0] : bmin[0], (k & 2) ? bmax[1] : bmin[1],
                               (k & 4) ? bmax[2] : bmin[2]};
                double d = (p[0] - eye[0]) * f[0] + (p[1] - eye[1]) * f[1] + (p[2] - eye[2]) * f[2];
                if (d < dmin) dmin = d;
                if (d > dmax) dmax = d;
            }
        }
        if (!(dmax > 0)) { dmin = 0.1; dmax = 1; } /* nothing in front: any valid range */
        double far_auto = dmax * 1.05 + 1e-6;
        double near_auto = dmin * 0.95;
        if (near_auto < far_auto * 1e-4) near_auto = far_auto * 1e-4;
        if (!(n > 0)) n = near_auto;
        if (!(fa > n)) fa = far_auto > n ? far_auto : n * 1e4;
    }
    double t = 1.0 / tan(0.5 * fov * PNPR_PI / 180.0);
    double aspect = (double)width / (double)height;
    double proj[16] = {0};
    proj[0] = t / aspect;
    proj[5] = t;
    proj[10] = -(fa + n) / (fa - n);
    proj[11] = -1;
    proj[14] = -2 * fa * n / (fa - n);
    memcpy(view_out, view, sizeof view);
    memcpy(proj_out, proj, sizeof proj);
    *r_near = n;
    *r_far = fa;
    return PNPR_OK;
}

pnpr_status pnpr_frame_camera_make(const pnpr_camera *cam, const double origin[3],
                                   const float bmin[3], const float bmax[3], int have_box,
                                   int width, int height, pnpr_frame_camera *r, pnpr_error *err)
{
    double view[16], proj[16], n, fa;
    pnpr_status st = lookat_matrices(cam, origin, bmin, bmax, have_box, width, height, view, proj, &n, &fa, err);
    if (st != PNPR_OK) return st;
    for (int i = 0; i < 16; i++) { r->view[i] = (float)view[i]; r->proj[i] = (float)proj[i]; }
    r->pixels_per_unit = (float)(proj[5] * height * 0.5);
    r->near_plane = n;
    r->far_plane = fa;
    r->ortho = 0;
    return PNPR_OK;
}

pnpr_status pnpr_camera_matrices_from_camera(const pnpr_camera *camera, const pnpr_cloud *cloud,
                                             int width, int height, pnpr_camera_matrices *r_m,
                                             pnpr_error *err)
{
    if (!camera || !r_m)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "camera matrices: camera and result are required");
    if (width <= 0 || height <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "camera matrices: size %d x %d is not positive", width, height);
    double origin[3] = {0, 0, 0};
    float bmin[3] = {0, 0, 0}, bmax[3] = {0, 0, 0};
    int have_box = 0;
    if (cloud) {
        memcpy(origin, cloud->origin, sizeof origin);
        have_box = pnpr_cloud_inlier_bounds(cloud, bmin, bmax) > 0;
    }
    double view[16], proj[16], n, fa;
    pnpr_status st = lookat_matrices(camera, origin, bmin, bmax, have_box, width, height, view, proj, &n, &fa, err);
    if (st != PNPR_OK) return st;
    /* world view = view_rel * translate(-origin) */
    memcpy(r_m->view, view, sizeof view);
    for (int row = 0; row < 4; row++)
        r_m->view[12 + row] = view[12 + row] - (view[row] * origin[0] + view[4 + row] * origin[1] + view[8 + row] * origin[2]);
    memcpy(r_m->projection, proj, sizeof proj);
    return PNPR_OK;
}

pnpr_status pnpr_frame_camera_from_matrices(const pnpr_camera_matrices *m, const double origin[3],
                                            int width, int height, pnpr_frame_camera *r, pnpr_error *err)
{
    const double *V = m->view;
    double P[16];
    for (int i = 0; i < 16; i++) {
        if (!isfinite(V[i]) || !isfinite(m->projection[i]))
            return pnpr_error_set(err, PNPR_ERR_NUMERIC, "camera matrices: view and projection must be finite");
        P[i] = m->projection[i];
    }
    if (V[3] != 0 || V[7] != 0 || V[11] != 0 || V[15] != 1)
        return pnpr_error_set(err, PNPR_ERR_NUMERIC, "camera matrices: the view must be affine (last row 0 0 0 1)");
    double det = V[0] * (V[5] * V[10] - V[9] * V[6]) - V[4] * (V[1] * V[10] - V[9] * V[2]) +
                 V[8] * (V[1] * V[6] - V[5] * V[2]);
    if (!(fabs(det) > 1e-300) || !isfinite(det))
        return pnpr_error_set(err, PNPR_ERR_NUMERIC, "camera matrices: the view is not invertible");
    double scale = cbrt(fabs(det));
    if (fabs(scale - 1) < 1e-12) scale = 1;
    /* the projection's last row (P[3], P[7], P[11], P[15]) picks the kind; normalise it so that
     * w = -z_eye (perspective) or w = 1 (orthographic): the same image, GL's usual form */
    int ortho;
    double k;
    if (P[3] != 0 || P[7] != 0)
        return pnpr_error_set(err, PNPR_ERR_NUMERIC, "camera matrices: the projection is neither perspective nor orthographic");
    if (P[11] == 0 && P[15] > 0) { ortho = 1; k = P[15]; }
    else if (P[11] < 0 && P[15] == 0) { ortho = 0; k = -P[11]; }
    else
        return pnpr_error_set(err, PNPR_ERR_NUMERIC, "camera matrices: the projection is neither perspective nor orthographic");
    for (int i = 0; i < 16; i++) P[i] /= k;
    if (P[0] == 0 || P[5] == 0 || P[10] == 0)
        return pnpr_error_set(err, PNPR_ERR_NUMERIC, "camera matrices: the projection is degenerate");
    double n, fa;
    if (ortho) {
        n = (P[14] + 1) / P[10];
        fa = (P[14] - 1) / P[10];
    } else {
        n = P[14] / (P[10] - 1);
        fa = P[14] / (P[10] + 1);
        if (!(n > 0) || !isfinite(n))
            return pnpr_error_set(err, PNPR_ERR_NUMERIC, "camera matrices: the perspective near plane is not in front of the eye");
    }
    /* rebase on the cloud's origin in double: view * translate(origin) */
    double view[16];
    memcpy(view, V, sizeof view);
    for (int row = 0; row < 4; row++)
        view[12 + row] = V[row] * origin[0] + V[4 + row] * origin[1] + V[8 + row] * origin[2] + V[12 + row];
    for (int i = 0; i < 16; i++) { r->view[i] = (float)view[i]; r->proj[i] = (float)P[i]; }
    r->pixels_per_unit = (float)(fabs(P[5]) * height * 0.5 * scale);
    r->near_plane = n;
    r->far_plane = fa;
    r->ortho = ortho;
    (void)width;
    return PNPR_OK;
}

double pnpr_box_coverage(const pnpr_frame_camera *fc, const float bmin[3], const float bmax[3],
                         int width, int height)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int k = 0; k < 8; k++) {
        double p[4] = {(k & 1) ? bmax[0] : bmin[0], (k & 2) ? bmax[1] : bmin[1],
                       (k & 4) ? bmax[2] : bmin[2], 1};
        double e[4] = {0}, c[4] = {0};
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) e[i] += (double)fc->view[j * 4 + i] * p[j];
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) c[i] += (double)fc->proj[j * 4 + i] * e[j];
        if (!(c[3] > 1e-9)) return (double)width * height; /* behind the eye: assume all */
        double x = (c[0] / c[3] * 0.5 + 0.5) * width, y = (c[1] / c[3] * 0.5 + 0.5) * height;
        if (x < x0) x0 = x;
        if (x > x1) x1 = x;
        if (y < y0) y0 = y;
        if (y > y1) y1 = y;
    }
    /* whole pixels: a box seen as a point or a line (one point, duplicates, a flat cloud edge-on)
     * still covers the pixels it falls on; one wholly outside the view covers none */
    x0 = floor(x0);
    y0 = floor(y0);
    x1 = floor(x1) + 1;
    y1 = floor(y1) + 1;
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > width) x1 = width;
    if (y1 > height) y1 = height;
    if (!(x1 > x0) || !(y1 > y0)) return 0;
    return (x1 - x0) * (y1 - y0);
}
