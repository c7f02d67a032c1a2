/* pointnpr bench quality [--full | --sparse] [-o DIR] [--check]: the picture-quality figures of
 * issue 11 on a generated LiDAR-like scene with known answers (bench/quality/, docs/quality.md).
 *
 * Generates the house scene (small: ~150k points, --full: ~1M, --sparse: ~40k) and the ball alone,
 * and draws every style as `pointnpr render --style S` draws a raw scan with default options: for
 * each style a fresh scan goes through the library's stage plan (pnpr_plan_make, the plan that
 * `pointnpr explain` prints and plugin/cli/cmd_render.c runs: features with plan.want, JSEG
 * labels when plan.segments says so, profile lines when plan.lines), then it is rendered with a
 * fixed camera at 1024x768. Writes the PNGs to DIR and prints a markdown table of the figures
 * and of the acceptance thresholds. --check: exit 1 when a threshold is missed. */
#include "cli.h"

#include <pointnpr/output.h>

#include <stdio.h>

#ifndef PNPR_HAVE_RENDER
int cli_bench_quality(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "pointnpr bench quality: this build has no renderer (libepoxy and libpng were not found)\n");
    return 1;
}
#else

#include "quality.h"

#include <pointnpr/features.h>
#include <pointnpr/lines.h>
#include <pointnpr/plan.h>
#include <pointnpr/render.h>
#include <pointnpr/segment.h>

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

enum { QW = 1024, QH = 768 };

/* The rows of the table: the styles the figures judge. (Cartoon segments by default now, so the
 * former extra row of cartoon over JSEG labels is the cartoon row itself.) */
enum { ROW_POINTS, ROW_LINES, ROW_CARTOON, ROW_SKETCHY, ROW_STIPPLE, ROW_COUNT };
static const char *const row_name[ROW_COUNT] = {"points", "lines", "cartoon", "sketchy", "stipple"};
static const pnpr_style row_style[ROW_COUNT] = {PNPR_STYLE_POINTS, PNPR_STYLE_LINES, PNPR_STYLE_CARTOON,
                                                PNPR_STYLE_SKETCHY, PNPR_STYLE_STIPPLE};

typedef struct figures {
    int done;
    pnpr_quality_edge_figures lines, all, ball_scene, ball_alone;
    double ink, speckle;
    pnpr_quality_tone_figures tone;
    int tone_ok;
    double seconds;
} figures;

typedef struct bench {
    const char *dir;
    const char *scene_ply; /* --scene-ply FILE: write the labelled scan and stop */
    pnpr_quality_preset preset;   /* of the house scene: small, full or sparse */
    pnpr_renderer *ren;
    uint8_t *px;
    pnpr_quality_scene scene, ball;
    pnpr_quality_view view, ball_view;
    pnpr_camera_matrices m, ball_m;
    figures fig[ROW_COUNT];
    size_t points, ball_points;
} bench;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void note(const char *what, double t0)
{
    fprintf(stderr, "bench quality: %-44s %6.2f s\n", what, now() - t0);
}

/* The fixed cameras (fov 42): the house scene from the south-south-west, 50 m above the ground (an
 * oblique view, about 50 degrees down), and the ball alone from the same direction, close enough
 * to fill about 35% of the image height (12 m away). */
static const double cam_eye[3] = {-4, -40, 50}, cam_target[3] = {1, 0, 0};

static void scene_camera(const pnpr_quality_scene *s, pnpr_camera *c)
{
    memset(c, 0, sizeof *c);
    for (int a = 0; a < 3; a++) {
        c->eye[a] = s->offset[a] + cam_eye[a];
        c->target[a] = s->offset[a] + cam_target[a];
    }
    c->up[2] = 1;
    c->fov_y_deg = 42;
}

