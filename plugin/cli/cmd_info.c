/* pointnpr info IN: what a point cloud file holds (format, count, origin, world bounding box,
 * optional arrays, extra properties, faces). */
#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage: pointnpr info IN\n"
            "  Describes a point cloud file (PLY, LAS, OBJ, OFF, PCD): format, point count, origin,\n"
            "  bounding box in world coordinates, colour/normals/labels, exact source\n"
            "  coordinates, extra properties with their types, face count, scanner viewpoint.\n");
}

static const char *format_name(pnpr_file_format f)
{
    switch (f) {
    case PNPR_FORMAT_PLY: return "PLY";
    case PNPR_FORMAT_LAS: return "LAS";
    case PNPR_FORMAT_OBJ: return "OBJ";
    case PNPR_FORMAT_OFF: return "OFF";
    case PNPR_FORMAT_PCD: return "PCD";
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

static const char *type_name(pnpr_type t)
{
    const char *s = pnpr_type_ply_name(t);
    return s[0] ? s : "unknown";
}

int cli_info(int argc, char **argv)
{
    const char *in = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { usage(stdout); return 0; }
        if (a[0] == '-' && a[1]) {
            fprintf(stderr, "pointnpr info: unknown option: %s\n", a);
            usage(stderr);
            return 2;
        }
        if (in) {
            fprintf(stderr, "pointnpr info: more than one input given ('%s')\n", a);
            usage(stderr);
            return 2;
        }
        in = a;
    }
    if (!in) { usage(stderr); return 2; }

    pnpr_cloud c = {0};
    pnpr_error err = {0};
    pnpr_status st = pnpr_read_file(in, NULL, &c, &err);
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
    if (finite) {
        printf("bbox min:    %.3f %.3f %.3f\n", lo[0], lo[1], lo[2]);
        printf("bbox max:    %.3f %.3f %.3f\n", hi[0], hi[1], hi[2]);
        printf("extent:      %.3f %.3f %.3f\n", hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
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
    pnpr_cloud_free(&c);
    return 0;
}
