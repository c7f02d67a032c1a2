/* pointnpr info IN: what a point cloud file holds (format, count, origin, world bounding box,
 * optional arrays, extra properties, faces). */
#include "cli.h"
#include "cli_opts.h"

#include <pointnpr/lod.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

/* --outlier-factor: the entry of the library's table (options.h). */
static const pnpr_option_desc *outlier_factor(void)
{
    size_t n;
    const pnpr_option_desc *table = pnpr_outlier_option_table(&n);
    return pnpr_option_find(table, n, "outlier-factor");
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: pointnpr info IN [--outlier-factor F] [--columns NAMES]\n"
            "  Describes a point cloud file (PLY, LAS, OBJ, OFF, PCD, XYZ, PTS, PWN, CSV/TXT): format,\n"
            "  point count, origin,\n"
            "  far outliers, bounding box in world coordinates, colour/normals/labels, exact source\n"
            "  coordinates, extra properties with their types, face count, scanner viewpoint.\n"
            "  Far outliers: points farther than F robust extents (the %g%% quantile of the distances\n"
            "  from the per-axis median) from the median, or beyond float range:\n",
            100 * PNPR_OUTLIER_QUANTILE);
    cli_option_usage(f, outlier_factor(), "F");
    cli_columns_usage(f);
}

static const char *format_name(pnpr_file_format f)
{
    switch (f) {
    case PNPR_FORMAT_PLY: return "PLY";
    case PNPR_FORMAT_LAS: return "LAS";
    case PNPR_FORMAT_OBJ: return "OBJ";
    case PNPR_FORMAT_OFF: return "OFF";
    case PNPR_FORMAT_PCD: return "PCD";
    case PNPR_FORMAT_XYZ: return "XYZ";
    case PNPR_FORMAT_PTS: return "PTS";
    case PNPR_FORMAT_PWN: return "PWN";
    case PNPR_FORMAT_CSV: return "CSV/TXT";
    default: return "unknown";
    }
}

/* The format pnpr_read_file used for a file it read: the extension, else the first bytes
 * (PLY, LAS and PCD by their signature; OFF is the only other format recognised by content). */
static pnpr_file_format detect_format(const char *path, const char **r_how)
{
    pnpr_file_format f = pnpr_format_from_path(path);
    *r_how = "from the extension";
    if (f != PNPR_FORMAT_AUTO) return f;
    *r_how = "from the content";
    unsigned char b[16] = {0};
    size_t n = 0;
    FILE *fp = fopen(path, "rb");
    if (fp) {
        n = fread(b, 1, sizeof b, fp);
        fclose(fp);
    }
    if ((n >= 4 && !memcmp(b, "ply\n", 4)) || (n >= 5 && !memcmp(b, "ply\r\n", 5))) return PNPR_FORMAT_PLY;
    if (n >= 4 && !memcmp(b, "LASF", 4)) return PNPR_FORMAT_LAS;
    if ((n >= 6 && !memcmp(b, "# .PCD", 6)) || (n >= 8 && !memcmp(b, "VERSION", 7) && (b[7] == ' ' || b[7] == '\t')))
        return PNPR_FORMAT_PCD;
    return PNPR_FORMAT_OFF;
}

/* ---- far outliers: the options and report shared with features, segment, render, lines ---- */

int cli_outlier_option(cli_outliers *o, const char *cmd, int argc, char **argv, int *i)
{
    const char *a = argv[*i];
    if (!strcmp(a, "--drop-outliers")) { o->drop = 1; return 1; }
    if (strcmp(a, "--outlier-factor") || *i + 1 >= argc) return 0;
    return cli_option_value(outlier_factor(), cmd, argv[++*i], &o->factor) ? 1 : -1;
}

void cli_outlier_usage(FILE *f)
{
    fprintf(f,
            "  --drop-outliers      remove far outliers after reading (an output cloud lacks them):\n"
            "                       points farther than F robust extents (the %g%% quantile of the\n"
            "                       distances from the per-axis median) from the median, or beyond\n"
            "                       float range\n",
            100 * PNPR_OUTLIER_QUANTILE);
    cli_option_usage(f, outlier_factor(), "F");
}

/* A coordinate: 3 decimals, or %.6g where that would print hundreds of digits (1e308). */
static void print_coord(FILE *f, const char *before, double v)
{
    fprintf(f, fabs(v) < 1e15 ? "%s%.3f" : "%s%.6g", before, v);
}

/* "N far outlier(s) (farther than L from the robust centre X Y Z; B beyond float range)" */
static void print_outliers(FILE *f, const pnpr_outlier_info *oi)
{
    fprintf(f, "%zu far outlier(s) (farther than %.6g from the robust centre", oi->far, oi->limit);
    for (int a = 0; a < 3; a++) print_coord(f, " ", oi->centre[a]);
    fprintf(f, "; %zu beyond float range)", oi->beyond_float);
}

int cli_outliers_apply(const cli_outliers *o, const char *cmd, const char *in, pnpr_cloud *cloud, int quiet,
                       pnpr_outlier_info *r_info)
{
    pnpr_outlier_info local;
    pnpr_outlier_info *oi = r_info ? r_info : &local;
    pnpr_outlier_options opts = {o->factor};
    pnpr_status st = o->drop ? pnpr_cloud_drop_outliers(cloud, &opts, oi) : pnpr_cloud_outliers(cloud, &opts, NULL, oi);
    if (st != PNPR_OK) {
        fprintf(stderr, "pointnpr %s: %s: far outliers: %s\n", cmd, in, pnpr_status_string(st));
        return 1;
    }
    if (!quiet && oi->far > 0) {
        fprintf(stderr, "%s: ", in);
        print_outliers(stderr, oi);
        fprintf(stderr, o->drop ? ": dropped\n"
                                : ": kept (those beyond float range are left out of the analysis); "
                                  "--drop-outliers removes them\n");
    }
    return 0;
}

