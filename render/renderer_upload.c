/* The renderer's uploads: a cloud (pnpr_renderer_set_cloud: the finite points' disk radii from
 * their spacing, the continuous resolution queue order, the vertices, the painterly data of
 * section 5.3), profile lines (pnpr_renderer_set_lines) and the style bytes of a style map. */
#include "renderer_internal.h"
#include "gl_state.h"
#include "../core/internal.h"
#include "../core/vec3.h"

#include <pointnpr/brush.h>
#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <pointnpr/outliers.h>

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- the cloud's per-point data ------------------------------------------------------------- */

/* What pnpr_renderer_set_cloud builds, stage by stage (upload_* below), before it goes to GL. */
typedef struct upload_ctx {
    const pnpr_cloud *cloud;
    pnpr_upload_options o;
    const pnpr_property *pc, *pd[3], *pdeg; /* feature class, direction, degree (painterly) */
    int features;
    uint32_t k;           /* the spacing neighbour */
    size_t nbins;         /* painterly bins */
    size_t n;             /* the finite points; j below indexes them */
    uint32_t *src;        /* cloud index of point j */
    float *xyz, *radius;  /* point j's position and disk radius */
    uint8_t *group;       /* point j's queue group */
    uint32_t *order;      /* the queue order: order[q] = j */
    size_t ngroups, starts[GROUP_MAX + 2];
    uint8_t *flat;        /* labels: each point's segment mean colour */
    float *shade;         /* colourless: the key light's darkness ... */
    uint8_t *grey;        /* ... and the grey of each point */
    uint32_t *nidx;       /* painterly: the nkk nearest of each point (itself included) */
    size_t nkk;
    uint32_t *porder, *inv;  /* painterly order (porder[q] = j); inv[j] = queue position */
    uint8_t *pbin, *pcol;    /* each point's bin; the blended colours (level-major, PAINT_COL_BYTES) */
    size_t pstarts[PAINT_MAX_BINS + 2];
    int paint;               /* painterly data built */
    int paint_skipped;       /* the cloud has them, pnpr_upload_options.skip_painterly left them out */
    const uint32_t *key;          /* what style maps read: cloud->label or the style key property */
    uint32_t *vlabel, *paint_src; /* style maps: keys in queue order; painterly -> queue index */
    uint8_t *zeros;               /* the initial style bytes */
    pnpr_brush_vertex *bverts;    /* brush: the brush attributes in queue order (NULL: no brush data) */
    float bmin[3], bmax[3];       /* the box without far outliers */
    pnpr_view_cells *cells;       /* the grid of cells over it */
    uint16_t *qkey, *pkey;        /* the per-cell queue keys in queue and painterly order */
    float *table;                 /* the frames' per-cell table (pnpr_renderer.cell_table) */
    pnpr_crq_cells queue, pqueue; /* the groups' and the painterly bins' per-cell queues */
} upload_ctx;

typedef struct label_index { uint32_t label, j; } label_index;

static int cmp_label(const void *a, const void *b)
{
    const label_index *x = a, *y = b;
    if (x->label != y->label) return x->label < y->label ? -1 : 1;
    return x->j < y->j ? -1 : x->j > y->j;
}

/* Mean colour (rounded) of each segment over its finite points: r_flat[3 j] for finite point j
 * (cloud index src[j]). Sorting (label, j) pairs handles any label values, PNPR_LABEL_NONE
 * included (one more segment). Without colours the points' shaded greys grey[j] are averaged
 * (each segment a flat grey by its mean lighting: faceted planes). */
static pnpr_status segment_means(const pnpr_cloud *cloud, const uint32_t *src, const uint8_t *grey, size_t n,
                                 uint8_t *r_flat)
{
    label_index *li = malloc(n * sizeof *li);
    if (!li) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t j = 0; j < n; j++) { li[j].label = cloud->label[src[j]]; li[j].j = (uint32_t)j; }
    qsort(li, n, sizeof *li, cmp_label);
    for (size_t a = 0; a < n;) {
        size_t b = a;
        double sum[3] = {0, 0, 0};
        while (b < n && li[b].label == li[a].label) {
            for (int c = 0; c < 3; c++) sum[c] += cloud->rgb ? cloud->rgb[3 * (size_t)src[li[b].j] + c] : grey[li[b].j];
            b++;
        }
        uint8_t mean[3];
        for (int c = 0; c < 3; c++) mean[c] = (uint8_t)(sum[c] / (double)(b - a) + 0.5);
        for (size_t k = a; k < b; k++) memcpy(r_flat + 3 * (size_t)li[k].j, mean, 3);
        a = b;
    }
    free(li);
    return PNPR_OK;
}

float pnpr_paint_brush(size_t pass, size_t bins)
{
    if (bins <= 1) return 1.0f;
    return (float)pow((double)PNPR_PAINT_MAX_BRUSH, (double)(bins - 1 - pass) / (double)(bins - 1));
}

