/* Effect names, parameter tables, presets and dispatch (effects.h). The tables are the one source
 * of every effect's defaults and ranges: pipeline files, the CLI, MeshLab and docs/effects.md read
 * them here. */
#include "effects_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct effect_def {
    const char *name;
    pnpr_effect_fn fn;
    int count;
    pnpr_effect_param_info params[PNPR_EFFECT_PARAMS_MAX];
} effect_def;

static const effect_def effect_defs[PNPR_EFFECT_COUNT_] = {
    [PNPR_EFFECT_SMOOTH] = {"smooth", pnpr_fx_smooth, 3, {
        {"radius", 4, 1, 32, "bilateral filter radius in px"},
        {"sigma_color", 0.1f, 0.01f, 1, "colour difference (0..1) that still smooths"},
        {"iterations", 2, 1, 8, "bilateral passes"}}},
    [PNPR_EFFECT_TOON] = {"toon", pnpr_fx_toon, 8, {
        {"iterations", 3, 1, 8, "bilateral abstraction passes (Winnemoeller: 3-4)"},
        {"sigma_color", 0.1f, 0.01f, 1, "abstraction: colour difference that still smooths"},
        {"radius", 3, 1, 16, "abstraction: bilateral radius in px"},
        {"levels", 8, 2, 32, "luminance bins of the quantisation"},
        {"sharpness", 3, 0.5f, 20, "quantisation sharpness (phi_q)"},
        {"edge_sigma", 1, 0.3f, 8, "DoG edge scale in px (sigma_e)"},
        {"edge_strength", 1, 0, 1, "darkness of the DoG edges (0 = none)"},
        {"silhouette", 1, 0, 1, "darkness of the segment's outline (its coverage border)"}}},
    [PNPR_EFFECT_WATERCOLOUR] = {"watercolour", pnpr_fx_watercolour, 7, {
        {"abstraction", 5, 1, 32, "colour abstraction radius in px"},
        {"density", 0.5f, 0, 2, "pigment density variation (paper + turbulence)"},
        {"paper_scale", 3, 1, 64, "paper grain size in px"},
        {"turbulence_scale", 40, 4, 400, "pigment turbulence size in px"},
        {"edge_darkening", 0.8f, 0, 2, "pigment accumulated at colour edges"},
        {"edge_width", 2, 0.5f, 16, "width of the darkened edges in px"},
        {"fill", 2, 0, 16, "gap filling and morphological smoothing radius in px: gaps between splats narrower than it are painted over with their surroundings' mean colour"}}},
    [PNPR_EFFECT_OIL] = {"oil", pnpr_fx_oil, 5, {
        {"length", 8, 1, 32, "smoothing length along the flow in px"},
        {"tensor_sigma", 3, 0.5f, 10, "structure tensor smoothing in px"},
        {"brush_scale", 3, 1, 16, "brush bristle texture size in px"},
        {"relief", 0.5f, 0, 2, "relief lighting of the paint"},
        {"levels", 0, 0, 32, "colour levels per channel before painting (0 = none)"}}},
    [PNPR_EFFECT_PENCIL] = {"pencil", pnpr_fx_pencil, 7, {
        {"spacing", 6, 2, 32, "hatch spacing in px"},
        {"angle", 45, -180, 180, "hatch angle in degrees"},
        {"layers", 3, 1, 4, "hatch layers (cross-hatching in darker tones)"},
        {"outline", 1, 0, 1, "outline darkness"},
        {"color", 0, 0, 1, "how much of the source colour tints the paper (0 = grey)"},
        {"silhouette", 1, 0, 1, "darkness of the segment's outline (its coverage border)"},
        {"normalise", 1, 0, 1, "1 = the layer's tone range stretched before hatching (light, low-contrast scans get hatched)"}}},
    [PNPR_EFFECT_POSTERISE] = {"posterise", pnpr_fx_posterise, 2, {
        {"levels", 4, 2, 64, "levels per channel"},
        {"normalise", 1, 0, 1, "1 = the luminance quantised over the layer's stretched tone range, hue kept (a light scan keeps several levels); 0 = each channel quantised as it is"}}},
    [PNPR_EFFECT_GRADE] = {"grade", pnpr_fx_grade, 7, {
        {"brightness", 0, -1, 1, "added to every channel"},
        {"contrast", 1, 0, 4, "around mid grey"},
        {"saturation", 1, 0, 4, "0 = grey, 1 = unchanged"},
        {"tint_r", 1, 0, 1, "tint colour, red"},
        {"tint_g", 1, 0, 1, "tint colour, green"},
        {"tint_b", 1, 0, 1, "tint colour, blue"},
        {"recolour", 0, 0, 1, "mix towards the tint colour at the pixel's luminance (1 = recoloured)"}}},
    [PNPR_EFFECT_EDGES] = {"edges", pnpr_fx_edges, 7, {
        {"sigma", 1, 0.3f, 8, "XDoG scale in px"},
        {"k", 1.6f, 1.1f, 5, "ratio of the two Gaussians"},
        {"tau", 0.98f, 0.5f, 1, "XDoG tau (sharpening)"},
        {"phi", 40, 0.5f, 200, "XDoG soft threshold slope (on luminance 0..1)"},
        {"strength", 1, 0, 1, "darkness of the edges"},
        {"silhouette", 1, 0, 1, "darkness of the segment's outline (its coverage border; catches outlines the colours do not show)"},
        {"paper", 0, 0, 1, "1 = the lines alone on the paper colour (a line drawing); 0 = over the image"}}},
};

