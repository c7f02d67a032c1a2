/* pointnpr bench quality — a LiDAR-like analytic scene with known answers, and picture-quality
 * figures measured on rendered images (docs/quality.md).
 *
 * Library target `pointnpr_quality` (bench/quality/, GL-free, links the core `pointnpr` only); the
 * `pointnpr bench quality` command and the tests link it. Three parts, one file each:
 *   quality_scene.c    the analytic scene: ground rectangle, buildings (convex prisms about +z,
 *                      flat or gabled roofs), trees (vertical trunk cylinder + crown sphere), a
 *                      sphere object; its true crease edges; a ray caster against it
 *   quality_scan.c     terrestrial-LiDAR sampling of the scene: rays over an angular grid from the
 *                      scanner positions (spread evenly over the sphere), first hit = a point,
 *                      Gaussian range noise, colours
 *   quality_metrics.c  the figures: visible-edge coverage and ink precision, sphere-silhouette
 *                      coverage, outline-ink fraction, speckle, feature-to-flat ink ratio
 *
 * Conventions: z is up; lengths are metres. The scene lives in its own local frame; world
 * coordinates (those of the cloud: cloud origin + offsets, and of the camera matrices) are
 * local + scene.offset, added in double. Every struct is caller-owned and fixed-size; options
 * are valid when zeroed (zero = the documented default). No global state. */
#ifndef PNPR_QUALITY_H
#define PNPR_QUALITY_H

#include <pointnpr/cloud.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the analytic scene ------------------------------------------------------------------- */

enum { PNPR_QUALITY_MAX_BUILDINGS = 8, PNPR_QUALITY_MAX_TREES = 8, PNPR_QUALITY_MAX_SPHERES = 4,
       PNPR_QUALITY_MAX_SCANNERS = 8, PNPR_QUALITY_MAX_EDGES = 16 * PNPR_QUALITY_MAX_BUILDINGS };

/* A building: a box on the ground (z = 0) with footprint centre, half sizes along its local x and
 * y axes, rotated by yaw about +z; walls up to wall_height; roof_height > 0 adds a gabled roof
 * whose ridge runs along the local x axis, roof_height above the eaves (a convex solid). */
typedef struct pnpr_quality_building {
    double centre[2], half[2], yaw_deg, wall_height, roof_height;
    uint8_t wall_rgb[3], roof_rgb[3];
} pnpr_quality_building;

/* A tree: a vertical trunk cylinder from the ground to trunk_height, a crown sphere. */
typedef struct pnpr_quality_tree {
    double base[2], trunk_radius, trunk_height, crown_centre_z, crown_radius;
} pnpr_quality_tree;

typedef struct pnpr_quality_sphere {
    double centre[3], radius;
    uint8_t rgb[3];
} pnpr_quality_sphere;

/* What a ray hit. */
typedef enum pnpr_quality_kind {
    PNPR_QUALITY_NOTHING = 0,
    PNPR_QUALITY_GROUND,
    PNPR_QUALITY_WALL,   /* a building's vertical face */
    PNPR_QUALITY_ROOF,   /* a building's top face(s) */
    PNPR_QUALITY_TRUNK,
    PNPR_QUALITY_CROWN,
    PNPR_QUALITY_SPHERE,
    PNPR_QUALITY_UNSEEN  /* only in pnpr_quality_kind_image: ground that no scanner sees */
} pnpr_quality_kind;

/* Kinds of true edges. Creases are building edges (dihedral angle >= the scene's crease_angle);
 * the others are view-dependent outlines (pnpr_quality_silhouettes). */
typedef enum pnpr_quality_edge_kind {
    PNPR_QUALITY_EDGE_CORNER = 0, /* vertical wall-wall edge */
    PNPR_QUALITY_EDGE_EAVE,       /* wall-roof edge (the top of a flat-roofed box's walls too) */
    PNPR_QUALITY_EDGE_RIDGE,      /* roof-roof edge of a gabled roof */
    PNPR_QUALITY_EDGE_RAKE,       /* sloped gable-wall-roof edge */
    PNPR_QUALITY_EDGE_FOOT,       /* wall-ground edge (concave) */
    PNPR_QUALITY_EDGE_OUTLINE     /* silhouettes: sphere and crown outlines, trunk sides, ground border */
} pnpr_quality_edge_kind;

