/* pointnpr explain: the stage plan for a requested output — which analysis stages run and why,
 * which are skipped, and which the input already carries (reused, not recomputed).
 *   pointnpr explain [IN] [--style S [--sketch a|b|c]] [--lines] [--segment METHOD] [--features]
 * The plan is the one the commands follow: `render` computes features only for styles that need
 * them (and only when IN lacks them), `lines` asks for classes only (PNPR_WANT_CLASSES), `segment`
 * needs no features. */
#include "cli.h"

#include <pointnpr/features.h>

#include <stdio.h>
#include <string.h>

typedef struct plan {
    uint32_t want;        /* PNPR_WANT_* bits of the feature analysis */
    const char *why[5];   /* reason per want bit (index = bit number) */
    int lines, segments;
    const char *segment_method, *segment_why;
} plan;

static void need(plan *p, uint32_t bit, const char *why)
{
    int b = 0;
    while ((1u << b) != bit) b++;
    if (!(p->want & bit)) p->why[b] = why;
    p->want |= bit;
}

/* What each style needs (PointWorks section 5; docs/rendering.md). */
static int style_plan(plan *p, const char *style, const char *sketch)
{
    if (!strcmp(style, "points")) return 1;
    if (!strcmp(style, "sketchy")) {
        need(p, PNPR_WANT_CLASSES, "sketchy draws directional points as strokes along their direction");
        if (!sketch || !strcmp(sketch, "c")) need(p, PNPR_WANT_DITHER, "sketchy variant c draws dithering points as hatches");
        return 1;
    }
    if (!strcmp(style, "stipple")) {
        need(p, PNPR_WANT_DITHER, "stipple draws dithering and feature points as dots");
        return 1;
    }
    if (!strcmp(style, "painterly")) {
        need(p, PNPR_WANT_DEGREE, "painterly sorts points into feature-degree bins");
        need(p, PNPR_WANT_CLASSES, "painterly puts directional strokes on top");
        return 1;
    }
    if (!strcmp(style, "cartoon")) {
        p->segments = 1;
        p->segment_method = "jseg";
        p->segment_why = "cartoon fills each segment with its mean colour";
        return 1;
    }
    if (!strcmp(style, "lines")) {
        p->lines = 1;
        return 1;
    }
    return 0;
}

static int has_props(const pnpr_cloud *c, const char *const *names)
{
    for (; *names; names++)
        if (!pnpr_cloud_find_property(c, *names)) return 0;
    return 1;
}