const char *pnpr_effect_name(pnpr_effect_kind kind)
{
    return (unsigned)kind < PNPR_EFFECT_COUNT_ ? effect_defs[kind].name : "";
}

pnpr_status pnpr_effect_from_name(const char *name, pnpr_effect_kind *r_kind)
{
    if (!name || !r_kind) return PNPR_ERR_INVALID_ARGUMENT;
    for (int i = 0; i < PNPR_EFFECT_COUNT_; i++)
        if (!strcasecmp(name, effect_defs[i].name)) { *r_kind = (pnpr_effect_kind)i; return PNPR_OK; }
    if (!strcasecmp(name, "watercolor")) { *r_kind = PNPR_EFFECT_WATERCOLOUR; return PNPR_OK; }
    if (!strcasecmp(name, "posterize")) { *r_kind = PNPR_EFFECT_POSTERISE; return PNPR_OK; }
    return PNPR_ERR_NOT_FOUND;
}

const pnpr_effect_param_info *pnpr_effect_params(pnpr_effect_kind kind, int *r_count)
{
    if ((unsigned)kind >= PNPR_EFFECT_COUNT_) { if (r_count) *r_count = 0; return NULL; }
    if (r_count) *r_count = effect_defs[kind].count;
    return effect_defs[kind].params;
}

float pnpr_effect_param(const pnpr_effect *e, int i)
{
    if (!e || (unsigned)e->kind >= PNPR_EFFECT_COUNT_ || i < 0 || i >= effect_defs[e->kind].count) return NAN;
    return (e->set >> i) & 1u ? e->params[i] : effect_defs[e->kind].params[i].def;
}

static pnpr_status check_image(const pnpr_image *im, const char *what, pnpr_error *err)
{
    if (!im || !im->rgba || im->width <= 0 || im->height <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: %s image missing or of size %dx%d", what,
                              im ? im->width : 0, im ? im->height : 0);
    if ((size_t)im->width > ((size_t)1 << 30) / (size_t)im->height)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: %s image %dx%d is too large", what,
                              im->width, im->height);
    return PNPR_OK;
}

pnpr_status pnpr_effect_apply(const pnpr_effect *e, const pnpr_image *src, pnpr_image *dst, uint64_t seed,
                              pnpr_error *err)
{
    if (!e || (unsigned)e->kind >= PNPR_EFFECT_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: unknown effect %d", e ? (int)e->kind : -1);
    pnpr_status st = check_image(src, "source", err);
    if (st == PNPR_OK) st = check_image(dst, "target", err);
    if (st != PNPR_OK) return st;
    if (src->width != dst->width || src->height != dst->height || src->rgba == dst->rgba)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: %s: source %dx%d and target %dx%d must be distinct images of one size",
                              effect_defs[e->kind].name, src->width, src->height, dst->width, dst->height);
    const effect_def *d = &effect_defs[e->kind];
    float p[PNPR_EFFECT_PARAMS_MAX];
    for (int i = 0; i < d->count; i++) {
        p[i] = pnpr_effect_param(e, i);
        if (!(p[i] >= d->params[i].min && p[i] <= d->params[i].max))
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: %s %s=%g is outside %g..%g", d->name,
                                  d->params[i].name, (double)p[i], (double)d->params[i].min, (double)d->params[i].max);
    }
    return d->fn(p, src, dst, seed, err);
}

