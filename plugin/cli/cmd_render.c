/* pointnpr render IN -o OUT.png|OUT.svg|OUT.pdf: a stylised image of a point cloud, rendered
 * headless (EGL surfaceless, OpenGL 3.3 core) by the PointWorks renderer (render/,
 * docs/rendering.md), or the same frame's strokes as a vector drawing (docs/export.md). */
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

#include "cli_render.h"
#include "cli_opts.h"

#include <pointnpr/camera_path.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef enum out_kind { OUT_PNG = 0, OUT_SVG, OUT_PDF } out_kind;

typedef struct render_args {
    const char *in, *out, *save_camera, *camera_path;
    double camera_at;
    int have_camera_at;
    int plot_order, merge_hatches;
    double min_mark;
    out_kind kind;
    pnpr_camera_path path; /* the --camera-path file, read before any work */
} render_args;

/* The options of render alone (cli_opts.h); --camera-at is NAN until given. */
static const cli_opt render_own[] = {
    {"--plot-order", NULL, CLI_FLAG, offsetof(render_args, plot_order), 0, 0, 0, 0, NULL, NULL, NULL,
     "vector: order the paths of each layer for a pen plotter (shorter pen-up travel)"},
    {"--merge-hatches", NULL, CLI_FLAG, offsetof(render_args, merge_hatches), 0, 0, 0, 0, NULL, NULL, NULL,
     "vector: hatches on one line become one path"},
    {"--min-mark", NULL, CLI_NUMBER, offsetof(render_args, min_mark), 0, 1e4, 0, 0, NULL, NULL, "PX",
     "vector: leave out strokes and lines shorter than PX (a pen plotter draws them as dots; default 0: every mark)"},
    {"--save-camera", NULL, CLI_TEXT, offsetof(render_args, save_camera), 0, 0, 0, 0, NULL, NULL, "FILE",
     "write the camera used (e.g. the automatic one) to FILE, to edit"},
    {"--camera-path", NULL, CLI_TEXT, offsetof(render_args, camera_path), 0, 0, 0, 0, NULL, NULL, "FILE",
     "the camera of a camera path (pointnpr animate, docs/export.md) ..."},
    {"--camera-at", NULL, CLI_NUMBER, offsetof(render_args, camera_at), -1e12, 1e12, 0, 0, NULL, NULL, "T",
     "... at T seconds (default: the first key's time)"},
    {"--output", "-o", CLI_TEXT, offsetof(render_args, out), 0, 0, 0, 0, NULL, NULL, "OUT", "the output file"},
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: pointnpr render IN -o OUT.png|OUT.svg|OUT.pdf [options]\n"
            "  Renders IN (PLY, LAS, OBJ, OFF, PCD, text) headless into a PNG, or draws the\n"
            "  frame's strokes, dots, lines and outlines as vector paths (SVG, PDF; styles sketchy,\n"
            "  stipple, lines, cartoon), or filters its segments in image space (--effects FILE, PNG).\n"
            "options:\n");
    cli_opts_usage(f, render_own, CLI_COUNT(render_own));
    cli_render_usage(f, 1024, 768);
}

/* Parses argv; returns -1 to go on, else the exit code (help, usage error). */
static int parse_args(int argc, char **argv, render_args *r, cli_render_opts *o)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int got = cli_opts_parse(render_own, CLI_COUNT(render_own), r, "render", argc, argv, &i);
        if (got == 0) got = cli_render_option(o, "render", argc, argv, &i);
        if (got < 0) return 2;
        if (got > 0) continue;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { usage(stdout); return 0; }
        if (cli_operand("render", a, &r->in, usage)) return 2;
    }
    r->have_camera_at = !isnan(r->camera_at);
    if (!cli_need_in_out("render", r->in, r->out, "OUT.png")) return 2;
    return -1;
}

