/* pointnpr command-line tool: dispatches to the subcommands in cmd_*.c. */
#include "cli.h"

#include <pointnpr/output.h>

#include <stdio.h>
#include <string.h>
#include <unistd.h>

int cli_progress_stderr(void *user, const char *stage, double fraction)
{
    cli_progress_state local = {{0}, 0, 0}, *ps = user ? user : &local;
    if (ps->tty == 0) ps->tty = isatty(fileno(stderr)) ? 1 : 2;
    int pct = (int)(fraction * 100.0);
    int same = strncmp(ps->stage, stage, sizeof ps->stage - 1) == 0;
    if (same && pct == ps->last_pct) return 0;
    if (!same) {
        snprintf(ps->stage, sizeof ps->stage, "%s", stage);
        ps->last_pct = -1;
    }
    if (same && ps->last_pct >= 100) return 0; /* already reported complete */
    ps->last_pct = pct;
    if (ps->tty == 1)
        fprintf(stderr, "\r%-20s %3d%%%s", stage, pct, pct >= 100 ? "\n" : "");
    else if (pct >= 100)
        fprintf(stderr, "%-20s done\n", stage);
    fflush(stderr);
    return 0;
}

void cli_report_error(const char *cmd, pnpr_status st, const pnpr_error *err)
{
    if (err && err->message[0])
        fprintf(stderr, "pointnpr %s: %s (%s)\n", cmd, err->message, pnpr_status_string(st));
    else
        fprintf(stderr, "pointnpr %s: %s\n", cmd, pnpr_status_string(st));
}

void cli_report_error_in(const char *cmd, const char *in, pnpr_status st, const pnpr_error *err)
{
    if (err && err->message[0] && strstr(err->message, in)) cli_report_error(cmd, st, err);
    else if (err && err->message[0])
        fprintf(stderr, "pointnpr %s: %s: %s (%s)\n", cmd, in, err->message, pnpr_status_string(st));
    else
        fprintf(stderr, "pointnpr %s: %s: %s\n", cmd, in, pnpr_status_string(st));
}

int cli_need_in_out(const char *cmd, const char *in, const char *out, const char *out_hint)
{
    if (in && out) return 1;
    fprintf(stderr, "pointnpr %s: %s (pointnpr %s --help lists the options)\n", cmd,
            !in ? "no input given" : "no output given", cmd);
    if (in && !out) fprintf(stderr, "  add -o %s\n", out_hint);
    return 0;
}

static void usage(FILE *f)
{
    fprintf(f,
            "pointnpr %s - non-photorealistic rendering of point clouds\n"
            "usage: pointnpr <command> [options]\n"
            "  info IN                      describe a point cloud file\n"
            "  convert IN... -o OUT.ply     convert/merge PLY, LAS, OBJ, OFF inputs into one PLY\n"
            "  features IN -o OUT.ply       normals, feature degree, classification, dithering\n"
            "  render IN -o OUT.png         stylised image (sketchy, stipple, painterly, cartoon, points)\n"
            "  animate IN -o OUT.mp4|DIR/   a camera path (file, --orbit, --flyover) as frames and a video\n"
            "  lines IN -o OUT.obj          profile lines (polylines; OBJ, PLY or SVG)\n"
            "  segment IN -o OUT.ply        segments (jseg, components, rgbgrow, labels)\n"
            "  merge-tiles -o OUT.ply ...   the tiles of a tiled features run as one cloud\n"
            "  bench accuracy [--out DIR]   error against run time of the feature analysis\n"
            "  explain [IN] --style S ...   which analysis stages an output needs, and why\n"
            "  options [--markdown]         every option's default and range (docs/options.md)\n"
            "run 'pointnpr <command> --help' for the options of a command\n",
            PNPR_VERSION_STRING);
}

int main(int argc, char **argv)
{
    if (argc < 2) { usage(stderr); return 2; }
    pnpr_output_cleanup_on_signals(); /* an interrupted command leaves no temporary file behind */
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) { usage(stdout); return 0; }
    if (!strcmp(cmd, "--version")) { printf("pointnpr %s\n", PNPR_VERSION_STRING); return 0; }
    if (!strcmp(cmd, "info")) return cli_info(argc - 1, argv + 1);
    if (!strcmp(cmd, "convert")) return cli_convert(argc - 1, argv + 1);
    if (!strcmp(cmd, "features")) return cli_features(argc - 1, argv + 1);
    if (!strcmp(cmd, "render")) return cli_render(argc - 1, argv + 1);
    if (!strcmp(cmd, "animate")) return cli_animate(argc - 1, argv + 1);
    if (!strcmp(cmd, "lines")) return cli_lines(argc - 1, argv + 1);
    if (!strcmp(cmd, "segment")) return cli_segment(argc - 1, argv + 1);
    if (!strcmp(cmd, "bench")) return cli_bench(argc - 1, argv + 1);
    if (!strcmp(cmd, "explain")) return cli_explain(argc - 1, argv + 1);
    if (!strcmp(cmd, "options")) return cli_options(argc - 1, argv + 1);
    if (!strcmp(cmd, "merge-tiles")) return cli_merge_tiles(argc - 1, argv + 1);
    fprintf(stderr, "pointnpr: unknown command '%s'\n", cmd);
    usage(stderr);
    return 2;
}