pnpr_status pnpr_effect_chain_apply(const pnpr_effect_chain *chain, const pnpr_image *src, pnpr_image *dst,
                                    uint64_t seed, pnpr_error *err)
{
    if (!chain || chain->count < 0 || chain->count > PNPR_EFFECT_CHAIN_MAX)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: bad chain");
    pnpr_status st = check_image(src, "source", err);
    if (st == PNPR_OK) st = check_image(dst, "target", err);
    if (st != PNPR_OK) return st;
    size_t bytes = (size_t)src->width * (size_t)src->height * 4;
    if (dst->width != src->width || dst->height != src->height || dst->rgba == src->rgba)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "effects: chain source and target must be distinct images of one size");
    if (chain->count == 0) { memcpy(dst->rgba, src->rgba, bytes); return PNPR_OK; }
    pnpr_image tmp = {src->width, src->height, NULL};
    if (chain->count > 1 && !(tmp.rgba = malloc(bytes)))
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "effects: out of memory (%zu bytes)", bytes);
    /* ping-pong so that the last effect writes dst: odd steps from the end go to tmp */
    const pnpr_image *in = src;
    for (int i = 0; i < chain->count && st == PNPR_OK; i++) {
        pnpr_image *out = ((chain->count - 1 - i) % 2 == 0) ? dst : &tmp;
        st = pnpr_effect_apply(&chain->effects[i], in, out, seed + (uint64_t)i * 0x9E3779B97F4A7C15ull, err);
        in = out;
    }
    free(tmp.rgba);
    return st;
}

/* ---- presets ---- */

#define FX(kind) {kind, 0, {0}}
#define FX1(kind, i0, v0) {kind, 1u << (i0), {[i0] = v0}}

static const pnpr_effect_preset presets[] = {
    {"cartoon", "toon shading with dark DoG edges (Winnemoeller)", {{FX(PNPR_EFFECT_TOON)}, 1}},
    {"watercolour", "smoothed, then watercolour pigment and darkened edges (Bousseau)",
     {{FX(PNPR_EFFECT_SMOOTH), FX(PNPR_EFFECT_WATERCOLOUR)}, 2}},
    {"oil", "oil paint along the image's flow (Semmo)", {{FX(PNPR_EFFECT_OIL)}, 1}},
    {"pencil", "pencil hatching with outlines", {{FX(PNPR_EFFECT_PENCIL)}, 1}},
    {"poster", "four tone levels with dark edges", {{FX(PNPR_EFFECT_SMOOTH), FX(PNPR_EFFECT_POSTERISE), FX(PNPR_EFFECT_EDGES)}, 3}},
    {"muted", "desaturated, lighter and softer: for context behind the subject",
     {{{PNPR_EFFECT_GRADE, 0x7u, {0.12f, 0.75f, 0.3f}}}, 1}},
    {"ink", "a line drawing: edges and outlines alone on the paper",
     {{FX(PNPR_EFFECT_SMOOTH), FX1(PNPR_EFFECT_EDGES, 6, 1.0f)}, 2}},
};

const pnpr_effect_preset *pnpr_effect_presets(int *r_count)
{
    if (r_count) *r_count = (int)(sizeof presets / sizeof presets[0]);
    return presets;
}

const pnpr_effect_preset *pnpr_effect_preset_find(const char *name)
{
    if (!name) return NULL;
    for (size_t i = 0; i < sizeof presets / sizeof presets[0]; i++)
        if (!strcasecmp(name, presets[i].name)) return &presets[i];
    return NULL;
}
