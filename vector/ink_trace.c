/* Centre lines of an ink mask (pnpr_drawing_trace_ink, drawing.h): the outlines a frame drew, as
 * paths. Written here: thinning and chain tracing on a small binary image are about a hundred
 * lines, and OpenCV's thinning lives in its contrib module (ximgproc), which Debian does not ship.
 * 1. Ink: alpha >= threshold.
 * 2. Thinning (Zhang & Suen, "A fast parallel algorithm for thinning digital patterns", CACM
 *    27(3), 1984): the two sub-iterations until nothing changes; bands of any width become
 *    8-connected curves one pixel wide.
 * 3. Chains: from every end and junction (crossing numbers 1 and >= 3), along unvisited pixels
 *    (4-neighbours before diagonal ones) to the next end or junction; what is left are loops.
 *    Vertices at pixel centres; chains of fewer than 3 pixels are specks and dropped.
 * 4. Two passes of (1/4, 1/2, 1/4) smoothing (ends kept), then Douglas-Peucker to 0.5 px.
 * 5. Width: 2 d - 1 px for the chain's mean chessboard distance d to the nearest pixel without
 *    ink (a band of 2k - 1 pixels has d = k at its centre), at least the given width: where
 *    outlines run together into a wider band, the path is as wide. */
#include <pointnpr/drawing.h>
#include "vector_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { SMOOTH_PASSES = 2, MIN_PIXELS = 3 };
#define SIMPLIFY_PX 0.5

/* The 8 neighbours in the order P2..P9 of the paper (N, NE, E, SE, S, SW, W, NW), y down. */
static const int NX[8] = {0, 1, 1, 1, 0, -1, -1, -1}, NY[8] = {-1, -1, 0, 1, 1, 1, 0, -1};

typedef struct ink_img {
    uint8_t *m;    /* 1 = ink (skeleton after thinning), 2 = visited */
    uint8_t *dist; /* chessboard distance of each ink pixel to the nearest pixel without ink */
    int w, h;
} ink_img;

static int at(const ink_img *g, int x, int y)
{
    return x >= 0 && y >= 0 && x < g->w && y < g->h ? g->m[(size_t)y * (size_t)g->w + (size_t)x] != 0 : 0;
}

/* One Zhang-Suen sub-iteration; returns the pixels removed. */
static size_t thin_step(ink_img *g, int step, uint8_t *mark)
{
    size_t removed = 0;
    for (int y = 0; y < g->h; y++)
        for (int x = 0; x < g->w; x++) {
            size_t i = (size_t)y * (size_t)g->w + (size_t)x;
            mark[i] = 0;
            if (!g->m[i]) continue;
            int p[8], b = 0, a = 0;
            for (int k = 0; k < 8; k++) b += p[k] = at(g, x + NX[k], y + NY[k]);
            for (int k = 0; k < 8; k++) a += !p[k] && p[(k + 1) & 7];
            if (b < 2 || b > 6 || a != 1) continue;
            /* p[0]=P2 N, p[2]=P4 E, p[4]=P6 S, p[6]=P8 W */
            if (step == 0 && !(p[0] && p[2] && p[4]) && !(p[2] && p[4] && p[6])) mark[i] = 1;
            if (step == 1 && !(p[0] && p[2] && p[6]) && !(p[0] && p[4] && p[6])) mark[i] = 1;
        }
    for (size_t i = 0; i < (size_t)g->w * (size_t)g->h; i++)
        if (mark[i]) { g->m[i] = 0; removed++; }
    return removed;
}

/* The crossing number: ink runs around the pixel (0 -> 1 transitions over its 8 neighbours in
 * turn): 1 at an end, 2 along a curve (also on the staircase corners a thinned curve keeps, where
 * the neighbour count is 3), 3 or more at a junction; 0 for an isolated pixel or a filled area. */
static int crossings(const ink_img *g, int x, int y)
{
    int p[8], a = 0;
    for (int k = 0; k < 8; k++) p[k] = at(g, x + NX[k], y + NY[k]);
    for (int k = 0; k < 8; k++) a += !p[k] && p[(k + 1) & 7];
    return a;
}

