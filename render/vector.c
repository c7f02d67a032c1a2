/* A rendered frame as a vector drawing (pnpr_renderer_drawing, render.h; docs/export.md, "Vector
 * drawings"). The frame is drawn as for a PNG; then, on the CPU:
 * - the queue prefixes the frame drew are read back from the GL vertex buffers (the same vertices,
 *   in the same order, so per-point choices such as the thinning of tone hatches are the same);
 * - each stroke, hatch and dot is placed exactly as the vertex shaders place it (stroke.vert,
 *   splat.vert; the formulas are repeated below in double);
 * - the visibility mask's depth buffer is read back, and a mark is kept where its fragments pass
 *   GL's depth test (LEQUAL against the mask, at the point's depth): a stroke is sampled every
 *   pixel along its axis and split into its visible runs, a dot is kept when half the pixels
 *   under it pass; hidden marks are absent from the file;
 * - a stroke's vector shape is its texture's support (the rows and columns with ink, measured on
 *   the generated textures, pnpr_stroke_textures), drawn at the ink's opacity x the tone
 *   hatches' lighter pencil x the queue's fade-in x the texture's mean alpha there: the same ink
 *   as the raster stroke, so pencil tone stays grey (a shape where the stroke is 40% opaque,
 *   drawn opaque, differed from the PNG at 1.42% of the pixels of the test scene and 5.1% of the
 *   lion's; this at 0.63% and 3.0%);
 * - profile lines (the `lines` style) follow line.vert (pulled towards the eye, the near plane,
 *   the minimum on-screen length), sampled and split the same way, joined across segments;
 * - outlines: the frame is drawn with only the outlines' ink in its colour attachment; that ink
 *   is read back and traced into centre lines (pnpr_drawing_trace_ink), so they are the
 *   outlines of the PNG, hidden parts already gone;
 * - marks repeated by duplicate points (ends within a quarter pixel) are drawn once
 *   (pnpr_drawing_dedupe);
 * - cartoon's colour areas: a frame drawn without outlines, its colours read back and traced
 *   along the pixel borders into filled areas (pnpr_drawing_trace_regions). */
#include "renderer_internal.h"
#include "gl_state.h"

#include <pointnpr/drawing.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { READ_CHUNK = 65536 }; /* vertices read back at a time */
#define DOT_VISIBLE 0.5  /* a dot is kept when this fraction of its pixels passes the depth test */

typedef struct vec_ctx {
    pnpr_renderer *r;
    const pnpr_frame_record *rec;
    const float *depth;          /* w x h window depths, GL rows bottom-up */
    int w, h;
    float frac_len[STROKE_LAYERS], frac_wid[STROKE_LAYERS], mean_alpha[STROKE_LAYERS]; /* texture_extents */
    pnpr_drawing *out;
    uint8_t ink[4];
    float queue_end, queue_fade; /* the group being read: its prefix and fade-in (as the shaders) */
} vec_ctx;

/* The queue's fade-in of the k-th point of the group being read (stroke.vert, splat.vert). */
static double queue_alpha(const vec_ctx *c, size_t k)
{
    if (!(c->queue_fade > 0)) return 1;
    double a = ((double)c->queue_end - (double)k) / c->queue_fade;
    return a < 0 ? 0 : a > 1 ? 1 : a;
}

static uint8_t unit_byte(float v) { return (uint8_t)(v <= 0 ? 0 : v >= 1 ? 255 : (int)(v * 255.0f + 0.5f)); }

/* Each texture's support (the columns and rows where it has any ink, as fractions of its length
 * and width) and its mean alpha there (grain and soft profile): a stroke's vector shape is the
 * support, drawn at that opacity, so that it carries the same ink as the raster stroke. */
