/* pointnpr lines IN -o OUT.obj|OUT.ply: profile lines from the directional feature points. */
#include "cli.h"
#include "cli_opts.h"

#include <pointnpr/camera.h>
#include <pointnpr/features.h>
#include <pointnpr/lines.h>
#include <pointnpr/plan.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* The options read from the library's tables (options.h), in usage order, and their metavars. */
static const char *const lines_names[] = {"spacing", "radius", "merge-tol", "min-length", "direction-weight", NULL};
static const char *const lines_metavars[] = {"H", "R", "T", "L", "B"};
static const char *const feature_names[] = {"k", "threshold", NULL};
static const char *const feature_metavars[] = {"N", "T"};
static const char *const svg_names[] = {"stroke-width", "taper", "outline-width", "outline-jump", NULL};
static const char *const svg_metavars[] = {"PX", "F", "PX", "F"};

/* The command's own arguments (cli_opts.h); the SVG drawing's options (svg_names) go to so. */
typedef struct lines_args {
    cli_common c;
    const char *svg, *in; /* in: the input, for messages */
    int show_hidden, no_corners, threads;
    pnpr_svg_options so; /* so.outline: --outline (1 on, -1 off, 0 the default: on) */
} lines_args;
static const cli_opt lines_opts[] = {
    {"--no-corners", NULL, CLI_FLAG, offsetof(lines_args, no_corners), 0, 0, 0, 0, NULL, NULL, NULL,
     "do not join line ends at corners and across gaps"},
    {"--svg", NULL, CLI_TEXT, offsetof(lines_args, svg), 0, 0, 0, 0, NULL, NULL, "OUT.svg",
     "also draw the lines as SVG through a camera, hidden parts removed by a depth test against IN's points"},
    {"--show-hidden", NULL, CLI_FLAG, offsetof(lines_args, show_hidden), 0, 0, 0, 0, NULL, NULL, NULL,
     "keep hidden parts in the SVG (and draw no outlines)"},
    CLI_OUTLINE_OPT(lines_args, so.outline,
                    "the SVG gets IN's silhouettes and occluding contours as paths (default on; docs/lines.md)"),
    CLI_THREADS_OPT(lines_args, threads),
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: pointnpr lines IN -o OUT.obj|OUT.ply [--svg OUT.svg] [options]\n"
            "       pointnpr lines IN --svg OUT.svg [options]\n"
            "  Profile lines (PointWorks): polylines through the directional feature points,\n"
            "  written as OBJ 'l' polylines or as PLY with an edge element (world coordinates).\n"
            "  The features are computed first when IN does not carry them (feature_class,\n"
            "  feature_dir_x/y/z, as written by 'pointnpr features').\n"
            "options (h = point spacing, estimated from the directional points):\n");
    size_t n, fn;
    const pnpr_option_desc *table = pnpr_lines_option_table(&n), *ftable = pnpr_features_option_table(&fn);
    for (size_t i = 0; lines_names[i]; i++) cli_table_usage(f, table, n, lines_names[i], lines_metavars[i]);
    cli_opts_usage(f, lines_opts, 2); /* --no-corners, --svg */
    fprintf(f,
            "  --eye X,Y,Z --target X,Y,Z --up X,Y,Z --fov DEG --size WxH\n"
            "                       the SVG's camera (as in 'pointnpr render'; default: the default view)\n"
            "  --up auto|x|y|z|-x|-y|-z  the up axis of the default view (auto: detected, docs/view.md)\n"
            "  --camera FILE        the SVG's camera from a file (as written by render --save-camera)\n");
    size_t sn;
    const pnpr_option_desc *st = pnpr_svg_option_table(&sn);
    for (size_t i = 0; svg_names[i]; i++) cli_table_usage(f, st, sn, svg_names[i], svg_metavars[i]);
    cli_opts_usage(f, lines_opts + 2, 3); /* --show-hidden, --outline, --threads */
    cli_opts_usage(f, cli_common_opts + 1, 1); /* --quiet */
    fprintf(f, "feature options, used when features are computed:\n");
    for (size_t i = 0; feature_names[i]; i++) cli_table_usage(f, ftable, fn, feature_names[i], feature_metavars[i]);
    cli_outlier_usage(f);
    cli_columns_usage(f);
}

