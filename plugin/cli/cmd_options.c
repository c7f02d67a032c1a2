/* pointnpr options [--markdown]: every options table of the library (options.h), as the commands
 * read them: name, member, default, range and help. docs/options.md is this command's Markdown
 * output (tests/cli_options_doc.sh holds it to it), so the documentation states each default and
 * range by reading the one table that the library, the CLI and the MeshLab dialogs use. */
#include "cli.h"

#include <string.h>

typedef const pnpr_option_desc *(*table_fn)(size_t *r_count);

static const struct {
    const char *title, *type, *where;
    table_fn table;
} tables[] = {
    {"features", "pnpr_features_options", "`features`, `lines` (when it computes features), MeshLab's feature filter",
     pnpr_features_option_table},
    {"outliers", "pnpr_outlier_options", "`info`, `features`, `lines`, `segment`, `render`, `animate` (with `--drop-outliers`)",
     pnpr_outlier_option_table},
    {"lines", "pnpr_lines_options", "`lines`, MeshLab's profile-lines filter", pnpr_lines_option_table},
    {"jseg", "pnpr_jseg_options", "`segment --method jseg`, MeshLab's segmentation filter", pnpr_jseg_option_table},
    {"rgbgrow", "pnpr_rgbgrow_options", "`segment --method rgbgrow`, MeshLab's segmentation filter",
     pnpr_rgbgrow_option_table},
    {"components", "pnpr_components_options", "`segment --method components`, MeshLab's segmentation filter",
     pnpr_components_option_table},
    {"region hierarchy", "pnpr_hierarchy_options", "`segment --segments/--threshold` and MeshLab's segmentation filter (the merge order; no option sets them)",
     pnpr_hierarchy_option_table},
    {"covariance split", "pnpr_split_options", "`segment --split`, the sphere tree of colourless clouds",
     pnpr_split_option_table},
    {"tone", "pnpr_tone_options", "`render`, `animate` (`--tone-gamma`, `--tone-contrast`), the dithering of `features`, the MeshLab decorator",
     pnpr_tone_option_table},
    {"brush preparation", "pnpr_brush_options", "`render --style brush`, the MeshLab decorator",
     pnpr_brush_option_table},
    {"sphere tree", "pnpr_sphere_tree_options", "`render --style hierarchy`, the MeshLab decorator",
     pnpr_sphere_tree_option_table},
    {"hierarchy style", "pnpr_hier_params", "`render --style hierarchy`, the MeshLab decorator", pnpr_hier_option_table},
    {"draw", "pnpr_draw_options", "`render`, `animate`, the MeshLab decorator (per frame)", pnpr_draw_option_table},
    {"upload", "pnpr_upload_options", "`render`, `animate`, the MeshLab decorator (per cloud)", pnpr_upload_option_table},
    {"svg", "pnpr_svg_options", "`lines --svg`", pnpr_svg_option_table},
    {"camera preset", "pnpr_camera_preset_options", "`animate --orbit/--flyover`", pnpr_camera_preset_option_table},
};

static void print_table(FILE *f, int markdown, size_t t)
{
    size_t n = 0;
    const pnpr_option_desc *d = tables[t].table(&n);
    if (markdown)
        fprintf(f, "\n## %s\n\n`%s`; read by %s.\n\n| option | member | default | range | meaning |\n|---|---|---|---|---|\n",
                tables[t].title, tables[t].type, tables[t].where);
    else
        fprintf(f, "%s (%s)\n", tables[t].title, tables[t].type);
    for (size_t i = 0; i < n; i++) {
        char def[64], range[64];
        pnpr_option_default_text(&d[i], def, sizeof def);
        pnpr_option_range_text(&d[i], range, sizeof range);
        const char *off = (d[i].flags & PNPR_OPTION_NEGATIVE_OFF) ? "; negative: off" : "";
        if (markdown)
            fprintf(f, "| `--%s` | `%s` | %s | %s%s | %s |\n", d[i].name, d[i].field, def, range, off, d[i].help);
        else
            fprintf(f, "  --%-22s default %s, %s%s: %s\n", d[i].name, def, range, off, d[i].help);
    }
}

int cli_options(int argc, char **argv)
{
    int markdown = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--markdown")) markdown = 1;
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: pointnpr options [--markdown]\n"
                   "  every options table of the library: option, default, range, meaning\n");
            return 0;
        } else {
            fprintf(stderr, "pointnpr options: unknown argument '%s' (only --markdown)\n", argv[i]);
            return 2;
        }
    }
    for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++) print_table(stdout, markdown, t);
    return 0;
}
