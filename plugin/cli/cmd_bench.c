/* pointnpr bench accuracy: error against run time of the feature analysis (work-precision).
 *
 * Sweeps the main accuracy knobs on shapes with known answers and measures, for each setting, the
 * run time of pnpr_compute_features and its error:
 *   - normals: a unit sphere (Fibonacci sampling, 100k points), mean and 95th-percentile angle
 *     between each normal and the true one, for k in 6..48 and for subsampled clouds (sampling);
 *   - features: a noisy cube (spacing h = 0.02, Gaussian noise 0.2 h), precision and recall of the
 *     feature points against the points within 1.5 h of an edge, for k in 8..48.
 * Writes DIR/accuracy.csv and two SVG plots (DIR/normals.svg, DIR/features.svg), prints a
 * markdown table. The renderer's point budget and the segmentation levels join this sweep when
 * their quality measures land (see docs/work-precision.md). */
#include "cli.h"

#include <pointnpr/output.h>

#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <pointnpr/segment.h>
#ifdef PNPR_HAVE_RENDER
#include <pointnpr/render.h>
#endif

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Deterministic uniform [0,1) and normal numbers (splitmix64), caller-owned state. */
static double uni(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * (1.0 / 9007199254740992.0);
}
static double gauss(uint64_t *s)
{
    double u = uni(s), v = uni(s);
    return sqrt(-2 * log(u > 1e-300 ? u : 1e-300)) * cos(6.283185307179586 * v);
}

/* Unit sphere: n points on a Fibonacci spiral, of which a random (seeded) `fraction` is kept —
 * a stride would leave the spiral's own lattice lines, not a sparser sampling. */
static pnpr_status make_sphere(pnpr_cloud *c, size_t n, double fraction)
{
    uint64_t seed = 99;
    uint8_t *keep = malloc(n);
    if (!keep) return PNPR_ERR_OUT_OF_MEMORY;
    size_t m = 0;
    for (size_t i = 0; i < n; i++) m += keep[i] = uni(&seed) < fraction;
    pnpr_status st = pnpr_cloud_alloc(c, m);
    const double ga = 3.883222077450933; /* golden angle */
    for (size_t i = 0, j = 0; st == PNPR_OK && i < n; i++) {
        if (!keep[i]) continue;
        double z = 1 - (2.0 * (double)i + 1) / (double)n, r = sqrt(1 - z * z), t = ga * (double)i;
        c->xyz[3 * j] = (float)(r * cos(t));
        c->xyz[3 * j + 1] = (float)(r * sin(t));
        c->xyz[3 * j + 2] = (float)z;
        j++;
    }
    free(keep);
    return st;
}

/* Cube [0,1]^3 on a grid of spacing h with Gaussian noise; r_edge[i] = 1 within 1.5h of an edge. */
static pnpr_status make_cube(pnpr_cloud *c, double h, double noise, uint8_t **r_edge)
{
    long m = (long)floor(1.0 / h + 0.5);
    size_t n = 0, cap = (size_t)(m + 1) * (size_t)(m + 1) * 6;
    float *p = malloc(cap * 3 * sizeof *p);
    uint8_t *edge = malloc(cap);
    if (!p || !edge) { free(p); free(edge); return PNPR_ERR_OUT_OF_MEMORY; }
    uint64_t seed = 17;
    for (long i = 0; i <= m; i++)
        for (long j = 0; j <= m; j++)
            for (long k = 0; k <= m; k++) {
                if (i > 0 && i < m && j > 0 && j < m && k > 0 && k < m) continue;
                double q[3] = {(double)i / (double)m, (double)j / (double)m, (double)k / (double)m};
                int near = 0; /* coordinates within 1.5h of 0 or 1 */
                for (int a = 0; a < 3; a++) near += fmin(q[a], 1 - q[a]) <= 1.5 * h;
                edge[n] = near >= 2;
                for (int a = 0; a < 3; a++) p[3 * n + a] = (float)(q[a] + noise * gauss(&seed));
                n++;
            }
    pnpr_status st = pnpr_cloud_alloc(c, n);
    if (st == PNPR_OK) memcpy(c->xyz, p, n * 3 * sizeof *p);
    free(p);
    if (st != PNPR_OK) { free(edge); return st; }
    *r_edge = edge;
    return PNPR_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y);
}

