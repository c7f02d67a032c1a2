/* Flat colour areas as filled paths (pnpr_drawing_trace_regions, drawing.h): the cartoon style's
 * colour areas in a vector drawing. Written here: crack following on a colour-indexed image is
 * about a hundred lines (potrace, the library that would do it, traces one bitmap at a time and
 * is GPL).
 * 1. Every pixel gets the index of its colour (a small open-addressing table); the background
 *    colour is left out.
 * 2. Each pixel side facing a pixel of another colour (or the image border) is a directed edge
 *    owned by the pixel's colour, clockwise on screen (the colour on the right): top +x, right +y,
 *    bottom -x, left -y. From a corner each direction holds at most one edge.
 * 3. Loops: from an unused edge, at each corner take the owner's next edge turning right first,
 *    then straight, then left (pixels of one colour that touch only at a corner stay apart).
 * 4. Each loop loses its collinear corners and is simplified (Douglas-Peucker, SIMPLIFY_PX) and
 *    becomes a subpath; all loops of one colour form one path filled with the even-odd rule, so
 *    holes (loops the other way round) stay open. Colours in order of their first pixel. */
#include <pointnpr/drawing.h>
#include "vector_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SIMPLIFY_PX 0.5
enum { MAX_COLOURS = 1 << 16 };

static const int DX[4] = {1, 0, -1, 0}, DY[4] = {0, 1, 0, -1}; /* +x, +y, -x, -y (y down) */

typedef struct region_ctx {
    int w, h;
    uint32_t *id;    /* per pixel: colour index + 1, 0 = background */
    uint32_t *edge;  /* per corner and direction: owning colour index + 1, 0 = none */
    uint32_t *colour; /* rgba of each index */
    size_t ncolours;
} region_ctx;

static uint32_t pixel_rgba(const uint8_t *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }

/* Step 1; 0 when out of memory or when there are more than MAX_COLOURS colours. */
static int index_colours(region_ctx *c, const uint8_t *rgba, int bottom_up, uint32_t background)
{
    size_t cap = 2 * MAX_COLOURS;
    uint32_t *key = malloc(cap * sizeof *key), *val = calloc(cap, sizeof *val);
    c->colour = malloc(MAX_COLOURS * sizeof *c->colour);
    int ok = key && val && c->colour;
    for (int y = 0; ok && y < c->h; y++)
        for (int x = 0; ok && x < c->w; x++) {
            uint32_t v = pixel_rgba(rgba + 4 * ((size_t)(bottom_up ? c->h - 1 - y : y) * (size_t)c->w + (size_t)x));
            size_t i = (size_t)y * (size_t)c->w + (size_t)x;
            if (v == background || (v >> 24) == 0) { c->id[i] = 0; continue; }
            size_t s = (v * 2654435761u) & (cap - 1);
            while (val[s] && key[s] != v) s = (s + 1) & (cap - 1);
            if (!val[s]) {
                if (c->ncolours == MAX_COLOURS) { ok = 0; break; }
                key[s] = v;
                c->colour[c->ncolours] = v;
                val[s] = (uint32_t)++c->ncolours;
            }
            c->id[i] = val[s];
        }
    free(key);
    free(val);
    return ok;
}

static uint32_t id_at(const region_ctx *c, int x, int y)
{
    return x >= 0 && y >= 0 && x < c->w && y < c->h ? c->id[(size_t)y * (size_t)c->w + (size_t)x] : 0;
}

static size_t corner(const region_ctx *c, int x, int y) { return (size_t)y * (size_t)(c->w + 1) + (size_t)x; }

/* Step 2. */
static void mark_edges(region_ctx *c)
{
    for (int y = 0; y < c->h; y++)
        for (int x = 0; x < c->w; x++) {
            uint32_t me = c->id[(size_t)y * (size_t)c->w + (size_t)x];
            if (!me) continue;
            if (id_at(c, x, y - 1) != me) c->edge[4 * corner(c, x, y) + 0] = me;         /* top: (x,y) -> (x+1,y) */
            if (id_at(c, x + 1, y) != me) c->edge[4 * corner(c, x + 1, y) + 1] = me;     /* right: down */
            if (id_at(c, x, y + 1) != me) c->edge[4 * corner(c, x + 1, y + 1) + 2] = me; /* bottom: -x */
            if (id_at(c, x - 1, y) != me) c->edge[4 * corner(c, x, y + 1) + 3] = me;     /* left: up */
        }
}

typedef pnpr_polybuf loop;

static int loop_push(loop *l, int x, int y) { return pnpr_polybuf_push(l, (float)x, (float)y); }

/* Step 3: the loop through edge (x, y, d) of colour `owner`, its corners where it turns. */
static int walk_loop(region_ctx *c, int x, int y, int d, uint32_t owner, loop *l)
{
    l->n = 0;
    int x0 = x, y0 = y, d0 = d, first = 1;
    do {
        if (!first) c->edge[4 * corner(c, x, y) + (size_t)d] = 0; /* the first edge last: it ends the loop */
        first = 0;
        x += DX[d];
        y += DY[d];
        int next = -1;
        const int turn[3] = {(d + 1) & 3, d, (d + 3) & 3};
        for (int t = 0; t < 3 && next < 0; t++)
            if (c->edge[4 * corner(c, x, y) + (size_t)turn[t]] == owner) next = turn[t];
        if (next < 0) break; /* cannot happen: every corner has as many edges out as in */
        if (next != d && !loop_push(l, x, y)) return 0;
        d = next;
    } while (!(x == x0 && y == y0 && d == d0));
    c->edge[4 * corner(c, x0, y0) + (size_t)d0] = 0;
    return 1;
}