static void texture_extents(vec_ctx *c)
{
    uint8_t *tex = malloc((size_t)STROKE_LAYERS * STROKE_TEX_W * STROKE_TEX_H);
    for (int L = 0; L < STROKE_LAYERS; L++) { c->frac_len[L] = 0.9f; c->frac_wid[L] = 0.5f; c->mean_alpha[L] = 1; }
    if (!tex) return;
    pnpr_stroke_textures(tex);
    for (int L = 0; L < STROKE_LAYERS; L++) {
        const uint8_t *t = tex + (size_t)L * STROKE_TEX_W * STROKE_TEX_H;
        int row[STROKE_TEX_W] = {0}, col[STROKE_TEX_H] = {0}, nl = 0, nw = 0, cnt = 0;
        double sum = 0;
        for (int y = 0; y < STROKE_TEX_H; y++)
            for (int x = 0; x < STROKE_TEX_W; x++) {
                row[x] |= t[y * STROKE_TEX_W + x] > 0;
                col[y] |= t[y * STROKE_TEX_W + x] > 0;
            }
        for (int x = 0; x < STROKE_TEX_W; x++) nl += row[x];
        for (int y = 0; y < STROKE_TEX_H; y++) nw += col[y];
        for (int y = 0; y < STROKE_TEX_H; y++)
            for (int x = 0; x < STROKE_TEX_W; x++)
                if (row[x] && col[y]) { sum += t[y * STROKE_TEX_W + x] / 255.0; cnt++; }
        if (!cnt) continue;
        c->frac_len[L] = (float)nl / STROKE_TEX_W;
        c->frac_wid[L] = (float)nw / STROKE_TEX_H;
        c->mean_alpha[L] = (float)(sum / cnt);
    }
    free(tex);
}

/* clip = proj * view * p (column-major), in double. */
static void to_clip(const float *V, const float *P, const double p[3], double clip[4])
{
    double e[4];
    for (int k = 0; k < 4; k++) e[k] = V[k] * p[0] + V[4 + k] * p[1] + V[8 + k] * p[2] + V[12 + k];
    for (int k = 0; k < 4; k++) clip[k] = P[k] * e[0] + P[4 + k] * e[1] + P[8 + k] * e[2] + P[12 + k] * e[3];
}

/* Whether a fragment at window pixel (x, y) (GL: y up) with window depth z passes the mask. */
static int passes(const vec_ctx *c, double x, double y, double z)
{
    int ix = (int)floor(x), iy = (int)floor(y);
    if (ix < 0 || iy < 0 || ix >= c->w || iy >= c->h) return 0;
    return z <= (double)c->depth[(size_t)iy * (size_t)c->w + (size_t)ix] + 1.0 / (1 << 23);
}

/* Adds the visible runs of the segment a -> b (window pixels, GL y up) at window depths za -> zb,
 * sampled every pixel, as paths (y flipped to the drawing's y down). */
static pnpr_status add_visible(vec_ctx *c, const double a[2], const double b[2], double za, double zb, float width,
                               const uint8_t rgba[4], pnpr_drawing_layer layer)
{
    double len = hypot(b[0] - a[0], b[1] - a[1]);
    int n = (int)ceil(len) + 1;
    if (n > 1 << 16) n = 1 << 16;
    int run = -1;
    for (int i = 0; i <= n; i++) {
        double t = n > 0 ? (double)i / n : 0;
        int vis = i < n + 1 && passes(c, a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), za + t * (zb - za));
        if (vis && run < 0) run = i;
        if ((!vis || i == n) && run >= 0) {
            int last = vis ? i : i - 1;
            double t0 = (double)run / n, t1 = (double)last / n;
            if (last == run) { t0 = fmax(0, t0 - 0.5 / n); t1 = fmin(1, t1 + 0.5 / n); }
            float xy[4] = {(float)(a[0] + t0 * (b[0] - a[0])), (float)(c->h - (a[1] + t0 * (b[1] - a[1]))),
                           (float)(a[0] + t1 * (b[0] - a[0])), (float)(c->h - (a[1] + t1 * (b[1] - a[1])))};
            pnpr_status st = pnpr_drawing_add(c->out, xy, 2, width, rgba, layer, 0);
            if (st != PNPR_OK) return st;
            run = -1;
        }
    }
    return PNPR_OK;
}

/* The hash of stroke.vert / splat.vert on an instance or vertex id, in [0, 1). */
static double id_hash(uint32_t id)
{
    uint32_t h = id * 2654435761u;
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    return (double)(h & 65535u) / 65536.0;
}

