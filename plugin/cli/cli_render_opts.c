/* The options of a stylised frame shared by `render` and `animate` (style, draw, tone, outline,
 * background, view, outliers), their usage lines, and the steps from a file to pixels: read, the
 * stage plan, the GL context and renderer, one snapshot. One place, so the two commands draw
 * the same frame from the same options. The options and the reading are built without the
 * renderer too (`animate --save-path` without -o needs only them); the steps that draw need it
 * (PNPR_HAVE_RENDER). */
#include "cli_render.h"
#include "cli_opts.h"

#include <pointnpr/look.h>

#include <pointnpr/features.h>
#include <pointnpr/lines.h>
#include <pointnpr/plan.h>
#include <pointnpr/segment.h>

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The options read from the library's tables (options.h, pnpr_draw_option_table and
 * pnpr_upload_option_table), and their metavars: usage lines, defaults, ranges and parsing. */
static const char *const draw_names[] = {"stroke-texture", "stroke-max", "density", "point-scale", "line-width", "line-min",
                                         "dot-size", "queue-fade", "levels", "outline-scale", "outline-width",
                                         "outline-jump", "outline-hole", "faint", "brush-scale", "brush-jitter", "brush-blur",
                                         NULL};
static const char *const upload_names[] = {"paint-bins", NULL};
static const char *const brush_names[] = {"brush-k", "brush-eps", "brush-normal-radius", NULL};
static const char *const hier_names[] = {"hier-abstraction", "stroke-px", "stroke-radius", "stroke-scale", "stroke-stretch",
                                         "no-smooth", "node-colour", "node-direction", "noise-angle", "noise-colour",
                                         "silhouette-deg", "borders", "hier-layers", NULL};
static const char *const tone_names[] = {"tone-gamma", "tone-contrast", NULL};
static const char *const tree_names[] = {"hier-spacing", "hier-leaf-factor", "hier-k", "hier-features",
                                         "hier-max-variation", NULL};

/* ---- the CLI's own render options (cli_opts.h): one entry each, parsed and described there ---- */

static int parse_brush(void *member, const char *cmd, const char *v)
{
    uint32_t b;
    char names[160];
    if (pnpr_brush_preset_find(v, &b) == PNPR_OK) { *(int *)member = (int)b; return 1; }
    fprintf(stderr, "pointnpr %s: --brush wants %s, got '%s'\n", cmd, pnpr_brush_preset_list(names, sizeof names, " | "), v);
    return 0;
}

static int parse_tam(void *member, const char *cmd, const char *v)
{
    int k = pnpr_tam_find(v);
    if (k >= 0) { *(int *)member = k; return 1; }
    fprintf(stderr, "pointnpr %s: --tam wants %s, %s or %s, got '%s'\n", cmd, pnpr_tam_name(PNPR_TAM_PAINT),
            pnpr_tam_name(PNPR_TAM_HATCH), pnpr_tam_name(PNPR_TAM_DOTS), v);
    return 0;
}

static int parse_layering(void *opts, const char *cmd, const char *v)
{
    cli_render_opts *o = opts;
    if (pnpr_layering_from_name(v, &o->layering) == PNPR_OK) { o->have_layering = 1; return 1; }
    fprintf(stderr, "pointnpr %s: --layering wants inpainted, fragment or none, got '%s'\n", cmd, v);
    return 0;
}

static int parse_effects_scale(void *opts, const char *cmd, const char *v)
{
    cli_render_opts *o = opts;
    double x;
    if (cli_parse_number(v, PNPR_EFFECTS_SCALE_MIN, 1, &x)) { o->fx_opts.scale = (float)x; o->have_fx_opts = 1; return 1; }
    fprintf(stderr, "pointnpr %s: --effects-scale wants a number in %g..1, got '%s'\n", cmd, (double)PNPR_EFFECTS_SCALE_MIN, v);
    return 0;
}

/* --budget N | all: "all" lifts the screen-space budget too (--density), checked in finish */
static int parse_budget(void *opts, const char *cmd, const char *v)
{
    cli_render_opts *o = opts;
    double x;
    if (!strcmp(v, "all")) { o->dopt.budget = 0; o->budget_all = 1; return 1; }
    if (cli_parse_number(v, 1, 4e9, &x) && x == floor(x)) { o->dopt.budget = (size_t)x; o->budget_all = 0; return 1; }
    fprintf(stderr, "pointnpr %s: --budget wants a positive integer or 'all', got '%s'\n", cmd, v);
    return 0;
}

static int parse_seed(void *member, const char *cmd, const char *v)
{
    char *end;
    errno = 0;
    unsigned long long s = strtoull(v, &end, 10);
    if (!errno && end != v && !*end && v[0] != '-') { *(uint64_t *)member = s; return 1; }
    fprintf(stderr, "pointnpr %s: --seed wants a non-negative integer, got '%s'\n", cmd, v);
    return 0;
}