static void ball_camera(const pnpr_quality_scene *s, pnpr_camera *c)
{
    double dir[3], l = 0;
    for (int a = 0; a < 3; a++) { dir[a] = cam_eye[a] - cam_target[a]; l += dir[a] * dir[a]; }
    l = sqrt(l);
    const double *ctr = s->sphere[0].centre;
    memset(c, 0, sizeof *c);
    for (int a = 0; a < 3; a++) {
        c->target[a] = s->offset[a] + ctr[a];
        c->eye[a] = c->target[a] + 12 * dir[a] / l;
    }
    c->up[2] = 1;
    c->fov_y_deg = 42;
}

static int make_view(const pnpr_camera *cam, const pnpr_cloud *cloud, pnpr_camera_matrices *m, pnpr_quality_view *v)
{
    pnpr_error err = {0};
    if (pnpr_camera_matrices_from_camera(cam, cloud, QW, QH, m, &err) != PNPR_OK) {
        fprintf(stderr, "pointnpr bench quality: camera: %s\n", err.message);
        return 0;
    }
    memcpy(v->view, m->view, sizeof v->view);
    memcpy(v->projection, m->projection, sizeof v->projection);
    v->width = QW;
    v->height = QH;
    return 1;
}

/* Renders the uploaded cloud in `style` through m into b->px and writes DIR/<prefix>-<name>.png. */
static int render(bench *b, pnpr_style style, const pnpr_camera_matrices *m, const char *prefix, const char *name)
{
    pnpr_draw_options o;
    memset(&o, 0, sizeof o);
    o.style = style;
    for (int a = 0; a < 4; a++) o.background[a] = 1;
    o.matrices = m;
    pnpr_error err = {0};
    pnpr_status st = pnpr_renderer_snapshot(b->ren, NULL, &o, QW, QH, NULL, b->px, NULL, &err);
    char path[4096];
    snprintf(path, sizeof path, "%s/%s-%s.png", b->dir, prefix, name);
    if (st == PNPR_OK) st = pnpr_write_png(path, b->px, QW, QH, 0, &err);
    if (st != PNPR_OK) cli_report_error("bench quality", st, &err);
    return st == PNPR_OK;
}

/* The figures of the house-scene image in b->px. */
static int measure_scene(bench *b, figures *f)
{
    pnpr_quality_image im = {b->px, QW, QH};
    static const uint8_t ink[3] = {20, 20, 26}; /* the renderer's default ink (0.08, 0.08, 0.1) */
    pnpr_status st = pnpr_quality_line_figures(&b->scene, &b->view, &im, NULL, &f->lines, &f->all);
    if (st == PNPR_OK) st = pnpr_quality_sphere_silhouette(&b->scene, 0, &b->view, &im, NULL, &f->ball_scene);
    if (st == PNPR_OK) st = pnpr_quality_outline_ink(&im, ink, NULL, &f->ink, NULL);
    if (st == PNPR_OK) st = pnpr_quality_speckle(&im, NULL, &f->speckle);
    if (st != PNPR_OK) { fprintf(stderr, "pointnpr bench quality: figures: %s\n", pnpr_status_string(st)); return 0; }
    pnpr_status tst = pnpr_quality_tone(&b->scene, &b->view, &im, NULL, &f->tone);
    f->tone_ok = tst == PNPR_OK;
    f->done = 1;
    return 1;
}

/* DIR/scene-truth.png: the points image paled, the visible crease samples in red and the visible
 * outlines (silhouettes, ground border) in blue, as the figures see them. */
