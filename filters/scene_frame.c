/* The scene frame of a cloud (include/pointnpr/view.h): robust bounds, up axis, ground plane and
 * a suggested view direction, for the default camera. docs/view.md explains every threshold.
 *
 * Steps: a seeded uniform subsample of the finite points (at most max_samples); per-axis
 * quantiles extended over their tails up to the first gap (robust bounds); far outliers counted
 * on every point; the up vector (user, format hint, ground plane by a seeded RANSAC, else +z);
 * the horizontal principal axes; elevation from the flatness, azimuth from the scanner side or
 * the legacy front, turned so that the wide axis runs across the screen. All sums in double
 * around the robust centre. */
#include "../core/internal.h"
#include <pointnpr/features.h>
#include <pointnpr/view.h>

#include "../core/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_SAMPLES 200000
#define DEFAULT_SEED 0x9e3779b97f4a7c15ull
#define Q_LO 0.005              /* per-axis quantiles of the robust core */
#define Q_HI 0.995
#define TAIL_GAP 0.05           /* tails join the core up to a gap of this x core extent */
#define MARGIN 0.01             /* bounds widened by this x extent on each side */
#define OUTLIER_DIAGS 1.0       /* far outlier: farther than this x robust diagonal from the bounds */
#define PLANE_TOL 0.015         /* RANSAC inlier distance, x robust diagonal */
#define PLANE_ITERS 256
#define PLANE_SCORE_SET 4096    /* hypotheses are scored on this many points */
#define GROUND_MIN 0.2          /* a ground holds at least this share of the points */
#define GROUND_MIN_SECOND 0.1   /* ... a floor under a wall that faces the camera (find_ground) */
#define ONE_SIDE_MAX 0.1        /* at most this share of the off-plane points below it */
#define PURE_PLANE 0.02         /* fewer off-plane points than this share: no side information */
#define SNAP_DEG 10.0
#define ORIGIN_DIAGS 3.0        /* world origin this close to the bounds: a likely RGB-D camera */
#define X_GROUND_COS 0.64      /* a plane whose normal is within 50 degrees of +-x is taken for a
                                 * facade, not a ground (x-up scenes are rare; --up x for them) */
#define SCANNER_ELEV_MIN 20.0   /* the scanner's own elevation, kept within these (degrees) */
#define SCANNER_ELEV_MAX 65.0
#define FACING_DEG 30.0         /* a plane whose normal is this close to the camera's direction is
                                 * a wall in front of it; a second plane is tried */
#define ELEV_TALL 30.0
#define ELEV_FLAT 55.0
#define FLAT_RATIO 0.05         /* up extent / horizontal extent at or below which ELEV_FLAT */
#define TALL_RATIO 0.5          /* at or above which ELEV_TALL */
#define ANISOTROPY 1.25         /* wide / narrow std. deviation above which the wide axis goes across */

static const double DEG = 3.14159265358979323846 / 180.0;

static void set3(double r[3], double x, double y, double z) { r[0] = x; r[1] = y; r[2] = z; }

static uint64_t rng_next(uint64_t *s) /* splitmix64 */
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* ---- subsample and robust bounds -------------------------------------------------------------- */

/* A seeded uniform sample of the finite points (reservoir sampling: all of them when there are
 * at most `max`; a stride would alias with scan lines and other periodic orders). */
static float *take_sample(const pnpr_cloud *cloud, size_t max, uint64_t seed, size_t *r_m, size_t *r_valid)
{
    size_t nf = 0;
    for (size_t i = 0; i < cloud->count; i++) nf += pnpr_finite3f(cloud->xyz + 3 * i);
    *r_valid = nf;
    size_t m = nf < max ? nf : max;
    *r_m = m;
    float *s = m ? malloc(3 * m * sizeof *s) : NULL;
    if (!s) return NULL;
    size_t k = 0;
    for (size_t i = 0; i < cloud->count; i++) {
        const float *p = cloud->xyz + 3 * i;
        if (!pnpr_finite3f(p)) continue;
        size_t j = k < m ? k : (size_t)(rng_next(&seed) % (k + 1));
        if (j < m) memcpy(s + 3 * j, p, 3 * sizeof *p);
        k++;
    }
    return s;
}

/* From the core [v[ilo], v[ihi]] of sorted values, walk outwards while consecutive values are
 * closer than `gap`. */
