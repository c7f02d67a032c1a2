/* pointnpr explain: the stage plan for a requested output — which analysis stages run and why,
 * which are skipped, and which the input already carries (reused, not recomputed).
 *   pointnpr explain [IN] [--style S [--sketch a|b|c]] [--outline on|off] [--lines]
 *                         [--segment METHOD] [--features]
 * It prints the library's plan (pnpr_plan_make, plan.h): the one `render` and `lines` execute. */
#include "cli.h"
#include "cli_opts.h"

#include <pointnpr/features.h>
#include <pointnpr/plan.h>

#include <stdio.h>
#include <string.h>

typedef struct row { const char *stage; int run; const char *why; } row;

/* The rows of the plan, in pipeline order. */
static int plan_rows(const pnpr_plan *p, int have_in, int brush_asked, const char *segment_method, row *r)
{
    const uint32_t w = p->want, n = p->needed;
    const int oriented = (w & PNPR_WANT_NORMALS) != 0, normals = (w & (PNPR_WANT_NORMALS | PNPR_WANT_NORMALS_ANY)) != 0;
    const char *reuse = "the input carries what is needed: reused";
    int k = 0;
    r[k++] = (row){"kd-tree + knn", w != 0, w ? "neighbourhoods for every stage below" : (n && have_in ? reuse : "no analysis needed")};
    r[k++] = (row){"normals (PCA)", w != 0,
                   w ? (normals ? (p->why[0] ? p->why[0] : p->why[4]) : "its plane-fit error drives the feature degree")
                     : (n && have_in ? reuse : "not needed")};
    r[k++] = (row){"orient", oriented, oriented ? p->why[0] : "no output needs oriented normals"};
    r[k++] = (row){"feature degree", (w & PNPR_WANT_DEGREE) != 0, w & PNPR_WANT_DEGREE ? p->why[1] : (n & PNPR_WANT_DEGREE && have_in ? reuse : "not needed")};
    r[k++] = (row){"classify", (w & PNPR_WANT_CLASSES) != 0, w & PNPR_WANT_CLASSES ? p->why[2] : (n & PNPR_WANT_CLASSES && have_in ? reuse : "not needed")};
    r[k++] = (row){"dither", (w & PNPR_WANT_DITHER) != 0,
                   w & PNPR_WANT_DITHER ? p->why[3] : (n & PNPR_WANT_DITHER && have_in ? reuse : "no output draws dithering points")};
    r[k++] = (row){"profile lines", p->lines, p->lines ? p->lines_why : "not requested"};
    int seg = segment_method ? 1 : p->segments == PNPR_PLAN_SEGMENTS_JSEG;
    r[k++] = (row){"segments", seg,
                   segment_method ? "requested (--segment)" : p->segments != PNPR_PLAN_SEGMENTS_NONE ? p->segments_why : "not requested"};
    r[k++] = (row){"brush sizes", p->brush,
                   p->brush ? p->brush_why : (brush_asked && have_in ? reuse : "no output draws brush strokes")};
    r[k++] = (row){"sphere hierarchy", p->hierarchy, p->hierarchy ? p->hierarchy_why : "no output draws the hierarchy's strokes"};
    return k;
}

/* What explain is asked about (cli_opts.h; --style, --sketch and --outline as render takes them). */
typedef struct explain_args {
    pnpr_style style;
    pnpr_sketch_variant sketch;
    int outline, lines, features, help;
    const char *segment, *style_name;
} explain_args;

static int parse_style(void *a, const char *cmd, const char *v)
{
    explain_args *e = a;
    if (!cli_parse_style(&e->style, cmd, v)) return 0;
    e->style_name = v;
    return 1;
}

