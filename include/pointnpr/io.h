/* pointnpr — io.h: reading and writing point clouds.
 *
 * PLY  (io/ply.c): ascii, binary_little_endian, binary_big_endian; any property order and
 *      scalar type; float or double coordinates (int/uint coordinates are kept exactly, as
 *      FLOAT64); vertex element required, face element kept,
 *      other elements skipped. Recognised vertex properties: x y z, nx ny nz,
 *      red green blue (uchar or ushort; also r g b / diffuse_red ...), label/segment (kept as
 *      labels); every other vertex property is kept as an extra property.
 * LAS  (io/las.c): versions 1.0-1.4, uncompressed, point formats 0-3 and 6-8; world =
 *      X*scale + offset; 16-bit RGB reduced to 8 bit (values that never exceed 255 are taken
 *      as 8-bit); intensity and classification kept as extra properties.
 * OFF  (io/off.c): ascii OFF as Geomview specifies it ('#' comments anywhere, [ST][C][N]OFF,
 *      colours as floats or bytes, polygonal faces); binary OFF and OBJ through OpenMesh
 *      (io/mesh_openmesh.cpp, behind the validating pre-pass io/mesh_check.c).
 * XYZ / PTS / PWN / CSV / TXT (io/text_points.c): text point clouds, one point a line, values
 *      separated by blanks, commas or semicolons; columns from a header row, opts->columns, or
 *      the format's defaults; coordinates kept as exact doubles.
 * PCD  (io/pcd.c): PCL's format, header versions 0.5-0.7, DATA ascii, binary and
 *      binary_compressed (LZF); x y z (float or double, double kept exactly as for PLY),
 *      rgb/rgba (packed 0x00RRGGBB) -> colours, normal_x/y/z -> normals, integer label ->
 *      labels, every other field kept as an extra property (COUNT > 1: NAME_0, NAME_1 ...);
 *      NaN points of organised clouds are kept; VIEWPOINT -> has_viewpoint / viewpoint.
 *      Written as binary PCD (pnpr_write_pcd_stream, or pnpr_write_file with a .pcd name).
 *
 * Errors are precise: pnpr_error says which file, which line or byte offset, what was expected. */
#ifndef POINTNPR_IO_H
#define POINTNPR_IO_H

#include "cloud.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pnpr_file_format {
    PNPR_FORMAT_AUTO = 0, /* from the extension (and magic bytes for reading) */
    PNPR_FORMAT_PLY,
    PNPR_FORMAT_LAS,
    PNPR_FORMAT_OBJ,
    PNPR_FORMAT_OFF,
    PNPR_FORMAT_PCD,
    PNPR_FORMAT_XYZ, /* text point clouds (io/text_points.c): x y z [nx ny nz] per line */
    PNPR_FORMAT_PTS, /* Leica PTS: count line, x y z [intensity [r g b]] */
    PNPR_FORMAT_PWN, /* x y z nx ny nz */
    PNPR_FORMAT_CSV, /* columns from a header row or opts->columns; also .txt */
    PNPR_FORMAT_COUNT_
} pnpr_file_format;

typedef enum pnpr_ply_encoding {
    PNPR_PLY_BINARY_LE = 0, /* default */
    PNPR_PLY_ASCII,
    PNPR_PLY_BINARY_BE
} pnpr_ply_encoding;

typedef struct pnpr_read_options {
    pnpr_file_format format; /* 0 = auto */
    pnpr_progress progress;
    /* Text point clouds only (XYZ, PTS, PWN, CSV, TXT): the column names, comma-separated
     * ("x,y,z,nx,ny,nz,r,g,b,intensity,_"; io/text_points.c lists them). NULL = a header row
     * when the file has one, else the format's defaults. Ignored by the other formats. */
    const char *columns;
    /* A point filter, for reading one tile of a cloud larger than memory (pointnpr/tiles.h).
     * NULL = every point. Binary PLY only, whose vertex records have a fixed size and follow no
     * element with lists (what pointnpr writes; other inputs are refused with
     * PNPR_ERR_UNSUPPORTED). Called once per vertex, in file order, with its index and its
     * coordinates as stored (NaN/Inf as read), before anything is allocated for the points; the
     * vertices it returns nonzero for are kept, in file order, and faces are not read. */
    int (*keep)(void *user, uint64_t index, const double position[3]);
    void *keep_user;
    /* With keep: only the vertices of these ranges are visited (range g: [ranges[2 g],
     * ranges[2 g + 1]) of vertex indices, ascending, not overlapping); the others are skipped
     * unread (a file ordered for drawing, pointnpr/lod.h). NULL = every vertex. A range beyond
     * the vertices or out of order, or ranges without keep, is PNPR_ERR_INVALID_ARGUMENT, before
     * keep sees a point. */
    const uint64_t *ranges;
    size_t range_count;
    /* PLY with double (or int) coordinates: the origin of the float offsets (finite), instead of
     * the centre of the points' own box (pnpr_cloud_set_world); NULL = that centre. Tiles take
     * the whole file's origin this way, so that their floats are those of a run in memory. */
    const double *origin;
} pnpr_read_options;

