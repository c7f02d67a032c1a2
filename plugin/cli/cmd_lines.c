/* pointnpr lines IN -o OUT.obj|OUT.ply: profile lines from the directional feature points. */
#include "cli.h"

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
    fprintf(f,
            "  --no-corners         do not join line ends at corners and across gaps\n"
            "  --svg OUT.svg        also draw the lines as SVG through a camera, hidden parts removed\n"
            "                       by a depth test against IN's points\n"
            "  --eye X,Y,Z --target X,Y,Z --up X,Y,Z --fov DEG --size WxH\n"
            "                       the SVG's camera (as in 'pointnpr render'; default: the default view)\n"
            "  --up auto|x|y|z|-x|-y|-z  the up axis of the default view (auto: detected, docs/view.md)\n"
            "  --camera FILE        the SVG's camera from a file (as written by render --save-camera)\n"
            "  --stroke-width PX    SVG stroke width (default 1.5)\n"
            "  --taper F            strokes narrow to a point over the fraction F of their length\n"
            "  --show-hidden        keep hidden parts in the SVG (and draw no outlines)\n"
            "  --outline on|off     the SVG gets IN's silhouettes and occluding contours as paths\n"
            "                       (default on; docs/lines.md)\n"
            "  --outline-width PX   their stroke width (default %g)\n"
            "  --outline-jump F     a contour is a depth jump of more than F disk depth extents (default %g)\n"
            "  --quiet              no progress on stderr\n"
            "feature options, used when features are computed:\n", (double)PNPR_SVG_OUTLINE_WIDTH, (double)PNPR_OUTLINE_JUMP);
    for (size_t i = 0; feature_names[i]; i++) cli_table_usage(f, ftable, fn, feature_names[i], feature_metavars[i]);
    cli_outlier_usage(f);
    cli_columns_usage(f);
}

/* The SVG drawing's options. */
typedef struct svg_args {
    const char *path, *in; /* in: the input, for messages */
    int show_hidden, outline; /* outline: 0 default (on), 1 on, -1 off */
    double stroke, taper, outline_width, outline_jump;
} svg_args;

/* Parses argv[*i] when it is an SVG option: 1 taken (*i advanced past its value), 0 not an SVG
 * option, -1 a bad value (reported). */
