/* Profile lines with known answers: a cube's 12 edges (clean and noisy), a cylinder's two rims, a
 * plane without lines, degenerate inputs, a 1e7 offset. */
#include "testutil.h"
#include <pointnpr/features.h>
#include <pointnpr/io.h>
#include <pointnpr/lines.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Distance from p to segment ab. */
static double seg_dist(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], t = 0, l2 = 0;
    for (int k = 0; k < 3; k++) { ab[k] = b[k] - a[k]; ap[k] = p[k] - a[k]; t += ab[k] * ap[k]; l2 += ab[k] * ab[k]; }
    t = l2 > 0 ? t / l2 : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    double d = 0;
    for (int k = 0; k < 3; k++) { double e = a[k] + t * ab[k] - p[k]; d += e * e; }
    return sqrt(d);
}

static void vertex(const pnpr_polylines *l, size_t i, const double off[3], double r[3])
{
    for (int k = 0; k < 3; k++) r[k] = l->origin[k] + (double)l->xyz[3 * i + k] - (off ? off[k] : 0);
}

/* Distance from p to the nearest polyline segment. */
static double line_dist(const pnpr_polylines *l, const double p[3], const double off[3])
{
    double best = INFINITY;
    for (size_t c = 0; c < l->count; c++) {
        size_t a = l->offset[c], b = l->offset[c + 1];
        for (size_t v = a; v < b; v++) {
            size_t w = v + 1 < b ? v + 1 : (l->closed[c] ? a : v);
            double pa[3], pb[3];
            vertex(l, v, off, pa);
            vertex(l, w, off, pb);
            double d = seg_dist(p, pa, pb);
            if (d < best) best = d;
        }
    }
    return best;
}

static double total_length(const pnpr_polylines *l)
{
    double len = 0;
    for (size_t c = 0; c < l->count; c++) {
        size_t a = l->offset[c], b = l->offset[c + 1];
        for (size_t v = a; v + 1 < b + (l->closed[c] ? 1 : 0); v++) {
            size_t w = v + 1 < b ? v + 1 : a;
            double d = 0;
            for (int k = 0; k < 3; k++) { double e = (double)l->xyz[3 * w + k] - l->xyz[3 * v + k]; d += e * e; }
            len += sqrt(d);
        }
    }
    return len;
}

/* Distance from p to the nearest edge of the cube [0,1]^3. */
static double cube_edge_dist(const double p[3])
{
    double best = INFINITY;
    for (int axis = 0; axis < 3; axis++) {
        int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int cu = 0; cu <= 1; cu++)
            for (int cv = 0; cv <= 1; cv++) {
                double t = p[axis] < 0 ? 0 : (p[axis] > 1 ? 1 : p[axis]);
                double d = (p[axis] - t) * (p[axis] - t) + (p[u] - cu) * (p[u] - cu) + (p[v] - cv) * (p[v] - cv);
                if (d < best) best = d;
            }
    }
    return sqrt(best);
}

static void cube_lines(double noise, const double off[3], int duplicate, pnpr_polylines *r, pnpr_lines_stats *s)
{
    const double h = 0.02;
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_cube(&c, 1.0, h, noise * h, off, 11), PNPR_OK);
    if (duplicate) {
        pnpr_cloud twin = {0};
        CHECK_STATUS(pnpr_cloud_append(&twin, &c), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_append(&c, &twin), PNPR_OK);
        pnpr_cloud_free(&twin);
    }
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_profile_lines(&c, NULL, r, s), PNPR_OK);
    pnpr_cloud_free(&c);
}