typedef struct degree_index { float d; uint32_t j; } degree_index;
static int cmp_degree(const void *a, const void *b)
{
    const degree_index *x = a, *y = b;
    if (x->d != y->d) return x->d < y->d ? -1 : 1;
    return x->j < y->j ? -1 : x->j > y->j;
}

/* Channel c of finite point j's colour (its vertex's, and what painterly blends): the cloud's, or
 * the shaded grey of a colourless cloud. */
static uint8_t point_rgb(const upload_ctx *u, const uint8_t *rgb, uint32_t j, int c)
{
    return rgb ? rgb[3 * (size_t)u->src[j] + c] : u->grey[j];
}

/* Finite point j's cell (pnpr_crq_cell_fn). */
static uint32_t point_cell(const void *user, uint32_t j)
{
    const upload_ctx *u = user;
    return pnpr_view_cells_index(u->cells, u->xyz + 3 * (size_t)j);
}

/* The painterly data (section 5.3): finite points sorted by feature_degree (non-finite = lowest)
 * and divided evenly into `bins` bins, each shuffled into a queue (pnpr_crq_order); the vertices
 * in that order (written to GL by upload_vertex_buffer) and, per pass L and point, the
 * blended colour: the mean colour of the point's neighbours (among its nkk nearest, itself
 * included) within the pass's brush radius pnpr_paint_brush(L) * radius (u->pcol, level-major
 * RGB8). */
static pnpr_status paint_data(upload_ctx *u)
{
    size_t n = u->n, bins = u->nbins, kk = u->nkk;
    degree_index *di = malloc(n * sizeof *di);
    uint8_t *bin = u->pbin = malloc(n);
    uint32_t *porder = u->porder = malloc(n * sizeof *porder);
    uint32_t *inv = u->inv = malloc(n * sizeof *inv);
    if (!di || !bin || !porder || !inv) { free(di); return PNPR_ERR_OUT_OF_MEMORY; }
    for (size_t j = 0; j < n; j++) {
        double d = pnpr_type_get(u->pdeg->type, u->pdeg->data, u->src[j]);
        di[j].d = isfinite(d) ? (float)d : -FLT_MAX;
        di[j].j = (uint32_t)j;
    }
    qsort(di, n, sizeof *di, cmp_degree);
    for (size_t rank = 0; rank < n; rank++) bin[di[rank].j] = (uint8_t)(rank * bins / n);
    free(di);
    /* a seed of its own, so that the bins' order is not the class queues' */
    pnpr_status st = pnpr_crq_order(n, bin, (uint32_t)bins, u->o.seed ^ 0x9E3779B97F4A7C15ull, porder, u->pstarts);
    if (st != PNPR_OK) return st;
    if (!(u->pkey = malloc(n * sizeof *u->pkey))) return PNPR_ERR_OUT_OF_MEMORY;
    st = pnpr_crq_cells_make(porder, u->pstarts, bins + 1, point_cell, u, pnpr_view_cells_size(u->cells),
                             u->o.seed ^ 0x9E3779B97F4A7C15ull, u->pkey, &u->pqueue);
    if (st != PNPR_OK) return st;
    uint8_t *col = u->pcol = malloc(bins * n * PAINT_COL_BYTES); /* after the sort's scratch is gone */
    if (!col) return PNPR_ERR_OUT_OF_MEMORY;
    const uint32_t *nidx = u->nidx;
    const uint8_t *rgb = u->cloud->rgb;
    for (size_t q = 0; q < n; q++) inv[u->order[q]] = (uint32_t)q;
    for (size_t q = 0; q < n; q++) {
        uint32_t j = porder[q];
        for (size_t L = 0; L < bins; L++) {
            double lim = (double)pnpr_paint_brush(L, bins) * u->radius[j];
            double sum[3] = {0, 0, 0};
            size_t cnt = 0;
            for (size_t t = 0; t < kk && nidx; t++) {
                uint32_t m = nidx[j * kk + t];
                if (m == PNPR_INDEX_NONE || !((double)pnpr_dist2f(u->xyz + 3 * (size_t)m, u->xyz + 3 * (size_t)j) <= lim * lim))
                    continue;
                for (int c = 0; c < 3; c++) sum[c] += point_rgb(u, rgb, m, c);
                cnt++;
            }
            uint8_t *o = col + PAINT_COL_BYTES * (L * n + q);
            for (int c = 0; c < 3; c++) o[c] = cnt ? (uint8_t)(sum[c] / (double)cnt + 0.5) : point_rgb(u, rgb, j, c);
        }
    }
    free(u->nidx); /* served its turn: not held while GL copies the buffers */
    u->nidx = NULL;
    return PNPR_OK;
}