typedef struct row { const char *study; double knob, seconds, e1, e2; size_t points; } row;

typedef struct plot_args {
    const row *rows;
    size_t n;
    const char *study, *title, *y1, *y2;
    double ymax;
} plot_args;

/* A log-x line plot as SVG: series = rows of one study; y1 (and y2 when named) against time. */
static int print_plot(FILE *f, const void *ctx)
{
    const plot_args *p = ctx;
    const row *rows = p->rows;
    const size_t n = p->n;
    const char *study = p->study, *title = p->title, *y1 = p->y1, *y2 = p->y2;
    const double ymax = p->ymax;
    const double W = 640, H = 400, L = 70, R = 20, T = 40, B = 50;
    double tmin = INFINITY, tmax = 0;
    for (size_t i = 0; i < n; i++)
        if (!strcmp(rows[i].study, study)) { tmin = fmin(tmin, rows[i].seconds); tmax = fmax(tmax, rows[i].seconds); }
    if (!(tmax > tmin)) tmax = tmin * 2 + 1e-3;
    double lx0 = log10(tmin) - 0.05, lx1 = log10(tmax) + 0.05;
#define PX(t) (L + (log10(t) - lx0) / (lx1 - lx0) * (W - L - R))
#define PY(v) (H - B - (v) / ymax * (H - T - B))
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" font-family=\"sans-serif\" font-size=\"12\">\n", W, H);
    fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n<text x=\"%g\" y=\"22\" font-size=\"14\">%s</text>\n", L, title);
    fprintf(f, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"black\"/>\n", L, H - B, W - R, H - B);
    fprintf(f, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"black\"/>\n", L, T, L, H - B);
    fprintf(f, "<text x=\"%g\" y=\"%g\">run time (s, log)</text>\n", (W - L) / 2, H - 12);
    for (int d = (int)floor(lx0 * 2); d <= (int)ceil(lx1 * 2); d++) { /* ticks at 1, 3.16, 10 ... */
        double t = pow(10, d / 2.0);
        if (log10(t) < lx0 || log10(t) > lx1) continue;
        fprintf(f, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%.3g</text>\n", PX(t), H - B + 16, t);
    }
    for (int g = 0; g <= 4; g++)
        fprintf(f, "<text x=\"%g\" y=\"%g\" text-anchor=\"end\">%.3g</text>\n", L - 6, PY(ymax * g / 4) + 4, ymax * g / 4);
    const char *names[2] = {y1, y2}, *colours[2] = {"#c03030", "#3050c0"};
    for (int s = 0; s < 2 && names[s]; s++) {
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\" points=\"", colours[s]);
        for (size_t i = 0; i < n; i++)
            if (!strcmp(rows[i].study, study)) fprintf(f, "%.1f,%.1f ", PX(rows[i].seconds), PY(s ? rows[i].e2 : rows[i].e1));
        fprintf(f, "\"/>\n");
        for (size_t i = 0; i < n; i++)
            if (!strcmp(rows[i].study, study))
                fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" fill=\"%s\" font-size=\"10\">%g</text>\n", PX(rows[i].seconds) + 3,
                        PY(s ? rows[i].e2 : rows[i].e1) - 4, colours[s], rows[i].knob);
        fprintf(f, "<text x=\"%g\" y=\"%g\" fill=\"%s\">%s</text>\n", W - R - 170, 14.0 + 14 * s, colours[s], names[s]);
    }
    fprintf(f, "</svg>\n");
#undef PX
#undef PY
    return ferror(f) != 0;
}

static void plot(const char *path, const row *rows, size_t n, const char *study, const char *title,
                 const char *y1, const char *y2, double ymax)
{
    plot_args p = {rows, n, study, title, y1, y2, ymax};
    pnpr_error err = {0};
    if (pnpr_output_write(path, print_plot, &p, &err) != PNPR_OK) fprintf(stderr, "pointnpr bench: %s\n", err.message);
}

