/* The traversal of Chi & Lee's sphere hierarchy (sec. 4, fig. 6; include/pointnpr/hierarchy.h):
 *  - region nodes: from the root down while S > abstraction x S(root) (sec. 4.1); with an
 *    importance map the threshold is lowered to (1 - importance) times that, the importance read
 *    at the node's projected centre and four points a projected radius away (the paper goes down
 *    to the stroke nodes and back up; reading around the node gives the same choice without a
 *    second pass, docs/hierarchy.md);
 *  - stroke nodes below each region node: down while the projected diameter exceeds stroke_px
 *    (view-dependent, eq. 7) or the radius exceeds stroke_radius (view-independent, eq. 6);
 *  - the smooth level transition (sec. 4.2.3): a stroke node n of size s_n <= T below a parent p of
 *    size s_p > T is drawn as the node interpolated towards p by u = (T - s_n) / (s_p - s_n): at
 *    u = 1 (p just split) n sits where p was, at u = 0 (n about to split) it is itself. The child
 *    G nearest to p's centre with the largest radius (largest radius minus distance) keeps alpha
 *    1, the other fades with alpha 1 - u, so one parent turns into its two children without a jump;
 *  - a node with |n.v| < sin(ThresholdDegree) is drawn as a silhouette stroke along the outline
 *    instead of a paint stroke (sec. 4.3);
 *  - region borders: leaf pairs adjacent across two regions of the cut at border_level, drawn as
 *    short ink strokes along the border between them (sec. 4.3: "we use leaf nodes");
 *  - strokes along the region node's (or node's) direction with Perlin noise on angle and
 *    brightness; the tone (TAM layer) from the light, the shading also in the paint colour.
 * Culling: the frustum only. The normals are unsigned fits, so the normal cone cannot tell front
 * from back; hidden strokes are removed by the renderer's depth pass (the paper's first pass). */
#include "sphere_internal.h"

#include <pointnpr/brush.h>
#include <pointnpr/options.h>

#include "../core/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Silhouettes: width in pixels, the darkening of the paint colour, the opacity. */
#define SILHOUETTE_PX 2.5
#define SILHOUETTE_OUT 0.6
#define SILHOUETTE_TINT 0.3
#define SILHOUETTE_ALPHA 0.85
/* The ink maps: no ink below this darkness (1 - light); strokes overlapping a pixel, about
 * (stroke_scale x node extent)^2 x stretch x pi / node area: 1.0^2 x 2.2 ~ 2.2, rounded up. */
#define INK_PAPER 0.1
#define INK_FLOOR 0.1
#define INK_OVERLAP 2.5

typedef struct trav {
    const pnpr_sphere_tree *t;
    const pnpr_hier_view *v;
    pnpr_hier_params p;
    double planes[6][4];
    double eye[3], right[3], up[3], back[3], light[3];
    float t_abs, t_px;
    pnpr_hier_stroke *out;
    size_t cap, np, ni;
    pnpr_hier_counts *c;
} trav;

typedef struct draw_node { /* a node as drawn: interpolated towards its parent */
    double c[3], n[3], d[3], col[3];
    double r, noise, alpha;
} draw_node;

/* ---- camera ----------------------------------------------------------------------------------- */

static void frustum(trav *s)
{
    const float *V = s->v->view, *P = s->v->proj;
    double m[16];
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double a = 0;
            for (int k = 0; k < 4; k++) a += (double)P[k * 4 + r] * V[c * 4 + k];
            m[c * 4 + r] = a;
        }
    for (int i = 0; i < 6; i++) {
        int row = i / 2;
        double sg = i % 2 ? -1.0 : 1.0, *pl = s->planes[i];
        for (int c = 0; c < 4; c++) pl[c] = m[c * 4 + 3] + sg * m[c * 4 + row];
        double len = sqrt(pl[0] * pl[0] + pl[1] * pl[1] + pl[2] * pl[2]);
        if (len > 0)
            for (int c = 0; c < 4; c++) pl[c] /= len;
    }
    for (int k = 0; k < 3; k++) {
        s->eye[k] = 0;
        for (int i = 0; i < 3; i++) s->eye[k] -= (double)V[4 * k + i] * V[12 + i];
        s->right[k] = V[4 * k];
        s->up[k] = V[4 * k + 1];
        s->back[k] = V[4 * k + 2];
    }
    double l[3] = {s->p.light[0], s->p.light[1], s->p.light[2]};
    if (pnpr_dot3(l, l) == 0) { l[0] = -0.35; l[1] = 0.6; l[2] = 0.72; } /* upper left, towards the viewer */
    pnpr_normalize3(l);
    for (int k = 0; k < 3; k++) s->light[k] = l[0] * s->right[k] + l[1] * s->up[k] + l[2] * s->back[k];
}