/* Window position (GL y up) and depth of clip coordinates. */
static void to_window(const vec_ctx *c, const double clip[4], double w, double r_xy[2], double *r_z)
{
    r_xy[0] = (clip[0] / w * 0.5 + 0.5) * c->w;
    r_xy[1] = (clip[1] / w * 0.5 + 0.5) * c->h;
    *r_z = clip[2] / w * 0.5 + 0.5;
}

/* The direction of a stroke in world space (stroke.vert): the feature direction (mode 0), or the
 * hatch direction fixed on the surface (mode 1; zero without a normal: the 45-degree screen hatch). */
static void stroke_dir(const pnpr_vertex *v, int mode, double dir[3])
{
    for (int k = 0; k < 3; k++) dir[k] = mode == 0 ? v->dir[k] : 0;
    if (mode == 0) return;
    double n[3] = {v->normal[0] / 127.0, v->normal[1] / 127.0, v->normal[2] / 127.0};
    double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (!(nn > 0.25)) return;
    for (int k = 0; k < 3; k++) n[k] /= sqrt(nn);
    const double h1[3] = {HATCH_DIR}, h2[3] = {HATCH_DIR2};
    for (int pass = 0; pass < 2; pass++) {
        const double *h = pass ? h2 : h1;
        double d = n[0] * h[0] + n[1] * h[1] + n[2] * h[2], t2 = 0;
        for (int k = 0; k < 3; k++) { dir[k] = h[k] - n[k] * d; t2 += dir[k] * dir[k]; }
        if (t2 >= 0.1 || pass == 1) {
            double l = sqrt(t2);
            for (int k = 0; k < 3; k++) dir[k] = l > 0 ? dir[k] / l : 0;
            return;
        }
    }
}

/* One stroke of stroke.vert (mode 0: along dir; mode 1: the hatch; thin: tone, lighter). */
static pnpr_status stroke_mark(vec_ctx *c, const pnpr_vertex *v, uint32_t instance, int mode, int thin, float length,
                               int tex_layer, pnpr_drawing_layer layer)
{
    const pnpr_frame_record *rec = c->rec;
    const pnpr_frame_camera *fc = &rec->fc;
    double p[3] = {v->pos[0], v->pos[1], v->pos[2]}, clip[4];
    to_clip(fc->view, fc->proj, p, clip);
    if (!(clip[3] > 1e-6) || fabs(clip[2]) > clip[3]) return PNPR_OK; /* outside the depth range: clipped */
    double w = clip[3], axis[2] = {0.70710678, 0.70710678}, dir[3];
    stroke_dir(v, mode, dir);
    if (dir[0] != 0 || dir[1] != 0 || dir[2] != 0) {
        double q[3] = {p[0] + dir[0] * v->radius, p[1] + dir[1] * v->radius, p[2] + dir[2] * v->radius}, c2[4];
        to_clip(fc->view, fc->proj, q, c2);
        if (c2[3] > 1e-6) {
            double sx = (c2[0] / c2[3] - clip[0] / w) * c->w, sy = (c2[1] / c2[3] - clip[1] / w) * c->h;
            double len = hypot(sx, sy);
            if (len > 1e-4) { axis[0] = sx / len; axis[1] = sy / len; }
        }
    }
    double rr = (double)v->radius * rec->point_scale;
    double rl = thin ? (double)c->r->mean_radius * rec->point_scale : rr; /* tone hatches: the mean length */
    double half_len = fmax(0.5 * length * rl * fc->pixels_per_unit / w, 1.5);
    double half_wid = 0.5 * rec->o.stroke_width;
    if (thin) {
        double r_px = rr * fc->pixels_per_unit / w;
        if (id_hash(instance) >= r_px * r_px / (2.0 * half_len * half_wid)) return PNPR_OK;
    }
    double centre[2], z;
    to_window(c, clip, w, centre, &z);
    uint8_t rgba[4];
    memcpy(rgba, c->ink, 4);
    if (rec->o.ink_from_points) memcpy(rgba, v->rgba, 3);
    /* the texture's support at ink x tone pencil x fade-in x the texture's mean alpha */
    double alpha = rgba[3] / 255.0 * queue_alpha(c, instance) * (thin ? SKETCH_TONE_INK : 1) * c->mean_alpha[tex_layer];
    rgba[3] = (uint8_t)(alpha * 255 + 0.5);
    double hl = half_len * c->frac_len[tex_layer];
    if (!rgba[3] || !(hl > 0)) return PNPR_OK;
    double a[2] = {centre[0] - axis[0] * hl, centre[1] - axis[1] * hl}, b[2] = {centre[0] + axis[0] * hl, centre[1] + axis[1] * hl};
    return add_visible(c, a, b, z, z, (float)(2 * half_wid * c->frac_wid[tex_layer]), rgba, layer);
}