int cli_explain(int argc, char **argv)
{
    plan p;
    memset(&p, 0, sizeof p);
    const char *in = NULL, *style = NULL, *sketch = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            printf("usage: pointnpr explain [IN] [--style points|sketchy|stipple|painterly|cartoon|lines]\n"
                   "                        [--sketch a|b|c] [--lines] [--segment METHOD] [--features]\n"
                   "  prints the analysis stages the requested outputs need, and why; with IN, which of\n"
                   "  them the file already carries (reused, not recomputed)\n");
            return 0;
        } else if (v && !strcmp(a, "--style")) { style = v; i++; }
        else if (v && !strcmp(a, "--sketch")) { sketch = v; i++; }
        else if (v && !strcmp(a, "--segment")) { p.segments = 1; p.segment_method = v; p.segment_why = "requested (--segment)"; i++; }
        else if (!strcmp(a, "--lines")) p.lines = 1;
        else if (!strcmp(a, "--features")) {
            need(&p, PNPR_WANT_NORMALS, "requested (--features: everything `pointnpr features` writes)");
            need(&p, PNPR_WANT_DITHER, "requested (--features)");
        }
        else if (a[0] == '-' && a[1]) { fprintf(stderr, "pointnpr explain: unknown option or missing value: %s\n", a); return 2; }
        else if (!in) in = a;
        else { fprintf(stderr, "pointnpr explain: more than one input given ('%s')\n", a); return 2; }
    }
    if (style && !style_plan(&p, style, sketch)) {
        fprintf(stderr, "pointnpr explain: unknown style '%s' (points, sketchy, stipple, painterly, cartoon, lines)\n", style);
        return 2;
    }
    if (p.lines) need(&p, PNPR_WANT_CLASSES, "profile lines connect directional points along their directions");
    /* wants imply their prerequisites */
    if (p.want & PNPR_WANT_DITHER) need(&p, PNPR_WANT_CLASSES, "dithering runs over the non-feature points");
    if (p.want & PNPR_WANT_CLASSES) need(&p, PNPR_WANT_DEGREE, "feature points are those above the degree threshold");

    int have_normals = 0, have_degree = 0, have_classes = 0, have_labels = 0, have_rgb = 0;
    if (in) {
        pnpr_cloud c = {0};
        pnpr_error err = {0};
        pnpr_status st = pnpr_read_file(in, NULL, &c, &err);
        if (st != PNPR_OK) { cli_report_error("explain", st, &err); return 1; }
        static const char *const deg[] = {"feature_degree", NULL};
        static const char *const cls[] = {"feature_class", "feature_dir_x", "feature_dir_y", "feature_dir_z", NULL};
        have_normals = c.normal != NULL;
        have_degree = has_props(&c, deg);
        have_classes = has_props(&c, cls);
        have_labels = c.label != NULL;
        have_rgb = c.rgb != NULL;
        printf("%s: %zu points%s%s%s%s%s\n", in, c.count, have_rgb ? ", colours" : "", have_normals ? ", normals" : "",
               have_degree ? ", feature_degree" : "", have_classes ? ", feature classes" : "", have_labels ? ", segment labels" : "");
        pnpr_cloud_free(&c);
    }
    int features_in_input = have_classes && have_degree;
    uint32_t want = p.want;
    if (in && features_in_input && !(want & PNPR_WANT_NORMALS)) want = 0; /* all reused */
    if (in && want == PNPR_WANT_NORMALS && have_normals) want = 0;
    int dither_needs_orient = (want & PNPR_WANT_DITHER) && !have_rgb;
    struct { const char *stage; int run; const char *why; } rows[9];
    int nr = 0;
#define ROW(s, r, w) do { rows[nr].stage = (s); rows[nr].run = (r); rows[nr].why = (w); nr++; } while (0)
    const char *reuse = "the input carries the features: reused";
    ROW("kd-tree + knn", want != 0, want ? "neighbourhoods for every stage below" : (p.want && in ? reuse : "no analysis requested"));
    ROW("normals (PCA)", want != 0, want ? (want & PNPR_WANT_NORMALS ? p.why[0] : "its plane-fit error drives the feature degree") : (p.want && in ? reuse : "not needed"));
    ROW("orient", (want & PNPR_WANT_NORMALS) || dither_needs_orient,
        (want & PNPR_WANT_NORMALS) ? p.why[0] : (dither_needs_orient ? "no colours: dithering takes the tone from oriented normals" : "no output needs oriented normals"));
    ROW("feature degree", (want & PNPR_WANT_DEGREE) != 0, want & PNPR_WANT_DEGREE ? p.why[1] : (p.want && in ? reuse : "not needed"));
    ROW("classify", (want & PNPR_WANT_CLASSES) != 0, want & PNPR_WANT_CLASSES ? p.why[2] : (p.want && in ? reuse : "not needed"));
    ROW("dither", (want & PNPR_WANT_DITHER) != 0,
        want & PNPR_WANT_DITHER ? p.why[3] : (p.want & PNPR_WANT_DITHER && in ? reuse : "no output draws dithering points"));
    ROW("profile lines", p.lines, p.lines ? (style && !strcmp(style, "lines") ? "the lines style draws them" : "requested (--lines)") : "not requested");
    ROW("segments", p.segments && !(have_labels && in), p.segments ? (have_labels && in ? "the input carries segment labels: reused" : p.segment_why) : "not requested");
#undef ROW
    printf("plan%s%s%s:\n", style ? " for --style " : "", style ? style : "", p.lines && !(style && !strcmp(style, "lines")) ? " + lines" : "");
    for (int r = 0; r < nr; r++) {
        printf("  %-16s %-5s %s", rows[r].stage, rows[r].run ? "run" : "skip", rows[r].why);
        if (r == nr - 1 && rows[r].run) printf(" (method %s)", p.segment_method);
        printf("\n");
    }
    return 0;
}