typedef struct csv_args {
    const row *rows;
    size_t n;
} csv_args;

static int print_csv(FILE *f, const void *ctx)
{
    const csv_args *c = ctx;
    fprintf(f, "study,knob,points,seconds,error1,error2\n");
    for (size_t i = 0; i < c->n; i++)
        fprintf(f, "%s,%g,%zu,%.6f,%.6g,%.6g\n", c->rows[i].study, c->rows[i].knob, c->rows[i].points,
                c->rows[i].seconds, c->rows[i].e1, c->rows[i].e2);
    return ferror(f) != 0;
}

/* Segmentation levels: a plane of 4 x 4 coloured patches (16 true segments, colour noise), JSEG,
 * the Chi & Lee region hierarchy, cuts at 64 .. 2 segments: ARI against the truth (error 1) and
 * the segment count (error 2) against the time of JSEG + hierarchy + cut. */
static size_t segment_study(row *rows, size_t room, int quick)
{
    const size_t side = quick ? 200 : 400, n = side * side;
    pnpr_cloud c = {0};
    uint32_t *truth = malloc(n * sizeof *truth), *labels = malloc(n * sizeof *labels), *cut = malloc(n * sizeof *cut);
    uint32_t *knn = NULL;
    pnpr_segment_merge *merges = NULL;
    pnpr_kdtree *tree = NULL;
    size_t nr = 0;
    if (!truth || !labels || !cut || pnpr_cloud_alloc(&c, n) != PNPR_OK || pnpr_cloud_alloc_rgb(&c) != PNPR_OK) goto done;
    uint64_t seed = 5;
    for (size_t j = 0; j < side; j++)
        for (size_t i = 0; i < side; i++) {
            size_t q = j * side + i, patch = (j * 4 / side) * 4 + i * 4 / side;
            c.xyz[3 * q] = 0.01f * (float)i;
            c.xyz[3 * q + 1] = 0.01f * (float)j;
            c.xyz[3 * q + 2] = 0;
            truth[q] = (uint32_t)patch;
            for (int a = 0; a < 3; a++) { /* 16 distinct patch colours (r, g on a 4 x 4 grid), plus noise */
                double base = a == 0 ? 35 + 60 * (double)(patch % 4) : (a == 1 ? 35 + 60 * (double)(patch / 4) : 80 + 30 * (double)((patch * 3) % 4));
                double v = base + 6 * gauss(&seed);
                c.rgb[3 * q + a] = (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
            }
        }
    pnpr_segment_info info;
    double t0 = now();
    if (pnpr_segment_jseg(c.xyz, c.rgb, n, NULL, labels, &info) != PNPR_OK) goto done;
    const size_t k = 16;
    knn = malloc(n * k * sizeof *knn);
    merges = malloc((info.segment_count + 1) * sizeof *merges);
    if (!knn || !merges || pnpr_kdtree_build(c.xyz, n, 0, &tree) != PNPR_OK) goto done;
    pnpr_knn_options ko = {0, {0}, 0};
    if (pnpr_knn_self(tree, n, k, &ko, knn, NULL) != PNPR_OK) goto done;
    pnpr_region_graph g = {knn, k, k};
    uint32_t nm = 0;
    if (pnpr_segment_hierarchy(c.rgb, n, &g, labels, info.segment_count, NULL, merges, &nm) != PNPR_OK) goto done;
    double base_time = now() - t0;
    const uint32_t targets[] = {64, 32, 16, 8, 4, 2};
    for (int t = 0; t < 6 && nr < room; t++) {
        double t1 = now();
        uint32_t S = 0;
        if (pnpr_segment_hierarchy_cut(labels, n, info.segment_count, merges, nm, targets[t], 0, cut, &S) != PNPR_OK) goto done;
        double sec = base_time + (now() - t1);
        pnpr_segment_score sc;
        if (pnpr_segment_score_labels(truth, cut, n, &sc) != PNPR_OK) goto done;
        row r = {"segment-levels", (double)targets[t], sec, sc.ari, (double)S, n};
        rows[nr++] = r;
    }
done:
    pnpr_kdtree_free(tree);
    free(knn); free(merges); free(truth); free(labels); free(cut);
    pnpr_cloud_free(&c);
    return nr;
}

#ifdef PNPR_HAVE_RENDER
/* Luma of an RGBA8 pixel. */
static double luma(const uint8_t *p)
{
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
}

/* PSNR (dB, luma) and mean SSIM over 8x8 windows (luma, the usual constants for 8-bit data). */
static void image_error(const uint8_t *a, const uint8_t *b, int w, int h, double *r_psnr, double *r_ssim)
{
    double mse = 0;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
        double d = luma(a + 4 * i) - luma(b + 4 * i);
        mse += d * d;
    }
    mse /= (double)w * (double)h;
    *r_psnr = mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : 99.0;
    const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    double sum = 0;
    int n = 0;
    for (int y = 0; y + 8 <= h; y += 8)
        for (int x = 0; x + 8 <= w; x += 8) {
            double ma = 0, mb = 0, va = 0, vb = 0, cov = 0;
            for (int dy = 0; dy < 8; dy++)
                for (int dx = 0; dx < 8; dx++) {
                    size_t q = 4 * ((size_t)(y + dy) * (size_t)w + (size_t)(x + dx));
                    ma += luma(a + q); mb += luma(b + q);
                }
            ma /= 64; mb /= 64;
            for (int dy = 0; dy < 8; dy++)
                for (int dx = 0; dx < 8; dx++) {
                    size_t q = 4 * ((size_t)(y + dy) * (size_t)w + (size_t)(x + dx));
                    double ea = luma(a + q) - ma, eb = luma(b + q) - mb;
                    va += ea * ea; vb += eb * eb; cov += ea * eb;
                }
            va /= 63; vb /= 63; cov /= 63;
            sum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            n++;
        }
    *r_ssim = n ? sum / n : 1;
}