static void extend_tails(const float *v, size_t m, size_t ilo, size_t ihi, double gap, float *r_lo, float *r_hi)
{
    while (ilo > 0 && (double)v[ilo] - (double)v[ilo - 1] <= gap) ilo--;
    while (ihi + 1 < m && (double)v[ihi + 1] - (double)v[ihi] <= gap) ihi++;
    *r_lo = v[ilo];
    *r_hi = v[ihi];
}

/* Robust bounds of the sample; sorted: 3*m scratch floats. */
static void robust_bounds(const float *s, size_t m, float *sorted, float r_lo[3], float r_hi[3])
{
    size_t ilo = (size_t)floor(Q_LO * (double)(m - 1)), ihi = (size_t)ceil(Q_HI * (double)(m - 1));
    double core = 0;
    for (int a = 0; a < 3; a++) {
        float *v = sorted + (size_t)a * m;
        for (size_t i = 0; i < m; i++) v[i] = s[3 * i + a];
        qsort(v, m, sizeof *v, pnpr_cmp_float);
        double e = (double)v[ihi] - (double)v[ilo];
        if (e > core) core = e;
    }
    for (int a = 0; a < 3; a++) extend_tails(sorted + (size_t)a * m, m, ilo, ihi, TAIL_GAP * core, &r_lo[a], &r_hi[a]);
    double ext = 0;
    for (int a = 0; a < 3; a++) ext = fmax(ext, (double)r_hi[a] - (double)r_lo[a]);
    for (int a = 0; a < 3; a++) { /* widen, never narrowing by float rounding */
        float lo = (float)((double)r_lo[a] - MARGIN * ext), hi = (float)((double)r_hi[a] + MARGIN * ext);
        if (lo < r_lo[a]) r_lo[a] = lo;
        if (hi > r_hi[a]) r_hi[a] = hi;
    }
}

static double box_diagonal(const float lo[3], const float hi[3])
{
    double d[3];
    for (int a = 0; a < 3; a++) d[a] = (double)hi[a] - (double)lo[a];
    return sqrt(pnpr_dot3(d, d));
}

/* Distance from a point (offsets, double) to the box; 0 inside. */
static double box_distance(const float lo[3], const float hi[3], const double p[3])
{
    double e[3];
    for (int a = 0; a < 3; a++) e[a] = fmax(fmax((double)lo[a] - p[a], p[a] - (double)hi[a]), 0.0);
    return sqrt(pnpr_dot3(e, e));
}

/* Far outliers among all points; a point whose offset overflowed float but whose source
 * coordinate is finite (src_xyz) is one too. */
static size_t count_outliers(const pnpr_cloud *c, const float lo[3], const float hi[3])
{
    double lim = OUTLIER_DIAGS * box_diagonal(lo, hi);
    size_t n = 0;
    for (size_t i = 0; i < c->count; i++) {
        const float *p = c->xyz + 3 * i;
        if (pnpr_finite3f(p)) {
            double q[3] = {p[0], p[1], p[2]};
            n += box_distance(lo, hi, q) > lim;
        } else if (c->src_xyz) {
            const double *w = c->src_xyz + 3 * i;
            n += isfinite(w[0]) && isfinite(w[1]) && isfinite(w[2]);
        }
    }
    return n;
}

/* Keeps the sample points inside the bounds, as doubles relative to `centre`. */
static size_t inside_points(const float *s, size_t m, const float lo[3], const float hi[3],
                            const double centre[3], double *r_pts)
{
    size_t n = 0;
    for (size_t i = 0; i < m; i++) {
        const float *p = s + 3 * i;
        if (p[0] < lo[0] || p[0] > hi[0] || p[1] < lo[1] || p[1] > hi[1] || p[2] < lo[2] || p[2] > hi[2]) continue;
        for (int a = 0; a < 3; a++) r_pts[3 * n + a] = (double)p[a] - centre[a];
        n++;
    }
    return n;
}

/* ---- ground plane ----------------------------------------------------------------------------- */

typedef struct plane {
    double n[3], d;             /* n.p + d = 0, n unit */
    size_t on, above, below;    /* points within tol, beyond it on the +n / -n side */
    double centroid[3];
} plane;