static int culled(const trav *s, const float c[3], float r)
{
    for (int i = 0; i < 6; i++) {
        const double *pl = s->planes[i];
        if (pl[0] * c[0] + pl[1] * c[1] + pl[2] * c[2] + pl[3] < -(double)r) return 1;
    }
    return 0;
}

static double eye_depth(const trav *s, const double c[3])
{
    const float *V = s->v->view;
    return -(V[2] * c[0] + V[6] * c[1] + V[10] * c[2] + V[14]);
}

/* Projected diameter in pixels (huge when the sphere reaches the camera). */
static double screen_size(const trav *s, const float cf[3], double r)
{
    if (s->v->ortho) return 2.0 * r * s->v->pixels_per_unit;
    double c[3] = {cf[0], cf[1], cf[2]}, z = eye_depth(s, c);
    return z > r ? 2.0 * r * s->v->pixels_per_unit / z : 1e30;
}

/* The importance (0..1) at world offset c, 0 without a map or outside the image. */
static double importance_at(const trav *s, const double c[3])
{
    const pnpr_hier_params *p = &s->p;
    const float *V = s->v->view, *P = s->v->image_proj ? s->v->image_proj : s->v->proj;
    double e[4], q[4];
    for (int r = 0; r < 4; r++) e[r] = V[r] * c[0] + V[4 + r] * c[1] + V[8 + r] * c[2] + V[12 + r];
    for (int r = 0; r < 4; r++) q[r] = P[r] * e[0] + P[4 + r] * e[1] + P[8 + r] * e[2] + P[12 + r] * e[3];
    if (!(q[3] > 0)) return 0;
    double x = (q[0] / q[3] * 0.5 + 0.5) * p->importance_w, y = (0.5 - q[1] / q[3] * 0.5) * p->importance_h;
    if (!(x >= 0 && y >= 0 && x < p->importance_w && y < p->importance_h)) return 0;
    return p->importance[(size_t)y * (size_t)p->importance_w + (size_t)x] / 255.0;
}

/* The largest importance at the node's projected centre and a projected radius around it. */
static double node_importance(const trav *s, const pnpr_sphere_node *n)
{
    if (!s->p.importance) return 0;
    double best = 0;
    for (int i = 0; i < 5; i++) {
        double c[3], off = i == 0 ? 0 : n->extent, sx = i == 1 ? 1 : i == 2 ? -1 : 0, sy = i == 3 ? 1 : i == 4 ? -1 : 0;
        for (int k = 0; k < 3; k++) c[k] = n->centre[k] + off * (sx * s->right[k] + sy * s->up[k]);
        double v = importance_at(s, c);
        if (v > best) best = v;
    }
    return best;
}

/* ---- output ----------------------------------------------------------------------------------- */

static pnpr_hier_stroke *slot(trav *s, pnpr_hier_kind kind)
{
    s->c->strokes[kind]++;
    if (!s->out || s->np + s->ni >= s->cap) { s->c->truncated = 1; return NULL; }
    return kind == PNPR_HIER_PAINT ? &s->out[s->np++] : &s->out[s->cap - 1 - s->ni++];
}

static void put(pnpr_hier_stroke *o, const double c[3], const double u[3], const double v[3], const double col[3],
                double alpha, double tone)
{
    for (int k = 0; k < 3; k++) {
        o->pos[k] = (float)c[k];
        o->u[k] = (float)u[k];
        o->v[k] = (float)v[k];
        double x = col[k] * 255.0;
        o->rgba[k] = (uint8_t)lrint(x < 0 ? 0 : x > 255 ? 255 : x);
    }
    o->rgba[3] = (uint8_t)lrint((alpha < 0 ? 0 : alpha > 1 ? 1 : alpha) * 255.0);
    o->tone = (float)tone;
}

/* The ink strokes were written backwards from the end: put them after the paint strokes. */
static void pack(trav *s)
{
    if (!s->out) return;
    pnpr_hier_stroke *ink = s->out + s->cap - s->ni;
    for (size_t i = 0; i < s->ni / 2; i++) {
        pnpr_hier_stroke tmp = ink[i];
        ink[i] = ink[s->ni - 1 - i];
        ink[s->ni - 1 - i] = tmp;
    }
    memmove(s->out + s->np, ink, s->ni * sizeof *ink);
}

