/* pointnpr — hierarchy.h: Chi & Lee's multiscale segmented sphere hierarchy ("Stylized and
 * Abstract Painterly Rendering System Using a Multiscale Segmented Sphere Hierarchy", the paper in
 * ../shared/papers/painterly-sphere-hierarchy-chi-lee.txt), the parts that need no GL:
 *   - the tree (sec. 3): uniform leaf spheres resampled from the points, JSEG regions of the leaves,
 *     the region adjacency graph's merge order above them (eq. 4) and covariance splitting within
 *     each region below them; every node carries position, radius, normal, normal cone, colour,
 *     curvature, a principal direction (interpolated across non-feature leaves) and its
 *     dissimilarity S (eq. 5)                                           (filters/sphere_tree.c)
 *   - the traversal (sec. 4): region nodes by the dissimilarity threshold, stroke nodes by radius
 *     (view-independent) or projected size (view-dependent) with the smooth level transition
 *     (sec. 4.2.3), silhouettes by the n.v band, region borders, an importance map; it writes
 *     the strokes of one frame                                      (filters/sphere_traverse.c)
 *   - the tonal art maps (Praun et al.), generated here: tones x scales  (filters/tam.c)
 * The renderer's `hierarchy` style draws the strokes (render.h); docs/hierarchy.md documents every
 * choice the paper leaves open. */
#ifndef POINTNPR_HIERARCHY_H
#define POINTNPR_HIERARCHY_H

#include "cloud.h"
#include "segment.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the tree -------------------------------------------------------------------------------- */

enum {
    PNPR_SPHERE_LEAF = 0,   /* a leaf: a resampled sphere holding the input points nearest to it */
    PNPR_SPHERE_STROKE = 1, /* an inner node of the covariance splitting within one JSEG region */
    PNPR_SPHERE_REGION = 2  /* a JSEG region's top node or a merge of the region adjacency graph */
};

/* A node, packed into 64 bytes (the renderer holds about one node per point beside its vertex
 * buffers; docs/hierarchy.md "Memory"): directions as signed 16-bit fractions of 1, colours as
 * bytes, the cone and curvature as unsigned 16-bit fractions. pnpr_sphere_normal and the functions
 * beside it give them as floats. */
typedef struct pnpr_sphere_node {
    float centre[3];      /* offset from the tree's origin: the centroid of its leaves */
    float radius;         /* bounding sphere around centre: holds the children's spheres (leaves:
                           * their points); culling */
    float extent;         /* the sphere around centre that holds its leaves' spheres (<= radius):
                           * the size of its stroke (the bounding spheres of bounding spheres grow
                           * level by level; docs/hierarchy.md) */
    float dissimilarity;  /* S of eq. 5 over colours (CIE76 delta E), 0 for leaves */
    int16_t normal[3];    /* unit, unsigned (a fitted normal) x PNPR_SPHERE_UNIT; 0 when unknown */
    int16_t dir[3];       /* unit tangent direction (sec. 3.1) x PNPR_SPHERE_UNIT: feature leaves'
                           * principal direction, interpolated across the others, averaged
                           * upwards; 0 = none */
    uint16_t cone;        /* half-angle of the cone around `normal` holding the children's cones
                           * (unsigned normals: angles folded into 0..pi/2), in (pi/2)/65535,
                           * rounded up so that it still holds them */
    uint16_t curvature;   /* mean surface variation lambda0 / (lambda0 + lambda1 + lambda2), in
                           * 1/65535 */
    uint8_t colour[3];    /* mean RGB of the points below, rounded */
    uint8_t kind;         /* PNPR_SPHERE_* */
    uint32_t parent;      /* PNPR_INDEX_NONE for the root */
    uint32_t child[2];    /* PNPR_INDEX_NONE for leaves */
    uint32_t leaf_begin;  /* its leaves: tree->leaves[leaf_begin .. pnpr_sphere_leaf_end - 1] */
    uint32_t region;      /* the hierarchy node (segment id < region_count, merges above) this node
                           * belongs to: inside a region its segment, region nodes their own id */
} pnpr_sphere_node;

/* The scale of pnpr_sphere_node.normal and .dir. */
#define PNPR_SPHERE_UNIT 32767

typedef struct pnpr_sphere_tree {
    double origin[3];          /* the cloud's origin: world = origin + centre */
    size_t node_count;
    pnpr_sphere_node *nodes;
    uint32_t root;             /* PNPR_INDEX_NONE for an empty tree */
    size_t leaf_count;
    uint32_t *leaves;          /* node index of each leaf, in depth-first order (so every node's
                                * leaves are one range) */
    size_t point_count;
    uint32_t *point_leaf;      /* the leaf (index into leaves) holding each input point;
                                * PNPR_INDEX_NONE for points with a non-finite coordinate */
    uint32_t merge_first;      /* the merges of the region adjacency graph are nodes merge_first ..
                                * node_count - 1, in merge order (their levels never decrease) */
    float *merge_level;        /* node_count - merge_first entries: merge m's level (monotone,
                                * pnpr_segment_merge.level); the region nodes below are level 0 */
    uint32_t region_count;     /* S: the JSEG regions of the leaves (segment ids 0 .. S-1) */
    size_t border_count;       /* leaf pairs adjacent across two regions (kNN of the leaves) */
    uint32_t *border;          /* 2 x border_count leaf indices */
    float spacing;             /* the leaf spacing (offset units) */
    int has_rgb;               /* the cloud had colours (else grey colours and geometric regions) */
} pnpr_sphere_tree;