/* Continuous-resolution-queue budget: image error of a budgeted frame against the full frame, and
 * the frame time, for the points and sketchy styles. Adds rows "render-<style>"; returns the
 * number added (0 when no GL context can be had: the study is skipped with a message). */
static size_t render_study(row *rows, size_t room, int quick)
{
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) {
        fprintf(stderr, "bench accuracy: render budget study skipped: %s\n", err.message);
        return 0;
    }
    pnpr_renderer *r = NULL;
    size_t nr = 0;
    pnpr_cloud c = {0};
    const int W = 512, H = 512;
    uint8_t *full = malloc((size_t)W * H * 4), *img = malloc((size_t)W * H * 4);
    if (!full || !img || pnpr_renderer_create(NULL, &r, &err) != PNPR_OK || make_sphere(&c, quick ? 50000 : 200000, 1.0) != PNPR_OK ||
        pnpr_cloud_alloc_rgb(&c) != PNPR_OK)
        goto done;
    for (size_t i = 0; i < c.count; i++) /* colour bands, so that the image has detail */
        for (int a = 0; a < 3; a++) c.rgb[3 * i + a] = (uint8_t)(127.5 + 127.5 * sin(9.0 * c.xyz[3 * i + a]));
    pnpr_features_options fo = {0};
    fo.want = PNPR_WANT_DITHER;
    if (pnpr_compute_features(&c, &fo, NULL) != PNPR_OK || pnpr_renderer_set_cloud(r, &c, NULL, &err) != PNPR_OK) goto done;
    const double fractions[] = {0.03, 0.1, 0.3, 1.0};
    for (int style = 0; style < 2; style++) {
        pnpr_draw_options o;
        memset(&o, 0, sizeof o);
        o.style = style ? PNPR_STYLE_SKETCHY : PNPR_STYLE_POINTS;
        for (int a = 0; a < 4; a++) o.background[a] = 1;
        pnpr_target t = {0, 0, 0, W, H, 1, 0};
        if (pnpr_renderer_draw(r, NULL, &o, &t, NULL, &err) != PNPR_OK || pnpr_renderer_read_frame(r, full, 0) != PNPR_OK) goto done;
        for (int f = 0; f < 4 && nr < room; f++) {
            o.budget = (size_t)(fractions[f] * (double)c.count);
            double t0 = now(), best = INFINITY;
            for (int rep = 0; rep < 3; rep++) { /* frame time: best of 3 (draw + read back) */
                t0 = now();
                if (pnpr_renderer_draw(r, NULL, &o, &t, NULL, &err) != PNPR_OK || pnpr_renderer_read_frame(r, img, 0) != PNPR_OK) goto done;
                if (now() - t0 < best) best = now() - t0;
            }
            double psnr, ssim;
            image_error(full, img, W, H, &psnr, &ssim);
            row rw = {style ? "render-sketchy" : "render-points", fractions[f], best, ssim, psnr, o.budget};
            rows[nr++] = rw;
        }
    }