/* A straight 3D segment (scene-local coordinates). angle_deg: the crease's dihedral turn (angle
 * between the two faces' normals), 0 for outlines. */
typedef struct pnpr_quality_segment {
    double a[3], b[3];
    pnpr_quality_edge_kind kind;
    double angle_deg;
} pnpr_quality_segment;

typedef enum pnpr_quality_preset {
    PNPR_QUALITY_PRESET_SMALL = 0, /* the house scene, about 150k points (tests) */
    PNPR_QUALITY_PRESET_FULL,      /* the same scene, finer angular grid: about 1M points (the bench) */
    PNPR_QUALITY_PRESET_BALL,      /* the sphere object alone, scanned from a ring of positions */
    PNPR_QUALITY_PRESET_SPARSE     /* the house scene, twice the small step: a quarter of its points */
} pnpr_quality_preset;

typedef struct pnpr_quality_scene {
    double offset[3];                 /* world = local + offset (a georeferenced-like origin) */
    int has_ground;                   /* the ground rectangle z = 0 over [ground_min, ground_max] */
    double ground_min[2], ground_max[2];
    int building_count, tree_count, sphere_count;
    pnpr_quality_building building[PNPR_QUALITY_MAX_BUILDINGS];
    pnpr_quality_tree tree[PNPR_QUALITY_MAX_TREES];
    pnpr_quality_sphere sphere[PNPR_QUALITY_MAX_SPHERES];
    /* scanning */
    int scanner_count;
    double scanner[PNPR_QUALITY_MAX_SCANNERS][3];
    double step_deg;                  /* angular grid step: elevation; azimuth step / cos(elevation) */
    double elevation_min_deg, elevation_max_deg;
    double max_range;                 /* rays longer than this return nothing */
    double range_sigma;               /* Gaussian range noise (m) */
    double foliage_depth;             /* crown hits go this much deeper on average (exponential) */
    uint64_t seed;
    /* true crease edges (filled by pnpr_quality_scene_edges) */
    double crease_angle_deg;          /* 0 = 20: building edges with a smaller turn are not creases */
    size_t edge_count;
    pnpr_quality_segment edge[PNPR_QUALITY_MAX_EDGES];
} pnpr_quality_scene;

/* Fills the scene of a preset (objects, scanners, grid, noise, seed) and its edges. */
void pnpr_quality_scene_init(pnpr_quality_scene *scene, pnpr_quality_preset preset);

/* (Re)computes scene->edge from the buildings (after editing a scene by hand). */
void pnpr_quality_scene_edges(pnpr_quality_scene *scene);

typedef struct pnpr_quality_hit {
    double t;                /* distance along the (unit) direction */
    double normal[3];        /* outward unit normal at the hit */
    pnpr_quality_kind kind;
    int index;               /* building / tree / sphere index (0 for the ground) */
} pnpr_quality_hit;

/* First hit of the ray origin + t * dir (dir need not be unit: it is normalised; zero or
 * non-finite: no hit) with t in (0, t_max] (t_max <= 0 or non-finite = no limit), scene-local
 * coordinates. Returns 1 and fills r_hit (may be NULL) on a hit, else 0. */
int pnpr_quality_raycast(const pnpr_quality_scene *scene, const double origin[3], const double dir[3],
                         double t_max, pnpr_quality_hit *r_hit);

/* The colour of a scanned point (rgb, before per-point noise) at a local position on `kind`. */
void pnpr_quality_colour(const pnpr_quality_scene *scene, const pnpr_quality_hit *hit,
                         const double p[3], uint8_t r_rgb[3]);

/* ---- scanning ----------------------------------------------------------------------------- */

typedef struct pnpr_quality_scan_stats {
    size_t rays, points, per_kind[PNPR_QUALITY_UNSEEN + 1];
} pnpr_quality_scan_stats;

/* Scans the scene into r_cloud (freed first): world coordinates (origin chosen by
 * pnpr_cloud_set_world, exact doubles in src_xyz), rgb, has_viewpoint = the first scanner,
 * up_hint = +z. Deterministic for a given scene (seeded). label (optional, r_cloud->label when
 * want_labels): the pnpr_quality_kind of each point's hit. stats may be NULL. */