/* ---- strokes ---------------------------------------------------------------------------------- */

static void view_vector(const trav *s, const double c[3], double r_v[3])
{
    for (int k = 0; k < 3; k++) r_v[k] = s->v->ortho ? s->back[k] : s->eye[k] - c[k];
    if (pnpr_normalize3(r_v) == 0) memcpy(r_v, s->back, sizeof s->back);
}

/* One pixel in cloud units at c. */
static double pixel_size(const trav *s, const double c[3])
{
    double z = s->v->ortho ? 1.0 : fmax(eye_depth(s, c), 1e-9);
    return z / s->v->pixels_per_unit;
}

/* A silhouette stroke along the outline: a line SILHOUETTE_PX wide whatever the stroke size (a
 * line, not a dab), as long as the node's stroke, moved from the node's centre (inside a curved
 * outline) out towards the outline by SILHOUETTE_OUT of its extent; paint: the node's colour
 * darkened, slightly transparent (an illustrator's tinted contour), the ink maps: ink. */
static void silhouette(trav *s, const draw_node *d, const double n[3], const double vv[3])
{
    double t[3], w[3], u[3], v[3], col[3], c[3], out[3];
    pnpr_cross3(n, vv, t);
    if (pnpr_normalize3(t) < 1e-9) return;
    pnpr_cross3(vv, t, w);
    pnpr_normalize3(w);
    double nv = pnpr_dot3(n, vv);
    for (int k = 0; k < 3; k++) out[k] = n[k] - nv * vv[k];
    if (pnpr_normalize3(out) < 1e-9) memset(out, 0, sizeof out);
    for (int k = 0; k < 3; k++) c[k] = d->c[k] + SILHOUETTE_OUT * d->r * out[k];
    double len = d->r * s->p.stroke_scale * s->p.stretch, half_w = 0.5 * SILHOUETTE_PX * pixel_size(s, c);
    for (int k = 0; k < 3; k++) {
        u[k] = t[k] * len;
        v[k] = w[k] * half_w;
        col[k] = s->p.tam == PNPR_TAM_PAINT ? d->col[k] / 255.0 * SILHOUETTE_TINT : s->p.ink[k];
    }
    pnpr_hier_stroke *o = slot(s, PNPR_HIER_SILHOUETTE);
    if (o) put(o, c, u, v, col, d->alpha * SILHOUETTE_ALPHA, PNPR_HIER_LINE_LAYER);
}

/* The ink maps' tone for a light level: the faint INK_FLOOR where the surface is lit (darkness
 * below INK_PAPER: a lit plane keeps a few strokes and does not vanish), then the coverage that,
 * laid down by about INK_OVERLAP overlapping strokes
 * (1 - (1 - c)^n), gives the darkness (a painter's value scale; without it, overlapping strokes
 * darken every tone: the first pictures drowned the features in ink). Returns the layer (with a
 * fraction) and *r_fade, the stroke's alpha below tone 0's coverage. */
static double ink_tone(double darkness, double *r_fade)
{
    double want = (darkness - INK_PAPER) / (1.0 - INK_PAPER);
    want = INK_FLOOR + (1.0 - INK_FLOOR) * (want < 0 ? 0 : want > 1 ? 1 : want);
    double c = 1.0 - pow(1.0 - 0.9 * want, 1.0 / INK_OVERLAP);
    *r_fade = 1.0;
    double c0 = pnpr_tam_tone_coverage(0);
    if (c <= c0) { *r_fade = c0 > 0 ? c / c0 : 0; return 0; }
    for (int t = 1; t < PNPR_TAM_TONES; t++) {
        double a = pnpr_tam_tone_coverage(t - 1), b = pnpr_tam_tone_coverage(t);
        if (c <= b) return (t - 1) + (c - a) / (b - a);
    }
    return PNPR_TAM_TONES - 1;
}

/* The stroke's axes: the direction in the tangent plane, turned by the noise. */
static void stroke_axes(const trav *s, const draw_node *d, const double n[3], const float *dir, double r_t[3],
                        double r_b[3])
{
    double dd[3] = {dir[0], dir[1], dir[2]}, t[3];
    float tf[3], nf[3] = {(float)n[0], (float)n[1], (float)n[2]}, bf[3];
    pnpr_sphere_tangent(nf, dd, tf);
    if (tf[0] == 0 && tf[1] == 0 && tf[2] == 0) pnpr_householder_frame(nf, tf, bf);
    for (int k = 0; k < 3; k++) t[k] = tf[k];
    double a = s->p.noise_angle > 0 ? s->p.noise_angle * 0.017453293 * d->noise : 0, nt[3];
    pnpr_cross3(n, t, nt);
    for (int k = 0; k < 3; k++) r_t[k] = cos(a) * t[k] + sin(a) * nt[k];
    pnpr_cross3(n, r_t, r_b);
}