/* Colourless clouds: the key light's darkness of every finite point j (cloud index src[j]) from
 * its normal (tone.h, light source, no curve; unknown normals give 0.5) and its grey,
 * 240 - 170 x darkness. */
static pnpr_status shade_greys(const pnpr_cloud *cloud, const uint32_t *src, size_t n, const pnpr_tone_options *tone,
                               float **r_shade, uint8_t **r_grey)
{
    *r_grey = NULL;
    float *nrm = cloud->normal ? malloc(3 * n * sizeof *nrm) : NULL;
    float *shade = malloc(n * sizeof *shade);
    pnpr_status st = !shade || (cloud->normal && !nrm) ? PNPR_ERR_OUT_OF_MEMORY : PNPR_OK;
    if (st == PNPR_OK && nrm)
        for (size_t j = 0; j < n; j++) memcpy(nrm + 3 * j, cloud->normal + 3 * (size_t)src[j], 3 * sizeof *nrm);
    pnpr_tone_options o = *tone;
    o.source = PNPR_TONE_LIGHT;
    o.contrast = 1;
    o.gamma = 1;
    if (st == PNPR_OK) st = pnpr_tone(NULL, nrm, n, &o, shade);
    free(nrm);
    uint8_t *grey = st == PNPR_OK ? malloc(n) : NULL;
    if (st == PNPR_OK && !grey) st = PNPR_ERR_OUT_OF_MEMORY;
    if (st != PNPR_OK) { free(shade); shade = NULL; }
    else for (size_t j = 0; j < n; j++) grey[j] = (uint8_t)lrintf(240.0f - 170.0f * shade[j]);
    *r_shade = shade;
    *r_grey = grey;
    return st;
}

/* The cartoon's cel bands of a colourless cloud: three greys by the key light's darkness (lit,
 * half-lit, in shadow), all darker than white paper so that no band vanishes into it. */
static uint8_t shade_band(float darkness)
{
    return darkness < 0.3f ? 226 : darkness < 0.55f ? 178 : 128;
}

/* A unit normal as 4 signed bytes (x, y, z * 127, 0); unknown, zero or non-finite: all 0. */
static void pack_normal(const float *n, int8_t r[4])
{
    memset(r, 0, 4);
    if (!n) return;
    double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    if (!(l > 1e-12) || !isfinite(l)) return;
    for (int a = 0; a < 3; a++) r[a] = (int8_t)lrint(127.0 * n[a] / l);
}

static int group_of_class(double c)
{
    switch ((int)c) {
    case PNPR_CLASS_DIRECTIONAL: return GROUP_DIRECTIONAL;
    case PNPR_CLASS_NONDIRECTIONAL: return GROUP_NONDIRECTIONAL;
    case PNPR_CLASS_DITHER: return GROUP_DITHER;
    default: return GROUP_NONE;
    }
}

/* ---- pnpr_renderer_set_cloud, stage by stage ------------------------------------------------ */

/* The arguments, the options (zeros: defaults) and the feature properties. */
static pnpr_status upload_check(const pnpr_cloud *cloud, const pnpr_upload_options *opts, upload_ctx *u,
                                pnpr_error *err)
{
    if (cloud->count > 0 && !cloud->xyz)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: cloud has points but no coordinates");
    if (cloud->count >= 0xFFFFFFFFu)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: too many points (%zu)", cloud->count);
    u->cloud = cloud;
    if (opts) u->o = *opts;
    if (u->o.spacing_k > PNPR_SPACING_K_MAX)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: spacing_k %u is more than %d",
                              (unsigned)u->o.spacing_k, PNPR_SPACING_K_MAX);
    size_t nt = 0;
    const pnpr_option_desc *table = pnpr_upload_option_table(&nt);
    pnpr_option_fill_defaults(table, nt, &u->o); /* the zeros: the table's defaults (options.h) */
    u->k = u->o.spacing_k;
    u->pc = pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_CLASS);
    u->pd[0] = pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DIR_X);
    u->pd[1] = pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DIR_Y);
    u->pd[2] = pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DIR_Z);
    u->features = !u->o.ignore_features && u->pc && u->pd[0] && u->pd[1] && u->pd[2];
    u->pdeg = u->features ? pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DEGREE) : NULL;
    u->paint_skipped = u->pdeg && u->o.skip_painterly;
    if (u->paint_skipped) u->pdeg = NULL; /* the degree serves the painterly data alone */
    if (u->o.painterly_bins > PAINT_MAX_BINS)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: painterly_bins %u is more than %d",
                              (unsigned)u->o.painterly_bins, PAINT_MAX_BINS);
    u->nbins = u->o.painterly_bins;
    u->key = cloud->label;
    if (u->o.style_key) {
        const pnpr_property *p = pnpr_cloud_find_property(cloud, u->o.style_key);
        if (!p) return pnpr_error_set(err, PNPR_ERR_NOT_FOUND, "renderer: no style key property '%s'", u->o.style_key);
        if (p->type != PNPR_TYPE_UINT32 || (cloud->count > 0 && !p->data))
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: style key property '%s' is not uint32",
                                  u->o.style_key);
        u->key = (const uint32_t *)p->data;
    }
    return PNPR_OK;
}

