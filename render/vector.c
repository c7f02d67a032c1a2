/* A rendered frame as a vector drawing (pnpr_renderer_drawing, render.h; docs/export.md, "Vector
 * drawings"). The frame is drawn as for a PNG; then, on the CPU:
 * - the queue prefixes the frame drew are read back from the GL vertex buffers (the same vertices,
 *   in the same order, so per-point choices such as the thinning of tone hatches are the same);
 * - each stroke, hatch and dot is placed exactly as the vertex shaders place it (stroke.vert,
 *   splat.vert; the formulas are repeated below in double);
 * - the visibility mask's depth buffer is read back, and a mark is kept where its fragments pass
 *   GL's depth test (LEQUAL against the mask, at the point's depth): a stroke is sampled every
 *   pixel along its axis and across its width and split into its visible runs, each along the
 *   centre of its visible samples and as wide as they are (add_visible_band); a profile line is
 *   sampled along its centre line (add_visible); hidden marks are absent from the file;
 * - a stroke's vector shape is its texture as the frame shows it at that size (the mipmap level GL
 *   picks from the texels a pixel spans, bilinear and between levels): the extent along and
 *   across where its averaged profiles reach half their peak, drawn at the opacity that carries
 *   the texture's ink there x the ink's opacity x the tone hatches' lighter pencil x the queue's
 *   fade-in; small marks (tone hatches of 3 x 2 px) are then the whole quad at its mean ink, as
 *   the frame draws them; a shape where the stroke is 40% opaque, drawn opaque, differed from the
 *   PNG at 1.42% of the pixels of the test scene and 5.1% of the lion's;
 * - a stipple dot is drawn whole when 90% of its ink passes the depth test; a partly hidden dot
 *   is its visible pixels (splat.frag's coverage) as one short stroke along their principal axis,
 *   as long and wide as their spread, at the opacity that carries their ink (the slivers the
 *   frame draws along occluding edges; dropping dots under half visible differed at 3.3% of the
 *   lion's pixels);
 * - profile lines (the `lines` style) follow line.vert (pulled towards the eye, the near plane,
 *   the minimum on-screen length), sampled and split the same way, joined across segments;
 * - outlines: the frame is drawn with only the outlines' ink in its colour attachment; that ink
 *   is read back and traced into centre lines as wide as its bands (pnpr_drawing_trace_ink), so
 *   they are the outlines of the PNG, hidden parts already gone;
 * - marks repeated by duplicate points (ends within a quarter pixel) are drawn once, with the
 *   opacity of all of them blended (pnpr_drawing_dedupe);
 * - cartoon's colour areas: a frame drawn without outlines, its colours read back and traced
 *   along the pixel borders into filled areas (pnpr_drawing_trace_regions);
 * - style maps of these styles: each vertex's marks in its own style (the style bytes the frame
 *   uploaded), the lines where the mask's stencil holds the lines style, and the colour areas of
 *   a second frame that draws cartoon's pass alone over the shared mask. */
#include "renderer_internal.h"
#include "gl_state.h"

#include <pointnpr/drawing.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { READ_CHUNK = 65536 }; /* vertices read back at a time */
#define DOT_WHOLE 0.9 /* a dot drawn whole when this fraction of its ink passes the depth test */
#define OUTLINE_MIN_WIDTH 1.0f /* px: traced outlines are as wide as the frame's bands, at least this */

enum { MIP_LEVELS = 8 }; /* a 128 x 32 texture: levels 0 (128 x 32) to 7 (1 x 1) */
enum { DRAWN_N = 128 };  /* samples along a profile for its drawn extent */

/* A texture's alpha averaged over one axis, with its mipmap chain (levels concatenated). */
typedef struct mip_profile { float t[2 * STROKE_TEX_W + MIP_LEVELS]; int n; } mip_profile;