static void plane_count(const double *pts, size_t m, double tol, plane *pl)
{
    pl->on = pl->above = pl->below = 0;
    for (size_t i = 0; i < m; i++) {
        double s = pnpr_dot3(pl->n, pts + 3 * i) + pl->d;
        if (s > tol) pl->above++;
        else if (s < -tol) pl->below++;
        else pl->on++;
    }
}

/* Least squares plane through the inliers of pl (smallest covariance eigenvector). */
static void plane_refine(const double *pts, size_t m, double tol, plane *pl)
{
    double c[3] = {0, 0, 0}, cov[3][3] = {{0}};
    size_t n = 0;
    for (size_t i = 0; i < m; i++)
        if (fabs(pnpr_dot3(pl->n, pts + 3 * i) + pl->d) <= tol) {
            for (int a = 0; a < 3; a++) c[a] += pts[3 * i + a];
            n++;
        }
    if (n < 3) return;
    for (int a = 0; a < 3; a++) c[a] /= (double)n;
    for (size_t i = 0; i < m; i++) {
        const double *p = pts + 3 * i;
        if (fabs(pnpr_dot3(pl->n, p) + pl->d) > tol) continue;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) cov[a][b] += (p[a] - c[a]) * (p[b] - c[b]);
    }
    double w[3], v[3][3];
    pnpr_eigen_sym3(cov, w, v);
    double nn[3] = {v[0][0], v[0][1], v[0][2]};
    if (!(pnpr_normalize3(nn) > 0.5)) return;
    if (pnpr_dot3(nn, pl->n) < 0) set3(nn, -nn[0], -nn[1], -nn[2]);
    memcpy(pl->n, nn, sizeof nn);
    memcpy(pl->centroid, c, sizeof c);
    pl->d = -pnpr_dot3(nn, c);
}

/* Seeded RANSAC: the plane with the most points within tol on an evenly spread scoring set,
 * refined twice by least squares on all points. 0 when no non-degenerate triple was found. */
static int ransac_plane(const double *pts, size_t m, double tol, double diag, uint64_t seed, plane *r_best)
{
    size_t step = m > PLANE_SCORE_SET ? m / PLANE_SCORE_SET : 1, best = 0;
    int found = 0;
    for (int it = 0; it < PLANE_ITERS; it++) {
        const double *a = pts + 3 * (rng_next(&seed) % m), *b = pts + 3 * (rng_next(&seed) % m),
                     *c = pts + 3 * (rng_next(&seed) % m);
        double u[3], v[3], n[3];
        for (int k = 0; k < 3; k++) { u[k] = b[k] - a[k]; v[k] = c[k] - a[k]; }
        pnpr_cross3(u, v, n);
        if (!(pnpr_normalize3(n) > 1e-6 * diag * diag)) continue; /* (nearly) collinear */
        size_t score = 0;
        double d = -pnpr_dot3(n, a);
        for (size_t i = 0; i < m; i += step) score += fabs(pnpr_dot3(n, pts + 3 * i) + d) <= tol;
        if (score > best) {
            best = score;
            memcpy(r_best->n, n, sizeof n);
            r_best->d = d;
            found = 1;
        }
    }
    if (!found) return 0;
    memset(r_best->centroid, 0, sizeof r_best->centroid);
    for (int r = 0; r < 2; r++) plane_refine(pts, m, tol, r_best);
    plane_count(pts, m, tol, r_best);
    return 1;
}

/* ---- up --------------------------------------------------------------------------------------- */

static void axis_vector(int axis_signed, double r[3]) /* +-1..3 -> +-x..z */
{
    int a = abs(axis_signed) - 1;
    set3(r, 0, 0, 0);
    r[a] = axis_signed > 0 ? 1 : -1;
}

static void snap_to_axis(double u[3])
{
    for (int a = 0; a < 3; a++)
        if (fabs(u[a]) >= cos(SNAP_DEG * DEG)) {
            double s = u[a] > 0 ? 1 : -1;
            set3(u, 0, 0, 0);
            u[a] = s;
            return;
        }
}

/* Where the scene was seen from, relative to the robust centre (offsets). */
typedef struct scanner {
    int have_vp;      /* the stored viewpoint (cloud->viewpoint) */
    int have_origin;  /* the world origin, a likely RGB-D camera (see likely_origin_camera) */
    double vp[3], org[3];
} scanner;