static void check_cube(const char *name, const pnpr_polylines *l, const pnpr_lines_stats *s, const double off[3])
{
    const double h = 0.02;
    /* every edge sample within 1.5 spacings of a line */
    size_t far = 0, samples = 0;
    double worst = 0;
    for (int axis = 0; axis < 3; axis++)
        for (int cu = 0; cu <= 1; cu++)
            for (int cv = 0; cv <= 1; cv++)
                for (int i = 0; i <= 100; i++) {
                    double p[3];
                    p[axis] = i / 100.0;
                    p[(axis + 1) % 3] = cu;
                    p[(axis + 2) % 3] = cv;
                    double d = line_dist(l, p, off);
                    if (d > worst) worst = d;
                    far += d > 1.5 * h;
                    samples++;
                }
    /* no line across a face: every vertex near an edge */
    size_t stray = 0;
    for (size_t v = 0; v < (l->count ? l->offset[l->count] : 0); v++) {
        double p[3];
        vertex(l, v, off, p);
        stray += cube_edge_dist(p) > 2 * h;
    }
    double len = total_length(l);
    fprintf(stderr, "%s: %zu polylines, length %.3f (edges 12), edge samples farther than 1.5h: %zu/%zu (worst %.4f), "
            "vertices off the edges: %zu, corners %zu, spacing %.4f\n", name, l->count, len, far, samples, worst, stray,
            s->corners, s->spacing_used);
    CHECK(far == 0);
    CHECK(fabs(len - 12.0) <= 1.2);
    CHECK(stray == 0);
}

static void test_cube(void)
{
    pnpr_polylines l = {0};
    pnpr_lines_stats s;
    cube_lines(0.0, NULL, 0, &l, &s);
    check_cube("cube", &l, &s, NULL);
    pnpr_lines_free(&l);
    cube_lines(0.2, NULL, 0, &l, &s);
    check_cube("cube, noise 0.2h", &l, &s, NULL);
    pnpr_lines_free(&l);
    cube_lines(0.0, NULL, 1, &l, &s);
    check_cube("cube, every point duplicated", &l, &s, NULL);
    pnpr_lines_free(&l);
    const double off[3] = {1e7, -1e7, 5e6};
    cube_lines(0.0, off, 0, &l, &s);
    check_cube("cube at 1e7 offset", &l, &s, off);
    pnpr_lines_free(&l);
}

/* Closed cylinder (radius 0.5, height 1, caps), spacing h: the rims are 90-degree creases. */
static pnpr_status make_cylinder(pnpr_cloud *c, double h, const double off[3])
{
    const double r = 0.5, pi2 = 6.283185307179586;
    size_t na = (size_t)(pi2 * r / h + 0.5), nz = (size_t)(1.0 / h + 0.5), ng = (size_t)(2 * r / h + 1.5);
    size_t cap = na * (nz + 1) + 2 * ng * ng;
    double *w = malloc(3 * cap * sizeof *w);
    if (!w) return PNPR_ERR_OUT_OF_MEMORY;
    size_t n = 0;
    for (size_t k = 0; k <= nz; k++)
        for (size_t a = 0; a < na; a++) {
            double t = pi2 * (double)a / (double)na;
            w[3 * n] = r * cos(t); w[3 * n + 1] = r * sin(t); w[3 * n + 2] = (double)k / (double)nz;
            n++;
        }
    for (int top = 0; top <= 1; top++)
        for (size_t i = 0; i < ng; i++)
            for (size_t j = 0; j < ng; j++) {
                double x = -r + (double)i * h, y = -r + (double)j * h;
                if (x * x + y * y > (r - 0.5 * h) * (r - 0.5 * h)) continue;
                w[3 * n] = x; w[3 * n + 1] = y; w[3 * n + 2] = top;
                n++;
            }
    for (size_t i = 0; i < 3 * n; i++) w[i] += off ? off[i % 3] : 0;
    pnpr_status st = pnpr_cloud_alloc(c, n);
    if (st == PNPR_OK) st = pnpr_cloud_set_world(c, w);
    if (st == PNPR_OK) { c->src_xyz = w; c->src_coord_type = PNPR_TYPE_FLOAT64; }
    else free(w);
    return st;
}