/* The checks between the options and the output names; -1 = fine, else the exit code. */
static int check_args(render_args *r, cli_render_opts *o)
{
    if (r->have_camera_at && !r->camera_path) { fprintf(stderr, "pointnpr render: --camera-at needs --camera-path FILE\n"); return 2; }
    if (r->camera_path && (o->view.have_eye || o->view.have_target)) {
        fprintf(stderr, "pointnpr render: --camera-path and --eye/--target/--camera are two cameras; give one\n");
        return 2;
    }
    if (!cli_render_opts_finish(o, "render")) return 2;
    pnpr_error err = {0};
    pnpr_status st = r->camera_path ? pnpr_camera_path_read(r->camera_path, &r->path, &err) : PNPR_OK;
    if (st != PNPR_OK) { cli_report_error("render", st, &err); return 2; }
    r->kind = cli_has_ext(r->out, ".svg") ? OUT_SVG : cli_has_ext(r->out, ".pdf") ? OUT_PDF : OUT_PNG;
    if (r->kind == OUT_PNG && !cli_has_ext(r->out, ".png") && !cli_output_is_stream(r->out)) {
        fprintf(stderr, "pointnpr render: the output's name must end in .png, .svg or .pdf (or be - or a device/FIFO: PNG), got '%s'\n", r->out);
        return 2;
    }
    if ((r->plot_order || r->merge_hatches || r->min_mark > 0) && r->kind == OUT_PNG) {
        fprintf(stderr, "pointnpr render: --plot-order, --merge-hatches and --min-mark are for vector output (.svg, .pdf)\n");
        return 2;
    }
    if (r->kind != OUT_PNG && o->fx.count) {
        fprintf(stderr, "pointnpr render: --effects filters pixels: the output must be a PNG, got '%s'\n", r->out);
        return 2;
    }
    if (r->kind != OUT_PNG) {
        st = pnpr_drawing_supported(&o->dopt, &err);
        if (st != PNPR_OK) { cli_report_error("render", st, &err); return 2; }
    }
    if (r->save_camera && !strcmp(r->save_camera, r->out)) {
        fprintf(stderr, "pointnpr render: -o and --save-camera name the same file %s\n", r->out);
        return 2;
    }
    if (!cli_check_output("render", r->out, &r->in, 1, 1) || (r->save_camera && !cli_check_output("render", r->save_camera, &r->in, 1, 0)))
        return 1;
    return -1;
}

/* The frame as a vector drawing: merged and ordered when asked, written as SVG or PDF. */
static int write_vector(cli_render_session *s, const cli_render_opts *o, const render_args *r, const pnpr_camera *camera)
{
    pnpr_error err = {0};
    pnpr_drawing d;
    pnpr_status st = pnpr_renderer_drawing(s->ren, camera, &o->dopt, o->view.width, o->view.height, &d, &err);
    if (st != PNPR_OK) { cli_report_error_in("render", r->in, st, &err); return 0; }
    size_t merged = 0, m = 0, dropped = 0;
    if (r->merge_hatches && st == PNPR_OK) st = pnpr_drawing_merge_collinear(&d, PNPR_LAYER_HATCHES, 1, 0.5f, 1, &merged);
    if (r->merge_hatches && st == PNPR_OK) st = pnpr_drawing_merge_collinear(&d, PNPR_LAYER_TONE, 1, 0.5f, 1, &m);
    if (r->min_mark > 0 && st == PNPR_OK) st = pnpr_drawing_drop_short(&d, (float)r->min_mark, &dropped);
    double travel = pnpr_drawing_travel(&d);
    if (r->plot_order && st == PNPR_OK) st = pnpr_drawing_order_for_plotter(&d);
    if (st == PNPR_OK)
        st = r->kind == OUT_SVG ? pnpr_drawing_write_svg(&d, r->out, &err) : pnpr_drawing_write_pdf(&d, r->out, &err);
    else pnpr_error_set(&err, st, "render: %s: out of memory", r->out);
    if (st != PNPR_OK) cli_report_error("render", st, &err);
    else if (!o->quiet) {
        fprintf(stderr, "%s: %zu paths (", r->in, d.count);
        for (int L = 0; L < PNPR_LAYER_COUNT_; L++) {
            size_t n = 0;
            for (size_t i = 0; i < d.count; i++) n += d.layer[i] == L;
            if (n) fprintf(stderr, "%s %zu, ", pnpr_drawing_layer_name((pnpr_drawing_layer)L), n);
        }
        fprintf(stderr, "%.0f px of ink), style %s, %dx%d", pnpr_drawing_ink_length(&d, PNPR_LAYER_COUNT_),
                o->smap.count ? "map" : pnpr_style_name(o->dopt.style), o->view.width, o->view.height);
        if (r->merge_hatches) fprintf(stderr, ", %zu hatches merged", merged + m);
        if (r->min_mark > 0) fprintf(stderr, ", %zu marks under %g px left out", dropped, r->min_mark);
        if (r->plot_order) fprintf(stderr, ", pen-up travel %.0f -> %.0f px", travel, pnpr_drawing_travel(&d));
        fprintf(stderr, " -> %s\n", r->out);
    }
    pnpr_drawing_free(&d);
    return st == PNPR_OK;
}

