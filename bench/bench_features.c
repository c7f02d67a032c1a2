/* Benchmark of the feature pipeline: a generated scan-like scene of N points (ground plane,
 * boxes, spheres, a cylinder; colours with texture and noise), per-stage times and peak memory.
 *   bench_features --points N [--k K] [--write cloud.ply [--write-only]] [--threads T]
 * Prints one markdown table row per stage and a summary; see bench/run.sh. */
#include "../tests/testutil.h"
#include <pointnpr/features.h>
#include <pointnpr/io.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

static long peak_rss_kb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

/* A point on one of the scene's surfaces, chosen by area. */
static void scene_point(pnpr_test_rng *rng, double p[3], uint8_t c[3])
{
    double u = pnpr_test_uniform(rng), a = pnpr_test_uniform(rng), b = pnpr_test_uniform(rng);
    double shade;
    if (u < 0.4) { /* ground 20 x 20 with a checker texture */
        p[0] = 20 * a - 10; p[1] = 20 * b - 10; p[2] = 0;
        shade = ((int)floor(p[0]) + (int)floor(p[1])) & 1 ? 0.8 : 0.5;
        c[0] = (uint8_t)(120 * shade); c[1] = (uint8_t)(160 * shade); c[2] = (uint8_t)(90 * shade);
    } else if (u < 0.7) { /* a box 4 x 3 x 2.5 on the ground */
        int face = (int)(pnpr_test_uniform(rng) * 5);
        double dims[3] = {4, 3, 2.5}, q[3];
        int ax = face % 3 == 2 ? 2 : face % 3; /* faces: x-, y-, top, x+, y+ */
        int s1 = (ax + 1) % 3, s2 = (ax + 2) % 3;
        q[ax] = (face == 2 || face >= 3) ? dims[ax] : 0;
        q[s1] = a * dims[s1]; q[s2] = b * dims[s2];
        p[0] = q[0] - 6; p[1] = q[1] - 2; p[2] = q[2];
        shade = 0.6 + 0.3 * ax / 2.0;
        c[0] = (uint8_t)(200 * shade); c[1] = (uint8_t)(80 * shade); c[2] = (uint8_t)(60 * shade);
    } else if (u < 0.85) { /* a sphere r = 1.5 */
        double z = 2 * a - 1, t = 6.283185307179586 * b, r = sqrt(1 - z * z);
        p[0] = 4 + 1.5 * r * cos(t); p[1] = 3 + 1.5 * r * sin(t); p[2] = 1.5 + 1.5 * z;
        c[0] = 60; c[1] = 90; c[2] = (uint8_t)(150 + 80 * z);
    } else { /* a cylinder r = 0.8, h = 4 */
        double t = 6.283185307179586 * a;
        p[0] = 3 + 0.8 * cos(t); p[1] = -5 + 0.8 * sin(t); p[2] = 4 * b;
        c[0] = c[1] = c[2] = (uint8_t)(100 + 100 * (b > 0.5));
    }
    for (int k = 0; k < 3; k++) p[k] += 0.002 * pnpr_test_normal(rng); /* 2 mm scan noise */
}

int main(int argc, char **argv)
{
    size_t n = 1000000;
    uint32_t k = 16;
    int threads = 0;
    const char *write = NULL;
    int write_only = 0; /* --write-only: generate the scene and write it, nothing else */
    for (int i = 1; i < argc; i++) {
        const char *v = i + 1 < argc ? argv[i + 1] : "0";
        if (!strcmp(argv[i], "--write-only")) write_only = 1;
        else if (!strcmp(argv[i], "--points")) n = (size_t)atol(v), i++;
        else if (!strcmp(argv[i], "--k")) k = (uint32_t)atoi(v), i++;
        else if (!strcmp(argv[i], "--threads")) threads = atoi(v), i++;
        else if (!strcmp(argv[i], "--write")) write = v, i++;
    }
    pnpr_cloud c = {0};
    if (pnpr_cloud_alloc(&c, n) != PNPR_OK || pnpr_cloud_alloc_rgb(&c) != PNPR_OK) return 1;
    pnpr_test_rng rng = {12345};
    for (size_t i = 0; i < n; i++) {
        double p[3];
        scene_point(&rng, p, c.rgb + 3 * i);
        for (int a = 0; a < 3; a++) c.xyz[3 * i + a] = (float)p[a];
    }
    c.src_coord_type = PNPR_TYPE_FLOAT32;
    if (write) {
        pnpr_error err = {0};
        if (pnpr_write_file(write, &c, NULL, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return 1; }
    }
    if (write_only) { pnpr_cloud_free(&c); return 0; }
    long rss0 = peak_rss_kb();
    pnpr_features_options o = {0};
    o.k = k;
    o.threads = threads;
    pnpr_features_stats s;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    pnpr_status st = pnpr_compute_features(&c, &o, &s);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double wall = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    long rss1 = peak_rss_kb();
    if (st != PNPR_OK) { fprintf(stderr, "features: %s\n", pnpr_status_string(st)); return 1; }
    double total = 0;
    printf("| stage | seconds |\n|---|---|\n");
    for (int i = 0; i < PNPR_STAGE_COUNT_; i++) {
        printf("| %s | %.3f |\n", pnpr_stage_name((pnpr_stage)i), s.seconds[i]);
        total += s.seconds[i];
    }
    printf("| sum of stages | %.3f |\n", total);
    printf("| **pnpr_compute_features, wall** (stages + reordering) | **%.3f** |\n\n", wall);
    printf("points %zu, k %u, threads %d, feature points %zu (directional %zu), dithering points %zu\n",
           n, s.k_used, threads ? threads : pnpr_default_threads(), s.feature_points, s.directional_points, s.dither_points);
    printf("peak RSS: before features %.1f MB, after %.1f MB; cloud + pipeline peak = %.1f bytes/point "
           "(the cloud itself: xyz 12 + rgb 3 + normals 12 + outputs 21 = 48 bytes/point)\n",
           rss0 / 1024.0, rss1 / 1024.0, rss1 * 1024.0 / (double)n);
    printf("BENCH_TOTAL_SECONDS %.3f\nBENCH_BYTES_PER_POINT %.1f\n", wall, rss1 * 1024.0 / (double)n);
    pnpr_cloud_free(&c);
    return 0;
}
