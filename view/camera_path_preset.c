/* Camera path presets (camera_path.h): an orbit around the start camera's target and a straight
 * flyover, both about the scene's up axis; the start camera of a cloud. Pure CPU. */
#include "camera_path_internal.h"
#include "../core/vec3.h"

#include <pointnpr/options.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PATH_PI = 3.14159265358979323846;

/* Orbit keys are at most this many degrees apart: the spline between them then stays within
 * 1e-4 of the radius of the circle (8e-5 measured; 10 degrees: 2e-3, the picture would breathe
 * by about a pixel at 720p). */
static const double ORBIT_KEY_DEGREES = 2;

/* Splits eye - target into its height along unit `up` and its horizontal part (r_h). */
static double split_view(const pnpr_camera *start, const double up[3], double r_h[3])
{
    double v[3] = {start->eye[0] - start->target[0], start->eye[1] - start->target[1], start->eye[2] - start->target[2]};
    double a = pnpr_dot3(v, up);
    for (int c = 0; c < 3; c++) r_h[c] = v[c] - a * up[c];
    return a;
}

static void key_set(pnpr_camera_key *k, double t, const double eye[3], const double target[3], const double up[3], double fov)
{
    k->time = t;
    memcpy(k->eye, eye, sizeof k->eye);
    memcpy(k->target, target, sizeof k->target);
    memcpy(k->up, up, sizeof k->up);
    k->fov_y_deg = fov;
}

static pnpr_status orbit(const pnpr_camera *start, const double up[3], double duration, double degrees, double fov,
                         pnpr_camera_path *p)
{
    double h[3], w[3];
    double a = split_view(start, up, h);
    pnpr_cross3(up, h, w); /* h turned 90 degrees about up */
    size_t n = (size_t)ceil(fabs(degrees) / ORBIT_KEY_DEGREES) + 1;
    if (n < 3) n = 3;
    p->keys = calloc(n, sizeof *p->keys);
    if (!p->keys) return PNPR_ERR_OUT_OF_MEMORY;
    p->count = n;
    for (size_t j = 0; j < n; j++) {
        double th = degrees * PATH_PI / 180.0 * (double)j / (double)(n - 1), eye[3];
        for (int c = 0; c < 3; c++) eye[c] = start->target[c] + a * up[c] + cos(th) * h[c] + sin(th) * w[c];
        key_set(&p->keys[j], duration * (double)j / (double)(n - 1), j == 0 ? start->eye : eye, start->target, up, fov);
    }
    if (fabs(degrees) == 360) { /* a closed loop: the last key is the first one again */
        memcpy(p->keys[n - 1].eye, p->keys[0].eye, sizeof p->keys[0].eye);
        p->loop = 1;
    }
    return PNPR_OK;
}

static pnpr_status flyover(const pnpr_camera *start, const double up[3], double duration, double fov, pnpr_camera_path *p)
{
    double h[3], f[3];
    double a = split_view(start, up, h), dist = sqrt(pnpr_dot3(h, h)), radius = dist / 2.2;
    if (!(a > 0)) a = 0.9 * radius; /* a start below its target: fly above it anyway */
    for (int c = 0; c < 3; c++) f[c] = -h[c] / dist;
    p->keys = calloc(2, sizeof *p->keys);
    if (!p->keys) return PNPR_ERR_OUT_OF_MEMORY;
    p->count = 2;
    for (int j = 0; j < 2; j++) {
        double eye[3], target[3];
        for (int c = 0; c < 3; c++) {
            eye[c] = start->target[c] + h[c] + a * up[c] + f[c] * 2.2 * radius * j;
            target[c] = eye[c] + f[c] * 1.2 * radius - a * up[c];
        }
        key_set(&p->keys[j], duration * j, eye, target, up, fov);
    }
    return PNPR_OK;
}