static int svg_option(svg_args *s, int argc, char **argv, int *i)
{
    const char *a = argv[*i], *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    int ok = 1;
    if (!strcmp(a, "--show-hidden")) { s->show_hidden = 1; return 1; }
    if (!v) return 0;
    if (!strcmp(a, "--svg")) s->path = v;
    else if (!strcmp(a, "--stroke-width")) ok = cli_parse_number(v, 1e-3, 1e3, &s->stroke);
    else if (!strcmp(a, "--taper")) ok = cli_parse_number(v, 0, 1, &s->taper);
    else if (!strcmp(a, "--outline")) {
        ok = !strcmp(v, "on") || !strcmp(v, "off");
        s->outline = !strcmp(v, "on") ? 1 : -1;
    } else if (!strcmp(a, "--outline-width")) ok = cli_parse_number(v, 0.1, 64, &s->outline_width);
    else if (!strcmp(a, "--outline-jump")) ok = cli_parse_number(v, 0.01, 1e3, &s->outline_jump);
    else return 0;
    (*i)++;
    if (ok) return 1;
    const char *want = !strcmp(a, "--stroke-width") ? "a positive number of pixels"
                       : !strcmp(a, "--taper")      ? "a fraction in [0,1]"
                       : !strcmp(a, "--outline")    ? "on or off"
                       : !strcmp(a, "--outline-width") ? "pixels in [0.1, 64]"
                                                    : "a positive number";
    fprintf(stderr, "pointnpr lines: %s wants %s, got '%s'\n", a, want, v);
    return -1;
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
static int write_svg(const svg_args *sa, const cli_view *view, const pnpr_polylines *lines, const pnpr_cloud *cloud,
                     int quiet)
{
    pnpr_svg_options so = {0};
    so.width = view->width;
    so.height = view->height;
    so.stroke_width = (float)sa->stroke;
    so.taper = (float)sa->taper;
    so.occluders = sa->show_hidden ? NULL : cloud;
    so.outline = sa->outline;
    so.outline_width = (float)sa->outline_width;
    so.outline_jump = (float)sa->outline_jump;
    pnpr_camera cam;
    pnpr_error err = {0};
    const pnpr_camera *camp = cli_view_camera(view, cloud, &cam);
    pnpr_status st = pnpr_write_lines_svg(sa->path, lines, camp, &so, &err);
    if (st != PNPR_OK) {
        cli_report_error_in("lines", sa->in, st, &err);
        return 0;
    }
    if (!quiet) fprintf(stderr, "wrote %s\n", sa->path);
    return 1;
}

/* The output names: kinds from the extensions (or "-" / a special file), not the same file twice,
 * writable and none of them the input. Returns 0, or the exit code after saying why. OUT may be
 * NULL when --svg is given. */
static int check_outputs(const char *in, const char *out, const svg_args *sa)
{
    if (out && !cli_has_ext(out, ".ply") && !cli_has_ext(out, ".obj") && !cli_output_is_stream(out)) {
        fprintf(stderr, "pointnpr lines: the output must end in .obj or .ply (or be - or a device/FIFO for OBJ), got '%s'\n", out);
        return 2;
    }
    if (sa->path && !cli_has_ext(sa->path, ".svg") && !cli_output_is_stream(sa->path)) {
        fprintf(stderr, "pointnpr lines: --svg wants a name ending in .svg (or -), got '%s'\n", sa->path);
        return 2;
    }
    if (out && sa->path && !strcmp(sa->path, out)) {
        fprintf(stderr, "pointnpr lines: -o and --svg name the same %s\n",
                strcmp(out, "-") ? "file" : "output (standard output can take only one)");
        return 2;
    }
    if ((out && !cli_check_output("lines", out, &in, 1, 0)) || (sa->path && !cli_check_output("lines", sa->path, &in, 1, 0)))
        return 1;
    return 0;
}

int cli_lines(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    pnpr_lines_options lo = {0};
    pnpr_features_options fo = {0};
    int quiet = 0;
    cli_outliers outliers = {0, 0};
    const char *columns = NULL;
    svg_args sa;
    memset(&sa, 0, sizeof sa);
    cli_view view;
    cli_view_init(&view, 1024, 768);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int vo = cli_view_option(&view, "lines", argc, argv, &i);
        if (vo < 0) return 2;
        if (vo > 0) continue;
        int oo = cli_outlier_option(&outliers, "lines", argc, argv, &i);
        if (oo == 0) oo = cli_columns_option(&columns, "lines", argc, argv, &i);
        if (oo < 0) return 2;
        if (oo > 0) continue;
        int so = svg_option(&sa, argc, argv, &i);
        if (so < 0) return 2;
        if (so > 0) continue;
        size_t n, fn;
        const pnpr_option_desc *table = pnpr_lines_option_table(&n), *ftable = pnpr_features_option_table(&fn);
        int to = cli_table_option(table, n, lines_names, &lo, "lines", argc, argv, &i);
        if (to == 0) to = cli_table_option(ftable, fn, feature_names, &fo, "lines", argc, argv, &i);
        if (to < 0) return 2;
        if (to > 0) continue;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { usage(stdout); return 0; }
        else if (!strcmp(a, "--quiet")) quiet = 1;
        else if (!strcmp(a, "--no-corners")) lo.no_corners = 1;
        else if (v && (!strcmp(a, "-o") || !strcmp(a, "--output"))) { out = v; i++; }
        else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "pointnpr lines: unknown option or missing value: %s\n", a);
            usage(stderr);
            return 2;
        } else if (!in) in = a;
        else { fprintf(stderr, "pointnpr lines: more than one input given ('%s')\n", a); return 2; }
    }
    if (!cli_need_in_out("lines", in, out ? out : sa.path, "OUT.obj (or --svg OUT.svg)")) return 2;
    if (!cli_view_check(&view, "lines")) return 2;
    sa.in = in;
    int rc = check_outputs(in, out, &sa);
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
    if (!run_plan(in, &cloud, &fo, sa.path && !sa.show_hidden && sa.outline >= 0, quiet)) {
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
    if (sa.path && !write_svg(&sa, &view, &lines, &cloud, quiet)) {
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
