/* pointnpr — options.h: the defaults and ranges of the options structs, one table per struct.
 *
 * Every numeric option of pnpr_features_options, pnpr_lines_options, the segmentation options,
 * pnpr_outlier_options and the renderer's pnpr_draw_options / pnpr_upload_options is described
 * once, here (filters/options_table.c, core/options_render.c): its name, where it lies
 * in the struct, its default, its accepted range and a line of help. The library fills zeros with
 * these defaults and checks ranges with pnpr_option_check; the CLI prints its usage text and parses
 * its options from the same entries, and the MeshLab dialogs take their defaults and ranges from
 * them (docs/architecture.md, "Where each decision lives").
 *
 * Zero still means "the default" in every struct (the structs are valid zero-initialised):
 * pnpr_X_defaults() returns the struct with each default written out, which computes the same as
 * the zeroed struct. A default that depends on the data (a radius of 3 point spacings) is 0 in the
 * table and in pnpr_X_defaults(); auto_scale and auto_text say what it is. (In the spirit of
 * sokol's query-defaults functions.) */
#ifndef POINTNPR_OPTIONS_H
#define POINTNPR_OPTIONS_H

#include "brush.h"
#include "camera_path.h"
#include "hierarchy.h"
#include "core.h"
#include "features.h"
#include "lines.h"
#include "outliers.h"
#include "render.h"
#include "segment.h"
#include "tone.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pnpr_option_type {
    PNPR_OPTION_INT = 0,   /* int */
    PNPR_OPTION_UINT,      /* uint32_t */
    PNPR_OPTION_FLOAT,     /* float */
    PNPR_OPTION_DOUBLE     /* double */
} pnpr_option_type;

enum {
    PNPR_OPTION_MIN_EXCLUSIVE = 1, /* the range is (min, max]: min itself is refused */
    PNPR_OPTION_ZERO_IS_VALUE = 2, /* 0 is an ordinary value (checked against the range), not the default */
    PNPR_OPTION_NEGATIVE_OFF = 4,  /* any negative value turns the step off */
    PNPR_OPTION_STYLE_DEFAULT = 8  /* the default of some styles only (the help says which; another
                                    * entry may describe the same member for other styles): 0 stays
                                    * in pnpr_X_defaults() and pnpr_option_fill_defaults */
};

/* A max of PNPR_OPTION_UNBOUNDED means "any finite value" (uint: any uint32 value). */
#define PNPR_OPTION_UNBOUNDED 1e300

typedef struct pnpr_option_desc {
    const char *name;      /* the CLI long option name without the dashes ("merge-tol") */
    const char *field;     /* the struct member, as messages name it ("merge_tol") */
    const char *group;     /* the struct, as messages name it ("lines") */
    pnpr_option_type type;
    size_t offset;         /* offsetof(struct, member) */
    double def;            /* the value 0 stands for; 0 when it is computed from the data */
    double min, max;       /* accepted range of a non-zero value, inclusive (see the flags) */
    unsigned flags;        /* PNPR_OPTION_* */
    double auto_scale;     /* def == 0: the default is auto_scale x auto_text ("3" "h"); 0 = just auto_text */
    const char *auto_text; /* def == 0: what the default is ("automatic", "h", "none") */
    const char *help;      /* one line, lower case, no final full stop */
} pnpr_option_desc;

/* The tables (static, constant) and the structs with every default filled in. */
const pnpr_option_desc *pnpr_features_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_lines_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_jseg_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_rgbgrow_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_components_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_hierarchy_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_split_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_tone_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_outlier_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_brush_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_sphere_tree_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_hier_option_table(size_t *r_count);

pnpr_features_options pnpr_features_defaults(void);
pnpr_lines_options pnpr_lines_defaults(void);
pnpr_jseg_options pnpr_jseg_defaults(void);
pnpr_rgbgrow_options pnpr_rgbgrow_defaults(void);
pnpr_components_options pnpr_components_defaults(void);
pnpr_hierarchy_options pnpr_hierarchy_defaults(void);
pnpr_split_options pnpr_split_defaults(void);
pnpr_tone_options pnpr_tone_defaults(void);
pnpr_outlier_options pnpr_outlier_defaults(void);
pnpr_brush_options pnpr_brush_defaults(void);
pnpr_sphere_tree_options pnpr_sphere_tree_defaults(void);
pnpr_hier_params pnpr_hier_defaults(void);