done:
    if (err.message[0] && nr == 0) fprintf(stderr, "bench accuracy: render budget study: %s\n", err.message);
    pnpr_cloud_free(&c);
    free(full);
    free(img);
    pnpr_renderer_destroy(r);
    pnpr_gl_context_destroy(ctx);
    return nr;
}
#endif

static int bench_accuracy(const char *dir, int quick)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) { fprintf(stderr, "pointnpr bench: cannot create %s: %s\n", dir, strerror(errno)); return 1; }
    row rows[64];
    size_t nr = 0;
    const size_t sphere_n = quick ? 20000 : 100000;
    const int ks[] = {6, 8, 12, 16, 24, 32, 48};
    /* normals against k, and against sampling at k = 16 */
    for (int study = 0; study < 2; study++) {
        int count = study ? 4 : 7;
        for (int t = 0; t < count; t++) {
            const double fractions[] = {0.125, 0.25, 0.5, 1};
            double fraction = study ? fractions[t] : 1;
            pnpr_cloud c = {0};
            if (make_sphere(&c, sphere_n, fraction) != PNPR_OK) return 1;
            pnpr_features_options o = {0};
            o.k = study ? 16 : (uint32_t)ks[t];
            double t0 = now();
            pnpr_status st = pnpr_compute_features(&c, &o, NULL);
            double sec = now() - t0;
            if (st != PNPR_OK) { pnpr_cloud_free(&c); return 1; }
            double *err = malloc(c.count * sizeof *err), sum = 0;
            if (!err) return 1;
            for (size_t i = 0; i < c.count; i++) {
                const float *p = c.xyz + 3 * i, *nn = c.normal + 3 * i;
                double cr[3] = {(double)p[1] * nn[2] - (double)p[2] * nn[1], (double)p[2] * nn[0] - (double)p[0] * nn[2],
                                (double)p[0] * nn[1] - (double)p[1] * nn[0]};
                double d = fabs((double)p[0] * nn[0] + (double)p[1] * nn[1] + (double)p[2] * nn[2]);
                err[i] = 57.29577951308232 * atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]), d);
                sum += err[i];
            }
            qsort(err, c.count, sizeof *err, cmp_double);
            row r = {study ? "normals-sampling" : "normals-k", study ? fraction : (double)o.k, sec,
                     sum / (double)c.count, err[(size_t)(0.95 * (double)(c.count - 1))], c.count};
            rows[nr++] = r;
            free(err);
            pnpr_cloud_free(&c);
            fprintf(stderr, "\r%-20s %zu/17", "bench accuracy", nr);
        }
    }
    /* features against k on the noisy cube */
    const int fk[] = {8, 12, 16, 24, 32, 48};
    for (int t = 0; t < 6; t++) {
        pnpr_cloud c = {0};
        uint8_t *edge = NULL;
        if (make_cube(&c, 0.02, 0.2 * 0.02, &edge) != PNPR_OK) return 1;
        pnpr_features_options o = {0};
        o.k = (uint32_t)fk[t];
        double t0 = now();
        pnpr_status st = pnpr_compute_features(&c, &o, NULL);
        double sec = now() - t0;
        if (st != PNPR_OK) { free(edge); pnpr_cloud_free(&c); return 1; }
        const uint8_t *cls = pnpr_cloud_find_property(&c, PNPR_PROP_FEATURE_CLASS)->data;
        size_t tp = 0, fp = 0, pos = 0;
        for (size_t i = 0; i < c.count; i++) {
            int flagged = cls[i] == PNPR_CLASS_DIRECTIONAL || cls[i] == PNPR_CLASS_NONDIRECTIONAL;
            pos += edge[i];
            tp += flagged && edge[i];
            fp += flagged && !edge[i];
        }
        row r = {"features-k", (double)o.k, sec, tp + fp ? (double)tp / (double)(tp + fp) : 0, pos ? (double)tp / (double)pos : 0, c.count};
        rows[nr++] = r;
        free(edge);
        pnpr_cloud_free(&c);
        fprintf(stderr, "\r%-20s %zu/17", "bench accuracy", nr);
    }
    nr += segment_study(rows + nr, sizeof rows / sizeof *rows - nr, quick);