/* The finite points: their cloud indices, positions and queue groups; the per-point arrays. */
static pnpr_status upload_finite(upload_ctx *u)
{
    const pnpr_cloud *cloud = u->cloud;
    size_t n = 0;
    for (size_t i = 0; i < cloud->count; i++) n += pnpr_finite3f(cloud->xyz + 3 * i);
    size_t m = n ? n : 1;
    u->src = malloc(m * sizeof *u->src);
    u->xyz = malloc(m * 3 * sizeof *u->xyz);
    u->radius = malloc(m * sizeof *u->radius);
    u->group = malloc(m);
    u->order = malloc(m * sizeof *u->order);
    u->flat = cloud->label ? malloc(m * 3) : NULL;
    if (!u->src || !u->xyz || !u->radius || !u->group || !u->order || (cloud->label && !u->flat))
        return PNPR_ERR_OUT_OF_MEMORY;
    n = 0;
    for (size_t i = 0; i < cloud->count; i++) {
        const float *p = cloud->xyz + 3 * i;
        if (!pnpr_finite3f(p)) continue;
        u->src[n] = (uint32_t)i;
        memcpy(u->xyz + 3 * n, p, 3 * sizeof *p);
        u->group[n] = u->features ? (uint8_t)group_of_class(pnpr_type_get(u->pc->type, u->pc->data, i)) : 0;
        n++;
    }
    u->n = n;
    return PNPR_OK;
}

/* The unclamped disk radii from the feature stage's point_spacing (props.h), when it holds this
 * upload's spacing neighbour and a usable value (finite, >= 0) for every point: 1; else 0 and the
 * upload runs its own kNN. The values are those the kNN would give (pnpr_spacing_from_lists), as
 * long as the points are those the features saw. */
static int stored_spacing(upload_ctx *u)
{
    const pnpr_property *p = pnpr_cloud_find_property(u->cloud, PNPR_PROP_POINT_SPACING);
    if (!p || !p->data || u->k != pnpr_upload_defaults().spacing_k) return 0;
    for (size_t j = 0; j < u->n; j++) {
        double v = pnpr_type_get(p->type, p->data, u->src[j]);
        if (!(v >= 0 && v <= FLT_MAX)) return 0;
        u->radius[j] = (float)v;
    }
    return 1;
}

/* The grid of cells over the box without far outliers, each point's cell, and the groups'
 * per-cell queues: the queue order sorted by key inside each group (crq.h). */
static pnpr_status upload_cells(upload_ctx *u)
{
    size_t n = u->n;
    if (pnpr_cloud_inlier_bounds(u->cloud, u->bmin, u->bmax) == 0) { /* far outliers do not stretch it */
        memset(u->bmin, 0, sizeof u->bmin);
        memset(u->bmax, 0, sizeof u->bmax);
    }
    u->cells = malloc(sizeof *u->cells);
    u->qkey = malloc((n ? n : 1) * sizeof *u->qkey);
    if (!u->cells || !u->qkey) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_view_cells_build(u->cells, u->xyz, n, u->bmin, u->bmax);
    if (!(u->table = calloc(4 * pnpr_view_cells_size(u->cells), sizeof *u->table)))
        return PNPR_ERR_OUT_OF_MEMORY;
    return pnpr_crq_cells_make(u->order, u->starts, u->ngroups + 1, point_cell, u,
                               pnpr_view_cells_size(u->cells), u->o.seed, u->qkey, &u->queue);
}

/* The disk radii (and painterly's neighbour lists), the queue order, the greys of a colourless
 * cloud and the segments' mean colours. */
static pnpr_status upload_order(upload_ctx *u)
{
    size_t n = u->n;
    pnpr_status st = PNPR_OK;
    if (n > 1 && !u->pdeg && stored_spacing(u)) { /* painterly needs the neighbour lists anyway */
        if ((st = pnpr_spacing_clamp(u->radius, n)) != PNPR_OK) return st;
    } else if (n > 0) {
        int paint = u->pdeg != NULL;
        pnpr_spacing_lists lists = {paint ? PAINT_K : 0, NULL, NULL, 0};
        st = pnpr_point_spacing(u->xyz, n, u->k, u->o.threads, u->radius, &lists);
        if (st != PNPR_OK) return st;
        u->nidx = lists.idx;
        free(lists.d2); /* paint_data computes the few distances it needs again (pnpr_dist2f) */
        u->nkk = lists.k;
    }
    u->ngroups = u->features ? GROUP_MAX : 1;
    st = pnpr_crq_order(n, u->group, (uint32_t)u->ngroups, u->o.seed, u->order, u->starts);
    if (st == PNPR_OK) st = upload_cells(u);
    if (st != PNPR_OK) return st;
    if (!u->cloud->rgb && n > 0 && (st = shade_greys(u->cloud, u->src, n, &u->o.tone, &u->shade, &u->grey)) != PNPR_OK)
        return st;
    if (u->cloud->label && n > 0) st = segment_means(u->cloud, u->src, u->grey, n, u->flat);
    return st;
}

