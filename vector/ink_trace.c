/* Centre lines of an ink mask (pnpr_drawing_trace_ink, drawing.h): the outlines a frame drew, as
 * paths. Written here: thinning and chain tracing on a small binary image are about a hundred
 * lines, and OpenCV's thinning lives in its contrib module (ximgproc), which Debian does not ship.
 * 1. Ink: alpha >= threshold.
 * 2. Thinning (Zhang & Suen, "A fast parallel algorithm for thinning digital patterns", CACM
 *    27(3), 1984): the two sub-iterations until nothing changes; bands of any width become
 *    8-connected curves one pixel wide.
 * 3. Chains: from every end and junction (crossing numbers 1 and >= 3), along unvisited pixels
 *    (4-neighbours before diagonal ones) to the next end or junction; what is left are loops.
 *    Vertices at pixel centres; a single pixel left (a speck, a small blob) is a dot of its
 *    blob's area.
 * 4. Centring: each vertex moves across the chain to the middle of the ink in a square as wide as
 *    the band around it (a band of even width is thinned to one of its two middle rows); open
 *    chains reach half a pixel past their end pixels (butt caps); then Douglas-Peucker to 0.5 px.
 * 5. Width: the median over the chain of the ink in that square over the chain's length through
 *    it, at least the given width: the path is as wide as the band it came from (wider where
 *    outlines run together). */
#include <pointnpr/drawing.h>
#include "vector_internal.h"
#include "../core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SIMPLIFY_PX 0.5

/* The 8 neighbours in the order P2..P9 of the paper (N, NE, E, SE, S, SW, W, NW), y down. */
static const int NX[8] = {0, 1, 1, 1, 0, -1, -1, -1}, NY[8] = {-1, -1, 0, 1, 1, 1, 0, -1};