typedef struct vec_ctx {
    pnpr_renderer *r;
    const pnpr_frame_record *rec;
    const float *depth;          /* w x h window depths, GL rows bottom-up */
    int w, h;
    mip_profile prof_u[STROKE_LAYERS], prof_v[STROKE_LAYERS]; /* texture_profiles */
    float prof_mean[STROKE_LAYERS];
    double *drawn;               /* [2 L + axis][level][DRAWN_N]: each profile's levels sampled as GL reads
                                  * them, once (drawn_extent interpolates between two per stroke) */
    pnpr_drawing *out;
    uint8_t ink[4];
    double fade;                 /* the vertex being read: its queue fade-in (as the shaders) */
    int style_filter;            /* >= 0: a style map's frame; marks of the vertices of this style only */
    const uint8_t *stencil;      /* a style map's frame with lines: the mask's stencil (style + 1) */
} vec_ctx;


static uint8_t unit_byte(float v) { return (uint8_t)(v <= 0 ? 0 : v >= 1 ? 255 : (int)(v * 255.0f + 0.5f)); }

static void mip_build(mip_profile *m);

/* Each texture's alpha averaged across (along its length u) and along (across its width v), with
 * their mipmaps, and its mean. */
static void texture_profiles(vec_ctx *c)
{
    uint8_t *tex = malloc((size_t)STROKE_LAYERS * STROKE_TEX_W * STROKE_TEX_H);
    for (int L = 0; L < STROKE_LAYERS; L++) {
        mip_profile *pu = &c->prof_u[L], *pv = &c->prof_v[L];
        pu->n = STROKE_TEX_W;
        pv->n = STROKE_TEX_H;
        for (int x = 0; x < STROKE_TEX_W; x++) pu->t[x] = tex ? 0 : 1; /* without memory: a plain bar */
        for (int y = 0; y < STROKE_TEX_H; y++) pv->t[y] = tex ? 0 : 1;
        c->prof_mean[L] = 1;
    }
    if (tex) pnpr_stroke_textures(tex);
    for (int L = 0; L < STROKE_LAYERS && tex; L++) {
        const uint8_t *t = tex + (size_t)L * STROKE_TEX_W * STROKE_TEX_H;
        double sum = 0;
        for (int y = 0; y < STROKE_TEX_H; y++)
            for (int x = 0; x < STROKE_TEX_W; x++) {
                c->prof_u[L].t[x] += t[y * STROKE_TEX_W + x] / (255.0f * STROKE_TEX_H);
                c->prof_v[L].t[y] += t[y * STROKE_TEX_W + x] / (255.0f * STROKE_TEX_W);
                sum += t[y * STROKE_TEX_W + x] / 255.0;
            }
        c->prof_mean[L] = (float)(sum / (STROKE_TEX_W * STROKE_TEX_H));
    }
    for (int L = 0; L < STROKE_LAYERS; L++) { mip_build(&c->prof_u[L]); mip_build(&c->prof_v[L]); }
    free(tex);
}

/* Level l of a profile's mipmap chain (as glGenerateMipmap: texel pairs averaged, at least one
 * texel): its texels and their count. */
static const float *mip_level(const mip_profile *m, int l, int *r_n)
{
    int off = 0, n = m->n;
    for (int k = 0; k < l; k++) { off += n; n = n > 1 ? n / 2 : 1; }
    *r_n = n;
    return m->t + off;
}

/* Builds the chain above level 0 (m->t[0 .. n - 1] and m->n set). */
static void mip_build(mip_profile *m)
{
    for (int l = 1; l < MIP_LEVELS; l++) {
        int np, n;
        const float *p = mip_level(m, l - 1, &np);
        float *q = (float *)mip_level(m, l, &n);
        for (int i = 0; i < n; i++) q[i] = np > 1 ? 0.5f * (p[2 * i] + p[2 * i + 1]) : p[0];
    }
}

/* Level l of a profile read with GL_LINEAR and GL_CLAMP_TO_EDGE at the DRAWN_N sample centres. */
static void level_samples(const mip_profile *m, int l, double *r)
{
    int n;
    const float *p = mip_level(m, l, &n);
    for (int i = 0; i < DRAWN_N; i++) {
        double t = (i + 0.5) / DRAWN_N, x = t * n - 0.5, f = x - floor(x);
        int i0 = (int)floor(x), i1 = i0 + 1;
        i0 = i0 < 0 ? 0 : i0 >= n ? n - 1 : i0;
        i1 = i1 < 0 ? 0 : i1 >= n ? n - 1 : i1;
        r[i] = (1 - f) * p[i0] + f * p[i1];
    }
}

