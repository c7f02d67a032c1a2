/* pointnpr lines IN -o OUT.obj|OUT.ply: profile lines from the directional feature points. */
#include "cli.h"

#include <pointnpr/features.h>
#include <pointnpr/lines.h>
#ifdef PNPR_HAVE_RENDER
#include <pointnpr/render.h>
#endif

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage: pointnpr lines IN -o OUT.obj|OUT.ply [options]\n"
            "  Profile lines (PointWorks): polylines through the directional feature points,\n"
            "  written as OBJ 'l' polylines or as PLY with an edge element (world coordinates).\n"
            "  The features are computed first when IN does not carry them (feature_class,\n"
            "  feature_dir_x/y/z, as written by 'pointnpr features').\n"
            "options (h = point spacing, estimated from the directional points):\n"
            "  --spacing H          the spacing h in world units (default: estimated)\n"
            "  --radius R           graph neighbourhood radius (default 3h)\n"
            "  --merge-tol T        merge points closer than T (default h)\n"
            "  --min-length L       drop spurs and isolated lines shorter than L (default 5h)\n"
            "  --direction-weight B how much edges across the feature direction cost (default 4)\n"
            "  --no-corners         do not join line ends at corners and across gaps\n"
            "  --svg OUT.svg        also draw the lines as SVG through a camera, hidden parts removed\n"
            "                       by a depth test against IN's points\n"
            "  --eye X,Y,Z --target X,Y,Z --up X,Y,Z --fov DEG --size WxH\n"
            "                       the SVG's camera (as in 'pointnpr render'; default: the default view)\n"
            "  --up auto|x|y|z|-x|-y|-z  the up axis of the default view (auto: detected, docs/view.md)\n"
            "  --camera FILE        the SVG's camera from a file (as written by render --save-camera)\n"
            "  --stroke-width PX    SVG stroke width (default 1.5)\n"
            "  --taper F            strokes narrow to a point over the fraction F of their length\n"
            "  --show-hidden        keep hidden parts in the SVG\n"
            "  --k N, --threshold T feature options used when features are computed\n"
            "  --quiet              no progress on stderr\n");
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcasecmp(s + n - m, suffix) == 0;
}

int cli_lines(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    pnpr_lines_options lo = {0};
    pnpr_features_options fo = {0};
    int quiet = 0, show_hidden = 0;
    const char *svg = NULL;
    double stroke = 0, taper = 0;
    cli_view view;
    cli_view_init(&view, 1024, 768);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        double x;
        int vo = cli_view_option(&view, "lines", argc, argv, &i);
        if (vo < 0) return 2;
        if (vo > 0) continue;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { usage(stdout); return 0; }
        else if (!strcmp(a, "--quiet")) quiet = 1;
        else if (!strcmp(a, "--show-hidden")) show_hidden = 1;
        else if (v && !strcmp(a, "--svg")) { svg = v; i++; }
        else if (v && !strcmp(a, "--stroke-width")) {
            if (!cli_parse_number(v, 1e-3, 1e3, &stroke)) { fprintf(stderr, "pointnpr lines: --stroke-width wants a positive number of pixels, got '%s'\n", v); return 2; }
            i++;
        } else if (v && !strcmp(a, "--taper")) {
            if (!cli_parse_number(v, 0, 1, &taper)) { fprintf(stderr, "pointnpr lines: --taper wants a fraction in [0,1], got '%s'\n", v); return 2; }
            i++;
        }
        else if (!strcmp(a, "--no-corners")) lo.no_corners = 1;
        else if (v && (!strcmp(a, "-o") || !strcmp(a, "--output"))) { out = v; i++; }
        else if (v && (!strcmp(a, "--spacing") || !strcmp(a, "--radius") || !strcmp(a, "--merge-tol") ||
                       !strcmp(a, "--min-length") || !strcmp(a, "--direction-weight") || !strcmp(a, "--k") ||
                       !strcmp(a, "--threshold"))) {
            if (!cli_parse_number(v, 1e-30, 1e30, &x)) { fprintf(stderr, "pointnpr lines: %s wants a positive number, got '%s'\n", a, v); return 2; }
            if (!strcmp(a, "--spacing")) lo.spacing = (float)x;
            else if (!strcmp(a, "--radius")) lo.connect_radius = (float)x;
            else if (!strcmp(a, "--merge-tol")) lo.merge_tol = (float)x;
            else if (!strcmp(a, "--min-length")) lo.min_length = (float)x;
            else if (!strcmp(a, "--direction-weight")) lo.direction_weight = (float)x;
            else if (!strcmp(a, "--k")) {
                if (x != floor(x) || x > 1024) { fprintf(stderr, "pointnpr lines: --k wants an integer in 1..1024\n"); return 2; }
                fo.k = (uint32_t)x;
            } else {
                if (x > 1) { fprintf(stderr, "pointnpr lines: --threshold wants a number in (0,1]\n"); return 2; }
                fo.threshold = (float)x;
            }
            i++;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "pointnpr lines: unknown option or missing value: %s\n", a);
            usage(stderr);
            return 2;
        } else if (!in) in = a;
        else { fprintf(stderr, "pointnpr lines: more than one input given ('%s')\n", a); return 2; }
    }
    if (!in || !out) { usage(stderr); return 2; }
    if (!cli_view_check(&view, "lines")) return 2;
