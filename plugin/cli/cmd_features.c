/* pointnpr features IN -o OUT.ply: normals, feature degree, classification, dithering points. */
#include "cli.h"

#include <pointnpr/features.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The options read from the library's table (options.h), in usage order, and their metavars. */
static const char *const table_names[] = {"k", "threshold", "confidence", "dither-scale", NULL};
static const char *const table_metavars[] = {"N", "T", "C", "S"};

/* --weights G,C: the two weight entries of the table. */
static void weights_usage(FILE *f, const pnpr_option_desc *table, size_t n)
{
    const pnpr_option_desc *g = pnpr_option_find(table, n, "weight-geometry");
    const pnpr_option_desc *c = pnpr_option_find(table, n, "weight-color");
    char range[64];
    pnpr_option_range_text(g, range, sizeof range);
    fprintf(f, "  --weights G,C        weights of the geometry and colour terms (default %g,%g, each %s,\n"
               "                       not both 0; only their ratio matters)\n", g->def, c->def, range);
}

static void usage(FILE *f)
{
    size_t n;
    const pnpr_option_desc *table = pnpr_features_option_table(&n);
    fprintf(f,
            "usage: pointnpr features IN -o OUT.ply [options]\n"
            "  Computes, per point, nx ny nz, feature_degree (0..1), feature_class (0 none,\n"
            "  1 non-directional, 2 directional, 3 dithering point), feature_confidence and\n"
            "  feature_dir_x/y/z, and writes them with every input property, in input order.\n"
            "options:\n");
    for (size_t i = 0; table_names[i]; i++) {
        cli_table_usage(f, table, n, table_names[i], table_metavars[i]);
        if (!strcmp(table_names[i], "threshold")) weights_usage(f, table, n);
    }
    fprintf(f,
            "  --viewpoint X,Y,Z    orient normals towards this point (world coordinates)\n"
            "  --recompute-normals  recompute normals even when the input has them\n"
            "  --threads N          worker threads (default: all cores)\n"
            "  --ascii              write ascii PLY (default binary little endian)\n"
            "  --quiet              no progress on stderr\n");
    cli_outlier_usage(f);
    cli_columns_usage(f);
}

/* --weights G,C: two values in the weight entries' range, not both 0. 0 after saying why. */
static int parse_weights(pnpr_features_options *fo, const char *v)
{
    size_t n;
    const pnpr_option_desc *table = pnpr_features_option_table(&n);
    const pnpr_option_desc *g = pnpr_option_find(table, n, "weight-geometry");
    const pnpr_option_desc *c = pnpr_option_find(table, n, "weight-color");
    double xs[2];
    if (!cli_parse_list(v, 2, xs) || !pnpr_option_in_range(g, xs[0]) || !pnpr_option_in_range(c, xs[1]) ||
        xs[0] + xs[1] <= 0) {
        char range[64];
        pnpr_option_range_text(g, range, sizeof range);
        fprintf(stderr, "pointnpr features: --weights wants G,C (two numbers %s, not both 0; "
                        "only their ratio matters), got '%s'\n", range, v);
        return 0;
    }
    pnpr_option_set(g, fo, xs[0]);
    pnpr_option_set(c, fo, xs[1]);
    return 1;
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
        size_t tn;
        const pnpr_option_desc *table = pnpr_features_option_table(&tn);
        int to = cli_table_option(table, tn, table_names, &fo, "features", argc, argv, &i);
        if (to < 0) return 2;
        if (to > 0) continue;
        double x;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { usage(stdout); return 0; }
        else if (!strcmp(a, "--quiet")) quiet = 1;
        else if (!strcmp(a, "--ascii")) wo.encoding = PNPR_PLY_ASCII;
        else if (!strcmp(a, "--recompute-normals")) fo.recompute_normals = 1;
        else if (v && (!strcmp(a, "-o") || !strcmp(a, "--output"))) { out = v; i++; }
        else if (v && !strcmp(a, "--weights")) {
            if (!parse_weights(&fo, v)) return 2;
            i++;
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
