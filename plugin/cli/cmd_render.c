/* pointnpr render IN -o OUT.png: a stylised image of a point cloud, rendered headless
 * (EGL surfaceless, OpenGL 3.3 core) by the PointWorks renderer (render/, docs/rendering.md). */
#include "cli.h"

#include <stdio.h>

#ifndef PNPR_HAVE_RENDER
int cli_render(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "pointnpr render: this build has no renderer (libepoxy and libpng were not found)\n");
    return 1;
}
#else

#include <pointnpr/features.h>
#include <pointnpr/lines.h>
#include <pointnpr/plan.h>
#include <pointnpr/render.h>
#include <pointnpr/segment.h>

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    float w_lines = 0, w_cartoon = 0, w_sketchy = 0; /* the outline widths, as the library says */
    pnpr_style_outline_default(PNPR_STYLE_LINES, &w_lines);
    pnpr_style_outline_default(PNPR_STYLE_CARTOON, &w_cartoon);
    pnpr_style_outline_default(PNPR_STYLE_SKETCHY, &w_sketchy);
    fprintf(f,
            "usage: pointnpr render IN -o OUT.png [options]\n"
            "  Renders IN (PLY, LAS, OBJ, OFF or a folder of tiles) headless into a PNG.\n"
            "options:\n"
            "  --style S            points | sketchy | lines | stipple | cartoon | painterly\n"
            "                       (default points)\n"
            "  --style-map FILE     intermingled styles: FILE has lines 'LABEL STYLE' (a segment label of\n"
            "                       IN, PLY property segment or label) and '* STYLE' (the default, else\n"
            "                       --style); '#' starts a comment\n"
            "  --sketch V           sketchy variant of the paper's figure 9: a (directional strokes),\n"
            "                       b (+ non-directional hatches), c (+ dithering hatches; default)\n"
            "  --stroke-texture T   directional stroke texture 0, 1 or 2 (default 0)\n"
            "  --size WxH           image size in pixels (default 1024x768)\n"
            "  --eye X,Y,Z --target X,Y,Z\n"
            "                       look-at camera in world coordinates (default: the default view,\n"
            "                       from above the detected ground, framing the content; docs/view.md)\n"
            "  --up auto|x|y|z|-x|-y|-z|X,Y,Z\n"
            "                       the up axis (default auto: the file's convention, else the ground\n"
            "                       plane, else z; with --eye/--target a vector, default 0,0,1)\n"
            "  --fov DEG            vertical field of view (default 45)\n"
            "  --camera FILE        the camera from a file (eye/target/up/fov lines, world coordinates)\n"
            "  --save-camera FILE   write the camera used (e.g. the automatic one) to FILE, to edit\n"
            "  --budget N           at most N points per frame (default: all)\n"
            "  --density D          at most D points per covered screen pixel (default: no limit)\n"
            "  --seed S             continuous resolution queue seed (default 0)\n"
            "  --point-scale F      disk radius multiplier (default 1)\n"
            "  --line-width PX      lines: stroke width in pixels (default 2)\n"
            "  --line-min PX        lines: profile lines shorter than PX on screen are left out (scan\n"
            "                       noise scribbles; default %g)\n"
            "  --dot-size PX        stipple: dot diameter in pixels (default 2.5)\n"
            "  --levels N           cartoon: colour levels per channel when IN has no segment labels\n"
            "                       (PLY property segment or label, pointnpr segment; default 4)\n"
            "  --outline-scale F    cartoon: the gap-closing disks under the splats are F times their size\n"
            "                       (default 2; the outline itself: --outline-width)\n"
            "  --tone S             what sets how dark a point is drawn (hatch and stipple density,\n"
            "                       the shading of colourless clouds): auto | color | light (a key light\n"
            "                       on the normals) | both (default auto: both when IN has colours)\n"
            "  --tone-gamma G       tone curve: darkness^G, > 1 keeps mid tones light (default 1.8)\n"
            "  --tone-contrast C    tone curve: contrast around mid grey (default 1)\n"
            "  --light X,Y,Z        direction towards the key light (default: from above, front left)\n"
            "  --outline on|off     silhouettes and occluding contours (default: on for lines and cartoon,\n"
            "                       off for the others; sketchy reads well with them on)\n"
            "  --outline-width PX   their width in pixels (default: lines %g, cartoon %g, sketchy %g)\n"
            "  --outline-jump F     a contour is a depth jump of more than F disk depth extents (default %g)\n"
            "  --outline-hole F     gaps enclosed within F projected disk extents are sampling holes,\n"
            "                       not outlines (default %g)\n"
            "  --paint-bins N       painterly: feature-degree bins = passes, 1..16 (default 4)\n"
            "  --faint F            lines: draw the cloud faintly under the lines, F in (0,1]\n"
            "                       of the point colour (default: lines only)\n"
            "  --background R,G,B   background colour, 0..255 each (default 255,255,255)\n"
            "  --alpha              transparent background, PNG with alpha\n"
            "  --max-tile PX        render in tiles of at most PX pixels (default: the GL limit;\n"
            "                       larger images are always tiled, progress per tile on stderr)\n"
            "  --quiet              no progress on stderr\n"
            "  What IN lacks is computed as `pointnpr explain IN --style S` shows: features for sketchy,\n"
            "  stipple, painterly and lines (+ the profile lines), normals for outlines and for shading\n"
            "  colourless clouds, JSEG segments for cartoon when IN has colours but no segment labels.\n",
            (double)PNPR_LINE_MIN_PX, (double)w_lines, (double)w_cartoon, (double)w_sketchy,
            (double)PNPR_OUTLINE_JUMP, (double)PNPR_OUTLINE_HOLE);
    cli_outlier_usage(f);
}