/* Step 3 for every loop, in one pass over the corners: each loop (simplified) a path of its
 * colour in `loops`; r_owner[i] = the colour index of loop i. */
static pnpr_status trace_loops(region_ctx *c, pnpr_drawing *loops, uint32_t **r_owner)
{
    loop l = {0};
    size_t cap = 0;
    pnpr_status st = PNPR_OK;
    for (int y = 0; y <= c->h && st == PNPR_OK; y++)
        for (int x = 0; x <= c->w && st == PNPR_OK; x++)
            for (int dir = 0; dir < 4 && st == PNPR_OK; dir++) {
                uint32_t k = c->edge[4 * corner(c, x, y) + (size_t)dir];
                if (!k) continue;
                if (!walk_loop(c, x, y, dir, k, &l)) { st = PNPR_ERR_OUT_OF_MEMORY; break; }
                size_t m = l.n >= 4 ? pnpr_simplify_polygon(l.xy, l.n, SIMPLIFY_PX) : l.n;
                if (m == 0) { st = PNPR_ERR_OUT_OF_MEMORY; break; }
                if (m < 3) continue;
                if (loops->count == cap) {
                    cap = cap ? 2 * cap : 256;
                    uint32_t *q = realloc(*r_owner, cap * sizeof *q);
                    if (!q) { st = PNPR_ERR_OUT_OF_MEMORY; break; }
                    *r_owner = q;
                }
                (*r_owner)[loops->count] = k;
                uint8_t rgba[4];
                for (int b = 0; b < 4; b++) rgba[b] = (uint8_t)(c->colour[k - 1] >> (8 * b));
                st = pnpr_drawing_add(loops, l.xy, m, 0, rgba, PNPR_LAYER_FILLS, PNPR_PATH_CLOSED | PNPR_PATH_FILL);
            }
    free(l.xy);
    return st;
}

/* Step 4: the loops of each colour (in colour order) as subpaths of one path. */
static pnpr_status emit_by_colour(const region_ctx *c, const pnpr_drawing *loops, const uint32_t *owner, pnpr_drawing *d,
                                  pnpr_drawing_layer layer)
{
    size_t *start = calloc(c->ncolours + 2, sizeof *start), *order = malloc((loops->count + 1) * sizeof *order);
    pnpr_status st = start && order ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; st == PNPR_OK && i < loops->count; i++) start[owner[i] + 1]++;
    for (size_t k = 1; st == PNPR_OK && k <= c->ncolours + 1; k++) start[k] += start[k - 1];
    for (size_t i = 0; st == PNPR_OK && i < loops->count; i++) order[start[owner[i]]++] = i;
    uint32_t prev = 0;
    for (size_t j = 0; st == PNPR_OK && j < loops->count; j++) {
        size_t i = order[j], a = loops->offset[i];
        uint8_t flags = PNPR_PATH_CLOSED | PNPR_PATH_FILL | (owner[i] == prev ? PNPR_PATH_SUBPATH : 0);
        st = pnpr_drawing_add(d, loops->xy + 2 * a, loops->offset[i + 1] - a, 0, loops->rgba + 4 * i, layer, flags);
        prev = owner[i];
    }
    free(start);
    free(order);
    return st;
}

pnpr_status pnpr_drawing_trace_regions(pnpr_drawing *d, const uint8_t *rgba, int w, int h, int bottom_up,
                                       const uint8_t background[4], pnpr_drawing_layer layer)
{
    if (!d || !rgba || w <= 0 || h <= 0 || !background || (unsigned)layer >= PNPR_LAYER_COUNT_) return PNPR_ERR_INVALID_ARGUMENT;
    region_ctx c;
    memset(&c, 0, sizeof c);
    c.w = w;
    c.h = h;
    size_t corners = ((size_t)w + 1) * ((size_t)h + 1);
    if (corners > SIZE_MAX / 16) return PNPR_ERR_OUT_OF_MEMORY;
    c.id = malloc((size_t)w * (size_t)h * sizeof *c.id);
    c.edge = calloc(4 * corners, sizeof *c.edge);
    pnpr_status st = c.id && c.edge ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK && !index_colours(&c, rgba, bottom_up, pixel_rgba(background)))
        st = c.colour ? PNPR_ERR_UNSUPPORTED : PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) mark_edges(&c);
    pnpr_drawing loops;
    memset(&loops, 0, sizeof loops);
    uint32_t *owner = NULL;
    if (st == PNPR_OK) st = trace_loops(&c, &loops, &owner);
    if (st == PNPR_OK) st = emit_by_colour(&c, &loops, owner, d, layer);
    pnpr_drawing_free(&loops);
    free(owner);
    free(c.id);
    free(c.edge);
    free(c.colour);
    return st;
}