/* The world origin lies outside the bounds but within ORIGIN_DIAGS robust diagonals of them:
 * an RGB-D frame in camera coordinates has its camera there. */
static int likely_origin_camera(const double o[3], const float lo[3], const float hi[3])
{
    double diag = box_diagonal(lo, hi), dist = box_distance(lo, hi, o);
    return diag > 0 && dist > 0 && dist <= ORIGIN_DIAGS * diag;
}

static scanner find_scanner(const pnpr_cloud *c, const float lo[3], const float hi[3], const double centre[3])
{
    scanner sc = {0, 0, {0, 0, 0}, {0, 0, 0}};
    double o[3] = {-c->origin[0], -c->origin[1], -c->origin[2]};
    for (int a = 0; a < 3; a++) {
        sc.vp[a] = (c->viewpoint[a] - c->origin[a]) - centre[a];
        sc.org[a] = o[a] - centre[a];
    }
    sc.have_vp = c->has_viewpoint && isfinite(sc.vp[0]) && isfinite(sc.vp[1]) && isfinite(sc.vp[2]);
    sc.have_origin = likely_origin_camera(o, lo, hi);
    return sc;
}

/* The most likely camera: the stored viewpoint, else the likely origin camera; NULL if none. */
static const double *scanner_eye(const scanner *sc)
{
    return sc->have_vp ? sc->vp : (sc->have_origin ? sc->org : NULL);
}

/* Without any side information: the sign that makes the first clear component among z, y, x
 * positive (z up, else y up, as most formats mean). */
static int prior_flip(const double n[3])
{
    for (int a = 2; a >= 0; a--)
        if (fabs(n[a]) > 0.5) return n[a] < 0;
    return n[0] < 0;
}

/* Ground plane test: orients pl->n towards the content (or the scanner) and returns 1 when the
 * plane is accepted as a ground. */
static int accept_ground(plane *pl, size_t m, double min_share, const scanner *sc)
{
    if ((double)pl->on < min_share * (double)m) return 0;
    size_t off = pl->above + pl->below, minority = pl->above < pl->below ? pl->above : pl->below;
    int flip;
    if (sc->have_vp && fabs(pnpr_dot3(pl->n, sc->vp) + pl->d) > 0) {
        /* a stored scanner position (PCD VIEWPOINT): scanners see the ground from above */
        flip = pnpr_dot3(pl->n, sc->vp) + pl->d < 0;
    } else if ((double)off < PURE_PLANE * (double)m) { /* no content off the plane: who sees it? */
        const double *eye = scanner_eye(sc);
        double s = eye ? pnpr_dot3(pl->n, eye) + pl->d : 0;
        flip = s != 0 ? s < 0 : prior_flip(pl->n);
    } else if ((double)minority <= ONE_SIDE_MAX * (double)off) {
        flip = pl->below > pl->above;
    } else if (sc->have_vp) {
        flip = pnpr_dot3(pl->n, sc->vp) + pl->d < 0; /* content on both sides: the scanner's side */
    } else return 0;
    if (flip) {
        set3(pl->n, -pl->n[0], -pl->n[1], -pl->n[2]);
        pl->d = -pl->d;
        size_t t = pl->above; pl->above = pl->below; pl->below = t;
    }
    return 1;
}

/* Does the plane face the camera (its normal within max_deg of the direction from the scene's
 * centre to the camera, either sign)? Then it is more likely a wall in front of an indoor camera
 * than a ground. */
static int faces_camera(const plane *pl, const scanner *sc, double max_deg)
{
    const double *eye = scanner_eye(sc);
    double d[3];
    if (!eye) return 0;
    memcpy(d, eye, sizeof d);
    return pnpr_normalize3(d) > 0 && fabs(pnpr_dot3(pl->n, d)) > cos(max_deg * DEG);
}

/* The ground: the largest plane that passes accept_ground; when it faces the camera, a second
 * plane found among the other points wins if it passes too (holding GROUND_MIN_SECOND of the
 * points) and does not face the camera itself. */
