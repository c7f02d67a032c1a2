/* The vector drawing container (include/pointnpr/drawing.h): paths appended in drawing order. */
#include <pointnpr/drawing.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *pnpr_drawing_layer_name(pnpr_drawing_layer layer)
{
    static const char *const names[PNPR_LAYER_COUNT_] = {"fills", "tone", "hatches", "strokes", "dots", "lines", "outlines"};
    return (unsigned)layer < PNPR_LAYER_COUNT_ ? names[layer] : "?";
}

void pnpr_drawing_free(pnpr_drawing *d)
{
    if (!d) return;
    free(d->offset);
    free(d->xy);
    free(d->stroke_width);
    free(d->rgba);
    free(d->layer);
    free(d->flags);
    int w = d->width, h = d->height;
    uint8_t bg[4];
    memcpy(bg, d->background, sizeof bg);
    memset(d, 0, sizeof *d);
    d->width = w;
    d->height = h;
    memcpy(d->background, bg, sizeof bg);
}

/* Grows one array to `cap` elements of `size` bytes; 0 on failure (the array unchanged). */
static int grow(void **p, size_t cap, size_t size)
{
    if (cap > SIZE_MAX / size) return 0;
    void *q = realloc(*p, cap * size);
    if (!q) return 0;
    *p = q;
    return 1;
}

static int reserve_paths(pnpr_drawing *d, size_t n)
{
    if (d->count + n <= d->cap_paths && d->offset) return 1;
    size_t cap = d->cap_paths ? d->cap_paths : 256;
    while (cap < d->count + n) {
        if (cap > SIZE_MAX / 2) return 0;
        cap *= 2;
    }
    if (!grow((void **)&d->offset, cap + 1, sizeof *d->offset) || !grow((void **)&d->stroke_width, cap, sizeof(float)) ||
        !grow((void **)&d->rgba, cap, 4) || !grow((void **)&d->layer, cap, 1) || !grow((void **)&d->flags, cap, 1))
        return 0;
    if (d->cap_paths == 0) d->offset[0] = 0;
    d->cap_paths = cap;
    return 1;
}

static int reserve_vertices(pnpr_drawing *d, size_t n)
{
    size_t have = d->count ? d->offset[d->count] : 0;
    if (have + n <= d->cap_vertices) return 1;
    size_t cap = d->cap_vertices ? d->cap_vertices : 512;
    while (cap < have + n) {
        if (cap > SIZE_MAX / 4) return 0;
        cap *= 2;
    }
    if (!grow((void **)&d->xy, cap, 2 * sizeof(float))) return 0;
    d->cap_vertices = cap;
    return 1;
}

pnpr_status pnpr_drawing_add(pnpr_drawing *d, const float *xy, size_t n, float width, const uint8_t rgba[4],
                             pnpr_drawing_layer layer, uint8_t flags)
{
    if (!d || !xy || n == 0 || (unsigned)layer >= PNPR_LAYER_COUNT_ || !isfinite(width) || width < 0)
        return PNPR_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < 2 * n; i++)
        if (!isfinite(xy[i])) return PNPR_ERR_INVALID_ARGUMENT;
    if (!reserve_paths(d, 1) || !reserve_vertices(d, n)) return PNPR_ERR_OUT_OF_MEMORY;
    size_t at = d->offset[d->count];
    memcpy(d->xy + 2 * at, xy, 2 * n * sizeof *xy);
    d->stroke_width[d->count] = width;
    memcpy(d->rgba + 4 * d->count, rgba, 4);
    d->layer[d->count] = (uint8_t)layer;
    d->flags[d->count] = flags;
    d->offset[++d->count] = at + n;
    return PNPR_OK;
}

double pnpr_drawing_ink_length(const pnpr_drawing *d, pnpr_drawing_layer layer)
{
    double len = 0;
    for (size_t i = 0; d && i < d->count; i++) {
        if (layer != PNPR_LAYER_COUNT_ && d->layer[i] != layer) continue;
        size_t a = d->offset[i], b = d->offset[i + 1];
        for (size_t v = a + 1; v < b; v++)
            len += hypot((double)d->xy[2 * v] - d->xy[2 * v - 2], (double)d->xy[2 * v + 1] - d->xy[2 * v - 1]);
        if ((d->flags[i] & PNPR_PATH_CLOSED) && b - a > 2)
            len += hypot((double)d->xy[2 * a] - d->xy[2 * b - 2], (double)d->xy[2 * a + 1] - d->xy[2 * b - 1]);
    }
    return len;
}

double pnpr_drawing_travel(const pnpr_drawing *d)
{
    double x = 0, y = 0, t = 0;
    for (size_t i = 0; d && i < d->count; i++) {
        size_t a = d->offset[i], b = d->offset[i + 1];
        t += hypot(d->xy[2 * a] - x, d->xy[2 * a + 1] - y);
        size_t last = (d->flags[i] & PNPR_PATH_CLOSED) ? a : b - 1;
        x = d->xy[2 * last];
        y = d->xy[2 * last + 1];
    }
    return t;
}

pnpr_status pnpr_drawing_extend(pnpr_drawing *d, float x, float y)
{
    if (!d || d->count == 0 || !isfinite(x) || !isfinite(y)) return PNPR_ERR_INVALID_ARGUMENT;
    if (!reserve_vertices(d, 1)) return PNPR_ERR_OUT_OF_MEMORY;
    size_t at = d->offset[d->count];
    d->xy[2 * at] = x;
    d->xy[2 * at + 1] = y;
    d->offset[d->count] = at + 1;
    return PNPR_OK;
}
