/* pointnpr features IN -o OUT.ply: normals, feature degree, classification, dithering points. */
#include "cli.h"
#include "cli_opts.h"

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

/* --weights G,C and --viewpoint X,Y,Z (below): CLI_CUSTOM entries on the features options. */
static int parse_weights(void *fo, const char *cmd, const char *v);
static int parse_viewpoint(void *fo, const char *cmd, const char *v);

/* The command's arguments: the library's features options and the CLI's own. */
typedef struct features_args {
    cli_common c;
    pnpr_features_options fo;
    int ascii;
} features_args;

static const cli_opt features_opts[] = {
    {"--weights", NULL, CLI_CUSTOM, offsetof(features_args, fo), 0, 0, 0, 0, NULL, parse_weights, "G,C",
     "weights of the geometry and colour terms (weights_usage)"},
    {"--viewpoint", NULL, CLI_CUSTOM, offsetof(features_args, fo), 0, 0, 0, 0, NULL, parse_viewpoint, "X,Y,Z",
     "orient normals towards this point (world coordinates)"},
    {"--recompute-normals", NULL, CLI_FLAG, offsetof(features_args, fo.recompute_normals), 0, 0, 0, 0, NULL, NULL,
     NULL, "recompute normals even when the input has them"},
    CLI_THREADS_OPT(features_args, fo.threads),
    CLI_ASCII_OPT(features_args, ascii),
};

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
    cli_opts_usage(f, features_opts + 1, CLI_COUNT(features_opts) - 1); /* --weights: weights_usage */
    cli_opts_usage(f, cli_common_opts + 1, 1); /* --quiet */
    cli_outlier_usage(f);
    cli_memory_usage(f);
    cli_columns_usage(f);
    fprintf(f, "tiles (clouds larger than memory; binary PLY input; docs/tiles.md):\n");
    cli_tile_usage(f, 1);
}

/* --weights G,C: two values in the weight entries' range, not both 0. 0 after saying why. */
static int parse_weights(void *fo, const char *cmd, const char *v)
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
        fprintf(stderr, "pointnpr %s: --weights wants G,C (two numbers %s, not both 0; "
                        "only their ratio matters), got '%s'\n", cmd, range, v);
        return 0;
    }
    pnpr_option_set(g, fo, xs[0]);
    pnpr_option_set(c, fo, xs[1]);
    return 1;
}

static int parse_viewpoint(void *fo, const char *cmd, const char *v)
{
    pnpr_features_options *o = fo;
    if (!cli_parse_list(v, 3, o->viewpoint)) {
        fprintf(stderr, "pointnpr %s: --viewpoint wants X,Y,Z, got '%s'\n", cmd, v);
        return 0;
    }
    o->has_viewpoint = 1;
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
    const char *in = NULL;
    features_args A;
    memset(&A, 0, sizeof A);
    pnpr_features_options *fo = &A.fo;
    pnpr_write_options wo = {0};
    cli_outliers outliers = {0, 0};
    const char *columns = NULL;
    size_t memory_limit = 0;
    cli_tile_args tiles;
    memset(&tiles, 0, sizeof tiles);
    size_t tn;
    const pnpr_option_desc *table = pnpr_features_option_table(&tn);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int oo = cli_outlier_option(&outliers, "features", argc, argv, &i);
        if (oo == 0) oo = cli_columns_option(&columns, "features", argc, argv, &i);
        if (oo == 0) oo = cli_memory_option(&memory_limit, "features", argc, argv, &i);
        if (oo == 0) oo = cli_tile_option(&tiles, "features", argc, argv, &i);
        if (oo == 0) oo = cli_table_option(table, tn, table_names, fo, "features", argc, argv, &i);
        if (oo == 0) oo = cli_opts_parse(features_opts, CLI_COUNT(features_opts), &A, "features", argc, argv, &i);
        if (oo == 0) oo = cli_opts_parse(cli_common_opts, CLI_COUNT(cli_common_opts), &A.c, "features", argc, argv, &i);
        if (oo < 0) return 2;
        if (A.c.help) { usage(stdout); return 0; }
        if (oo > 0) continue;
        if (cli_operand("features", a, &in, usage)) return 2;
    }
    const char *out = A.c.out;
    int quiet = A.c.quiet;
    if (A.ascii) wo.encoding = PNPR_PLY_ASCII;
    if (!cli_need_in_out("features", in, out, "OUT.ply")) return 2;
    int out_rc = cli_cloud_output("features", out, in, &wo);
    if (out_rc) return out_rc;

    cli_progress_state ps = {{0}, 0, 0};
    pnpr_progress prog = {quiet ? NULL : cli_progress_stderr, &ps};
    pnpr_read_options ro = {0};
    ro.columns = columns;
    ro.progress = prog;
    fo->progress = prog;
    wo.progress = prog;
    if (cli_tile_wanted(&tiles)) {
        if (outliers.drop || columns) {
            fprintf(stderr, "pointnpr features: tiles read binary PLY as it is: --drop-outliers and --columns do not apply\n");
            return 2;
        }
        cli_features_run run = {in, out, fo, &wo, prog, quiet};
        return cli_features_tiles(&run, &tiles, memory_limit, argc, argv);
    }
    pnpr_cloud cloud = {0};
    pnpr_error err = {0};
    if (!cli_memory_check_file("features", in, memory_limit)) return 1;
    pnpr_status st = pnpr_read_file(in, &ro, &cloud, &err);
    if (st != PNPR_OK) { cli_report_error("features", st, &err); return 1; }
    if (cli_outliers_apply(&outliers, "features", in, &cloud, quiet, NULL)) { pnpr_cloud_free(&cloud); return 1; }
    pnpr_memory_plan mp = {cloud.count, fo->k ? fo->k : pnpr_features_defaults().k, cloud.normal == NULL, 0, 0, 0, 0, 0};
    if (!cli_memory_check_plan("features", in, memory_limit, &mp)) { pnpr_cloud_free(&cloud); return 1; }

    pnpr_features_stats stats;
    st = pnpr_features_check_options(fo, &err);
    if (st == PNPR_OK) st = pnpr_compute_features(&cloud, fo, &stats);
    if (st != PNPR_OK) {
        if (err.message[0]) cli_report_error("features", st, &err);
        else fprintf(stderr, "pointnpr features: %s: %s\n", in, pnpr_status_string(st));
        pnpr_cloud_free(&cloud);
        return 1;
    }
    if (stats.valid_points < 3) warn_few_points(in, cloud.count, &stats);
    if (!quiet) {
        fprintf(stderr, "points %zu (valid %zu), k %u, threshold %.3f%s\n", cloud.count, stats.valid_points,
                stats.k_used, stats.threshold_used, fo->threshold > 0 ? "" : " (automatic)");
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
