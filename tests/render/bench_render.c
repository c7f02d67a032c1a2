/* Renderer benchmark: ms/frame of each style against `points` on the same cloud and camera, in
 * one run, headless (EGL surfaceless), every point drawn (no screen-space budget). Never run by
 * ctest (timings are reported, not asserted).
 *   bench_render [IN.ply] [--size WxH] [--frames N] [--out DIR]
 * Without IN: a generated 1M-point noisy cube with computed features.
 * --out DIR: also each frame as `animate` makes it (snapshot, read back, PNG written to DIR), and
 * for the styles with strokes the vector export (drawing, SVG, PDF to DIR): times and sizes. */
#include "testutil.h"

#include <pointnpr/brush.h>
#include <pointnpr/hierarchy.h>
#include <pointnpr/features.h>
#include <pointnpr/lines.h>
#include <pointnpr/io.h>
#include <pointnpr/render.h>

#include <epoxy/gl.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static double file_mb(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? (double)sb.st_size / 1e6 : -1;
}

/* One frame as `animate` makes it: snapshot, read back, PNG. Returns ms, or -1. */
static double animate_frame(pnpr_renderer *r, const pnpr_camera *cam, const pnpr_draw_options *o, int w, int h,
                            uint8_t *px, const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.png", dir, name);
    pnpr_error err = {0};
    double s = now();
    if (pnpr_renderer_snapshot(r, cam, o, w, h, NULL, px, NULL, &err) != PNPR_OK ||
        pnpr_write_png(path, px, w, h, 0, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return -1; }
    return (now() - s) * 1e3;
}

/* The vector export of one frame: drawing, SVG, PDF; prints times and sizes. */
static void vector_export(pnpr_renderer *r, const pnpr_camera *cam, const pnpr_draw_options *o, int w, int h,
                          const char *dir, const char *name)
{
    char svg[1024], pdf[1024];
    snprintf(svg, sizeof svg, "%s/%s.svg", dir, name);
    snprintf(pdf, sizeof pdf, "%s/%s.pdf", dir, name);
    pnpr_error err = {0};
    pnpr_drawing d = {0};
    double t0 = now();
    if (pnpr_renderer_drawing(r, cam, o, w, h, &d, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return; }
    double t1 = now();
    pnpr_status a = pnpr_drawing_write_svg(&d, svg, &err);
    double t2 = now();
    pnpr_status b = pnpr_drawing_write_pdf(&d, pdf, &err);
    double t3 = now();
    if (a == PNPR_OK && b == PNPR_OK)
        printf("| %s | %zu | %.2f | %.2f | %.1f | %.2f | %.1f |\n", name, d.count, t1 - t0, t2 - t1, file_mb(svg), t3 - t2, file_mb(pdf));
    pnpr_drawing_free(&d);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The hierarchy's frame time against its leaf count (the trend of Chi & Lee's table 1): trees of
 * coarser leaves (leaf factor), the same view and stroke size; the median of `frames`. */
static void hierarchy_sweep(pnpr_renderer *r, const pnpr_cloud *c, const pnpr_camera *cam, int w, int h, int frames,
                            double base, double *ms)
{
    printf("\nhierarchy: frame time against leaf count (stroke size 12 px; and 6 px)\n"
           "| leaf factor | leaves | build s | strokes | ms/frame | x points | strokes at 6 px | ms/frame |\n"
           "|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    const float factors[4] = {1.5f, 3, 6, 12};
    for (int k = 0; k < 4; k++) {
        pnpr_sphere_tree t;
        pnpr_sphere_tree_options to = {0};
        to.leaf_factor = factors[k];
        pnpr_sphere_tree_stats ts;
        if (pnpr_sphere_tree_build(c, &to, &t, &ts, NULL) != PNPR_OK) return;
        pnpr_renderer_set_hierarchy(r, &t);
        printf("| %g | %zu | %.2f |", (double)factors[k], ts.leaves, ts.seconds);
        for (int px = 12; px >= 6; px -= 6) {
            pnpr_draw_options o;
            memset(&o, 0, sizeof o);
            o.style = PNPR_STYLE_HIERARCHY;
            o.hierarchy.stroke_px = (float)px;
            o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
            pnpr_target tg = {0, 0, 0, w, h, 1, 0};
            pnpr_render_stats st = {0};
            for (int f = -1; f < frames; f++) {
                glFinish();
                double s = now();
                if (pnpr_renderer_draw(r, cam, &o, &tg, &st, NULL) != PNPR_OK) break;
                glFinish();
                if (f >= 0) ms[f] = (now() - s) * 1e3;
            }
            qsort(ms, (size_t)frames, sizeof *ms, cmp_double);
            if (px == 12) printf(" %zu | %.1f | %.2f |", st.strokes_drawn, ms[frames / 2], ms[frames / 2] / base);
            else printf(" %zu | %.1f |", st.strokes_drawn, ms[frames / 2]);
        }
        printf("\n");
        pnpr_renderer_set_hierarchy(r, NULL);
        pnpr_sphere_tree_free(&t);
    }
}

int main(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    int w = 1024, h = 768, frames = 7;
    double gen_points = 1e6;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc) { if (sscanf(argv[++i], "%dx%d", &w, &h) != 2) return 2; }
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc) frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--points") && i + 1 < argc) gen_points = atof(argv[++i]);
        else in = argv[i];
    }
    if (frames < 1 || frames > 1000 || w < 1 || h < 1 || !(gen_points >= 6 && gen_points <= 1e9)) return 2;
    pnpr_cloud cloud = {0};
    pnpr_error err = {0};
    double t0 = now();
    if (in) {
        if (pnpr_read_file(in, NULL, &cloud, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return 1; }
    } else {
        /* 6 faces of (1/h)^2 points: h = 1/408 gives 1,000,000 points (+ shared edges); in tiles
         * of 8 x 8 x 8 colours (the brush style's clusters) */
        static const double off[3] = {0, 0, 0};
        if (pnpr_test_cube(&cloud, 1.0, 1.0 / floor(sqrt(gen_points / 6)), 0.0004, off, 11) != PNPR_OK) return 1;
        if (pnpr_cloud_alloc_rgb(&cloud) != PNPR_OK) return 1;
        for (size_t i = 0; i < cloud.count; i++)
            for (int c = 0; c < 3; c++) cloud.rgb[3 * i + c] = (uint8_t)(90 + 20 * ((int)floor(cloud.xyz[3 * i + c] * 8 + 4) & 3));
    }
    double t_read = now() - t0;
    t0 = now();
    if (!pnpr_cloud_find_property(&cloud, "feature_class")) {
        pnpr_features_options fo = {0};
        if (pnpr_compute_features(&cloud, &fo, NULL) != PNPR_OK) { fprintf(stderr, "features failed\n"); return 1; }
    }
    double t_feat = now() - t0;
    t0 = now();
    pnpr_brush_stats bs;
    if (pnpr_brush_prepare(&cloud, NULL, &bs, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return 1; }
    double t_brush = now() - t0;
    t0 = now();
    pnpr_sphere_tree tree;
    pnpr_sphere_tree_stats ts;
    if (pnpr_sphere_tree_build(&cloud, NULL, &tree, &ts, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return 1; }
    double t_tree = now() - t0;

    pnpr_gl_context *ctx = NULL;
    if (pnpr_gl_context_create(&ctx, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return 1; }
    pnpr_renderer *r = NULL;
    if (pnpr_renderer_create(NULL, &r, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return 1; }
    t0 = now();
    if (pnpr_renderer_set_cloud(r, &cloud, NULL, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return 1; }
    double t_upload = now() - t0;
    pnpr_renderer_set_hierarchy(r, &tree);
    t0 = now();
    pnpr_polylines lines = {0};
    if (pnpr_profile_lines(&cloud, NULL, &lines, NULL) != PNPR_OK) { fprintf(stderr, "profile lines failed\n"); return 1; }
    if (pnpr_renderer_set_lines(r, &lines, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return 1; }
    double t_lines = now() - t0;
    pnpr_lines_free(&lines);
    static const double dir[3] = {1, -1.6, 1.1};
    pnpr_camera cam;
    if (pnpr_camera_fit(&cloud, dir, 45, (float)w / h, &cam) != PNPR_OK) return 1;

    const char *renderer_name = (const char *)glGetString(GL_RENDERER);
    printf("cloud: %s, %zu points; %dx%d; %s; median of %d frames (after 1 warm-up)\n",
           in ? in : "generated noisy cube", cloud.count, w, h, renderer_name ? renderer_name : "?", frames);
    printf("read %.2f s, features %.2f s, brush preparation %.2f s (%zu clusters), sphere hierarchy %.2f s (%zu leaves, "
           "%zu regions), upload (kNN spacing + queue) %.2f s, profile lines + upload %.2f s\n",
           t_read, t_feat, t_brush, bs.clusters, t_tree, ts.leaves, ts.regions, t_upload, t_lines);
    printf("| style | points drawn | strokes | ms/frame | x points |%s\n|---|---:|---:|---:|---:|%s\n",
           out ? " animate frame: + read back + PNG, ms |" : "", out ? "---:|" : "");
    uint8_t *px = out ? malloc((size_t)w * h * 4) : NULL;
    if (out && !px) return 1;
    /* outline: 0 = the style's default, -1 = off, 1 = on (the cost of the outline passes) */
    struct { const char *name; pnpr_style style; pnpr_sketch_variant v; float faint; int outline; } runs[] = {
        {"points", PNPR_STYLE_POINTS, PNPR_SKETCH_ALL, 0, 0},
        {"sketchy (a) directional", PNPR_STYLE_SKETCHY, PNPR_SKETCH_DIRECTIONAL, 0, 0},
        {"sketchy (a), outline on", PNPR_STYLE_SKETCHY, PNPR_SKETCH_DIRECTIONAL, 0, 1},
        {"sketchy (b) + non-directional", PNPR_STYLE_SKETCHY, PNPR_SKETCH_NONDIRECTIONAL, 0, 0},
        {"sketchy (c) + dithering", PNPR_STYLE_SKETCHY, PNPR_SKETCH_ALL, 0, 0},
        {"lines", PNPR_STYLE_LINES, PNPR_SKETCH_ALL, 0, 0},
        {"lines, outline off", PNPR_STYLE_LINES, PNPR_SKETCH_ALL, 0, -1},
        {"lines --faint 0.3", PNPR_STYLE_LINES, PNPR_SKETCH_ALL, 0.3f, 0},
        {"stipple", PNPR_STYLE_STIPPLE, PNPR_SKETCH_ALL, 0, 0},
        {"cartoon", PNPR_STYLE_CARTOON, PNPR_SKETCH_ALL, 0, 0},
        {"cartoon, outline off", PNPR_STYLE_CARTOON, PNPR_SKETCH_ALL, 0, -1},
        {"painterly", PNPR_STYLE_PAINTERLY, PNPR_SKETCH_ALL, 0, 0},
        {"brush", PNPR_STYLE_BRUSH, PNPR_SKETCH_ALL, 0, 0},
        {"brush, moving (--brush-blur 1.5)", PNPR_STYLE_BRUSH, PNPR_SKETCH_ALL, 0, 0},
        {"hierarchy", PNPR_STYLE_HIERARCHY, PNPR_SKETCH_ALL, 0, 0},
    };
    double base = 0;
    double *ms = malloc(sizeof(double) * (size_t)frames);
    for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
        pnpr_draw_options o;
        memset(&o, 0, sizeof o);
        o.style = runs[k].style;
        o.density = -1; /* every point (the worst case, as docs/benchmarks.md reports it) */
        o.sketch_variant = runs[k].v;
        o.faint = runs[k].faint;
        o.outline = runs[k].outline;
        o.brush_blur = strstr(runs[k].name, "blur") ? 1.5f : 0.0f;
        o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
        pnpr_target t = {0, 0, 0, w, h, 1, 0};
        pnpr_render_stats st;
        for (int f = -1; f < frames; f++) {
            glFinish();
            double s = now();
            if (pnpr_renderer_draw(r, &cam, &o, &t, &st, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return 1; }
            glFinish();
            if (f >= 0) ms[f] = (now() - s) * 1e3;
        }
        qsort(ms, (size_t)frames, sizeof *ms, cmp_double);
        double med = ms[frames / 2];
        if (k == 0) base = med;
        printf("| %s | %zu | %zu | %.1f | %.2f |", runs[k].name, st.points_drawn, st.strokes_drawn, med, med / base);
        if (out) {
            char name[64];
            snprintf(name, sizeof name, "frame-%zu", k);
            printf(" %.1f |", animate_frame(r, &cam, &o, w, h, px, out, name));
        }
        printf("\n");
    }
    hierarchy_sweep(r, &cloud, &cam, w, h, frames, base, ms);
    free(ms);
    pnpr_renderer_set_hierarchy(r, NULL);
    pnpr_sphere_tree_free(&tree);
    if (out) {
        printf("\nvector export, %dx%d:\n| style | paths | drawing s | SVG s | SVG MB | PDF s | PDF MB |\n|---|---:|---:|---:|---:|---:|---:|\n", w, h);
        const pnpr_style vs[4] = {PNPR_STYLE_SKETCHY, PNPR_STYLE_STIPPLE, PNPR_STYLE_LINES, PNPR_STYLE_CARTOON};
        for (int k = 0; k < 4; k++) {
            pnpr_draw_options o;
            memset(&o, 0, sizeof o);
            o.style = vs[k];
            o.density = -1;
            o.background[0] = o.background[1] = o.background[2] = o.background[3] = 1;
            vector_export(r, &cam, &o, w, h, out, pnpr_style_name(vs[k]));
        }
    }
    free(px);
    pnpr_renderer_destroy(r);
    pnpr_gl_context_destroy(ctx);
    pnpr_cloud_free(&cloud);
    return 0;
}
