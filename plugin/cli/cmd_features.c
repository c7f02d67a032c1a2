/* pointnpr features IN -o OUT.ply: normals, feature degree, classification, dithering points. */
#include "cli.h"

#include <pointnpr/features.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage: pointnpr features IN -o OUT.ply [options]\n"
            "  Computes, per point, nx ny nz, feature_degree (0..1), feature_class (0 none,\n"
            "  1 non-directional, 2 directional, 3 dithering point), feature_confidence and\n"
            "  feature_dir_x/y/z, and writes them with every input property, in input order.\n"
            "options:\n"
            "  --k N                neighbourhood size (default 16)\n"
            "  --threshold T        feature-degree threshold in (0,1] (default: automatic)\n"
            "  --weights G,C        weights of the geometry and colour terms (default 0.5,0.5)\n"
            "  --confidence C       min line-fit confidence of directional points (default 0.6)\n"
            "  --dither-scale S     tone multiplier for the dithering density (default 1)\n"
            "  --viewpoint X,Y,Z    orient normals towards this point (world coordinates)\n"
            "  --recompute-normals  recompute normals even when the input has them\n"
            "  --threads N          worker threads (default: all cores)\n"
            "  --ascii              write ascii PLY (default binary little endian)\n"
            "  --quiet              no progress on stderr\n");
    cli_outlier_usage(f);
    cli_columns_usage(f);
}

/* Fewer than 3 usable points: says how many points there are and why the others are left out. */
static void warn_few_points(const char *in, size_t count, const pnpr_features_stats *s)
{
    fprintf(stderr, "pointnpr features: warning: %s has %zu point(s) with usable coordinates (of %zu: %zu with "
                    "NaN/Inf coordinates, %zu beyond float range from the others); at least 3 are needed for "
                    "normals and features, all outputs are 0\n",
            in, s->valid_points, count, count - s->valid_points - s->beyond_float, s->beyond_float);
}