static int find_ground(const double *pts, size_t m, double diag, uint64_t seed, const scanner *sc, plane *r_pl)
{
    double tol = PLANE_TOL * diag;
    if (!(diag > 0) || m < 3 || !ransac_plane(pts, m, tol, diag, seed, r_pl) || !accept_ground(r_pl, m, GROUND_MIN, sc))
        return 0;
    int implausible = fabs(r_pl->n[0]) > X_GROUND_COS; /* an x-up scene is rare: a facade */
    if (!implausible && !faces_camera(r_pl, sc, FACING_DEG)) return 1;
    double *rest = malloc(3 * m * sizeof *rest);
    size_t k = 0;
    for (size_t i = 0; rest && i < m; i++)
        if (fabs(pnpr_dot3(r_pl->n, pts + 3 * i) + r_pl->d) > tol) memcpy(rest + 3 * k++, pts + 3 * i, 3 * sizeof *pts);
    plane p2;
    int found = k >= 3 && ransac_plane(rest, k, tol, diag, seed + 1, &p2);
    free(rest);
    if (!found) return !implausible;
    plane_count(pts, m, tol, &p2);
    if (accept_ground(&p2, m, GROUND_MIN_SECOND, sc) && !faces_camera(&p2, sc, FACING_DEG) && !(fabs(p2.n[0]) > X_GROUND_COS)) {
        *r_pl = p2;
        return 1;
    }
    return !implausible;
}

/* ---- view direction --------------------------------------------------------------------------- */

/* The minimal rotation taking +z to u applied to v (about x when u = -z). */
static void rotate_z_to(const double u[3], const double v[3], double r[3])
{
    double z[3] = {0, 0, 1}, k[3], kxv[3];
    pnpr_cross3(z, u, k);
    double s = pnpr_normalize3(k), c = u[2];
    if (!(s > 1e-12)) {
        if (c > 0) { memcpy(r, v, 3 * sizeof *r); return; }
        set3(k, 1, 0, 0);
        s = 0;
    }
    pnpr_cross3(k, v, kxv);
    double kv = pnpr_dot3(k, v);
    for (int a = 0; a < 3; a++) r[a] = v[a] * c + kxv[a] * s + k[a] * kv * (1 - c);
}

/* The horizontal principal axis (sign fixed: its largest component positive) and the ratio of
 * the standard deviations along it and across it (1 = isotropic). */
static double horizontal_axis(const double *pts, size_t m, const double u[3], double r_wide[3])
{
    double mean[3] = {0, 0, 0}, cov[3][3] = {{0}}, w[3], vec[3][3];
    for (size_t i = 0; i < m; i++)
        for (int a = 0; a < 3; a++) mean[a] += pts[3 * i + a] / (double)m;
    for (size_t i = 0; i < m; i++) {
        double q[3], h = pnpr_dot3(pts + 3 * i, u) - pnpr_dot3(mean, u);
        for (int a = 0; a < 3; a++) q[a] = pts[3 * i + a] - mean[a] - h * u[a]; /* in the ground plane */
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) cov[a][b] += q[a] * q[b];
    }
    pnpr_eigen_sym3(cov, w, vec); /* ascending: ~0 (up), narrow, wide */
    memcpy(r_wide, vec[2], 3 * sizeof *r_wide);
    double h = pnpr_dot3(r_wide, u);
    for (int a = 0; a < 3; a++) r_wide[a] -= h * u[a];
    if (!(pnpr_normalize3(r_wide) > 0.5)) rotate_z_to(u, (double[3]){1, 0, 0}, r_wide); /* no spread: any */
    int big = fabs(r_wide[0]) >= fabs(r_wide[1]) ? (fabs(r_wide[0]) >= fabs(r_wide[2]) ? 0 : 2)
                                                 : (fabs(r_wide[1]) >= fabs(r_wide[2]) ? 1 : 2);
    if (r_wide[big] < 0) set3(r_wide, -r_wide[0], -r_wide[1], -r_wide[2]); /* independent of the solver */
    return w[1] > 0 && w[2] > 0 ? sqrt(w[2] / w[1]) : (w[2] > 0 ? INFINITY : 1.0);
}

