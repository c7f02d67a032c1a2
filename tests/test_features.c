/* PointWorks feature analysis with known answers: sphere normals, cube edges and corners, colour
 * boundaries, dithering density, georeferenced offsets, degenerate clouds. */
#include "testutil.h"
#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEG(x) ((x) * 180.0 / 3.14159265358979323846)

/* Angle between two vectors in degrees, well conditioned near 0 (acos of a dot product is not:
 * two equal float unit vectors whose length is 1 - 1e-7 would differ by 0.025 degrees). */
static double angle_deg(const double a[3], const double b[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    double cross = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    return DEG(atan2(cross, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]));
}

static float *prop_f(pnpr_cloud *c, const char *name)
{
    pnpr_property *p = pnpr_cloud_find_property(c, name);
    return p && p->type == PNPR_TYPE_FLOAT32 ? p->data : NULL;
}
static uint8_t *prop_class(pnpr_cloud *c)
{
    pnpr_property *p = pnpr_cloud_find_property(c, "feature_class");
    return p && p->type == PNPR_TYPE_UINT8 ? p->data : NULL;
}

static void test_eigen(void)
{
    double w[3], v[3][3];
    const double diag[3][3] = {{3, 0, 0}, {0, 1, 0}, {0, 0, 2}};
    pnpr_eigen_sym3(diag, w, v);
    CHECK_NEAR(w[0], 1, 1e-12); CHECK_NEAR(w[1], 2, 1e-12); CHECK_NEAR(w[2], 3, 1e-12);
    CHECK_NEAR(fabs(v[0][1]), 1, 1e-12); CHECK_NEAR(fabs(v[2][0]), 1, 1e-12);
    /* rotated matrix with a known spectrum at tiny and huge scales */
    for (int s = -12; s <= 12; s += 6) {
        double sc = pow(10.0, s), c = cos(0.3), si = sin(0.3);
        double R[3][3] = {{c, -si, 0}, {si, c, 0}, {0, 0, 1}}, L[3] = {1e-9 * sc, 2 * sc, 5 * sc}, A[3][3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                A[i][j] = 0;
                for (int m = 0; m < 3; m++) A[i][j] += R[i][m] * L[m] * R[j][m];
            }
        pnpr_eigen_sym3(A, w, v);
        CHECK_NEAR(w[0] / sc, 1e-9, 1e-9);
        CHECK_NEAR(w[1] / sc, 2, 1e-9);
        CHECK_NEAR(w[2] / sc, 5, 1e-9);
        CHECK_NEAR(fabs(v[0][0] * c + v[0][1] * si), 1, 1e-9); /* smallest belongs to R's column 0 */
    }
    /* repeated eigenvalues and NaN */
    const double iso[3][3] = {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    pnpr_eigen_sym3(iso, w, v);
    CHECK(w[0] == 2 && w[2] == 2);
    const double bad[3][3] = {{NAN, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    pnpr_eigen_sym3(bad, w, v);
    CHECK(w[0] == 0 && w[1] == 0 && w[2] == 0 && v[0][0] == 1);
}

/* Rounds world coordinates to a grid of 2^-20 (~1 micrometre), as a scanner or a LAS file at
 * scale 1e-6 stores them: then the cloud at a 5e6 offset is exactly the cloud at the origin
 * moved, and any difference in the results is ours, not the input's double rounding. */
static void quantise(pnpr_cloud *c, const double offset[3])
{
    const double q = 1048576.0;
    for (size_t i = 0; i < 3 * c->count; i++) /* exact: multiples of 2^-20 below 2^3 */
        c->src_xyz[i] = floor(c->src_xyz[i] * q + 0.5) / q + (offset ? offset[i % 3] : 0);
    CHECK_STATUS(pnpr_cloud_set_world(c, c->src_xyz), PNPR_OK);
}

/* Unit sphere, 100k points: mean normal error < 0.3 degree, all oriented outward, no features. */
static void sphere_normals(const double offset[3], float **r_normals)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_sphere(&c, 100000, 1.0, NULL, 42), PNPR_OK);
    quantise(&c, offset);
    pnpr_features_options o = {0};
    pnpr_features_stats s;
    CHECK_STATUS(pnpr_compute_features(&c, &o, &s), PNPR_OK);
    double sum = 0, worst = 0;
    size_t inward = 0;
    for (size_t i = 0; i < c.count; i++) {
        double w[3], n[3] = {c.normal[3 * i], c.normal[3 * i + 1], c.normal[3 * i + 2]}, d = 0;
        pnpr_cloud_world(&c, i, w);
        for (int a = 0; a < 3; a++) { w[a] -= offset ? offset[a] : 0; d += n[a] * w[a]; }
        if (d < 0) inward++;
        double ang = angle_deg(n, w); /* the true normal of the unit sphere is the position */
        if (ang > 90) ang = 180 - ang;
        sum += ang;
        if (ang > worst) worst = ang;
    }
    double mean = sum / (double)c.count;
    fprintf(stderr, "sphere: mean normal error %.4f deg, worst %.3f, inward %zu, features %zu\n", mean, worst,
            inward, s.feature_points);
    CHECK(mean < 0.3);
    CHECK(inward == 0);
    CHECK(s.feature_points < c.count / 200); /* uniform surface: (almost) no feature points */
    if (r_normals) {
        *r_normals = malloc(3 * c.count * sizeof(float));
        memcpy(*r_normals, c.normal, 3 * c.count * sizeof(float));
    }
    pnpr_cloud_free(&c);
}

static void test_sphere_and_offset(void)
{
    float *n0 = NULL, *n1 = NULL;
    const double geo[3] = {5e6, 5e6, 5e6};
    sphere_normals(NULL, &n0);
    sphere_normals(geo, &n1);
    double worst = 0;
    for (size_t i = 0; n0 && n1 && i < 100000; i++) {
        double a[3] = {n0[3 * i], n0[3 * i + 1], n0[3 * i + 2]}, b[3] = {n1[3 * i], n1[3 * i + 1], n1[3 * i + 2]};
        double ang = angle_deg(a, b);
        if (ang > worst) worst = ang;
    }
    fprintf(stderr, "sphere at 5e6 offset vs origin: worst normal difference %.6f deg\n", worst);
    CHECK(worst < 0.01);
    free(n0); free(n1);
}

typedef struct cube_result {
    size_t edge, edge_flagged, edge_dir, edge_dir_ok, face, face_flagged, corner, corner_dir;
} cube_result;

/* Known answers for the cube [0,1]^3 sampled with spacing h: a point is an edge point when it
 * lies on an edge (two coordinates at 0 or 1) at least 3h from a corner, a face point when it
 * is at least 3h from every edge, a corner point when within 1.5h of a corner. */
static cube_result analyse_cube(const double offset[3], double h, pnpr_cloud *keep)
{
    cube_result r = {0};
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_cube(&c, 1.0, h, 0.0, offset, 3), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    uint8_t *cls = prop_class(&c);
    float *dx = prop_f(&c, "feature_dir_x"), *dy = prop_f(&c, "feature_dir_y"), *dz = prop_f(&c, "feature_dir_z");
    CHECK(cls && dx && dy && dz);
    if (!cls || !dx || !dy || !dz) return r;
    for (size_t i = 0; i < c.count; i++) {
        double w[3], ds[3];
        pnpr_cloud_world(&c, i, w);
        for (int a = 0; a < 3; a++) {
            double x = w[a] - (offset ? offset[a] : 0);
            ds[a] = fmin(fabs(x), fabs(1 - x));
        }
        int axis = 0; /* the axis along which an edge point runs: the one not at the boundary */
        for (int a = 1; a < 3; a++) if (ds[a] > ds[axis]) axis = a;
        double s[3] = {ds[0], ds[1], ds[2]};
        for (int a = 0; a < 3; a++) for (int b = a + 1; b < 3; b++) if (s[b] < s[a]) { double t = s[a]; s[a] = s[b]; s[b] = t; }
        if (s[1] < 1e-6 && s[2] >= 3 * h) {
            r.edge++;
            r.edge_flagged += cls[i] != PNPR_CLASS_NONE && cls[i] != PNPR_CLASS_DITHER;
            if (cls[i] == PNPR_CLASS_DIRECTIONAL) {
                r.edge_dir++;
                double d[3] = {dx[i], dy[i], dz[i]};
                double e[3] = {0, 0, 0};
                e[axis] = d[axis] < 0 ? -1 : 1;
                r.edge_dir_ok += angle_deg(d, e) <= 10.0;
            }
        } else if (s[1] >= 3 * h) {
            r.face++;
            r.face_flagged += cls[i] == PNPR_CLASS_DIRECTIONAL || cls[i] == PNPR_CLASS_NONDIRECTIONAL;
        } else if (s[2] < 1.5 * h) {
            r.corner++;
            r.corner_dir += cls[i] == PNPR_CLASS_DIRECTIONAL;
        }
    }
    if (keep) *keep = c; else pnpr_cloud_free(&c);
    return r;
}

static void test_cube(void)
{
    const double geo[3] = {5e6, -3e6, 1234.5};
    for (int pass = 0; pass < 2; pass++) {
        cube_result r = analyse_cube(pass ? geo : NULL, 0.02, NULL);
        fprintf(stderr, "cube%s: edge %zu flagged %zu directional %zu (dir within 10deg: %zu), face %zu flagged %zu, corner %zu directional %zu\n",
                pass ? " at offset" : "", r.edge, r.edge_flagged, r.edge_dir, r.edge_dir_ok, r.face, r.face_flagged, r.corner, r.corner_dir);
        CHECK(r.edge > 500 && r.face > 10000 && r.corner >= 8);
        CHECK(r.edge_flagged >= 0.9 * r.edge);
        CHECK(r.face_flagged <= 0.05 * r.face);
        CHECK(r.edge_dir >= 0.9 * r.edge);
        CHECK(r.edge_dir_ok == r.edge_dir);
        CHECK(r.corner_dir == 0);
    }
    /* the same classes at the offset as at the origin */
    pnpr_cloud a = {0}, b = {0};
    analyse_cube(NULL, 0.02, &a);
    analyse_cube(geo, 0.02, &b);
    uint8_t *ca = prop_class(&a), *cb = prop_class(&b);
    size_t diff = 0;
    for (size_t i = 0; ca && cb && i < a.count; i++) diff += (ca[i] == PNPR_CLASS_DITHER) != (cb[i] == PNPR_CLASS_DITHER) ? 0 : ca[i] != cb[i];
    CHECK_MSG(diff == 0, "%zu feature classes differ between origin and 5e6 offset", diff);
    pnpr_cloud_free(&a); pnpr_cloud_free(&b);
}

/* A flat plane, left half red, right half blue: the colour term alone finds the boundary. */
static void test_colour_boundary(void)
{
    pnpr_cloud c = {0};
    const size_t nx = 100, ny = 60;
    CHECK_STATUS(pnpr_test_plane(&c, nx, ny, 0.01, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    for (size_t i = 0; i < c.count; i++) {
        int left = (i % nx) < nx / 2;
        c.rgb[3 * i] = left ? 200 : 30; c.rgb[3 * i + 1] = 40; c.rgb[3 * i + 2] = left ? 30 : 200;
    }
    for (int mode = 0; mode < 2; mode++) {
        pnpr_features_options o = {0};
        if (mode == 1) { o.weight_geometry = 0; o.weight_color = 1; } /* colour term alone */
        float *deg;
        CHECK_STATUS(pnpr_compute_features(&c, &o, NULL), PNPR_OK);
        deg = prop_f(&c, "feature_degree");
        uint8_t *cls = prop_class(&c);
        size_t near = 0, near_flag = 0, far = 0, far_flag = 0;
        for (size_t i = 0; i < c.count; i++) {
            long col = (long)(i % nx);
            long dist = col < (long)nx / 2 ? (long)nx / 2 - 1 - col : col - (long)nx / 2; /* 0 next to the boundary */
            int flagged = cls[i] == PNPR_CLASS_DIRECTIONAL || cls[i] == PNPR_CLASS_NONDIRECTIONAL;
            if (dist == 0) { near++; near_flag += flagged; }
            if (dist >= 4) { far++; far_flag += flagged; CHECK(deg[i] < 0.05f); }
        }
        fprintf(stderr, "colour boundary (mode %d): next to boundary %zu/%zu flagged, far %zu/%zu\n", mode, near_flag, near, far_flag, far);
        CHECK(near_flag >= 0.9 * near);
        CHECK(far_flag == 0);
    }
    pnpr_cloud_free(&c);
}

/* A plane whose grey tone rises linearly from white (x=0) to black (x=1): the fraction of
 * dithering points in each tenth of the plane follows the tone within 0.05. */
/* Issue 18: the whole pipeline gives byte-identical outputs on 1, 2 and 7 threads (a noisy,
 * coloured cube of 14 400 points: every stage, the dithering's error diffusion included). */
static void test_thread_counts(void)
{
    pnpr_cloud c[3] = {{0}, {0}, {0}};
    const int threads[3] = {1, 2, 7};
    for (int t = 0; t < 3; t++) {
        CHECK_STATUS(pnpr_test_cube(&c[t], 1.0, 0.02, 0.002, NULL, 5), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_alloc_rgb(&c[t]), PNPR_OK);
        for (size_t i = 0; i < c[t].count; i++) /* colour bands, so that the colour term has work */
            for (int a = 0; a < 3; a++) c[t].rgb[3 * i + a] = (uint8_t)(60 + 40 * (a + (int)(4 * c[t].xyz[3 * i + a])));
        pnpr_features_options o = {0};
        o.threads = threads[t];
        CHECK_STATUS(pnpr_compute_features(&c[t], &o, NULL), PNPR_OK);
    }
    size_t props = c[0].prop_count, differ = 0, dither = 0;
    for (int t = 1; t < 3; t++) {
        CHECK(c[t].prop_count == props && c[t].normal && c[0].normal);
        if (c[t].prop_count != props || !c[t].normal || !c[0].normal) break;
        differ += memcmp(c[0].normal, c[t].normal, 3 * c[0].count * sizeof(float)) != 0;
        for (size_t p = 0; p < props; p++) {
            const pnpr_property *a = &c[0].props[p], *b = &c[t].props[p];
            int same = !strcmp(a->name, b->name) && a->type == b->type &&
                       !memcmp(a->data, b->data, c[0].count * pnpr_type_size(a->type));
            if (!same) fprintf(stderr, "threads %d: property %s differs from 1 thread\n", threads[t], a->name);
            differ += !same;
        }
    }
    uint8_t *cls = prop_class(&c[0]);
    for (size_t i = 0; cls && i < c[0].count; i++) dither += cls[i] == PNPR_CLASS_DITHER;
    fprintf(stderr, "threads 1 / 2 / 7: %zu points, %zu properties, %zu dithering points, %zu outputs differ\n",
            c[0].count, props, dither, differ);
    CHECK(props >= 5 && dither > 0 && differ == 0);
    for (int t = 0; t < 3; t++) pnpr_cloud_free(&c[t]);
}

static void test_dither_density(void)
{
    pnpr_cloud c = {0};
    const size_t nx = 400, ny = 100;
    CHECK_STATUS(pnpr_test_plane(&c, nx, ny, 0.0025, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    for (size_t i = 0; i < c.count; i++) {
        double t = (double)(i % nx) / (double)(nx - 1);
        uint8_t g = (uint8_t)(255.0 * (1.0 - t) + 0.5);
        c.rgb[3 * i] = c.rgb[3 * i + 1] = c.rgb[3 * i + 2] = g;
    }
    pnpr_features_options o = {0};
    o.weight_geometry = 1; /* geometry only: a gradient this smooth is no feature either way */
    o.tone.source = PNPR_TONE_COLOR;
    o.tone.gamma = 1;      /* the identity tone curve: the dithering itself is under test */
    CHECK_STATUS(pnpr_compute_features(&c, &o, NULL), PNPR_OK);
    uint8_t *cls = prop_class(&c);
    for (int band = 0; band < 10; band++) {
        size_t n = 0, d = 0;
        double tone = 0;
        for (size_t i = 0; i < c.count; i++) {
            size_t col = i % nx;
            if ((int)(col * 10 / nx) != band) continue;
            n++;
            d += cls[i] == PNPR_CLASS_DITHER;
            tone += 1.0 - c.rgb[3 * i] / 255.0;
        }
        double frac = (double)d / (double)n, want = tone / (double)n;
        fprintf(stderr, "dither band %d: tone %.3f, dithering fraction %.3f\n", band, want, frac);
        CHECK_NEAR(frac, want, 0.05);
    }
    pnpr_cloud_free(&c);
}

static pnpr_status run_small(const float *pts, size_t n, pnpr_features_stats *s, pnpr_cloud *c)
{
    pnpr_cloud_free(c);
    pnpr_status st = pnpr_cloud_alloc(c, n);
    if (st != PNPR_OK) return st;
    if (n) memcpy(c->xyz, pts, 3 * n * sizeof(float));
    return pnpr_compute_features(c, NULL, s);
}

static void test_degenerate(void)
{
    pnpr_cloud c = {0};
    pnpr_features_stats s;
    /* empty cloud: defined empty result */
    CHECK_STATUS(run_small(NULL, 0, &s, &c), PNPR_OK);
    CHECK(pnpr_cloud_find_property(&c, "feature_class") != NULL);
    /* one point, two points: no plane, zero normals, no features */
    float one[6] = {1, 2, 3, 1, 2, 4};
    CHECK_STATUS(run_small(one, 1, &s, &c), PNPR_OK);
    CHECK(c.normal[0] == 0 && c.normal[1] == 0 && c.normal[2] == 0);
    CHECK_STATUS(run_small(one, 2, &s, &c), PNPR_OK);
    CHECK(s.feature_points == 0);
    /* all points identical: zero normals, no features, no crash */
    float *same = calloc(3 * 500, sizeof(float));
    for (int i = 0; i < 500; i++) { same[3 * i] = 7; same[3 * i + 1] = -1; same[3 * i + 2] = 0.5f; }
    CHECK_STATUS(run_small(same, 500, &s, &c), PNPR_OK);
    int allzero = 1;
    for (size_t i = 0; i < 3 * c.count; i++) allzero &= c.normal[i] == 0.0f;
    CHECK(allzero);
    CHECK(s.feature_points == 0);
    /* collinear: unit normals perpendicular to the line */
    float *line = calloc(3 * 300, sizeof(float));
    for (int i = 0; i < 300; i++) { line[3 * i] = 0.01f * i; line[3 * i + 1] = 0.02f * i; }
    CHECK_STATUS(run_small(line, 300, &s, &c), PNPR_OK);
    int perp = 1;
    for (size_t i = 0; i < c.count; i++) {
        const float *n = c.normal + 3 * i;
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        perp &= fabs(len - 1) < 1e-4 && fabs(n[0] * 1 + n[1] * 2) / sqrt(5.0) < 1e-3;
    }
    CHECK(perp);
    /* coplanar grid: normals +-z (propagated: all the same sign), no features */
    pnpr_cloud_free(&c);
    CHECK_STATUS(pnpr_test_plane(&c, 50, 50, 0.1, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, &s), PNPR_OK);
    size_t up = 0;
    for (size_t i = 0; i < c.count; i++) up += c.normal[3 * i + 2] > 0.9999f;
    CHECK(up == c.count);
    CHECK(s.feature_points == 0);
    /* fewer points than k: k is clamped */
    CHECK_STATUS(run_small(line, 5, &s, &c), PNPR_OK);
    CHECK(s.k_used == 5);
    /* NaN/Inf coordinates: those points get nothing, the others are analysed as without them */
    line[3 * 10] = NAN; line[3 * 20 + 1] = INFINITY;
    CHECK_STATUS(run_small(line, 300, &s, &c), PNPR_OK);
    CHECK(s.valid_points == 298);
    CHECK(c.normal[30] == 0 && c.normal[31] == 0 && c.normal[32] == 0);
    CHECK(prop_class(&c)[10] == PNPR_CLASS_NONE);
    CHECK(fabs(c.normal[3 * 11] * 1 + c.normal[3 * 11 + 1] * 2) < 1e-3);
    /* bad options: exact error codes */
    pnpr_features_options o = {0};
    o.threshold = 2;
    CHECK_STATUS(pnpr_compute_features(&c, &o, NULL), PNPR_ERR_INVALID_ARGUMENT);
    o.threshold = 0; o.k = 100000;
    CHECK_STATUS(pnpr_compute_features(&c, &o, NULL), PNPR_ERR_INVALID_ARGUMENT);
    o.k = 0; o.weight_color = -1;
    CHECK_STATUS(pnpr_compute_features(&c, &o, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_compute_features(NULL, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    free(same); free(line);
    pnpr_cloud_free(&c);
}

/* Normals face a given viewpoint; input normals are kept unless recomputation is asked for. */
static void test_viewpoint_and_keep(void)
{
    pnpr_cloud c = {0};
    const double off[3] = {1000, 2000, 3000};
    CHECK_STATUS(pnpr_test_plane(&c, 30, 30, 0.1, off), PNPR_OK);
    pnpr_features_options o = {0};
    o.has_viewpoint = 1;
    o.viewpoint[0] = 1001; o.viewpoint[1] = 2001; o.viewpoint[2] = 3000 - 10; /* below the plane */
    CHECK_STATUS(pnpr_compute_features(&c, &o, NULL), PNPR_OK);
    size_t down = 0;
    for (size_t i = 0; i < c.count; i++) down += c.normal[3 * i + 2] < -0.9999f;
    CHECK(down == c.count);
    /* keep: set a recognisable normal, run again without recompute */
    for (size_t i = 0; i < c.count; i++) { c.normal[3 * i] = 1; c.normal[3 * i + 1] = 0; c.normal[3 * i + 2] = 0; }
    pnpr_features_stats s;
    CHECK_STATUS(pnpr_compute_features(&c, NULL, &s), PNPR_OK);
    CHECK(c.normal[0] == 1 && c.normal[2] == 0);
    CHECK(s.runs[PNPR_STAGE_ORIENT] == 0 && s.runs[PNPR_STAGE_NORMALS] == 1);
    o.has_viewpoint = 0; o.recompute_normals = 1;
    CHECK_STATUS(pnpr_compute_features(&c, &o, &s), PNPR_OK);
    CHECK(fabs(c.normal[2]) > 0.9999f);
    CHECK(s.runs[PNPR_STAGE_ORIENT] == 1);
    pnpr_cloud_free(&c);
}

static int cancel_at_knn(void *user, const char *stage, double f)
{
    (void)f;
    int *calls = user;
    (*calls)++;
    return strcmp(stage, "knn") == 0;
}

static void test_cancel(void)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_sphere(&c, 20000, 1, NULL, 1), PNPR_OK);
    int calls = 0;
    pnpr_features_options o = {0};
    o.progress.fn = cancel_at_knn;
    o.progress.user = &calls;
    pnpr_features_stats s;
    CHECK_STATUS(pnpr_compute_features(&c, &o, &s), PNPR_ERR_CANCELLED);
    CHECK(calls >= 2);
    CHECK(s.runs[PNPR_STAGE_NORMALS] == 0);
    pnpr_cloud_free(&c);
}

/* Computing only what is needed: each wanted output runs its stages and no other (stage run
 * counters), and its values equal those of the full run. */
static void test_wanted_outputs(void)
{
    pnpr_cloud full = {0};
    CHECK_STATUS(pnpr_test_cube(&full, 1.0, 0.04, 0.0, NULL, 3), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&full, NULL, NULL), PNPR_OK);
    const float *deg_full = prop_f(&full, "feature_degree");
    const uint8_t *cls_full = prop_class(&full);
    struct { uint32_t want; int orient, degree, classify, dither; } cases[] = {
        {PNPR_WANT_NORMALS, 1, 0, 0, 0},
        {PNPR_WANT_DEGREE, 0, 1, 0, 0},
        {PNPR_WANT_CLASSES, 0, 1, 1, 0},
        {PNPR_WANT_DITHER, 0, 1, 1, 1}, /* no colours: the tone's two-sided light needs no orientation */
        {PNPR_WANT_DEGREE | PNPR_WANT_NORMALS, 1, 1, 0, 0},
    };
    for (size_t t = 0; t < sizeof cases / sizeof *cases; t++) {
        pnpr_cloud c = {0};
        CHECK_STATUS(pnpr_test_cube(&c, 1.0, 0.04, 0.0, NULL, 3), PNPR_OK);
        pnpr_features_options o = {0};
        o.want = cases[t].want;
        pnpr_features_stats s;
        CHECK_STATUS(pnpr_compute_features(&c, &o, &s), PNPR_OK);
        CHECK_MSG(s.runs[PNPR_STAGE_KNN] == 1 && s.runs[PNPR_STAGE_NORMALS] == 1, "want %u", (unsigned)o.want);
        CHECK_MSG((int)s.runs[PNPR_STAGE_ORIENT] == cases[t].orient, "want %u: orient ran %u", (unsigned)o.want, (unsigned)s.runs[PNPR_STAGE_ORIENT]);
        CHECK_MSG((int)s.runs[PNPR_STAGE_FEATURE_DEGREE] == cases[t].degree, "want %u", (unsigned)o.want);
        CHECK_MSG((int)s.runs[PNPR_STAGE_CLASSIFY] == cases[t].classify, "want %u", (unsigned)o.want);
        CHECK_MSG((int)s.runs[PNPR_STAGE_DITHER] == cases[t].dither, "want %u", (unsigned)o.want);
        /* only the wanted outputs are stored, and they equal the full run's */
        CHECK((c.normal != NULL) == (cases[t].orient != 0));
        CHECK((prop_f(&c, "feature_degree") != NULL) == (cases[t].degree != 0));
        CHECK((prop_class(&c) != NULL) == (cases[t].classify != 0));
        const float *deg = prop_f(&c, "feature_degree");
        const uint8_t *cls = prop_class(&c);
        size_t diff = 0;
        for (size_t i = 0; i < c.count; i++) {
            if (deg) diff += deg[i] != deg_full[i];
            if (cls && cases[t].dither) diff += cls[i] != cls_full[i];
            if (cls && !cases[t].dither) diff += cls[i] != (cls_full[i] == PNPR_CLASS_DITHER ? PNPR_CLASS_NONE : cls_full[i]);
            if (c.normal && cases[t].orient) diff += memcmp(c.normal + 3 * i, full.normal + 3 * i, 3 * sizeof(float)) != 0;
        }
        CHECK_MSG(diff == 0, "want %u: %zu values differ from the full run", (unsigned)o.want, diff);
        pnpr_cloud_free(&c);
    }
    pnpr_features_options bad = {0};
    bad.want = 16;
    CHECK_STATUS(pnpr_compute_features(&full, &bad, NULL), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_cloud_free(&full);
}

/* point_spacing (props.h): written from the feature stage's own neighbour lists, it equals the
 * upload's spacing routine (pnpr_point_spacing, its own kd-tree and kNN) once clamped, bit for
 * bit, on a noisy cube with duplicated points and NaN points; NaN points get 0; a run whose
 * lists do not reach the 4th neighbour (k 4) removes an older one instead of leaving it stale. */
static void test_point_spacing(void)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_cube(&c, 1.0, 0.04, 0.004, NULL, 5), PNPR_OK);
    for (size_t i = 0; i + 1 < c.count; i += 97) memcpy(c.xyz + 3 * (i + 1), c.xyz + 3 * i, 3 * sizeof(float));
    c.xyz[3 * 10] = NAN;
    c.xyz[3 * 500 + 2] = INFINITY;
    float *ref = malloc(c.count * sizeof *ref), *got = malloc(c.count * sizeof *got);
    CHECK(ref && got);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    const float *sp = prop_f(&c, PNPR_PROP_POINT_SPACING);
    CHECK(sp != NULL);
    if (sp && ref && got) {
        CHECK(sp[10] == 0 && sp[500] == 0);
        size_t m = 0; /* the finite points, as the upload takes them */
        float *xyz = malloc(3 * c.count * sizeof *xyz);
        for (size_t i = 0; xyz && i < c.count; i++)
            if (isfinite(c.xyz[3 * i]) && isfinite(c.xyz[3 * i + 1]) && isfinite(c.xyz[3 * i + 2])) {
                memcpy(xyz + 3 * m, c.xyz + 3 * i, 3 * sizeof(float));
                got[m++] = sp[i];
            }
        CHECK_STATUS(pnpr_point_spacing(xyz, m, 4, 0, ref, NULL), PNPR_OK);
        CHECK_STATUS(pnpr_spacing_clamp(got, m), PNPR_OK);
        size_t diff = 0;
        for (size_t i = 0; i < m; i++) diff += got[i] != ref[i];
        CHECK_MSG(m == c.count - 2 && diff == 0, "%zu of %zu clamped spacings differ from pnpr_point_spacing", diff, m);
        free(xyz);
    }
    pnpr_features_options o = {0};
    o.k = 4;
    CHECK_STATUS(pnpr_compute_features(&c, &o, NULL), PNPR_OK);
    CHECK_MSG(pnpr_cloud_find_property(&c, PNPR_PROP_POINT_SPACING) == NULL, "k 4 left a stale point_spacing");
    free(ref);
    free(got);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_thread_counts();
    test_point_spacing();
    test_wanted_outputs();
    test_eigen();
    test_sphere_and_offset();
    test_cube();
    test_colour_boundary();
    test_dither_density();
    test_degenerate();
    test_viewpoint_and_keep();
    test_cancel();
    return pnpr_test_finish("test_features");
}