/* Reads a style map file: lines "LABEL STYLE" and "* STYLE" (the default), '#' comments, blank
 * lines. Returns 0 with a message naming the line on a bad line. */
static int read_style_map(const char *path, pnpr_style_map_entry **r_map, size_t *r_count, pnpr_style *r_default,
                          int *r_have_default)
{
    FILE *f = fopen(path, "r");
    if (!f) { fprintf(stderr, "pointnpr render: --style-map: cannot open '%s': %s\n", path, strerror(errno)); return 0; }
    char line[512];
    size_t cap = 0, n = 0;
    pnpr_style_map_entry *map = NULL;
    int ok = 1, lineno = 0;
    while (ok && fgets(line, sizeof line, f)) {
        lineno++;
        char *hash = strchr(line, '#');
        if (hash) *hash = 0;
        char a[256], b[256], extra[2];
        int got = sscanf(line, "%255s %255s %1s", a, b, extra);
        if (got <= 0) continue; /* blank */
        pnpr_style s;
        if (got != 2) {
            fprintf(stderr, "pointnpr render: --style-map %s:%d: want 'LABEL STYLE' or '* STYLE'\n", path, lineno);
            ok = 0;
        } else if (pnpr_style_from_name(b, &s) != PNPR_OK) {
            fprintf(stderr, "pointnpr render: --style-map %s:%d: unknown style '%s' (points, sketchy, lines, stipple, cartoon, painterly)\n", path, lineno, b);
            ok = 0;
        } else if (!strcmp(a, "*")) {
            *r_default = s;
            *r_have_default = 1;
        } else {
            char *end;
            errno = 0;
            unsigned long long v = strtoull(a, &end, 10);
            if (errno || end == a || *end || a[0] == '-' || v > 0xFFFFFFFFull) {
                fprintf(stderr, "pointnpr render: --style-map %s:%d: label '%s' is not an integer in 0..4294967295 or '*'\n", path, lineno, a);
                ok = 0;
            } else {
                if (n == cap) {
                    cap = cap ? 2 * cap : 16;
                    pnpr_style_map_entry *m2 = realloc(map, cap * sizeof *m2);
                    if (!m2) { fprintf(stderr, "pointnpr render: --style-map: out of memory\n"); ok = 0; break; }
                    map = m2;
                }
                map[n].label = (uint32_t)v;
                map[n].style = s;
                n++;
            }
        }
    }
    fclose(f);
    if (!ok) { free(map); return 0; }
    *r_map = map;
    *r_count = n;
    return 1;
}

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
static int run_plan(const char *in, pnpr_cloud *cloud, const pnpr_draw_options *dopt, const int *uses,
                    const pnpr_tone_options *tone, int quiet, pnpr_progress prog)
{
    pnpr_plan_request req = {0};
    for (int s = 0; s < PNPR_STYLE_COUNT_; s++)
        if (uses[s]) req.styles |= 1u << s;
    req.sketch_variant = dopt->sketch_variant;
    req.outline = dopt->outline;
    pnpr_plan plan;
    pnpr_status st = pnpr_plan_make(&req, cloud, &plan);
    if (st == PNPR_OK && plan.want) {
        if (!quiet) fprintf(stderr, "%s: computing %s (pointnpr explain shows the plan; pointnpr features saves them)\n", in,
                            (plan.want & ~(uint32_t)(PNPR_WANT_NORMALS | PNPR_WANT_NORMALS_ANY)) ? "features" : "normals");
        pnpr_features_options fo = {0};
        fo.progress = prog;
        fo.want = plan.want;
        fo.tone = *tone;
        st = pnpr_compute_features(cloud, &fo, NULL);
    }
    if (st != PNPR_OK) { fprintf(stderr, "pointnpr render: %s: features: %s\n", in, pnpr_status_string(st)); return 0; }
    if (plan.segments != PNPR_PLAN_SEGMENTS_JSEG || cloud->count == 0) return 1;
    if (!quiet) fprintf(stderr, "%s: segmenting the colours (JSEG) for the cartoon's flat regions (pointnpr segment saves them)\n", in);
    if ((st = pnpr_cloud_alloc_labels(cloud)) == PNPR_OK) {
        pnpr_jseg_options jo = {0};
        jo.progress = prog;
        pnpr_segment_info info;
        st = pnpr_segment_jseg(cloud->xyz, cloud->rgb, cloud->count, &jo, cloud->label, &info);
        if (st == PNPR_OK && !quiet) fprintf(stderr, "%s: %u segments\n", in, (unsigned)info.segment_count);
    }
    if (st != PNPR_OK) { fprintf(stderr, "pointnpr render: %s: segments: %s\n", in, pnpr_status_string(st)); return 0; }
    return 1;
}

