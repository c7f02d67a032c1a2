/* pointnpr — plan.h: the stage planner. From what an output draws (styles, outlines, profile
 * lines) and what the cloud already carries, it decides which analysis stages run and why. Every
 * host follows this one plan: `pointnpr render` and `lines` execute it, `pointnpr explain`
 * prints it, the MeshLab decorator computes what it says. docs/rendering.md, "The plan". */
#ifndef POINTNPR_PLAN_H
#define POINTNPR_PLAN_H

#include "cloud.h"
#include "style.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pnpr_plan_segments {
    PNPR_PLAN_SEGMENTS_NONE = 0, /* no output needs segments */
    PNPR_PLAN_SEGMENTS_INPUT,    /* the cloud's labels (cloud->label) are used as they are */
    PNPR_PLAN_SEGMENTS_JSEG,     /* 3D JSEG with its defaults (pnpr_segment_jseg) */
    PNPR_PLAN_SEGMENTS_SHADE     /* no colours to segment: flat bands of the light's tone instead */
} pnpr_plan_segments;

/* What the output draws. Zero = nothing (a valid, empty plan). */
typedef struct pnpr_plan_request {
    uint32_t styles;        /* one bit (1u << style) per style the frame draws (style maps: all) */
    pnpr_sketch_variant sketch_variant;
    int outline;            /* -1 off, 0 each style's default, 1 on (outlines use normals) */
    int lines;              /* profile lines wanted besides the lines style (`pointnpr lines`) */
    uint32_t want;          /* more PNPR_WANT_* bits asked by the command itself */
} pnpr_plan_request;

typedef struct pnpr_plan {
    uint32_t want;          /* PNPR_WANT_* bits pnpr_compute_features must compute (0: none) */
    uint32_t needed;        /* the bits the output needs, before what the cloud carries is taken off */
    const char *why[5];     /* why each bit is needed (index = bit number), NULL if not */
    int lines;              /* compute the profile lines */
    const char *lines_why;
    pnpr_plan_segments segments;
    const char *segments_why;
    int brush;              /* run pnpr_brush_prepare (brush.h): splat sizes, clusters, normals */
    const char *brush_why;
    int hierarchy;          /* build the sphere tree (hierarchy.h) for the hierarchy style */
    const char *hierarchy_why;
    int reused_features;    /* the cloud carries the feature outputs that are needed */
    int reused_normals;     /* the cloud carries normals */
} pnpr_plan;

/* The plan for `req` on `cloud` (NULL: a cloud of unknown content, planned as if it had colours
 * and nothing else). PNPR_ERR_INVALID_ARGUMENT for an unknown style bit or variant. */
PNPR_NODISCARD pnpr_status pnpr_plan_make(const pnpr_plan_request *req, const pnpr_cloud *cloud, pnpr_plan *r_plan);

/* Whether the cloud carries the outputs of the PNPR_WANT_* bits (normals of either kind, feature_degree,
 * feature_class + feature_dir_x/y/z; dithering points cannot be told apart from classes: a
 * cloud with classes counts as carrying them). */
int pnpr_plan_cloud_has(const pnpr_cloud *cloud, uint32_t want);

#ifdef __cplusplus
}
#endif
#endif