static int write_truth(bench *b)
{
    size_t npx = (size_t)QW * QH, ns = pnpr_quality_silhouettes(&b->scene, &b->view, 0, NULL, 0);
    uint8_t *mask = calloc(npx, 1);
    pnpr_quality_segment *sil = malloc((ns + 1) * sizeof *sil);
    if (!mask || !sil) { free(mask); free(sil); return 0; }
    ns = pnpr_quality_silhouettes(&b->scene, &b->view, 0, sil, ns);
    pnpr_quality_options o;
    memset(&o, 0, sizeof o);
    o.radius_px = 1.2f;
    pnpr_quality_visible_mask(&b->scene, &b->view, sil, ns, &o, 2, mask);
    pnpr_quality_visible_mask(&b->scene, &b->view, b->scene.edge, b->scene.edge_count, &o, 1, mask);
    static const uint8_t colour[3][3] = {{0, 0, 0}, {220, 20, 20}, {20, 60, 230}};
    for (size_t i = 0; i < npx; i++)
        for (int c = 0; c < 3; c++)
            b->px[4 * i + c] = mask[i] ? colour[mask[i]][c] : (uint8_t)(255 - (255 - b->px[4 * i + c]) / 3);
    free(mask);
    free(sil);
    char path[4096];
    snprintf(path, sizeof path, "%s/scene-truth.png", b->dir);
    pnpr_error err = {0};
    pnpr_status st = pnpr_write_png(path, b->px, QW, QH, 0, &err);
    if (st != PNPR_OK) cli_report_error("bench quality", st, &err);
    return st == PNPR_OK;
}

/* DIR/<prefix>-lines-check.png, where the line figures come from: the visible truth (creases and
 * outlines, or the ball's outline) in light blue where some ink lies within 2 px and in orange
 * where none does (missed), ink near the truth in black and stray ink in red. */
static int write_check(bench *b, const pnpr_quality_scene *s, const pnpr_quality_view *v, int ball)
{
    const size_t npx = (size_t)QW * QH;
    size_t ns = ball ? 512 : pnpr_quality_silhouettes(s, v, 0, NULL, 0);
    uint8_t *near = calloc(npx, 1), *line = calloc(npx, 1), *inked = calloc(npx, 1);
    pnpr_quality_segment *seg = malloc((s->edge_count + ns + 1) * sizeof *seg);
    int ok = near && line && inked && seg;
    if (ok && ball) ok = pnpr_quality_circle(v, s->offset, s->sphere[0].centre, s->sphere[0].radius, 512, seg) == PNPR_OK;
    else if (ok) {
        memcpy(seg, s->edge, s->edge_count * sizeof *seg);
        ns = s->edge_count + pnpr_quality_silhouettes(s, v, 0, seg + s->edge_count, ns);
    }
    if (ok) {
        pnpr_quality_options o;
        memset(&o, 0, sizeof o);
        pnpr_quality_visible_mask(s, v, seg, ns, &o, 1, near);
        o.radius_px = 0.8f;
        pnpr_quality_visible_mask(s, v, seg, ns, &o, 1, line);
        for (int y = 0; y < QH; y++) /* ink within 2 px of each pixel (its centre) */
            for (int x = 0; x < QW; x++) {
                if (!(pnpr_quality_luminance(b->px + 4 * ((size_t)y * QW + x)) < 0.5)) continue;
                for (int dy = -2; dy <= 2; dy++)
                    for (int dx = -2; dx <= 2; dx++)
                        if (dx * dx + dy * dy <= 4 && x + dx >= 0 && y + dy >= 0 && x + dx < QW && y + dy < QH)
                            inked[(size_t)(y + dy) * QW + x + dx] = 1;
            }
        static const uint8_t c[5][3] = {{255, 255, 255}, {150, 200, 255}, {255, 150, 0}, {0, 0, 0}, {230, 0, 0}};
        for (size_t i = 0; i < npx; i++) {
            int ink = pnpr_quality_luminance(b->px + 4 * i) < 0.5;
            int k = ink ? (near[i] ? 3 : 4) : (line[i] ? (inked[i] ? 1 : 2) : 0);
            memcpy(b->px + 4 * i, c[k], 3);
        }
    }
    free(near); free(line); free(inked); free(seg);
    if (!ok) return 0;
    char path[4096];
    snprintf(path, sizeof path, "%s/%s-lines-check.png", b->dir, ball ? "ball" : "scene");
    pnpr_error err = {0};
    pnpr_status st = pnpr_write_png(path, b->px, QW, QH, 0, &err);
    if (st != PNPR_OK) cli_report_error("bench quality", st, &err);
    return st == PNPR_OK;
}