#ifndef PNPR_HAVE_RENDER
    if (svg) { fprintf(stderr, "pointnpr lines: --svg needs the renderer, which this build does not have\n"); return 2; }
#endif
    int as_ply = ends_with(out, ".ply");
    if (!as_ply && !ends_with(out, ".obj")) {
        fprintf(stderr, "pointnpr lines: the output must end in .obj or .ply, got '%s'\n", out);
        return 2;
    }

    cli_progress_state ps = {{0}, 0, 0};
    pnpr_progress prog = {quiet ? NULL : cli_progress_stderr, &ps};
    pnpr_read_options ro = {0};
    ro.progress = prog;
    fo.progress = prog;
    lo.progress = prog;
    pnpr_cloud cloud = {0};
    pnpr_error err = {0};
    pnpr_status st = pnpr_read_file(in, &ro, &cloud, &err);
    if (st != PNPR_OK) { cli_report_error("lines", st, &err); return 1; }
    if (!pnpr_cloud_find_property(&cloud, "feature_class") || !pnpr_cloud_find_property(&cloud, "feature_dir_x") ||
        !pnpr_cloud_find_property(&cloud, "feature_dir_y") || !pnpr_cloud_find_property(&cloud, "feature_dir_z")) {
        if (!quiet) fprintf(stderr, "%s has no feature properties: computing them\n", in);
        fo.want = PNPR_WANT_CLASSES; /* lines need directional points, not dithering or normals */
        st = pnpr_compute_features(&cloud, &fo, NULL);
        if (st != PNPR_OK) {
            fprintf(stderr, "pointnpr lines: %s: features: %s\n", in, pnpr_status_string(st));
            pnpr_cloud_free(&cloud);
            return 1;
        }
    }
    pnpr_polylines lines = {0};
    pnpr_lines_stats stats;
    st = pnpr_profile_lines(&cloud, &lo, &lines, &stats);
    if (st != PNPR_OK) {
        fprintf(stderr, "pointnpr lines: %s: %s\n", in, pnpr_status_string(st));
        pnpr_cloud_free(&cloud);
        return 1;
    }
#ifdef PNPR_HAVE_RENDER
    if (svg) {
        pnpr_svg_options so = {0};
        so.width = view.width;
        so.height = view.height;
        so.stroke_width = (float)stroke;
        so.taper = (float)taper;
        so.occluders = show_hidden ? NULL : &cloud;
        pnpr_camera cam;
        const pnpr_camera *camp = cli_view_camera(&view, &cloud, &cam);
        st = pnpr_write_lines_svg(svg, &lines, camp, &so, &err);
        if (st != PNPR_OK) {
            cli_report_error("lines", st, &err);
            pnpr_lines_free(&lines);
            pnpr_cloud_free(&cloud);
            return 1;
        }
        if (!quiet) fprintf(stderr, "wrote %s\n", svg);
    }
#else
    (void)show_hidden; (void)stroke; (void)taper;
#endif
    pnpr_cloud_free(&cloud);
    if (stats.directional_points == 0)
        fprintf(stderr, "pointnpr lines: %s has no directional feature points: no lines (the output is empty)\n", in);
    else if (!quiet)
        fprintf(stderr, "directional points %zu -> %zu nodes, spacing %.4g; %zu polylines, %zu corners, total length %.4g\n"
                        "  graph %.3f s, spanning forest %.3f s (%zu of %zu edges), fit %.3f s\n",
                stats.directional_points, stats.merged_nodes, stats.spacing_used, stats.chains, stats.corners,
                stats.total_length, stats.seconds_graph, stats.seconds_mst, stats.forest_edges, stats.graph_edges,
                stats.seconds_fit);
    st = as_ply ? pnpr_write_lines_ply(out, &lines, &err) : pnpr_write_lines_obj(out, &lines, &err);
    pnpr_lines_free(&lines);
    if (st != PNPR_OK) { cli_report_error("lines", st, &err); return 1; }
    if (!quiet) fprintf(stderr, "wrote %s\n", out);
    return 0;
}
