/* pointnpr — props.h: the names of the per-point properties the library writes and reads, in one
 * place. Library, CLI and MeshLab code name a property only through these macros; the names are
 * part of the file formats (PLY/PCD property names), so they never change.
 *
 * Extra properties (pnpr_cloud.props, type as stored):
 *   PNPR_PROP_FEATURE_DEGREE      float  0..1, likelihood that the point lies on a feature
 *   PNPR_PROP_FEATURE_CLASS       uchar  PNPR_CLASS_* (features.h): none, non-directional,
 *                                        directional, dithering point
 *   PNPR_PROP_FEATURE_CONFIDENCE  float  0..1, how well neighbouring feature points fit a line
 *   PNPR_PROP_FEATURE_DIR_X/Y/Z   float  the feature's direction (directional points)
 *   PNPR_PROP_POINT_SPACING       float  the distance to the 4th nearest other point (the renderer's
 *                                        default spacing_k), unclamped: the feature stage writes it
 *                                        from its neighbour lists so that the upload needs no kNN
 *                                        of its own (pnpr_spacing_from_lists, knn.h); 0 = none
 *   PNPR_PROP_BRUSH_SIZE          float  stroke-based splatting: the splat size r + eps (brush.h)
 *   PNPR_PROP_BRUSH_CLUSTER       uint   stroke-based splatting: the colour cluster (brush.h)
 *   PNPR_PROP_INTENSITY           ushort LAS intensity (text clouds: as read)
 *   PNPR_PROP_CLASSIFICATION      uchar  LAS classification
 *   PNPR_PROP_SOURCE_INDEX        uint   a tile's point: its index in the whole file (tiles.h)
 *   PNPR_PROP_TILE_CORE           uchar  a tile's point: 1 in its core, 0 in its halo (tiles.h)
 *   PNPR_PROP_TILE_COMPONENT      uint   a components tile's point: its component in the tile (tiles.h)
 *
 * Segment labels (pnpr_cloud.label, uint) are written as PNPR_PROP_SEGMENT, or as
 * PNPR_PROP_LABEL when an extra property already uses that name; readers take either.
 *
 * MeshLab only: PNPR_PROP_FEATURE_DIR is the per-vertex Point3 attribute that holds the three
 * direction components together (the filter and decorator store classes and segments as float
 * attributes under the names above). */
#ifndef POINTNPR_PROPS_H
#define POINTNPR_PROPS_H

#define PNPR_PROP_FEATURE_DEGREE "feature_degree"
#define PNPR_PROP_FEATURE_CLASS "feature_class"
#define PNPR_PROP_FEATURE_CONFIDENCE "feature_confidence"
#define PNPR_PROP_FEATURE_DIR_X "feature_dir_x"
#define PNPR_PROP_FEATURE_DIR_Y "feature_dir_y"
#define PNPR_PROP_FEATURE_DIR_Z "feature_dir_z"
#define PNPR_PROP_FEATURE_DIR "feature_dir"
#define PNPR_PROP_POINT_SPACING "point_spacing"

#define PNPR_PROP_BRUSH_SIZE "brush_size"
#define PNPR_PROP_BRUSH_CLUSTER "brush_cluster"

#define PNPR_PROP_SEGMENT "segment"
#define PNPR_PROP_LABEL "label"
#define PNPR_PROP_SEG_RED "seg_red"     /* a segment's mean colour (pnpr_segment_add_colors) */
#define PNPR_PROP_SEG_GREEN "seg_green"
#define PNPR_PROP_SEG_BLUE "seg_blue"

#define PNPR_PROP_INTENSITY "intensity"
#define PNPR_PROP_CLASSIFICATION "classification"

#define PNPR_PROP_SOURCE_INDEX "source_index"
#define PNPR_PROP_TILE_CORE "tile_core"
#define PNPR_PROP_TILE_COMPONENT "tile_component"

#endif