static int measure_ball(bench *b, figures *f)
{
    pnpr_quality_image im = {b->px, QW, QH};
    pnpr_status st = pnpr_quality_sphere_silhouette(&b->ball, 0, &b->ball_view, &im, NULL, &f->ball_alone);
    if (st != PNPR_OK) fprintf(stderr, "pointnpr bench quality: ball figures: %s\n", pnpr_status_string(st));
    return st == PNPR_OK;
}

static int upload(bench *b, const pnpr_cloud *c)
{
    pnpr_error err = {0};
    pnpr_status st = pnpr_renderer_set_cloud(b->ren, c, NULL, &err);
    if (st != PNPR_OK) cli_report_error("bench quality", st, &err);
    return st == PNPR_OK;
}

static int failed(const char *what, const char *stage, pnpr_status st)
{
    fprintf(stderr, "pointnpr bench quality: %s: %s: %s\n", what, stage, pnpr_status_string(st));
    return 0;
}

/* The features of the plan (tone options zeroed = the defaults; their up, +z, is the camera's). */
static int run_features(pnpr_cloud *c, uint32_t want, const char *what)
{
    double t0 = now();
    pnpr_features_options fo = {0};
    fo.want = want;
    pnpr_status st = pnpr_compute_features(c, &fo, NULL);
    if (st != PNPR_OK) return failed(what, "features", st);
    note("  features", t0);
    return 1;
}

/* JSEG labels into c->label with the default options. */
static int run_jseg(pnpr_cloud *c, const char *what)
{
    double t0 = now();
    pnpr_segment_info info;
    pnpr_status st = pnpr_cloud_alloc_labels(c);
    if (st == PNPR_OK) st = pnpr_segment_jseg(c->xyz, c->rgb, c->count, NULL, c->label, &info);
    if (st != PNPR_OK) return failed(what, "jseg", st);
    fprintf(stderr, "bench quality: %s: jseg: %u segments\n", what, info.segment_count);
    note("  jseg", t0);
    return 1;
}

/* The profile lines of the cloud (want) or none, handed to the renderer. */
static int run_lines(bench *b, const pnpr_cloud *c, int want, const char *what)
{
    pnpr_polylines lines = {0};
    if (want) {
        pnpr_lines_stats ls;
        pnpr_status st = pnpr_profile_lines(c, NULL, &lines, &ls);
        if (st != PNPR_OK) return failed(what, "profile lines", st);
        fprintf(stderr, "bench quality: %s: %zu profile lines, %.1f m\n", what, lines.count, ls.total_length);
    }
    pnpr_error err = {0};
    pnpr_status st = pnpr_renderer_set_lines(b->ren, want ? &lines : NULL, &err);
    pnpr_lines_free(&lines);
    if (st != PNPR_OK) cli_report_error("bench quality", st, &err);
    return st == PNPR_OK;
}

/* What `pointnpr render --style S` computes for the raw scan c with default options
 * (plugin/cli/cmd_render.c: run_plan, then the upload, then set_profile_lines): the library's
 * stage plan for the one style, its features, its JSEG labels, its profile lines. */
static int prepare(bench *b, pnpr_cloud *c, pnpr_style style, const char *what)
{
    pnpr_plan_request req = {0};
    req.styles = 1u << style;
    pnpr_plan plan;
    pnpr_status st = pnpr_plan_make(&req, c, &plan);
    if (st != PNPR_OK) return failed(what, "plan", st);
    if (plan.want && !run_features(c, plan.want, what)) return 0;
    if (plan.segments == PNPR_PLAN_SEGMENTS_JSEG && c->count > 0 && !run_jseg(c, what)) return 0;
    return upload(b, c) && run_lines(b, c, plan.lines, what);
}