/* One stipple dot of splat.vert (fixed size; thin: tone), kept when DOT_VISIBLE of it passes. */
static pnpr_status dot_mark(vec_ctx *c, const pnpr_vertex *v, uint32_t vertex_id, size_t k, int thin)
{
    const pnpr_frame_record *rec = c->rec;
    const pnpr_frame_camera *fc = &rec->fc;
    double p[3] = {v->pos[0], v->pos[1], v->pos[2]}, clip[4];
    to_clip(fc->view, fc->proj, p, clip);
    if (!(clip[3] > 1e-6) || fabs(clip[2]) > clip[3] || fabs(clip[0]) > clip[3] || fabs(clip[1]) > clip[3])
        return PNPR_OK; /* GL drops a point whose centre is clipped */
    double size = rec->o.dot_size;
    if (thin) {
        double r_px = (double)v->radius * fc->pixels_per_unit / fmax(clip[3], 1e-6);
        if (id_hash(vertex_id) >= r_px * r_px / (0.785 * size * size)) return PNPR_OK;
    }
    double centre[2], z;
    to_window(c, clip, clip[3], centre, &z);
    double rad = 0.5 * size;
    int in = 0, vis = 0;
    for (int y = (int)floor(centre[1] - rad); y <= (int)floor(centre[1] + rad); y++)
        for (int x = (int)floor(centre[0] - rad); x <= (int)floor(centre[0] + rad); x++) {
            double dx = x + 0.5 - centre[0], dy = y + 0.5 - centre[1];
            if (dx * dx + dy * dy > rad * rad) continue;
            in++;
            vis += passes(c, x + 0.5, y + 0.5, z);
        }
    if (in == 0 || vis < DOT_VISIBLE * in) return PNPR_OK;
    float xy[2] = {(float)centre[0], (float)(c->h - centre[1])};
    uint8_t rgba[4];
    memcpy(rgba, c->ink, 4);
    rgba[3] = (uint8_t)(rgba[3] * queue_alpha(c, k) + 0.5);
    if (!rgba[3]) return PNPR_OK;
    return pnpr_drawing_add(c->out, xy, 1, (float)size, rgba, PNPR_LAYER_DOTS, PNPR_PATH_DOT);
}

/* The queue prefix of group g read back in chunks; each vertex becomes a mark. */
static pnpr_status group_marks(vec_ctx *c, int g, int kind, pnpr_vertex *buf)
{
    const pnpr_frame_record *rec = c->rec;
    size_t first = c->r->group_start[g], n = rec->gdraw[g];
    float length = rec->o.stroke_length;
    c->queue_end = (float)n;
    c->queue_fade = pnpr_queue_fade_length(n, c->r->group_start[g + 1] - first, rec->o.queue_fade);
    pnpr_status st = PNPR_OK;
    for (size_t k0 = 0; k0 < n && st == PNPR_OK; k0 += READ_CHUNK) {
        size_t m = n - k0 < READ_CHUNK ? n - k0 : READ_CHUNK;
        glBindBuffer(GL_ARRAY_BUFFER, c->r->vbo);
        glGetBufferSubData(GL_ARRAY_BUFFER, (GLintptr)((first + k0) * sizeof *buf), (GLsizeiptr)(m * sizeof *buf), buf);
        for (size_t k = 0; k < m && st == PNPR_OK; k++) {
            uint32_t id = (uint32_t)(k0 + k);
            if (kind == 0) { /* sketchy */
                int dir = g == GROUP_DIRECTIONAL;
                st = stroke_mark(c, buf + k, id, dir ? 0 : 1, g == GROUP_DITHER, dir ? length : 0.5f * length,
                                 dir ? rec->o.stroke_texture : STROKE_LAYER_HATCH,
                                 dir ? PNPR_LAYER_STROKES : g == GROUP_DITHER ? PNPR_LAYER_TONE : PNPR_LAYER_HATCHES);
            } else {
                st = dot_mark(c, buf + k, (uint32_t)(first + k0 + k), k0 + k, g == GROUP_DITHER);
            }
        }
    }
    return st;
}

