/* Generated scenes with a known up for the default-view tests (tests/test_view.c,
 * tests/render/test_render_view.c): a square ground with boxes standing on it, built in ground
 * coordinates (g0, g1 across the ground, h above it) and placed in the world by a frame, so that
 * the same scene can be z-up, y-up or an RGB-D camera frame (y down, z forward). Header only
 * (static inline) so that both test executables share it. */
#ifndef PNPR_TEST_VIEW_SCENE_H
#define PNPR_TEST_VIEW_SCENE_H

#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct view_frame {
    double at[3];                 /* world position of the ground's centre */
    double e0[3], e1[3], up[3];   /* world directions of g0, g1 and h */
    double scale;                 /* world units per ground unit */
    double origin[3];             /* the cloud's origin */
} view_frame;

typedef struct view_box { double c0, c1, s0, s1, height; } view_box;

typedef struct view_scene {
    double side, spacing, noise, wave; /* ground side, sample spacing, noise sigma, terrain wave */
    const view_box *boxes;
    int box_count;
} view_scene;

/* z up, origin (5e6, 5e6, 0) */
static inline view_frame view_frame_zup(void)
{
    view_frame f = {{5e6 + 3, 5e6 - 2, 40}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 1, {5e6, 5e6, 0}};
    return f;
}
/* y up (z up turned: x, y, z -> x, z, -y), origin (5e6, 0, 5e6) */
static inline view_frame view_frame_yup(void)
{
    view_frame f = {{5e6 - 4, 12, 5e6 + 1}, {1, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1, {5e6, 0, 5e6}};
    return f;
}
/* an RGB-D frame in camera coordinates: y down, z forward, the camera at the world origin
 * (= the cloud's origin), the ground 1.2 below it, the scene scaled to 3 m at z 1..4 */
static inline view_frame view_frame_rgbd(double side)
{
    view_frame f = {{0, 1.2, 2.5}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0}, 3.0 / side, {0, 0, 0}};
    return f;
}

static inline int view_under_box(const view_scene *s, double g0, double g1)
{
    for (int b = 0; b < s->box_count; b++) {
        const view_box *x = &s->boxes[b];
        if (fabs(g0 - x->c0) < 0.5 * x->s0 && fabs(g1 - x->c1) < 0.5 * x->s1) return 1;
    }
    return 0;
}

/* Ground coordinates of every sample (3 per point) into *r (malloc'd); returns the count. */
static inline size_t view_scene_samples(const view_scene *s, double **r)
{
    size_t cap = 1024, n = 0;
    double *p = malloc(3 * cap * sizeof *p);
    int m = (int)(s->side / s->spacing + 0.5);
#define VIEW_PUSH(a, b, c) do { if (n == cap) { cap *= 2; p = realloc(p, 3 * cap * sizeof *p); } \
    p[3 * n] = (a); p[3 * n + 1] = (b); p[3 * n + 2] = (c); n++; } while (0)
    for (int i = 0; i <= m; i++)
        for (int j = 0; j <= m; j++) {
            double g0 = -0.5 * s->side + i * s->spacing, g1 = -0.5 * s->side + j * s->spacing;
            if (!view_under_box(s, g0, g1))
                VIEW_PUSH(g0, g1, s->wave * sin(6.283185 * g0 / s->side) * cos(6.283185 * g1 / s->side));
        }
    for (int b = 0; b < s->box_count; b++) {
        const view_box *x = &s->boxes[b];
        int n0 = (int)(x->s0 / s->spacing) + 1, n1 = (int)(x->s1 / s->spacing) + 1, nh = (int)(x->height / s->spacing) + 1;
        for (int i = 0; i <= n0; i++)
            for (int j = 0; j <= n1; j++) /* top */
                VIEW_PUSH(x->c0 + x->s0 * (i / (double)n0 - 0.5), x->c1 + x->s1 * (j / (double)n1 - 0.5), x->height);
        for (int k = 0; k < nh; k++) {
            double h = x->height * k / nh;
            for (int i = 0; i <= n0; i++) { /* the four sides */
                double g0 = x->c0 + x->s0 * (i / (double)n0 - 0.5);
                VIEW_PUSH(g0, x->c1 - 0.5 * x->s1, h);
                VIEW_PUSH(g0, x->c1 + 0.5 * x->s1, h);
            }
            for (int j = 1; j < n1; j++) {
                double g1 = x->c1 + x->s1 * (j / (double)n1 - 0.5);
                VIEW_PUSH(x->c0 - 0.5 * x->s0, g1, h);
                VIEW_PUSH(x->c0 + 0.5 * x->s0, g1, h);
            }
        }
    }
#undef VIEW_PUSH
    *r = p;
    return n;
}

/* World coordinate of ground coordinates g through frame f. */
static inline void view_to_world(const view_frame *f, const double g[3], double w[3])
{
    for (int a = 0; a < 3; a++) w[a] = f->at[a] + f->scale * (g[0] * f->e0[a] + g[1] * f->e1[a] + g[2] * f->up[a]);
}

/* The scene in frame f, with `extra` spare points at the end (zero offsets) for outliers. */
static inline pnpr_status view_make(pnpr_cloud *c, const view_scene *s, const view_frame *f, size_t extra, uint64_t seed)
{
    double *g;
    size_t n = view_scene_samples(s, &g);
    pnpr_status st = pnpr_cloud_alloc(c, n + extra);
    if (st != PNPR_OK) { free(g); return st; }
    memcpy(c->origin, f->origin, sizeof c->origin);
    pnpr_test_rng rng = {seed};
    for (size_t i = 0; i < n; i++) {
        double w[3];
        view_to_world(f, g + 3 * i, w);
        for (int a = 0; a < 3; a++)
            c->xyz[3 * i + a] = (float)(w[a] - f->origin[a] + s->noise * f->scale * pnpr_test_normal(&rng));
    }
    free(g);
    return PNPR_OK;
}

static const view_box VIEW_TOWN_BOXES[] = {
    {-25, -20, 15, 10, 12}, {20, -25, 10, 10, 20}, {0, 20, 25, 12, 8}, {30, 25, 8, 8, 15}, {-30, 25, 6, 14, 10}};
/* 100 x 100 ground, five boxes 8..20 high, spacing 0.5, noise 0.02 */
static inline view_scene view_town(void)
{
    view_scene s = {100, 0.5, 0.02, 0, VIEW_TOWN_BOXES, (int)(sizeof VIEW_TOWN_BOXES / sizeof VIEW_TOWN_BOXES[0])};
    return s;
}

static const view_box VIEW_AERIAL_BOXES[] = {
    {-60, -50, 20, 12, 5}, {40, -60, 15, 15, 4}, {-20, 30, 25, 10, 5}, {60, 50, 12, 20, 3.5}, {10, -10, 8, 8, 4.5},
    {-70, 70, 10, 10, 5}, {75, -5, 14, 9, 4}};
/* 200 x 200 gently waving terrain (+-0.5), buildings 3.5..5 high: flat and wide */
static inline view_scene view_aerial(void)
{
    view_scene s = {200, 1, 0.05, 0.5, VIEW_AERIAL_BOXES, (int)(sizeof VIEW_AERIAL_BOXES / sizeof VIEW_AERIAL_BOXES[0])};
    return s;
}

#endif