/* One row: a fresh scan of s, prepared for the row's style, rendered, measured. */
static int run_row(bench *b, const pnpr_quality_scene *s, int r, int ball)
{
    const char *prefix = ball ? "ball" : "scene";
    char what[64];
    snprintf(what, sizeof what, "%s %s", prefix, row_name[r]);
    pnpr_cloud c = {0};
    int ok = pnpr_quality_scan(s, 0, &c, NULL) == PNPR_OK && prepare(b, &c, row_style[r], what);
    pnpr_cloud_free(&c);
    double t0 = now();
    if (!ok || !render(b, row_style[r], ball ? &b->ball_m : &b->m, prefix, row_name[r])) return 0;
    double tr = now() - t0;
    if (!(ball ? measure_ball(b, &b->fig[r]) : measure_scene(b, &b->fig[r]))) return 0;
    if (!ball && r == ROW_POINTS && !write_truth(b)) return 0;
    if (r == ROW_LINES && !write_check(b, ball ? &b->ball : &b->scene, ball ? &b->ball_view : &b->view, ball))
        return 0;
    if (!ball) b->fig[r].seconds = tr;
    snprintf(what, sizeof what, "%s %s (render %.2f s) + figures", prefix, row_name[r], tr);
    note(what, t0);
    return 1;
}

/* The scan once for its size and the camera's near and far planes (the cloud's bounds), then
 * every row. */
static int run_rows(bench *b, const pnpr_quality_scene *s, int ball)
{
    pnpr_cloud c = {0};
    double t0 = now();
    if (pnpr_quality_scan(s, 0, &c, NULL) != PNPR_OK) return 0;
    note(ball ? "ball scan" : "scan", t0);
    pnpr_camera cam;
    if (ball) ball_camera(s, &cam);
    else scene_camera(s, &cam);
    int ok = make_view(&cam, &c, ball ? &b->ball_m : &b->m, ball ? &b->ball_view : &b->view);
    *(ball ? &b->ball_points : &b->points) = c.count;
    if (!ball)
        fprintf(stderr, "bench quality: scene: %zu points from %d scanners, %zu crease edges\n", c.count,
                s->scanner_count, s->edge_count);
    pnpr_cloud_free(&c);
    for (int r = 0; ok && r < ROW_COUNT; r++) ok = run_row(b, s, r, ball);
    return ok;
}

/* The house scene of the preset; the ball alone at the same relative density (sparse: twice the
 * angular step, a quarter of the points). */
static int run_scenes(bench *b)
{
    pnpr_quality_scene_init(&b->ball, PNPR_QUALITY_PRESET_BALL);
    if (b->preset == PNPR_QUALITY_PRESET_SPARSE) b->ball.step_deg *= 2;
    pnpr_quality_scene_init(&b->scene, b->preset);
    return run_rows(b, &b->ball, 1) && run_rows(b, &b->scene, 0);
}

/* ---- the report ----------------------------------------------------------------------------- */

static void print_figures(FILE *f, const bench *b)
{
    fprintf(f, "| style | crease coverage | ink precision | crease+outline coverage | ball outline (scene) "
               "| ball outline (alone) | outline ink | speckle | feature/flat ink | render s |\n"
               "|---|---|---|---|---|---|---|---|---|---|\n");
    for (int r = 0; r < ROW_COUNT; r++) {
        const figures *g = &b->fig[r];
        if (!g->done) continue;
        char tone[64];
        if (g->tone_ok)
            snprintf(tone, sizeof tone, "%.2f (%.3f / %.3f)", g->tone.ratio, g->tone.feature_darkness, g->tone.flat_darkness);
        else snprintf(tone, sizeof tone, "n/a");
        fprintf(f, "| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.4f | %s | %.2f |\n", row_name[r],
                g->lines.coverage, g->lines.precision, g->all.coverage, g->ball_scene.coverage, g->ball_alone.coverage,
                g->ink, g->speckle, tone, g->seconds);
    }
}