/* The sketchy strokes or stipple dots of the frame. */
static pnpr_status point_marks(vec_ctx *c)
{
    const pnpr_frame_record *rec = c->rec;
    int sketchy = rec->o.style == PNPR_STYLE_SKETCHY;
    if (!sketchy && rec->o.style != PNPR_STYLE_STIPPLE) return PNPR_OK;
    int want[3] = {1, !sketchy || rec->o.sketch_variant != PNPR_SKETCH_DIRECTIONAL,
                   !sketchy || rec->o.sketch_variant == PNPR_SKETCH_ALL};
    pnpr_vertex *buf = malloc(READ_CHUNK * sizeof *buf);
    if (!buf) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_status st = PNPR_OK;
    /* the frame's drawing order: directional, non-directional, tone */
    for (int g = GROUP_DIRECTIONAL; g <= GROUP_DITHER && st == PNPR_OK; g++)
        if (want[g] && rec->gdraw[g] && c->r->has_features) st = group_marks(c, g, sketchy ? 0 : 1, buf);
    free(buf);
    return st;
}

/* Adds a visible run of a profile line: it continues the last path when it starts where that one
 * ends (the next segment of the same polyline), else it starts a path. */
static pnpr_status line_run(pnpr_drawing *d, const float xy[4], float width, const uint8_t rgba[4])
{
    if (d->count > 0 && d->layer[d->count - 1] == PNPR_LAYER_LINES) {
        size_t last = d->offset[d->count] - 1;
        if (d->xy[2 * last] == xy[0] && d->xy[2 * last + 1] == xy[1] && d->stroke_width[d->count - 1] == width)
            return pnpr_drawing_extend(d, xy[2], xy[3]);
    }
    return pnpr_drawing_add(d, xy, 2, width, rgba, PNPR_LAYER_LINES, 0);
}

/* One segment of line.vert: pulled towards the eye, cut at the near plane, dropped when its
 * polyline is shorter than the minimum on screen; its visible runs. */