/* Every profile's levels sampled (c->drawn). */
static pnpr_status drawn_levels(vec_ctx *c)
{
    c->drawn = malloc((size_t)2 * STROKE_LAYERS * MIP_LEVELS * DRAWN_N * sizeof *c->drawn);
    if (!c->drawn) return PNPR_ERR_OUT_OF_MEMORY;
    for (int L = 0; L < STROKE_LAYERS; L++)
        for (int l = 0; l < MIP_LEVELS; l++) {
            level_samples(&c->prof_u[L], l, c->drawn + ((size_t)(2 * L) * MIP_LEVELS + l) * DRAWN_N);
            level_samples(&c->prof_v[L], l, c->drawn + ((size_t)(2 * L + 1) * MIP_LEVELS + l) * DRAWN_N);
        }
    return PNPR_OK;
}

/* A profile as the frame shows it at level of detail lod (GL_LINEAR_MIPMAP_LINEAR between its
 * sampled levels, [MIP_LEVELS][DRAWN_N]): the extent where it reaches half its peak, as a
 * fraction of its length, and its mean. */
static void drawn_extent(const double *levels, double lod, double *r_frac, double *r_mean)
{
    lod = fmin(fmax(lod, 0), MIP_LEVELS - 1);
    int l0 = (int)floor(lod), l1 = l0 + 1 < MIP_LEVELS ? l0 + 1 : l0;
    const double *v0 = levels + (size_t)l0 * DRAWN_N, *v1 = levels + (size_t)l1 * DRAWN_N;
    double d[DRAWN_N], peak = 0, mean = 0;
    int lo = DRAWN_N, hi = -1;
    for (int i = 0; i < DRAWN_N; i++) {
        d[i] = v0[i] + (lod - l0) * (v1[i] - v0[i]);
        peak = fmax(peak, d[i]);
        mean += d[i] / DRAWN_N;
    }
    for (int i = 0; i < DRAWN_N; i++)
        if (peak > 0 && d[i] >= 0.5 * peak) { lo = i < lo ? i : lo; hi = i; }
    *r_frac = hi >= lo ? (double)(hi - lo + 1) / DRAWN_N : 0;
    *r_mean = mean;
}

/* The vector shape of a stroke of texture layer L, half_len x half_wid px along axis: GL's level
 * of detail from the texels a pixel spans; the fractions of the quad's length and width where the
 * texture as drawn reaches half its peak, and the opacity that carries its ink there. */
