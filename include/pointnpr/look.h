/* pointnpr — looks: named combinations of draw options that read as a finished illustration at
 * first sight (a style with its variant, outline, widths, ink and paper). One table, read by
 * `pointnpr render|animate --look NAME` and the MeshLab decorator's Look parameter; docs/rendering.md,
 * "Looks", shows each on the sample scans. */
#ifndef POINTNPR_LOOK_H
#define POINTNPR_LOOK_H

#include "render.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pnpr_look {
    const char *name;            /* lower case, no spaces: the CLI's and the settings' spelling */
    const char *description;     /* one line, for usage texts and tooltips */
    pnpr_style style;
    pnpr_sketch_variant sketch_variant;
    int outline;                 /* pnpr_draw_options.outline: 0 the style's, 1 on, -1 off */
    float outline_width;         /* px; 0 = the style's */
    float line_width;            /* px; 0 = the draw option table's */
    float dot_size;              /* px; 0 = the table's */
    float faint;                 /* lines: the cloud faintly under them; 0 = none */
    float ink[4];                /* linear RGBA; all zero = the table's ink */
    unsigned char paper[3];      /* the background, 0..255 as `--background` */
    int brush_preset;            /* brush: pnpr_brush_presets index */
    float brush_scale;           /* brush: splat half-size in r + eps units; 0 = the table's */
} pnpr_look;

/* The looks in order; *r_count (may be NULL) receives how many. Index 0 is the default look. */
const pnpr_look *pnpr_looks(size_t *r_count);
/* The index of a look by name (case ignored); PNPR_ERR_NOT_FOUND. */
PNPR_NODISCARD pnpr_status pnpr_look_find(const char *name, size_t *r_index);
/* The looks' names joined by `sep` into buf (cap > 0 bytes, NUL-terminated, truncated to fit).
 * Returns buf. */
const char *pnpr_look_list(char *buf, size_t cap, const char *sep);
/* Writes the look into o: the style always; every other member the look sets (the sketch
 * variant, outline, widths, faint, ink, brush and its scale) only where o still holds zero (zero = the default,
 * so an explicit choice of the caller wins); the background when o's is all zero (then opaque). */
void pnpr_look_apply(const pnpr_look *look, pnpr_draw_options *o);

#ifdef __cplusplus
}
#endif

#endif