static int parse_light(void *member, const char *cmd, const char *v)
{
    double *l = member;
    if (cli_parse_list(v, 3, l) && (l[0] != 0 || l[1] != 0 || l[2] != 0)) return 1;
    fprintf(stderr, "pointnpr %s: --light wants a non-zero direction X,Y,Z, got '%s'\n", cmd, v);
    return 0;
}

static int parse_background(void *member, const char *cmd, const char *v)
{
    double *bg = member;
    if (cli_parse_list(v, 3, bg) && bg[0] >= 0 && bg[0] <= 255 && bg[1] >= 0 && bg[1] <= 255 && bg[2] >= 0 && bg[2] <= 255)
        return 1;
    fprintf(stderr, "pointnpr %s: --background wants R,G,B in 0..255, got '%s'\n", cmd, v);
    return 0;
}

static int parse_look(void *member, const char *cmd, const char *v)
{
    size_t i = 0;
    if (pnpr_look_find(v, &i) == PNPR_OK) {
        *(int *)member = (int)i + 1;
        return 1;
    }
    char names[200];
    fprintf(stderr, "pointnpr %s: --look wants one of %s, got '%s'\n", cmd, pnpr_look_list(names, sizeof names, ", "), v);
    return 0;
}

/* --style, remembered as given (member is dopt.style inside cli_render_opts) */
static int parse_render_style(void *member, const char *cmd, const char *v)
{
    cli_render_opts *o = (cli_render_opts *)(void *)((char *)member - offsetof(cli_render_opts, dopt.style));
    o->style_given = 1;
    return cli_parse_style(member, cmd, v);
}

static const char *const tone_sources[] = {"auto", "color", "light", "both", NULL}; /* pnpr_tone_source */

#define R_OPT(name, kind, member, parse, metavar, help)                                                              \
    {name, NULL, kind, offsetof(cli_render_opts, member), 0, 0, 0, 0, NULL, parse, metavar, help}
static const cli_opt render_opts[] = {
    {"--style", NULL, CLI_CUSTOM, offsetof(cli_render_opts, dopt.style), 0, 0, 0, 0, NULL, parse_render_style, "S",
     "the drawing style (docs/rendering.md)"},
    R_OPT("--look", CLI_CUSTOM, look, parse_look, "NAME",
          "a finished look: a style with its variant, outline, widths, ink and paper (the library's looks, "
          "docs/rendering.md \"Looks\"; a wrong name lists them); the options given beside it win"),
    R_OPT("--style-map", CLI_TEXT, style_map_path, NULL, "FILE",
          "intermingled styles: FILE has lines 'LABEL STYLE' (a segment label of IN, PLY property segment or "
          "label) and '* STYLE' (the default, else --style); '#' starts a comment"),
    R_OPT("--effects", CLI_TEXT, effects_path, NULL, "FILE",
          "segment-specific image-space effects (docs/effects.md): FILE gives segments (labels) effect chains "
          "(toon, watercolour, oil, pencil, posterise, grade, edges, smooth) and presets; one layer each, "
          "depth-inpainted and composited with a depth test"),
    {"--layering", NULL, CLI_CUSTOM, 0, 0, 0, 0, 0, NULL, parse_layering, "M",
     "effects: inpainted (default) | fragment | none (paper figure 12)"},
    {"--effects-scale", NULL, CLI_CUSTOM, 0, 0, 0, 0, 0, NULL, parse_effects_scale, "S",
     "effects: layers at S (1/16..1) of the size, grown to it: a quick draft of a pipeline (the decorator's "
     "preview while moving)"},
    R_OPT("--effects-serial", CLI_FLAG, fx_opts.serial, NULL, NULL,
          "effects: filters on the GL thread, not overlapped with the next layer's rasterisation (the same "
          "pixels; for measurements)"),
    CLI_SKETCH_OPT(cli_render_opts, dopt.sketch_variant),
    {"--budget", NULL, CLI_CUSTOM, 0, 0, 0, 0, 0, NULL, parse_budget, "N|all",
     "at most N points sent per frame, the near cells thinned first (default: no count, the screen-space "
     "budget --density only); all: every point, however dense the view"},
    R_OPT("--seed", CLI_CUSTOM, uopt.seed, parse_seed, "S", "continuous resolution queue seed (default 0)"),
    {"--sample", NULL, CLI_NUMBER, offsetof(cli_render_opts, sample), 0, 1, 1, 0, NULL, NULL, "S",
     "read a sample of this share of a binary PLY's points, a preview of a cloud larger than memory: uniform, "
     "or by the view with a camera (render --eye/--target or --camera-path; animate: its frames; near points "
     "kept, far and unseen ones thinned) (default: every point, or the share that fits --memory-limit; "
     "docs/tiles.md)"},
    {"--tone", NULL, CLI_CHOICE, offsetof(cli_render_opts, tone.source), 0, 0, 0, 0, tone_sources, NULL, NULL,
     "what sets how dark a point is drawn (hatch and stipple density, the shading of colourless clouds): "
     "a key light on the normals, the colours, or both (default auto: both when IN has colours)"},
    R_OPT("--light", CLI_CUSTOM, tone.light, parse_light, "X,Y,Z",
          "direction towards the key light (default: from above, front left)"),
    CLI_OUTLINE_OPT(cli_render_opts, dopt.outline,
                    "silhouettes and occluding contours (default: the style's, pnpr_style_outline_default; "
                    "sketchy reads well with them on)"),
    R_OPT("--brush", CLI_CUSTOM, dopt.brush_preset, parse_brush, "B", "brush: the brush preset (docs/brush.md)"),
    R_OPT("--tam", CLI_CUSTOM, dopt.hierarchy.tam, parse_tam, "M", "hierarchy: the tonal art map (docs/hierarchy.md)"),
    R_OPT("--importance", CLI_TEXT, importance_path, NULL, "FILE",
          "hierarchy: a grey PNG stretched over the image: white keeps detail (every colour region, strokes "
          "half the size), black abstracts"),
    R_OPT("--background", CLI_CUSTOM, bg, parse_background, "R,G,B",
          "background colour, 0..255 each (default 255,255,255)"),
    R_OPT("--alpha", CLI_FLAG, alpha, NULL, NULL, "transparent background, PNG with alpha"),
    {"--max-tile", NULL, CLI_INT, offsetof(cli_render_opts, max_tile), 16, 1e6, 0, 0, NULL, NULL, "PX",
     "render in tiles of at most PX pixels (default: the GL limit; larger images are always tiled, progress "
     "per tile on stderr)"},
    R_OPT("--quiet", CLI_FLAG, quiet, NULL, NULL, "no progress on stderr"),
};