static void test_cylinder(void)
{
    const double h = 0.02, r = 0.5, circ = 6.283185307179586 * r;
    pnpr_cloud c = {0};
    CHECK_STATUS(make_cylinder(&c, h, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    pnpr_polylines l = {0};
    pnpr_lines_stats s;
    CHECK_STATUS(pnpr_profile_lines(&c, NULL, &l, &s), PNPR_OK);
    /* per rim: polylines whose vertices lie near z = 0 (or 1) and radius r */
    for (int rim = 0; rim <= 1; rim++) {
        size_t lines = 0, closed = 0, off_rim = 0;
        double len = 0, max_gap = 0;
        for (size_t p = 0; p < l.count; p++) {
            size_t a = l.offset[p], b = l.offset[p + 1];
            double z0 = l.origin[2] + l.xyz[3 * a + 2];
            if (fabs(z0 - rim) > 0.1) continue;
            lines++;
            closed += l.closed[p];
            for (size_t v = a; v < b; v++) {
                double x = l.origin[0] + l.xyz[3 * v], y = l.origin[1] + l.xyz[3 * v + 1], z = l.origin[2] + l.xyz[3 * v + 2];
                off_rim += fabs(sqrt(x * x + y * y) - r) > 1.5 * h || fabs(z - rim) > 1.5 * h;
                if (v + 1 < b) {
                    double d = 0;
                    for (int k = 0; k < 3; k++) { double e = (double)l.xyz[3 * v + 3 + k] - l.xyz[3 * v + k]; d += e * e; }
                    len += sqrt(d);
                }
            }
            if (!l.closed[p]) { /* distance between its ends: the gap left open */
                double d = 0;
                for (int k = 0; k < 3; k++) { double e = (double)l.xyz[3 * (b - 1) + k] - l.xyz[3 * a + k]; d += e * e; }
                if (sqrt(d) > max_gap) max_gap = sqrt(d);
            }
        }
        fprintf(stderr, "cylinder rim z=%d: %zu polyline(s), %zu closed, length %.3f (circumference %.3f), largest open gap %.4f, vertices off the rim %zu\n",
                rim, lines, closed, len, circ, max_gap, off_rim);
        CHECK(lines == 1);
        CHECK(closed == 1 || max_gap < 0.05 * circ);
        CHECK(fabs(len - circ) < 0.1 * circ);
        CHECK(off_rim == 0);
    }
    CHECK(l.count == 2); /* nothing on the side or the caps */
    pnpr_lines_free(&l);
    pnpr_cloud_free(&c);
}

static void test_plane_and_degenerate(void)
{
    pnpr_cloud c = {0};
    pnpr_polylines l = {0};
    pnpr_lines_stats s;
    /* a plane: no directional points, no lines */
    CHECK_STATUS(pnpr_test_plane(&c, 60, 60, 0.02, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_profile_lines(&c, NULL, &l, &s), PNPR_OK);
    CHECK(l.count == 0 && s.directional_points == 0);
    pnpr_lines_free(&l);
    /* features missing: NOT_FOUND */
    pnpr_cloud bare = {0};
    CHECK_STATUS(pnpr_test_plane(&bare, 5, 5, 0.1, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_profile_lines(&bare, NULL, &l, &s), PNPR_ERR_NOT_FOUND);
    pnpr_cloud_free(&bare);
    /* directional points all on one line: one straight polyline along it */
    enum { N = 200 };
    float p[3 * N], d[3 * N];
    for (int i = 0; i < N; i++) {
        p[3 * i] = 0.01f * i; p[3 * i + 1] = 0.02f * i; p[3 * i + 2] = 0;
        d[3 * i] = 1 / sqrtf(5); d[3 * i + 1] = 2 / sqrtf(5); d[3 * i + 2] = 0;
    }
    const double o[3] = {0, 0, 0};
    CHECK_STATUS(pnpr_profile_lines_points(p, d, N, o, NULL, &l, &s), PNPR_OK);
    CHECK(l.count == 1);
    CHECK_NEAR(s.total_length, 199 * 0.01 * sqrt(5.0), 0.05);
    pnpr_lines_free(&l);
    /* duplicates only: all points identical -> no line, no crash */
    for (int i = 0; i < 3 * N; i++) p[i] = 1.5f;
    CHECK_STATUS(pnpr_profile_lines_points(p, d, N, o, NULL, &l, &s), PNPR_OK);
    CHECK(l.count == 0);
    pnpr_lines_free(&l);
    /* NaN positions and zero directions are skipped; no points at all is fine */
    p[0] = NAN; d[3] = d[4] = d[5] = 0;
    CHECK_STATUS(pnpr_profile_lines_points(p, d, N, o, NULL, &l, &s), PNPR_OK);
    CHECK(s.directional_points == N - 2);
    pnpr_lines_free(&l);
    CHECK_STATUS(pnpr_profile_lines_points(NULL, NULL, 0, o, NULL, &l, &s), PNPR_OK);
    CHECK(l.count == 0 && l.offset != NULL);
    pnpr_lines_free(&l);
    /* bad options: exact error codes */
    pnpr_lines_options bad = {0};
    bad.spacing = -1;
    CHECK_STATUS(pnpr_profile_lines_points(p, d, N, o, &bad, &l, &s), PNPR_ERR_INVALID_ARGUMENT);
    bad.spacing = NAN;
    CHECK_STATUS(pnpr_profile_lines_points(p, d, N, o, &bad, &l, &s), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_profile_lines_points(p, d, N, o, NULL, NULL, &s), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_cloud_free(&c);
}

/* The same lines at a 1e7 offset as at the origin: the input differs only by the double rounding
 * of 1e7 + x (~1e-9): same count, same length to 1e-3, every vertex of each set within half a
 * spacing of the other set. (Not closer: on a regular grid many neighbour distances tie exactly,
 * and a 1e-9 difference can flip a discrete choice — which candidate line wins, which point a
 * merge takes — moving a line by up to a third of a spacing; both sets stay within 1.5 spacings
 * of the true edges, which test_cube checks.) */
static void test_offset_same_lines(void)
{
    pnpr_polylines a = {0}, b = {0};
    pnpr_lines_stats sa, sb;
    const double off[3] = {1e7, -1e7, 5e6};
    cube_lines(0.0, NULL, 0, &a, &sa);
    cube_lines(0.0, off, 0, &b, &sb);
    CHECK(a.count == b.count);
    CHECK(fabs(sa.total_length - sb.total_length) < 1e-3 * sa.total_length);
    double worst = 0;
    for (int pass = 0; pass < 2; pass++) {
        const pnpr_polylines *x = pass ? &b : &a, *y = pass ? &a : &b;
        const double *xo = pass ? off : NULL, *yo = pass ? NULL : off;
        for (size_t i = 0; i < (x->count ? x->offset[x->count] : 0); i++) {
            double p[3];
            vertex(x, i, xo, p);
            double d = line_dist(y, p, yo);
            if (d > worst) worst = d;
        }
    }
    fprintf(stderr, "1e7 offset vs origin: %zu vs %zu polylines, length %.6f vs %.6f, largest distance between the two sets %.2e\n",
            a.count, b.count, sa.total_length, sb.total_length, worst);
    CHECK(worst < 0.5 * 0.02);
    pnpr_lines_free(&a);
    pnpr_lines_free(&b);
}

static void test_writers(void)
{
    pnpr_polylines l = {0};
    pnpr_lines_stats s;
    const double off[3] = {1e7, 0, 0};
    cube_lines(0.0, off, 0, &l, &s);
    pnpr_error err = {0};
    char obj[512], ply[512];
    snprintf(obj, sizeof obj, "%s/lines_cube.obj", PNPR_TEST_SCRATCH);
    snprintf(ply, sizeof ply, "%s/lines_cube.ply", PNPR_TEST_SCRATCH);
    CHECK_STATUS(pnpr_write_lines_obj(obj, &l, &err), PNPR_OK);
    CHECK_STATUS(pnpr_write_lines_ply(ply, &l, &err), PNPR_OK);
    /* OBJ: one v per vertex, one l per polyline, world coordinates with the offset */
    FILE *f = fopen(obj, "r");
    CHECK(f != NULL);
    size_t nv = 0, nl = 0;
    double x0 = 0;
    char line[4096];
    while (f && fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') { if (nv == 0) x0 = strtod(line + 2, NULL); nv++; }
        if (line[0] == 'l' && line[1] == ' ') nl++;
    }
    if (f) fclose(f);
    CHECK(nv == l.offset[l.count] && nl == l.count);
    CHECK(fabs(x0 - 1e7) < 2);
    /* PLY: reads back through our own reader with exactly those vertices */
    pnpr_cloud back = {0};
    CHECK_STATUS(pnpr_read_file(ply, NULL, &back, &err), PNPR_OK);
    CHECK(back.count == l.offset[l.count]);
    pnpr_cloud_free(&back);
    CHECK_STATUS(pnpr_write_lines_obj("/nonexistent-dir/x.obj", &l, &err), PNPR_ERR_IO);
    pnpr_lines_free(&l);
}

/* The shift, graph, edge sort and fit stages run in parallel: 1, 2 and 7 threads give the same
 * polylines, vertex for vertex (the noisy cube; random segments with a graph large enough for the
 * sort's parts). */
static void test_threads_same_lines(void)
{
    const double h = 0.02;
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_cube(&c, 1.0, h, 0.2 * h, NULL, 11), PNPR_OK);
    CHECK_STATUS(pnpr_compute_features(&c, NULL, NULL), PNPR_OK);
    pnpr_polylines l[3] = {{0}, {0}, {0}};
    pnpr_lines_stats s[3];
    const int threads[3] = {1, 2, 7};
    for (int k = 0; k < 3; k++) {
        pnpr_lines_options o;
        memset(&o, 0, sizeof o);
        o.threads = threads[k];
        CHECK_STATUS(pnpr_profile_lines(&c, &o, &l[k], &s[k]), PNPR_OK);
    }
    printf("threads 1 / 2 / 7: %zu / %zu / %zu polylines, %zu graph edges\n", l[0].count, l[1].count, l[2].count,
           s[0].graph_edges);
    CHECK(l[0].count >= 12 && s[0].graph_edges > 1000);
    for (int k = 1; k < 3; k++) {
        CHECK(l[k].count == l[0].count && s[k].graph_edges == s[0].graph_edges && s[k].forest_edges == s[0].forest_edges);
        if (l[k].count != l[0].count) continue;
        CHECK(!memcmp(l[k].offset, l[0].offset, (l[0].count + 1) * sizeof *l[0].offset));
        CHECK(!memcmp(l[k].closed, l[0].closed, l[0].count));
        CHECK(!memcmp(l[k].xyz, l[0].xyz, 3 * l[0].offset[l[0].count] * sizeof *l[0].xyz));
    }
    for (int k = 0; k < 3; k++) pnpr_lines_free(&l[k]);
    pnpr_cloud_free(&c);
    /* 30 000 points on 300 random noisy segments (as bench_lines): enough graph edges (about
     * 69 000) for the edge sort to split into 2 and 4 parts */
    enum { N = 30000 };
    float *p = malloc(N * 3 * sizeof *p), *d = malloc(N * 3 * sizeof *d);
    if (!p || !d) { free(p); free(d); CHECK(0); return; }
    pnpr_test_rng rng = {7};
    for (size_t s0 = 0; s0 < N; s0 += 100) {
        double o[3], dir[3], len = 0;
        for (int a = 0; a < 3; a++) { o[a] = 15 * pnpr_test_uniform(&rng); dir[a] = pnpr_test_normal(&rng); len += dir[a] * dir[a]; }
        len = sqrt(len);
        for (size_t i = s0; i < s0 + 100; i++)
            for (int a = 0; a < 3; a++) {
                p[3 * i + a] = (float)(o[a] + (double)(i - s0) * 0.01 * dir[a] / len + 0.0005 * pnpr_test_normal(&rng));
                d[3 * i + a] = (float)(dir[a] / len);
            }
    }
    const double origin[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        pnpr_lines_options o;
        memset(&o, 0, sizeof o);
        o.threads = threads[k];
        CHECK_STATUS(pnpr_profile_lines_points(p, d, N, origin, &o, &l[k], &s[k]), PNPR_OK);
    }
    printf("random segments, threads 1 / 2 / 7: %zu / %zu / %zu polylines, %zu graph edges, %zu corners\n", l[0].count,
           l[1].count, l[2].count, s[0].graph_edges, s[0].corners);
    CHECK(l[0].count >= 200 && s[0].graph_edges > 4 * 4096);
    for (int k = 1; k < 3; k++) {
        CHECK(l[k].count == l[0].count && s[k].forest_edges == s[0].forest_edges && s[k].corners == s[0].corners);
        if (l[k].count != l[0].count) continue;
        CHECK(!memcmp(l[k].offset, l[0].offset, (l[0].count + 1) * sizeof *l[0].offset));
        CHECK(!memcmp(l[k].xyz, l[0].xyz, 3 * l[0].offset[l[0].count] * sizeof *l[0].xyz));
    }
    for (int k = 0; k < 3; k++) pnpr_lines_free(&l[k]);
    free(p);
    free(d);
}

int main(void)
{
    test_threads_same_lines();
    test_cube();
    test_cylinder();
    test_plane_and_degenerate();
    test_offset_same_lines();
    test_writers();
    return pnpr_test_finish("test_lines");
}
