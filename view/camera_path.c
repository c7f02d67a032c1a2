/* Camera paths: checks and evaluation (camera_path.h). Positions by cubic Hermite splines with
 * Catmull-Rom tangents in time, up vectors carried by the smallest rotation of the view
 * direction and re-orthogonalised, field of view linear. Pure CPU. */
#include "camera_path_internal.h"
#include "../core/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void pnpr_camera_path_free(pnpr_camera_path *path)
{
    if (!path) return;
    free(path->keys);
    path->keys = NULL;
    path->count = 0;
    path->loop = 0;
}

double pnpr_camera_path_duration(const pnpr_camera_path *path)
{
    return path && path->count > 1 ? path->keys[path->count - 1].time - path->keys[0].time : 0;
}

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

int pnpr_camera_key_problem(const pnpr_camera_key *k, char *why, size_t size)
{
    double d[3] = {k->target[0] - k->eye[0], k->target[1] - k->eye[1], k->target[2] - k->eye[2]}, c[3];
    if (!isfinite(k->time) || !finite3(k->eye) || !finite3(k->target) || !finite3(k->up) || !isfinite(k->fov_y_deg)) {
        snprintf(why, size, "a value is not a finite number");
        return 2;
    }
    if (!(k->fov_y_deg > 0 && k->fov_y_deg < 179)) { snprintf(why, size, "fov %g is not in (0, 179)", k->fov_y_deg); return 1; }
    if (d[0] == 0 && d[1] == 0 && d[2] == 0) { snprintf(why, size, "eye and target are the same point"); return 1; }
    pnpr_cross3(d, k->up, c);
    double lu = sqrt(pnpr_dot3(k->up, k->up));
    if (!(lu > 0) || sqrt(pnpr_dot3(c, c)) < 1e-6 * lu * sqrt(pnpr_dot3(d, d))) {
        snprintf(why, size, "up (%g,%g,%g) is zero or parallel to the view direction", k->up[0], k->up[1], k->up[2]);
        return 1;
    }
    return 0;
}

int pnpr_camera_path_loop_closed(const pnpr_camera_path *p)
{
    const pnpr_camera_key *a = &p->keys[0], *b = &p->keys[p->count - 1];
    return p->count >= 3 && !memcmp(a->eye, b->eye, sizeof a->eye) && !memcmp(a->target, b->target, sizeof a->target) &&
           !memcmp(a->up, b->up, sizeof a->up);
}

pnpr_status pnpr_camera_path_check(const pnpr_camera_path *path, pnpr_error *err)
{
    if (!path || !path->keys || path->count == 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "a camera path needs at least one key");
    if (path->count > PNPR_CAMERA_PATH_KEYS_MAX)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "a camera path has at most %d keys, got %zu",
                              PNPR_CAMERA_PATH_KEYS_MAX, path->count);
    char why[160];
    for (size_t i = 0; i < path->count; i++) {
        int p = pnpr_camera_key_problem(&path->keys[i], why, sizeof why);
        if (p) return pnpr_error_set(err, p == 2 ? PNPR_ERR_NUMERIC : PNPR_ERR_INVALID_ARGUMENT, "camera path key %zu: %s", i + 1, why);
        if (i > 0 && !(path->keys[i].time > path->keys[i - 1].time))
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "camera path key %zu: time %g is not after the previous key's %g",
                                  i + 1, path->keys[i].time, path->keys[i - 1].time);
    }
    if (path->loop && !pnpr_camera_path_loop_closed(path))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT,
                              "a looped camera path needs at least 3 keys, the last repeating the first key's eye, target and up");
    return PNPR_OK;
}

static const double *key_point(const pnpr_camera_key *k, int which) { return which ? k->target : k->eye; }

/* The Catmull-Rom tangent (in time) of eye (which 0) or target (1) at key i. */
static void tangent(const pnpr_camera_path *p, size_t i, int which, double m[3])
{
    size_t n = p->count, lo = i > 0 ? i - 1 : 0, hi = i + 1 < n ? i + 1 : n - 1;
    double dt = p->keys[hi].time - p->keys[lo].time;
    const double *a = key_point(&p->keys[lo], which), *b = key_point(&p->keys[hi], which);
    if (p->loop && (i == 0 || i == n - 1)) { /* wrap: key n-2 precedes key 0 == key n-1 */
        a = key_point(&p->keys[n - 2], which);
        b = key_point(&p->keys[1], which);
        dt = (p->keys[1].time - p->keys[0].time) + (p->keys[n - 1].time - p->keys[n - 2].time);
    }
    for (int c = 0; c < 3; c++) m[c] = dt > 0 ? (b[c] - a[c]) / dt : 0;
}