/* The usage line of render_opts' entry `name`. */
static void opt_usage(FILE *f, const char *name)
{
    const cli_opt *o = cli_opts_find(render_opts, CLI_COUNT(render_opts), name);
    if (o) cli_opts_usage(f, o, 1);
}

static void draw_usage(FILE *f, const char *name, const char *metavar)
{
    size_t n;
    const pnpr_option_desc *t = pnpr_draw_option_table(&n);
    cli_table_usage(f, t, n, name, metavar);
}

void cli_render_usage(FILE *f, int width, int height)
{
    float w_lines = 0, w_cartoon = 0, w_sketchy = 0; /* the outline widths, as the library says */
    pnpr_style_outline_default(PNPR_STYLE_LINES, &w_lines);
    pnpr_style_outline_default(PNPR_STYLE_CARTOON, &w_cartoon);
    pnpr_style_outline_default(PNPR_STYLE_SKETCHY, &w_sketchy);
    size_t un, bn;
    const pnpr_option_desc *ut = pnpr_upload_option_table(&un), *bt = pnpr_brush_option_table(&bn);
    char styles[160], brushes[160];
    char more[256];
    opt_usage(f, "--style");
    snprintf(more, sizeof more, "(%s; default %s)", pnpr_style_list(styles, sizeof styles, " | ", 0),
             pnpr_style_name((pnpr_style)0));
    cli_usage_more(f, more);
    char looks[200];
    opt_usage(f, "--look");
    snprintf(more, sizeof more, "(%s)", pnpr_look_list(looks, sizeof looks, " | "));
    cli_usage_more(f, more);
    static const char *const first[] = {"--style-map", "--effects", "--layering", "--effects-scale",
                                        "--effects-serial", "--sketch"};
    for (size_t k = 0; k < sizeof first / sizeof first[0]; k++) opt_usage(f, first[k]);
    draw_usage(f, "stroke-texture", "T");
    fprintf(f,
            "  --size WxH           image size in pixels (default %dx%d)\n"
            "  --eye X,Y,Z --target X,Y,Z\n"
            "                       look-at camera in world coordinates (default: the default view,\n"
            "                       from above the detected ground, framing the content; docs/view.md)\n"
            "  --up auto|x|y|z|-x|-y|-z|X,Y,Z\n"
            "                       the up axis (default auto: the file's convention, else the ground\n"
            "                       plane, else z; with --eye/--target a vector, default 0,0,1)\n"
            "  --fov DEG            vertical field of view (default 45)\n"
            "  --camera FILE        the camera from a file (eye/target/up/fov lines, world coordinates)\n",
            width, height);
    opt_usage(f, "--budget");
    draw_usage(f, "density", "D");
    cli_usage_more(f, "(negative: no limit, as --budget all)");
    opt_usage(f, "--seed");
    opt_usage(f, "--sample");
    draw_usage(f, "point-scale", "F");
    draw_usage(f, "stroke-max", "PX");
    draw_usage(f, "line-width", "PX");
    draw_usage(f, "line-min", "PX");
    draw_usage(f, "dot-size", "PX");
    draw_usage(f, "queue-fade", "F");
    cli_usage_more(f, "(0 = none: under a budget, marks pop in and out)");
    draw_usage(f, "levels", "N");
    draw_usage(f, "outline-scale", "F");
    opt_usage(f, "--tone");
    size_t on;
    const pnpr_option_desc *ot = pnpr_tone_option_table(&on);
    cli_table_usage(f, ot, on, "tone-gamma", "G");
    cli_table_usage(f, ot, on, "tone-contrast", "C");
    opt_usage(f, "--light");
    opt_usage(f, "--outline");
    draw_usage(f, "outline-width", "PX");
    fprintf(f, "                       (the style's: lines %g, cartoon %g, sketchy %g)\n", (double)w_lines,
            (double)w_cartoon, (double)w_sketchy);
    draw_usage(f, "outline-jump", "F");
    draw_usage(f, "outline-hole", "F");
    cli_table_usage(f, ut, un, "paint-bins", "N");
    opt_usage(f, "--brush");
    snprintf(more, sizeof more, "(%s; default %s)", pnpr_brush_preset_list(brushes, sizeof brushes, " | "),
             pnpr_brush_presets(NULL)[0].name);
    cli_usage_more(f, more);
    draw_usage(f, "brush-scale", "F");
    draw_usage(f, "brush-jitter", "DEG");
    draw_usage(f, "brush-blur", "PX");
    cli_table_usage(f, bt, bn, "brush-k", "K");
    cli_table_usage(f, bt, bn, "brush-eps", "E");
    cli_table_usage(f, bt, bn, "brush-normal-radius", "F");
    opt_usage(f, "--tam");
    snprintf(more, sizeof more, "(%s | %s | %s; default %s)", pnpr_tam_name(PNPR_TAM_PAINT),
             pnpr_tam_name(PNPR_TAM_HATCH), pnpr_tam_name(PNPR_TAM_DOTS), pnpr_tam_name(PNPR_TAM_PAINT));
    cli_usage_more(f, more);
    size_t hn, tn;
    const pnpr_option_desc *ht = pnpr_hier_option_table(&hn), *tt = pnpr_sphere_tree_option_table(&tn);
    static const char *const hier_meta[] = {"A", "PX", "R", "F", "F", "0|1", "0|1", "0|1", "DEG", "F", "DEG", "L", "N"};
    for (int k = 0; hier_names[k]; k++) cli_table_usage(f, ht, hn, hier_names[k], hier_meta[k]);
    static const char *const tree_meta[] = {"H", "F", "K", "F", "F"};
    for (int k = 0; tree_names[k]; k++) cli_table_usage(f, tt, tn, tree_names[k], tree_meta[k]);
    opt_usage(f, "--importance");
    draw_usage(f, "faint", "F");
    static const char *const last[] = {"--background", "--alpha", "--max-tile", "--quiet"};
    for (size_t k = 0; k < sizeof last / sizeof last[0]; k++) opt_usage(f, last[k]);
    fprintf(f,
            "  What IN lacks is computed as `pointnpr explain IN --style S` shows: features for sketchy,\n"
            "  stipple, painterly and lines (+ the profile lines), normals for outlines and for shading\n"
            "  colourless clouds, JSEG segments for cartoon when IN has colours but no segment labels,\n"
            "  brush sizes, colour clusters and normals for brush, the sphere hierarchy for hierarchy.\n");
    cli_outlier_usage(f);
    cli_memory_usage(f);
    cli_columns_usage(f);
}