/* Largest pnpr_sphere_tree_options.k. */
#define PNPR_SPHERE_K_MAX 64

typedef struct pnpr_sphere_tree_options {
    float spacing;        /* leaf spacing in the cloud's units; 0 = leaf_factor x the median point
                           * spacing */
    float leaf_factor;    /* see spacing (options table) */
    uint32_t k;           /* neighbouring leaves for normals, curvature and directions */
    float feature_fraction; /* leaves with the highest curvature keep their principal direction
                           * (the RBF interpolation's centres, sec. 3.1) */
    float max_variation;  /* colourless clouds: the geometric regions' covariance-split bound */
    pnpr_jseg_options jseg;       /* the regions (zero = the defaults; its k, min_size apply to leaves) */
    pnpr_hierarchy_options merge; /* the region adjacency graph's merge order (eq. 4) */
    int use_labels;       /* 1: regions from cloud->label (a leaf takes its seed point's label)
                           * instead of JSEG; 0: JSEG (colourless: covariance split) */
    int threads;          /* 0 = all cores */
    pnpr_progress progress; /* stages "leaves", "knn", JSEG's ("quantise", "J", "grow", "merge"),
                           * "hierarchy", "tree" */
} pnpr_sphere_tree_options;

typedef struct pnpr_sphere_tree_stats {
    size_t leaves, nodes, regions, border_pairs;
    double seconds;
} pnpr_sphere_tree_stats;

/* Builds the tree of a cloud. An empty (or all-NaN) cloud gives an empty tree (root NONE).
 * Options outside their ranges (pnpr_sphere_tree_option_table) give PNPR_ERR_INVALID_ARGUMENT
 * with a message in err (may be NULL). Release with pnpr_sphere_tree_free. r_stats may be NULL. */
PNPR_NODISCARD pnpr_status pnpr_sphere_tree_build(const pnpr_cloud *cloud, const pnpr_sphere_tree_options *opts,
                                                  pnpr_sphere_tree *r_tree, pnpr_sphere_tree_stats *r_stats,
                                                  pnpr_error *err);
void pnpr_sphere_tree_free(pnpr_sphere_tree *tree); /* leaves a zeroed tree; NULL ok */

/* A packed node's fields as floats: the unit normal and direction (unit length again; 0 when
 * unknown), the colour 0..255, the cone in radians, the curvature. */
void pnpr_sphere_normal(const pnpr_sphere_node *n, float r_normal[3]);
void pnpr_sphere_dir(const pnpr_sphere_node *n, float r_dir[3]);
void pnpr_sphere_colour(const pnpr_sphere_node *n, float r_rgb[3]);
float pnpr_sphere_cone(const pnpr_sphere_node *n);
float pnpr_sphere_curvature(const pnpr_sphere_node *n);
/* The end of node i's leaf range (one past its last leaf in tree->leaves): its rightmost leaf's
 * leaf_begin + 1, found by descending (the tree's depth); 0 for an index out of range. */
uint32_t pnpr_sphere_leaf_end(const pnpr_sphere_tree *tree, uint32_t i);

struct pnpr_camera_matrices; /* camera.h */

/* ---- the traversal ----------------------------------------------------------------------------- */

/* One stroke of a frame: a quad centred at pos spanned by +-u and +-v (offsets from the tree's
 * origin), drawn with TAM layer `tone` in colour rgba (alpha: the smooth transition's). */
typedef struct pnpr_hier_stroke {
    float pos[3];
    float u[3];           /* half-length along the stroke direction */
    float v[3];           /* half-width */
    uint8_t rgba[4];
    float tone;           /* TAM tone 0 .. PNPR_TAM_TONES - 1, fractions blend the two tones around;
                           * PNPR_HIER_LINE_LAYER: a plain tapered line (silhouettes, borders) */
} pnpr_hier_stroke;

/* The tone of silhouette and border strokes: the renderer's layer after the map's tones, a solid
 * line tapered at its ends (a hatch or dot texture would break a 2-pixel line into dashes). */
#define PNPR_HIER_LINE_LAYER PNPR_TAM_TONES

typedef enum pnpr_hier_kind { PNPR_HIER_PAINT = 0, PNPR_HIER_SILHOUETTE, PNPR_HIER_BORDER, PNPR_HIER_KIND_COUNT_ } pnpr_hier_kind;

