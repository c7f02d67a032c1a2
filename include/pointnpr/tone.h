/* pointnpr — tone.h: how dark each point should be drawn (GL-free, core library).
 *
 * The tone of a point is a darkness in [0,1] (0 = paper white, 1 = full ink). It drives the
 * density of the dithering points (sketchy hatches, stipple dots: pnpr_features_options.tone)
 * and the shading of clouds without colours (the renderer's grey levels and the cartoon's
 * cel bands: pnpr_upload_options.tone). Sources:
 *   - colour: 1 - Rec. 601 luma of the point colour;
 *   - light: a key light from above (two-sided Lambert with ambient, so that normals of either
 *     orientation shade alike): 1 - (ambient + (1 - ambient) |n . l|);
 *   - both: the light's brightness times the colour's, the colour weighted by colour_weight:
 *     1 - shade * (1 - colour_weight * colour darkness) (lighting carries the form, colour the
 *     regions; a uniformly coloured lit ground stays light).
 * Then the curve t' = clamp((t - 0.5) * contrast + 0.5, 0, 1) ^ gamma: gamma > 1 keeps the large
 * mid-tone areas light and leaves the darkest parts dark. docs/rendering.md, "Tone", has the
 * defaults and why. */
#ifndef POINTNPR_TONE_H
#define POINTNPR_TONE_H

#include "core.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pnpr_tone_source {
    PNPR_TONE_AUTO = 0, /* both with colours and normals, light with normals only, colour with
                         * colours only, else a flat 0.5 */
    PNPR_TONE_COLOR,
    PNPR_TONE_LIGHT,
    PNPR_TONE_BOTH,
    PNPR_TONE_SOURCE_COUNT_
} pnpr_tone_source;

typedef struct pnpr_tone_options {
    pnpr_tone_source source;
    double up[3];        /* the scene's up (pnpr_scene_frame); zero = +z */
    double light[3];     /* direction towards the key light; zero = from above, tilted towards
                          * the scene's -y side and to the left (pnpr_tone_light) */
    /* zero = the default; defaults and ranges: pnpr_tone_option_table (options.h) */
    float ambient;       /* the shade of a surface facing away from the light */
    float colour_weight; /* both: the colour's share */
    float contrast;
    float gamma;
} pnpr_tone_options;

/* The effective light direction (unit) of the options. */
void pnpr_tone_light(const pnpr_tone_options *opts, double r_light[3]);

/* Per point darkness in [0,1] into r_tone. rgb (3 bytes a point) and normals (3 floats, any
 * length, zero = unknown: shaded as ambient + half) may be NULL. A source the data cannot serve
 * (colour without rgb, light without normals) falls back to the other, else to 0.5.
 * PNPR_ERR_INVALID_ARGUMENT for bad options (unknown source, negative or non-finite values,
 * ambient or colour_weight above 1, a zero light vector only when explicitly non-finite). */
PNPR_NODISCARD pnpr_status pnpr_tone(const uint8_t *rgb, const float *normals, size_t count,
                      const pnpr_tone_options *opts, float *r_tone);

#ifdef __cplusplus
}
#endif
#endif