typedef struct ink_img {
    uint8_t *m;    /* 1 = ink (skeleton after thinning), 2 = visited */
    uint8_t *ink;  /* the ink before thinning (1 = ink) */
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

/* Douglas-Peucker to SIMPLIFY_PX (vector/simplify.c); out of memory keeps the chain as it is. */
static void simplify(chain *c)
{
    size_t m = pnpr_simplify_polyline(c->p.xy, c->p.n, SIMPLIFY_PX);
    if (m) c->p.n = m;
}

/* The unit direction of the chain at vertex i (from the vertices 2 before to 2 after it). */
static void chain_tangent(const chain *c, size_t i, int closed, double t[2])
{
    size_t n = c->p.n, a, b;
    if (closed) { a = (i + n - 2) % n; b = (i + 2) % n; }
    else { a = i >= 2 ? i - 2 : 0; b = i + 2 < n ? i + 2 : n - 1; }
    double dx = c->p.xy[2 * b] - c->p.xy[2 * a], dy = c->p.xy[2 * b + 1] - c->p.xy[2 * a + 1], l = hypot(dx, dy);
    t[0] = l > 0 ? dx / l : 1;
    t[1] = l > 0 ? dy / l : 0;
}

/* Moves each vertex (a pixel centre of the thinned curve) across the chain to the middle of the
 * ink around it (the ink in a square as wide as the band, its offset along the chain's normal; a
 * band of even width is thinned to one of its two middle rows), and returns the band's width: the
 * median of the ink in each square over the chain's length through it. */
static double centre_on_ink(const ink_img *g, chain *c, int closed)
{
    size_t n = c->p.n;
    float *moved = malloc(2 * n * sizeof *moved), *wid = malloc(n * sizeof *wid);
    if (!moved || !wid) { free(moved); free(wid); return 2.0 * c->dsum / (double)n - 1.0; }
    for (size_t i = 0; i < n; i++) {
        double t[2], cx = c->p.xy[2 * i], cy = c->p.xy[2 * i + 1], sum = 0;
        chain_tangent(c, i, closed, t);
        int x = (int)cx, y = (int)cy, r = g->dist[(size_t)y * (size_t)g->w + (size_t)x], cnt = 0;
        if (r < 1) r = 1;
        for (int qy = y - r; qy <= y + r; qy++)
            for (int qx = x - r; qx <= x + r; qx++)
                if (qx >= 0 && qy >= 0 && qx < g->w && qy < g->h && g->ink[(size_t)qy * (size_t)g->w + (size_t)qx]) {
                    sum += -t[1] * (qx + 0.5 - cx) + t[0] * (qy + 0.5 - cy);
                    cnt++;
                }
        double off = cnt ? sum / cnt : 0;
        moved[2 * i] = (float)(cx - t[1] * off);
        moved[2 * i + 1] = (float)(cy + t[0] * off);
        wid[i] = (float)(cnt * fmax(fabs(t[0]), fabs(t[1])) / (2 * r + 1));
    }
    memcpy(c->p.xy, moved, 2 * n * sizeof *moved);
    double width = pnpr_median_float(wid, n);
    free(moved);
    free(wid);
    return width;
}

/* An open chain's ends run from pixel centres to the ends of the ink: half a pixel further (the
 * paths have butt caps). */
static void extend_ends(chain *c)
{
    size_t n = c->p.n;
    for (int e = 0; e < 2; e++) {
        float *p = c->p.xy + (e ? 2 * (n - 1) : 0), *q = c->p.xy + (e ? 2 * (n - 2) : 2);
        double dx = p[0] - q[0], dy = p[1] - q[1], l = hypot(dx, dy);
        if (l > 1e-6) { p[0] += (float)(0.5 * dx / l); p[1] += (float)(0.5 * dy / l); }
    }
}

typedef struct trace_out {
    const ink_img *g;
    pnpr_drawing *d;
    float width;
    const uint8_t *rgba;
    pnpr_drawing_layer layer;
} trace_out;

/* A single pixel left by thinning (a speck, or a small blob): a dot of the blob's ink area. */
static pnpr_status emit_speck(const trace_out *o, const chain *c)
{
    const ink_img *g = o->g;
    int x = (int)c->p.xy[0], y = (int)c->p.xy[1], r = g->dist[(size_t)y * (size_t)g->w + (size_t)x], cnt = 0;
    double sx = 0, sy = 0;
    for (int qy = y - r; qy <= y + r; qy++)
        for (int qx = x - r; qx <= x + r; qx++)
            if (qx >= 0 && qy >= 0 && qx < g->w && qy < g->h && g->ink[(size_t)qy * (size_t)g->w + (size_t)qx]) {
                sx += qx + 0.5;
                sy += qy + 0.5;
                cnt++;
            }
    if (!cnt) return PNPR_OK;
    float xy[2] = {(float)(sx / cnt), (float)(sy / cnt)};
    return pnpr_drawing_add(o->d, xy, 1, (float)(2 * sqrt(cnt / 3.14159265358979)), o->rgba, o->layer, PNPR_PATH_DOT);
}

/* A chain as a path: as wide as the ink it came from (2 d - 1 for a mean distance d, where
 * outlines ran together), at least the given width. */
static pnpr_status emit(const trace_out *o, chain *c, int closed, size_t pixels)
{
    if (pixels < 2) return emit_speck(o, c);
    double band = centre_on_ink(o->g, c, closed);
    float width = band > o->width ? (float)band : o->width;
    if (!closed) extend_ends(c);
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
    ink_img g = {malloc(n), malloc(n), malloc(n), w, h};
    uint8_t *aux = malloc(n);
    if (!g.m || !g.ink || !g.dist || !aux) { free(g.m); free(g.ink); free(g.dist); free(aux); return PNPR_ERR_OUT_OF_MEMORY; }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            g.m[(size_t)y * (size_t)w + (size_t)x] = alpha[(size_t)(bottom_up ? h - 1 - y : y) * (size_t)w + (size_t)x] >= threshold;
    memcpy(g.ink, g.m, n);
    distances(&g);
    while (thin_step(&g, 0, aux) + thin_step(&g, 1, aux) > 0) {}
    for (int y = 0; y < h; y++) /* junctions */
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            aux[i] = g.m[i] && crossings(&g, x, y) >= 3;
        }
    trace_out o = {&g, d, width, rgba, layer};
    pnpr_status st = trace_chains(&g, aux, &o);
    free(g.m);
    free(g.ink);
    free(g.dist);
    free(aux);
    return st;
}