/* Loads the text file of option `opt` (at most max bytes). Returns 0 after a message. */
static int load_text(const char *cmd, const char *opt, const char *path, size_t max, char **r_text, size_t *r_size)
{
    pnpr_error err = {0};
    pnpr_status st = pnpr_text_file_load(path, max, r_text, r_size, &err);
    size_t n = strlen(path);
    if (st == PNPR_OK) return 1;
    const char *why = !strncmp(err.message, path, n) && !strncmp(err.message + n, ": ", 2) ? err.message + n + 2 : err.message;
    fprintf(stderr, "pointnpr %s: %s: cannot open '%s': %s\n", cmd, opt, path, why);
    return 0;
}

/* Reads a style map file (pnpr_style_map_parse, style.h). Returns 0 after a message naming the
 * line on a bad line. */
static int read_style_map(const char *cmd, const char *path, pnpr_style_map *r_map)
{
    char *text = NULL;
    size_t size = 0;
    if (!load_text(cmd, "--style-map", path, PNPR_STYLE_MAP_FILE_MAX, &text, &size)) return 0;
    pnpr_error err = {0};
    pnpr_status st = pnpr_style_map_parse(text, size, path, r_map, &err);
    free(text);
    if (st != PNPR_OK) fprintf(stderr, "pointnpr %s: --style-map %s\n", cmd, err.message);
    return st == PNPR_OK;
}

/* Reads an effects pipeline file (pnpr_effect_pipeline_parse, effects.h); the same. */
static int read_effects(const char *cmd, const char *path, pnpr_effect_pipeline *r_pipe)
{
    char *text = NULL;
    size_t size = 0;
    if (!load_text(cmd, "--effects", path, PNPR_EFFECT_PIPELINE_FILE_MAX, &text, &size)) return 0;
    pnpr_error err = {0};
    pnpr_status st = pnpr_effect_pipeline_parse(text, size, path, r_pipe, &err);
    free(text);
    if (st != PNPR_OK) fprintf(stderr, "pointnpr %s: --effects %s\n", cmd, err.message);
    return st == PNPR_OK;
}

