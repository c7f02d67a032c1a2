/* The defaults and ranges of the renderer's options structs, pnpr_draw_options and
 * pnpr_upload_options (render.h; options.h): the one place they are written. The structs are
 * plain data, so the table lives in the core library (no GL): the renderer fills the zeros of
 * the options it is given from here (pnpr_renderer_check_options, the upload), the CLI's
 * render/animate usage text and parser and the MeshLab decorator's dialog read these entries;
 * tests/test_options_table.c holds them to it. */
#include "options_internal.h"

#include <string.h>

#define PER_STYLE PNPR_OPTION_STYLE_DEFAULT

#define D(...) OPT("draw", pnpr_draw_options, __VA_ARGS__)
static const pnpr_option_desc draw_table[] = {
    D("stroke-texture", stroke_texture, INT, 0, 0, 2, ZERO_VALUE, 0, NULL,
      "directional stroke texture (paper fig. 5 a-c)"),
    /* 2: clouds of up to 2 points per covered pixel draw every point; denser views (a large scan
     * in a small window or zoomed out) keep the ink of 2 (docs/rendering.md, "Continuous
     * resolution queue": lion sketchy at 160x120 covers 52% of the cloud's pixels in ink when every
     * point draws, 23% under 2) */
    D("density", density, FLOAT, 2, 1e-9, UNB, NEG_OFF, 0, NULL,
      "at most this many points per covered pixel (the screen-space budget)"),
    D("point-scale", point_scale, FLOAT, 1, 1e-3, 1e3, 0, 0, NULL, "disk radius multiplier"),
    D("mask-scale", mask_scale, FLOAT, 1.5, 0, UNB, EXCL | PER_STYLE, 0, NULL,
      "visibility-mask disks in disk radii x point scale (all styles but cartoon)"),
    D("outline-scale", mask_scale, FLOAT, 2, 1, 100, PER_STYLE, 0, NULL,
      "cartoon: gap-closing disks, times the splat size"),
    D("stroke-length", stroke_length, FLOAT, 6, 0, UNB, EXCL, 0, NULL,
      "directional stroke length in disk radii (hatches: half)"),
    D("stroke-width", stroke_width, FLOAT, 2, 0, UNB, EXCL, 0, NULL, "stroke width in pixels"),
    /* 48 px: a close-up draws the strokes of a view from further away (at 1024x768 a stroke of the
     * default views is 6 to 20 px) instead of streaks across the frame (issue 15) */
    D("stroke-max", stroke_max, FLOAT, 48, 1, 1e4, NEG_OFF, 0, NULL,
      "longest directional stroke or hatch in pixels (close-ups: no streaks)"),
    /* ink: all four 0 = this colour; painterly's strokes then take the point colours */
    D("ink-r", ink[0], FLOAT, 0.08, 0, 1, ZERO_VALUE | PER_STYLE, 0, NULL, "ink colour, red (linear)"),
    D("ink-g", ink[1], FLOAT, 0.08, 0, 1, ZERO_VALUE | PER_STYLE, 0, NULL, "ink colour, green (linear)"),
    D("ink-b", ink[2], FLOAT, 0.1, 0, 1, ZERO_VALUE | PER_STYLE, 0, NULL, "ink colour, blue (linear)"),
    D("ink-a", ink[3], FLOAT, 1, 0, 1, ZERO_VALUE | PER_STYLE, 0, NULL, "ink opacity"),
    D("line-width", line_width, FLOAT, 2, 1e-2, 1e3, 0, 0, NULL, "lines: stroke width in pixels"),
    D("line-min", line_min_px, FLOAT, PNPR_LINE_MIN_PX, 0.01, 1e4, 0, 0, NULL,
      "lines: profile lines shorter on screen are left out"),
    D("faint", faint, FLOAT, 0, 0, 1, EXCL, 0, "none",
      "lines: the cloud faintly under them, this much"),
    D("dot-size", dot_size, FLOAT, 2.5, 1e-2, 1e3, 0, 0, NULL, "stipple: dot diameter in pixels"),
    D("levels", levels, INT, 4, 2, 256, 0, 0, NULL, "cartoon: colour levels per channel (no labels)"),
    D("outline", outline, INT, 0, -1, 1, 0, 0, "the style's", "outlines: 1 on, -1 off"),
    D("outline-width", outline_width, FLOAT, 0, 0.1, 64, 0, 0, "the style's", "outline width in pixels"),
    D("outline-jump", outline_jump, FLOAT, PNPR_OUTLINE_JUMP, 0.01, 1e3, 0, 0, NULL,
      "a contour is a depth jump over this many extents"),
    D("outline-hole", outline_hole, FLOAT, PNPR_OUTLINE_HOLE, 0.01, 1e3, 0, 0, NULL,
      "holes closed within this many disk extents"),
    D("brush-preset", brush_preset, INT, 0, 0, PNPR_BRUSH_PRESET_COUNT - 1, ZERO_VALUE, 0, NULL,
      "brush: the brush, by its index in pnpr_brush_presets (brush.h)"),
    D("brush-scale", brush_scale, FLOAT, 1, 0.05, 20, 0, 0, NULL, "brush: splat half-size in r + eps units"),
    D("brush-blur", brush_blur, FLOAT, 0, 0, 8, ZERO_VALUE, 0, NULL,
      "brush: > 0: the fast blend while moving (alpha blending + Gaussian blur of this sigma, px)"),
    D("brush-jitter", brush_jitter, FLOAT, 15, 0, 90, NEG_OFF, 0, NULL,
      "brush: strokes turn by up to this many degrees per point"),
    D("queue-fade", queue_fade, FLOAT, PNPR_QUEUE_FADE, 0, 1, NEG_OFF, 0, NULL,
      "sketchy, stipple: the fraction of a budget that fades in"),
};