/* Extents of the points along up, across the screen and along the horizontal view direction h. */
static void view_extents(const double *pts, size_t m, const double h[3], pnpr_view_info *info)
{
    double across[3], lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    pnpr_cross3(h, info->up, across);
    const double *ax[3] = {info->up, across, h};
    for (size_t i = 0; i < m; i++)
        for (int k = 0; k < 3; k++) {
            double t = pnpr_dot3(pts + 3 * i, ax[k]);
            lo[k] = fmin(lo[k], t);
            hi[k] = fmax(hi[k], t);
        }
    info->extent_up = m ? hi[0] - lo[0] : 0;
    info->extent_across = m ? hi[1] - lo[1] : 0;
    info->extent_depth = m ? hi[2] - lo[2] : 0;
}

static double elevation_for(const pnpr_view_info *info)
{
    double horiz = fmax(info->extent_across, info->extent_depth);
    double r = horiz > 0 ? info->extent_up / horiz : 1.0;
    double t = (TALL_RATIO - r) / (TALL_RATIO - FLAT_RATIO);
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    return ELEV_TALL + t * (ELEV_FLAT - ELEV_TALL);
}

/* The horizontal part of v, unit; 0 when it is shorter than min_len. */
static int horizontal(const double u[3], const double v[3], double min_len, double r[3])
{
    double h = pnpr_dot3(v, u);
    for (int a = 0; a < 3; a++) r[a] = v[a] - h * u[a];
    return pnpr_normalize3(r) > min_len;
}

/* Azimuth (scanner side, else the front), turned to put the wide axis across the screen,
 * elevation from the flatness seen that way. */
static void view_direction(const double *pts, size_t m, const scanner *sc, double diag, pnpr_view_info *info)
{
    const double *u = info->up;
    double h[3], narrow[3];
    if (sc->have_vp && horizontal(u, sc->vp, 0.05 * diag, h)) info->azimuth_source = PNPR_AZIMUTH_VIEWPOINT;
    else if (sc->have_origin && horizontal(u, sc->org, 0.05 * diag, h)) info->azimuth_source = PNPR_AZIMUTH_ORIGIN;
    else {
        double front[3];
        rotate_z_to(u, (double[3]){0, -1, 0}, front);
        horizontal(u, front, 0, h);
        info->azimuth_source = PNPR_AZIMUTH_FRONT;
    }
    /* without a stored scanner position, the wide side faces the viewer; with one (PCD
     * VIEWPOINT), the view is the scanner's azimuth and elevation (an RGB-D frame or a scan from
     * outside reads best from where it was taken), the elevation kept within 20..65 degrees */
    int anisotropic = horizontal_axis(pts, m, u, info->wide_axis) > ANISOTROPY;
    if (anisotropic && info->azimuth_source != PNPR_AZIMUTH_VIEWPOINT) {
        pnpr_cross3(u, info->wide_axis, narrow);
        double s = pnpr_dot3(narrow, h) < 0 ? -1 : 1;
        for (int a = 0; a < 3; a++) h[a] = s * narrow[a];
    }
    view_extents(pts, m, h, info);
    info->elevation_deg = elevation_for(info);
    const double *eye = info->azimuth_source == PNPR_AZIMUTH_VIEWPOINT ? sc->vp : NULL;
    double to_eye[3];
    if (eye) {
        memcpy(to_eye, eye, sizeof to_eye);
        if (pnpr_normalize3(to_eye) > 0) {
            double e = asin(fmax(-1.0, fmin(1.0, pnpr_dot3(to_eye, u)))) / DEG;
            info->elevation_deg = fmax(SCANNER_ELEV_MIN, fmin(SCANNER_ELEV_MAX, e));
        }
    }
    double ce = cos(info->elevation_deg * DEG), se = sin(info->elevation_deg * DEG);
    for (int a = 0; a < 3; a++) info->view_dir[a] = ce * h[a] + se * u[a];
    pnpr_normalize3(info->view_dir);
}

/* ---- the whole ------------------------------------------------------------------------------- */

static pnpr_status check_options(const pnpr_view_options *o)
{
    if ((unsigned)o->up_mode >= PNPR_UP_MODE_COUNT_) return PNPR_ERR_INVALID_ARGUMENT;
    if (o->up_mode != PNPR_UP_VECTOR) return PNPR_OK;
    double u[3] = {o->up[0], o->up[1], o->up[2]};
    return pnpr_normalize3(u) > 0 ? PNPR_OK : PNPR_ERR_INVALID_ARGUMENT;
}