/* Vertex q of the queue order (point j = order[q], cloud index i). */
static void fill_vertex(const upload_ctx *u, size_t q, pnpr_vertex *v)
{
    const pnpr_cloud *cloud = u->cloud;
    uint32_t j = u->order[q];
    size_t i = u->src[j];
    memcpy(v->pos, u->xyz + 3 * (size_t)j, sizeof v->pos);
    v->radius = u->radius[j];
    for (int c = 0; c < 3; c++) v->rgba[c] = point_rgb(u, cloud->rgb, j, c);
    v->rgba[3] = 255;
    if (cloud->label) memcpy(v->flat, u->flat + 3 * (size_t)j, 3);
    else if (!cloud->rgb) v->flat[0] = v->flat[1] = v->flat[2] = shade_band(u->shade[j]);
    else memcpy(v->flat, v->rgba, 3);
    v->flat[3] = 255;
    pack_normal(cloud->normal ? cloud->normal + 3 * i : NULL, v->normal);
    v->dir[0] = v->dir[1] = v->dir[2] = 0;
    if (u->features) {
        float d[3];
        double l2 = 0;
        for (int a = 0; a < 3; a++) {
            d[a] = (float)pnpr_type_get(u->pd[a]->type, u->pd[a]->data, i);
            if (!isfinite(d[a])) d[a] = 0;
            l2 += (double)d[a] * d[a];
        }
        if (l2 > 0) for (int a = 0; a < 3; a++) v->dir[a] = (float)(d[a] / sqrt(l2));
    }
}

/* The brush attributes (stroke-based splatting, brush.h) in queue order when the cloud carries
 * brush_size and brush_cluster: the size, and the stretch and layers of the point's cluster. */
static pnpr_status brush_data(upload_ctx *u)
{
    const pnpr_cloud *c = u->cloud;
    const pnpr_property *ps = pnpr_cloud_find_property(c, PNPR_PROP_BRUSH_SIZE);
    const pnpr_property *pc = pnpr_cloud_find_property(c, PNPR_PROP_BRUSH_CLUSTER);
    if (!ps || !pc || u->n == 0) return PNPR_OK;
    size_t n = u->n;
    uint32_t *cl = malloc(n * sizeof *cl);
    float *stretch = malloc(n * sizeof *stretch), *size = malloc(n * sizeof *size), *sorted = malloc(n * sizeof *sorted);
    uint8_t *layers = malloc(n);
    u->bverts = malloc(n * sizeof *u->bverts);
    pnpr_status st = PNPR_ERR_OUT_OF_MEMORY;
    if (cl && stretch && size && sorted && layers && u->bverts) {
        for (size_t j = 0; j < n; j++) {
            double v = pnpr_type_get(pc->type, pc->data, u->src[j]);
            cl[j] = v >= 0 && v < 4294967295.0 ? (uint32_t)v : 0xFFFFFFFFu;
        }
        st = pnpr_brush_cluster_shapes(u->xyz, cl, n, PNPR_BRUSH_SMALL_CLUSTER, stretch, layers);
    }
    /* sizes (0 = none: the disk radius is drawn), capped at PNPR_BRUSH_SIZE_CAP x the median of
     * the others, as the disk radii are (a few isolated far points would otherwise paint washes
     * across the picture) */
    size_t m = 0;
    for (size_t j = 0; st == PNPR_OK && j < n; j++) {
        double s = pnpr_type_get(ps->type, ps->data, u->src[j]);
        size[j] = isfinite(s) && s > 0 ? (float)s : 0.0f;
        if (size[j] > 0) sorted[m++] = size[j];
    }
    float cap = m ? PNPR_BRUSH_SIZE_CAP * pnpr_median_float(sorted, m) : 0;
    for (size_t q = 0; st == PNPR_OK && q < n; q++) {
        uint32_t j = u->order[q];
        u->bverts[q] = (pnpr_brush_vertex){size[j] < cap ? size[j] : cap, stretch[j], (float)layers[j]};
    }
    free(cl); free(stretch); free(size); free(sorted); free(layers);
    return st;
}

/* The vertices, the painterly data, and for style maps the labels in queue order, the
 * painterly order's main indices and zero style bytes. */