int cli_features(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    pnpr_features_options fo = {0};
    pnpr_write_options wo = {0};
    cli_outliers outliers = {0, 0};
    const char *columns = NULL;
    int quiet = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        int oo = cli_outlier_option(&outliers, "features", argc, argv, &i);
        if (oo == 0) oo = cli_columns_option(&columns, "features", argc, argv, &i);
        if (oo < 0) return 2;
        if (oo > 0) continue;
        double x, xs[3];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { usage(stdout); return 0; }
        else if (!strcmp(a, "--quiet")) quiet = 1;
        else if (!strcmp(a, "--ascii")) wo.encoding = PNPR_PLY_ASCII;
        else if (!strcmp(a, "--recompute-normals")) fo.recompute_normals = 1;
        else if (v && (!strcmp(a, "-o") || !strcmp(a, "--output"))) { out = v; i++; }
        else if (v && !strcmp(a, "--k")) {
            if (!cli_parse_number(v, 1, PNPR_FEATURES_K_MAX, &x) || x != floor(x)) {
                fprintf(stderr, "pointnpr features: --k wants an integer in 1..%d, got '%s'\n", PNPR_FEATURES_K_MAX, v);
                return 2;
            }
            fo.k = (uint32_t)x; i++;
        } else if (v && !strcmp(a, "--threshold")) {
            if (!cli_parse_number(v, 1e-6, 1, &x)) { fprintf(stderr, "pointnpr features: --threshold wants a number in (0,1], got '%s'\n", v); return 2; }
            fo.threshold = (float)x; i++;
        } else if (v && !strcmp(a, "--weights")) {
            if (!cli_parse_list(v, 2, xs) || xs[0] < 0 || xs[1] < 0 || xs[0] + xs[1] <= 0 || xs[0] > 1e6 || xs[1] > 1e6) {
                fprintf(stderr, "pointnpr features: --weights wants G,C (two numbers in [0, 1e6], not both 0; "
                                "only their ratio matters), got '%s'\n", v);
                return 2;
            }
            fo.weight_geometry = (float)xs[0]; fo.weight_color = (float)xs[1]; i++;
        } else if (v && !strcmp(a, "--confidence")) {
            if (!cli_parse_number(v, 1e-6, 1, &x)) { fprintf(stderr, "pointnpr features: --confidence wants a number in (0,1], got '%s'\n", v); return 2; }
            fo.direction_confidence = (float)x; i++;
        } else if (v && !strcmp(a, "--dither-scale")) {
            if (!cli_parse_number(v, 1e-6, 1e6, &x)) { fprintf(stderr, "pointnpr features: --dither-scale wants a positive number, got '%s'\n", v); return 2; }
            fo.dither_scale = (float)x; i++;
        } else if (v && !strcmp(a, "--viewpoint")) {
            if (!cli_parse_list(v, 3, fo.viewpoint)) { fprintf(stderr, "pointnpr features: --viewpoint wants X,Y,Z, got '%s'\n", v); return 2; }
            fo.has_viewpoint = 1; i++;
        } else if (v && !strcmp(a, "--threads")) {
            if (!cli_parse_number(v, 1, PNPR_THREADS_MAX, &x) || x != floor(x)) { fprintf(stderr, "pointnpr features: --threads wants an integer in 1..%d, got '%s'\n", PNPR_THREADS_MAX, v); return 2; }
            fo.threads = (int)x; i++;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "pointnpr features: unknown option or missing value: %s\n", a);
            usage(stderr);
            return 2;
        } else if (!in) in = a;
        else { fprintf(stderr, "pointnpr features: more than one input given ('%s')\n", a); return 2; }
    }
    if (!cli_need_in_out("features", in, out, "OUT.ply")) return 2;
    int out_rc = cli_cloud_output("features", out, in, &wo);
    if (out_rc) return out_rc;

    cli_progress_state ps = {{0}, 0, 0};
    pnpr_progress prog = {quiet ? NULL : cli_progress_stderr, &ps};
    pnpr_read_options ro = {0};
    ro.columns = columns;
    ro.progress = prog;
    fo.progress = prog;
    wo.progress = prog;
    pnpr_cloud cloud = {0};
    pnpr_error err = {0};
    pnpr_status st = pnpr_read_file(in, &ro, &cloud, &err);
    if (st != PNPR_OK) { cli_report_error("features", st, &err); return 1; }
    if (cli_outliers_apply(&outliers, "features", in, &cloud, quiet, NULL)) { pnpr_cloud_free(&cloud); return 1; }

    pnpr_features_stats stats;
    st = pnpr_features_check_options(&fo, &err);
    if (st == PNPR_OK) st = pnpr_compute_features(&cloud, &fo, &stats);
    if (st != PNPR_OK) {
        if (err.message[0]) cli_report_error("features", st, &err);
        else fprintf(stderr, "pointnpr features: %s: %s\n", in, pnpr_status_string(st));
        pnpr_cloud_free(&cloud);
        return 1;
    }
    if (stats.valid_points < 3) warn_few_points(in, cloud.count, &stats);
    if (!quiet) {
        fprintf(stderr, "points %zu (valid %zu), k %u, threshold %.3f%s\n", cloud.count, stats.valid_points,
                stats.k_used, stats.threshold_used, fo.threshold > 0 ? "" : " (automatic)");
        fprintf(stderr, "feature points %zu (directional %zu, non-directional %zu), dithering points %zu\n",
                stats.feature_points, stats.directional_points, stats.feature_points - stats.directional_points,
                stats.dither_points);
        for (int s = 0; s < PNPR_STAGE_COUNT_; s++)
            if (stats.runs[s]) fprintf(stderr, "  %-16s %8.3f s\n", pnpr_stage_name((pnpr_stage)s), stats.seconds[s]);
    }
    char comment[256];
    snprintf(comment, sizeof comment, "pointnpr features k=%u threshold=%.4f", stats.k_used, stats.threshold_used);
    wo.comment = comment;
    st = pnpr_write_file(out, &cloud, &wo, &err);
    pnpr_cloud_free(&cloud);
    if (st != PNPR_OK) { cli_report_error("features", st, &err); return 1; }
    if (!quiet) fprintf(stderr, "wrote %s\n", out);
    return 0;
}
