/* pointnpr explain: the stage plan for a requested output — which analysis stages run and why,
 * which are skipped, and which the input already carries (reused, not recomputed).
 *   pointnpr explain [IN] [--style S [--sketch a|b|c]] [--outline on|off] [--lines]
 *                         [--segment METHOD] [--features]
 * It prints the library's plan (pnpr_plan_make, plan.h): the one `render` and `lines` execute. */
#include "cli.h"

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

int cli_explain(int argc, char **argv)
{
    pnpr_plan_request req = {0};
    const char *in = NULL, *style = NULL, *segment_method = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            char names[160];
            printf("usage: pointnpr explain [IN] [--style %s]\n", pnpr_style_list(names, sizeof names, "|", 0));
            printf(
                   "                        [--sketch a|b|c] [--outline on|off] [--lines] [--segment METHOD]\n"
                   "                        [--features]\n"
                   "  prints the analysis stages the requested outputs need, and why; with IN, which of\n"
                   "  them the file already carries (reused, not recomputed). `render` and `lines` follow\n"
                   "  this plan.\n");
            return 0;
        } else if (v && !strcmp(a, "--style")) {
            pnpr_style s;
            if (pnpr_style_from_name(v, &s) != PNPR_OK) {
                char names[160];
                fprintf(stderr, "pointnpr explain: unknown style '%s' (%s)\n", v, pnpr_style_list(names, sizeof names, ", ", 0));
                return 2;
            }
            req.styles |= 1u << s;
            style = v;
            i++;
        } else if (v && !strcmp(a, "--sketch")) {
            if (strlen(v) != 1 || v[0] < 'a' || v[0] > 'c') { fprintf(stderr, "pointnpr explain: --sketch wants a, b or c, got '%s'\n", v); return 2; }
            req.sketch_variant = v[0] == 'a' ? PNPR_SKETCH_DIRECTIONAL : v[0] == 'b' ? PNPR_SKETCH_NONDIRECTIONAL : PNPR_SKETCH_ALL;
            i++;
        } else if (v && !strcmp(a, "--outline")) {
            if (strcmp(v, "on") && strcmp(v, "off")) { fprintf(stderr, "pointnpr explain: --outline wants on or off, got '%s'\n", v); return 2; }
            req.outline = !strcmp(v, "on") ? 1 : -1;
            i++;
        } else if (v && !strcmp(a, "--segment")) { segment_method = v; i++; }
        else if (!strcmp(a, "--lines")) req.lines = 1;
        else if (!strcmp(a, "--features")) req.want |= PNPR_WANT_ALL;
        else if (a[0] == '-' && a[1]) { fprintf(stderr, "pointnpr explain: unknown option or missing value: %s\n", a); return 2; }
        else if (!in) in = a;
        else { fprintf(stderr, "pointnpr explain: more than one input given ('%s')\n", a); return 2; }
    }
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