#define U(...) OPT("upload", pnpr_upload_options, __VA_ARGS__)
static const pnpr_option_desc upload_table[] = {
    U("spacing-k", spacing_k, UINT, 4, 1, PNPR_SPACING_K_MAX, 0, 0, NULL,
      "disk radius = distance to this nearest other point"),
    U("paint-bins", painterly_bins, UINT, 4, 1, PNPR_PAINTERLY_BINS_MAX, 0, 0, NULL,
      "painterly: feature-degree bins = passes"),
};

#define V(...) OPT("svg", pnpr_svg_options, __VA_ARGS__)
static const pnpr_option_desc svg_table[] = {
    V("stroke-width", stroke_width, FLOAT, 1.5, 1e-3, 1e3, 0, 0, NULL, "SVG stroke width in pixels"),
    V("taper", taper, FLOAT, 0, 0, 1, ZERO_VALUE, 0, NULL,
      "strokes narrow to a point over this fraction of their length"),
    V("point-radius", point_radius, FLOAT, 0, 0, UNB, EXCL, 0, "median spacing",
      "the occluders' disk radius (world units)"),
    V("depth-tolerance", depth_tolerance, FLOAT, 0, 0, UNB, EXCL, 3, " point radii",
      "a line is hidden behind a surface nearer by more than this (world units)"),
    V("outline-width", outline_width, FLOAT, PNPR_SVG_OUTLINE_WIDTH, 0.1, 64, 0, 0, NULL, "outline width in pixels"),
    V("outline-jump", outline_jump, FLOAT, PNPR_OUTLINE_JUMP, 0.01, 1e3, 0, 0, NULL,
      "a contour is a depth jump over this many extents"),
};

#define PR(...) OPT("camera preset", pnpr_camera_preset_options, __VA_ARGS__)
static const pnpr_option_desc preset_table[] = {
    PR("duration", duration, DOUBLE, 10, 1e-3, 1e6, 0, 0, NULL, "seconds of a preset (a path file has its own times)"),
    PR("degrees", degrees, DOUBLE, 360, -36000, 36000, 0, 0, NULL, "orbit: the angle turned (negative: clockwise from above)"),
};

const pnpr_option_desc *pnpr_camera_preset_option_table(size_t *r_count)
{
    if (r_count) *r_count = COUNT(preset_table);
    return preset_table;
}

const pnpr_option_desc *pnpr_svg_option_table(size_t *r_count)
{
    if (r_count) *r_count = COUNT(svg_table);
    return svg_table;
}

const pnpr_option_desc *pnpr_draw_option_table(size_t *r_count)
{
    if (r_count) *r_count = COUNT(draw_table);
    return draw_table;
}

const pnpr_option_desc *pnpr_upload_option_table(size_t *r_count)
{
    if (r_count) *r_count = COUNT(upload_table);
    return upload_table;
}

pnpr_draw_options pnpr_draw_defaults(void)
{
    pnpr_draw_options o = {0};
    pnpr_option_set_defaults(draw_table, COUNT(draw_table), &o);
    return o;
}

pnpr_upload_options pnpr_upload_defaults(void)
{
    pnpr_upload_options o = {0};
    pnpr_option_set_defaults(upload_table, COUNT(upload_table), &o);
    return o;
}

pnpr_status pnpr_draw_check(const pnpr_draw_options *o, pnpr_error *err)
{
    const char *other = o && o->style == PNPR_STYLE_CARTOON ? "mask-scale" : "outline-scale";
    for (size_t i = 0; o && i < COUNT(draw_table); i++) {
        if (!strcmp(draw_table[i].name, other)) continue; /* mask_scale: the entry of o's style */
        pnpr_status st = pnpr_option_check(&draw_table[i], 1, o, err);
        if (st != PNPR_OK) return st;
    }
    return PNPR_OK;
}

static double draw_default(const char *name)
{
    return pnpr_option_find(draw_table, COUNT(draw_table), name)->def;
}

float pnpr_draw_mask_scale(const pnpr_draw_options *o, pnpr_style style)
{
    if (o && o->mask_scale > 0) return o->mask_scale;
    return (float)draw_default(style == PNPR_STYLE_CARTOON ? "outline-scale" : "mask-scale");
}

int pnpr_draw_ink(const pnpr_draw_options *o, float r_ink[4])
{
    static const char *const names[4] = {"ink-r", "ink-g", "ink-b", "ink-a"};
    int given = o && (o->ink[0] != 0 || o->ink[1] != 0 || o->ink[2] != 0 || o->ink[3] != 0);
    for (int c = 0; c < 4; c++) r_ink[c] = given ? o->ink[c] : (float)draw_default(names[c]);
    return given;
}
