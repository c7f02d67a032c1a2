/* Segment-specific image-space effects, the renderer's side (render.h, pnpr_renderer_effects):
 * Wegen et al.'s per-frame loop. Each layer (a pipeline node's labels, or one label with
 * per_label) is drawn as its own frame with the node's style (pnpr_draw_options.layer_labels:
 * only its points take part), read back as colour + depth, filtered by the node's chain,
 * inpainted and merged into the image (effects/composite.c). docs/effects.md. */
#include "renderer_internal.h"

#include "../core/internal.h"
#include "../effects/effects_internal.h"

#include <pthread.h>

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
    qsort(v, r->count, sizeof *v, pnpr_cmp_u32);
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

/* A rasterised layer (colour with coverage as alpha, depth), handed from the GL thread to the
 * filters. */
typedef struct fx_slot {
    pnpr_image raster;
    float *depth;
    const fx_layer *layer;
    int full; /* 1: rasterised, waiting for the filters (owned by the filter side until cleared) */
} fx_slot;

/* The filter side of the frame: its scratch, the composite so far and what it measured. With a
 * filter thread, mu/cv guard `full`, `closed`, `failed` and `st`; the rest belongs to one side. */
typedef struct fx_frame {
    const pnpr_effect_pipeline *p;
    uint64_t seed;
    fx_slot slot[2];          /* two with a filter thread (one rasterised while one is filtered) */
    pnpr_image filtered, out; /* out: the composite (the caller's image, or the preview's) */
    float *inpainted, *acc_depth;
    uint8_t *mask;
    double filter_s, inpaint_s, composite_s;
    size_t merged;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    int closed, failed;       /* no more layers will come; a layer failed (either side) */
    pnpr_status st;           /* the filter side's failure */
    pnpr_error err;
} fx_frame;

static void free_frame(fx_frame *f)
{
    for (int k = 0; k < 2; k++) { free(f->slot[k].raster.rgba); free(f->slot[k].depth); }
    free(f->filtered.rgba);
    free(f->inpainted);
    free(f->acc_depth);
    free(f->mask);
}

/* Scratch for w x h layers composited into `out` (w x h RGBA8); `slots` raster slots. */
static pnpr_status alloc_frame(fx_frame *f, int w, int h, uint8_t *out, int slots)
{
    size_t n = (size_t)w * (size_t)h;
    int ok = 1;
    for (int k = 0; k < slots; k++) {
        f->slot[k].raster = (pnpr_image){w, h, malloc(n * 4)};
        f->slot[k].depth = malloc(n * sizeof(float));
        ok = ok && f->slot[k].raster.rgba && f->slot[k].depth;
    }
    f->filtered = (pnpr_image){w, h, malloc(n * 4)};
    f->out = (pnpr_image){w, h, out};
    f->inpainted = malloc(n * sizeof(float));
    f->acc_depth = malloc(n * sizeof(float));
    f->mask = malloc(n);
    if (ok && out && f->filtered.rgba && f->inpainted && f->acc_depth && f->mask) return PNPR_OK;
    free_frame(f);
    return PNPR_ERR_OUT_OF_MEMORY;
}

/* The GL side: draws layer l with its node's style into the renderer's frame and reads it back
 * into the slot (coverage as alpha). */
static pnpr_status rasterise(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *base,
                             const pnpr_effect_pipeline *p, const fx_layer *l, fx_slot *slot, pnpr_error *err)
{
    const pnpr_effect_node *nd = &p->nodes[l->node];
    pnpr_draw_options o = *base;
    o.style = nd->style;
    if (nd->point_scale > 0) o.point_scale = nd->point_scale;
    o.layer_labels = l->labels;
    o.layer_label_count = l->count;
    o.layer_exclude = l->count == 0;
    o.background[3] = 1.0f; /* opaque paper for the filters */
    pnpr_target tgt = {0, 0, 0, slot->raster.width, slot->raster.height, 1, 0};
    pnpr_status st = pnpr_renderer_draw(r, camera, &o, &tgt, NULL, err);
    if (st != PNPR_OK) return st;
    st = pnpr_renderer_read_frame(r, slot->raster.rgba, 1);
    if (st == PNPR_OK) st = pnpr_renderer_read_depth(r, slot->depth);
    if (st != PNPR_OK) return pnpr_error_set(err, st, "effects: reading the layer of node '%s' back", nd->name);
    size_t npx = (size_t)slot->raster.width * (size_t)slot->raster.height;
    for (size_t i = 0; i < npx; i++) slot->raster.rgba[4 * i + 3] = slot->depth[i] < 1.0f ? 255 : 0; /* coverage */
    slot->layer = l;
    return PNPR_OK;
}