/* The most points a frame draws: the screen-space budget (--density x the image's pixels, at most
 * --budget); 0 = every point. */
static size_t frame_points(const cli_render_opts *o)
{
    size_t dn;
    const pnpr_option_desc *dt = pnpr_draw_option_table(&dn);
    pnpr_draw_options d = o->dopt;
    pnpr_option_fill_defaults(dt, dn, &d);
    double frame = d.density < 0 ? 0 : (double)d.density * o->view.width * o->view.height;
    if (d.budget > 0 && (frame == 0 || (double)d.budget < frame)) frame = (double)d.budget;
    return frame >= 1e18 ? (size_t)1e18 : (size_t)frame;
}

/* The styles of the frame (the pipeline's, or the style and its map) as bits 1u << style. */
static uint32_t style_bits(const cli_render_opts *o)
{
    uint32_t bits = 0;
    for (int s = 0; s < PNPR_STYLE_COUNT_; s++)
        if (o->uses[s]) bits |= 1u << s;
    return bits;
}

/* The stage plan of the styles this frame draws for `cloud` (the features it lacks, the cartoon's
 * segments) and the memory plan of what is left to do once it is read (memory.h). */
static pnpr_status memory_plan(const cli_render_opts *o, const pnpr_cloud *cloud, pnpr_plan *r_plan,
                               pnpr_memory_plan *r_mp)
{
    pnpr_plan_request req = {0};
    req.styles = style_bits(o);
    req.sketch_variant = o->dopt.sketch_variant;
    req.outline = o->dopt.outline;
    pnpr_status st = pnpr_plan_make(&req, cloud, r_plan);
    *r_mp = (pnpr_memory_plan){cloud->count, r_plan->want ? pnpr_features_defaults().k : 0,
                               r_plan->want && !cloud->normal, r_plan->segments == PNPR_PLAN_SEGMENTS_JSEG,
                               req.styles, o->view.width, o->view.height, frame_points(o)};
    return st;
}

/* cli_plan_fn for cli_read_fitting: the stages a sample of the file will run, from its header's
 * properties (a read that keeps no point). */
static void sample_plan(const pnpr_cloud *header, void *user, pnpr_memory_plan *mp)
{
    pnpr_plan plan;
    pnpr_memory_plan m;
    if (memory_plan(user, header, &plan, &m) != PNPR_OK) return;
    mp->features_k = m.features_k;
    mp->normals_stored = m.normals_stored;
    mp->segments = m.segments;
}

#ifdef PNPR_HAVE_RENDER
/* Progress of a tiled snapshot: one line per tile (single-frame images print nothing). */
static int tile_progress(void *user, const char *stage, double fraction)
{
    (void)user;
    if (strcmp(stage, "tile 1/1") != 0) fprintf(stderr, "render: %s (%.0f %%)\n", stage, 100.0 * fraction);
    return 0;
}

/* Runs the stage plan (pnpr_plan_make, the one `pointnpr explain` prints) for the styles this
 * frame draws: features (only the outputs the styles need, the dithering following `tone`) and
 * the cartoon's segments. Returns 0 after printing why. */