pnpr_status pnpr_quality_scan(const pnpr_quality_scene *scene, int want_labels, pnpr_cloud *r_cloud,
                              pnpr_quality_scan_stats *r_stats);

/* ---- images, views and figures ------------------------------------------------------------ */

/* An RGBA8 image, top row first (as pnpr_renderer_snapshot writes it); alpha is ignored. */
typedef struct pnpr_quality_image {
    const uint8_t *rgba;
    int width, height;
} pnpr_quality_image;

/* A camera as OpenGL matrices in world coordinates (column-major m[col * 4 + row], the layout of
 * pnpr_camera_matrices), for a width x height image. Perspective or orthographic. */
typedef struct pnpr_quality_view {
    double view[16], projection[16];
    int width, height;
} pnpr_quality_view;

typedef struct pnpr_quality_options {
    float radius_px;         /* "near": pixel centre within this many px of a sample; 0 = 2 */
    float step_px;           /* edge sampling step on screen; 0 = 0.5 */
    float ink_luminance;     /* ink pixel: luminance below this fraction of the background's; 0 = 0.5 */
    float depth_abs, depth_rel; /* a sample at distance d is visible when the first hit along its
                              * pixel ray is at >= d - (depth_abs + depth_rel * d); 0 = 0.05 m, 0.002 */
    int custom_background;   /* 0 = the background is white (255, 255, 255) */
    uint8_t background[3];
    float drawn_tolerance;   /* drawn pixel: some channel differs from the background by more than
                              * this (0..1); 0 = 0.02 */
    float ink_distance;      /* outline ink: Euclidean RGB distance (0..1 channels) to the ink colour
                              * at most this; 0 = 0.2 */
    float speckle_delta;     /* speckle: "differs strongly" = some channel differs by more (0..1); 0 = 0.25 */
    int open_margin_px;      /* open ground: at least this far (Chebyshev, px) from any pixel whose ray
                              * hits no ground; 0 = 10 */
} pnpr_quality_options;

/* Luminance of an RGBA8 pixel in [0,1]: Rec. 709 weights on the 8-bit values / 255. */
double pnpr_quality_luminance(const uint8_t *px);

/* World point -> pixel coordinates (x right, y down; pixel (i, j) covers [i, i+1) x [j, j+1)).
 * Returns 0 (and leaves x, y) when the point is behind the eye or the view is degenerate. */
int pnpr_quality_project(const pnpr_quality_view *view, const double world[3], double *r_x, double *r_y);

/* The view-dependent outlines of the scene seen through `view`: ground border (4 segments), each
 * trunk's two silhouette lines, each crown's and sphere's silhouette circle (the tangent circle
 * from the eye, as `circle_segments` chords; 0 = 256). Writes at most `cap` segments into r_seg
 * (may be NULL) and returns how many there are. */
size_t pnpr_quality_silhouettes(const pnpr_quality_scene *scene, const pnpr_quality_view *view,
                                int circle_segments, pnpr_quality_segment *r_seg, size_t cap);

/* The silhouette circle of one sphere (centre, radius in scene-local coordinates) through `view`
 * as `n` chords (n >= 3) into r_seg (n entries). PNPR_ERR_NUMERIC when the eye is inside it. */
pnpr_status pnpr_quality_circle(const pnpr_quality_view *view, const double offset[3],
                                const double centre[3], double radius, int n,
                                pnpr_quality_segment *r_seg);

typedef struct pnpr_quality_edge_figures {
    double coverage;         /* covered / visible samples (0 when there are none) */
    double precision;        /* ink pixels near a visible reference sample / ink pixels (0 when no ink) */
    size_t samples, visible_samples, covered_samples;
    size_t ink_pixels, ink_near;
} pnpr_quality_edge_figures;

/* Coverage of the `truth` segments and precision of the ink against truth + `extra` (scene-local
 * segments): each segment is sampled every step_px on screen; a sample counts when it is inside
 * the image and visible (first hit of the scene along its pixel ray within the depth tolerance);
 * a visible truth sample is covered when an ink pixel's centre lies within radius_px; an ink pixel
 * is near when its centre lies within radius_px of a visible truth or extra sample. */