typedef struct pnpr_write_options {
    pnpr_file_format format;     /* 0 = auto from extension; PLY and PCD are written */
    pnpr_ply_encoding encoding;  /* PLY: 0 = binary little endian (PCD is always binary) */
    /* Coordinates are written in the source type: double when cloud->src_xyz or
     * src_coord_type == FLOAT64, float otherwise (but double when src_coord_type is NONE and
     * origin + offset is not exactly a float). force_double writes doubles always. */
    int force_double;
    const char *comment;         /* optional "comment" line, may be NULL */
    pnpr_progress progress;
} pnpr_write_options;

/* Reads any supported file into `cloud` (which must be empty or zeroed; it is freed first). */
PNPR_NODISCARD pnpr_status pnpr_read_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                           pnpr_error *err);

PNPR_NODISCARD pnpr_status pnpr_read_ply_memory(const void *data, size_t size, const pnpr_read_options *opts,
                                 pnpr_cloud *cloud, pnpr_error *err);
PNPR_NODISCARD pnpr_status pnpr_read_las_memory(const void *data, size_t size, const pnpr_read_options *opts,
                                 pnpr_cloud *cloud, pnpr_error *err);
PNPR_NODISCARD pnpr_status pnpr_read_pcd_memory(const void *data, size_t size, const pnpr_read_options *opts,
                                 pnpr_cloud *cloud, pnpr_error *err);
/* Text point clouds from memory (format: PNPR_FORMAT_XYZ, _PTS, _PWN or _CSV in opts->format;
 * AUTO reads as CSV: a header row or the column defaults). */
PNPR_NODISCARD pnpr_status pnpr_read_text_memory(const void *data, size_t size, const pnpr_read_options *opts,
                                  pnpr_cloud *cloud, pnpr_error *err);
/* OBJ/OFF through OpenMesh (vertices, vertex colours and normals when present, faces).
 * pnpr_read_file reads ascii OFF with io/off.c instead. */
PNPR_NODISCARD pnpr_status pnpr_read_mesh_file(const char *path, const pnpr_read_options *opts,
                                pnpr_cloud *cloud, pnpr_error *err);

/* Writes PLY or PCD (format, else the extension; "-" is PLY on standard output) the way every
 * output is written (pointnpr/output.h): never half a file, never a special file replaced. */
PNPR_NODISCARD pnpr_status pnpr_write_file(const char *path, const pnpr_cloud *cloud,
                            const pnpr_write_options *opts, pnpr_error *err);

/* Writes PLY to a caller-provided sink (fn returns 0 on success). */
typedef int (*pnpr_write_fn)(void *user, const void *data, size_t size);

/* A sink that collects the bytes in memory: pass pnpr_mem_sink_write and a zeroed pnpr_mem_sink;
 * data (size bytes) grows by doubling; release it with free(). Fails (returns 1) only when memory
 * runs out, keeping what it had. */
typedef struct pnpr_mem_sink {
    unsigned char *data;
    size_t size, cap;
} pnpr_mem_sink;
int pnpr_mem_sink_write(void *user, const void *data, size_t size);
PNPR_NODISCARD pnpr_status pnpr_write_ply_stream(pnpr_write_fn fn, void *user, const pnpr_cloud *cloud,
                                  const pnpr_write_options *opts, pnpr_error *err);

/* Joins files into one PLY at `path` with one input in memory at a time (a folder of tiles larger
 * than memory: docs/tiles.md). Every input must write the same PLY header but for its count (the
 * same properties and types; inputs without points are skipped), and none may have faces; the
 * records are those of the inputs joined in memory and written (pnpr_cloud_append,
 * pnpr_write_file), the header has one padding comment line more (room for the count, written
 * last). The output is a regular file or a new name, none of the inputs (pnpr_output_check),
 * written as every output is (output.h); a device, pipe or "-" is refused (PNPR_ERR_UNSUPPORTED),
 * as is an input that does not fit, naming it. r_points (may be NULL): the points written. */
typedef struct pnpr_join_options {
    pnpr_read_options read;   /* how each input is read (columns of text inputs); no keep or origin */
    pnpr_write_options write; /* encoding, comment, force_double (format: PLY) */
    pnpr_progress progress;   /* stage "join": the share of the inputs done */
} pnpr_join_options;
PNPR_NODISCARD pnpr_status pnpr_join_ply(const char *const *inputs, size_t count, const char *path,
                                         const pnpr_join_options *opts, uint64_t *r_points, pnpr_error *err);

/* Writes binary PCD to a caller-provided sink (x y z, normals, rgb, label, extra properties). */
PNPR_NODISCARD pnpr_status pnpr_write_pcd_stream(pnpr_write_fn fn, void *user, const pnpr_cloud *cloud,
                                  const pnpr_write_options *opts, pnpr_error *err);

pnpr_file_format pnpr_format_from_path(const char *path);

#ifdef __cplusplus
}
#endif
#endif