static int run_plan(const char *cmd, const char *in, pnpr_cloud *cloud, pnpr_sphere_tree *tree, const cli_render_opts *o, int quiet,
                    pnpr_progress prog)
{
    pnpr_plan plan;
    pnpr_memory_plan mp;
    pnpr_status st = memory_plan(o, cloud, &plan, &mp);
    /* what is left to do must fit (memory.h), before any of it */
    if (st == PNPR_OK && !cli_memory_check_plan(cmd, in, o->memory_limit, &mp)) return 0;
    if (st == PNPR_OK && plan.want) {
        if (!quiet) fprintf(stderr, "%s: computing %s (pointnpr explain shows the plan; pointnpr features saves them)\n", in,
                            (plan.want & ~(uint32_t)(PNPR_WANT_NORMALS | PNPR_WANT_NORMALS_ANY)) ? "features" : "normals");
        pnpr_features_options fo = {0};
        fo.progress = prog;
        fo.want = plan.want;
        fo.tone = o->tone;
        st = pnpr_compute_features(cloud, &fo, NULL);
    }
    if (st != PNPR_OK) { fprintf(stderr, "pointnpr %s: %s: features: %s\n", cmd, in, pnpr_status_string(st)); return 0; }
    if (plan.brush && cloud->count > 0) {
        if (!quiet) fprintf(stderr, "%s: preparing the brush strokes (sizes, colour clusters, normals)\n", in);
        pnpr_brush_options bo = o->bopt;
        bo.progress = prog;
        pnpr_brush_stats bs;
        pnpr_error err = {0};
        if ((st = pnpr_brush_prepare(cloud, &bo, &bs, &err)) != PNPR_OK) {
            fprintf(stderr, "pointnpr %s: %s: %s\n", cmd, in, err.message);
            return 0;
        }
        if (!quiet) fprintf(stderr, "%s: %zu clusters, mean brush size %.4g\n", in, bs.clusters, bs.mean_size);
    }
    if (plan.hierarchy) {
        if (!quiet) fprintf(stderr, "%s: building the sphere hierarchy (leaf spheres, regions, their merges)\n", in);
        pnpr_sphere_tree_options to = o->topt;
        to.progress = prog;
        to.use_labels = cloud->label != NULL;
        pnpr_sphere_tree_stats ts;
        pnpr_error err = {0};
        if ((st = pnpr_sphere_tree_build(cloud, &to, tree, &ts, &err)) != PNPR_OK) {
            fprintf(stderr, "pointnpr %s: %s: %s\n", cmd, in, err.message);
            return 0;
        }
        if (!quiet)
            fprintf(stderr, "%s: %zu leaf spheres, %zu regions, %zu nodes (%.2f s)\n", in, ts.leaves, ts.regions, ts.nodes,
                    ts.seconds);
    }
    if (plan.segments != PNPR_PLAN_SEGMENTS_JSEG || cloud->count == 0) return 1;
    if (!quiet) fprintf(stderr, "%s: segmenting the colours (JSEG) for the cartoon's flat regions (pointnpr segment saves them)\n", in);
    if ((st = pnpr_cloud_alloc_labels(cloud)) == PNPR_OK) {
        pnpr_jseg_options jo = {0};
        jo.progress = prog;
        pnpr_segment_info info;
        st = pnpr_segment_jseg(cloud->xyz, cloud->rgb, cloud->count, &jo, cloud->label, &info);
        if (st == PNPR_OK && !quiet) fprintf(stderr, "%s: %u segments\n", in, (unsigned)info.segment_count);
    }
    if (st != PNPR_OK) { fprintf(stderr, "pointnpr %s: %s: segments: %s\n", cmd, in, pnpr_status_string(st)); return 0; }
    return 1;
}

/* The profile lines of the lines style, handed to the renderer. Returns 0 after printing why. */
static int set_profile_lines(const char *cmd, const char *in, const pnpr_cloud *cloud, pnpr_renderer *ren, int quiet, pnpr_progress prog)
{
    pnpr_polylines lines = {0};
    pnpr_lines_options lo = {0};
    lo.progress = prog;
    pnpr_lines_stats ls;
    pnpr_error err = {0};
    pnpr_status st = pnpr_profile_lines(cloud, &lo, &lines, &ls);
    if (st != PNPR_OK) { fprintf(stderr, "pointnpr %s: %s: profile lines: %s\n", cmd, in, pnpr_status_string(st)); return 0; }
    if (!quiet) fprintf(stderr, "%s: %zu profile lines, total length %.6g\n", in, lines.count, ls.total_length);
    st = pnpr_renderer_set_lines(ren, &lines, &err);
    pnpr_lines_free(&lines);
    if (st != PNPR_OK) { cli_report_error(cmd, st, &err); return 0; }
    return 1;
}
#endif


/* The options of the tables (draw_names, upload_names): values in the table's range. --queue-fade 0
 * means none (a negative queue_fade). As cli_table_option. */
static int table_option(cli_render_opts *o, const char *cmd, int argc, char **argv, int *ip)
{
    size_t dn, un;
    const pnpr_option_desc *dt = pnpr_draw_option_table(&dn), *ut = pnpr_upload_option_table(&un);
    size_t bn;
    const pnpr_option_desc *bt = pnpr_brush_option_table(&bn);
    int r = cli_table_option(dt, dn, draw_names, &o->dopt, cmd, argc, argv, ip);
    if (r == 0) r = cli_table_option(ut, un, upload_names, &o->uopt, cmd, argc, argv, ip);
    if (r == 0) r = cli_table_option(bt, bn, brush_names, &o->bopt, cmd, argc, argv, ip);
    size_t hn, tn;
    const pnpr_option_desc *ht = pnpr_hier_option_table(&hn), *tt = pnpr_sphere_tree_option_table(&tn);
    if (r == 0) r = cli_table_option(ht, hn, hier_names, &o->dopt.hierarchy, cmd, argc, argv, ip);
    if (r == 0) r = cli_table_option(tt, tn, tree_names, &o->topt, cmd, argc, argv, ip);
    size_t on;
    const pnpr_option_desc *ot = pnpr_tone_option_table(&on);
    if (r == 0) r = cli_table_option(ot, on, tone_names, &o->tone, cmd, argc, argv, ip);
    if (r > 0 && !strcmp(argv[*ip - 1], "--queue-fade") && o->dopt.queue_fade == 0) o->dopt.queue_fade = -1.0f;
    return r;
}

int cli_render_option(cli_render_opts *o, const char *cmd, int argc, char **argv, int *ip)
{
    int r = cli_view_option(&o->view, cmd, argc, argv, ip);
    if (r == 0) r = cli_outlier_option(&o->outliers, cmd, argc, argv, ip);
    if (r == 0) r = cli_columns_option(&o->columns, cmd, argc, argv, ip);
    if (r == 0) r = cli_memory_option(&o->memory_limit, cmd, argc, argv, ip);
    if (r == 0) r = table_option(o, cmd, argc, argv, ip);
    if (r == 0) r = cli_opts_parse(render_opts, CLI_COUNT(render_opts), o, cmd, argc, argv, ip);
    return r;
}