static void stroke_shape(const vec_ctx *c, int L, double half_len, double half_wid, const double axis[2], double *r_fl,
                         double *r_fw, double *r_alpha)
{
    double su = STROKE_TEX_W / (2 * half_len), sv = STROKE_TEX_H / (2 * half_wid);
    double rx = hypot(su * axis[0], sv * axis[1]), ry = hypot(su * axis[1], sv * axis[0]);
    double lod = log2(fmax(fmax(rx, ry), 1e-9)), mu, mv;
    drawn_extent(c->drawn + (size_t)(2 * L) * MIP_LEVELS * DRAWN_N, lod, r_fl, &mu);
    drawn_extent(c->drawn + (size_t)(2 * L + 1) * MIP_LEVELS * DRAWN_N, lod, r_fw, &mv);
    double area = *r_fl * *r_fw;
    *r_alpha = area > 0 ? mu * mv / area / fmax(c->prof_mean[L], 1e-9) : 0; /* the ink as drawn */
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

/* A profile line's fragment: the depth test, and under a style map the stencil test of the lines'
 * pass (the lines show over the points of the lines style only). */
static int line_passes(const vec_ctx *c, double x, double y, double z)
{
    if (!passes(c, x, y, z)) return 0;
    return !c->stencil || c->stencil[(size_t)floor(y) * (size_t)c->w + (size_t)floor(x)] == PNPR_STYLE_LINES + 1;
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
        int vis = i < n + 1 && line_passes(c, a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), za + t * (zb - za));
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

/* A visible run of a stroke band (add_visible_band): its vertices (window px, GL y up), the
 * share of the width its samples cover, summed, and its last sample. */
enum { BAND_ACROSS_MAX = 16, BAND_RUN_MAX = 32 };
typedef struct band_run {
    float xy[2 * BAND_RUN_MAX];
    int nv, samples;
    double share, last[2], last_off;
} band_run;

static void band_vertex(band_run *run, double x, double y)
{
    run->xy[2 * run->nv] = (float)x;
    run->xy[2 * run->nv + 1] = (float)y;
    run->nv++;
}

/* Whether the run's last vertex is its last sample. */
static int band_at_last(const band_run *run)
{
    return run->nv > 0 && run->xy[2 * run->nv - 2] == (float)run->last[0] && run->xy[2 * run->nv - 1] == (float)run->last[1];
}

/* Adds the run as a path (y flipped to the drawing's y down) as wide as its mean share of
 * `width`, and empties it. */
static pnpr_status band_flush(vec_ctx *c, band_run *run, float width, const uint8_t rgba[4], pnpr_drawing_layer layer)
{
    for (int v = 0; v < run->nv; v++) run->xy[2 * v + 1] = (float)c->h - run->xy[2 * v + 1];
    pnpr_status st = pnpr_drawing_add(c->out, run->xy, (size_t)run->nv, (float)(width * run->share / run->samples), rgba,
                                      layer, 0);
    run->nv = run->samples = 0;
    run->share = 0;
    return st;
}

/* Ends a run at its last sample (a single sample: half a step either way, `step` px along u). */
static pnpr_status band_end(vec_ctx *c, band_run *run, const double u[2], double step, float width, const uint8_t rgba[4],
                            pnpr_drawing_layer layer)
{
    if (run->samples == 0) return PNPR_OK;
    if (run->samples == 1) {
        run->xy[0] -= (float)(u[0] * 0.5 * step);
        run->xy[1] -= (float)(u[1] * 0.5 * step);
        band_vertex(run, run->last[0] + u[0] * 0.5 * step, run->last[1] + u[1] * 0.5 * step);
    } else if (!band_at_last(run)) {
        band_vertex(run, run->last[0], run->last[1]);
    }
    return band_flush(c, run, width, rgba, layer);
}

/* The visible part of a stroke a -> b (window px, GL y up), `width` px wide, at window depth z.
 * The raster tests each fragment of the quad, so a stroke along an occluding edge keeps its
 * visible side: the band is sampled every pixel along and every pixel across; each visible run
 * is one path through the centres of its visible samples, as wide as their mean share of the
 * width (a stroke that is all visible: the one segment a -> b at its width). */
static pnpr_status add_visible_band(vec_ctx *c, const double a[2], const double b[2], double z, float width,
                                    const uint8_t rgba[4], pnpr_drawing_layer layer)
{
    double len = hypot(b[0] - a[0], b[1] - a[1]);
    double u[2] = {len > 0 ? (b[0] - a[0]) / len : 1, len > 0 ? (b[1] - a[1]) / len : 0};
    int n = (int)ceil(len) + 1, m = (int)ceil(width);
    n = n > 1 << 16 ? 1 << 16 : n;
    m = m < 1 ? 1 : m > BAND_ACROSS_MAX ? BAND_ACROSS_MAX : m;
    band_run run;
    memset(&run, 0, sizeof run);
    pnpr_status st = PNPR_OK;
    for (int i = 0; i <= n && st == PNPR_OK; i++) {
        double t = (double)i / n, x = a[0] + t * (b[0] - a[0]), y = a[1] + t * (b[1] - a[1]), off = 0;
        int k = 0;
        for (int j = 0; j < m; j++) {
            double o = ((j + 0.5) / m - 0.5) * width;
            if (passes(c, x - u[1] * o, y + u[0] * o, z)) { off += o; k++; }
        }
        if (k == 0) { st = band_end(c, &run, u, len / n, width, rgba, layer); continue; }
        off /= k;
        double p[2] = {x - u[1] * off, y + u[0] * off};
        if (run.samples > 0 && off != run.last_off) { /* the visible side moves: a jog */
            if (run.nv >= BAND_RUN_MAX - 2) { /* a long jagged run goes on in a new path */
                band_vertex(&run, run.last[0], run.last[1]);
                double share = run.share / run.samples;
                st = band_flush(c, &run, width, rgba, layer);
                run.samples = 1;
                run.share = share;
            }
            if (!band_at_last(&run)) band_vertex(&run, run.last[0], run.last[1]);
            band_vertex(&run, p[0], p[1]);
        } else if (run.samples == 0) {
            band_vertex(&run, p[0], p[1]);
        }
        run.samples++;
        run.share += (double)k / m;
        run.last[0] = p[0];
        run.last[1] = p[1];
        run.last_off = off;
    }
    if (st == PNPR_OK) st = band_end(c, &run, u, len / n, width, rgba, layer);
    return st;
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
    double rl = thin ? (double)c->r->tone_radius * rec->point_scale : rr; /* tone hatches: the mean length */
    double half_len = fmax(fmin(0.5 * length * rl * fc->pixels_per_unit / w, (double)pnpr_stroke_half_max(&c->rec->o)), 1.5);
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
    double fl, fw, fa;
    stroke_shape(c, tex_layer, half_len, half_wid, axis, &fl, &fw, &fa);
    if (fa > 1) { fw *= fa; fa = 1; } /* more ink than an opaque shape carries: wider */
    double alpha = rgba[3] / 255.0 * c->fade * (thin ? SKETCH_TONE_INK : 1) * fa;
    rgba[3] = (uint8_t)(alpha * 255 + 0.5);
    double hl = half_len * fl;
    if (!rgba[3] || !(hl > 0)) return PNPR_OK;
    double a[2] = {centre[0] - axis[0] * hl, centre[1] - axis[1] * hl}, b[2] = {centre[0] + axis[0] * hl, centre[1] + axis[1] * hl};
    return add_visible_band(c, a, b, z, (float)(2 * half_wid * fw), rgba, layer);
}

/* The ink of a mark's visible pixels: its coverage summed, first and second moments (window
 * pixels, GL y up); `all`: the coverage of the whole mark. */
typedef struct ink_moments { double all, vis, sx, sy, sxx, sxy, syy; } ink_moments;

static void moments_add(ink_moments *m, double x, double y, double a)
{
    m->vis += a;
    m->sx += a * x;
    m->sy += a * y;
    m->sxx += a * x * x;
    m->sxy += a * x * y;
    m->syy += a * y * y;
}

/* The pixels splat.frag inks for a dot of `size` px at `centre` (a sprite of size + 1 px, the
 * coverage falling off over the edge's last pixel), and those of them that pass the depth test. */
static void dot_coverage(const vec_ctx *c, const double centre[2], double z, double size, ink_moments *m)
{
    memset(m, 0, sizeof *m);
    double rad = 0.5 * size, half = 0.5 * (size + 1);
    for (int y = (int)floor(centre[1] - half); y <= (int)floor(centre[1] + half); y++)
        for (int x = (int)floor(centre[0] - half); x <= (int)floor(centre[0] + half); x++) {
            double px = x + 0.5, py = y + 0.5, dist = hypot(px - centre[0], py - centre[1]);
            double a = fmin(fmax(rad + 0.5 - dist, 0), 1);
            if (dist > half || !(a > 0)) continue;
            m->all += a;
            if (passes(c, px, py, z)) moments_add(m, px, py, a);
        }
}

/* A partly hidden mark as the raster draws it: its visible pixels as one short stroke along their
 * principal axis, as long and wide as their spread (a pixel counted as its square), at the opacity
 * that carries their ink. */
static pnpr_status partial_mark(vec_ctx *c, const ink_moments *m, const uint8_t rgba_in[4], pnpr_drawing_layer layer)
{
    double mx = m->sx / m->vis, my = m->sy / m->vis;
    double vxx = m->sxx / m->vis - mx * mx + 1.0 / 12, vyy = m->syy / m->vis - my * my + 1.0 / 12;
    double vxy = m->sxy / m->vis - mx * my;
    double tr = 0.5 * (vxx + vyy), det = vxx * vyy - vxy * vxy, disc = sqrt(fmax(tr * tr - det, 0));
    double l1 = tr + disc, l2 = fmax(tr - disc, 1.0 / 12), ang = 0.5 * atan2(2 * vxy, vxx - vyy);
    double len = sqrt(12 * l1), wid = sqrt(12 * l2);
    double alpha = rgba_in[3] / 255.0 * m->vis / (len * wid);
    if (alpha > 1) { wid *= alpha; alpha = 1; } /* the ink as a wider stroke */
    uint8_t rgba[4] = {rgba_in[0], rgba_in[1], rgba_in[2], (uint8_t)(alpha * 255 + 0.5)};
    if (!rgba[3]) return PNPR_OK;
    double ax = 0.5 * len * cos(ang), ay = 0.5 * len * sin(ang);
    float xy[4] = {(float)(mx - ax), (float)(c->h - (my - ay)), (float)(mx + ax), (float)(c->h - (my + ay))};
    return pnpr_drawing_add(c->out, xy, 2, (float)wid, rgba, layer, 0);
}

/* One stipple dot of splat.vert (fixed size; thin: tone): whole when DOT_WHOLE of its ink passes
 * the depth test, else its visible part (partial_mark). */
static pnpr_status dot_mark(vec_ctx *c, const pnpr_vertex *v, uint32_t vertex_id, int thin)
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
    uint8_t rgba[4];
    memcpy(rgba, c->ink, 4);
    rgba[3] = (uint8_t)(rgba[3] * c->fade + 0.5);
    if (!rgba[3]) return PNPR_OK;
    ink_moments m;
    dot_coverage(c, centre, z, size, &m);
    if (!(m.vis > 0)) return PNPR_OK;
    if (m.vis >= DOT_WHOLE * m.all) {
        float xy[2] = {(float)centre[0], (float)(c->h - centre[1])};
        return pnpr_drawing_add(c->out, xy, 1, (float)size, rgba, PNPR_LAYER_DOTS, PNPR_PATH_DOT);
    }
    return partial_mark(c, &m, rgba, PNPR_LAYER_DOTS);
}