/* The filter side: filters, inpaints and merges the slot's layer into the composite. */
static pnpr_status finish_layer(fx_frame *f, const fx_slot *slot, pnpr_error *err)
{
    const pnpr_effect_pipeline *p = f->p;
    const fx_layer *l = slot->layer;
    const pnpr_effect_node *nd = &p->nodes[l->node];
    double t1 = pnpr_now();
    pnpr_status st = pnpr_effect_chain_apply(&nd->chain, &slot->raster, &f->filtered, f->seed ^ (uint64_t)l->node, err);
    if (st != PNPR_OK) return st;
    double t2 = pnpr_now();
    /* the inpainted depth only where it is composited; layering none needs only the mask */
    int use_inpainted = p->layering == PNPR_LAYERING_INPAINTED && nd->inpaint;
    pnpr_inpaint_options io = nd->inpaint_opts;
    if (use_inpainted || p->layering == PNPR_LAYERING_NONE)
        st = pnpr_depth_inpaint(&slot->raster, &f->filtered, slot->depth, &io, use_inpainted ? f->inpainted : NULL,
                                f->mask, err);
    if (st != PNPR_OK) return st;
    double t3 = pnpr_now();
    pnpr_layer layer = {&f->filtered, use_inpainted ? f->inpainted : slot->depth, f->mask};
    st = pnpr_layers_merge(&layer, p->layering, &f->out, f->acc_depth, err);
    f->filter_s += t2 - t1;
    f->inpaint_s += t3 - t2;
    f->composite_s += pnpr_now() - t3;
    f->merged += st == PNPR_OK;
    return st;
}

/* The filter thread: takes the slots in turn until the GL side closes the frame or a layer fails. */
static void *filter_thread(void *arg)
{
    fx_frame *f = arg;
    for (size_t i = 0;; i++) {
        fx_slot *slot = &f->slot[i % 2];
        pthread_mutex_lock(&f->mu);
        while (!slot->full && !f->closed) pthread_cond_wait(&f->cv, &f->mu);
        int go = slot->full && !f->failed;
        pthread_mutex_unlock(&f->mu);
        if (!go) break;
        pnpr_status st = finish_layer(f, slot, &f->err);
        pthread_mutex_lock(&f->mu);
        slot->full = 0;
        if (st != PNPR_OK) { f->failed = 1; f->st = st; }
        pthread_cond_broadcast(&f->cv);
        pthread_mutex_unlock(&f->mu);
        if (st != PNPR_OK) break;
    }
    return NULL;
}

/* Waits until `slot` is free (the filters took its layer); 0 when the filter side failed. */
static int wait_free(fx_frame *f, fx_slot *slot)
{
    pthread_mutex_lock(&f->mu);
    while (slot->full && !f->failed) pthread_cond_wait(&f->cv, &f->mu);
    int ok = !f->failed;
    pthread_mutex_unlock(&f->mu);
    return ok;
}

/* Hands a rasterised slot to the filter thread (ok) or tells it that no more will come. */
static void hand_over(fx_frame *f, fx_slot *slot, int ok)
{
    pthread_mutex_lock(&f->mu);
    if (ok) slot->full = 1;
    else f->closed = 1;
    pthread_cond_broadcast(&f->cv);
    pthread_mutex_unlock(&f->mu);
}

static pnpr_status report_layer(const pnpr_effects_options *eopts, size_t i, size_t n, pnpr_error *err)
{
    char stage[64];
    snprintf(stage, sizeof stage, "layer %zu/%zu", i + 1, n);
    if (pnpr_progress_report(eopts ? &eopts->progress : NULL, stage, (double)(i + 1) / (double)n))
        return pnpr_error_set(err, PNPR_ERR_CANCELLED, "effects: cancelled");
    return PNPR_OK;
}

/* Every layer: rasterised here (the GL thread), filtered and merged here (serial) or on a filter
 * thread that overlaps layer i's filters with layer i+1's rasterisation. Layers are merged in
 * order either way: the same pixels. */