void cli_render_opts_init(cli_render_opts *o, int width, int height)
{
    memset(o, 0, sizeof *o);
    cli_view_init(&o->view, width, height);
    o->bg[0] = -1; /* not given */
}

int cli_render_opts_finish(cli_render_opts *o, const char *cmd)
{
    if (!cli_view_check(&o->view, cmd)) return 0;
    if (o->fx_opts.serial) o->have_fx_opts = 1; /* --effects-serial */
    if (o->budget_all && o->dopt.density != 0) {
        fprintf(stderr, "pointnpr %s: --budget all draws every point and --density limits them; give one\n", cmd);
        return 0;
    }
    if (o->budget_all) o->dopt.density = -1; /* no screen-space budget (render.h) */
    if (o->look && o->style_given) {
        fprintf(stderr, "pointnpr %s: --look chooses the style; give --look or --style\n", cmd);
        return 0;
    }
    if (o->bg[0] >= 0) { /* given (black too: opaque, so the look keeps it) */
        for (int c = 0; c < 3; c++) o->dopt.background[c] = (float)(o->bg[c] / 255.0);
        o->dopt.background[3] = 1;
    }
    if (o->look) pnpr_look_apply(&pnpr_looks(NULL)[o->look - 1], &o->dopt); /* fills what was not given */
    if (o->bg[0] < 0 && !o->look) o->dopt.background[0] = o->dopt.background[1] = o->dopt.background[2] = 1;
    o->dopt.background[3] = o->alpha ? 0.0f : 1.0f;
    if (o->style_map_path && !read_style_map(cmd, o->style_map_path, &o->smap)) return 0;
    if (o->smap.have_default) o->dopt.style = o->smap.default_style;
    o->dopt.style_map = o->smap.entries;
    o->dopt.style_map_count = o->smap.count;
#ifdef PNPR_HAVE_RENDER
    if (o->importance_path) {
        pnpr_error err = {0};
        int w = 0, h = 0;
        if (pnpr_read_png_grey(o->importance_path, &o->importance, &w, &h, &err) != PNPR_OK) {
            fprintf(stderr, "pointnpr %s: --importance %s\n", cmd, err.message);
            return 0;
        }
        o->dopt.hierarchy.importance = o->importance;
        o->dopt.hierarchy.importance_w = w;
        o->dopt.hierarchy.importance_h = h;
    }
#endif
    memset(o->uses, 0, sizeof o->uses); /* the default and the mapped styles */
    o->uses[o->dopt.style] = 1;
    for (size_t m = 0; m < o->smap.count; m++) o->uses[o->smap.entries[m].style] = 1;
    if ((o->have_layering || o->have_fx_opts) && !o->effects_path) {
        const char *opt = o->have_layering ? "--layering" : o->fx_opts.scale > 0 ? "--effects-scale" : "--effects-serial";
        fprintf(stderr, "pointnpr %s: %s is for --effects FILE\n", cmd, opt);
        return 0;
    }
    if (!o->effects_path) return 1;
    if (o->style_map_path) {
        fprintf(stderr, "pointnpr %s: --effects and --style-map both choose styles per segment; give one\n", cmd);
        return 0;
    }
    if (!read_effects(cmd, o->effects_path, &o->fx)) return 0;
    if (o->have_layering) o->fx.layering = o->layering;
    memset(o->uses, 0, sizeof o->uses); /* the styles of the pipeline's nodes */
    for (size_t k = 0; k < o->fx.count; k++) o->uses[o->fx.nodes[k].style] = 1;
    return 1;
}

void cli_render_opts_free(cli_render_opts *o)
{
    free(o->importance);
    o->importance = NULL;
    pnpr_style_map_free(&o->smap);
    pnpr_effect_pipeline_free(&o->fx);
}

int cli_render_load(cli_render_session *s, const cli_render_opts *o, const char *cmd, const char *in,
                    const cli_sample_views *views)
{
    memset(s, 0, sizeof *s);
    s->prog.fn = o->quiet ? NULL : cli_progress_stderr;
    s->prog.user = &s->ps;
    pnpr_read_options ro = {0};
    ro.progress = s->prog;
    ro.columns = o->columns;
    pnpr_memory_plan mp = {0, 0, 0, 0, style_bits(o), o->view.width, o->view.height, 0};
    mp.drawn = frame_points(o);
    if (!cli_read_fitting(cmd, in, &ro, &mp, sample_plan, (void *)o, o->memory_limit, o->sample, views, (double)mp.drawn,
                          o->quiet, &s->cloud, &s->tone_radius))
        return 0;
    return cli_outliers_apply(&o->outliers, cmd, in, &s->cloud, o->quiet, NULL) == 0;
}