static pnpr_status upload_vertices(upload_ctx *u)
{
    size_t n = u->n;
    u->paint = u->pdeg && n > 0;
    if (u->paint) {
        pnpr_status st = paint_data(u);
        if (st != PNPR_OK) return st;
    }
    if (u->key) {
        u->vlabel = malloc((n ? n : 1) * sizeof *u->vlabel);
        if (!u->vlabel) return PNPR_ERR_OUT_OF_MEMORY;
        for (size_t q = 0; q < n; q++) u->vlabel[q] = u->key[u->src[u->order[q]]];
    }
    if (u->paint) {
        u->paint_src = malloc(n * sizeof *u->paint_src);
        if (!u->paint_src) return PNPR_ERR_OUT_OF_MEMORY;
        for (size_t q = 0; q < n; q++) u->paint_src[q] = u->inv[u->porder[q]];
    }
    u->zeros = calloc(n ? n : 1, 1);
    if (!u->zeros) return PNPR_ERR_OUT_OF_MEMORY;
    return brush_data(u);
}

/* The vertices into the bound GL_ARRAY_BUFFER, filled and written a chunk at a time, so that the
 * upload never holds all of them beside the GL's own copy (40 bytes/point less at the peak, twice
 * for painterly): in queue order, or with porder in painterly order (vertex q of the buffer is
 * the queue's u->inv[porder[q]]). */
static void upload_vertex_buffer(const upload_ctx *u, const uint32_t *porder)
{
    size_t n = u->n;
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * sizeof(pnpr_vertex)), NULL, GL_STATIC_DRAW);
    enum { CHUNK = 1024 };
    pnpr_vertex buf[CHUNK];
    for (size_t q0 = 0; q0 < n; q0 += CHUNK) {
        size_t c = n - q0 < CHUNK ? n - q0 : CHUNK;
        for (size_t q = 0; q < c; q++) fill_vertex(u, porder ? u->inv[porder[q0 + q]] : q0 + q, buf + q);
        glBufferSubData(GL_ARRAY_BUFFER, (GLintptr)(q0 * sizeof *buf), (GLsizeiptr)(c * sizeof *buf), buf);
    }
}

/* The GL buffers: style bytes (zero), vertices, painterly vertices and colours. */
static void upload_buffers(pnpr_renderer *r, upload_ctx *u)
{
    size_t n = u->n;
    int paint = u->paint;
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    /* the queue keys first, freed once GL has them: not held while the vertices are copied */
    glBindBuffer(GL_ARRAY_BUFFER, r->key_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(2 * (n ? n : 1)), n ? u->qkey : NULL, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, r->paint_key_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(paint ? 2 * n : 2), paint ? u->pkey : NULL, GL_STATIC_DRAW);
    free(u->qkey);
    free(u->pkey);
    u->qkey = u->pkey = NULL;
    glBindBuffer(GL_ARRAY_BUFFER, r->style_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n ? n : 1), u->zeros, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, r->paint_style_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(paint ? n : 1), u->zeros, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
    upload_vertex_buffer(u, NULL);
    glBindBuffer(GL_ARRAY_BUFFER, r->paint_vbo);
    if (paint) upload_vertex_buffer(u, u->porder);
    else glBufferData(GL_ARRAY_BUFFER, 0, NULL, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, r->paint_col_vbo);
    glBufferData(GL_ARRAY_BUFFER, paint ? (GLsizeiptr)(u->nbins * n * PAINT_COL_BYTES) : 0, paint ? u->pcol : NULL, GL_STATIC_DRAW);
    pnpr_brush_gl_upload(&r->brush, u->bverts, n);
    pnpr_gl_state_restore(&saved);
}

/* The renderer's description of the uploaded cloud; takes over the style-map arrays and the
 * per-cell queues. */
static void upload_commit(pnpr_renderer *r, upload_ctx *u)
{
    free(r->cell_table);
    r->cell_table = u->table;
    u->table = NULL;
    r->cells = pnpr_view_cells_size(u->cells);
    pnpr_crq_cells_free(&r->queue);
    pnpr_crq_cells_free(&r->paint_queue);
    r->queue = u->queue;
    r->paint_queue = u->pqueue;
    memset(&u->queue, 0, sizeof u->queue);
    memset(&u->pqueue, 0, sizeof u->pqueue);
    const pnpr_cloud *cloud = u->cloud;
    size_t n = u->n;
    r->paint_bins = u->paint ? u->nbins : 0;
    r->paint_skipped = u->paint_skipped;
    if (u->paint) for (size_t b = 0; b <= u->nbins + 1; b++) r->paint_start[b] = u->pstarts[b];
    free(r->vlabel); free(r->paint_src); free(r->vstyle); free(r->ulabels);
    r->ulabels = NULL; r->ulabel_count = 0;
    r->vlabel = u->vlabel; r->paint_src = u->paint_src; r->vstyle = u->zeros; r->vstyle_hidden = 0;
    u->vlabel = NULL; u->paint_src = NULL; u->zeros = NULL;
    r->count = n;
    r->group_count = u->ngroups;
    for (size_t g = 0; g <= u->ngroups + 1; g++) r->group_start[g] = u->starts[g];
    r->has_features = u->features;
    r->has_labels = cloud->label != NULL;
    r->has_rgb = cloud->rgb != NULL;
    r->max_radius = 0;
    double rsum = 0;
    for (size_t j = 0; j < n; j++) {
        if (u->radius[j] > r->max_radius) r->max_radius = u->radius[j];
        rsum += u->radius[j];
    }
    r->mean_radius = n ? (float)(rsum / (double)n) : 0;
    r->tone_radius = u->o.tone_radius > 0 && isfinite(u->o.tone_radius) ? u->o.tone_radius : r->mean_radius;
    memcpy(r->origin, cloud->origin, sizeof r->origin);
    memcpy(r->bmin, u->bmin, sizeof r->bmin);
    memcpy(r->bmax, u->bmax, sizeof r->bmax);
    r->view_cells = *u->cells;
}

