/* pointnpr — view.h: how a scene stands, for a default view (GL-free, core library).
 *
 * pnpr_scene_frame looks at a cloud the way a person placing a camera would: where the content
 * is (robust bounds that ignore far outliers), which way is up (the user's choice, the format's
 * hint, else the dominant ground plane, else +z) and from where to look at it (from above the
 * ground, from the scanner's side when known, the wide side of the scene across the screen).
 * The camera built on it is pnpr_camera_default (camera.h). docs/view.md documents every
 * threshold and why.
 *
 * All positions are the cloud's float offsets (world = cloud->origin + offset); directions are
 * unit vectors, the same in both. Non-finite points are ignored. Deterministic: the same cloud
 * and options give the same result on every machine. */
#ifndef POINTNPR_VIEW_H
#define POINTNPR_VIEW_H

#include "cloud.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which way is up. */
typedef enum pnpr_up_mode {
    PNPR_UP_AUTO = 0, /* the format's hint, else the ground plane, else +z */
    PNPR_UP_POS_X,
    PNPR_UP_POS_Y,
    PNPR_UP_POS_Z,
    PNPR_UP_NEG_X,
    PNPR_UP_NEG_Y,
    PNPR_UP_NEG_Z,
    PNPR_UP_VECTOR,   /* pnpr_view_options.up (any finite non-zero vector) */
    PNPR_UP_MODE_COUNT_
} pnpr_up_mode;

/* How the up vector was decided. */
typedef enum pnpr_up_source {
    PNPR_UP_FROM_DEFAULT = 0, /* no evidence: +z (the legacy default) */
    PNPR_UP_FROM_HINT,        /* cloud->up_hint (e.g. LAS: +z) */
    PNPR_UP_FROM_PLANE,       /* the dominant plane with the content on one side (a ground) */
    PNPR_UP_FROM_USER         /* up_mode other than AUTO */
} pnpr_up_source;

/* Where the azimuth came from. */
typedef enum pnpr_azimuth_source {
    PNPR_AZIMUTH_FRONT = 0,   /* the legacy front (-y for z up), mapped into the up frame */
    PNPR_AZIMUTH_VIEWPOINT,   /* cloud->viewpoint (stored scanner position) */
    PNPR_AZIMUTH_ORIGIN       /* the world origin, a likely RGB-D camera position (docs/view.md) */
} pnpr_azimuth_source;

typedef struct pnpr_view_options {
    pnpr_up_mode up_mode;  /* 0 = AUTO */
    double up[3];          /* PNPR_UP_VECTOR only */
    size_t max_samples;    /* points analysed (a seeded uniform subsample); 0 = 200000 */
    uint64_t seed;         /* the subsample's and the plane search's generator; 0 = a fixed default */
} pnpr_view_options;

typedef struct pnpr_view_info {
    double up[3];                  /* unit; snapped to an axis when within 10 degrees of one */
    pnpr_up_source up_source;
    float lo[3], hi[3];            /* robust bounds (offsets) */
    size_t valid;                  /* points with finite offsets */
    size_t outliers;               /* far outliers (see docs/view.md), counted on every point */
    int has_ground;                /* a ground plane was found (and used when AUTO decided) */
    double ground_point[3];        /* a point of it (offsets, the inliers' centroid) */
    double ground_normal[3];       /* unit, towards the content side */
    double ground_fraction;        /* share of the analysed points on it */
    double view_dir[3];            /* unit, from the target towards the eye */
    double elevation_deg;          /* angle of view_dir above the ground (30..55) */
    pnpr_azimuth_source azimuth_source;
    double wide_axis[3];           /* unit horizontal principal axis (across the screen when the
                                    * scene is anisotropic: its spread > 1.25 x the other's) */
    double extent_up, extent_across, extent_depth; /* extents of the points inside the robust
                                    * bounds along up, the screen's horizontal and the horizontal
                                    * part of view_dir */
} pnpr_view_info;

/* Analyses the cloud. PNPR_ERR_EMPTY when it has no finite point; PNPR_ERR_INVALID_ARGUMENT
 * for NULL cloud/r_info, an unknown up_mode or a zero/non-finite up vector; PNPR_ERR_OUT_OF_MEMORY.
 * opts may be NULL (all defaults). */
PNPR_NODISCARD pnpr_status pnpr_scene_frame(const pnpr_cloud *cloud, const pnpr_view_options *opts,
                             pnpr_view_info *r_info);

/* Parses "auto", "x", "+x", "-x", ... "-z" (the CLI's --up) into r_mode; 0 if not one of them. */
int pnpr_up_mode_parse(const char *text, pnpr_up_mode *r_mode);
/* The unit vector of an axis mode (PNPR_UP_POS_X .. PNPR_UP_NEG_Z) into r_up; 0 (r_up untouched)
 * for AUTO, VECTOR and unknown modes. */
int pnpr_up_mode_axis(pnpr_up_mode mode, double r_up[3]);

#ifdef __cplusplus
}
#endif
#endif