#ifdef PNPR_HAVE_RENDER
int cli_render_start(cli_render_session *s, cli_render_opts *o, const char *cmd, const char *in, const double tone_up[3])
{
    if (tone_up) memcpy(o->tone.up, tone_up, sizeof o->tone.up);
    o->uopt.tone = o->tone;
    o->uopt.skip_painterly = !o->uses[PNPR_STYLE_PAINTERLY]; /* only what the frames need */
    o->uopt.tone_radius = s->tone_radius;
    if (!run_plan(cmd, in, &s->cloud, &s->tree, o, o->quiet, s->prog)) return 0;
    pnpr_error err = {0};
    pnpr_status st = pnpr_gl_context_create(&s->ctx, &err);
    if (st == PNPR_OK) st = pnpr_renderer_create(NULL, &s->ren, &err);
    if (st != PNPR_OK) { cli_report_error(cmd, st, &err); return 0; }
    st = pnpr_renderer_set_cloud(s->ren, &s->cloud, &o->uopt, &err);
    if (st != PNPR_OK) { cli_report_error_in(cmd, in, st, &err); return 0; }
    if (s->tree.nodes) pnpr_renderer_set_hierarchy(s->ren, &s->tree);
    if (o->uses[PNPR_STYLE_LINES] && !set_profile_lines(cmd, in, &s->cloud, s->ren, o->quiet, s->prog)) return 0;
    size_t bytes = 0;
    st = pnpr_image_bytes(o->view.width, o->view.height, 0, &bytes, &err);
    if (st != PNPR_OK) { cli_report_error(cmd, st, &err); return 0; }
    s->pixels = malloc(bytes);
    if (!s->pixels) {
        fprintf(stderr, "pointnpr %s: cannot allocate %zu bytes for a %dx%d image\n", cmd, bytes, o->view.width, o->view.height);
        return 0;
    }
    return 1;
}

/* Progress of the effects' layers: one line per layer. */
static int layer_progress(void *user, const char *stage, double fraction)
{
    (void)user;
    fprintf(stderr, "render: effects %s (%.0f %%)\n", stage, 100.0 * fraction);
    return 0;
}

/* cli_render_frame through the effects pipeline (one frame: no tiles). */
static int effects_frame(cli_render_session *s, const cli_render_opts *o, const char *cmd, const char *in,
                         const pnpr_camera *camera, pnpr_render_stats *r_stats)
{
    pnpr_effects_options eo = o->fx_opts;
    eo.seed = o->uopt.seed;
    eo.progress.fn = o->quiet ? NULL : layer_progress;
    pnpr_effects_stats es;
    pnpr_error err = {0};
    if (r_stats) memset(r_stats, 0, sizeof *r_stats);
    int lim = pnpr_renderer_max_size(s->ren);
    if (o->view.width > lim || o->view.height > lim) {
        fprintf(stderr, "pointnpr %s: --effects images are one frame: at most %dx%d on this GL, asked %dx%d\n", cmd, lim,
                lim, o->view.width, o->view.height);
        return 0;
    }
    pnpr_status st = pnpr_renderer_effects(s->ren, camera, &o->dopt, &o->fx, o->view.width, o->view.height, &eo,
                                           s->pixels, &es, &err);
    if (st != PNPR_OK) { cli_report_error_in(cmd, in, st, &err); return 0; }
    if (!o->quiet)
        fprintf(stderr, "%s: effects: %zu layers of %dx%d (raster %.2f s, filters %.2f s, inpainting %.2f s, compositing %.2f s%s), layering %s\n",
                in, es.layers, es.layer_width, es.layer_height, es.raster_s, es.filter_s, es.inpaint_s, es.composite_s,
                eo.serial ? "" : "; filters on their own thread", pnpr_layering_name(o->fx.layering));
    return 1;
}

int cli_render_frame(cli_render_session *s, const cli_render_opts *o, const char *cmd, const char *in,
                     const pnpr_camera *camera, int tiles, pnpr_render_stats *r_stats)
{
    if (o->fx.count) return effects_frame(s, o, cmd, in, camera, r_stats);
    pnpr_snapshot_options so = {0};
    so.max_tile_size = o->max_tile;
    so.unpremultiply = o->alpha;
    so.progress.fn = o->quiet || !tiles ? NULL : tile_progress;
    pnpr_error err = {0};
    pnpr_status st = pnpr_renderer_snapshot(s->ren, camera, &o->dopt, o->view.width, o->view.height, &so, s->pixels, r_stats, &err);
    if (st != PNPR_OK) cli_report_error_in(cmd, in, st, &err);
    return st == PNPR_OK;
}
#endif

void cli_render_end(cli_render_session *s)
{
    free(s->pixels);
#ifdef PNPR_HAVE_RENDER
    pnpr_renderer_destroy(s->ren);
    pnpr_gl_context_destroy(s->ctx);
#endif
    pnpr_cloud_free(&s->cloud);
    pnpr_sphere_tree_free(&s->tree);
    memset(s, 0, sizeof *s);
}