typedef struct pnpr_hier_view {
    const float *view, *proj; /* column-major 4x4, the tree's frame (offsets from its origin) */
    int width, height;        /* the viewport, pixels */
    float pixels_per_unit;    /* proj[5] x height / 2 (of the whole image when tiled) */
    int ortho;                /* orthographic projection */
    const float *image_proj;  /* tiles: the whole image's projection, for the importance map
                               * (NULL = proj) */
} pnpr_hier_view;

typedef struct pnpr_hier_params {
    float abstraction;    /* region nodes: descend while S > abstraction x S(root); negative = no
                           * abstraction (every leaf its own region node) */
    float stroke_px;      /* view-dependent (default): stroke nodes of projected diameter <= this */
    float stroke_radius;  /* > 0: view-independent: stroke nodes of radius <= this (cloud units) */
    float stroke_scale;   /* a stroke's half-width in node radii */
    float stretch;        /* its half-length in half-widths */
    int no_smooth;        /* 1: plain level switching (no interpolated nodes, sec. 4.2.3) */
    int node_colour;      /* 1: strokes in the node's colour; 0: the region node's (sec. 4.3) */
    int node_direction;   /* 1: the node's direction; 0: the region node's */
    float noise_angle;    /* Perlin noise on the direction: at most this many degrees (negative = none) */
    float noise_colour;   /* and on the brightness: at most this fraction (negative = none) */
    float silhouette_deg; /* ThresholdDegree: nodes with |n.v| < sin(this) are drawn as silhouettes
                           * (negative = none) */
    float border_level;   /* > 0: region borders between the regions of this merge level
                           * (pnpr_segment_merge.level units); 0 = none */
    int tam;              /* the tonal art map, pnpr_tam_kind; hatch and dots draw in the ink colour */
    int layers;           /* the renderer: 2 = a second, fine layer over the first (sec. 5.1) */
    int fine_layer;       /* the traversal of that layer: only nodes of high detail (curvature or
                           * colour difference to the region), at half the stroke size, in their
                           * own colour, no silhouettes or borders */
    const uint8_t *importance; /* NULL or importance_w x importance_h grey bytes (row 0 at the top):
                           * white keeps every region and halves the strokes, black = as elsewhere */
    int importance_w, importance_h;
    float light[3];       /* direction towards the light in eye space (0 = from the upper left) */
    float ink[3];         /* silhouette and border colour, 0..1 */
    const struct pnpr_camera_matrices *lod_camera; /* the renderer: strokes chosen as this camera
                           * (camera.h, world matrices) sees them, drawn through the frame's: the
                           * selection frozen while the view moves (NULL = the frame's camera) */
} pnpr_hier_params;

typedef struct pnpr_hier_counts {
    size_t strokes[PNPR_HIER_KIND_COUNT_];
    size_t region_nodes;  /* region nodes the traversal chose */
    double weighted;      /* paint strokes counted by their alpha */
    int truncated;        /* more strokes than the capacity: the rest were dropped */
} pnpr_hier_counts;

/* Writes the strokes of one frame into r_strokes (capacity `cap`; NULL with cap 0 counts them):
 * the paint strokes in traversal order, then the silhouettes, then the borders (r_counts says how
 * many of each; when they do not fit, truncated is set and what did not fit is left out).
 * Frustum-culled; deterministic. Parameters: zeros are the defaults of pnpr_hier_option_table
 * (options.h); PNPR_ERR_INVALID_ARGUMENT for a bad view or a parameter out of range. */
PNPR_NODISCARD pnpr_status pnpr_sphere_tree_traverse(const pnpr_sphere_tree *tree, const pnpr_hier_view *view,
                                                     const pnpr_hier_params *params, pnpr_hier_stroke *r_strokes,
                                                     size_t cap, pnpr_hier_counts *r_counts);

/* ---- tonal art maps ------------------------------------------------------------------------- */

#define PNPR_TAM_TONES 6   /* tone 0 the lightest */
#define PNPR_TAM_SIZE 64   /* the finest level's side, pixels */
#define PNPR_TAM_LEVELS 4  /* levels 64, 32, 16, 8 */

typedef enum pnpr_tam_kind { PNPR_TAM_PAINT = 0, PNPR_TAM_HATCH, PNPR_TAM_DOTS, PNPR_TAM_COUNT_ } pnpr_tam_kind;

/* Level `level` (side PNPR_TAM_SIZE >> level) of every tone: r_alpha receives PNPR_TAM_TONES
 * images of side x side coverage bytes (255 = full paint/ink), tone-major, row-major.
 * PNPR_ERR_INVALID_ARGUMENT for a kind or level out of range. Deterministic. */
PNPR_NODISCARD pnpr_status pnpr_tam_level(pnpr_tam_kind kind, int level, uint8_t *r_alpha);
/* The mean ink coverage that tone `tone` of the hatch and dots maps is made for (0 out of range). */
double pnpr_tam_tone_coverage(int tone);
const char *pnpr_tam_name(pnpr_tam_kind kind);  /* "paint", "hatch", "dots"; "" out of range */
int pnpr_tam_find(const char *name);            /* the kind, -1 when unknown (case-insensitive) */

#ifdef __cplusplus
}
#endif
#endif