static void upload_free(upload_ctx *u)
{
    free(u->src); free(u->xyz); free(u->radius); free(u->group); free(u->order); free(u->flat);
    free(u->nidx); free(u->porder); free(u->inv); free(u->pbin); free(u->pcol);
    free(u->vlabel); free(u->paint_src); free(u->zeros); free(u->shade); free(u->grey); free(u->bverts);
    free(u->cells); free(u->qkey); free(u->pkey); free(u->table);
    pnpr_crq_cells_free(&u->queue);
    pnpr_crq_cells_free(&u->pqueue);
}

pnpr_status pnpr_renderer_set_cloud(pnpr_renderer *r, const pnpr_cloud *cloud,
                                    const pnpr_upload_options *opts, pnpr_error *err)
{
    if (!r || !cloud) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: NULL renderer or cloud");
    upload_ctx u;
    memset(&u, 0, sizeof u);
    pnpr_status st = upload_check(cloud, opts, &u, err);
    if (st != PNPR_OK) return st;
    st = upload_finite(&u);
    if (st == PNPR_OK) st = upload_order(&u);
    if (st == PNPR_OK) st = upload_vertices(&u);
    if (st == PNPR_OK) {
        upload_buffers(r, &u);
        upload_commit(r, &u);
    }
    upload_free(&u);
    return st;
}

int pnpr_renderer_has_features(const pnpr_renderer *r) { return r && r->has_features; }
int pnpr_renderer_has_labels(const pnpr_renderer *r) { return r && r->has_labels; }

pnpr_status pnpr_renderer_set_lines(pnpr_renderer *r, const pnpr_polylines *lines, pnpr_error *err)
{
    if (!r) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: NULL renderer");
    size_t segs = 0;
    if (lines && lines->count > 0) {
        if (!lines->offset)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: lines without offsets");
        if (lines->offset[0] != 0)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: lines: offset[0] is %zu, not 0", lines->offset[0]);
        for (size_t i = 0; i < lines->count; i++) {
            size_t a = lines->offset[i], b = lines->offset[i + 1];
            if (b < a)
                return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: lines: offsets decrease at polyline %zu", i);
            if (b - a >= 2) segs += (b - a - 1) + (lines->closed && lines->closed[i] && b - a >= 3);
        }
        if (!isfinite(lines->origin[0]) || !isfinite(lines->origin[1]) || !isfinite(lines->origin[2]))
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: lines: non-finite origin");
        if (lines->offset[lines->count] > 0 && !lines->xyz)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: lines have vertices but no coordinates");
        if (segs > (size_t)0x7FFFFFFF / LINE_FLOATS)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "renderer: too many line segments (%zu)", segs);
    }
    float *buf = malloc((segs ? segs : 1) * LINE_FLOATS * sizeof *buf);
    if (!buf) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "renderer: lines: out of memory");
    size_t m = 0;
    for (size_t i = 0; segs && i < lines->count; i++) {
        size_t a = lines->offset[i], b = lines->offset[i + 1];
        if (b - a < 2) continue;
        size_t n = b - a, nseg = (n - 1) + (lines->closed && lines->closed[i] && n >= 3), first = m;
        double length = 0;
        for (size_t k = 0; k < nseg; k++) {
            const float *p = lines->xyz + 3 * (a + k), *q = lines->xyz + 3 * (a + (k + 1) % n);
            if (!pnpr_finite3f(p) || !pnpr_finite3f(q)) continue;
            memcpy(buf + LINE_FLOATS * m, p, 3 * sizeof *p);
            memcpy(buf + LINE_FLOATS * m + 3, q, 3 * sizeof *q);
            length += sqrt(((double)q[0] - p[0]) * (q[0] - p[0]) + ((double)q[1] - p[1]) * (q[1] - p[1]) +
                           ((double)q[2] - p[2]) * (q[2] - p[2]));
            m++;
        }
        for (size_t k = first; k < m; k++) buf[LINE_FLOATS * k + 6] = (float)length; /* the polyline's */
    }
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    glBindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m * LINE_FLOATS * sizeof *buf), m ? buf : NULL, GL_STATIC_DRAW);
    pnpr_gl_state_restore(&saved);
    free(buf);
    r->line_segments = m;
    if (m) memcpy(r->line_origin, lines->origin, sizeof r->line_origin);
    return PNPR_OK;
}