/* The renderer's options (render.h; the table is in the core library, core/options_render.c):
 * per-frame pnpr_draw_options and pnpr_upload_options. pnpr_draw_defaults() leaves the members
 * whose default depends on the style at 0: mask_scale (entries "mask-scale" and, for cartoon,
 * "outline-scale"), outline and outline_width (pnpr_style_outline_default, style.h) and ink (all
 * four 0: the "ink-*" entries; painterly's strokes then take the point colours). The enums,
 * budget, seed, threads and the colours of the background are not in the tables. */
const pnpr_option_desc *pnpr_draw_option_table(size_t *r_count);
const pnpr_option_desc *pnpr_upload_option_table(size_t *r_count);
/* The SVG drawing of profile lines (pnpr_svg_options, camera.h; `lines --svg`). */
const pnpr_option_desc *pnpr_svg_option_table(size_t *r_count);
/* The camera path presets (pnpr_camera_preset_options, camera_path.h; `animate --orbit/--flyover`). */
const pnpr_option_desc *pnpr_camera_preset_option_table(size_t *r_count);
pnpr_draw_options pnpr_draw_defaults(void);
pnpr_upload_options pnpr_upload_defaults(void);
/* Checks every tabled member of o against its entry (pnpr_option_check), mask_scale against the
 * entry of o->style ("outline-scale" for cartoon, else "mask-scale"). The renderer calls it on
 * every frame's options; hosts need not re-check. */
PNPR_NODISCARD pnpr_status pnpr_draw_check(const pnpr_draw_options *o, pnpr_error *err);
/* mask_scale of o (NULL ok) for `style`, its default when 0 (cartoon: "outline-scale"). */
float pnpr_draw_mask_scale(const pnpr_draw_options *o, pnpr_style style);
/* The ink of o (NULL ok) into r_ink, the default when all four are 0; returns whether o gives one. */
int pnpr_draw_ink(const pnpr_draw_options *o, float r_ink[4]);

/* ---- working with a table (core/options.c) ------------------------------------------------- */

/* The entry called `name` (CLI name), or NULL. */
const pnpr_option_desc *pnpr_option_find(const pnpr_option_desc *table, size_t count, const char *name);
/* The entry's member of the struct at opts, as a double / set from a double (converted). */
double pnpr_option_get(const pnpr_option_desc *d, const void *opts);
void pnpr_option_set(const pnpr_option_desc *d, void *opts, double value);
/* Writes every entry's default into the struct (data-dependent ones and STYLE_DEFAULT ones: 0). */
void pnpr_option_set_defaults(const pnpr_option_desc *table, size_t count, void *opts);
/* Replaces the zeros that mean "the default" by the default (leaves ZERO_IS_VALUE and
 * STYLE_DEFAULT members, negative "off" values and data-dependent defaults alone). */
void pnpr_option_fill_defaults(const pnpr_option_desc *table, size_t count, void *opts);
/* Whether `value` lies in the entry's range (finite; an integer for int types). Zero and
 * negative "off" values are NOT special here: this is the range an explicit setting must meet. */
int pnpr_option_in_range(const pnpr_option_desc *d, double value);
/* Checks every entry of the struct: 0 (the default, unless ZERO_IS_VALUE), a negative value of a
 * NEGATIVE_OFF entry, or a value in range. Else PNPR_ERR_INVALID_ARGUMENT with a message naming the
 * option and its range in err (may be NULL): "features: k 1025 is not in 1..1024 (0 = 16)". */
PNPR_NODISCARD pnpr_status pnpr_option_check(const pnpr_option_desc *table, size_t count, const void *opts, pnpr_error *err);
/* Text for usage lines and messages (NUL-terminated, truncated to cap):
 *   range:   "in 1..1024", "in (0, 1]", "in [0, 1e+06]", "> 0", ">= 1"
 *   default: "16", "0.6", "automatic", "3h", "h" */
void pnpr_option_range_text(const pnpr_option_desc *d, char *buf, size_t cap);
void pnpr_option_default_text(const pnpr_option_desc *d, char *buf, size_t cap);

#ifdef __cplusplus
}
#endif
#endif