/* The queue prefix of group g read back in chunks (the vertices and their queue keys); each
 * vertex its cell's queue keeps becomes a mark. */
static pnpr_status group_marks(vec_ctx *c, int g, int kind, pnpr_vertex *buf, uint16_t *keys)
{
    const pnpr_frame_record *rec = c->rec;
    size_t first = c->r->group_start[g], n = rec->gdraw[g];
    float length = rec->o.stroke_length;
    pnpr_status st = PNPR_OK;
    for (size_t k0 = 0; k0 < n && st == PNPR_OK; k0 += READ_CHUNK) {
        size_t m = n - k0 < READ_CHUNK ? n - k0 : READ_CHUNK;
        glBindBuffer(GL_ARRAY_BUFFER, c->r->vbo);
        glGetBufferSubData(GL_ARRAY_BUFFER, (GLintptr)((first + k0) * sizeof *buf), (GLsizeiptr)(m * sizeof *buf), buf);
        glBindBuffer(GL_ARRAY_BUFFER, c->r->key_vbo);
        glGetBufferSubData(GL_ARRAY_BUFFER, (GLintptr)((first + k0) * sizeof *keys), (GLsizeiptr)(m * sizeof *keys), keys);
        for (size_t k = 0; k < m && st == PNPR_OK; k++) {
            uint32_t id = (uint32_t)(k0 + k);
            if (c->style_filter >= 0 && c->r->vstyle[first + k0 + k] != (uint8_t)c->style_filter) continue;
            c->fade = pnpr_renderer_queue_alpha(c->r, buf[k].pos, keys[k]);
            if (c->fade < 0) continue;
            if (kind == 0) { /* sketchy */
                int dir = g == GROUP_DIRECTIONAL;
                st = stroke_mark(c, buf + k, id, dir ? 0 : 1, g == GROUP_DITHER, dir ? length : 0.5f * length,
                                 dir ? rec->o.stroke_texture : STROKE_LAYER_HATCH,
                                 dir ? PNPR_LAYER_STROKES : g == GROUP_DITHER ? PNPR_LAYER_TONE : PNPR_LAYER_HATCHES);
            } else {
                st = dot_mark(c, buf + k, (uint32_t)(first + k0 + k), g == GROUP_DITHER);
            }
        }
    }
    return st;
}