/* The profile lines of the lines style, handed to the renderer. Returns 0 after printing why. */
static int set_profile_lines(const char *in, const pnpr_cloud *cloud, pnpr_renderer *ren, int quiet, pnpr_progress prog)
{
    pnpr_polylines lines = {0};
    pnpr_lines_options lo = {0};
    lo.progress = prog;
    pnpr_lines_stats ls;
    pnpr_error err = {0};
    pnpr_status st = pnpr_profile_lines(cloud, &lo, &lines, &ls);
    if (st != PNPR_OK) { fprintf(stderr, "pointnpr render: %s: profile lines: %s\n", in, pnpr_status_string(st)); return 0; }
    if (!quiet) fprintf(stderr, "%s: %zu profile lines, total length %.6g\n", in, lines.count, ls.total_length);
    st = pnpr_renderer_set_lines(ren, &lines, &err);
    pnpr_lines_free(&lines);
    if (st != PNPR_OK) { cli_report_error("render", st, &err); return 0; }
    return 1;
}

int cli_render(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    pnpr_draw_options dopt;
    memset(&dopt, 0, sizeof dopt);
    pnpr_upload_options uopt;
    memset(&uopt, 0, sizeof uopt);
    pnpr_tone_options tone;
    memset(&tone, 0, sizeof tone);
    int quiet = 0, alpha = 0, max_tile = 0;
    cli_outliers outliers = {0, 0};
    const char *save_camera = NULL;
    cli_view view;
    cli_view_init(&view, 1024, 768);
    double bg[3] = {255, 255, 255};
    const char *style_map_path = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        double x;
        int vo = cli_view_option(&view, "render", argc, argv, &i);
        if (vo < 0) return 2;
        if (vo > 0) continue;
        int oo = cli_outlier_option(&outliers, "render", argc, argv, &i);
        if (oo < 0) return 2;
        if (oo > 0) continue;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { usage(stdout); return 0; }
        else if (!strcmp(a, "--quiet")) quiet = 1;
        else if (!strcmp(a, "--alpha")) alpha = 1;
        else if (v && !strcmp(a, "--save-camera")) { save_camera = v; i++; }
        else if (v && !strcmp(a, "--max-tile")) {
            if (!cli_parse_number(v, 16, 1e6, &x) || x != floor(x)) { fprintf(stderr, "pointnpr render: --max-tile wants an integer >= 16, got '%s'\n", v); return 2; }
            max_tile = (int)x; i++;
        }
        else if (v && (!strcmp(a, "-o") || !strcmp(a, "--output"))) { out = v; i++; }
        else if (v && !strcmp(a, "--style")) {
            pnpr_style s;
            if (pnpr_style_from_name(v, &s) != PNPR_OK) { fprintf(stderr, "pointnpr render: --style wants points, sketchy, lines, stipple, cartoon or painterly, got '%s'\n", v); return 2; }
            dopt.style = s; i++;
        } else if (v && !strcmp(a, "--style-map")) {
            style_map_path = v; i++;
        } else if (v && !strcmp(a, "--sketch")) {
            if (!strcmp(v, "a")) dopt.sketch_variant = PNPR_SKETCH_DIRECTIONAL;
            else if (!strcmp(v, "b")) dopt.sketch_variant = PNPR_SKETCH_NONDIRECTIONAL;
            else if (!strcmp(v, "c")) dopt.sketch_variant = PNPR_SKETCH_ALL;
            else { fprintf(stderr, "pointnpr render: --sketch wants a, b or c, got '%s'\n", v); return 2; }
            i++;
        } else if (v && !strcmp(a, "--stroke-texture")) {
            if (!cli_parse_number(v, 0, 2, &x) || x != floor(x)) { fprintf(stderr, "pointnpr render: --stroke-texture wants 0, 1 or 2, got '%s'\n", v); return 2; }
            dopt.stroke_texture = (int)x; i++;
        } else if (v && !strcmp(a, "--budget")) {
            if (!cli_parse_number(v, 1, 4e9, &x) || x != floor(x)) { fprintf(stderr, "pointnpr render: --budget wants a positive integer, got '%s'\n", v); return 2; }
            dopt.budget = (size_t)x; i++;
        } else if (v && !strcmp(a, "--density")) {
            if (!cli_parse_number(v, 1e-9, 1e9, &x)) { fprintf(stderr, "pointnpr render: --density wants a positive number, got '%s'\n", v); return 2; }
            dopt.density = (float)x; i++;
        } else if (v && !strcmp(a, "--seed")) {
            char *end;
            errno = 0;
            unsigned long long s = strtoull(v, &end, 10);
            if (errno || end == v || *end || v[0] == '-') { fprintf(stderr, "pointnpr render: --seed wants a non-negative integer, got '%s'\n", v); return 2; }
            uopt.seed = s; i++;
        } else if (v && !strcmp(a, "--point-scale")) {
            if (!cli_parse_number(v, 1e-3, 1e3, &x)) { fprintf(stderr, "pointnpr render: --point-scale wants a positive number, got '%s'\n", v); return 2; }
            dopt.point_scale = (float)x; i++;
        } else if (v && !strcmp(a, "--line-width")) {
            if (!cli_parse_number(v, 1e-2, 1e3, &x)) { fprintf(stderr, "pointnpr render: --line-width wants a positive number of pixels, got '%s'\n", v); return 2; }
            dopt.line_width = (float)x; i++;
        } else if (v && !strcmp(a, "--line-min")) {
            if (!cli_parse_number(v, 0.01, 1e4, &x)) { fprintf(stderr, "pointnpr render: --line-min wants a positive number of pixels, got '%s'\n", v); return 2; }
            dopt.line_min_px = (float)x; i++;
        } else if (v && !strcmp(a, "--dot-size")) {
            if (!cli_parse_number(v, 1e-2, 1e3, &x)) { fprintf(stderr, "pointnpr render: --dot-size wants a positive number of pixels, got '%s'\n", v); return 2; }
            dopt.dot_size = (float)x; i++;
        } else if (v && !strcmp(a, "--levels")) {
            if (!cli_parse_number(v, 2, 256, &x) || x != floor(x)) { fprintf(stderr, "pointnpr render: --levels wants an integer in 2..256, got '%s'\n", v); return 2; }
            dopt.levels = (int)x; i++;
        } else if (v && !strcmp(a, "--outline-scale")) {
            if (!cli_parse_number(v, 1, 100, &x)) { fprintf(stderr, "pointnpr render: --outline-scale wants a number >= 1, got '%s'\n", v); return 2; }
            dopt.mask_scale = (float)x; i++;
        } else if (v && !strcmp(a, "--tone")) {
            static const char *const names[] = {"auto", "color", "light", "both"};
            int t = 0;
            while (t < 4 && strcmp(v, names[t])) t++;
            if (t == 4) { fprintf(stderr, "pointnpr render: --tone wants auto, color, light or both, got '%s'\n", v); return 2; }
            tone.source = (pnpr_tone_source)t; i++;
        } else if (v && !strcmp(a, "--tone-gamma")) {
            if (!cli_parse_number(v, 0.05, 20, &x)) { fprintf(stderr, "pointnpr render: --tone-gamma wants a number in [0.05, 20], got '%s'\n", v); return 2; }
            tone.gamma = (float)x; i++;
        } else if (v && !strcmp(a, "--tone-contrast")) {
            if (!cli_parse_number(v, 0.01, 100, &x)) { fprintf(stderr, "pointnpr render: --tone-contrast wants a number in [0.01, 100], got '%s'\n", v); return 2; }
            tone.contrast = (float)x; i++;
        } else if (v && !strcmp(a, "--light")) {
            if (!cli_parse_list(v, 3, tone.light) || (tone.light[0] == 0 && tone.light[1] == 0 && tone.light[2] == 0)) {
                fprintf(stderr, "pointnpr render: --light wants a non-zero direction X,Y,Z, got '%s'\n", v); return 2;
            }
            i++;
        } else if (v && !strcmp(a, "--outline")) {
            if (strcmp(v, "on") && strcmp(v, "off")) { fprintf(stderr, "pointnpr render: --outline wants on or off, got '%s'\n", v); return 2; }
            dopt.outline = !strcmp(v, "on") ? 1 : -1; i++;
        } else if (v && !strcmp(a, "--outline-width")) {
            if (!cli_parse_number(v, 0.1, 64, &x)) { fprintf(stderr, "pointnpr render: --outline-width wants pixels in [0.1, 64], got '%s'\n", v); return 2; }
            dopt.outline_width = (float)x; i++;
        } else if (v && !strcmp(a, "--outline-jump")) {
            if (!cli_parse_number(v, 0.01, 1e3, &x)) { fprintf(stderr, "pointnpr render: --outline-jump wants a positive number, got '%s'\n", v); return 2; }
            dopt.outline_jump = (float)x; i++;
        } else if (v && !strcmp(a, "--outline-hole")) {
            if (!cli_parse_number(v, 0.01, 1e3, &x)) { fprintf(stderr, "pointnpr render: --outline-hole wants a positive number, got '%s'\n", v); return 2; }
            dopt.outline_hole = (float)x; i++;
        } else if (v && !strcmp(a, "--paint-bins")) {
            if (!cli_parse_number(v, 1, 16, &x) || x != floor(x)) { fprintf(stderr, "pointnpr render: --paint-bins wants an integer in 1..16, got '%s'\n", v); return 2; }
            uopt.painterly_bins = (uint32_t)x; i++;
        } else if (v && !strcmp(a, "--faint")) {
            if (!cli_parse_number(v, 1e-6, 1, &x)) { fprintf(stderr, "pointnpr render: --faint wants a number in (0,1], got '%s'\n", v); return 2; }
            dopt.faint = (float)x; i++;
        } else if (v && !strcmp(a, "--background")) {
            if (!cli_parse_list(v, 3, bg) || bg[0] < 0 || bg[0] > 255 || bg[1] < 0 || bg[1] > 255 || bg[2] < 0 || bg[2] > 255) {
                fprintf(stderr, "pointnpr render: --background wants R,G,B in 0..255, got '%s'\n", v); return 2;
            }
            i++;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "pointnpr render: unknown option or missing value: %s\n", a);
            usage(stderr);
            return 2;
        } else if (!in) in = a;
        else { fprintf(stderr, "pointnpr render: more than one input given ('%s')\n", a); return 2; }
    }
    if (!in || !out) { usage(stderr); return 2; }
    if (!cli_view_check(&view, "render")) return 2;
    if (!cli_has_ext(out, ".png") && !cli_output_is_stream(out)) {
        fprintf(stderr, "pointnpr render: the output is a PNG image: its name must end in .png (or be - or a device/FIFO), got '%s'\n", out);
        return 2;
    }
    if (save_camera && !strcmp(save_camera, out)) {
        fprintf(stderr, "pointnpr render: -o and --save-camera name the same file %s\n", out);
        return 2;
    }
    if (!cli_check_output("render", out, &in, 1, 1) || (save_camera && !cli_check_output("render", save_camera, &in, 1, 0)))
        return 1;
    const int width = view.width, height = view.height;
    for (int c = 0; c < 3; c++) dopt.background[c] = (float)(bg[c] / 255.0);
    dopt.background[3] = alpha ? 0.0f : 1.0f;

    pnpr_style_map_entry *smap = NULL;
    size_t smap_count = 0;
    int map_has_default = 0;
    pnpr_style map_default = dopt.style;
    if (style_map_path && !read_style_map(style_map_path, &smap, &smap_count, &map_default, &map_has_default)) return 2;
    if (map_has_default) dopt.style = map_default;
    dopt.style_map = smap;
    dopt.style_map_count = smap_count;
    /* the styles this frame may draw: the default and the mapped ones */
    int uses[PNPR_STYLE_COUNT_] = {0};
    uses[dopt.style] = 1;
    for (size_t m = 0; m < smap_count; m++) uses[smap[m].style] = 1;

    cli_progress_state ps = {{0}, 0, 0};
    pnpr_progress prog = {quiet ? NULL : cli_progress_stderr, &ps};
    pnpr_read_options ro = {0};
    ro.progress = prog;
    pnpr_cloud cloud = {0};
    pnpr_error err = {0};
    pnpr_gl_context *ctx = NULL;
    pnpr_renderer *ren = NULL;
    uint8_t *pixels = NULL;
    int rc = 1;
    pnpr_status st = pnpr_read_file(in, &ro, &cloud, &err);
    if (st != PNPR_OK) { cli_report_error("render", st, &err); goto done; }
    if (cli_outliers_apply(&outliers, "render", in, &cloud, quiet, NULL)) goto done;

    /* the camera first: its up vector is the tone's "above" (the key light comes from there) */
    pnpr_camera cam;
    const pnpr_camera *camp = cli_view_camera(&view, &cloud, &cam);
    if (camp) memcpy(tone.up, camp->up, sizeof tone.up);
    uopt.tone = tone;
    if (!run_plan(in, &cloud, &dopt, uses, &tone, quiet, prog)) goto done;

    st = pnpr_gl_context_create(&ctx, &err);
    if (st != PNPR_OK) { cli_report_error("render", st, &err); goto done; }
    st = pnpr_renderer_create(NULL, &ren, &err);
    if (st != PNPR_OK) { cli_report_error("render", st, &err); goto done; }
    st = pnpr_renderer_set_cloud(ren, &cloud, &uopt, &err);
    if (st != PNPR_OK) { cli_report_error_in("render", in, st, &err); goto done; }
    if (uses[PNPR_STYLE_LINES] && !set_profile_lines(in, &cloud, ren, quiet, prog)) goto done;

    if (save_camera && camp &&
        !cli_write_camera_file(save_camera, camp->eye, camp->target, camp->up, camp->fov_y_deg > 0 ? camp->fov_y_deg : 45)) {
        fprintf(stderr, "pointnpr render: cannot write the camera file %s\n", save_camera);
        goto done;
    }
    size_t bytes = 0;
    st = pnpr_image_bytes(width, height, 0, &bytes, &err);
    if (st != PNPR_OK) { cli_report_error("render", st, &err); goto done; }
    pixels = malloc(bytes);
    if (!pixels) {
        fprintf(stderr, "pointnpr render: cannot allocate %zu bytes for a %dx%d image\n", bytes, width, height);
        goto done;
    }
    pnpr_snapshot_options so = {0};
    so.max_tile_size = max_tile;
    so.unpremultiply = alpha;
    so.progress.fn = quiet ? NULL : tile_progress;
    pnpr_render_stats stats;
    st = pnpr_renderer_snapshot(ren, camp, &dopt, width, height, &so, pixels, &stats, &err);
    if (st != PNPR_OK) { cli_report_error_in("render", in, st, &err); goto done; }
    st = pnpr_write_png(out, pixels, width, height, alpha, &err);
    if (st != PNPR_OK) { cli_report_error("render", st, &err); goto done; }
    if (!quiet)
        fprintf(stderr, "%s: %zu of %zu points drawn, %zu strokes, style %s, %dx%d -> %s\n", in,
                stats.points_drawn, stats.points_total, stats.strokes_drawn,
                smap_count ? "map" : pnpr_style_name(dopt.style), width, height, out);
    rc = 0;
done:
    free(smap);
    free(pixels);
    pnpr_renderer_destroy(ren);
    pnpr_gl_context_destroy(ctx);
    pnpr_cloud_free(&cloud);
    return rc;
}
#endif