static const char *type_name(pnpr_type t)
{
    const char *s = pnpr_type_ply_name(t);
    return s[0] ? s : "unknown";
}

/* A file ordered for drawing (lod.h): its grid and how full its cells are; or why its order
 * cannot be used. */
static void print_lod(const char *in)
{
    pnpr_lod l;
    pnpr_error err = {0};
    pnpr_status st = pnpr_lod_open(in, &l, &err);
    if (st == PNPR_ERR_UNSUPPORTED && !strstr(err.message, "version")) return;
    if (st != PNPR_OK) {
        printf("drawing:     its order for drawing cannot be used: %s\n", err.message);
        return;
    }
    uint32_t used = 0, most = 0;
    for (uint32_t k = 0; k < l.cells; k++) {
        uint32_t n = pnpr_lod_cell_points(&l, k);
        used += n > 0;
        most = n > most ? n : most;
    }
    uint32_t outside = pnpr_lod_cell_points(&l, l.cells);
    printf("drawing:     ordered for drawing: %u x %u x %u cells of %.6g (%u holding points, at most %u), %u points "
           "outside them (far or not finite)\n", l.n[0], l.n[1], l.n[2], l.side, used, most, outside);
    pnpr_lod_free(&l);
}

int cli_info(int argc, char **argv)
{
    const char *in = NULL;
    cli_outliers outliers = {0, 0};
    pnpr_read_options ro = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { usage(stdout); return 0; }
        int oo = strcmp(a, "--drop-outliers") ? cli_outlier_option(&outliers, "info", argc, argv, &i) : 0;
        if (oo == 0) oo = cli_columns_option(&ro.columns, "info", argc, argv, &i);
        if (oo < 0) return 2;
        if (oo > 0) continue;
        if (cli_operand("info", a, &in, usage)) return 2;
    }
    if (!in) { fprintf(stderr, "pointnpr info: no input given\n"); usage(stderr); return 2; }

    pnpr_cloud c = {0};
    pnpr_error err = {0};
    pnpr_status st = pnpr_read_file(in, &ro, &c, &err);
    if (st != PNPR_OK) { cli_report_error("info", st, &err); return 1; }

    const char *how;
    pnpr_file_format fmt = detect_format(in, &how);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    size_t finite = 0;
    for (size_t i = 0; i < c.count; i++) {
        double w[3];
        pnpr_cloud_world(&c, i, w);
        if (!isfinite(w[0]) || !isfinite(w[1]) || !isfinite(w[2])) continue;
        finite++;
        for (int a = 0; a < 3; a++) {
            if (w[a] < lo[a]) lo[a] = w[a];
            if (w[a] > hi[a]) hi[a] = w[a];
        }
    }

    printf("file:        %s\n", in);
    printf("format:      %s (%s)\n", format_name(fmt), how);
    printf("points:      %zu\n", c.count);
    if (finite != c.count)
        printf("finite:      %zu (%zu points with NaN/Inf coordinates)\n", finite, c.count - finite);
    printf("origin:      %.3f %.3f %.3f\n", c.origin[0], c.origin[1], c.origin[2]);
    pnpr_outlier_info oi;
    pnpr_outlier_options oo = {outliers.factor};
    if (pnpr_cloud_outliers(&c, &oo, NULL, &oi) == PNPR_OK) {
        printf("outliers:    ");
        print_outliers(stdout, &oi);
        printf("\n");
    }
    if (finite) {
        const char *labels[3] = {"bbox min:   ", "bbox max:   ", "extent:     "};
        for (int row = 0; row < 3; row++) {
            printf("%s", labels[row]);
            for (int a = 0; a < 3; a++) print_coord(stdout, " ", row == 0 ? lo[a] : row == 1 ? hi[a] : hi[a] - lo[a]);
            printf("\n");
        }
    } else {
        printf("bbox:        none (no point with finite coordinates)\n");
    }
    printf("colour:      %s\n", c.rgb ? "yes (8-bit RGB)" : "no");
    printf("normals:     %s\n", c.normal ? "yes" : "no");
    printf("labels:      %s\n", c.label ? "yes" : "no");
    if (c.src_xyz)
        printf("source xyz:  exact, kept as %s\n", type_name(c.src_coord_type == PNPR_TYPE_NONE ? PNPR_TYPE_FLOAT64
                                                                                              : c.src_coord_type));
    else
        printf("source xyz:  not kept (float offsets reproduce the source; source type %s)\n",
               c.src_coord_type == PNPR_TYPE_NONE ? "unknown" : type_name(c.src_coord_type));
    if (c.prop_count == 0) {
        printf("properties:  none\n");
    } else {
        printf("properties:  ");
        for (size_t k = 0; k < c.prop_count; k++)
            printf("%s%s (%s)", k ? ", " : "", c.props[k].name, type_name(c.props[k].type));
        printf("\n");
    }
    printf("faces:       %zu\n", c.faces.count);
    if (c.has_viewpoint)
        printf("viewpoint:   %.3f %.3f %.3f\n", c.viewpoint[0], c.viewpoint[1], c.viewpoint[2]);
    print_lod(in);
    pnpr_cloud_free(&c);
    return 0;
}