static pnpr_status segment_marks(vec_ctx *c, const float *seg, const float lview[16], pnpr_drawing *tmp)
{
    const pnpr_frame_record *rec = c->rec;
    const pnpr_frame_camera *fc = &rec->fc;
    double e[2][4];
    for (int s = 0; s < 2; s++) {
        const float *p = seg + 3 * s;
        for (int k = 0; k < 4; k++) e[s][k] = lview[k] * p[0] + lview[4 + k] * p[1] + lview[8 + k] * p[2] + lview[12 + k];
    }
    double ps = rec->o.point_scale, pull = 2.0 * c->r->mean_radius * ps * rec->lod;
    for (int s = 0; s < 2; s++) {
        if (fc->ortho) { e[s][2] += pull; continue; }
        double len = sqrt(e[s][0] * e[s][0] + e[s][1] * e[s][1] + e[s][2] * e[s][2]);
        double f = fmax(1 - pull / fmax(len, 1e-30), 0.05);
        for (int k = 0; k < 3; k++) e[s][k] *= f;
    }
    double depth = fc->ortho ? 1 : fmax(-0.5 * (e[0][2] + e[1][2]), 1e-6);
    double min_px = rec->o.line_min_px;
    if (seg[6] * fc->pixels_per_unit / depth < min_px) return PNPR_OK;
    if (!fc->ortho) {
        double lim = -fc->near_plane * 1.001;
        if (e[0][2] > lim && e[1][2] > lim) return PNPR_OK;
        for (int s = 0; s < 2; s++) {
            double *a = e[s], *b = e[1 - s];
            if (a[2] <= lim) continue;
            double t = (a[2] - lim) / (a[2] - b[2]);
            for (int k = 0; k < 4; k++) a[k] += t * (b[k] - a[k]);
        }
    }
    double win[2][2], z[2];
    for (int s = 0; s < 2; s++) {
        double clip[4];
        for (int k = 0; k < 4; k++)
            clip[k] = fc->proj[k] * e[s][0] + fc->proj[4 + k] * e[s][1] + fc->proj[8 + k] * e[s][2] + fc->proj[12 + k] * e[s][3];
        if (!(clip[3] > 0)) return PNPR_OK;
        to_window(c, clip, clip[3], win[s], &z[s]);
    }
    pnpr_drawing *keep = c->out;
    c->out = tmp; /* the runs of this segment, then joined to the polylines */
    tmp->count = 0;
    if (tmp->offset) tmp->offset[0] = 0;
    float width = rec->o.line_width;
    pnpr_status st = add_visible(c, win[0], win[1], z[0], z[1], width, c->ink, PNPR_LAYER_LINES);
    c->out = keep;
    for (size_t i = 0; i < tmp->count && st == PNPR_OK; i++) st = line_run(c->out, tmp->xy + 2 * tmp->offset[i], width, c->ink);
    return st;
}

/* line.vert draws square caps: the ends of each line path reach half its width further. */
static void line_caps(pnpr_drawing *d, size_t from)
{
    for (size_t i = from; i < d->count; i++) {
        if (d->layer[i] != PNPR_LAYER_LINES) continue;
        float *a = d->xy + 2 * d->offset[i], *b = d->xy + 2 * (d->offset[i + 1] - 1);
        float *a2 = a + 2, *b2 = b - 2; /* the neighbours of the ends (every path has >= 2 vertices) */
        double h = 0.5 * d->stroke_width[i];
        double la = hypot(a[0] - a2[0], a[1] - a2[1]), lb = hypot(b[0] - b2[0], b[1] - b2[1]);
        if (la > 1e-6) { a[0] += (float)(h * (a[0] - a2[0]) / la); a[1] += (float)(h * (a[1] - a2[1]) / la); }
        if (lb > 1e-6) { b[0] += (float)(h * (b[0] - b2[0]) / lb); b[1] += (float)(h * (b[1] - b2[1]) / lb); }
    }
}

/* The profile lines of the `lines` style. */
static pnpr_status line_marks(vec_ctx *c)
{
    const pnpr_renderer *r = c->r;
    if (c->rec->o.style != PNPR_STYLE_LINES || r->line_segments == 0) return PNPR_OK;
    const pnpr_frame_camera *fc = &c->rec->fc;
    double d[3] = {r->line_origin[0] - r->origin[0], r->line_origin[1] - r->origin[1], r->line_origin[2] - r->origin[2]};
    float lview[16];
    memcpy(lview, fc->view, sizeof lview);
    for (int row = 0; row < 4; row++)
        lview[12 + row] = (float)((double)fc->view[row] * d[0] + (double)fc->view[4 + row] * d[1] +
                                  (double)fc->view[8 + row] * d[2] + (double)fc->view[12 + row]);
    float *buf = malloc((size_t)READ_CHUNK * LINE_FLOATS * sizeof *buf);
    pnpr_drawing tmp;
    memset(&tmp, 0, sizeof tmp);
    if (!buf) return PNPR_ERR_OUT_OF_MEMORY;
    size_t from = c->out->count;
    pnpr_status st = PNPR_OK;
    for (size_t k0 = 0; k0 < r->line_segments && st == PNPR_OK; k0 += READ_CHUNK) {
        size_t m = r->line_segments - k0 < READ_CHUNK ? r->line_segments - k0 : READ_CHUNK;
        glBindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
        glGetBufferSubData(GL_ARRAY_BUFFER, (GLintptr)(k0 * LINE_FLOATS * sizeof *buf),
                           (GLsizeiptr)(m * LINE_FLOATS * sizeof *buf), buf);
        for (size_t k = 0; k < m && st == PNPR_OK; k++) st = segment_marks(c, buf + LINE_FLOATS * k, lview, &tmp);
    }
    if (st == PNPR_OK) line_caps(c->out, from);
    pnpr_drawing_free(&tmp);
    free(buf);
    return st;
}