static void paint(trav *s, const draw_node *d, const pnpr_sphere_node *R)
{
    double n[3] = {d->n[0], d->n[1], d->n[2]}, vv[3], t[3], b[3], u[3], v[3], col[3];
    view_vector(s, d->c, vv);
    int known = pnpr_dot3(n, n) > 0.25;
    if (known) {
        pnpr_normalize3(n);
        if (pnpr_dot3(n, vv) < 0)
            for (int k = 0; k < 3; k++) n[k] = -n[k];
        if (s->p.silhouette_deg > 0 && !s->p.fine_layer && pnpr_dot3(n, vv) < sin(s->p.silhouette_deg * 0.017453293)) {
            silhouette(s, d, n, vv);
            return;
        }
    } else {
        memcpy(n, s->back, sizeof n);
    }
    float dir[3];
    pnpr_sphere_dir(R, dir);
    if (s->p.node_direction || s->p.fine_layer)
        for (int k = 0; k < 3; k++) dir[k] = (float)d->d[k];
    stroke_axes(s, d, n, dir, t, b);
    double shade = known ? fmax(0.0, pnpr_dot3(n, s->light)) : 0.8;
    double tone = (1.0 - shade) * (PNPR_TAM_TONES - 1), fade = 1.0; /* between two layers: blended */
    if (s->p.tam != PNPR_TAM_PAINT) {
        tone = ink_tone(1.0 - shade, &fade);
        for (int k = 0; k < 3; k++) col[k] = s->p.ink[k];
    } else {
        /* the light in the paint too (TAM tones alone leave colourless scans flat) */
        double dark = (s->t->has_rgb ? 0.35 : 0.6) * (1.0 - shade);
        double jit = s->p.noise_colour > 0 ? s->p.noise_colour * d->noise : 0;
        for (int k = 0; k < 3; k++) {
            double base = s->p.node_colour || s->p.fine_layer ? d->col[k] : (double)R->colour[k];
            col[k] = base / 255.0 * (1.0 - dark) * (1.0 + jit);
        }
    }
    double w = d->r * s->p.stroke_scale;
    for (int k = 0; k < 3; k++) {
        u[k] = t[k] * w * s->p.stretch;
        v[k] = b[k] * w;
    }
    pnpr_hier_stroke *o = slot(s, PNPR_HIER_PAINT);
    if (o) put(o, d->c, u, v, col, d->alpha * fade, tone);
    s->c->weighted += d->alpha;
}

/* ---- the walk --------------------------------------------------------------------------------- */

static void from_node(const pnpr_sphere_tree *t, const pnpr_sphere_node *n, draw_node *d)
{
    float nn[3], dd[3];
    pnpr_sphere_normal(n, nn);
    pnpr_sphere_dir(n, dd);
    for (int k = 0; k < 3; k++) {
        d->c[k] = n->centre[k];
        d->n[k] = nn[k];
        d->d[k] = dd[k];
        d->col[k] = n->colour[k];
    }
    d->r = n->extent;
    d->noise = pnpr_sphere_noise(t, n);
    d->alpha = 1.0;
}

/* Whether n is its parent's child G: the largest radius minus distance to the parent's centre. */
static int is_g(const pnpr_sphere_tree *t, uint32_t ni)
{
    const pnpr_sphere_node *p = &t->nodes[t->nodes[ni].parent];
    double best = -HUGE_VAL;
    uint32_t g = p->child[0];
    for (int i = 0; i < 2; i++) {
        const pnpr_sphere_node *c = &t->nodes[p->child[i]];
        double d[3] = {(double)c->centre[0] - p->centre[0], (double)c->centre[1] - p->centre[1], (double)c->centre[2] - p->centre[2]};
        double score = c->extent - sqrt(pnpr_dot3(d, d));
        if (score > best) { best = score; g = p->child[i]; }
    }
    return g == ni;
}