/* The up vector: user, hint, ground plane, default (the ground is reported whenever found). */
static void decide_up(const pnpr_cloud *c, const pnpr_view_options *o, uint64_t seed, const double *pts, size_t m,
                      double diag, const scanner *sc, const double centre[3], pnpr_view_info *info)
{
    plane pl;
    int ground = find_ground(pts, m, diag, seed ^ 0x5eed5eedull, sc, &pl);
    if (ground) {
        info->has_ground = 1;
        memcpy(info->ground_normal, pl.n, sizeof pl.n);
        for (int a = 0; a < 3; a++) info->ground_point[a] = pl.centroid[a] + centre[a];
        info->ground_fraction = (double)pl.on / (double)m;
    }
    if (o->up_mode == PNPR_UP_VECTOR) {
        memcpy(info->up, o->up, sizeof info->up);
        info->up_source = PNPR_UP_FROM_USER;
    } else if (pnpr_up_mode_axis(o->up_mode, info->up)) {
        info->up_source = PNPR_UP_FROM_USER;
    } else if (c->up_hint >= -3 && c->up_hint <= 3 && c->up_hint != 0) {
        axis_vector(c->up_hint, info->up);
        info->up_source = PNPR_UP_FROM_HINT;
    } else if (ground) {
        memcpy(info->up, pl.n, sizeof pl.n);
        snap_to_axis(info->up);
        info->up_source = PNPR_UP_FROM_PLANE;
    } else {
        set3(info->up, 0, 0, 1);
        info->up_source = PNPR_UP_FROM_DEFAULT;
    }
    pnpr_normalize3(info->up);
}

pnpr_status pnpr_scene_frame(const pnpr_cloud *cloud, const pnpr_view_options *opts, pnpr_view_info *r_info)
{
    if (!cloud || !r_info || (cloud->count && !cloud->xyz)) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_view_options o = {0};
    if (opts) o = *opts;
    pnpr_status st = check_options(&o);
    if (st != PNPR_OK) return st;
    memset(r_info, 0, sizeof *r_info);
    size_t m = 0;
    uint64_t seed = o.seed ? o.seed : DEFAULT_SEED;
    float *s = take_sample(cloud, o.max_samples ? o.max_samples : DEFAULT_SAMPLES, seed, &m, &r_info->valid);
    if (r_info->valid == 0) return PNPR_ERR_EMPTY;
    float *sorted = s ? malloc(3 * m * sizeof *sorted) : NULL;
    double *pts = sorted ? malloc(3 * m * sizeof *pts) : NULL;
    if (!pts) { free(s); free(sorted); return PNPR_ERR_OUT_OF_MEMORY; }
    robust_bounds(s, m, sorted, r_info->lo, r_info->hi);
    free(sorted);
    r_info->outliers = count_outliers(cloud, r_info->lo, r_info->hi);
    double centre[3], diag = box_diagonal(r_info->lo, r_info->hi);
    for (int a = 0; a < 3; a++) centre[a] = 0.5 * ((double)r_info->lo[a] + (double)r_info->hi[a]);
    size_t n = inside_points(s, m, r_info->lo, r_info->hi, centre, pts);
    free(s);
    scanner sc = find_scanner(cloud, r_info->lo, r_info->hi, centre);
    decide_up(cloud, &o, seed, pts, n, diag, &sc, centre, r_info);
    view_direction(pts, n, &sc, diag, r_info);
    free(pts);
    return PNPR_OK;
}

int pnpr_up_mode_parse(const char *text, pnpr_up_mode *r_mode)
{
    static const char *names[] = {"auto", "x", "y", "z", "-x", "-y", "-z"};
    if (!text || !r_mode) return 0;
    const char *t = text[0] == '+' && text[1] && text[2] == 0 ? text + 1 : text;
    for (int i = 0; i < 7; i++)
        if (!strcmp(t, names[i])) { *r_mode = (pnpr_up_mode)i; return 1; }
    return 0;
}

int pnpr_up_mode_axis(pnpr_up_mode mode, double r_up[3])
{
    if (mode < PNPR_UP_POS_X || mode > PNPR_UP_NEG_Z || !r_up) return 0;
    int k = (int)mode - (int)PNPR_UP_POS_X; /* 0..5: +x +y +z -x -y -z */
    axis_vector(k < 3 ? k + 1 : -(k - 2), r_up);
    return 1;
}