/* The sketchy strokes and stipple dots of the frame (under a style map, each of its points' style),
 * in the frame's order: stipple, then sketchy; within a style directional, non-directional, tone. */
static pnpr_status point_marks(vec_ctx *c)
{
    const pnpr_frame_record *rec = c->rec;
    const pnpr_style kinds[2] = {PNPR_STYLE_STIPPLE, PNPR_STYLE_SKETCHY};
    pnpr_vertex *buf = malloc(READ_CHUNK * sizeof *buf);
    uint16_t *keys = malloc(READ_CHUNK * sizeof *keys);
    if (!buf || !keys) { free(buf); free(keys); return PNPR_ERR_OUT_OF_MEMORY; }
    pnpr_status st = PNPR_OK;
    for (int k = 0; k < 2 && st == PNPR_OK; k++) {
        int sketchy = kinds[k] == PNPR_STYLE_SKETCHY;
        if (rec->mapped ? !rec->used[kinds[k]] : rec->o.style != kinds[k]) continue;
        int want[3] = {1, !sketchy || rec->o.sketch_variant != PNPR_SKETCH_DIRECTIONAL,
                       !sketchy || rec->o.sketch_variant == PNPR_SKETCH_ALL};
        c->style_filter = rec->mapped ? (int)kinds[k] : -1;
        for (int g = GROUP_DIRECTIONAL; g <= GROUP_DITHER && st == PNPR_OK; g++)
            if (want[g] && rec->gdraw[g] && c->r->has_features) st = group_marks(c, g, sketchy ? 0 : 1, buf, keys);
    }
    c->style_filter = -1;
    free(buf);
    free(keys);
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
    int lines = c->rec->mapped ? c->rec->used[PNPR_STYLE_LINES] > 0 : c->rec->o.style == PNPR_STYLE_LINES;
    if (!lines || r->line_segments == 0) return PNPR_OK;
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
    st = pnpr_drawing_trace_ink(c->out, rgba, c->w, c->h, 1, threshold, OUTLINE_MIN_WIDTH, c->ink,
                                PNPR_LAYER_OUTLINES);
    free(rgba);
    if (st != PNPR_OK) pnpr_error_set(err, st, "vector: outlines of a %dx%d frame: out of memory", c->w, c->h);
    return st;
}

