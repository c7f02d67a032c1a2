/* Writers for profile lines: OBJ polylines (`l` statements) and PLY with an `edge` element.
 * World coordinates = origin + offset in double, printed with %.17g (exact round trip). */
#include <pointnpr/polylines.h>

#include "../core/internal.h"
#include <pointnpr/output.h>

#include <stdio.h>
#include <string.h>

static int valid_lines(const pnpr_polylines *l)
{
    return l && (l->count == 0 || (l->offset && l->xyz && l->closed));
}

static size_t vertex_total(const pnpr_polylines *l)
{
    return l->count && l->offset ? l->offset[l->count] : 0;
}

static int print_obj(FILE *f, const void *ctx)
{
    const pnpr_polylines *l = ctx;
    int bad = fprintf(f, "# profile lines by pointnpr %s: %zu polylines\n", PNPR_VERSION_STRING, l->count) < 0;
    size_t nv = vertex_total(l);
    for (size_t i = 0; i < nv && !bad; i++)
        bad = fprintf(f, "v %.17g %.17g %.17g\n", l->origin[0] + (double)l->xyz[3 * i],
                      l->origin[1] + (double)l->xyz[3 * i + 1], l->origin[2] + (double)l->xyz[3 * i + 2]) < 0;
    for (size_t p = 0; p < l->count && !bad; p++) {
        bad = fputc('l', f) == EOF;
        for (size_t v = l->offset[p]; v < l->offset[p + 1] && !bad; v++) bad = fprintf(f, " %zu", v + 1) < 0;
        if (l->closed[p] && l->offset[p + 1] > l->offset[p]) bad |= fprintf(f, " %zu", l->offset[p] + 1) < 0;
        bad |= fputc('\n', f) == EOF;
    }
    return bad;
}

pnpr_status pnpr_write_lines_obj(const char *path, const pnpr_polylines *l, pnpr_error *err)
{
    if (!valid_lines(l)) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "invalid polylines");
    return pnpr_output_write(path, print_obj, l, err);
}

static int print_ply(FILE *f, const void *ctx)
{
    const pnpr_polylines *l = ctx;
    size_t nv = vertex_total(l), ne = 0;
    for (size_t p = 0; p < l->count; p++) {
        size_t c = l->offset[p + 1] - l->offset[p];
        ne += c > 1 ? c - 1 + (l->closed[p] && c > 2) : 0;
    }
    int bad = fprintf(f,
                      "ply\nformat ascii 1.0\ncomment profile lines by pointnpr %s\n"
                      "element vertex %zu\nproperty double x\nproperty double y\nproperty double z\n"
                      "element edge %zu\nproperty int vertex1\nproperty int vertex2\nend_header\n",
                      PNPR_VERSION_STRING, nv, ne) < 0;
    for (size_t i = 0; i < nv && !bad; i++)
        bad = fprintf(f, "%.17g %.17g %.17g\n", l->origin[0] + (double)l->xyz[3 * i],
                      l->origin[1] + (double)l->xyz[3 * i + 1], l->origin[2] + (double)l->xyz[3 * i + 2]) < 0;
    for (size_t p = 0; p < l->count && !bad; p++) {
        size_t a = l->offset[p], b = l->offset[p + 1];
        for (size_t v = a + 1; v < b && !bad; v++) bad = fprintf(f, "%zu %zu\n", v - 1, v) < 0;
        if (l->closed[p] && b - a > 2 && !bad) bad = fprintf(f, "%zu %zu\n", b - 1, a) < 0;
    }
    return bad;
}

pnpr_status pnpr_write_lines_ply(const char *path, const pnpr_polylines *l, pnpr_error *err)
{
    if (!valid_lines(l)) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "invalid polylines");
    return pnpr_output_write(path, print_ply, l, err);
}
