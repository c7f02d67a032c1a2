/* A sample of a cloud for a view or a camera path's frames (include/pointnpr/crq.h, docs/tiles.md
 * "Drawing a cloud larger than memory"): the cone tests, the depth histograms and the solve for c. */
#include <pointnpr/crq.h>

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

/* A look-at view's unit direction and the tangent of its cone's half-angle (its diagonal's,
 * widened by PNPR_VIEW_SAMPLE_MARGIN); 0 unless eye and target are apart and finite, fov_deg in
 * (0, 180), width and height > 0. */
static int look_view(const double eye[3], const double target[3], double fov_deg, int width, int height,
                     double r_f[3], double *r_tan)
{
    double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    double len = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(len > 0) || !isfinite(len) || !isfinite(eye[0] + eye[1] + eye[2]) || !(fov_deg > 0 && fov_deg < 180) ||
        width <= 0 || height <= 0)
        return 0;
    double ty = tan(0.5 * fov_deg * PI / 180.0), tx = ty * width / height;
    *r_tan = PNPR_VIEW_SAMPLE_MARGIN * sqrt(tx * tx + ty * ty);
    for (int i = 0; i < 3; i++) r_f[i] = f[i] / len;
    return isfinite(*r_tan);
}

/* One view into slot v->views. */
static pnpr_status set_view(pnpr_view_sample *v, const double eye[3], const double target[3], double fov_deg,
                            int width, int height)
{
    double f[3], tan_cone;
    if (!v || !eye || !target || v->views < 0 || v->views >= PNPR_VIEW_SAMPLE_VIEWS ||
        !look_view(eye, target, fov_deg, width, height, f, &tan_cone))
        return PNPR_ERR_INVALID_ARGUMENT;
    int k = v->views++;
    for (int i = 0; i < 3; i++) {
        v->eye[i][k] = eye[i];
        v->forward[i][k] = f[i];
    }
    v->tan2[k] = v->tan2_own[k] = tan_cone * tan_cone;
    v->cos_own[k] = 1;
    return PNPR_OK;
}

pnpr_status pnpr_view_sample_init(pnpr_view_sample *v, const double eye[3], const double target[3], double fov_deg,
                                  int width, int height)
{
    if (!v) return PNPR_ERR_INVALID_ARGUMENT;
    memset(v, 0, sizeof *v);
    return set_view(v, eye, target, fov_deg, width, height);
}

pnpr_status pnpr_view_sample_add_view(pnpr_view_sample *v, const double eye[3], const double target[3],
                                      double fov_deg, int width, int height)
{
    return set_view(v, eye, target, fov_deg, width, height);
}

/* View k also stands for cameras whose eyes lie within `reach` of its eye, whose cones reach
 * `half_angle` (radians) about its axis, their own half-angles at most `own`: its half-angle
 * becomes at least half_angle (at most 89.9 degrees), its apex moves back along its axis by
 * reach / sin(half-angle), so that its cone holds theirs (a cone holds the ball of radius reach
 * about the eye, and every cone from there turned within it). A point's depth in such a camera is
 * at least (its distance from the eye - reach) x cos(own), the least a point in their cones may
 * have: view_depths takes that, and at most the depth from the view's own eye. */
static void widen(pnpr_view_sample *v, int k, double half_angle, double reach, double own)
{
    const double most = 89.9 * PI / 180.0;
    double now = atan(sqrt(v->tan2[k])), a = half_angle < now ? now : half_angle < most ? half_angle : most;
    double t = tan(a), back = reach / sin(a);
    for (int i = 0; i < 3; i++) v->eye[i][k] -= back * v->forward[i][k];
    v->tan2[k] = t * t;
    v->back[k] = back;
    v->reach[k] = reach;
    v->cos_own[k] = cos(own);
    v->widened = 1;
}

/* The frame of view j of m over n frames: spread evenly, the first and the last among them. */
static size_t kept_frame(size_t j, size_t m, size_t n)
{
    return m > 1 ? (size_t)floor((double)j * (double)(n - 1) / (double)(m - 1) + 0.5) : 0;
}