static const char *preset_name(pnpr_quality_preset p)
{
    return p == PNPR_QUALITY_PRESET_FULL ? "full" : (p == PNPR_QUALITY_PRESET_SPARSE ? "sparse" : "small");
}

/* The acceptance criteria of issue 11; returns how many are missed. any_density: the issue asks
 * for it at any density (cartoon outlines "not in sampling holes, at any density"), so the sparse
 * scene judges it; the others it reports only (the sparse ball's underside is barely sampled by
 * scanners above it: its silhouette there is not in the data). */
/* Prints the acceptance table to f (NULL: only counts); returns the number of figures missed. */
static int print_acceptance(FILE *f, const bench *b)
{
    const figures *L = &b->fig[ROW_LINES], *C = &b->fig[ROW_CARTOON], *S = &b->fig[ROW_SKETCHY];
    struct { const char *what; double value, limit; int at_most, any_density; } a[] = {
        {"lines: visible crease and outline edges inked within 2 px", L->all.coverage, 0.8, 0, 0},
        {"lines: visible crease edges inked within 2 px", L->lines.coverage, 0.8, 0, 0},
        {"lines: ink within 2 px of a true edge or outline (precision)", L->lines.precision, 0.8, 0, 0},
        {"lines: ball silhouette inked (ball alone)", L->ball_alone.coverage, 0.8, 0, 0},
        {"lines: ball silhouette inked (in the scene)", L->ball_scene.coverage, 0.8, 0, 0},
        {"cartoon: outline ink / drawn pixels", C->ink, 0.15, 1, 1},
        {"cartoon: speckle", C->speckle, 0.02, 1, 0},
        {"sketchy: feature / open-ground ink", S->tone_ok ? S->tone.ratio : 0, 5, 0, 0},
    };
    const int sparse = b->preset == PNPR_QUALITY_PRESET_SPARSE;
    int missed = 0;
    if (f) fprintf(f, "| acceptance (issue 11) | today | threshold | |\n|---|---|---|---|\n");
    for (size_t i = 0; i < sizeof a / sizeof *a; i++) {
        int pass = a[i].at_most ? a[i].value <= a[i].limit : a[i].value >= a[i].limit;
        int judged = !sparse || a[i].any_density;
        missed += judged && !pass;
        if (f)
            fprintf(f, "| %s | %.3f | %s %.2f | %s |\n", a[i].what, a[i].value, a[i].at_most ? "<=" : ">=", a[i].limit,
                    !judged ? "(not judged when sparse)" : (pass ? "pass" : "**miss**"));
    }
    return missed;
}

/* The figures and the acceptance table; 0 when every write succeeded. */
static int print_report(FILE *out, const void *ctx)
{
    const bench *b = ctx;
    fprintf(out, "Scene: %s, %zu points (ball alone: %zu), %zu crease edges, %dx%d, fixed camera.\n\n",
            preset_name(b->preset), b->points, b->ball_points, b->scene.edge_count, QW, QH);
    print_figures(out, b);
    fprintf(out, "\n");
    print_acceptance(out, b);
    return ferror(out) != 0;
}

static int report(const bench *b)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/figures.md", b->dir);
    pnpr_error err = {0};
    print_report(stdout, b);
    if (pnpr_output_write(path, print_report, b, &err) != PNPR_OK)
        fprintf(stderr, "pointnpr bench quality: %s\n", err.message);
    int missed = print_acceptance(NULL, b);
    fprintf(stderr, "bench quality: images and figures.md in %s; %d acceptance figure(s) missed\n", b->dir, missed);
    return missed;
}

