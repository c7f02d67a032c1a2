/* Internal interface of the image-space effects (effects/): one function per effect, each in its
 * own file, called by pnpr_effect_apply (effects/effect.c) with checked arguments; the OpenCV
 * building blocks (effects/cv_adapter.cpp). */
#ifndef PNPR_EFFECTS_INTERNAL_H
#define PNPR_EFFECTS_INTERNAL_H

#include <pointnpr/effects.h>

/* An effect: src -> dst (same size, distinct, checked), parameters resolved to values in range
 * (p[i] = pnpr_effect_param(e, i)). */
typedef pnpr_status (*pnpr_effect_fn)(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed,
                                      pnpr_error *err);

pnpr_status pnpr_fx_smooth(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_toon(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_watercolour(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_oil(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_pencil(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_posterise(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_grade(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);
pnpr_status pnpr_fx_edges(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err);

/* Whether this build has OpenCV (0: the pnpr_cv_* functions return PNPR_ERR_UNSUPPORTED). */
int pnpr_cv_available(void);

#endif
