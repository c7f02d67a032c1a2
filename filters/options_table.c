/* The defaults and ranges of the filters' options structs (options.h): the one place they are
 * written. The library fills zeros from here, the CLI's usage text and parser and the MeshLab
 * dialogs read these entries; tests/test_options_table.c and tests/cli_options.sh hold them to it. */
#include "../core/options_internal.h"

#define F(...) OPT("features", pnpr_features_options, __VA_ARGS__)
static const pnpr_option_desc features_table[] = {
    F("k", k, UINT, 16, 1, PNPR_FEATURES_K_MAX, 0, 0, NULL, "neighbourhood size"),
    F("threshold", threshold, FLOAT, 0, 0, 1, EXCL, 0, "automatic", "feature-degree threshold"),
    F("weight-geometry", weight_geometry, FLOAT, 0.5, 0, 1e6, ZERO_VALUE, 0, NULL,
      "weight of the geometry term (normalised with the colour weight; both 0 = the defaults)"),
    F("weight-color", weight_color, FLOAT, 0.5, 0, 1e6, ZERO_VALUE, 0, NULL,
      "weight of the colour term (colourless clouds use geometry only)"),
    F("confidence", direction_confidence, FLOAT, 0.6, 0, 1, EXCL, 0, NULL,
      "min line-fit confidence of directional points"),
    F("dither-scale", dither_scale, FLOAT, 1, 0, 1e6, EXCL, 0, NULL, "tone multiplier for the dithering density"),
};

#define L(...) OPT("lines", pnpr_lines_options, __VA_ARGS__)
static const pnpr_option_desc lines_table[] = {
    L("spacing", spacing, FLOAT, 0, 0, UNB, EXCL, 0, "estimated", "the spacing h in world units"),
    L("radius", connect_radius, FLOAT, 0, 0, UNB, EXCL, 3, "h", "graph neighbourhood radius"),
    L("merge-tol", merge_tol, FLOAT, 0, 0, UNB, EXCL, 1, "h", "merge points closer than this"),
    L("shift-iterations", shift_iterations, INT, 4, 1, PNPR_LINES_SHIFT_MAX, NEG_OFF, 0, NULL,
      "noise-reducing shifts across the feature"),
    L("direction-weight", direction_weight, FLOAT, 4, 0, UNB, EXCL, 0, NULL,
      "how much edges across the feature direction cost"),
    L("min-length", min_length, FLOAT, 0, 0, UNB, EXCL, 5, "h", "drop spurs and isolated lines shorter than this"),
    L("sample-tol", sample_tol, FLOAT, 0, 0, UNB, EXCL, 0.05, "h", "max chord deviation of the output polylines"),
};

#define J(...) OPT("jseg", pnpr_jseg_options, __VA_ARGS__)
static const pnpr_option_desc jseg_table[] = {
    J("classes", classes, UINT, 16, 1, PNPR_JSEG_CLASSES_MAX, 0, 0, NULL, "colour classes of the quantiser"),
    J("quant-distance", quant_distance, FLOAT, 12, 0, UNB, EXCL | NEG_OFF, 0, NULL,
      "class centres closer than this (CIE76 delta E) become one class"),
    J("k", k, UINT, 24, 2, PNPR_SEGMENT_K_MAX, 0, 0, NULL, "J neighbourhood size"),
    J("radius", radius, FLOAT, 0, 0, UNB, EXCL, 0, "none", "J neighbourhood radius"),
    J("seed-factor", seed_factor, FLOAT, 0.6, 0, UNB, EXCL, 0, NULL, "seed points: J <= this x mean J"),
    J("grow-bound", grow_bound, FLOAT, 0, 0, UNB, EXCL, 0, "none", "growth stops at J >= this x mean J"),
    J("seed-min-size", seed_min_size, UINT, 0, 1, UNB, 0, 1, "k", "seed regions smaller than this are dropped"),
    J("merge-distance", merge_distance, FLOAT, 10, 0, UNB, EXCL | NEG_OFF, 0, NULL,
      "adjacent regions closer in mean colour (CIE76 delta E) merge"),
    J("min-size", min_size, UINT, 0, 1, UNB, 0, 0, "max(k, points / 1000)", "smaller segments merge into a neighbour"),
};

#define R(...) OPT("rgbgrow", pnpr_rgbgrow_options, __VA_ARGS__)
static const pnpr_option_desc rgbgrow_table[] = {
    R("k", k, UINT, 16, 2, PNPR_SEGMENT_K_MAX, 0, 0, NULL, "neighbours considered per point"),
    R("radius", distance, FLOAT, 0, 0, UNB, EXCL, 3, " x median spacing", "neighbour distance"),
    R("point-distance", point_distance, FLOAT, 25, 0, UNB, EXCL, 0, NULL,
      "a neighbour joins when its RGB colour differs by less (0..255 units)"),
    R("region-distance", region_distance, FLOAT, 10, 0, UNB, EXCL | NEG_OFF, 0, NULL,
      "adjacent regions closer in mean colour (CIE76 delta E) merge"),
    R("min-size", min_size, UINT, 10, 1, UNB, 0, 0, NULL, "smaller segments merge into a neighbour"),
};