/* Node ni drawn at size sn below threshold T (the smooth transition towards its parent). */
static void interpolate(const trav *s, uint32_t ni, double sn, double T, draw_node *d)
{
    const pnpr_sphere_node *n = &s->t->nodes[ni];
    draw_node p;
    from_node(s->t, n, d);
    from_node(s->t, &s->t->nodes[n->parent], &p);
    double sp = screen_size(s, s->t->nodes[n->parent].centre, p.r);
    double u = sp > sn ? (T - sn) / (sp - sn) : 0;
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    double sn_ = pnpr_dot3(d->n, p.n) < 0 ? -1 : 1;
    double sd = pnpr_dot3(d->d, p.d) < 0 ? -1 : 1;
    for (int k = 0; k < 3; k++) {
        d->c[k] += u * (p.c[k] - d->c[k]);
        d->n[k] += u * (sn_ * p.n[k] - d->n[k]);
        d->d[k] += u * (sd * p.d[k] - d->d[k]);
        d->col[k] += u * (p.col[k] - d->col[k]);
    }
    d->r += u * (p.r - d->r);
    d->noise += u * (p.noise - d->noise);
    d->alpha = is_g(s->t, ni) ? 1.0 : 1.0 - u;
}

/* The fine layer's test: curvature or colour difference to the region (sec. 5.1's classes). */
static int detailed(const pnpr_sphere_node *n, const pnpr_sphere_node *R)
{
    float a[3], b[3];
    pnpr_sphere_colour(n, a);
    pnpr_sphere_colour(R, b);
    return pnpr_sphere_curvature(n) > 0.05f || pnpr_sphere_colour_distance(a, b) > 12.0;
}

static void emit(trav *s, uint32_t ni, uint32_t ri, double sn, double T)
{
    const pnpr_sphere_node *n = &s->t->nodes[ni], *R = &s->t->nodes[ri];
    if (s->p.fine_layer && !detailed(n, R)) return;
    draw_node d;
    if (!s->p.no_smooth && s->p.stroke_radius <= 0 && ni != ri) interpolate(s, ni, sn, T, &d);
    else from_node(s->t, n, &d);
    if (d.alpha > 0) paint(s, &d, R);
}

/* The stroke nodes below region node ri. */
static void region_strokes(trav *s, uint32_t ri, uint32_t *stack)
{
    const pnpr_sphere_node *nodes = s->t->nodes;
    size_t top = 0;
    stack[top++] = ri;
    while (top) {
        uint32_t i = stack[--top];
        const pnpr_sphere_node *n = &nodes[i];
        if (i != ri && culled(s, n->centre, n->radius)) continue;
        int vi = s->p.stroke_radius > 0;
        double sn = vi ? n->extent : screen_size(s, n->centre, n->extent);
        double T = vi ? s->p.stroke_radius : s->t_px * (1.0 - 0.5 * node_importance(s, n));
        if (n->child[0] == PNPR_INDEX_NONE || sn <= T) {
            emit(s, i, ri, sn, T);
            continue;
        }
        stack[top++] = n->child[1];
        stack[top++] = n->child[0];
    }
}

static void walk(trav *s, uint32_t *stack, uint32_t *stack2)
{
    const pnpr_sphere_node *nodes = s->t->nodes;
    size_t top = 0;
    stack[top++] = s->t->root;
    while (top) {
        uint32_t i = stack[--top];
        const pnpr_sphere_node *n = &nodes[i];
        if (culled(s, n->centre, n->radius)) continue;
        double T = s->t_abs * (1.0 - node_importance(s, n));
        if (n->child[0] == PNPR_INDEX_NONE || n->dissimilarity <= T) {
            s->c->region_nodes++;
            region_strokes(s, i, stack2);
            continue;
        }
        stack[top++] = n->child[1];
        stack[top++] = n->child[0];
    }
}

/* ---- region borders --------------------------------------------------------------------------- */

static uint32_t find_root(uint32_t *par, uint32_t i)
{
    while (par[i] != i) {
        par[i] = par[par[i]];
        i = par[i];
    }
    return i;
}