pnpr_status pnpr_quality_edges(const pnpr_quality_scene *scene, const pnpr_quality_view *view,
                               const pnpr_quality_image *image, const pnpr_quality_segment *truth,
                               size_t truth_count, const pnpr_quality_segment *extra,
                               size_t extra_count, const pnpr_quality_options *opts,
                               pnpr_quality_edge_figures *r);

/* The line-drawing figures of a scene: coverage of its visible crease edges, precision against
 * creases + silhouettes (r_lines); and coverage of creases + silhouettes together (r_all, may be
 * NULL). */
pnpr_status pnpr_quality_line_figures(const pnpr_quality_scene *scene, const pnpr_quality_view *view,
                                      const pnpr_quality_image *image, const pnpr_quality_options *opts,
                                      pnpr_quality_edge_figures *r_lines, pnpr_quality_edge_figures *r_all);

/* Marks (sets to `value`) the pixels whose centre lies within radius_px of a visible sample of
 * the segments (r_mask: width * height bytes, top row first, not cleared first); returns the
 * number of visible samples. For pictures of the truth and for tests. */
size_t pnpr_quality_visible_mask(const pnpr_quality_scene *scene, const pnpr_quality_view *view,
                                 const pnpr_quality_segment *seg, size_t count,
                                 const pnpr_quality_options *opts, uint8_t value, uint8_t *r_mask);

/* Silhouette coverage of sphere `index` of the scene (occluded parts removed by ray casting). */
pnpr_status pnpr_quality_sphere_silhouette(const pnpr_quality_scene *scene, int index,
                                           const pnpr_quality_view *view, const pnpr_quality_image *image,
                                           const pnpr_quality_options *opts, pnpr_quality_edge_figures *r);

/* Drawn pixels (differing from the background) and, among them, those within ink_distance of
 * `ink_rgb`: r_fraction = ink / drawn (0 when nothing is drawn). r_drawn may be NULL. */
pnpr_status pnpr_quality_outline_ink(const pnpr_quality_image *image, const uint8_t ink_rgb[3],
                                     const pnpr_quality_options *opts, double *r_fraction,
                                     size_t *r_drawn);

/* Speckle: the fraction of drawn pixels that differ strongly (speckle_delta) from both their left
 * and right neighbours, or from both their upper and lower neighbours (at the image border the
 * one neighbour stands for both). 0 when nothing is drawn. */
pnpr_status pnpr_quality_speckle(const pnpr_quality_image *image, const pnpr_quality_options *opts,
                                 double *r_fraction);

typedef struct pnpr_quality_tone_figures {
    double ratio;            /* feature / max(flat, 1/255) */
    double feature_darkness; /* mean 1 - luminance of pixels within radius_px of visible crease samples */
    double flat_darkness;    /* mean 1 - luminance of open-ground pixels */
    size_t feature_pixels, flat_pixels;
} pnpr_quality_tone_figures;

/* Feature-to-flat ink ratio. Open ground: pixels whose centre ray first hits the ground at a
 * point some scanner sees (so that the scan has points there), more than open_margin_px
 * (Chebyshev) from any pixel whose ray hits an object or nothing (unseen ground does not count as
 * an object). PNPR_ERR_EMPTY when either set is empty. */
pnpr_status pnpr_quality_tone(const pnpr_quality_scene *scene, const pnpr_quality_view *view,
                              const pnpr_quality_image *image, const pnpr_quality_options *opts,
                              pnpr_quality_tone_figures *r);

/* The first-hit kind of every pixel's centre ray (width * height bytes, pnpr_quality_kind values,
 * top row first); ground pixels that no scanner sees (occlusion shadows, beyond the range or the
 * elevation window) get PNPR_QUALITY_UNSEEN when `scanned_only`. For the tone figure and tests. */
pnpr_status pnpr_quality_kind_image(const pnpr_quality_scene *scene, const pnpr_quality_view *view,
                                    int scanned_only, uint8_t *r_kind);

#ifdef __cplusplus
}
#endif
#endif