pnpr_status pnpr_view_sample_init_frames(pnpr_view_sample *v, const double *eyes, const double *targets,
                                         const double *fovs, size_t n, int width, int height)
{
    if (!v || !eyes || !targets || !fovs || n == 0) return PNPR_ERR_INVALID_ARGUMENT;
    memset(v, 0, sizeof *v);
    size_t m = n < PNPR_VIEW_SAMPLE_VIEWS ? n : PNPR_VIEW_SAMPLE_VIEWS;
    for (size_t j = 0; j < m; j++) {
        size_t f = kept_frame(j, m, n);
        pnpr_status st = set_view(v, eyes + 3 * f, targets + 3 * f, fovs[f], width, height);
        if (st != PNPR_OK) return st;
    }
    for (size_t j = 0; j < m && m < n; j++) { /* the frames between a view's neighbours */
        size_t f = kept_frame(j, m, n), lo = j ? kept_frame(j - 1, m, n) + 1 : 0;
        size_t hi = j + 1 < m ? kept_frame(j + 1, m, n) : n;
        double fj[3], half = 0, reach = 0, own = 0;
        for (int i = 0; i < 3; i++) fj[i] = v->forward[i][j];
        for (size_t g = lo; g < hi; g++) {
            double fg[3], t, e2 = 0;
            if (!look_view(eyes + 3 * g, targets + 3 * g, fovs[g], width, height, fg, &t)) return PNPR_ERR_INVALID_ARGUMENT;
            double c = fj[0] * fg[0] + fj[1] * fg[1] + fj[2] * fg[2], cone = atan(t);
            for (int i = 0; i < 3; i++) e2 += (eyes[3 * g + i] - eyes[3 * f + i]) * (eyes[3 * g + i] - eyes[3 * f + i]);
            if (!isfinite(e2)) return PNPR_ERR_INVALID_ARGUMENT;
            half = fmax(half, cone + acos(c < -1 ? -1 : c > 1 ? 1 : c));
            own = fmax(own, cone);
            reach = fmax(reach, sqrt(e2));
        }
        widen(v, (int)j, half, reach, own);
    }
    return PNPR_OK;
}

/* The views' slots in whole groups of 4 (PNPR_VIEW_SAMPLE_VIEWS is a multiple of 4). */
static int views_rounded(const pnpr_view_sample *v)
{
    return v->views <= 0 ? 0 : v->views >= PNPR_VIEW_SAMPLE_VIEWS ? PNPR_VIEW_SAMPLE_VIEWS : (v->views + 3) & ~3;
}

/* The depth of p in each view's own frame (its eye and cone before widening), else 0: each view's
 * histogram is its frame's, for the frame's cap (a widened view's depths are those of the frames
 * it stands for, nearer). */
static void own_depths(const pnpr_view_sample *restrict v, const double *restrict p, double *restrict r_z)
{
    const int slots = views_rounded(v);
    for (int k = 0; k < slots; k++) {
        double b = v->back[k];
        double dx = p[0] - v->eye[0][k] - b * v->forward[0][k], dy = p[1] - v->eye[1][k] - b * v->forward[1][k],
               dz = p[2] - v->eye[2][k] - b * v->forward[2][k];
        double z = dx * v->forward[0][k] + dy * v->forward[1][k] + dz * v->forward[2][k];
        double r2 = dx * dx + dy * dy + dz * dz - z * z;
        int seen = (z > 0) & (r2 <= z * z * v->tan2_own[k]);
        r_z[k] = seen ? z : 0;
    }
}

/* The eye depth of p in each view that sees it, else 0 (NaN and Inf too: the comparisons fail); a
 * widened view's the least of the cameras it stands for (widen), at least 1e-6 of the depth from
 * its apex; in the slots up to `views` rounded up to 4 (the slots after `views` see nothing): one loop without
 * branches (the compiler's vectors). */
