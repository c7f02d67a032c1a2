/* Validating pre-pass over an OBJ or OFF file (not installed), run by io/mesh_openmesh.cpp
 * before OpenMesh sees the file: it walks the file once, streaming, the way OpenMesh 9's readers
 * tokenise it, and rejects everything they would misread, loop on or allocate without bound
 * (io/mesh_check.c has the rules). Plain C; usable from C++. */
#ifndef PNPR_MESH_CHECK_H
#define PNPR_MESH_CHECK_H

#include <pointnpr/io.h>

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PNPR_MESH_MAX_VERTICES 2147483647u     /* OpenMesh's vertex handles are int */
#define PNPR_MESH_MAX_CORNERS 65536u           /* corners of one OBJ face */
#define PNPR_MESH_MAX_CORNER_WORK 4294967296ull /* sum over OBJ faces of corners^2 */

/* Receives each ascii vertex, in file order: its exact coordinates and the floats that OpenMesh
 * reads from the same text (strtof). Returns non-zero to stop the check with
 * PNPR_ERR_OUT_OF_MEMORY. */
typedef int (*pnpr_mesh_vertex_fn)(void *user, const double xyz[3], const float xyz_f[3]);

typedef struct pnpr_mesh_check {
    /* in */
    pnpr_file_format format;   /* PNPR_FORMAT_OBJ or PNPR_FORMAT_OFF */
    const char *openmesh_path; /* OBJ: the name OpenMesh will open (mtllib names are resolved
                                * against its folder, as OpenMesh does); NULL = the path */
    pnpr_mesh_vertex_fn vertex; /* optional */
    void *user;
    /* out, on PNPR_OK */
    uint64_t vertices; /* the vertices OpenMesh will report */
    uint64_t faces;    /* face statements (OBJ) / records (OFF) */
    int binary;        /* OFF BINARY: coordinates are float32, no vertex callback */
} pnpr_mesh_check;

/* Checks the file. Errors: "PATH: line N: ..." (err->line = N) for text, "PATH: byte N: ..."
 * (err->offset = N) for binary OFF data; PNPR_ERR_TRUNCATED when the file holds less than it
 * announces, PNPR_ERR_FORMAT for malformed content, PNPR_ERR_UNSUPPORTED for valid content past
 * OpenMesh's limits, PNPR_ERR_IO, PNPR_ERR_OUT_OF_MEMORY (from the callback). */
pnpr_status pnpr_mesh_check_file(const char *path, pnpr_mesh_check *mc, pnpr_error *err);

#ifdef __cplusplus
}
#endif
#endif