#define C(...) OPT("components", pnpr_components_options, __VA_ARGS__)
static const pnpr_option_desc components_table[] = {
    C("radius", distance, FLOAT, 0, 0, UNB, EXCL, 3, " x median spacing", "neighbour distance"),
    C("min-size", min_size, UINT, 1, 1, UNB, 0, 0, NULL, "smaller components join the nearest kept one"),
};

#define P(...) OPT("split", pnpr_split_options, __VA_ARGS__)
static const pnpr_option_desc split_table[] = {
    P("split", max_variation, FLOAT, 0.02, 0, 0.34, EXCL, 0, NULL, /* the variation is at most 1/3 */
      "split segments whose surface variation exceeds this"),
    P("split-min", min_size, UINT, 32, 1, UNB, 0, 0, NULL, "smallest part a split may leave"),
};

#define TN(...) OPT("tone", pnpr_tone_options, __VA_ARGS__)
static const pnpr_option_desc tone_table[] = {
    TN("tone-ambient", ambient, FLOAT, 0.3, 0, 1, EXCL, 0, NULL, "key light: the shade of a surface facing away"),
    TN("tone-colour-weight", colour_weight, FLOAT, 0.45, 0, 1, EXCL, 0, NULL,
       "tone both: the colour's share (the light's: the rest)"),
    TN("tone-contrast", contrast, FLOAT, 1, 0.01, 100, 0, 0, NULL, "tone curve: contrast around mid grey"),
    TN("tone-gamma", gamma, FLOAT, 2.8, 0.05, 100, 0, 0, NULL, "tone curve: darkness^G, > 1 keeps mid tones light"),
};

#define H(...) OPT("hierarchy", pnpr_hierarchy_options, __VA_ARGS__)
static const pnpr_option_desc hierarchy_table[] = {
    H("alpha", alpha, FLOAT, 0.3, 0, UNB, EXCL, 0, NULL, "size rule: small = size < alpha x mean initial size"),
    H("epsilon", epsilon, FLOAT, 0.05, 0, UNB, EXCL, 0, NULL, "merge cost factor of pairs not both small"),
};

#define O(...) OPT("outliers", pnpr_outlier_options, __VA_ARGS__)
static const pnpr_option_desc outlier_table[] = {
    O("outlier-factor", factor, DOUBLE, PNPR_OUTLIER_FACTOR, PNPR_OUTLIER_FACTOR_MIN, PNPR_OUTLIER_FACTOR_MAX, 0, 0,
      NULL, "far outliers: farther than this many robust extents"),
};

#define B(...) OPT("brush", pnpr_brush_options, __VA_ARGS__)
static const pnpr_option_desc brush_table[] = {
    B("brush-k", k, UINT, 8, 1, PNPR_BRUSH_K_MAX, 0, 0, NULL, "brush: splat size from the mean distance to this many neighbours"),
    B("brush-eps", eps, FLOAT, 0, 0, UNB, EXCL, 0, "their std", "brush: the size's error term eps (units)"),
    B("brush-normal-radius", normal_radius, FLOAT, 3, 0.5, 16, 0, 0, NULL,
      "brush: normals fitted within the cluster over this many sizes"),
};

#define T(...) OPT("sphere tree", pnpr_sphere_tree_options, __VA_ARGS__)
static const pnpr_option_desc sphere_tree_table[] = {
    T("hier-spacing", spacing, FLOAT, 0, 0, UNB, EXCL, 0, "leaf factor x median spacing",
      "hierarchy: leaf sphere spacing (units)"),
    T("hier-leaf-factor", leaf_factor, FLOAT, 1.5, 0.5, 64, 0, 0, NULL,
      "hierarchy: leaf spacing in median point spacings"),
    T("hier-k", k, UINT, 12, 4, PNPR_SPHERE_K_MAX, 0, 0, NULL, "hierarchy: neighbouring leaves for normals and directions"),
    T("hier-features", feature_fraction, FLOAT, 0.1, 0, 1, EXCL, 0, NULL,
      "hierarchy: fraction of leaves (highest curvature) whose direction is kept"),
    T("hier-max-variation", max_variation, FLOAT, 0, 0, 0.34, EXCL, 0, "the split's",
      "hierarchy: colourless clouds: surface variation bound of the geometric regions"),
};