/* ---- style maps (intermingled styles): the style bytes ---------------------------------------- */

typedef struct map_key { uint32_t label, index; pnpr_style style; } map_key;
static int cmp_map_key(const void *a, const void *b)
{
    const map_key *x = a, *y = b;
    if (x->label != y->label) return x->label < y->label ? -1 : 1;
    return x->index < y->index ? -1 : x->index > y->index;
}

int pnpr_draw_has_layer(const pnpr_draw_options *o)
{
    return o->layer_label_count > 0 || o->layer_exclude;
}

static int sorted_has(const uint32_t *v, size_t n, uint32_t x)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (v[mid] < x) lo = mid + 1;
        else hi = mid;
    }
    return lo < n && v[lo] == x;
}

/* Hides (PNPR_VSTYLE_HIDDEN) the vertices outside o's layer and takes them out of r_used. */
static pnpr_status hide_outside_layer(const pnpr_renderer *r, const pnpr_draw_options *o, uint8_t *r_style,
                                      size_t *r_used)
{
    size_t m = o->layer_label_count;
    uint32_t *keys = malloc((m ? m : 1) * sizeof *keys);
    if (!keys) return PNPR_ERR_OUT_OF_MEMORY;
    if (m) memcpy(keys, o->layer_labels, m * sizeof *keys);
    qsort(keys, m, sizeof *keys, pnpr_cmp_u32);
    for (size_t q = 0; q < r->count; q++) {
        int listed = r->vlabel && sorted_has(keys, m, r->vlabel[q]);
        if (listed != !o->layer_exclude) {
            r_used[r_style[q]]--;
            r_style[q] = (uint8_t)PNPR_VSTYLE_HIDDEN;
        }
    }
    free(keys);
    return PNPR_OK;
}

pnpr_status pnpr_renderer_resolve_styles(const pnpr_renderer *r, const pnpr_draw_options *o, uint8_t *r_style,
                                         size_t *r_used)
{
    size_t m = r->vlabel ? o->style_map_count : 0;
    map_key *keys = malloc((m ? m : 1) * sizeof *keys);
    if (!keys) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; i < m; i++) {
        keys[i].label = o->style_map[i].label;
        keys[i].index = (uint32_t)i;
        keys[i].style = o->style_map[i].style;
    }
    qsort(keys, m, sizeof *keys, cmp_map_key);
    for (int s = 0; s < PNPR_STYLE_COUNT_; s++) r_used[s] = 0;
    for (size_t q = 0; q < r->count; q++) {
        uint32_t label = r->vlabel ? r->vlabel[q] : 0;
        size_t lo = 0, hi = m; /* first key with a larger label */
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (keys[mid].label <= label) lo = mid + 1;
            else hi = mid;
        }
        pnpr_style s = lo > 0 && keys[lo - 1].label == label ? keys[lo - 1].style : o->style;
        r_style[q] = (uint8_t)s;
        r_used[s]++;
    }
    free(keys);
    return pnpr_draw_has_layer(o) ? hide_outside_layer(r, o, r_style, r_used) : PNPR_OK;
}

pnpr_status pnpr_renderer_upload_styles(pnpr_renderer *r, const uint8_t *vstyle)
{
    if (!memcmp(vstyle, r->vstyle, r->count)) return PNPR_OK;
    glBindBuffer(GL_ARRAY_BUFFER, r->style_vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)r->count, vstyle);
    if (r->paint_bins && r->paint_src) {
        uint8_t *ps = malloc(r->count);
        if (!ps) return PNPR_ERR_OUT_OF_MEMORY;
        for (size_t q = 0; q < r->count; q++) ps[q] = vstyle[r->paint_src[q]];
        glBindBuffer(GL_ARRAY_BUFFER, r->paint_style_vbo);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)r->count, ps);
        free(ps);
    }
    memcpy(r->vstyle, vstyle, r->count);
    r->vstyle_hidden = memchr(vstyle, (int)PNPR_VSTYLE_HIDDEN, r->count) != NULL;
    return PNPR_OK;
}


void pnpr_renderer_set_hierarchy(pnpr_renderer *r, const pnpr_sphere_tree *tree)
{
    if (r) r->hier.tree = tree;
}