int cli_render(int argc, char **argv)
{
    render_args r = {0};
    r.camera_at = NAN; /* not given */
    cli_render_opts o;
    cli_render_opts_init(&o, 1024, 768);
    int rc = parse_args(argc, argv, &r, &o);
    if (rc < 0) rc = check_args(&r, &o);
    if (rc >= 0) { pnpr_camera_path_free(&r.path); cli_render_opts_free(&o); return rc; }
    rc = 1;
    cli_render_session s;
    memset(&s, 0, sizeof s);
    pnpr_camera cam;
    const pnpr_camera *camp = NULL;
    double tone_up[3] = {0, 0, 0};
    /* the camera a sample of a cloud larger than memory follows: the path's, or --eye/--target's
     * (its up does not matter to the sample) */
    pnpr_camera given = {{0}, {0}, {0}, (float)o.view.fov, 0, 0};
    memcpy(given.eye, o.view.eye, sizeof given.eye);
    memcpy(given.target, o.view.target, sizeof given.target);
    if (r.camera_path &&
        pnpr_camera_path_eval(&r.path, r.have_camera_at ? r.camera_at : r.path.keys[0].time, &given) != PNPR_OK)
        goto done;
    const cli_sample_views views = {&given, 1, NULL, NULL};
    int have_given = r.camera_path || (o.view.have_eye && o.view.have_target);
    if (!cli_render_load(&s, &o, "render", r.in, have_given ? &views : NULL)) goto done;
    /* the camera first: its up vector is the tone's "above" (the key light comes from there) */
    if (r.camera_path) { /* the path's first up is the key light's above, as in `animate` */
        memcpy(tone_up, r.path.keys[0].up, sizeof tone_up);
        cam = given;
        camp = &cam;
    } else if ((camp = cli_view_camera(&o.view, &s.cloud, &cam)) != NULL)
        memcpy(tone_up, camp->up, sizeof tone_up);
    if (!cli_render_start(&s, &o, "render", r.in, camp ? tone_up : NULL)) goto done;
    if (r.save_camera && camp &&
        !cli_write_camera_file(r.save_camera, camp->eye, camp->target, camp->up, camp->fov_y_deg > 0 ? camp->fov_y_deg : 45)) {
        fprintf(stderr, "pointnpr render: cannot write the camera file %s\n", r.save_camera);
        goto done;
    }
    if (r.kind != OUT_PNG) {
        rc = write_vector(&s, &o, &r, camp) ? 0 : 1;
        goto done;
    }
    pnpr_render_stats stats;
    if (!cli_render_frame(&s, &o, "render", r.in, camp, 1, &stats)) goto done;
    pnpr_error err = {0};
    pnpr_status st = pnpr_write_png(r.out, s.pixels, o.view.width, o.view.height, o.alpha, &err);
    if (st != PNPR_OK) { cli_report_error("render", st, &err); goto done; }
    if (!o.quiet && o.fx.count)
        fprintf(stderr, "%s: effects of %s, %dx%d -> %s\n", r.in, o.effects_path, o.view.width, o.view.height, r.out);
    else if (!o.quiet)
        fprintf(stderr, "%s: %zu of %zu points drawn, %zu strokes, style %s, %dx%d -> %s\n", r.in,
                stats.points_drawn, stats.points_total, stats.strokes_drawn,
                o.smap.count ? "map" : pnpr_style_name(o.dopt.style), o.view.width, o.view.height, r.out);
    rc = 0;
done:
    cli_render_end(&s);
    pnpr_camera_path_free(&r.path);
    cli_render_opts_free(&o);
    return rc;
}
#endif