#define S(...) OPT("hierarchy style", pnpr_hier_params, __VA_ARGS__)
static const pnpr_option_desc hier_table[] = {
    S("hier-abstraction", abstraction, FLOAT, 0.01, 0, 1, NEG_OFF, 0, NULL,
      "hierarchy: region nodes of dissimilarity below this fraction of the root's (negative: none)"),
    S("stroke-px", stroke_px, FLOAT, 8, 1, 512, 0, 0, NULL, "hierarchy: stroke diameter on screen, pixels"),
    S("stroke-radius", stroke_radius, FLOAT, 0, 0, UNB, EXCL, 0, "view-dependent",
      "hierarchy: view-independent strokes of this radius (units)"),
    S("stroke-scale", stroke_scale, FLOAT, 1.0, 0.1, 8, 0, 0, NULL, "hierarchy: stroke half-width in node radii"),
    S("stroke-stretch", stretch, FLOAT, 2.2, 1, 8, 0, 0, NULL, "hierarchy: stroke length over width"),
    S("no-smooth", no_smooth, INT, 0, 0, 1, ZERO_VALUE, 0, NULL, "hierarchy: plain level switching"),
    S("node-colour", node_colour, INT, 0, 0, 1, ZERO_VALUE, 0, NULL, "hierarchy: strokes in node, not region, colour"),
    S("node-direction", node_direction, INT, 0, 0, 1, ZERO_VALUE, 0, NULL,
      "hierarchy: strokes along node, not region, direction"),
    S("noise-angle", noise_angle, FLOAT, 12, 0, 90, NEG_OFF, 0, NULL, "hierarchy: Perlin noise on directions, degrees"),
    S("noise-colour", noise_colour, FLOAT, 0.1, 0, 1, NEG_OFF, 0, NULL, "hierarchy: Perlin noise on brightness"),
    S("silhouette-deg", silhouette_deg, FLOAT, 8, 0, 60, NEG_OFF, 0, NULL,
      "hierarchy: silhouette band ThresholdDegree (negative: none)"),
    S("borders", border_level, FLOAT, 0, 0, UNB, ZERO_VALUE, 0, NULL, "hierarchy: region borders at this merge level (0: none)"),
    S("tam", tam, INT, 0, 0, PNPR_TAM_COUNT_ - 1, ZERO_VALUE, 0, NULL, "hierarchy: tonal art map"),
    S("hier-layers", layers, INT, 1, 1, 2, 0, 0, NULL, "hierarchy: 2 = a fine layer over the first"),
};

#define TABLE_FUNCTIONS(X, table)                                                                                     \
    const pnpr_option_desc *pnpr_##X##_option_table(size_t *r_count)                                                 \
    {                                                                                                                  \
        if (r_count) *r_count = COUNT(table);                                                                          \
        return table;                                                                                                  \
    }

TABLE_FUNCTIONS(features, features_table)
TABLE_FUNCTIONS(lines, lines_table)
TABLE_FUNCTIONS(jseg, jseg_table)
TABLE_FUNCTIONS(rgbgrow, rgbgrow_table)
TABLE_FUNCTIONS(components, components_table)
TABLE_FUNCTIONS(hierarchy, hierarchy_table)
TABLE_FUNCTIONS(split, split_table)
TABLE_FUNCTIONS(tone, tone_table)
TABLE_FUNCTIONS(outlier, outlier_table)
TABLE_FUNCTIONS(brush, brush_table)
TABLE_FUNCTIONS(sphere_tree, sphere_tree_table)
TABLE_FUNCTIONS(hier, hier_table)

#define DEFAULTS_FUNCTION(X, S, table)                                                                                \
    S pnpr_##X##_defaults(void)                                                                                        \
    {                                                                                                                  \
        S o = {0};                                                                                                     \
        pnpr_option_set_defaults(table, COUNT(table), &o);                                                             \
        return o;                                                                                                      \
    }

DEFAULTS_FUNCTION(features, pnpr_features_options, features_table)
DEFAULTS_FUNCTION(lines, pnpr_lines_options, lines_table)
DEFAULTS_FUNCTION(jseg, pnpr_jseg_options, jseg_table)
DEFAULTS_FUNCTION(rgbgrow, pnpr_rgbgrow_options, rgbgrow_table)
DEFAULTS_FUNCTION(components, pnpr_components_options, components_table)
DEFAULTS_FUNCTION(hierarchy, pnpr_hierarchy_options, hierarchy_table)
DEFAULTS_FUNCTION(split, pnpr_split_options, split_table)
DEFAULTS_FUNCTION(tone, pnpr_tone_options, tone_table)
DEFAULTS_FUNCTION(outlier, pnpr_outlier_options, outlier_table)
DEFAULTS_FUNCTION(brush, pnpr_brush_options, brush_table)
DEFAULTS_FUNCTION(sphere_tree, pnpr_sphere_tree_options, sphere_tree_table)
DEFAULTS_FUNCTION(hier, pnpr_hier_params, hier_table)