/* The outlines of the frame: the ink the outline shaders drew (alone in the colour attachment:
 * PNPR_OUTLINES_INK_ONLY), traced into centre lines where its coverage is at least
 * half. */
static pnpr_status outline_marks(vec_ctx *c, pnpr_error *err)
{
    const pnpr_frame_record *rec = c->rec;
    if (!rec->outline) return PNPR_OK;
    size_t n = (size_t)c->w * (size_t)c->h;
    uint8_t *rgba = malloc(4 * n);
    if (!rgba) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "vector: outlines of a %dx%d frame: out of memory", c->w, c->h);
    pnpr_status st = pnpr_renderer_read_raw(c->r, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    if (st != PNPR_OK) { free(rgba); return pnpr_error_set(err, st, "vector: outlines: no frame to read"); }
    for (size_t i = 0; i < n; i++) rgba[i] = rgba[4 * i + 3]; /* alpha, in place */
    uint8_t threshold = (uint8_t)(c->ink[3] / 2 > 0 ? c->ink[3] / 2 : 1);
    st = pnpr_drawing_trace_ink(c->out, rgba, c->w, c->h, 1, threshold, rec->outline_width, c->ink,
                                PNPR_LAYER_OUTLINES);
    free(rgba);
    if (st != PNPR_OK) pnpr_error_set(err, st, "vector: outlines of a %dx%d frame: out of memory", c->w, c->h);
    return st;
}

/* Cartoon: its flat colour areas, from the frame drawn with an outline pass of no ink (it still
 * paints the mask disks' overhang beyond the silhouettes in the background, as in the PNG), its
 * colour attachment read back and traced into filled areas (pnpr_drawing_trace_regions). */
static pnpr_status fill_marks(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts, int w, int h,
                              pnpr_drawing *out, pnpr_error *err)
{
    pnpr_frame_record rec;
    memset(&rec, 0, sizeof rec);
    rec.outline_pass = PNPR_OUTLINES_NO_INK;
    pnpr_status st = pnpr_renderer_draw_recorded(r, camera, opts, w, h, &rec, err);
    if (st != PNPR_OK) return st;
    uint8_t *rgba = malloc((size_t)w * (size_t)h * 4);
    if (!rgba) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "vector: colour areas of a %dx%d frame: out of memory", w, h);
    st = pnpr_renderer_read_raw(r, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    if (st != PNPR_OK) { free(rgba); return pnpr_error_set(err, st, "vector: colour areas: no frame to read"); }
    /* the frame is premultiplied; the background as the clear colour wrote it */
    uint8_t bg[4];
    float a = rec.o.background[3];
    for (int k = 0; k < 3; k++) bg[k] = unit_byte(rec.o.background[k] * a);
    bg[3] = unit_byte(a);
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
        uint8_t *p = rgba + 4 * i;
        if (p[3] && p[3] < 255 && !(p[0] == bg[0] && p[1] == bg[1] && p[2] == bg[2] && p[3] == bg[3]))
            for (int k = 0; k < 3; k++) p[k] = (uint8_t)(p[k] * 255 / p[3] < 255 ? p[k] * 255 / p[3] : 255);
    }
    st = pnpr_drawing_trace_regions(out, rgba, w, h, 1, bg, PNPR_LAYER_FILLS);
    free(rgba);
    if (st != PNPR_OK)
        pnpr_error_set(err, st, st == PNPR_ERR_UNSUPPORTED ? "vector: the cartoon frame has more than 65536 colours"
                                                          : "vector: colour areas of a %dx%d frame: out of memory", w, h);
    return st;
}

