/* pointnpr — cloud.h: the point cloud model shared by every module.
 *
 * Positions are float offsets from a double-precision origin: world = origin + xyz[i].
 * Georeferenced scans (coordinates ~5e6) therefore keep sub-millimetre detail in float,
 * and no stage ever subtracts large doubles in float.
 *
 * When the source file stored coordinates that the float offsets cannot reproduce exactly
 * (double coordinates, LAS scaled integers), the reader also keeps them in `src_xyz`
 * (doubles, world units) so that writers put back exactly what came in.
 * For float sources the origin is 0 and xyz holds the source floats bit for bit.
 *
 * The cloud owns its arrays (allocated with malloc by readers and pnpr_cloud_* helpers,
 * released by pnpr_cloud_free). A zero-initialised pnpr_cloud is a valid empty cloud. */
#ifndef POINTNPR_CLOUD_H
#define POINTNPR_CLOUD_H

#include "core.h"
#include "props.h" /* PNPR_PROP_*: the names of the per-point properties */

#ifdef __cplusplus
extern "C" {
#endif

/* Scalar types, named as in PLY. */
typedef enum pnpr_type {
    PNPR_TYPE_NONE = 0,
    PNPR_TYPE_INT8,    /* char   */
    PNPR_TYPE_UINT8,   /* uchar  */
    PNPR_TYPE_INT16,   /* short  */
    PNPR_TYPE_UINT16,  /* ushort */
    PNPR_TYPE_INT32,   /* int    */
    PNPR_TYPE_UINT32,  /* uint   */
    PNPR_TYPE_FLOAT32, /* float  */
    PNPR_TYPE_FLOAT64, /* double */
    PNPR_TYPE_COUNT_
} pnpr_type;

size_t pnpr_type_size(pnpr_type t);           /* 0 for NONE/invalid */
const char *pnpr_type_ply_name(pnpr_type t);  /* "uchar", "float", ...; "" for invalid */
/* Value of element i of a typed array, converted to double. */
double pnpr_type_get(pnpr_type t, const void *data, size_t i);
/* Stores v (rounded/saturated for integer types, NaN -> 0) into element i. */
void pnpr_type_set(pnpr_type t, void *data, size_t i, double v);

/* An extra per-point property kept through to the output (e.g. "intensity", "classification"). */
typedef struct pnpr_property {
    char name[64];
    pnpr_type type;
    void *data; /* count * pnpr_type_size(type) bytes, native byte order */
} pnpr_property;

/* Faces from a PLY/OBJ/OFF input, kept so that a PLY output writes them back.
 * Face f has corners index[offset[f] .. offset[f+1]-1]. */
typedef struct pnpr_faces {
    size_t count;
    uint32_t *offset; /* count + 1 entries */
    uint32_t *index;
} pnpr_faces;

typedef struct pnpr_cloud {
    size_t count;
    double origin[3];
    float *xyz;        /* 3*count, offsets from origin; required when count > 0 */
    double *src_xyz;   /* 3*count world coordinates as read, or NULL (see above) */
    pnpr_type src_coord_type; /* type of x/y/z in the source (FLOAT32 or FLOAT64; NONE = unknown -> float) */
    uint8_t *rgb;      /* 3*count, 8 bit per channel, or NULL */
    float *normal;     /* 3*count unit normals, or NULL */
    uint32_t *label;   /* count segment labels, or NULL */
    size_t prop_count;
    pnpr_property *props;
    pnpr_faces faces;
    /* What the file says about how it was captured (0 = unknown); used by the default view
     * (pnpr_scene_frame) and kept by writers that can store it. */
    int has_viewpoint;  /* viewpoint holds the scanner position (world), e.g. PCD VIEWPOINT */
    double viewpoint[3];
    int up_hint;        /* the format's up axis: +-1, +-2, +-3 = +-x, +-y, +-z (LAS: +3) */
} pnpr_cloud;

void pnpr_cloud_free(pnpr_cloud *cloud); /* frees everything, leaves a zeroed cloud; NULL ok */

/* Allocates xyz for `count` points (contents zero), freeing what the cloud held. */
PNPR_NODISCARD pnpr_status pnpr_cloud_alloc(pnpr_cloud *cloud, size_t count);
/* Allocate the optional arrays (zero-filled) if absent; no-op when present. */
PNPR_NODISCARD pnpr_status pnpr_cloud_alloc_rgb(pnpr_cloud *cloud);
PNPR_NODISCARD pnpr_status pnpr_cloud_alloc_normals(pnpr_cloud *cloud);
PNPR_NODISCARD pnpr_status pnpr_cloud_alloc_labels(pnpr_cloud *cloud);
PNPR_NODISCARD pnpr_status pnpr_cloud_alloc_src_xyz(pnpr_cloud *cloud);

/* Finds an extra property by name; NULL if absent. */
pnpr_property *pnpr_cloud_find_property(const pnpr_cloud *cloud, const char *name);
/* Adds (or replaces, if the name exists) a zero-filled extra property; r_prop may be NULL. */
PNPR_NODISCARD pnpr_status pnpr_cloud_add_property(pnpr_cloud *cloud, const char *name, pnpr_type type,
                                    pnpr_property **r_prop);
PNPR_NODISCARD pnpr_status pnpr_cloud_remove_property(pnpr_cloud *cloud, const char *name);

/* World coordinate of point i (uses src_xyz when present, else origin + xyz). */
void pnpr_cloud_world(const pnpr_cloud *cloud, size_t i, double r_world[3]);

/* Sets the origin and float offsets from world coordinates (3*count doubles).
 * The origin is the centre of the finite bounding box of the points that are not far outliers
 * (outliers.h; without far outliers: of all finite points), so that one point at 1e9 does not
 * take the content's float precision. Non-finite coordinates stay non-finite in xyz, and so do
 * offsets that overflow float (a coordinate of 1e308): stages treat such points as invalid.
 * Does not touch src_xyz. */
PNPR_NODISCARD pnpr_status pnpr_cloud_set_world(pnpr_cloud *cloud, const double *world);
/* The same with a given origin (finite): offsets (float)(world - origin), as set_world computes
 * them; a tile of a cloud (tiles.h) takes the whole cloud's origin this way. */
PNPR_NODISCARD pnpr_status pnpr_cloud_set_world_at(pnpr_cloud *cloud, const double *world, const double origin[3]);

/* Appends all points of `src` to `dst` (re-expressing offsets in dst's origin, which is
 * chosen from the union's bounding box when dst is empty). Optional arrays and extra
 * properties present in either cloud are kept (missing values are zero); faces are
 * re-indexed. */
PNPR_NODISCARD pnpr_status pnpr_cloud_append(pnpr_cloud *dst, const pnpr_cloud *src);

/* Removes the points with keep[i] == 0 (count entries) from every per-point array and extra
 * property, keeping the order of the others; faces with a removed corner are dropped, the others
 * re-indexed. r_removed (may be NULL) receives how many points went. */
PNPR_NODISCARD pnpr_status pnpr_cloud_keep(pnpr_cloud *cloud, const uint8_t *keep, size_t *r_removed);

/* Reorders the points: point p becomes the point perm[p] was. perm must be a permutation of
 * 0..count-1 (not checked: an index repeated copies a point twice, one out of range reads out of
 * bounds). Not for a cloud with faces (PNPR_ERR_INVALID_ARGUMENT). */
PNPR_NODISCARD pnpr_status pnpr_cloud_permute(pnpr_cloud *cloud, const uint32_t *perm);

/* Bounding box of the finite offsets; returns the number of finite points. */
size_t pnpr_cloud_bounds(const pnpr_cloud *cloud, float r_min[3], float r_max[3]);

#ifdef __cplusplus
}
#endif
#endif
