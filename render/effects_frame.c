/* Segment-specific image-space effects, the renderer's side (render.h, pnpr_renderer_effects):
 * Wegen et al.'s per-frame loop. Each layer (a pipeline node's labels, or one label with
 * per_label) is drawn as its own frame with the node's style (pnpr_draw_options.layer_labels:
 * only its points take part), read back as colour + depth, filtered by the node's chain,
 * inpainted and merged into the image (effects/composite.c). docs/effects.md. */
#include "renderer_internal.h"

#include "../core/internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One layer: the node whose configuration it takes and its labels (a slice of the caller's array;
 * count 0 with exclude = every point, for clouds without labels). */
typedef struct fx_layer {
    size_t node;
    const uint32_t *labels;
    size_t count;
} fx_layer;

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

typedef struct node_label { size_t node; uint32_t label; } node_label;
static int cmp_node_label(const void *a, const void *b)
{
    const node_label *x = a, *y = b;
    if (x->node != y->node) return x->node < y->node ? -1 : 1;
    return x->label < y->label ? -1 : x->label > y->label;
}

/* The distinct labels of the uploaded cloud, ascending, in r->ulabels: sorted once per upload,
 * not per frame. */
static pnpr_status distinct_labels(pnpr_renderer *r)
{
    if (r->ulabels || !r->vlabel || r->count == 0) return PNPR_OK;
    uint32_t *v = malloc(r->count * sizeof *v);
    if (!v) return PNPR_ERR_OUT_OF_MEMORY;
    memcpy(v, r->vlabel, r->count * sizeof *v);
    qsort(v, r->count, sizeof *v, cmp_u32);
    size_t n = 0;
    for (size_t i = 0; i < r->count; i++)
        if (i == 0 || v[i] != v[n - 1]) v[n++] = v[i];
    uint32_t *shrunk = realloc(v, n * sizeof *v);
    r->ulabels = shrunk ? shrunk : v;
    r->ulabel_count = n;
    return PNPR_OK;
}

/* The distinct labels of the uploaded cloud, grouped by their node in node order (ascending
 * within a node), in *r_labels (owned), their nodes in *r_nodes (owned, parallel). */
static pnpr_status cloud_labels(pnpr_renderer *r, const pnpr_effect_pipeline *p, uint32_t **r_labels,
                                size_t **r_nodes, size_t *r_count)
{
    *r_labels = NULL;
    *r_nodes = NULL;
    *r_count = 0;
    pnpr_status st = distinct_labels(r);
    if (st != PNPR_OK || !r->ulabels) return st;
    size_t n = r->ulabel_count;
    node_label *nl = malloc(n * sizeof *nl);
    size_t *node = malloc(n * sizeof *node);
    uint32_t *out = malloc(n * sizeof *out);
    if (!nl || !node || !out) { free(nl); free(node); free(out); return PNPR_ERR_OUT_OF_MEMORY; }
    for (size_t i = 0; i < n; i++) nl[i] = (node_label){pnpr_effect_pipeline_node_of(p, r->ulabels[i]), r->ulabels[i]};
    qsort(nl, n, sizeof *nl, cmp_node_label);
    for (size_t i = 0; i < n; i++) { out[i] = nl[i].label; node[i] = nl[i].node; }
    free(nl);
    *r_labels = out;
    *r_nodes = node;
    *r_count = n;
    return PNPR_OK;
}

/* The layers: per node, one for its labels or one per label (per_label). */
static pnpr_status plan_layers(const pnpr_effect_pipeline *p, const uint32_t *labels, const size_t *nodes,
                               size_t nl, fx_layer **r_layers, size_t *r_count)
{
    fx_layer *L = malloc((nl ? nl : 1) * sizeof *L);
    if (!L) return PNPR_ERR_OUT_OF_MEMORY;
    size_t n = 0;
    if (nl == 0) L[n++] = (fx_layer){0, NULL, 0}; /* no labels: the root draws every point */
    for (size_t i = 0; i < nl;) {
        size_t j = i + 1;
        while (j < nl && nodes[j] == nodes[i]) j++;
        if (p->nodes[nodes[i]].per_label)
            for (size_t k = i; k < j; k++) L[n++] = (fx_layer){nodes[i], labels + k, 1};
        else
            L[n++] = (fx_layer){nodes[i], labels + i, j - i};
        i = j;
    }
    *r_layers = L;
    *r_count = n;
    return PNPR_OK;
}

/* Scratch of one layer. */
typedef struct fx_buffers {
    pnpr_image raster, filtered, out;
    float *depth, *inpainted, *acc_depth;
    uint8_t *mask;
} fx_buffers;

static void free_buffers(fx_buffers *b)
{
    free(b->raster.rgba);
    free(b->filtered.rgba);
    free(b->depth);
    free(b->inpainted);
    free(b->acc_depth);
    free(b->mask);
}

static pnpr_status alloc_buffers(fx_buffers *b, int w, int h, uint8_t *out)
{
    memset(b, 0, sizeof *b);
    size_t n = (size_t)w * (size_t)h;
    b->raster = (pnpr_image){w, h, malloc(n * 4)};
    b->filtered = (pnpr_image){w, h, malloc(n * 4)};
    b->out = (pnpr_image){w, h, out};
    b->depth = malloc(n * sizeof(float));
    b->inpainted = malloc(n * sizeof(float));
    b->acc_depth = malloc(n * sizeof(float));
    b->mask = malloc(n);
    if (b->raster.rgba && b->filtered.rgba && b->depth && b->inpainted && b->acc_depth && b->mask) return PNPR_OK;
    free_buffers(b);
    return PNPR_ERR_OUT_OF_MEMORY;
}