#ifdef PNPR_HAVE_RENDER
    nr += render_study(rows + nr, sizeof rows / sizeof *rows - nr, quick);
#endif
    fprintf(stderr, "\n");
    char path[4096];
    snprintf(path, sizeof path, "%s/accuracy.csv", dir);
    csv_args csv = {rows, nr};
    pnpr_error err = {0};
    if (pnpr_output_write(path, print_csv, &csv, &err) != PNPR_OK) { fprintf(stderr, "pointnpr bench: %s\n", err.message); return 1; }
    snprintf(path, sizeof path, "%s/normals-k.svg", dir);
    plot(path, rows, nr, "normals-k", "Sphere normals: error vs time, labels = k", "mean error (deg)", "95th percentile (deg)", 1.0);
    snprintf(path, sizeof path, "%s/normals-sampling.svg", dir);
    plot(path, rows, nr, "normals-sampling", "Sphere normals (k=16): error vs time, labels = fraction of points", "mean error (deg)", "95th percentile (deg)", 2.0);
    snprintf(path, sizeof path, "%s/features-k.svg", dir);
    plot(path, rows, nr, "features-k", "Noisy cube features: quality vs time, labels = k", "precision", "recall", 1.0);
    for (int st = 0; st < 2; st++) {
        const char *name = st ? "render-sketchy" : "render-points";
        snprintf(path, sizeof path, "%s/%s.svg", dir, name);
        plot(path, rows, nr, name, st ? "Sketchy frame: SSIM vs frame time, labels = budget fraction"
                                       : "Points frame: SSIM vs frame time, labels = budget fraction",
             "SSIM vs the full frame", NULL, 1.0);
    }
    printf("| study | knob | points | seconds | error 1 | error 2 |\n|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < nr; i++)
        printf("| %s | %g | %zu | %.3f | %.4g | %.4g |\n", rows[i].study, rows[i].knob, rows[i].points, rows[i].seconds, rows[i].e1, rows[i].e2);
    fprintf(stderr, "wrote %s/accuracy.csv and its plots (*.svg)\n", dir);
    return 0;
}

int cli_bench(int argc, char **argv)
{
    const char *what = argc > 1 ? argv[1] : NULL, *dir = "bench-accuracy";
    if (what && !strcmp(what, "quality")) return cli_bench_quality(argc, argv); /* cmd_bench_quality.c */
    int quick = 0;
    for (int i = 2; i < argc; i++) {
        if (!strcmp(argv[i], "--quick")) quick = 1;
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) dir = argv[++i];
        else { fprintf(stderr, "pointnpr bench: unknown option %s\n", argv[i]); return 2; }
    }
    if (!what || strcmp(what, "accuracy")) {
        fprintf(stderr, "usage: pointnpr bench accuracy [--out DIR] [--quick]\n"
                        "  error against run time of the feature analysis (docs/work-precision.md)\n"
                        "       pointnpr bench quality [--full | --sparse] [-o DIR] [--check]\n"
                        "  picture-quality figures of every style on a generated scene (docs/quality.md)\n");
        return what && (!strcmp(what, "--help") || !strcmp(what, "-h")) ? 0 : 2;
    }
    return bench_accuracy(dir, quick);
}