static void hermite(const pnpr_camera_path *p, size_t i, double s, int which, double r[3])
{
    double m0[3], m1[3], h = p->keys[i + 1].time - p->keys[i].time;
    tangent(p, i, which, m0);
    tangent(p, i + 1, which, m1);
    const double *p0 = key_point(&p->keys[i], which), *p1 = key_point(&p->keys[i + 1], which);
    double s2 = s * s, s3 = s2 * s;
    double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    for (int c = 0; c < 3; c++) r[c] = h00 * p0[c] + h10 * h * m0[c] + h01 * p1[c] + h11 * h * m1[c];
}

/* The key's unit view direction and its up made orthonormal to it. */
static void key_frame(const pnpr_camera_key *k, double d[3], double u[3])
{
    for (int c = 0; c < 3; c++) d[c] = k->target[c] - k->eye[c];
    pnpr_normalize3(d);
    double a = pnpr_dot3(k->up, d);
    for (int c = 0; c < 3; c++) u[c] = k->up[c] - a * d[c];
    pnpr_normalize3(u);
}

/* v rotated by the smallest rotation taking unit a to unit b (v unchanged when a = -b). */
static void rotate_min(const double a[3], const double b[3], const double v[3], double r[3])
{
    double c = pnpr_dot3(a, b), k[3], kv[3];
    if (c <= -1 + 1e-12) { memcpy(r, v, 3 * sizeof *r); return; }
    pnpr_cross3(a, b, k);
    pnpr_cross3(k, v, kv);
    double kd = pnpr_dot3(k, v) / (1 + c);
    for (int j = 0; j < 3; j++) r[j] = v[j] * c + kv[j] + k[j] * kd;
}

/* u made orthogonal to unit d and unit; 0 when it is (nearly) parallel to d. */
static int orthonormalize(double u[3], const double d[3])
{
    double a = pnpr_dot3(u, d);
    for (int c = 0; c < 3; c++) u[c] -= a * d[c];
    return pnpr_normalize3(u) > 1e-9;
}

/* The up at parameter s of segment i for the view direction d (unit). */
static void segment_up(const pnpr_camera_path *p, size_t i, double s, const double d[3], double up[3])
{
    double d0[3], u0[3], d1[3], u1[3], ua[3], ub[3];
    key_frame(&p->keys[i], d0, u0);
    key_frame(&p->keys[i + 1], d1, u1);
    rotate_min(d0, d, u0, ua);
    rotate_min(d1, d, u1, ub);
    double w = s * s * (3 - 2 * s);
    for (int c = 0; c < 3; c++) up[c] = (1 - w) * ua[c] + w * ub[c];
    if (orthonormalize(up, d)) return;
    memcpy(up, ua, sizeof ua); /* the two carried ups cancel: keep the first key's */
    if (!orthonormalize(up, d)) memcpy(up, u0, sizeof u0);
}

static void set_camera(pnpr_camera *cam, const double eye[3], const double target[3], const double up[3], double fov)
{
    memset(cam, 0, sizeof *cam);
    memcpy(cam->eye, eye, sizeof cam->eye);
    memcpy(cam->target, target, sizeof cam->target);
    memcpy(cam->up, up, sizeof cam->up);
    cam->fov_y_deg = (float)fov;
}

pnpr_status pnpr_camera_path_eval(const pnpr_camera_path *path, double t, pnpr_camera *r_camera)
{
    if (!path || !path->keys || path->count == 0 || !r_camera || isnan(t)) return PNPR_ERR_INVALID_ARGUMENT;
    const pnpr_camera_key *k = path->keys;
    size_t n = path->count;
    double d[3], u[3];
    if (n == 1 || t <= k[0].time || t >= k[n - 1].time) { /* hold the end key */
        const pnpr_camera_key *e = (n == 1 || t <= k[0].time) ? &k[0] : &k[n - 1];
        key_frame(e, d, u);
        set_camera(r_camera, e->eye, e->target, u, e->fov_y_deg);
        return PNPR_OK;
    }
    size_t lo = 0, hi = n - 1; /* the last key with time <= t */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (k[mid].time <= t) lo = mid; else hi = mid;
    }
    double s = (t - k[lo].time) / (k[lo + 1].time - k[lo].time), eye[3], target[3];
    hermite(path, lo, s, 0, eye);
    hermite(path, lo, s, 1, target);
    for (int c = 0; c < 3; c++) d[c] = target[c] - eye[c];
    if (!(pnpr_normalize3(d) > 0)) { /* eye meets target: the keys' directions blended */
        double d0[3], d1[3], u0[3];
        key_frame(&k[lo], d0, u0);
        key_frame(&k[lo + 1], d1, u0);
        for (int c = 0; c < 3; c++) d[c] = (1 - s) * d0[c] + s * d1[c];
        if (!(pnpr_normalize3(d) > 0)) memcpy(d, d0, sizeof d0);
    }
    segment_up(path, lo, s, d, u);
    set_camera(r_camera, eye, target, u, k[lo].fov_y_deg + s * (k[lo + 1].fov_y_deg - k[lo].fov_y_deg));
    return PNPR_OK;
}