/* Runs the stage plan for profile lines (+ normals for the SVG's outlines, which weigh depth jumps
 * by the surface's slant): computes only what the cloud does not carry. 0 on failure (reported). */
static int run_plan(const char *in, pnpr_cloud *cloud, pnpr_features_options *fo, int outline_normals, int quiet)
{
    pnpr_plan_request req = {0};
    req.lines = 1;
    if (outline_normals) req.want = PNPR_WANT_NORMALS_ANY;
    pnpr_plan plan;
    pnpr_status st = pnpr_plan_make(&req, cloud, &plan);
    if (st == PNPR_OK && plan.want) {
        if (!quiet && (plan.want & PNPR_WANT_CLASSES)) fprintf(stderr, "%s has no feature properties: computing them\n", in);
        else if (!quiet) fprintf(stderr, "%s has no normals: computing them for the outlines\n", in);
        fo->want = plan.want;
        st = pnpr_compute_features(cloud, fo, NULL);
    }
    if (st != PNPR_OK) fprintf(stderr, "pointnpr lines: %s: features: %s\n", in, pnpr_status_string(st));
    return st == PNPR_OK;
}

/* Draws the lines (and the cloud's outlines) as SVG; 0 on failure (reported). */
static int write_svg(const lines_args *sa, const cli_view *view, const pnpr_polylines *lines, const pnpr_cloud *cloud,
                     int quiet)
{
    pnpr_svg_options so = sa->so;
    so.width = view->width;
    so.height = view->height;
    so.occluders = sa->show_hidden ? NULL : cloud;
    pnpr_camera cam;
    pnpr_error err = {0};
    const pnpr_camera *camp = cli_view_camera(view, cloud, &cam);
    pnpr_status st = pnpr_write_lines_svg(sa->svg, lines, camp, &so, &err);
    if (st != PNPR_OK) {
        cli_report_error_in("lines", sa->in, st, &err);
        return 0;
    }
    if (!quiet) fprintf(stderr, "wrote %s\n", sa->svg);
    return 1;
}

/* The output names: kinds from the extensions (or "-" / a special file), not the same file twice,
 * writable and none of them the input. Returns 0, or the exit code after saying why. OUT may be
 * NULL when --svg is given. */
static int check_outputs(const char *in, const char *out, const lines_args *sa)
{
    if (out && !cli_has_ext(out, ".ply") && !cli_has_ext(out, ".obj") && !cli_output_is_stream(out)) {
        fprintf(stderr, "pointnpr lines: the output must end in .obj or .ply (or be - or a device/FIFO for OBJ), got '%s'\n", out);
        return 2;
    }
    if (sa->svg && !cli_has_ext(sa->svg, ".svg") && !cli_output_is_stream(sa->svg)) {
        fprintf(stderr, "pointnpr lines: --svg wants a name ending in .svg (or -), got '%s'\n", sa->svg);
        return 2;
    }
    if (out && sa->svg && !strcmp(sa->svg, out)) {
        fprintf(stderr, "pointnpr lines: -o and --svg name the same %s\n",
                strcmp(out, "-") ? "file" : "output (standard output can take only one)");
        return 2;
    }
    if ((out && !cli_check_output("lines", out, &in, 1, 0)) || (sa->svg && !cli_check_output("lines", sa->svg, &in, 1, 0)))
        return 1;
    return 0;
}

