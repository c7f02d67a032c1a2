/* Scaling of the profile-line stage: N directional points on random straight features (segments
 * of 100 points, spacing 0.01, 5% position noise, in a cube growing with N so the density stays
 * the same), N = 10k .. 1M. Prints a markdown table: graph, spanning forest and fit times.
 *   bench_lines [MAX_N [THREADS [shuffle]]]   (THREADS 0 or none: all cores)
 * The points come segment after segment, as a scan's file order keeps neighbours near each other;
 * `shuffle` puts them in random order instead (a file without spatial order). */
#include "../tests/testutil.h"
#include <pointnpr/lines.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    size_t max_n = argc > 1 ? (size_t)atol(argv[1]) : 1000000;
    pnpr_lines_options lo = {0};
    lo.threads = argc > 2 ? atoi(argv[2]) : 0; /* 0: all cores */
    const int shuffle = argc > 3 && !strcmp(argv[3], "shuffle");
    const size_t sizes[] = {10000, 30000, 100000, 300000, 1000000};
    printf("| directional points | graph edges | forest edges | polylines | graph s | spanning forest s | fit s | total s |\n");
    printf("|---|---|---|---|---|---|---|---|\n");
    for (size_t si = 0; si < sizeof sizes / sizeof *sizes && sizes[si] <= max_n; si++) {
        size_t n = sizes[si];
        float *p = malloc(n * 3 * sizeof *p), *d = malloc(n * 3 * sizeof *d);
        if (!p || !d) return 1;
        pnpr_test_rng rng = {99};
        double side = 0.5 * cbrt((double)n); /* same feature density at every N */
        const double h = 0.01;
        for (size_t s = 0; s < n; s += 100) {
            double o[3], dir[3], l = 0;
            for (int a = 0; a < 3; a++) { o[a] = side * pnpr_test_uniform(&rng); dir[a] = pnpr_test_normal(&rng); l += dir[a] * dir[a]; }
            l = sqrt(l);
            for (int a = 0; a < 3; a++) dir[a] /= l;
            for (size_t i = s; i < s + 100 && i < n; i++)
                for (int a = 0; a < 3; a++) {
                    p[3 * i + a] = (float)(o[a] + (double)(i - s) * h * dir[a] + 0.05 * h * pnpr_test_normal(&rng));
                    d[3 * i + a] = (float)dir[a];
                }
        }
        for (size_t i = n - 1; shuffle && i > 0; i--) { /* Fisher-Yates */
            size_t k = (size_t)(pnpr_test_uniform(&rng) * (double)(i + 1));
            k = k > i ? i : k;
            for (int a = 0; a < 3; a++) {
                float t = p[3 * i + a]; p[3 * i + a] = p[3 * k + a]; p[3 * k + a] = t;
                t = d[3 * i + a]; d[3 * i + a] = d[3 * k + a]; d[3 * k + a] = t;
            }
        }
        const double origin[3] = {0, 0, 0};
        pnpr_polylines lines;
        pnpr_lines_stats st;
        double t0 = pnpr_test_seconds();
        pnpr_status r = pnpr_profile_lines_points(p, d, n, origin, &lo, &lines, &st);
        double t = pnpr_test_seconds() - t0;
        if (r != PNPR_OK) { fprintf(stderr, "bench_lines: %s\n", pnpr_status_string(r)); return 1; }
        printf("| %zu | %zu | %zu | %zu | %.3f | %.3f | %.3f | %.3f |\n", n, st.graph_edges, st.forest_edges, st.chains,
               st.seconds_graph, st.seconds_mst, st.seconds_fit, t);
        fflush(stdout);
        pnpr_lines_free(&lines);
        free(p);
        free(d);
    }
    return 0;
}