static void view_depths(const pnpr_view_sample *restrict v, const double *restrict p, double *restrict r_z)
{
    if (!v->widened) { /* the views are their frames': their depths, without the distance's root */
        own_depths(v, p, r_z);
        return;
    }
    const int slots = views_rounded(v);
    for (int k = 0; k < slots; k++) {
        double dx = p[0] - v->eye[0][k], dy = p[1] - v->eye[1][k], dz = p[2] - v->eye[2][k];
        double z = dx * v->forward[0][k] + dy * v->forward[1][k] + dz * v->forward[2][k];
        double r2 = dx * dx + dy * dy + dz * dz - z * z;
        int seen = (z > 0) & (r2 <= z * z * v->tan2[k]); /* no branch: the loop vectorises */
        /* a widened view (widen): the least depth of the cameras it stands for; a plain one (back
         * and reach 0, cos_own 1): its depth, as the distance is not less */
        double b = v->back[k], e2 = dx * dx + dy * dy + dz * dz - 2.0 * b * z + b * b;
        double from_eye = z - b, least = (sqrt(e2 > 0 ? e2 : 0) - v->reach[k]) * v->cos_own[k];
        double depth = from_eye < least ? from_eye : least, floor = 1e-6 * z;
        r_z[k] = seen ? (depth > floor ? depth : floor) : 0;
    }
}

/* The least positive of the depths of `slots` views, 0 when none is. */
static double least_depth(const double *z, int slots)
{
    double least = HUGE_VAL;
    for (int k = 0; k < slots; k++) least = z[k] > 0 && z[k] < least ? z[k] : least;
    return least < HUGE_VAL ? least : 0;
}

double pnpr_view_sample_depth(const pnpr_view_sample *v, const double p[3])
{
    double z[PNPR_VIEW_SAMPLE_VIEWS];
    view_depths(v, p, z);
    return least_depth(z, views_rounded(v));
}

/* 16 bins an octave from 2^-64: the exponent and the mantissa's first 4 bits, the top 16 bits of
 * the double after its sign (no log2: a path adds every point to each of its views' histograms).
 * z is positive and finite. */
static int depth_bin(double z)
{
    uint64_t bits;
    memcpy(&bits, &z, sizeof bits);
    long b = (long)(bits >> 48) - (1023L - 64L) * 16L;
    return b < 0 ? 0 : b >= PNPR_VIEW_SAMPLE_BINS ? PNPR_VIEW_SAMPLE_BINS - 1 : (int)b;
}

static void depths_add(pnpr_view_depths *h, double z, uint64_t n)
{
    int b = depth_bin(z);
    if (!h->visible || z < h->z_min) h->z_min = z;
    if (!h->visible || z > h->z_max) h->z_max = z;
    h->count[b] += n;
    h->inv_z2[b] += (double)n / (z * z);
    h->visible += n;
}

void pnpr_view_sample_add_n(pnpr_view_sample *v, const double p[3], uint64_t n)
{
    double z[PNPR_VIEW_SAMPLE_VIEWS];
    view_depths(v, p, z);
    double least = least_depth(z, views_rounded(v));
    if (!(least > 0)) return;
    depths_add(&v->least, least, n);
    if (!v->each || v->views < 2) return;
    if (v->widened) own_depths(v, p, z);
    for (int k = 0; k < v->views; k++)
        if (z[k] > 0) depths_add(&v->each[k], z[k], n);
}

void pnpr_view_sample_add(pnpr_view_sample *v, const double p[3]) { pnpr_view_sample_add_n(v, p, 1); }

void pnpr_view_sample_clear(pnpr_view_sample *v)
{
    memset(&v->least, 0, sizeof v->least);
    for (int k = 0; v->each && k < v->views; k++) memset(&v->each[k], 0, sizeof v->each[k]);
    v->c = 0;
}

/* The expected count for c: a bin gives c x its sum of 1/z^2, at most its count (exact unless the
 * share reaches 1 inside the bin). */
static double expected(const pnpr_view_depths *h, double c)
{
    double n = 0;
    for (int b = 0; b < PNPR_VIEW_SAMPLE_BINS; b++) {
        double s = c * h->inv_z2[b];
        n += s < (double)h->count[b] ? s : (double)h->count[b];
    }
    return n;
}

/* c for an expected count of `want` of the depths of h; HUGE_VAL when all fit, 0 for none. */
static double depths_solve(const pnpr_view_depths *h, double want)
{
    if (!(want > 0)) return 0; /* nothing (NaN too) */
    if (!((double)h->visible > want)) return HUGE_VAL;
    /* log2 c between the depths squared: shares from 2^-80 at the nearest to 1 at the farthest */
    double lo = 2.0 * log2(h->z_min) - 80.0, hi = 2.0 * log2(h->z_max) + 1.0;
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (expected(h, exp2(mid)) > want) hi = mid;
        else lo = mid;
    }
    return exp2(lo);
}