/* Cartoon: its flat colour areas, from the frame drawn with an outline pass of no ink (it still
 * paints the mask disks' overhang beyond the silhouettes in the background, as in the PNG), its
 * colour attachment read back and traced into filled areas (pnpr_drawing_trace_regions). Under a
 * style map, the frame's pass 2 draws the cartoon points alone over the one mask of every style
 * (their outline disks' ink where they are in front, as in the PNG); nothing when no point is
 * cartoon. */
static pnpr_status fill_marks(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts, int w, int h,
                              pnpr_drawing *out, pnpr_error *err)
{
    pnpr_frame_record rec;
    memset(&rec, 0, sizeof rec);
    rec.outline_pass = PNPR_OUTLINES_NO_INK;
    rec.pass_only = PNPR_STYLE_CARTOON + 1; /* under a style map: the cartoon points' colours alone */
    pnpr_status st = pnpr_renderer_draw_recorded(r, camera, opts, w, h, &rec, err);
    if (st != PNPR_OK) return st;
    if (rec.mapped ? !rec.used[PNPR_STYLE_CARTOON] : rec.o.style != PNPR_STYLE_CARTOON) return PNPR_OK;
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

static int vector_style(pnpr_style s)
{
    return s == PNPR_STYLE_SKETCHY || s == PNPR_STYLE_STIPPLE || s == PNPR_STYLE_LINES || s == PNPR_STYLE_CARTOON;
}

static pnpr_status refuse_style(pnpr_error *err, const char *which, pnpr_style s)
{
    return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                          "vector: %sstyle '%s' fills areas; vector drawings are made of the strokes of sketchy, "
                          "stipple, lines and the colour areas and outlines of cartoon",
                          which, pnpr_style_name(s));
}