static const cli_opt explain_opts[] = {
    {"--style", NULL, CLI_CUSTOM, 0, 0, 0, 0, 0, NULL, parse_style, "S", "the style to draw"},
    CLI_SKETCH_OPT(explain_args, sketch),
    CLI_OUTLINE_OPT(explain_args, outline, "outlines on or off (default: the style's)"),
    {"--lines", NULL, CLI_FLAG, offsetof(explain_args, lines), 0, 0, 0, 0, NULL, NULL, NULL, "profile lines too"},
    {"--segment", NULL, CLI_TEXT, offsetof(explain_args, segment), 0, 0, 0, 0, NULL, NULL, "METHOD", "segments too"},
    {"--features", NULL, CLI_FLAG, offsetof(explain_args, features), 0, 0, 0, 0, NULL, NULL, NULL, "every feature"},
    {"--help", "-h", CLI_FLAG, offsetof(explain_args, help), 0, 0, 0, 0, NULL, NULL, NULL, "this text"},
};

static void usage(FILE *f)
{
    char names[160];
    fprintf(f, "usage: pointnpr explain [IN] [--style %s]\n", pnpr_style_list(names, sizeof names, "|", 0));
    fprintf(f, "                        [--sketch a|b|c] [--outline on|off] [--lines] [--segment METHOD]\n"
               "                        [--features]\n"
               "  prints the analysis stages the requested outputs need, and why; with IN, which of\n"
               "  them the file already carries (reused, not recomputed). `render` and `lines` follow\n"
               "  this plan.\n");
    cli_opts_usage(f, explain_opts, CLI_COUNT(explain_opts));
}

int cli_explain(int argc, char **argv)
{
    pnpr_plan_request req = {0};
    const char *in = NULL;
    explain_args e;
    memset(&e, 0, sizeof e);
    for (int i = 1; i < argc; i++) {
        int r = cli_opts_parse(explain_opts, CLI_COUNT(explain_opts), &e, "explain", argc, argv, &i);
        if (r < 0) return 2;
        if (e.help) { usage(stdout); return 0; }
        if (r == 0 && cli_operand("explain", argv[i], &in, usage)) return 2;
    }
    if (e.style_name) req.styles |= 1u << e.style;
    req.sketch_variant = e.sketch;
    req.outline = e.outline;
    req.lines = e.lines;
    if (e.features) req.want |= PNPR_WANT_ALL;
    const char *style = e.style_name, *segment_method = e.segment;
    pnpr_cloud c = {0};
    if (in) {
        pnpr_error err = {0};
        pnpr_status st = pnpr_read_file(in, NULL, &c, &err);
        if (st != PNPR_OK) { cli_report_error("explain", st, &err); return 1; }
        printf("%s: %zu points%s%s%s%s%s\n", in, c.count, c.rgb ? ", colours" : "", c.normal ? ", normals" : "",
               pnpr_plan_cloud_has(&c, PNPR_WANT_DEGREE) ? ", feature_degree" : "",
               pnpr_plan_cloud_has(&c, PNPR_WANT_CLASSES) ? ", feature classes" : "", c.label ? ", segment labels" : "");
    }
    pnpr_plan p;
    pnpr_status st = pnpr_plan_make(&req, in ? &c : NULL, &p);
    pnpr_cloud_free(&c);
    if (st != PNPR_OK) { fprintf(stderr, "pointnpr explain: %s\n", pnpr_status_string(st)); return 2; }
    row rows[10];
    int nr = plan_rows(&p, in != NULL, (req.styles >> PNPR_STYLE_BRUSH) & 1, segment_method, rows);
    printf("plan%s%s%s:\n", style ? " for --style " : "", style ? style : "", p.lines && !(style && !strcmp(style, "lines")) ? " + lines" : "");
    for (int r = 0; r < nr; r++) {
        printf("  %-16s %-5s %s", rows[r].stage, rows[r].run ? "run" : "skip", rows[r].why);
        if (!strcmp(rows[r].stage, "segments") && rows[r].run) printf(" (method %s)", segment_method ? segment_method : "jseg");
        printf("\n");
    }
    return 0;
}