/* Rasterises, filters, inpaints and merges one layer. */
static pnpr_status do_layer(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *base,
                            const pnpr_effect_pipeline *p, const fx_layer *l, uint64_t seed, fx_buffers *b,
                            pnpr_effects_stats *s, pnpr_error *err)
{
    const pnpr_effect_node *nd = &p->nodes[l->node];
    pnpr_draw_options o = *base;
    o.style = nd->style;
    if (nd->point_scale > 0) o.point_scale = nd->point_scale;
    o.layer_labels = l->labels;
    o.layer_label_count = l->count;
    o.layer_exclude = l->count == 0;
    o.background[3] = 1.0f; /* opaque paper for the filters */
    pnpr_target tgt = {0, 0, 0, b->raster.width, b->raster.height, 1};
    double t0 = pnpr_now();
    pnpr_status st = pnpr_renderer_draw(r, camera, &o, &tgt, NULL, err);
    if (st != PNPR_OK) return st;
    st = pnpr_renderer_read_frame(r, b->raster.rgba, 1);
    if (st == PNPR_OK) st = pnpr_renderer_read_depth(r, b->depth);
    if (st != PNPR_OK) return pnpr_error_set(err, st, "effects: reading the layer of node '%s' back", nd->name);
    size_t npx = (size_t)b->raster.width * (size_t)b->raster.height;
    for (size_t i = 0; i < npx; i++) b->raster.rgba[4 * i + 3] = b->depth[i] < 1.0f ? 255 : 0; /* coverage */
    double t1 = pnpr_now();
    st = pnpr_effect_chain_apply(&nd->chain, &b->raster, &b->filtered, seed ^ (uint64_t)l->node, err);
    if (st != PNPR_OK) return st;
    double t2 = pnpr_now();
    /* the inpainted depth only where it is composited; layering none needs only the mask */
    int use_inpainted = p->layering == PNPR_LAYERING_INPAINTED && nd->inpaint;
    pnpr_inpaint_options io = nd->inpaint_opts;
    if (use_inpainted || p->layering == PNPR_LAYERING_NONE)
        st = pnpr_depth_inpaint(&b->raster, &b->filtered, b->depth, &io, use_inpainted ? b->inpainted : NULL, b->mask, err);
    if (st != PNPR_OK) return st;
    double t3 = pnpr_now();
    pnpr_layer layer = {&b->filtered, use_inpainted ? b->inpainted : b->depth, b->mask};
    st = pnpr_layers_merge(&layer, p->layering, &b->out, b->acc_depth, err);
    double t4 = pnpr_now();
    s->raster_s += t1 - t0;
    s->filter_s += t2 - t1;
    s->inpaint_s += t3 - t2;
    s->composite_s += t4 - t3;
    s->layers++;
    return st;
}

static uint8_t to_byte(float v)
{
    float c = v < 0 ? 0 : v > 1 ? 1 : v;
    return (uint8_t)(c * 255.0f + 0.5f);
}

pnpr_status pnpr_renderer_effects(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                  const pnpr_effect_pipeline *p, int width, int height, const pnpr_effects_options *eopts,
                                  uint8_t *r_rgba, pnpr_effects_stats *r_stats, pnpr_error *err)
{
    pnpr_effects_stats stats;
    memset(&stats, 0, sizeof stats);
    if (r_stats) *r_stats = stats;
    if (!r || !p || !p->nodes || p->count == 0 || !r_rgba)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: NULL renderer, pipeline or image");
    pnpr_draw_options base;
    memset(&base, 0, sizeof base);
    if (opts) base = *opts;
    if (base.style_map_count > 0 || pnpr_draw_has_layer(&base))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: the pipeline chooses the styles and layers (no style map or layer in the draw options)");
    if (width <= 0 || height <= 0 || width > r->max_size || height > r->max_size)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: image size %dx%d is outside 1..%d", width, height,
                              (int)r->max_size);
    uint32_t *labels = NULL;
    size_t *nodes = NULL, nl = 0, nlayers = 0;
    fx_layer *layers = NULL;
    fx_buffers b;
    pnpr_status st = cloud_labels(r, p, &labels, &nodes, &nl);
    if (st == PNPR_OK) st = plan_layers(p, labels, nodes, nl, &layers, &nlayers);
    if (st == PNPR_OK) st = alloc_buffers(&b, width, height, r_rgba);
    if (st != PNPR_OK) {
        free(labels); free(nodes); free(layers);
        return pnpr_error_set(err, st, "effects: %dx%d image: out of memory", width, height);
    }
    uint8_t bg[4];
    for (int c = 0; c < 4; c++) bg[c] = to_byte(base.background[c]);
    st = pnpr_layers_clear(bg, &b.out, b.acc_depth, err);
    uint64_t seed = eopts ? eopts->seed : 0;
    for (size_t i = 0; i < nlayers && st == PNPR_OK; i++) {
        st = do_layer(r, camera, &base, p, &layers[i], seed, &b, &stats, err);
        char stage[64];
        snprintf(stage, sizeof stage, "layer %zu/%zu", i + 1, nlayers);
        if (st == PNPR_OK && pnpr_progress_report(eopts ? &eopts->progress : NULL, stage, (double)(i + 1) / (double)nlayers))
            st = pnpr_error_set(err, PNPR_ERR_CANCELLED, "effects: cancelled");
    }
    free_buffers(&b);
    free(labels); free(nodes); free(layers);
    if (r_stats) *r_stats = stats;
    return st;
}