static pnpr_status run_layers(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *base,
                              fx_frame *f, const fx_layer *layers, size_t n, const pnpr_effects_options *eopts,
                              int threaded, double *r_raster_s, pnpr_error *err)
{
    pthread_t th;
    if (threaded && pthread_create(&th, NULL, filter_thread, f) != 0) threaded = 0;
    pnpr_status st = PNPR_OK;
    for (size_t i = 0; i < n && st == PNPR_OK; i++) {
        fx_slot *slot = &f->slot[threaded ? i % 2 : 0];
        if (threaded && !wait_free(f, slot)) break;
        double t0 = pnpr_now();
        st = rasterise(r, camera, base, f->p, &layers[i], slot, err);
        *r_raster_s += pnpr_now() - t0;
        if (st == PNPR_OK && threaded) hand_over(f, slot, 1);
        else if (st == PNPR_OK) st = finish_layer(f, slot, err);
        if (st == PNPR_OK) st = report_layer(eopts, i, n, err);
    }
    if (!threaded) return st;
    pthread_mutex_lock(&f->mu);
    if (st != PNPR_OK) f->failed = 1; /* the filters drop what is left */
    pthread_mutex_unlock(&f->mu);
    hand_over(f, NULL, 0);
    pthread_join(th, NULL);
    if (st == PNPR_OK && f->failed) {
        st = f->st;
        if (err) *err = f->err;
    }
    return st;
}

/* The size of the layers: the image's, or `scale` of it (a preview), at least 1 x 1. */
static void layer_size(float scale, int width, int height, int *r_w, int *r_h)
{
    *r_w = width;
    *r_h = height;
    if (!(scale > 0.0f && scale < 1.0f)) return;
    int w = (int)((float)width * scale + 0.5f), h = (int)((float)height * scale + 0.5f);
    *r_w = w < 1 ? 1 : w;
    *r_h = h < 1 ? 1 : h;
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
    float scale = eopts ? eopts->scale : 0.0f;
    if (!(scale >= 0.0f && scale <= 1.0f) || (scale > 0.0f && scale < PNPR_EFFECTS_SCALE_MIN))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: scale %g is outside %g..1 (0 = 1)", (double)scale,
                              (double)PNPR_EFFECTS_SCALE_MIN);
    int lw, lh, threaded = !(eopts && eopts->serial);
    layer_size(scale, width, height, &lw, &lh);
    int preview = lw != width || lh != height;
    uint32_t *labels = NULL;
    size_t *nodes = NULL, nl = 0, nlayers = 0;
    fx_layer *layers = NULL;
    fx_frame f;
    memset(&f, 0, sizeof f);
    f.p = p;
    f.seed = eopts ? eopts->seed : 0;
    uint8_t *small = preview ? malloc((size_t)lw * (size_t)lh * 4) : NULL;
    pnpr_status st = cloud_labels(r, p, &labels, &nodes, &nl);
    if (st == PNPR_OK) st = plan_layers(p, labels, nodes, nl, &layers, &nlayers);
    if (st == PNPR_OK) st = alloc_frame(&f, lw, lh, preview ? small : r_rgba, threaded ? 2 : 1);
    if (st != PNPR_OK) {
        free(labels); free(nodes); free(layers); free(small);
        return pnpr_error_set(err, st, "effects: %dx%d image: out of memory", lw, lh);
    }
    pthread_mutex_init(&f.mu, NULL);
    pthread_cond_init(&f.cv, NULL);
    uint8_t bg[4];
    for (int c = 0; c < 4; c++) bg[c] = pnpr_fx_byte(base.background[c]);
    st = pnpr_layers_clear(bg, &f.out, f.acc_depth, err);
    if (st == PNPR_OK) st = run_layers(r, camera, &base, &f, layers, nlayers, eopts, threaded, &stats.raster_s, err);
    if (st == PNPR_OK && preview) st = pnpr_cv_resize_rgba8(small, lw, lh, r_rgba, width, height, err);
    pthread_cond_destroy(&f.cv);
    pthread_mutex_destroy(&f.mu);
    stats.layers = f.merged;
    stats.filter_s = f.filter_s;
    stats.inpaint_s = f.inpaint_s;
    stats.composite_s = f.composite_s;
    stats.layer_width = lw;
    stats.layer_height = lh;
    free_frame(&f);
    free(labels); free(nodes); free(layers); free(small);
    if (r_stats) *r_stats = stats;
    return st;
}