void pnpr_view_sample_solve(pnpr_view_sample *v, double want, double frame_want)
{
    double c = depths_solve(&v->least, want);
    if (frame_want > 0 && (v->views == 1 || v->each)) {
        double cap = 0;
        for (int k = 0; k < v->views; k++) { /* a view that sees no more than it draws: all whole */
            const pnpr_view_depths *h = v->views == 1 ? &v->least : &v->each[k];
            double ck = (double)h->visible > frame_want ? depths_solve(h, frame_want) : h->z_max * h->z_max;
            if (h->visible && ck > cap) cap = ck;
        }
        if (cap < c) c = cap;
    }
    v->c = c;
}

double pnpr_view_sample_share(const pnpr_view_sample *v, const double p[3])
{
    double z = pnpr_view_sample_depth(v, p);
    if (z == 0) return 0;
    double s = v->c / (z * z);
    return s < 1 ? s : 1;
}

/* ---- balls (the cells of a file ordered for drawing, pointnpr/lod.h) ---------------------- */

/* The least depth a point within rho of c may have in view k when the view may see one: its own
 * frame's cone (own) or the view's; 0 when it sees none, -1 when one may lie at any depth. A
 * cone moved back along its axis by rho / sin(half-angle) holds every ball of radius rho about
 * a point of the cone; the depth bounds are view_depths' less rho. */
static double ball_view_depth(const pnpr_view_sample *v, int k, const double c[3], double rho, int own)
{
    double t2 = own ? v->tan2_own[k] : v->tan2[k], back = own ? 0 : v->back[k];
    double shift = rho * sqrt((1.0 + t2) / t2), e[3], d[3], f[3], z = 0, r2 = 0, dist2 = 0;
    for (int i = 0; i < 3; i++) {
        f[i] = v->forward[i][k];
        e[i] = v->eye[i][k] + v->back[k] * f[i]; /* the view's eye (its apex for a plain view) */
        d[i] = c[i] - (own ? e[i] : v->eye[i][k]) + shift * f[i];
        z += d[i] * f[i];
        r2 += d[i] * d[i];
        dist2 += (c[i] - e[i]) * (c[i] - e[i]);
    }
    r2 -= z * z;
    if (!(z > 0) || !(r2 <= z * z * t2)) return 0;
    double from_eye = z - shift - back - rho;
    double least = own ? from_eye : (sqrt(dist2) - rho - v->reach[k]) * v->cos_own[k];
    double depth = from_eye < least ? from_eye : least;
    return depth > 0 ? depth : -1;
}

/* The least of the views' depths (ball_view_depth): 0 when none sees the ball, -1 when near. */
static double ball_depth(const pnpr_view_sample *v, const double c[3], double rho)
{
    double least = HUGE_VAL;
    if (!isfinite(c[0] + c[1] + c[2]) || !(rho >= 0) || !isfinite(rho)) return 0;
    for (int k = 0; k < v->views; k++) {
        double z = ball_view_depth(v, k, c, rho, 0);
        if (z < 0) return -1;
        if (z > 0 && z < least) least = z;
    }
    return least < HUGE_VAL ? least : 0;
}

void pnpr_view_sample_add_ball(pnpr_view_sample *v, const double c[3], double rho, uint64_t n)
{
    double z = ball_depth(v, c, rho);
    if (z == 0 || n == 0) return;
    depths_add(&v->least, z < 0 ? PNPR_VIEW_SAMPLE_NEAR : z, n);
    for (int k = 0; v->each && v->views > 1 && k < v->views; k++) {
        double zk = ball_view_depth(v, k, c, rho, 1);
        if (zk != 0) depths_add(&v->each[k], zk < 0 ? PNPR_VIEW_SAMPLE_NEAR : zk, n);
    }
}

double pnpr_view_sample_ball_share(const pnpr_view_sample *v, const double c[3], double rho)
{
    double z = ball_depth(v, c, rho);
    if (z == 0) return 0;
    if (z < 0) return 1;
    double s = v->c / (z * z);
    return s < 1 ? s : 1;
}