int cli_lines(int argc, char **argv)
{
    const char *in = NULL;
    pnpr_lines_options lo = {0};
    pnpr_features_options fo = {0};
    cli_outliers outliers = {0, 0};
    const char *columns = NULL;
    lines_args A;
    memset(&A, 0, sizeof A);
    cli_view view;
    cli_view_init(&view, 1024, 768);
    size_t n, fn, sn;
    const pnpr_option_desc *table = pnpr_lines_option_table(&n), *ftable = pnpr_features_option_table(&fn);
    const pnpr_option_desc *stable = pnpr_svg_option_table(&sn);
    for (int i = 1; i < argc; i++) {
        int oo = cli_view_option(&view, "lines", argc, argv, &i);
        if (oo == 0) oo = cli_outlier_option(&outliers, "lines", argc, argv, &i);
        if (oo == 0) oo = cli_columns_option(&columns, "lines", argc, argv, &i);
        if (oo == 0) oo = cli_table_option(table, n, lines_names, &lo, "lines", argc, argv, &i);
        if (oo == 0) oo = cli_table_option(ftable, fn, feature_names, &fo, "lines", argc, argv, &i);
        if (oo == 0) oo = cli_table_option(stable, sn, svg_names, &A.so, "lines", argc, argv, &i);
        if (oo == 0) oo = cli_opts_parse(lines_opts, CLI_COUNT(lines_opts), &A, "lines", argc, argv, &i);
        if (oo == 0) oo = cli_opts_parse(cli_common_opts, CLI_COUNT(cli_common_opts), &A.c, "lines", argc, argv, &i);
        if (oo < 0) return 2;
        if (A.c.help) { usage(stdout); return 0; }
        if (oo == 0 && cli_operand("lines", argv[i], &in, usage)) return 2;
    }
    const char *out = A.c.out;
    const int quiet = A.c.quiet;
    lo.no_corners = A.no_corners;
    lo.threads = fo.threads = A.threads;
    lines_args *sa = &A;
    if (!cli_need_in_out("lines", in, out ? out : sa->svg, "OUT.obj (or --svg OUT.svg)")) return 2;
    if (!cli_view_check(&view, "lines")) return 2;
    sa->in = in;
    int rc = check_outputs(in, out, sa);
    if (rc) return rc;
    const int as_ply = out && cli_has_ext(out, ".ply");

    cli_progress_state ps = {{0}, 0, 0};
    pnpr_progress prog = {quiet ? NULL : cli_progress_stderr, &ps};
    pnpr_read_options ro = {0};
    ro.columns = columns;
    ro.progress = prog;
    fo.progress = prog;
    lo.progress = prog;
    pnpr_cloud cloud = {0};
    pnpr_error err = {0};
    pnpr_status st = pnpr_read_file(in, &ro, &cloud, &err);
    if (st != PNPR_OK) { cli_report_error("lines", st, &err); return 1; }
    if (cli_outliers_apply(&outliers, "lines", in, &cloud, quiet, NULL)) { pnpr_cloud_free(&cloud); return 1; }
    if (!run_plan(in, &cloud, &fo, sa->svg && !sa->show_hidden && sa->so.outline >= 0, quiet)) {
        pnpr_cloud_free(&cloud);
        return 1;
    }
    pnpr_polylines lines = {0};
    pnpr_lines_stats stats;
    st = pnpr_profile_lines(&cloud, &lo, &lines, &stats);
    if (st != PNPR_OK) {
        fprintf(stderr, "pointnpr lines: %s: %s\n", in, pnpr_status_string(st));
        pnpr_cloud_free(&cloud);
        return 1;
    }
    if (sa->svg && !write_svg(sa, &view, &lines, &cloud, quiet)) {
        pnpr_lines_free(&lines);
        pnpr_cloud_free(&cloud);
        return 1;
    }
    pnpr_cloud_free(&cloud);
    if (stats.directional_points == 0)
        fprintf(stderr, "pointnpr lines: %s has no directional feature points: no lines (the output is empty)\n", in);
    else if (!quiet)
        fprintf(stderr, "directional points %zu -> %zu nodes, spacing %.4g; %zu polylines, %zu corners, total length %.4g\n"
                        "  graph %.3f s, spanning forest %.3f s (%zu of %zu edges), fit %.3f s\n",
                stats.directional_points, stats.merged_nodes, stats.spacing_used, stats.chains, stats.corners,
                stats.total_length, stats.seconds_graph, stats.seconds_mst, stats.forest_edges, stats.graph_edges,
                stats.seconds_fit);
    if (out) st = as_ply ? pnpr_write_lines_ply(out, &lines, &err) : pnpr_write_lines_obj(out, &lines, &err);
    pnpr_lines_free(&lines);
    if (st != PNPR_OK) { cli_report_error("lines", st, &err); return 1; }
    if (!quiet && out) fprintf(stderr, "wrote %s\n", out);
    return 0;
}