/* Chessboard distance transform of the ink (two passes), capped at 255. */
static void distances(ink_img *g)
{
    int w = g->w, h = g->h;
    for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < w * h; k++) {
            int i = pass ? w * h - 1 - k : k, x = i % w, y = i / w, d = g->m[i] ? 255 : 0;
            int s = pass ? 1 : -1; /* the neighbours already visited in this pass */
            if (d) {
                d = pass ? g->dist[i] : 255;
                int nb[4][2] = {{x + s, y}, {x - 1, y + s}, {x, y + s}, {x + 1, y + s}};
                for (int q = 0; q < 4; q++) {
                    int qx = nb[q][0], qy = nb[q][1];
                    int v = qx >= 0 && qy >= 0 && qx < w && qy < h ? g->dist[qy * w + qx] : 0;
                    if (v + 1 < d) d = v + 1;
                }
            }
            g->dist[i] = (uint8_t)d;
        }
}

/* A chain being walked: pixel centres; the sum of the ink's distances along it. */
typedef struct chain { pnpr_polybuf p; double dsum; } chain;

static int chain_push(chain *c, const ink_img *g, int x, int y)
{
    c->dsum += g->dist[(size_t)y * (size_t)g->w + (size_t)x];
    return pnpr_polybuf_push(&c->p, (float)x + 0.5f, (float)y + 0.5f);
}

/* The next pixel from (x, y): an unvisited neighbour (4-neighbours first), else a junction that is
 * not `from`; 0 when none. */
static int next_pixel(const ink_img *g, const uint8_t *junction, int x, int y, int fx, int fy, int *nx, int *ny)
{
    static const int order[8] = {0, 2, 4, 6, 1, 3, 5, 7};
    for (int pass = 0; pass < 2; pass++)
        for (int o = 0; o < 8; o++) {
            int qx = x + NX[order[o]], qy = y + NY[order[o]];
            if (!at(g, qx, qy) || (qx == fx && qy == fy)) continue;
            size_t i = (size_t)qy * (size_t)g->w + (size_t)qx;
            if (pass == 0 && g->m[i] == 1 && !junction[i]) { *nx = qx; *ny = qy; return 1; }
            if (pass == 1 && junction[i]) { *nx = qx; *ny = qy; return 1; }
        }
    return 0;
}

/* Smooths the interior vertices (closed: all) and simplifies (Douglas-Peucker) in place. */
static void smooth(chain *c, int closed)
{
    size_t n = c->p.n;
    if (n < 3) return;
    float *t = malloc(2 * n * sizeof *t);
    if (!t) return;
    for (int pass = 0; pass < SMOOTH_PASSES; pass++) {
        memcpy(t, c->p.xy, 2 * n * sizeof *t);
        for (size_t i = 0; i < n; i++) {
            if (!closed && (i == 0 || i == n - 1)) continue;
            size_t a = i ? i - 1 : n - 1, b = i + 1 < n ? i + 1 : 0;
            for (int k = 0; k < 2; k++) c->p.xy[2 * i + k] = 0.25f * t[2 * a + k] + 0.5f * t[2 * i + k] + 0.25f * t[2 * b + k];
        }
    }
    free(t);
}

/* Douglas-Peucker to SIMPLIFY_PX (vector/simplify.c); out of memory keeps the chain as it is. */
static void simplify(chain *c)
{
    size_t m = pnpr_simplify_polyline(c->p.xy, c->p.n, SIMPLIFY_PX);
    if (m) c->p.n = m;
}

typedef struct trace_out {
    pnpr_drawing *d;
    float width;
    const uint8_t *rgba;
    pnpr_drawing_layer layer;
} trace_out;

/* A chain as a path: as wide as the ink it came from (2 d - 1 for a mean distance d, where
 * outlines ran together), at least the given width. */
static pnpr_status emit(const trace_out *o, chain *c, int closed, size_t pixels)
{
    if (pixels < MIN_PIXELS) return PNPR_OK;
    double band = 2.0 * c->dsum / (double)c->p.n - 1.0;
    float width = band > o->width ? (float)band : o->width;
    smooth(c, closed);
    simplify(c);
    return pnpr_drawing_add(o->d, c->p.xy, c->p.n, width, o->rgba, o->layer, closed ? PNPR_PATH_CLOSED : 0);
}

