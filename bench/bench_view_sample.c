/* The cost a point of the sample by the views of a camera path (docs/tiles.md, "A sample by a
 * path's frames"): N points on a road 2 km x 40 m, the views of 1, 8, 64 and 251 frames of a
 * camera flown 600 m along it at 2 m, looking ahead (251 frames: 64 views, widened). Prints a markdown table: nanoseconds a point to add
 * it to the histograms (the first pass over a file) and to find its share (the second), and the
 * views that see a point on average.
 *   bench_view_sample [N]   (default 4000000) */
#include "../tests/testutil.h"
#include <pointnpr/crq.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    size_t n = argc > 1 ? (size_t)atol(argv[1]) : 4000000;
    double *p = malloc(3 * n * sizeof *p);
    static pnpr_view_sample v;
    static pnpr_view_depths each[PNPR_VIEW_SAMPLE_VIEWS];
    if (!p || n == 0) return 1;
    uint64_t s = 1;
    for (size_t i = 0; i < 3 * n; i += 3) { /* a 64-bit LCG (Knuth's MMIX constants) */
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        p[i] = (double)(s >> 11) / 9007199254740992.0 * 2000.0;
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        p[i + 1] = (double)(s >> 11) / 9007199254740992.0 * 40.0 - 20.0;
        p[i + 2] = 0;
    }
    printf("| frames | views | add ns/point | share ns/point | views seeing a point |\n"
           "|---:|---:|---:|---:|---:|\n");
    enum { MOST = 251 }; /* 10 s at 25 frames/s: more frames than views, which are widened */
    static double eyes[3 * MOST], targets[3 * MOST], fovs[MOST];
    const int counts[4] = {1, 8, PNPR_VIEW_SAMPLE_VIEWS, MOST};
    for (int c = 0; c < 4; c++) {
        int m = counts[c];
        for (int k = 0; k < m; k++) {
            double t = m > 1 ? 600.0 * k / (m - 1) : 0;
            eyes[3 * k] = 2 + t, eyes[3 * k + 1] = 0, eyes[3 * k + 2] = 2;
            targets[3 * k] = 60 + t, targets[3 * k + 1] = 0, targets[3 * k + 2] = 1;
            fovs[k] = 45;
        }
        if (pnpr_view_sample_init_frames(&v, eyes, targets, fovs, (size_t)m, 400, 225) != PNPR_OK) return 1;
        for (int k = 0; k < PNPR_VIEW_SAMPLE_VIEWS; k++) each[k] = (pnpr_view_depths){0};
        v.each = v.views > 1 ? each : NULL;
        double t0 = pnpr_test_seconds();
        for (size_t i = 0; i < n; i++) pnpr_view_sample_add(&v, p + 3 * i);
        double t1 = pnpr_test_seconds();
        pnpr_view_sample_solve(&v, 0.25 * (double)n, 180000);
        double kept = 0, t2 = pnpr_test_seconds();
        for (size_t i = 0; i < n; i++) kept += pnpr_view_sample_share(&v, p + 3 * i);
        double t3 = pnpr_test_seconds(), seen = 0;
        for (int k = 0; k < v.views && v.views > 1; k++) seen += (double)each[k].visible;
        printf("| %d | %d | %.0f | %.0f | %.1f |\n", m, v.views, 1e9 * (t1 - t0) / (double)n,
               1e9 * (t3 - t2) / (double)n, v.views > 1 ? seen / (double)n : (double)v.least.visible / (double)n);
        if (!(kept >= 0)) return 1;
    }
    free(p);
    return 0;
}
