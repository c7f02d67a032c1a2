/* pointnpr — polylines.h: the polyline type of the profile lines (lines.h), on its own so that
 * code that only stores, draws or writes polylines (io/, view/, the renderer) needs no more of
 * the lines API. lines.h includes it. */
#ifndef POINTNPR_POLYLINES_H
#define POINTNPR_POLYLINES_H

#include "core.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Polylines as float offsets from a double origin (like pnpr_cloud). Polyline i has vertices
 * offset[i] .. offset[i+1]-1; closed[i] != 0 when its last vertex connects back to its first
 * (the first vertex is not repeated). Allocated by the library: release with pnpr_lines_free. */
typedef struct pnpr_polylines {
    size_t count;
    size_t *offset;   /* count + 1 */
    float *xyz;       /* 3 * offset[count] */
    uint8_t *closed;  /* count */
    double origin[3];
} pnpr_polylines;

void pnpr_lines_free(pnpr_polylines *lines); /* leaves it zeroed; NULL ok */

/* Writers (world coordinates, %.17g-exact): OBJ with one `l` statement per polyline (closed
 * ones repeat their first vertex index), PLY with a vertex and an `edge` element. Written to
 * path + ".tmp" and renamed. */
PNPR_NODISCARD pnpr_status pnpr_write_lines_obj(const char *path, const pnpr_polylines *lines, pnpr_error *err);
PNPR_NODISCARD pnpr_status pnpr_write_lines_ply(const char *path, const pnpr_polylines *lines, pnpr_error *err);

#ifdef __cplusplus
}
#endif
#endif
