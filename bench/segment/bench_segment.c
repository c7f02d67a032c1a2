/* Segmentation benchmark: our JSEG and rgbgrow on generated scenes of touching coloured
 * primitives with known labels (ARI against the truth, wall time). Writes each scene as
 * OUTDIR/scene_<name>.bin (uint64 n; n x {float x,y,z; uint8 r,g,b,pad; uint32 truth}) for the
 * PCL peer (segment_pcl). Usage: bench_segment OUTDIR [spacing] */
#include "../../tests/testutil.h"
#include <pointnpr/segment.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct scene { size_t n, cap; float *xyz; uint8_t *rgb; uint32_t *truth; } scene;

static double gauss(uint64_t *s)
{
    double u[2];
    for (int i = 0; i < 2; i++) {
        *s ^= *s << 13; *s ^= *s >> 7; *s ^= *s << 17;
        u[i] = ((double)(*s >> 11) + 0.5) / 9007199254740992.0;
    }
    return sqrt(-2 * log(u[0])) * cos(6.283185307179586 * u[1]);
}

static void add(scene *s, double x, double y, double z, const int c[3], uint32_t obj, double ps, double cs, uint64_t *rng)
{
    if (s->n == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 65536;
        s->xyz = realloc(s->xyz, 3 * s->cap * sizeof *s->xyz);
        s->rgb = realloc(s->rgb, 3 * s->cap);
        s->truth = realloc(s->truth, s->cap * sizeof *s->truth);
        if (!s->xyz || !s->rgb || !s->truth) abort();
    }
    double p[3] = {x, y, z};
    for (int a = 0; a < 3; a++) s->xyz[3 * s->n + a] = (float)(p[a] + ps * gauss(rng));
    for (int a = 0; a < 3; a++) {
        double v = c[a] + cs * gauss(rng);
        s->rgb[3 * s->n + a] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v + 0.5);
    }
    s->truth[s->n++] = obj;
}

/* The scene of tests/test_segment.c: plane, cube, sphere, cylinder (touching). */
static void make_scene(scene *s, double h, double ps, double cs, uint64_t seed)
{
    static const int grey[3] = {140, 140, 140}, red[3] = {200, 40, 40}, blue[3] = {40, 60, 200}, green[3] = {40, 170, 60};
    const double PI = 3.14159265358979323846;
    uint64_t rng = seed;
    memset(s, 0, sizeof *s);
    for (double x = -1; x <= 1 + 1e-9; x += h)
        for (double y = -1; y <= 1 + 1e-9; y += h)
            if (!(x > -0.5 && x < 0.1 && y > -0.3 && y < 0.3)) add(s, x, y, 0, grey, 0, ps, cs, &rng);
    int m = (int)(0.6 / h + 0.5);
    for (int i = 0; i <= m; i++)
        for (int j = 0; j <= m; j++) {
            double u = -0.5 + 0.6 * i / m, v = 0.6 * j / m, w = -0.3 + 0.6 * i / m;
            if (j > 0) {
                add(s, u, -0.3, v, red, 1, ps, cs, &rng); add(s, u, 0.3, v, red, 1, ps, cs, &rng);
                if (i > 0 && i < m) { add(s, -0.5, w, v, red, 1, ps, cs, &rng); add(s, 0.1, w, v, red, 1, ps, cs, &rng); }
            }
            if (i > 0 && i < m && j > 0 && j < m) add(s, u, -0.3 + 0.6 * j / m, 0.6, red, 1, ps, cs, &rng);
        }
    double r = 0.35;
    size_t ns = (size_t)(4 * PI * r * r / (h * h));
    for (size_t i = 0; i < ns; i++) {
        double z = 1 - 2 * (i + 0.5) / ns, rr = sqrt(1 - z * z), phi = i * PI * (3 - sqrt(5.0));
        add(s, 0.45 + h + r * rr * cos(phi), r * rr * sin(phi), 0.35 + r * z, blue, 2, ps, cs, &rng);
    }
    double cr = 0.2;
    int nr = (int)(2 * PI * cr / h), nz = (int)(0.8 / h);
    for (int a = 0; a < nr; a++)
        for (int b = 1; b <= nz; b++) {
            double t = 2 * PI * a / nr;
            add(s, -0.2 + cr * cos(t), 0.5 + h + cr * sin(t), 0.8 * b / nz, green, 3, ps, cs, &rng);
        }
    for (double x = -cr; x <= cr; x += h)
        for (double y = -cr; y <= cr; y += h)
            if (x * x + y * y < (cr - h / 2) * (cr - h / 2)) add(s, -0.2 + x, 0.5 + h + y, 0.8, green, 3, ps, cs, &rng);
}

static void write_scene(const scene *s, const char *path)
{
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); return; }
    uint64_t n = s->n;
    fwrite(&n, sizeof n, 1, f);
    for (size_t i = 0; i < s->n; i++) {
        uint8_t c[4] = {s->rgb[3 * i], s->rgb[3 * i + 1], s->rgb[3 * i + 2], 0};
        fwrite(s->xyz + 3 * i, sizeof(float), 3, f);
        fwrite(c, 1, 4, f);
        fwrite(s->truth + i, sizeof(uint32_t), 1, f);
    }
    fclose(f);
}

int main(int argc, char **argv)
{
    const char *outdir = argc > 1 ? argv[1] : ".";
    double h = argc > 2 ? atof(argv[2]) : 0.005;
    static const struct { const char *name; double ps, cs; } kinds[2] = {{"clean", 0.001, 4}, {"noisy", 0.004, 20}};
    printf("%-6s %-8s %9s %8s %9s %5s %5s %9s\n", "scene", "method", "points", "ARI", "segments", "over", "under", "seconds");
    for (int q = 0; q < 2; q++) {
        scene s;
        make_scene(&s, h, kinds[q].ps * h / 0.02, kinds[q].cs, 11 + q);
        char path[1024];
        snprintf(path, sizeof path, "%s/scene_%s.bin", outdir, kinds[q].name);
        write_scene(&s, path);
        uint32_t *labels = malloc(s.n * sizeof *labels);
        for (int m = 0; m < 2; m++) {
            pnpr_segment_info info;
            double best = INFINITY;
            pnpr_status st = PNPR_OK;
            for (int rep = 0; rep < 3 && st == PNPR_OK; rep++) {
                double t0 = pnpr_test_seconds();
                st = m == 0 ? pnpr_segment_jseg(s.xyz, s.rgb, s.n, NULL, labels, &info)
                            : pnpr_segment_rgbgrow(s.xyz, s.rgb, s.n, NULL, labels, &info);
                double t = pnpr_test_seconds() - t0;
                if (t < best) best = t;
            }
            pnpr_segment_score sc = {0};
            if (st == PNPR_OK) st = pnpr_segment_score_labels(s.truth, labels, s.n, &sc);
            if (st != PNPR_OK) { fprintf(stderr, "failed: %s\n", pnpr_status_string(st)); return 1; }
            printf("%-6s %-8s %9zu %8.4f %9u %5u %5u %9.3f\n", kinds[q].name, m == 0 ? "jseg" : "rgbgrow", s.n, sc.ari,
                   sc.result_segments, sc.over_segmented, sc.under_segmented, best);
        }
        free(labels); free(s.xyz); free(s.rgb); free(s.truth);
    }
    return 0;
}
