/* pointnpr — the looks table (look.h). The values were chosen by looking at the lion scan, a
 * generated aerial farm and the coloured test cube (docs/rendering.md, "Looks"). */
#include <pointnpr/look.h>

#include "internal.h"

#include <string.h>
#include <strings.h>

static const pnpr_look looks[] = {
    {"pencil", "graphite sketch: strokes along the features, hatches for the tone", PNPR_STYLE_SKETCHY, PNPR_SKETCH_ALL,
     0, 0, 0, 0, 0, {0, 0, 0, 0}, {255, 255, 255}, 0, 0},
    {"contour", "a light line sketch: strokes along the features and outlines, no hatching", PNPR_STYLE_SKETCHY,
     PNPR_SKETCH_DIRECTIONAL, 1, 0, 0, 0, 0, {0, 0, 0, 0}, {255, 255, 255}, 0, 0},
    {"sepia", "brown ink on cream paper: the pencil sketch of an old notebook", PNPR_STYLE_SKETCHY, PNPR_SKETCH_ALL, 1, 0,
     0, 0, 0, {0.20f, 0.09f, 0.03f, 1}, {244, 234, 212}, 0, 0},
    {"stipple", "ink dots for the tone and the features, with outlines", PNPR_STYLE_STIPPLE, PNPR_SKETCH_ALL, 1, 0, 0, 0,
     0, {0, 0, 0, 0}, {255, 255, 255}, 0, 0},
    {"comic", "flat colours with bold outlines", PNPR_STYLE_CARTOON, PNPR_SKETCH_ALL, 1, 3.5f, 0, 0, 0, {0, 0, 0, 0},
     {255, 255, 255}, 0, 0},
    {"technical", "profile lines and outlines over a faint picture of the scan", PNPR_STYLE_LINES, PNPR_SKETCH_ALL, 1, 0,
     0, 0, 0.3f, {0, 0, 0, 0}, {255, 255, 255}, 0, 0},
    {"blueprint", "white profile lines and outlines on blue paper", PNPR_STYLE_LINES, PNPR_SKETCH_ALL, 1, 0, 0, 0, 0,
     {0.85f, 0.9f, 1, 1}, {24, 56, 112}, 0, 0},
    {"painting", "brush dabs in the points' colours, large to small", PNPR_STYLE_PAINTERLY, PNPR_SKETCH_ALL, 0, 0, 0, 0,
     0, {0, 0, 0, 0}, {255, 255, 255}, 0, 0},
    {"oil", "bristle brush strokes on surface-aligned splats, large enough to see the brushwork", PNPR_STYLE_BRUSH,
     PNPR_SKETCH_ALL, 0, 0, 0, 0, 0, {0, 0, 0, 0}, {255, 255, 255}, 0, 2},
};

const pnpr_look *pnpr_looks(size_t *r_count)
{
    if (r_count) *r_count = sizeof looks / sizeof looks[0];
    return looks;
}

pnpr_status pnpr_look_find(const char *name, size_t *r_index)
{
    if (!name || !r_index) return PNPR_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < sizeof looks / sizeof looks[0]; i++)
        if (!strcasecmp(name, looks[i].name)) {
            *r_index = i;
            return PNPR_OK;
        }
    return PNPR_ERR_NOT_FOUND;
}

const char *pnpr_look_list(char *buf, size_t cap, const char *sep)
{
    const char *names[sizeof looks / sizeof looks[0]];
    for (size_t i = 0; i < sizeof looks / sizeof looks[0]; i++) names[i] = looks[i].name;
    return pnpr_join_names(buf, cap, sep, names, sizeof looks / sizeof looks[0], 0);
}

static void fill(float *member, float value)
{
    if (*member == 0) *member = value;
}

void pnpr_look_apply(const pnpr_look *look, pnpr_draw_options *o)
{
    if (!look || !o) return;
    o->style = look->style;
    if (o->sketch_variant == PNPR_SKETCH_ALL) o->sketch_variant = look->sketch_variant;
    if (o->outline == 0) o->outline = look->outline;
    fill(&o->outline_width, look->outline_width);
    fill(&o->line_width, look->line_width);
    fill(&o->dot_size, look->dot_size);
    fill(&o->faint, look->faint);
    if (o->ink[0] == 0 && o->ink[1] == 0 && o->ink[2] == 0 && o->ink[3] == 0) memcpy(o->ink, look->ink, sizeof o->ink);
    if (o->background[0] == 0 && o->background[1] == 0 && o->background[2] == 0 && o->background[3] == 0) {
        for (int c = 0; c < 3; c++) o->background[c] = look->paper[c] / 255.0f;
        o->background[3] = 1;
    }
    if (o->brush_preset == 0) o->brush_preset = look->brush_preset;
    fill(&o->brush_scale, look->brush_scale);
}