static int usage(FILE *f, int rc)
{
    fprintf(f, "usage: pointnpr bench quality [--full | --sparse] [-o DIR] [--check]\n"
               "  picture-quality figures of every style on a generated LiDAR-like scene with known\n"
               "  edges (docs/quality.md); images and figures.md go to DIR (default bench-quality)\n"
               "  --full    the 1M-point scene (default: the small one, ~150k points)\n"
               "  --sparse  the scene at a quarter of the small one's density (~40k points); the ball\n"
               "            alone likewise; judges only the figures the issue asks at any density\n"
               "  --check   exit 1 when an acceptance threshold of issue 11 is missed\n"
               "  --scene-ply FILE  only write the scene's scan as PLY, each point labelled by the\n"
               "            surface it hit: 1 ground, 2 wall, 3 roof, 4 trunk, 5 crown, 6 sphere (a\n"
               "            generated scene with known segments, e.g. for --effects)\n");
    return rc;
}

/* Parses the options into b; returns -1 to go on, else the exit code. */
static int parse(bench *b, int argc, char **argv, int *r_check)
{
    int presets = 0;
    for (int i = 2; i < argc; i++) {
        if (!strcmp(argv[i], "--full")) { b->preset = PNPR_QUALITY_PRESET_FULL; presets++; }
        else if (!strcmp(argv[i], "--sparse")) { b->preset = PNPR_QUALITY_PRESET_SPARSE; presets++; }
        else if (!strcmp(argv[i], "--check")) *r_check = 1;
        else if ((!strcmp(argv[i], "-o") || !strcmp(argv[i], "--out")) && i + 1 < argc) b->dir = argv[++i];
        else if (!strcmp(argv[i], "--scene-ply") && i + 1 < argc) b->scene_ply = argv[++i];
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return usage(stdout, 0);
        else { fprintf(stderr, "pointnpr bench quality: unknown option %s\n", argv[i]); return usage(stderr, 2); }
    }
    if (presets > 1) { fprintf(stderr, "pointnpr bench quality: --full and --sparse exclude each other\n"); return usage(stderr, 2); }
    return -1;
}

/* --scene-ply: the house scene's scan with its surface kinds as segment labels. */
static int write_scene(const bench *b)
{
    pnpr_quality_scene s;
    pnpr_quality_scene_init(&s, b->preset);
    pnpr_cloud c = {0};
    pnpr_error err = {0};
    pnpr_status st = pnpr_quality_scan(&s, 1, &c, NULL);
    if (st == PNPR_OK) st = pnpr_write_file(b->scene_ply, &c, NULL, &err);
    if (st != PNPR_OK) fprintf(stderr, "pointnpr bench quality: %s: %s\n", b->scene_ply, err.message[0] ? err.message : pnpr_status_string(st));
    else fprintf(stderr, "bench quality: %zu labelled points -> %s\n", c.count, b->scene_ply);
    pnpr_cloud_free(&c);
    return st == PNPR_OK ? 0 : 1;
}

int cli_bench_quality(int argc, char **argv)
{
    bench *b = calloc(1, sizeof *b);
    if (!b) return 1;
    b->dir = "bench-quality";
    b->preset = PNPR_QUALITY_PRESET_SMALL;
    int check = 0, rc = parse(b, argc, argv, &check);
    if (rc >= 0) { free(b); return rc; }
    if (b->scene_ply) { rc = write_scene(b); free(b); return rc; }
    rc = 1;
    if (mkdir(b->dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "pointnpr bench quality: cannot create %s: %s\n", b->dir, strerror(errno));
        free(b);
        return 1;
    }
    pnpr_gl_context *ctx = NULL;
    pnpr_error err = {0};
    b->px = malloc((size_t)QW * QH * 4);
    if (!b->px) fprintf(stderr, "pointnpr bench quality: out of memory\n");
    else if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK || pnpr_renderer_create(NULL, &b->ren, &err) != PNPR_OK) {
        fprintf(stderr, "pointnpr bench quality: no renderer: %s\n", err.message);
        rc = ctx ? 1 : 77; /* 77: no headless GL here (tests report it as skipped) */
    } else if (run_scenes(b)) {
        int missed = report(b);
        rc = check && missed ? 1 : 0;
    }
    pnpr_renderer_destroy(b->ren);
    pnpr_gl_context_destroy(ctx);
    free(b->px);
    free(b);
    return rc;
}
#endif