static void border_stroke(trav *s, const pnpr_sphere_node *a, const pnpr_sphere_node *b)
{
    float nf[3];
    pnpr_sphere_normal(a, nf);
    double c[3], d[3], n[3] = {nf[0], nf[1], nf[2]}, t[3], w[3], u[3], v[3];
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * ((double)a->centre[k] + b->centre[k]);
        d[k] = (double)b->centre[k] - a->centre[k];
    }
    if (pnpr_dot3(n, n) < 0.25) memcpy(n, s->back, sizeof n);
    pnpr_cross3(n, d, t);
    if (pnpr_normalize3(t) < 1e-12) return;
    pnpr_cross3(n, t, w);
    pnpr_normalize3(w);
    double px = pixel_size(s, c);
    double half_w = fmax(0.12 * s->t->spacing, 0.7 * px), half_l = fmax(0.6 * s->t->spacing, 1.5 * px);
    for (int k = 0; k < 3; k++) {
        u[k] = t[k] * half_l;
        v[k] = w[k] * half_w;
    }
    double ink[3] = {s->p.ink[0], s->p.ink[1], s->p.ink[2]};
    pnpr_hier_stroke *o = slot(s, PNPR_HIER_BORDER);
    if (o) put(o, c, u, v, ink, 1.0, PNPR_HIER_LINE_LAYER);
}

/* Borders between the regions of the cut at border_level: merges in order while their level
 * stays within it (levels never decrease), union-find over the region ids. */
static pnpr_status borders(trav *s)
{
    const pnpr_sphere_tree *t = s->t;
    if (s->p.border_level <= 0 || s->p.fine_layer || !t->border_count) return PNPR_OK;
    size_t ids = (size_t)t->region_count + (t->node_count - t->merge_first);
    uint32_t *par = malloc(ids * sizeof *par);
    if (!par) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; i < ids; i++) par[i] = (uint32_t)i;
    for (size_t m = t->merge_first; m < t->node_count && t->merge_level[m - t->merge_first] <= s->p.border_level; m++)
        for (int c = 0; c < 2; c++) par[t->nodes[t->nodes[m].child[c]].region] = t->nodes[m].region;
    for (size_t i = 0; i < t->border_count; i++) {
        const pnpr_sphere_node *a = &t->nodes[t->leaves[t->border[2 * i]]], *b = &t->nodes[t->leaves[t->border[2 * i + 1]]];
        if (find_root(par, a->region) == find_root(par, b->region) || culled(s, a->centre, a->radius)) continue;
        border_stroke(s, a, b);
    }
    free(par);
    return PNPR_OK;
}

/* ---- entry ------------------------------------------------------------------------------------ */

static int view_ok(const pnpr_hier_view *v)
{
    if (!v || !v->view || !v->proj || v->width <= 0 || v->height <= 0 || !(v->pixels_per_unit > 0) ||
        !isfinite(v->pixels_per_unit))
        return 0;
    for (int i = 0; i < 16; i++)
        if (!isfinite(v->view[i]) || !isfinite(v->proj[i]) || (v->image_proj && !isfinite(v->image_proj[i]))) return 0;
    return 1;
}

pnpr_status pnpr_sphere_tree_traverse(const pnpr_sphere_tree *tree, const pnpr_hier_view *view,
                                      const pnpr_hier_params *params, pnpr_hier_stroke *r_strokes, size_t cap,
                                      pnpr_hier_counts *r_counts)
{
    pnpr_hier_counts local;
    trav s = {0};
    s.c = r_counts ? r_counts : &local;
    memset(s.c, 0, sizeof *s.c);
    if (!tree || !view_ok(view) || (cap && !r_strokes)) return PNPR_ERR_INVALID_ARGUMENT;
    s.p = params ? *params : (pnpr_hier_params){0};
    size_t nt;
    const pnpr_option_desc *table = pnpr_hier_option_table(&nt);
    if (pnpr_option_check(table, nt, &s.p, NULL) != PNPR_OK) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_option_fill_defaults(table, nt, &s.p);
    if (s.p.importance && (s.p.importance_w <= 0 || s.p.importance_h <= 0)) return PNPR_ERR_INVALID_ARGUMENT;
    if (tree->root == PNPR_INDEX_NONE || tree->node_count == 0) return PNPR_OK;
    s.t = tree;
    s.v = view;
    s.out = r_strokes;
    s.cap = cap;
    s.t_abs = s.p.abstraction < 0 ? -1.0f : s.p.abstraction * tree->nodes[tree->root].dissimilarity;
    s.t_px = s.p.stroke_px * (s.p.fine_layer ? 0.5f : 1.0f);
    frustum(&s);
    uint32_t *stack = malloc(2 * (tree->node_count + 1) * sizeof *stack);
    if (!stack) return PNPR_ERR_OUT_OF_MEMORY;
    walk(&s, stack, stack + tree->node_count + 1);
    free(stack);
    pnpr_status st = borders(&s);
    pack(&s);
    return st;
}
