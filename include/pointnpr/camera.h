/* pointnpr — camera.h: look-at cameras of a point cloud and what is drawn through them without
 * GL. Pure CPU, in the core library `pointnpr` (view/camera.c, view/svg_lines.c,
 * view/svg_outline.c), so that a build without the renderer still has the default camera, the
 * camera files and paths (camera_path.h) and the SVG line drawings of `pointnpr lines --svg`.
 * render.h includes this header: the renderer takes these cameras (pnpr_renderer_draw,
 * pnpr_draw_options.matrices). */
#ifndef POINTNPR_CAMERA_H
#define POINTNPR_CAMERA_H

#include "cloud.h"
#include "polylines.h"
#include "style.h"
#include "view.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- camera --------------------------------------------------------------------------------- */

typedef struct pnpr_camera {
    double eye[3], target[3], up[3]; /* look-at in world coordinates (double) */
    float fov_y_deg;                 /* vertical field of view; 0 = 45 */
    float near_plane, far_plane;     /* 0 = automatic from the cloud's bounds (without its far
                                      * outliers: pnpr_cloud_inlier_bounds, which the far planes
                                      * then may clip) */
} pnpr_camera;

/* An explicit camera as OpenGL matrices (column-major, m[col * 4 + row], like glGetDoublev of
 * GL_MODELVIEW_MATRIX / GL_PROJECTION_MATRIX), both in double and in world coordinates: `view`
 * maps world positions (origin + offset) to eye space, `projection` eye space to clip space.
 * It covers what pnpr_camera cannot: off-centre frusta (glFrustum with l != -r, e.g. one tile of
 * a larger image) and orthographic projections (glOrtho). The renderer rebases the view on the
 * cloud's origin in double (view * translate(origin)) before converting to float, so large
 * origins keep their precision. Requirements (else PNPR_ERR_NUMERIC):
 *   - view: finite, affine (row 3 = 0 0 0 1), invertible upper 3x3; a uniform scale is allowed
 *     (MeshLab's trackball scales the scene): disk sizes follow it;
 *   - projection: finite, either perspective (row 3 = 0 0 -k 0 with k > 0, near plane > 0) or
 *     orthographic (row 3 = 0 0 0 k with k > 0), and projection[0], projection[5] != 0.
 * Point sizes: pixels per world unit at clip w = 1 = |projection[5]| * height / 2 * view scale
 * (perspective: divided by the eye depth as usual; orthographic: constant over the image).
 * Used through pnpr_draw_options.matrices. */
typedef struct pnpr_camera_matrices {
    double view[16];
    double projection[16];
} pnpr_camera_matrices;

/* The matrices of a look-at camera for a width x height frame, as the renderer builds them for
 * `cloud` (automatic near/far from its bounds when the camera leaves them at 0): drawing with
 * them through pnpr_draw_options.matrices gives the same frame as drawing with `camera`.
 * cloud may be NULL (then near/far must be set, or a default range is used). */
PNPR_NODISCARD pnpr_status pnpr_camera_matrices_from_camera(const pnpr_camera *camera, const pnpr_cloud *cloud,
                                             int width, int height, pnpr_camera_matrices *r_m,
                                             pnpr_error *err);

/* A camera that frames the cloud's finite bounding box (of the points that are not far outliers:
 * pnpr_cloud_inlier_bounds, outliers.h) from `dir` (world direction from the
 * target towards the eye; NULL = the default view (0, -1, 0.5), i.e. from the front, slightly
 * above, z up), with the vertical fov (0 = 45) and the image aspect width/height (0 = 1).
 * PNPR_ERR_EMPTY when the cloud has no finite point. */
PNPR_NODISCARD pnpr_status pnpr_camera_fit(const pnpr_cloud *cloud, const double dir[3], float fov_y_deg,
                            float aspect, pnpr_camera *r_camera);

/* The default camera (docs/view.md): looks along pnpr_scene_frame's suggested direction (from
 * above the detected ground, from the scanner's side when known, the wide side across the
 * screen) with its up vector, and frames the content inside the robust bounds as tightly as the
 * frustum allows (target centred on the projected extent, 5% margin on the tighter axis). When
 * the cloud has far outliers, near/far are set from the robust bounds so that the automatic
 * depth range does not stretch to them. fov_y_deg 0 = 45, aspect 0 = 1; opts may be NULL;
 * r_info (may be NULL) receives the analysis. PNPR_ERR_EMPTY without a finite point. */
PNPR_NODISCARD pnpr_status pnpr_camera_default(const pnpr_cloud *cloud, const pnpr_view_options *opts,
                                float fov_y_deg, float aspect, pnpr_camera *r_camera,
                                pnpr_view_info *r_info);

/* ---- SVG line drawings ---------------------------------------------------------------------- */

/* Profile lines (include/pointnpr/lines.h) as an SVG drawing through a camera. Hidden parts are
 * removed with a depth test against the occluder cloud (usually the scan the lines came from):
 * its points are splatted as disks of `point_radius` into a CPU depth buffer at the drawing's
 * resolution, and a stretch of line is drawn where it lies no deeper than the buffer plus
 * `depth_tolerance` (lines sit on the surface they were found on). */
typedef struct pnpr_svg_options {
    int width, height;      /* drawing size in px; 0 = 1024 x 768 */
    float stroke_width;     /* px; 0 = 1.5 */
    float taper;            /* 0..1: fraction of each stroke's length over which its two ends
                             * narrow to a point (drawn as filled outlines); 0 = plain strokes */
    const pnpr_cloud *occluders; /* NULL = nothing is hidden */
    float point_radius;     /* world units; 0 = the occluders' median nearest-neighbour distance */
    float depth_tolerance;  /* world units; 0 = 3 point radii */
    uint8_t stroke_rgb[3];  /* stroke colour; all 0 = black */
    uint8_t background_rgb[3]; int background; /* background != 0: fill the page with it */
    /* Outlines: the occluders' silhouettes and occluding contours as <path>s in their own group
     * <g id="outlines">, before the profile lines (docs/lines.md, "Outlines in the SVG"). Found
     * with the renderer's rules on a CPU surface buffer of the occluders (disks of 1.5 x the
     * distance to each point's 4th nearest neighbour; depth extents from cloud->normal when
     * present): sampling holes enclosed in 8 directions closed, a contour where the surface
     * behind lies more than `outline_jump` depth extents farther, each line moved inside its
     * near surface by the disks' overhang. Only what is visible is drawn. */
    int outline;            /* 0 = on when there are occluders, 1 = on, -1 = off (no occluders:
                             * no outlines either way) */
    float outline_width;    /* px; 0 = PNPR_SVG_OUTLINE_WIDTH */
    float outline_jump;     /* depth extents; 0 = PNPR_OUTLINE_JUMP (style.h) */
} pnpr_svg_options;

/* camera NULL = pnpr_camera_fit of the occluders (or of the lines when there are none).
 * Written to path + ".tmp" and renamed. PNPR_ERR_INVALID_ARGUMENT for a size outside 1..32768
 * or a negative / non-finite width, taper, radius, tolerance, outline width or jump. */
PNPR_NODISCARD pnpr_status pnpr_write_lines_svg(const char *path, const pnpr_polylines *lines,
                                 const pnpr_camera *camera, const pnpr_svg_options *opts,
                                 pnpr_error *err);

#ifdef __cplusplus
}
#endif
#endif