/* Walks from (x, y) through (nx, ny) until an end or a junction; pixels passed become visited. */
static pnpr_status walk(ink_img *g, const uint8_t *junction, const trace_out *o, chain *c, int x, int y, int nx, int ny)
{
    c->p.n = 0;
    c->dsum = 0;
    if (!chain_push(c, g, x, y)) return PNPR_ERR_OUT_OF_MEMORY;
    int px = x, py = y;
    size_t pixels = 1;
    for (;;) {
        size_t i = (size_t)ny * (size_t)g->w + (size_t)nx;
        if (!chain_push(c, g, nx, ny)) return PNPR_ERR_OUT_OF_MEMORY;
        pixels++;
        if (junction[i]) break;
        g->m[i] = 2;
        int qx, qy;
        if (!next_pixel(g, junction, nx, ny, px, py, &qx, &qy)) break;
        px = nx; py = ny; nx = qx; ny = qy;
    }
    return emit(o, c, 0, pixels);
}

/* Step 3: open chains from ends and junctions, then the loops. */
static pnpr_status trace_chains(ink_img *g, const uint8_t *junction, const trace_out *o)
{
    chain c = {0};
    pnpr_status st = PNPR_OK;
    for (int y = 0; y < g->h && st == PNPR_OK; y++)
        for (int x = 0; x < g->w && st == PNPR_OK; x++) {
            size_t i = (size_t)y * (size_t)g->w + (size_t)x;
            if (!g->m[i] || (!junction[i] && crossings(g, x, y) != 1) || (!junction[i] && g->m[i] == 2)) continue;
            if (!junction[i]) g->m[i] = 2;
            int nx, ny;
            while (st == PNPR_OK && next_pixel(g, junction, x, y, -1, -1, &nx, &ny)) {
                size_t j = (size_t)ny * (size_t)g->w + (size_t)nx;
                if (junction[j] && (junction[i] || (size_t)ny * (size_t)g->w + (size_t)nx < i)) break; /* junction pairs: no chain */
                st = walk(g, junction, o, &c, x, y, nx, ny);
                if (junction[j]) break;
            }
        }
    for (int y = 0; y < g->h && st == PNPR_OK; y++) /* loops: every pixel has two neighbours */
        for (int x = 0; x < g->w && st == PNPR_OK; x++) {
            size_t i = (size_t)y * (size_t)g->w + (size_t)x;
            if (g->m[i] != 1) continue;
            g->m[i] = 2;
            c.p.n = 0;
            c.dsum = 0;
            size_t pixels = 1;
            int px = -1, py = -1, cx = x, cy = y, nx, ny;
            st = chain_push(&c, g, x, y) ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
            while (st == PNPR_OK && next_pixel(g, junction, cx, cy, px, py, &nx, &ny) &&
                   g->m[(size_t)ny * (size_t)g->w + (size_t)nx] == 1) {
                g->m[(size_t)ny * (size_t)g->w + (size_t)nx] = 2;
                if (!chain_push(&c, g, nx, ny)) st = PNPR_ERR_OUT_OF_MEMORY;
                pixels++;
                px = cx; py = cy; cx = nx; cy = ny;
            }
            int dx = abs(cx - x), dy = abs(cy - y); /* closed when the walk came back beside its start */
            if (st == PNPR_OK) st = emit(o, &c, pixels > 3 && dx <= 1 && dy <= 1, pixels);
        }
    free(c.p.xy);
    return st;
}

pnpr_status pnpr_drawing_trace_ink(pnpr_drawing *d, const uint8_t *alpha, int w, int h, int bottom_up, uint8_t threshold,
                                   float width, const uint8_t rgba[4], pnpr_drawing_layer layer)
{
    if (!d || !alpha || w <= 0 || h <= 0 || !rgba || (unsigned)layer >= PNPR_LAYER_COUNT_ || !(width >= 0))
        return PNPR_ERR_INVALID_ARGUMENT;
    size_t n = (size_t)w * (size_t)h;
    ink_img g = {malloc(n), malloc(n), w, h};
    uint8_t *aux = malloc(n);
    if (!g.m || !g.dist || !aux) { free(g.m); free(g.dist); free(aux); return PNPR_ERR_OUT_OF_MEMORY; }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            g.m[(size_t)y * (size_t)w + (size_t)x] = alpha[(size_t)(bottom_up ? h - 1 - y : y) * (size_t)w + (size_t)x] >= threshold;
    distances(&g);
    while (thin_step(&g, 0, aux) + thin_step(&g, 1, aux) > 0) {}
    for (int y = 0; y < h; y++) /* junctions */
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            aux[i] = g.m[i] && crossings(&g, x, y) >= 3;
        }
    trace_out o = {d, width, rgba, layer};
    pnpr_status st = trace_chains(&g, aux, &o);
    free(g.m);
    free(g.dist);
    free(aux);
    return st;
}