/* Whether a frame of opts may draw style s: its style (under a map the default of the labels not
 * listed) or a map entry's. */
static int may_draw(const pnpr_draw_options *opts, pnpr_style s)
{
    for (size_t i = 0; opts->style_map && i < opts->style_map_count; i++)
        if (opts->style_map[i].style == s) return 1;
    return opts->style == s;
}

pnpr_status pnpr_drawing_supported(const pnpr_draw_options *opts, pnpr_error *err)
{
    pnpr_style s = opts ? opts->style : PNPR_STYLE_POINTS;
    size_t n = opts && opts->style_map ? opts->style_map_count : 0;
    for (size_t i = 0; i < n; i++) {
        pnpr_style si = opts->style_map[i].style;
        if (vector_style(si)) continue;
        char which[64];
        snprintf(which, sizeof which, "style map entry %zu (label %u): ", i + 1, (unsigned)opts->style_map[i].label);
        return refuse_style(err, which, si);
    }
    if (opts && (opts->layer_label_count > 0 || opts->layer_exclude))
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "vector: segment layers (image-space effects) are pixels, not vectors");
    /* under a map the default style matters only where a label is not in it: checked when drawn */
    if (n == 0 && !vector_style(s)) return refuse_style(err, "", s);
    if (may_draw(opts, PNPR_STYLE_LINES) && opts->faint > 0)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                              "vector: faint %g draws the cloud under the lines as areas; a vector drawing has the "
                              "lines alone (faint 0)", (double)opts->faint);
    return PNPR_OK;
}

/* The styles the frame drew (a style map's resolved): each must be one a drawing is made of. */
static pnpr_status check_drawn(const pnpr_frame_record *rec, pnpr_error *err)
{
    if (!rec->mapped) return vector_style(rec->o.style) ? PNPR_OK : refuse_style(err, "the points' ", rec->o.style);
    for (int s = 0; s < PNPR_STYLE_COUNT_; s++)
        if (rec->used[s] && !vector_style((pnpr_style)s))
            return refuse_style(err, "the style map's default (the labels it does not list), ", (pnpr_style)s);
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
    uint8_t *stencil = NULL;
    if (c->rec->mapped && c->rec->used[PNPR_STYLE_LINES]) {
        if (!(stencil = malloc((size_t)c->w * (size_t)c->h))) {
            free(depth);
            return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "vector: stencil of a %dx%d frame: out of memory", c->w, c->h);
        }
        if ((st = pnpr_renderer_read_raw(c->r, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil)) != PNPR_OK) {
            free(stencil);
            free(depth);
            c->depth = NULL;
            return pnpr_error_set(err, st, "vector: stencil: no frame to read");
        }
        c->stencil = stencil;
    }
    texture_profiles(c);
    st = drawn_levels(c);
    /* bottom to top as the frame draws them: strokes or dots, lines, outlines */
    if (st == PNPR_OK) st = point_marks(c);
    if (st == PNPR_OK) st = line_marks(c);
    if (st != PNPR_OK) pnpr_error_set(err, st, "vector: %dx%d drawing: out of memory", c->w, c->h);
    if (st == PNPR_OK) st = outline_marks(c, err);
    free(depth);
    c->depth = NULL;
    free(stencil);
    c->stencil = NULL;
    free(c->drawn);
    c->drawn = NULL;
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
    if (may_draw(opts, PNPR_STYLE_CARTOON)) { /* a frame of its own: only when it may be drawn */
        st = fill_marks(r, camera, opts, width, height, r_drawing, err);
        if (st != PNPR_OK) { pnpr_drawing_free(r_drawing); return st; }
    }
    pnpr_frame_record rec;
    memset(&rec, 0, sizeof rec);
    rec.outline_pass = PNPR_OUTLINES_INK_ONLY;
    st = pnpr_renderer_draw_recorded(r, camera, opts, width, height, &rec, err);
    if (st == PNPR_OK) st = check_drawn(&rec, err);
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
    c.style_filter = -1;
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