pnpr_status pnpr_camera_path_preset(pnpr_camera_preset preset, const pnpr_camera *start, const double up[3],
                                    const pnpr_camera_preset_options *opts, pnpr_camera_path *r_path, pnpr_error *err)
{
    if (!start || !r_path) return PNPR_ERR_INVALID_ARGUMENT;
    memset(r_path, 0, sizeof *r_path);
    pnpr_camera_preset_options o = {0, 0};
    if (opts) o = *opts;
    size_t nt;
    const pnpr_option_desc *table = pnpr_camera_preset_option_table(&nt);
    pnpr_status cst = pnpr_option_check(table, nt, &o, err); /* the ranges: options.h */
    if (cst != PNPR_OK) return cst;
    pnpr_option_fill_defaults(table, nt, &o);
    double duration = o.duration, degrees = o.degrees;
    double u[3] = {up ? up[0] : start->up[0], up ? up[1] : start->up[1], up ? up[2] : start->up[2]}, h[3];
    double fov = start->fov_y_deg > 0 ? start->fov_y_deg : 45;
    if ((unsigned)preset >= PNPR_PRESET_COUNT_) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "unknown camera preset %d", (int)preset);
    if (!(pnpr_normalize3(u) > 0) || !isfinite(u[0] + u[1] + u[2]))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "camera preset: the up axis is zero or not finite");
    split_view(start, u, h);
    double v[3] = {start->eye[0] - start->target[0], start->eye[1] - start->target[1], start->eye[2] - start->target[2]};
    if (!(sqrt(pnpr_dot3(h, h)) > 1e-6 * sqrt(pnpr_dot3(v, v))))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "camera preset: the start camera looks along the up axis (no horizontal direction to move in)");
    pnpr_status st = preset == PNPR_PRESET_ORBIT ? orbit(start, u, duration, degrees, fov, r_path) : flyover(start, u, duration, fov, r_path);
    if (st == PNPR_OK) st = pnpr_camera_path_check(r_path, err);
    if (st != PNPR_OK) pnpr_camera_path_free(r_path);
    return st;
}

/* The distance from the target at which the points inside the robust bounds (at most 20000 of
 * them, evenly strided) fit the frustum (5% margin, as the default camera) when the eye at unit
 * direction d0 from the target is turned about `up` to any of 36 azimuths. */
static double orbit_fit_distance(const pnpr_cloud *cloud, const pnpr_view_info *info, const double target[3],
                                 const double d0[3], const double up[3], double tan_x, double tan_y)
{
    size_t stride = cloud->count / 20000 + 1;
    double need = 0, h0[3], w0[3], a = pnpr_dot3(d0, up);
    for (int c = 0; c < 3; c++) h0[c] = d0[c] - a * up[c];
    pnpr_cross3(up, h0, w0);
    for (int k = 0; k < 36; k++) {
        double th = k * PATH_PI / 18, d[3], s[3], u[3], f[3];
        for (int c = 0; c < 3; c++) { d[c] = a * up[c] + cos(th) * h0[c] + sin(th) * w0[c]; f[c] = -d[c]; }
        pnpr_cross3(f, up, s);
        pnpr_normalize3(s);
        pnpr_cross3(s, f, u);
        for (size_t i = 0; i < cloud->count; i += stride) {
            const float *q = cloud->xyz + 3 * i;
            int in = 1;
            for (int c = 0; c < 3; c++) in &= q[c] >= info->lo[c] && q[c] <= info->hi[c]; /* NaN: out */
            if (!in) continue;
            double p[3] = {cloud->origin[0] + q[0] - target[0], cloud->origin[1] + q[1] - target[1], cloud->origin[2] + q[2] - target[2]};
            double x = fabs(pnpr_dot3(p, s)) / tan_x, y = fabs(pnpr_dot3(p, u)) / tan_y, z = pnpr_dot3(p, d);
            if (z + (x > y ? x : y) > need) need = z + (x > y ? x : y);
        }
    }
    return need;
}

pnpr_status pnpr_camera_preset_start(const pnpr_cloud *cloud, const pnpr_view_options *view_opts, float fov_y_deg,
                                     float aspect, pnpr_camera *r_start, double r_up[3])
{
    pnpr_view_info info;
    if (!(fov_y_deg > 0 && fov_y_deg < 179)) fov_y_deg = 45;
    if (!(aspect > 0) || !isfinite(aspect)) aspect = 1;
    pnpr_status st = pnpr_camera_default(cloud, view_opts, fov_y_deg, aspect, r_start, &info);
    if (st != PNPR_OK) return st;
    memcpy(r_up, info.up, sizeof info.up);
    double tan_y = tan(0.5 * fov_y_deg * PATH_PI / 180.0) / 1.05, tan_x = tan_y * aspect;
    double v[3] = {r_start->eye[0] - r_start->target[0], r_start->eye[1] - r_start->target[1], r_start->eye[2] - r_start->target[2]};
    double dist = sqrt(pnpr_dot3(v, v)), d[3] = {v[0] / dist, v[1] / dist, v[2] / dist};
    double need = orbit_fit_distance(cloud, &info, r_start->target, d, info.up, tan_x, tan_y);
    if (dist > 0 && need > dist)
        for (int c = 0; c < 3; c++) r_start->eye[c] = r_start->target[c] + d[c] * need;
    r_start->near_plane = r_start->far_plane = 0; /* the path's cameras use the automatic range */
    return PNPR_OK;
}