pnpr_status pnpr_drawing_supported(const pnpr_draw_options *opts, pnpr_error *err)
{
    pnpr_style s = opts ? opts->style : PNPR_STYLE_POINTS;
    if (opts && opts->style_map_count > 0)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "vector: style maps are not drawn as vectors yet (use one style)");
    if (opts && (opts->layer_label_count > 0 || opts->layer_exclude))
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "vector: segment layers (image-space effects) are pixels, not vectors");
    if (s != PNPR_STYLE_SKETCHY && s != PNPR_STYLE_STIPPLE && s != PNPR_STYLE_LINES && s != PNPR_STYLE_CARTOON)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                              "vector: style '%s' fills areas; vector drawings are made of the strokes of sketchy, "
                              "stipple, lines and the colour areas and outlines of cartoon",
                              pnpr_style_name(s));
    return PNPR_OK;
}

static pnpr_status drawing_from_frame(vec_ctx *c, pnpr_error *err)
{
    pnpr_status st = PNPR_OK;
    c->depth = NULL;
    float *depth = malloc((size_t)c->w * (size_t)c->h * sizeof *depth);
    if (!depth) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "vector: depth of a %dx%d frame: out of memory", c->w, c->h);
    st = pnpr_renderer_read_raw(c->r, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    if (st != PNPR_OK) { free(depth); return pnpr_error_set(err, st, "vector: depth: no frame to read"); }
    c->depth = depth;
    texture_extents(c);
    /* bottom to top as the frame draws them: strokes or dots, lines, outlines */
    st = point_marks(c);
    if (st == PNPR_OK) st = line_marks(c);
    if (st != PNPR_OK) pnpr_error_set(err, st, "vector: %dx%d drawing: out of memory", c->w, c->h);
    if (st == PNPR_OK) st = outline_marks(c, err);
    free(depth);
    c->depth = NULL;
    return st;
}

pnpr_status pnpr_renderer_drawing(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                  int width, int height, pnpr_drawing *r_drawing, pnpr_error *err)
{
    if (!r || !r_drawing) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "vector: NULL renderer or drawing");
    memset(r_drawing, 0, sizeof *r_drawing);
    pnpr_status st = pnpr_drawing_supported(opts, err);
    if (st != PNPR_OK) return st;
    if (width <= 0 || height <= 0 || width > r->max_size || height > r->max_size)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "vector: drawing size %dx%d is not within 1..%d (this GL's frame limit)",
                              width, height, (int)r->max_size);
    if (opts->style == PNPR_STYLE_CARTOON) {
        st = fill_marks(r, camera, opts, width, height, r_drawing, err);
        if (st != PNPR_OK) { pnpr_drawing_free(r_drawing); return st; }
    }
    pnpr_frame_record rec;
    memset(&rec, 0, sizeof rec);
    rec.outline_pass = PNPR_OUTLINES_INK_ONLY;
    st = pnpr_renderer_draw_recorded(r, camera, opts, width, height, &rec, err);
    if (st != PNPR_OK) { pnpr_drawing_free(r_drawing); return st; }
    r_drawing->width = width;
    r_drawing->height = height;
    for (int k = 0; k < 4; k++) r_drawing->background[k] = unit_byte(rec.o.background[k]);
    vec_ctx c;
    memset(&c, 0, sizeof c);
    c.r = r;
    c.rec = &rec;
    c.w = width;
    c.h = height;
    c.out = r_drawing;
    for (int k = 0; k < 4; k++) c.ink[k] = unit_byte(rec.ink[k]);
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    pnpr_gl_state_neutral();
    st = drawing_from_frame(&c, err);
    pnpr_gl_state_restore(&saved);
    /* duplicate points of a scan make the same mark twice: drawn once */
    if (st == PNPR_OK && pnpr_drawing_dedupe(r_drawing, 0.25f, NULL) != PNPR_OK)
        st = pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "vector: %dx%d drawing: out of memory", width, height);
    if (st != PNPR_OK) pnpr_drawing_free(r_drawing);
    return st;
}
