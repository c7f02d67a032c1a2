/* pointnpr — MeshLab 2020.09 filter plugin (see filter_pointnpr.h, docs/meshlab.md).
 *
 * Data path: the current layer's live vertices -> pnpr_cloud (double origin = centre of the
 * finite bounding box, float offsets; colours when the layer has per-vertex colour; normals when
 * the layer has meaningful ones) -> pnpr_compute_features -> back into the layer: vertex quality
 * (feature degree), normals (when computed), per-vertex attributes feature_class (float),
 * feature_confidence (float), feature_dir (Point3f), optionally vertex colours by class.
 *
 * No C++ exception leaves applyFilter: everything runs inside one try block and failures come
 * back as errorMessage + false, which MeshLab shows to the user (GUI) or prints (meshlabserver). */
#include "filter_pointnpr.h"
#include "vcg_attributes.h"

#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <pointnpr/lines.h>
#include <pointnpr/lod.h>
#include <pointnpr/options.h>
#include <pointnpr/outliers.h>
#include <pointnpr/segment.h>
#include <pointnpr/style.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <new>
#include <string>
#include <typeinfo>
#include <vector>

#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>

/* Owns a pnpr_cloud for the duration of a call (freed on every path, exceptions included). */
struct CloudGuard {
    pnpr_cloud cloud;
    CloudGuard() { std::memset(&cloud, 0, sizeof cloud); }
    ~CloudGuard() { pnpr_cloud_free(&cloud); }
    CloudGuard(const CloudGuard &) = delete;
    CloudGuard &operator=(const CloudGuard &) = delete;
};

/* The current layer's live vertices as a pnpr_cloud: cloud point i is verts[i]; origin = centre
 * of the finite bounding box (double), float offsets (NaN/Inf vertices stay non-finite there:
 * every library call leaves them out). Shared by every filter. */
struct LayerCloud {
    std::vector<CMeshO::VertexPointer> verts;
    size_t finite = 0;
    bool hasColor = false;
    bool keepNormals = false; /* the layer's own normals were copied into the cloud */
    CloudGuard g;
};

/* pnpr_progress -> vcg::CallBackPos: the library reports a fraction per named stage; MeshLab
 * wants one percentage. A bridge owns the slice [lo, hi] of MeshLab's bar; with featureStages the
 * feature pipeline's stages are mapped to equal sub-slices in pipeline order (stages the run skips
 * just make the bar jump), otherwise each stage's fraction fills the slice. A host callback
 * returning false cancels the run. */
struct ProgressBridge {
    vcg::CallBackPos *cb;
    int lo, hi;
    bool featureStages;
    const char *prefix;
    int last_percent;
    std::string text;
};

namespace {
using pnpr_meshlab::findAttribute;

ProgressBridge makeBridge(vcg::CallBackPos *cb, int lo, int hi, bool featureStages, const char *prefix)
{
    ProgressBridge pb = {cb, lo, hi, featureStages, prefix, -1, std::string()};
    return pb;
}

int progressToMeshLab(void *user, const char *stage, double fraction)
{
    ProgressBridge *pb = static_cast<ProgressBridge *>(user);
    if (!pb || !pb->cb) return 0;
    if (!(fraction >= 0.0)) fraction = 0.0;
    if (fraction > 1.0) fraction = 1.0;
    double pos = fraction;
    if (pb->featureStages) {
        int index = PNPR_STAGE_COUNT_ - 1;
        for (int s = 0; s < PNPR_STAGE_COUNT_; s++) {
            if (stage && std::strcmp(stage, pnpr_stage_name(static_cast<pnpr_stage>(s))) == 0) {
                index = s;
                break;
            }
        }
        pos = (index + fraction) / PNPR_STAGE_COUNT_;
    }
    int percent = pb->lo + static_cast<int>((pb->hi - pb->lo) * pos);
    percent = std::min(std::max(percent, 0), 100);
    if (percent == pb->last_percent) return 0;
    pb->last_percent = percent;
    pb->text = std::string(pb->prefix) + ": " + (stage ? stage : "");
    return pb->cb(percent, pb->text.c_str()) ? 0 : 1;
}

pnpr_progress progressOf(ProgressBridge &pb)
{
    pnpr_progress p;
    p.fn = progressToMeshLab;
    p.user = &pb;
    return p;
}

const char *const kAttrClass = PNPR_PROP_FEATURE_CLASS;
const char *const kAttrConfidence = PNPR_PROP_FEATURE_CONFIDENCE;
const char *const kAttrDir = PNPR_PROP_FEATURE_DIR;

/* Class palette of "Colour points by class" (also documented in docs/meshlab.md). */
const unsigned char kPalette[4][3] = {
    {200, 200, 200}, /* 0 none: light grey */
    {40, 100, 230},  /* 1 non-directional feature: blue */
    {220, 30, 30},   /* 2 directional feature: red */
    {20, 20, 20},    /* 3 dithering point: near black */
};

/* A named per-vertex attribute of exactly type T: an attribute of that name but another type
 * (e.g. left by another plugin) would alias memory through vcglib's size-only lookup, so it is
 * replaced. */
template <class T>
typename CMeshO::template PerVertexAttributeHandle<T> attributeOfType(CMeshO &m, const char *name)
{
    CMeshO::PointerToAttribute key;
    key._name = name;
    auto it = m.vert_attr.find(key);
    if (it != m.vert_attr.end() && it->_type != std::type_index(typeid(T)))
        vcg::tri::Allocator<CMeshO>::DeletePerVertexAttribute(m, name);
    return vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<T>(m, name);
}


bool finite3(const Point3m &p)
{
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

/* MeshLab keeps vertex positions as float (MESHLAB_SCALAR=float): a layer loaded from doubles far
 * from the origin was rounded to the float step (ulp) at its coordinates' magnitude. The figures
 * of that rounding against the layer's point spacing as MeshLab holds it: the median distance
 * between distinct positions (rounding makes vertices coincide; 0 when fewer than 2 are left). */
struct FloatPrecision {
    double magnitude = 0; /* largest |coordinate| of a point that is not a far outlier */
    double ulp = 0;       /* the float step there */
    size_t distinct = 0;  /* distinct finite positions (counted when the quick test fires) */
    double spacing = 0;
    bool lossy = false;   /* spacing < kStepsPerSpacing * ulp */
};

/* A spacing of fewer float steps than this warns: positions are then off by up to ulp/2 = 1/16
 * of the spacing. Measured with the CLI on a rotated 51x51x51 grid cube whose coordinates were
 * rounded to a step of h/k (h the spacing): 526-535 of its 540 edge points are directional and
 * no face point is a feature for k >= 3, 520 at k = 2, 497 at k = 1.4, and 782 face points become
 * features at k = 0.7; the unit cube at 1e7 (k = 0.02) has none left. 8 warns with a margin of
 * 4 before the first measurable change. */
const double kStepsPerSpacing = 8.0;

using Pos = std::array<float, 3>;

/* The quick test samples at most kSlabSamples points; each scans at most kSlabScan points. */
const size_t kSlabSamples = 2048, kSlabScan = 4096;

/* Quick test on pts sorted along axis a: whether at least a quarter of a stride sample has a
 * distinct point closer than c, looked for in its slab |q[a] - p[a]| <= c (a slab that holds
 * none in its first kSlabScan points counts as none). At most kSlabSamples x kSlabScan
 * distances: on the lion scan (342k points) ~2 ms after the sort, which takes ~50 ms. */
bool someCloserThan(const std::vector<Pos> &pts, int a, double c)
{
    const size_t step = std::max<size_t>(1, pts.size() / kSlabSamples);
    size_t tested = 0, close = 0;
    for (size_t i = 0; i < pts.size(); i += step, tested++) {
        const Pos &p = pts[i];
        auto it = std::lower_bound(pts.begin(), pts.end(), static_cast<float>(p[a] - c),
                                   [a](const Pos &q, float v) { return q[a] < v; });
        for (size_t s = 0; it != pts.end() && (*it)[a] <= p[a] + c && s < kSlabScan; ++it, ++s) {
            double d2 = 0;
            for (int k = 0; k < 3; k++) d2 += (double((*it)[k]) - p[k]) * (double((*it)[k]) - p[k]);
            if (d2 > 0 && d2 < c * c) { close++; break; }
        }
    }
    return 4 * close >= tested;
}

FloatPrecision floatPrecision(const pnpr_cloud &cloud)
{
    FloatPrecision fp;
    float lo[3], hi[3];
    if (pnpr_cloud_inlier_bounds(&cloud, lo, hi) == 0) return fp; /* no finite point */
    int a = 0; /* the widest axis: the thinnest slabs */
    for (int c = 0; c < 3; c++) {
        fp.magnitude = std::max({fp.magnitude, std::fabs(cloud.origin[c] + lo[c]), std::fabs(cloud.origin[c] + hi[c])});
        if (hi[c] - lo[c] > hi[a] - lo[a]) a = c;
    }
    const float m = static_cast<float>(fp.magnitude);
    fp.ulp = static_cast<double>(std::nextafter(m, std::numeric_limits<float>::infinity())) - m;
    const double close = kStepsPerSpacing * fp.ulp;
    std::vector<Pos> pts;
    pts.reserve(cloud.count);
    for (size_t i = 0; i < cloud.count; i++) {
        const float *p = cloud.xyz + 3 * i;
        if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) pts.push_back({{p[0], p[1], p[2]}});
    }
    std::sort(pts.begin(), pts.end(), [a](const Pos &p, const Pos &q) { return p[a] < q[a]; });
    if (pts.size() < 2 || !someCloserThan(pts, a, close)) return fp; /* the usual case ends here */
    /* the figures: distinct positions only (the library's spacing looks for a distinct point among
     * 8 neighbours, which a layer rounded onto a few positions does not have) */
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    fp.distinct = pts.size();
    pnpr_kdtree *tree = nullptr;
    if (pts.size() < 2 || pnpr_kdtree_build(pts[0].data(), pts.size(), sizeof pts[0], &tree) != PNPR_OK)
        return fp; /* no verdict */
    fp.spacing = pnpr_kdtree_median_spacing(tree, 0);
    pnpr_kdtree_free(tree);
    fp.lossy = fp.spacing > 0 && fp.spacing < close;
    return fp;
}

} // namespace

FilterPointnprPlugin::FilterPointnprPlugin()
{
    typeList << FP_FEATURES << FP_SELECT_FEATURES << FP_PROFILE_LINES << FP_SEGMENT_JSEG << FP_SEGMENT_GROW << FP_LAYER_STYLE
             << FP_OPEN_SAMPLE;
    for (FilterIDType tt : types()) actionList << new QAction(filterName(tt), this);
}

QString FilterPointnprPlugin::pluginName() const
{
    return "FilterPointnpr";
}

QString FilterPointnprPlugin::filterName(FilterIDType filter) const
{
    switch (filter) {
    case FP_FEATURES: return "NPR: Compute feature degree and classify points";
    case FP_SELECT_FEATURES: return "NPR: Select feature points";
    case FP_PROFILE_LINES: return "NPR: Profile lines";
    case FP_SEGMENT_JSEG: return "NPR: Segment (JSEG)";
    case FP_SEGMENT_GROW: return "NPR: Segment (connected components / colour region growing)";
    case FP_LAYER_STYLE: return "NPR: Set layer style";
    case FP_OPEN_SAMPLE: return "NPR: Open a sample of a large PLY";
    default: return QString();
    }
}

QString FilterPointnprPlugin::filterInfo(FilterIDType filter) const
{
    switch (filter) {
    case FP_FEATURES:
        return "PointWorks feature analysis of the current layer's vertices (pointnpr " PNPR_VERSION_STRING
               "): PCA normals over the k nearest neighbours, a <i>feature degree</i> in [0,1] from the "
               "variation of the plane-fit error and the colour gradient, classification of feature points "
               "into <i>directional</i> (on a line, e.g. a crease) and <i>non-directional</i> points, and "
               "<i>dithering points</i> chosen among the others by error diffusion of the tone.<br>"
               "Results: <b>vertex quality</b> = feature degree (use the quality colouring, histogram and "
               "selection filters on it); per-vertex attributes <b>feature_class</b> (float: 0 none, "
               "1 non-directional, 2 directional, 3 dithering), <b>feature_confidence</b> (float, line-fit "
               "confidence) and <b>feature_dir</b> (Point3f, line direction); vertex normals when they are "
               "computed. To keep the attributes in a PLY file, tick them (V(f)/V(3f)) in the save dialog.<br>"
               "A layer with faces is analysed through its vertices only (faces are left unchanged).<br>"
               "See: <i>Hui Xu, Nathan Gossett, Baoquan Chen</i>, <b>\"Abstraction and Depiction of Sparsely "
               "Scanned Outdoor Environments\"</b> (PointWorks).";
    case FP_SELECT_FEATURES:
        return "Selects the vertices of the current layer whose <b>feature_class</b> attribute (computed by "
               "<i>NPR: Compute feature degree and classify points</i>) is the chosen class: directional or "
               "non-directional feature points, any feature point, or dithering points.";
    case FP_PROFILE_LINES:
        return "PointWorks <i>profile lines</i> of the current layer: the directional feature points are linked "
               "into a neighbour graph, shifted onto the feature, merged, connected by a minimum spanning forest "
               "that prefers edges along the feature direction, split into chains (short spurs dropped, chain "
               "ends joined at corners), fitted with cubic B-splines and sampled into polylines.<br>"
               "The feature classes and directions come from the layer's <b>feature_class</b>/<b>feature_dir</b> "
               "attributes (<i>NPR: Compute feature degree and classify points</i>); a layer without them is "
               "analysed first with the k/threshold/confidence below (the layer itself is left unchanged).<br>"
               "Result: a <b>new polyline layer</b> (vertices + edges, no faces) named after the source layer, "
               "with the source layer's transformation. Save it as OBJ (polylines become <tt>l</tt> lines; "
               "PLY export drops edges). No layer is added when there are no lines.<br>"
               "See: <i>Hui Xu, Nathan Gossett, Baoquan Chen</i>, <b>\"Abstraction and Depiction of Sparsely "
               "Scanned Outdoor Environments\"</b> (PointWorks), section 5.2.";
    case FP_SEGMENT_JSEG:
        return "3D JSEG colour segmentation of the current layer (needs per-vertex colour): colours quantised "
               "in CIE L*a*b*, a local J value (class separation) per point over its neighbours, seed regions "
               "of low J grown in J order, similar and small regions merged. Optionally a level of the region "
               "hierarchy (HSI colour distance with the size rule) cut at a segment count or threshold.<br>"
               "Result: per-vertex attribute <b>segment</b> (float label 0..S-1; -1 for NaN/Inf vertices); "
               "optionally vertex colours = segment mean colour (on by default) and vertex quality = label.<br>"
               "See: <i>Ming-Te Chi, Tong-Yee Lee</i>, <b>\"Stylized and Abstract Painterly Rendering System "
               "Using a Multiscale Segmented Sphere Hierarchy\"</b>, section 3.2.";
    case FP_SEGMENT_GROW:
        return "Segments the current layer by <b>connected components</b> (points closer than a distance are "
               "connected; geometry only) or by <b>colour region growing</b> (a neighbour joins a region when "
               "its colour is close; adjacent regions of similar mean colour merge; needs per-vertex colour).<br>"
               "Result: per-vertex attribute <b>segment</b> (float label 0..S-1; -1 for NaN/Inf vertices); "
               "optionally vertex colours by segment (mean colour, or a distinct colour per segment for a layer "
               "without colours) and vertex quality = label.";
    case FP_LAYER_STYLE:
        return "Gives the current layer its own style in the <b>NPR render</b> decoration (Render menu): e.g. a "
               "building in <i>cartoon</i> and the trees around it in <i>sketchy</i>, one picture with one "
               "visibility. <i>The decoration's Style</i> returns the layer to the decoration's own Style "
               "parameter. The choice is kept with the layer (a per-mesh attribute) for this session; it "
               "changes nothing else in the layer.";
    case FP_OPEN_SAMPLE:
        return "Opens a <b>uniform sample</b> of a binary PLY too large for MeshLab's memory as a <b>new layer</b>: "
               "about the asked number of points, each kept by a hash of its place in the file (the same points "
               "at every run). A file ordered for drawing (<tt>pointnpr convert IN.ply -o OUT.ply --lod</tt>) is "
               "read only where the sample lies; another binary PLY takes a pass over its coordinates first. "
               "Positions, normals and colours are kept, and the feature properties of <tt>pointnpr features</tt> "
               "become vertex quality and the attributes the other NPR filters and the NPR render decoration "
               "read.<br>See docs/tiles.md, \"A file ordered for drawing\".";
    default: return QString();
    }
}

MeshFilterInterface::FilterClass FilterPointnprPlugin::getClass(QAction *a)
{
    if (ID(a) == FP_SELECT_FEATURES)
        return FilterClass(MeshFilterInterface::PointSet | MeshFilterInterface::Selection);
    return MeshFilterInterface::PointSet;
}

MeshFilterInterface::FILTER_ARITY FilterPointnprPlugin::filterArity(QAction *a) const
{
    return ID(a) == FP_OPEN_SAMPLE ? NONE : SINGLE_MESH; /* it opens a layer of its own */
}

int FilterPointnprPlugin::getPreConditions(QAction *) const
{
    return MeshModel::MM_NONE; /* vertex count and attributes are checked with clear messages */
}

int FilterPointnprPlugin::postCondition(QAction *a) const
{
    if (ID(a) == FP_SELECT_FEATURES) return MeshModel::MM_VERTFLAGSELECT;
    if (ID(a) == FP_PROFILE_LINES || ID(a) == FP_LAYER_STYLE || ID(a) == FP_OPEN_SAMPLE)
        return MeshModel::MM_NONE; /* a new layer / an attribute */
    if (ID(a) == FP_SEGMENT_JSEG || ID(a) == FP_SEGMENT_GROW)
        return MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR;
    return MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTNORMAL | MeshModel::MM_VERTCOLOR;
}

namespace {
/* Every default and range the dialogs show comes from the library's options tables (options.h):
 * no numeric default or range of these options is written in this file. */
typedef const pnpr_option_desc *(*OptionTable)(size_t *);

const pnpr_option_desc *optionOf(OptionTable table, const char *name)
{
    size_t n = 0;
    const pnpr_option_desc *t = table(&n);
    return pnpr_option_find(t, n, name);
}

/* "in 1..1024", "> 0" */
QString rangeOf(OptionTable table, const char *name)
{
    char buf[64];
    pnpr_option_range_text(optionOf(table, name), buf, sizeof buf);
    return QString::fromUtf8(buf);
}

/* "16", "3h", "max(k, points / 1000)" */
QString defaultOf(OptionTable table, const char *name)
{
    char buf[64];
    pnpr_option_default_text(optionOf(table, name), buf, sizeof buf);
    return QString::fromUtf8(buf);
}

/* A dialog parameter and the option it sets (the option's CLI name in the table). */
struct DialogLabel {
    const char *option;
    const char *label;
};

/* The dialogs show each default as a value, so there 0 stands for itself (refused where the range
 * excludes it) unless the default is computed from the data (0 = automatic / none). Checks opts
 * against the table's ranges; false with "the seed factor must be > 0 (got 0)" in why. */
bool dialogOptionsOk(OptionTable table, const void *opts, const DialogLabel *labels, size_t count, QString &why)
{
    size_t n = 0;
    const pnpr_option_desc *t = table(&n);
    for (size_t i = 0; i < count; i++) {
        const pnpr_option_desc *d = pnpr_option_find(t, n, labels[i].option);
        const double v = pnpr_option_get(d, opts);
        if ((v == 0 && d->def == 0) || (v < 0 && (d->flags & PNPR_OPTION_NEGATIVE_OFF)) || pnpr_option_in_range(d, v))
            continue;
        why = QString("%1 must be %2 (got %3)").arg(labels[i].label).arg(rangeOf(table, d->name)).arg(v);
        return false;
    }
    pnpr_error err;
    std::memset(&err, 0, sizeof err);
    if (pnpr_option_check(t, n, opts, &err) == PNPR_OK) return true;
    why = QString::fromUtf8(err.message);
    return false;
}

const DialogLabel kFeatureLabels[] = {{"k", "k"}, {"threshold", "the feature threshold"},
                                      {"confidence", "the directional confidence"}, {"dither-scale", "the dither scale"}};
const DialogLabel kLinesLabels[] = {{"spacing", "the sample spacing"}, {"radius", "the neighbourhood radius"},
                                    {"merge-tol", "the merge tolerance"}, {"min-length", "the minimum line length"},
                                    {"direction-weight", "the direction weight"},
                                    {"shift-iterations", "the noise-reducing shifts"}};
const DialogLabel kJsegLabels[] = {{"classes", "the colour classes"}, {"k", "k"}, {"radius", "the neighbourhood radius"},
                                   {"seed-factor", "the seed factor"}, {"min-size", "the minimum segment size"},
                                   {"quant-distance", "the class merge distance"},
                                   {"merge-distance", "the region merge distance"}};
const DialogLabel kGrowLabels[] = {{"k", "k"}, {"radius", "the neighbour distance"},
                                   {"point-distance", "the point colour distance"},
                                   {"region-distance", "the region merge distance"},
                                   {"min-size", "the minimum segment size"}};
const DialogLabel kComponentsLabels[] = {{"radius", "the neighbour distance"}, {"min-size", "the minimum segment size"}};
#define LABELS(a) a, sizeof(a) / sizeof((a)[0])

/* An integer parameter into an unsigned option; false when it is negative. */
bool uintParam(const RichParameterList &par, const char *name, uint32_t &r)
{
    const int v = par.getInt(name);
    if (v < 0) return false;
    r = static_cast<uint32_t>(v);
    return true;
}

void featureParameters(RichParameterList &par)
{
    const pnpr_features_options fd = pnpr_features_defaults();
    const OptionTable F = pnpr_features_option_table;
    par.addParam(RichInt("k", static_cast<int>(fd.k), "Neighbours (k)",
                         QString("Number of nearest neighbours of each point (the point itself included), %1. "
                                 "The default suits typical scans; raise it for noisy scans. Clamped to the number "
                                 "of points.").arg(rangeOf(F, "k"))));
    par.addParam(RichFloat("threshold", fd.threshold, "Feature threshold",
                           QString("Feature-degree threshold %1 above which a point is a feature point. "
                                   "0 = automatic (Otsu split of the degree histogram, never below 0.15).")
                               .arg(rangeOf(F, "threshold"))));
    par.addParam(RichFloat("weightGeometry", fd.weight_geometry, "Geometry weight",
                           "Weight of the geometric term (variation of the plane-fit error: creases, corners). "
                           "The two weights are normalised to sum 1."));
    par.addParam(RichFloat("weightColor", fd.weight_color, "Colour weight",
                           "Weight of the colour term (colour gradient across the neighbourhood). Ignored "
                           "(geometry only) when the layer has no per-vertex colour."));
    par.addParam(RichFloat("directionConfidence", fd.direction_confidence, "Directional confidence",
                           QString("Minimum line-fit confidence %1 for a feature point to be directional "
                                   "(class 2); below it the point is non-directional (class 1).")
                               .arg(rangeOf(F, "confidence"))));
    par.addParam(RichFloat("ditherScale", fd.dither_scale, "Dither scale",
                           QString("Multiplies the tone (darkness from the colour, else from the normal lit from +z) "
                                   "before dithering: more or fewer dithering points (class 3), %1.")
                               .arg(rangeOf(F, "dither-scale"))));
}

void linesParameters(RichParameterList &par)
{
    const pnpr_lines_options ld = pnpr_lines_defaults();
    const pnpr_features_options fd = pnpr_features_defaults();
    const OptionTable L = pnpr_lines_option_table, F = pnpr_features_option_table;
    par.addParam(RichFloat("spacing", ld.spacing, "Sample spacing h",
                           "Sample spacing h of the directional points, in the layer's units. 0 = automatic "
                           "(median nearest-neighbour distance among the directional points). The defaults "
                           "below are multiples of h."));
    par.addParam(RichFloat("radius", ld.connect_radius, "Neighbourhood radius",
                           QString("Directional points closer than this are linked in the graph. 0 = %1. Larger "
                                   "values bridge gaps in sparse scans but may link neighbouring parallel creases.")
                               .arg(defaultOf(L, "radius"))));
    par.addParam(RichFloat("mergeTolerance", ld.merge_tol, "Merge tolerance",
                           QString("Shifted points closer than this are merged into one node. 0 = %1.")
                               .arg(defaultOf(L, "merge-tol"))));
    par.addParam(RichFloat("minLength", ld.min_length, "Minimum line length",
                           QString("Spurs and isolated lines shorter than this are dropped. 0 = %1; raise it to keep "
                                   "only long profile lines.").arg(defaultOf(L, "min-length"))));
    par.addParam(RichFloat("directionWeight", ld.direction_weight, "Direction weight",
                           QString("How much more an edge costs when it crosses the points' feature directions "
                                   "instead of following them (beta in the edge weight; %1, default %2). Higher "
                                   "values follow the creases more strictly.")
                               .arg(rangeOf(L, "direction-weight")).arg(defaultOf(L, "direction-weight"))));
    par.addParam(RichInt("shiftIterations", ld.shift_iterations, "Noise-reducing shifts",
                         QString("Iterations that move every directional point towards its neighbours across "
                                 "the feature (0 = none, at most %1).").arg(optionOf(L, "shift-iterations")->max)));
    par.addParam(RichBool("corners", true, "Join at corners",
                          "Join line ends that point at a common corner (and bridge small gaps). Off: lines "
                          "stop short of corners."));
    par.addParam(RichBool("recomputeFeatures", false, "Recompute features",
                          "Always run the feature analysis (with the three parameters below) instead of using "
                          "the layer's feature_class/feature_dir attributes. Layers without those attributes "
                          "are analysed anyway; the layer itself is never changed by this filter."));
    par.addParam(RichInt("k", static_cast<int>(fd.k), "Neighbours (k)",
                         QString("Feature analysis (when it runs): nearest neighbours of each point, %1.")
                             .arg(rangeOf(F, "k"))));
    par.addParam(RichFloat("threshold", fd.threshold, "Feature threshold",
                           QString("Feature analysis (when it runs): feature-degree threshold %1; 0 = automatic.")
                               .arg(rangeOf(F, "threshold"))));
    par.addParam(RichFloat("directionConfidence", fd.direction_confidence, "Directional confidence",
                           QString("Feature analysis (when it runs): minimum line-fit confidence %1 of a "
                                   "directional point.").arg(rangeOf(F, "confidence"))));
}

void labelToQualityParameter(RichParameterList &par)
{
    par.addParam(RichBool("labelToQuality", false, "Label to vertex quality",
                          "Also store the segment label in the vertex quality (overwriting e.g. the feature "
                          "degree): then 'Select by Vertex Quality' selects segments and meshlabserver's "
                          "'-m vq' saves the labels."));
}

void jsegParameters(RichParameterList &par)
{
    const pnpr_jseg_options jd = pnpr_jseg_defaults();
    const OptionTable J = pnpr_jseg_option_table;
    par.addParam(RichInt("segments", 0, "Segment count (hierarchy)",
                         "> 0: cut the region hierarchy (HSI colour distance, size rule) of the JSEG regions at "
                         "this many segments (fewer when JSEG found fewer). 0 = the JSEG regions as they are."));
    par.addParam(RichFloat("hierarchyThreshold", 0.0f, "Hierarchy threshold",
                           "> 0: cut the region hierarchy where the HSI colour distance of a merge exceeds this "
                           "(0..~1.5; e.g. 0.1). Combined with the segment count, the coarser limit wins. "
                           "0 = no threshold."));
    par.addParam(RichInt("classes", static_cast<int>(jd.classes), "Colour classes",
                         QString("k-means colour classes of the quantiser (%1) before close class centres merge.")
                             .arg(rangeOf(J, "classes"))));
    par.addParam(RichFloat("quantDistance", jd.quant_distance, "Class merge distance",
                           "Class centres closer than this CIE76 colour difference (delta E) become one class. "
                           "0 = never merge classes."));
    par.addParam(RichInt("k", static_cast<int>(jd.k), "Neighbours (k)",
                         QString("J neighbourhood: the k nearest points (the point included), %1.").arg(rangeOf(J, "k"))));
    par.addParam(RichFloat("radius", jd.radius, "Neighbourhood radius",
                           "> 0: the J neighbourhood keeps only those of the k nearest within this distance "
                           "(layer units). 0 = no radius limit."));
    par.addParam(RichFloat("seedFactor", jd.seed_factor, "Seed factor",
                           QString("Seed points are those with J <= factor x mean J (%1; smaller: fewer, more "
                                   "uniform seeds, fewer segments).").arg(rangeOf(J, "seed-factor"))));
    par.addParam(RichFloat("mergeDistance", jd.merge_distance, "Region merge distance",
                           "Adjacent regions whose mean colours differ by less (CIE76 delta E) merge. "
                           "0 = no colour merge."));
    par.addParam(RichInt("minSize", static_cast<int>(jd.min_size), "Minimum segment size",
                         QString("Regions with fewer points merge into the closest-coloured neighbour. "
                                 "0 = automatic (%1).").arg(defaultOf(J, "min-size"))));
    par.addParam(RichBool("colorBySegment", true, "Colour vertices by segment",
                          "OVERWRITES the vertex colours with each segment's mean colour (the flat-shaded look "
                          "artists want to see; on by default). Off: only the 'segment' attribute is written."));
    labelToQualityParameter(par);
}

void growParameters(RichParameterList &par)
{
    const pnpr_rgbgrow_options rd = pnpr_rgbgrow_defaults();
    const OptionTable R = pnpr_rgbgrow_option_table;
    par.addParam(RichEnum("method", 0, QStringList() << "Connected components" << "Colour region growing",
                          "Method", "Connected components: geometry only (points closer than the distance "
                          "are connected). Colour region growing: neighbours of similar colour join a region "
                          "(needs per-vertex colour)."));
    par.addParam(RichFloat("distance", rd.distance, "Neighbour distance",
                           QString("Points farther apart than this are never connected (layer units). 0 = %1.")
                               .arg(defaultOf(R, "radius"))));
    par.addParam(RichInt("minSize", static_cast<int>(rd.min_size), "Minimum segment size",
                         "Components: smaller components join the component of their nearest point in a kept "
                         "one (1 = keep all). Region growing: smaller regions merge into the closest-coloured "
                         "neighbour."));
    par.addParam(RichInt("k", static_cast<int>(rd.k), "Neighbours (k)",
                         QString("Region growing: neighbours considered per point, %1 (components use all points "
                                 "within the distance).").arg(rangeOf(R, "k"))));
    par.addParam(RichFloat("pointColorDistance", rd.point_distance, "Point colour distance",
                           QString("Region growing: a neighbour joins when its RGB colour differs from the point's "
                                   "by less than this (Euclidean, 0..255 units; %1).").arg(rangeOf(R, "point-distance"))));
    par.addParam(RichFloat("regionColorDistance", rd.region_distance, "Region merge distance",
                           "Region growing: adjacent regions whose mean colours differ less (CIE76 delta E) "
                           "merge. 0 = no merge."));
    par.addParam(RichBool("colorBySegment", false, "Colour vertices by segment",
                          "OVERWRITES the vertex colours: each segment's mean colour, or for a layer without "
                          "colours a distinct colour per segment. Off: only the 'segment' attribute is written."));
    labelToQualityParameter(par);
}
} // namespace

void FilterPointnprPlugin::initParameterSet(QAction *a, MeshModel &m, RichParameterList &par)
{
    switch (ID(a)) {
    case FP_FEATURES:
        featureParameters(par);
        par.addParam(RichBool("recomputeNormals", false, "Recompute normals",
                              "Always estimate new normals (PCA over the k neighbours) and write them into the layer. "
                              "When off, the layer's normals are kept if they are meaningful (almost all finite and "
                              "non-zero); layers without normals (all zero, e.g. a plain point cloud) get computed "
                              "normals written back."));
        par.addParam(RichBool("useViewpoint", false, "Orient towards viewpoint",
                              "Orient computed normals towards the viewpoint below (e.g. the scanner position). "
                              "Off: consistent orientation by propagation over the neighbour graph."));
        par.addParam(RichPoint3f("viewpoint", vcg::Point3f(0, 0, 0), "Viewpoint",
                                 "Viewpoint in scene (world) coordinates, used when 'Orient towards viewpoint' is on; "
                                 "the layer transformation is taken into account."));
        par.addParam(RichBool("colorByClass", false, "Colour points by class",
                              "OVERWRITES the layer's vertex colours with a class palette: grey none, blue "
                              "non-directional, red directional, black dithering. Off: colours are left unchanged "
                              "(use the quality or attribute colouring filters instead)."));
        break;
    case FP_SELECT_FEATURES:
        par.addParam(RichEnum("featureClass", 0,
                              QStringList() << "Directional feature points" << "Non-directional feature points"
                                            << "Any feature point" << "Dithering points",
                              "Class", "Which vertices to select, from the feature_class attribute: directional "
                              "(2), non-directional (1), any feature point (1 or 2), dithering points (3)."));
        par.addParam(RichBool("addToSelection", false, "Add to current selection",
                              "Keep the current vertex selection and add the class to it; off: replace it."));
        break;
    case FP_PROFILE_LINES: linesParameters(par); break;
    case FP_SEGMENT_JSEG: jsegParameters(par); break;
    case FP_SEGMENT_GROW: growParameters(par); break;
    case FP_LAYER_STYLE: {
        /* the library's styles, in its order (index + 1), after "the decoration's Style" */
        QStringList names("The decoration's Style");
        for (int st = 0; st < (int)PNPR_STYLE_COUNT_; st++) names << pnpr_style_name((pnpr_style)st);
        int current = -1;
        if (!pnpr_meshlab::layerStyle(m.cm, current) || current >= (int)PNPR_STYLE_COUNT_) current = -1;
        par.addParam(RichEnum("style", current + 1, names, "Style",
                              "This layer's style in the NPR render decoration; the first entry: the decoration's "
                              "Style parameter."));
        break;
    }
    case FP_OPEN_SAMPLE:
        par.addParam(RichOpenFile("file", QString(), QStringList() << "*.ply", "PLY file",
                                  "A binary PLY (what pointnpr writes), best ordered for drawing "
                                  "(pointnpr convert IN.ply -o OUT.ply --lod)."));
        par.addParam(RichInt("points", PNPR_LOD_SAMPLE_POINTS, "Points",
                             "About this many points of the file are opened (all of them when it has no more)."));
        break;
    default: break;
    }
}

bool FilterPointnprPlugin::fail(const QString &message)
{
    errorMessage = message;
    Log(qUtf8Printable("pointnpr: " + message));
    return false;
}

bool FilterPointnprPlugin::applyFilter(QAction *a, MeshDocument &md, const RichParameterList &par,
                                       vcg::CallBackPos *cb)
{
    errorMessage.clear();
    try {
        switch (ID(a)) {
        case FP_FEATURES: return computeFeatures(md, par, cb);
        case FP_SELECT_FEATURES: return selectFeatures(md, par);
        case FP_PROFILE_LINES: return profileLines(md, par, cb);
        case FP_SEGMENT_JSEG: return segment(md, par, cb, true);
        case FP_SEGMENT_GROW: return segment(md, par, cb, false);
        case FP_LAYER_STYLE: return layerStyle(md, par);
        case FP_OPEN_SAMPLE: return openSample(md, par, cb);
        default: return fail("unknown filter");
        }
    } catch (const std::bad_alloc &) {
        return fail("out of memory");
    } catch (const std::exception &e) {
        return fail(QString("internal error: ") + e.what());
    } catch (...) {
        return fail("internal error (unknown exception)");
    }
}

/* ---- shared helpers ---------------------------------------------------------------------- */

bool FilterPointnprPlugin::loadLayerCloud(MeshModel &mm, bool withColor, bool withLayerNormals, const char *what,
                                          const char *leftOutNote, LayerCloud &lc)
{
    CMeshO &m = mm.cm;
    const QString layer = mm.label();

    /* ---- live vertices, the finite ones counted ---- */
    lc.verts.clear();
    lc.verts.reserve(m.vert.size());
    for (CMeshO::VertexIterator vi = m.vert.begin(); vi != m.vert.end(); ++vi)
        if (!vi->IsD()) lc.verts.push_back(&*vi);
    const size_t n = lc.verts.size();
    if (n == 0) return fail(QString("layer '%1' has no vertices: nothing to analyse").arg(layer));
    if (m.fn > 0)
        Log("pointnpr: layer '%s' is a mesh with %d faces: the %s use its %zu vertices only; faces are "
            "left unchanged", qUtf8Printable(layer), m.fn, what, n);

    size_t finite = 0;
    for (CMeshO::VertexPointer v : lc.verts) finite += finite3(v->cP());
    lc.finite = finite;
    if (finite == 0)
        return fail(QString("layer '%1': none of its %2 vertices has finite coordinates").arg(layer).arg(n));
    if (finite < n)
        Log("pointnpr: %zu of %zu vertices have NaN/Inf coordinates: they are left out (%s)", n - finite, n,
            leftOutNote);

    /* ---- the cloud: the library's robust origin (pnpr_cloud_set_world: the bbox centre of the
     * points that are not far outliers), float offsets ---- */
    pnpr_cloud &cloud = lc.g.cloud;
    pnpr_status st = pnpr_cloud_alloc(&cloud, n);
    if (st != PNPR_OK) return fail(QString("cannot allocate the cloud: %1").arg(pnpr_status_string(st)));
    {
        std::vector<double> world(3 * n);
        for (size_t i = 0; i < n; i++) {
            const Point3m &p = lc.verts[i]->cP();
            for (int c = 0; c < 3; c++) world[3 * i + c] = static_cast<double>(p[c]);
        }
        if ((st = pnpr_cloud_set_world(&cloud, world.data())) != PNPR_OK)
            return fail(QString("cannot place the cloud: %1").arg(pnpr_status_string(st)));
    }
    cloud.src_coord_type = PNPR_TYPE_FLOAT32;
    const FloatPrecision fp = floatPrecision(cloud);
    if (fp.lossy)
        Log(GLLogStream::WARNING,
            "pointnpr: WARNING: layer '%s' lies up to %.9g from the origin, where MeshLab's float coordinates "
            "step by %.3g; its %zu points sit on %zu distinct positions, a median %.3g apart (%.3g times the "
            "step): MeshLab keeps positions only to that step (finer coordinates in the file were rounded "
            "when it was loaded), so the %s are unreliable. Moving the layer now (Filters > Normals, "
            "Curvatures and Orientation > Transform: Translate, Center, set Origin) cannot restore them: "
            "move the data near the origin before MeshLab loads it, or run the pointnpr command on the file "
            "(it keeps double coordinates)",
            qUtf8Printable(layer), fp.magnitude, fp.ulp, finite, fp.distinct, fp.spacing, fp.spacing / fp.ulp, what);
    lc.hasColor = withColor && mm.hasDataMask(MeshModel::MM_VERTCOLOR);
    if (lc.hasColor) {
        if ((st = pnpr_cloud_alloc_rgb(&cloud)) != PNPR_OK)
            return fail(QString("cannot allocate colours: %1").arg(pnpr_status_string(st)));
        for (size_t i = 0; i < n; i++) {
            const vcg::Color4b &col = lc.verts[i]->cC();
            for (int c = 0; c < 3; c++) cloud.rgb[3 * i + c] = col[c];
        }
    }

    /* Normals: kept (normalised) when the layer has them and they are meaningful: at least 99% of
     * the finite vertices carry a finite non-zero normal (MeshLab's normals of meshes are
     * area/angle-weighted sums, not unit length); else the library computes them. */
    lc.keepNormals = false;
    if (withLayerNormals && mm.hasDataMask(MeshModel::MM_VERTNORMAL)) {
        size_t good = 0;
        for (CMeshO::VertexPointer v : lc.verts) {
            if (!finite3(v->cP())) continue;
            const Point3m &nn = v->cN();
            const double len = std::sqrt(double(nn[0]) * nn[0] + double(nn[1]) * nn[1] + double(nn[2]) * nn[2]);
            good += (std::isfinite(len) && len > 1e-12);
        }
        lc.keepNormals = good > 0 && good >= finite - finite / 100;
    }
    if (lc.keepNormals) {
        if ((st = pnpr_cloud_alloc_normals(&cloud)) != PNPR_OK)
            return fail(QString("cannot allocate normals: %1").arg(pnpr_status_string(st)));
        for (size_t i = 0; i < n; i++) {
            const Point3m &nn = lc.verts[i]->cN();
            const double len = std::sqrt(double(nn[0]) * nn[0] + double(nn[1]) * nn[1] + double(nn[2]) * nn[2]);
            if (!(std::isfinite(len) && len > 0)) continue; /* stays (0,0,0) */
            for (int c = 0; c < 3; c++) cloud.normal[3 * i + c] = static_cast<float>(nn[c] / len);
        }
    }
    return true;
}

/* The feature parameters (k, threshold, directionConfidence; with `all` also the weights and the
 * dither scale), checked before anything changes. */
bool FilterPointnprPlugin::checkFeatureParams(const RichParameterList &par, bool all, pnpr_features_options &fo)
{
    fo = pnpr_features_defaults();
    if (!uintParam(par, "k", fo.k)) return fail(QString("k must not be negative (got %1)").arg(par.getInt("k")));
    fo.threshold = par.getFloat("threshold");
    fo.direction_confidence = par.getFloat("directionConfidence");
    if (all) {
        fo.weight_geometry = par.getFloat("weightGeometry");
        fo.weight_color = par.getFloat("weightColor");
        fo.dither_scale = par.getFloat("ditherScale");
        const pnpr_option_desc *w = optionOf(pnpr_features_option_table, "weight-geometry");
        const pnpr_option_desc *wc = optionOf(pnpr_features_option_table, "weight-color");
        if (!pnpr_option_in_range(w, fo.weight_geometry) || !pnpr_option_in_range(wc, fo.weight_color) ||
            !(fo.weight_geometry + fo.weight_color > 0))
            return fail(QString("the weights must be non-negative and not both 0, each %1 (got %2, %3)")
                            .arg(rangeOf(pnpr_features_option_table, "weight-geometry"))
                            .arg(fo.weight_geometry).arg(fo.weight_color));
    }
    QString why;
    if (!dialogOptionsOk(pnpr_features_option_table, &fo, LABELS(kFeatureLabels), why)) return fail(why);
    return true;
}

/* pnpr_compute_features on the layer cloud; the layer is not touched. */
bool FilterPointnprPlugin::runFeatures(LayerCloud &lc, pnpr_features_options &fo, ProgressBridge &pb,
                                       pnpr_features_stats &stats, double &seconds)
{
    fo.recompute_normals = 0; /* without cloud.normal the library computes them anyway */
    fo.progress = progressOf(pb);
    std::memset(&stats, 0, sizeof stats);
    QElapsedTimer timer;
    timer.start();
    const pnpr_status st = pnpr_compute_features(&lc.g.cloud, &fo, &stats);
    seconds = timer.elapsed() / 1000.0;
    if (st == PNPR_ERR_CANCELLED) return fail("cancelled; the layer is unchanged");
    if (st != PNPR_OK) return fail(QString("feature analysis failed: %1").arg(pnpr_status_string(st)));
    return true;
}

/* ---- NPR: Compute feature degree and classify points ------------------------------------- */

namespace {
/* Before a filter writes new attributes: those of an older version of the layer dropped
 * (pnpr_meshlab::dropStaleAttributes), and what the log says of it (empty: nothing dropped). */
QString dropStale(CMeshO &m, const QString &layer)
{
    std::string path;
    const bool sample = pnpr_meshlab::meshValue<std::string>(m, pnpr_meshlab::kSampleFileName, path);
    if (!pnpr_meshlab::dropStaleAttributes(m)) return QString();
    return QString("pointnpr: layer '%1': dropped the attributes of an older version of the layer (reloaded or edited)%2")
        .arg(layer)
        .arg(sample ? "; as edited it is no longer a sample of its file: the NPR render decoration draws it as it is"
                    : "");
}

/* The cloud's features (feature_degree ... properties, as the library and the files name them)
 * into the layer: vertex quality = degree, the attributes feature_class, feature_confidence and
 * feature_dir on vertex verts[i] for cloud point i (every other vertex 0), normals when
 * withNormals, the class palette when colorByClass; counts per class; the stamp written. False
 * (nothing changed) when the cloud lacks a feature property, or normals asked for. */
bool storeFeatures(MeshModel &mm, const std::vector<CMeshO::VertexPointer> &verts, const pnpr_cloud &cloud,
                   bool withNormals, bool colorByClass, size_t counts[4])
{
    CMeshO &m = mm.cm;
    const pnpr_property *pDeg = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_DEGREE);
    const pnpr_property *pCls = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_CLASS);
    const pnpr_property *pConf = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_CONFIDENCE);
    const pnpr_property *pDx = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_DIR_X);
    const pnpr_property *pDy = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_DIR_Y);
    const pnpr_property *pDz = pnpr_cloud_find_property(&cloud, PNPR_PROP_FEATURE_DIR_Z);
    if (!pDeg || !pCls || !pConf || !pDx || !pDy || !pDz || (withNormals && !cloud.normal)) return false;
    mm.updateDataMask(MeshModel::MM_VERTQUALITY);
    auto hClass = attributeOfType<float>(m, kAttrClass);
    auto hConf = attributeOfType<float>(m, kAttrConfidence);
    auto hDir = attributeOfType<vcg::Point3f>(m, kAttrDir);
    if (colorByClass) mm.updateDataMask(MeshModel::MM_VERTCOLOR);
    /* every vertex, deleted ones included, gets defined attribute values */
    for (CMeshO::VertexIterator vi = m.vert.begin(); vi != m.vert.end(); ++vi) {
        hClass[vi] = 0.0f;
        hConf[vi] = 0.0f;
        hDir[vi] = vcg::Point3f(0, 0, 0);
    }
    for (size_t i = 0; i < verts.size(); i++) {
        CMeshO::VertexPointer v = verts[i];
        const double deg = pnpr_type_get(pDeg->type, pDeg->data, i);
        int cls = static_cast<int>(pnpr_type_get(pCls->type, pCls->data, i));
        if (cls < 0 || cls > 3) cls = 0;
        counts[cls]++;
        v->Q() = static_cast<float>(deg);
        hClass[v] = static_cast<float>(cls);
        hConf[v] = static_cast<float>(pnpr_type_get(pConf->type, pConf->data, i));
        hDir[v] = vcg::Point3f(static_cast<float>(pnpr_type_get(pDx->type, pDx->data, i)),
                               static_cast<float>(pnpr_type_get(pDy->type, pDy->data, i)),
                               static_cast<float>(pnpr_type_get(pDz->type, pDz->data, i)));
        if (withNormals)
            v->N() = Point3m(cloud.normal[3 * i], cloud.normal[3 * i + 1], cloud.normal[3 * i + 2]);
        if (colorByClass)
            v->C() = vcg::Color4b(kPalette[cls][0], kPalette[cls][1], kPalette[cls][2], 255);
    }
    pnpr_meshlab::writeStamp(m); /* what readers check the attributes against (vcg_attributes.h) */
    return true;
}
} // namespace

bool FilterPointnprPlugin::computeFeatures(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb)
{
    MeshModel *mm = md.mm();
    if (!mm) return fail("there is no current layer");
    CMeshO &m = mm->cm;
    const QString layer = mm->label();

    /* ---- parameters, checked before anything changes ---- */
    pnpr_features_options fo;
    if (!checkFeatureParams(par, true, fo)) return false;
    const float threshold = fo.threshold;
    const bool recompute = par.getBool("recomputeNormals");
    const bool colorByClass = par.getBool("colorByClass");

    LayerCloud lc;
    if (!loadLayerCloud(*mm, true, !recompute, "features", "class 0, quality 0", lc)) return false;
    pnpr_cloud &cloud = lc.g.cloud;
    const size_t n = lc.verts.size();
    const bool hasColor = lc.hasColor, keepNormals = lc.keepNormals;

    if (par.getBool("useViewpoint")) {
        /* scene coordinates -> the layer's own vertex coordinates (inverse of the layer transform) */
        const vcg::Point3f vpf = par.getPoint3m("viewpoint");
        vcg::Matrix44d tr;
        tr.Import(m.Tr);
        const vcg::Matrix44d inv = vcg::Inverse(tr);
        const vcg::Point3d local = inv * vcg::Point3d(vpf[0], vpf[1], vpf[2]);
        if (!(std::isfinite(local[0]) && std::isfinite(local[1]) && std::isfinite(local[2])))
            return fail("the viewpoint (or the layer transformation) is not finite");
        fo.has_viewpoint = 1;
        for (int c = 0; c < 3; c++) fo.viewpoint[c] = local[c];
    }

    /* ---- run ---- */
    ProgressBridge pb = makeBridge(cb, 0, 100, true, "NPR features");
    pnpr_features_stats stats;
    double seconds = 0;
    if (!runFeatures(lc, fo, pb, stats, seconds)) return false;

    /* ---- write back (nothing above touched the layer) ---- */
    const QString dropped = dropStale(m, layer);
    if (!dropped.isEmpty()) Log("%s", qUtf8Printable(dropped));
    size_t counts[4] = {0, 0, 0, 0};
    if (!storeFeatures(*mm, lc.verts, cloud, !keepNormals, colorByClass, counts))
        return fail("internal error: the library returned no feature properties");
    Log("pointnpr: layer '%s': %zu points (%zu valid), k %u, threshold %.3f%s, %s colour, normals %s",
        qUtf8Printable(layer), n, stats.valid_points, stats.k_used, stats.threshold_used,
        threshold > 0 ? "" : " (automatic)", hasColor ? "with" : "without",
        keepNormals ? "kept from the layer" : "computed and written back");
    Log("pointnpr: %zu feature points (%zu directional, %zu non-directional), %zu dithering points; %.3f s",
        counts[1] + counts[2], counts[2], counts[1], counts[3], seconds);
    Log("pointnpr: stored vertex quality = feature degree, attributes feature_class (float 0..3), "
        "feature_confidence (float), feature_dir (Point3f)%s",
        colorByClass ? ", vertex colours = class palette" : "");
    if (cb) cb(100, "NPR features: done");
    return true;
}

bool FilterPointnprPlugin::selectFeatures(MeshDocument &md, const RichParameterList &par)
{
    MeshModel *mm = md.mm();
    if (!mm) return fail("there is no current layer");
    CMeshO &m = mm->cm;
    CMeshO::PerVertexAttributeHandle<float> hClass;
    if (!findAttribute<float>(m, kAttrClass, hClass))
        return fail(QString("layer '%1' has no feature classes (per-vertex attribute %2): run "
                            "'NPR: Compute feature degree and classify points' on it first")
                        .arg(mm->label())
                        .arg(kAttrClass));
    if (pnpr_meshlab::checkStamp(m) == pnpr_meshlab::StampState::Stale)
        return fail(QString("layer '%1': its feature classes belong to an older version of the layer (reloaded, or "
                            "its vertices changed since they were computed): run 'NPR: Compute feature degree and "
                            "classify points' on it again")
                        .arg(mm->label()));
    const int which = par.getEnum("featureClass");
    if (which < 0 || which > 3) return fail(QString("unknown class choice %1").arg(which));
    const bool add = par.getBool("addToSelection");
    static const char *const names[4] = {"directional feature points", "non-directional feature points",
                                         "feature points", "dithering points"};
    size_t chosen = 0, total = 0;
    for (CMeshO::VertexIterator vi = m.vert.begin(); vi != m.vert.end(); ++vi) {
        if (vi->IsD()) continue;
        const int cls = static_cast<int>(std::lround(hClass[vi]));
        bool pick = false;
        switch (which) {
        case 0: pick = cls == PNPR_CLASS_DIRECTIONAL; break;
        case 1: pick = cls == PNPR_CLASS_NONDIRECTIONAL; break;
        case 2: pick = cls == PNPR_CLASS_DIRECTIONAL || cls == PNPR_CLASS_NONDIRECTIONAL; break;
        default: pick = cls == PNPR_CLASS_DITHER; break;
        }
        if (pick) {
            vi->SetS();
            chosen++;
        } else if (!add) {
            vi->ClearS();
        }
        total += vi->IsS() ? 1 : 0;
    }
    m.svn = static_cast<int>(total);
    Log("pointnpr: layer '%s': selected %zu %s (%zu vertices selected in all)", qUtf8Printable(mm->label()),
        chosen, names[which], total);
    return true;
}

/* ---- NPR: Profile lines ------------------------------------------------------------------- */

namespace {

/* Owns a pnpr_polylines for the duration of a call. */
struct LinesGuard {
    pnpr_polylines lines;
    LinesGuard() { std::memset(&lines, 0, sizeof lines); }
    ~LinesGuard() { pnpr_lines_free(&lines); }
    LinesGuard(const LinesGuard &) = delete;
    LinesGuard &operator=(const LinesGuard &) = delete;
};

bool nonNegative(float x) { return x >= 0.0f && std::isfinite(x); }

} // namespace

bool FilterPointnprPlugin::profileLines(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb)
{
    MeshModel *mm = md.mm();
    if (!mm) return fail("there is no current layer");
    CMeshO &m = mm->cm;
    const QString layer = mm->label();

    /* ---- parameters, checked before anything changes ---- */
    pnpr_lines_options lo = pnpr_lines_defaults();
    lo.spacing = par.getFloat("spacing");
    lo.connect_radius = par.getFloat("radius");
    lo.merge_tol = par.getFloat("mergeTolerance");
    lo.min_length = par.getFloat("minLength");
    lo.direction_weight = par.getFloat("directionWeight");
    const int shifts = par.getInt("shiftIterations");
    if (shifts < 0) return fail(QString("the noise-reducing shifts must not be negative, 0 = none (got %1)").arg(shifts));
    lo.shift_iterations = shifts == 0 ? -1 : shifts; /* the dialog's 0 is "none" */
    lo.no_corners = par.getBool("corners") ? 0 : 1;
    QString why;
    if (!dialogOptionsOk(pnpr_lines_option_table, &lo, LABELS(kLinesLabels), why)) return fail(why);
    pnpr_features_options fo;
    if (!checkFeatureParams(par, false, fo)) return false;

    CMeshO::PerVertexAttributeHandle<float> hClass;
    CMeshO::PerVertexAttributeHandle<vcg::Point3f> hDir;
    const bool stale = pnpr_meshlab::checkStamp(m) == pnpr_meshlab::StampState::Stale;
    const bool fromLayer = !par.getBool("recomputeFeatures") && !stale && findAttribute<float>(m, kAttrClass, hClass) &&
                           findAttribute<vcg::Point3f>(m, kAttrDir, hDir);
    if (stale && findAttribute<float>(m, kAttrClass, hClass))
        Log("pointnpr: layer '%s': its feature attributes belong to an older version of the layer (reloaded or edited): "
            "computed anew", qUtf8Printable(mm->label()));

    LayerCloud lc;
    if (!loadLayerCloud(*mm, true, true, "profile lines", "no line passes through them", lc)) return false;
    pnpr_cloud &cloud = lc.g.cloud;
    const size_t n = lc.verts.size();

    /* ---- run: features (unless the layer has them), then the lines ---- */
    LinesGuard lg;
    pnpr_polylines &lines = lg.lines;
    pnpr_lines_stats ls;
    std::memset(&ls, 0, sizeof ls);
    double featureSeconds = 0;
    QElapsedTimer timer;
    pnpr_status st;
    if (fromLayer) {
        std::vector<float> xyz, dir;
        for (size_t i = 0; i < n; i++) {
            CMeshO::VertexPointer v = lc.verts[i];
            if (!finite3(v->cP()) || std::lround(hClass[v]) != PNPR_CLASS_DIRECTIONAL) continue;
            const vcg::Point3f d = hDir[v];
            const double len = std::sqrt(double(d[0]) * d[0] + double(d[1]) * d[1] + double(d[2]) * d[2]);
            if (!(std::isfinite(len) && len > 1e-12)) continue;
            for (int c = 0; c < 3; c++) {
                xyz.push_back(cloud.xyz[3 * i + c]);
                dir.push_back(static_cast<float>(d[c] / len));
            }
        }
        Log("pointnpr: layer '%s': feature classes and directions taken from its attributes (%s, %s)",
            qUtf8Printable(layer), kAttrClass, kAttrDir);
        ProgressBridge pb = makeBridge(cb, 0, 100, false, "NPR profile lines");
        lo.progress = progressOf(pb);
        timer.start();
        st = pnpr_profile_lines_points(xyz.data(), dir.data(), xyz.size() / 3, cloud.origin, &lo, &lines, &ls);
    } else {
        ProgressBridge pf = makeBridge(cb, 0, 70, true, "NPR profile lines: features");
        pnpr_features_stats fs;
        if (!runFeatures(lc, fo, pf, fs, featureSeconds)) return false;
        Log("pointnpr: layer '%s' analysed for the lines (it is left unchanged): %zu points, k %u, threshold %.3f, "
            "%s colour; %.3f s", qUtf8Printable(layer), n, fs.k_used, fs.threshold_used, lc.hasColor ? "with" : "without",
            featureSeconds);
        ProgressBridge pb = makeBridge(cb, 70, 100, false, "NPR profile lines");
        lo.progress = progressOf(pb);
        timer.start();
        st = pnpr_profile_lines(&cloud, &lo, &lines, &ls);
    }
    const double seconds = timer.elapsed() / 1000.0;
    if (st == PNPR_ERR_CANCELLED) return fail("cancelled; no layer was added");
    if (st != PNPR_OK)
        return fail(QString("profile lines of layer '%1' failed: %2").arg(layer).arg(pnpr_status_string(st)));

    /* ---- the polylines that have an edge ---- */
    size_t nv = 0, ne = 0, polylines = 0, closedCount = 0;
    for (size_t l = 0; l < lines.count; l++) {
        const size_t len = lines.offset[l + 1] - lines.offset[l];
        if (len < 2) continue;
        polylines++;
        nv += len;
        ne += len - 1;
        if (lines.closed[l] && len > 2) {
            ne++;
            closedCount++;
        }
    }
    if (polylines == 0) {
        if (ls.directional_points == 0)
            return fail(QString("no profile lines: layer '%1' has no directional feature points (lower the feature "
                                "threshold or the directional confidence, or check the layer is a scan with creases); "
                                "no layer was added").arg(layer));
        return fail(QString("no profile lines: the %1 directional points of layer '%2' form no line longer than the "
                            "minimum length (lower it or raise the neighbourhood radius); no layer was added")
                        .arg(ls.directional_points)
                        .arg(layer));
    }
    if (nv > static_cast<size_t>(std::numeric_limits<int>::max()) || ne > static_cast<size_t>(std::numeric_limits<int>::max()))
        return fail("too many line vertices for one MeshLab layer");

    /* ---- the new layer: in the source layer's frame (origin + offsets in double -> float) ---- */
    MeshModel *out = md.addNewMesh("", layer + " profile lines", true);
    if (!out) return fail("MeshLab could not add a layer");
    try {
        CMeshO &o = out->cm;
        o.Tr = m.Tr;
        CMeshO::VertexIterator vi = vcg::tri::Allocator<CMeshO>::AddVertices(o, nv);
        std::vector<CMeshO::VertexPointer> vp;
        vp.reserve(nv);
        for (size_t l = 0; l < lines.count; l++) {
            const size_t a = lines.offset[l], b = lines.offset[l + 1];
            if (b - a < 2) continue;
            for (size_t j = a; j < b; j++, ++vi) {
                for (int c = 0; c < 3; c++)
                    vi->P()[c] = static_cast<Scalarm>(lines.origin[c] + static_cast<double>(lines.xyz[3 * j + c]));
                vi->N() = Point3m(0, 0, 0);
                vp.push_back(&*vi);
            }
        }
        CMeshO::EdgeIterator ei = vcg::tri::Allocator<CMeshO>::AddEdges(o, ne);
        size_t base = 0;
        for (size_t l = 0; l < lines.count; l++) {
            const size_t len = lines.offset[l + 1] - lines.offset[l];
            if (len < 2) continue;
            for (size_t j = 0; j + 1 < len; j++, ++ei) {
                ei->V(0) = vp[base + j];
                ei->V(1) = vp[base + j + 1];
            }
            if (lines.closed[l] && len > 2) {
                ei->V(0) = vp[base + len - 1];
                ei->V(1) = vp[base];
                ++ei;
            }
            base += len;
        }
        vcg::tri::UpdateBounding<CMeshO>::Box(o);
    } catch (...) {
        md.delMesh(out); /* never leave a half-built layer behind */
        throw;
    }

    Log("pointnpr: layer '%s': %zu directional points -> %zu polylines (%zu closed, %zu corners joined), %zu vertices, "
        "%zu edges, total length %.6g, spacing h %.6g; %.3f s", qUtf8Printable(layer), ls.directional_points, polylines,
        closedCount, ls.corners, nv, ne, ls.total_length, static_cast<double>(ls.spacing_used), seconds + featureSeconds);
    Log("pointnpr: new layer '%s' (polylines: vertices + edges; save as OBJ to keep them)", qUtf8Printable(out->label()));
    if (cb) cb(100, "NPR profile lines: done");
    return true;
}

/* ---- NPR: Segment ------------------------------------------------------------------------- */

namespace {

const char *const kAttrSegment = PNPR_PROP_SEGMENT;

/* A distinct colour per label (golden-ratio hue steps) for layers without colours. */
vcg::Color4b labelColor(uint32_t label)
{
    const double h = std::fmod(label * 0.6180339887498949, 1.0) * 6.0, s = 0.65, v = 0.95;
    const int i = static_cast<int>(h) % 6;
    const double f = h - std::floor(h), p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r = v, g = t, b = p;
    switch (i) {
    case 1: r = q; g = v; b = p; break;
    case 2: r = p; g = v; b = t; break;
    case 3: r = p; g = q; b = v; break;
    case 4: r = t; g = p; b = v; break;
    case 5: r = v; g = p; b = q; break;
    default: break;
    }
    return vcg::Color4b(static_cast<unsigned char>(255 * r + 0.5), static_cast<unsigned char>(255 * g + 0.5),
                        static_cast<unsigned char>(255 * b + 0.5), 255);
}

/* Owns a kd-tree. */
struct TreeGuard {
    pnpr_kdtree *tree = nullptr;
    TreeGuard() = default;
    ~TreeGuard() { pnpr_kdtree_free(tree); }
    TreeGuard(const TreeGuard &) = delete;
    TreeGuard &operator=(const TreeGuard &) = delete;
};

} // namespace

bool FilterPointnprPlugin::segment(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb, bool jseg)
{
    MeshModel *mm = md.mm();
    if (!mm) return fail("there is no current layer");
    CMeshO &m = mm->cm;
    const QString layer = mm->label();
    const int method = jseg ? -1 : par.getEnum("method"); /* 0 components, 1 colour region growing */
    const char *const methodName = jseg ? "JSEG" : (method == 0 ? "connected components" : "colour region growing");
    if (!jseg && method != 0 && method != 1) return fail(QString("unknown method %1").arg(method));
    const bool needColor = jseg || method == 1;

    /* ---- parameters, checked before anything changes ---- */
    pnpr_jseg_options jo = pnpr_jseg_defaults();
    pnpr_components_options co = pnpr_components_defaults();
    pnpr_rgbgrow_options ro = pnpr_rgbgrow_defaults();
    int segmentsWanted = 0;
    float hThreshold = 0;
    QString why;
    if (jseg) {
        segmentsWanted = par.getInt("segments");
        hThreshold = par.getFloat("hierarchyThreshold");
        if (segmentsWanted < 0) return fail(QString("the segment count must be >= 0, 0 = no hierarchy cut (got %1)").arg(segmentsWanted));
        if (!nonNegative(hThreshold)) return fail(QString("the hierarchy threshold must be >= 0, 0 = none (got %1)").arg(hThreshold));
        if (!uintParam(par, "classes", jo.classes) || !uintParam(par, "k", jo.k) || !uintParam(par, "minSize", jo.min_size))
            return fail("the colour classes, k and the minimum segment size must not be negative");
        const float qd = par.getFloat("quantDistance"), md2 = par.getFloat("mergeDistance");
        jo.quant_distance = qd > 0 ? qd : -1.0f; /* the dialog's 0 is "none" */
        jo.radius = par.getFloat("radius");
        jo.seed_factor = par.getFloat("seedFactor");
        jo.merge_distance = md2 > 0 ? md2 : -1.0f;
        if (!dialogOptionsOk(pnpr_jseg_option_table, &jo, LABELS(kJsegLabels), why)) return fail(why);
    } else {
        const float dist = par.getFloat("distance");
        uint32_t minSize = 0;
        if (!uintParam(par, "minSize", minSize) || !uintParam(par, "k", ro.k))
            return fail("k and the minimum segment size must not be negative");
        co.distance = dist;
        co.min_size = minSize > 1 ? minSize : 1u; /* 0 and 1: keep all */
        ro.distance = dist;
        ro.point_distance = par.getFloat("pointColorDistance");
        const float rcd = par.getFloat("regionColorDistance");
        ro.region_distance = rcd > 0 ? rcd : -1.0f; /* the dialog's 0 is "none" */
        ro.min_size = minSize > 1 ? minSize : 1u;
        const bool ok = method == 1 ? dialogOptionsOk(pnpr_rgbgrow_option_table, &ro, LABELS(kGrowLabels), why)
                                    : dialogOptionsOk(pnpr_components_option_table, &co, LABELS(kComponentsLabels), why);
        if (!ok) return fail(why);
    }
    const bool colorBy = par.getBool("colorBySegment");
    const bool toQuality = par.getBool("labelToQuality");

    LayerCloud lc;
    if (!loadLayerCloud(*mm, needColor || colorBy, false, "segments", "segment -1", lc)) return false;
    if (needColor && !lc.hasColor)
        return fail(QString("layer '%1' has no per-vertex colour: %2 segments by colour (use 'NPR: Segment (connected "
                            "components / colour region growing)' with connected components for a layer without "
                            "colours)").arg(layer).arg(methodName));
    const pnpr_cloud &cloud = lc.g.cloud;
    const size_t n = lc.verts.size();
    if (n > (size_t(1) << 24))
        return fail(QString("layer '%1' has %2 vertices: more than 2^24, labels would not be exact as floats").arg(layer).arg(n));

    /* ---- run ---- */
    std::vector<uint32_t> labels(n);
    pnpr_segment_info info;
    std::memset(&info, 0, sizeof info);
    QElapsedTimer timer;
    timer.start();
    pnpr_status st;
    const bool cut = jseg && (segmentsWanted > 0 || hThreshold > 0);
    ProgressBridge pb = makeBridge(cb, 0, cut ? 80 : 100, false, jseg ? "NPR JSEG" : "NPR segments");
    if (jseg) {
        jo.progress = progressOf(pb);
        st = pnpr_segment_jseg(cloud.xyz, cloud.rgb, n, &jo, labels.data(), &info);
    } else if (method == 0) {
        co.progress = progressOf(pb);
        st = pnpr_segment_components(cloud.xyz, n, &co, labels.data(), &info);
    } else {
        ro.progress = progressOf(pb);
        st = pnpr_segment_rgbgrow(cloud.xyz, cloud.rgb, n, &ro, labels.data(), &info);
    }
    if (st == PNPR_ERR_CANCELLED) return fail("cancelled; the layer is unchanged");
    if (st != PNPR_OK)
        return fail(QString("%1 segmentation of layer '%2' failed: %3").arg(methodName).arg(layer).arg(pnpr_status_string(st)));
    uint32_t S = info.segment_count;
    const uint32_t regions = S;
    const uint32_t invalid = info.invalid_segment;
    if (cut && S > 1) {
        /* the region hierarchy over the valid segments (the invalid segment, the last label, stays apart) */
        const uint32_t hs = invalid != PNPR_LABEL_NONE ? S - 1 : S;
        const size_t kk = n > 10 ? 10 : n;
        std::vector<uint32_t> knn(n * kk);
        std::vector<pnpr_segment_merge> merges(hs > 1 ? hs - 1 : 1);
        TreeGuard tg;
        ProgressBridge ph = makeBridge(cb, 80, 100, false, "NPR JSEG: hierarchy");
        pnpr_knn_options ko;
        std::memset(&ko, 0, sizeof ko);
        ko.progress = progressOf(ph);
        if ((st = pnpr_kdtree_build(cloud.xyz, n, 0, &tg.tree)) == PNPR_OK &&
            (st = pnpr_knn_self(tg.tree, n, kk, &ko, knn.data(), nullptr)) == PNPR_OK) {
            pnpr_region_graph g = {knn.data(), kk, kk};
            pnpr_hierarchy_options ho;
            std::memset(&ho, 0, sizeof ho);
            ho.progress = progressOf(ph);
            uint32_t nm = 0;
            if ((st = pnpr_segment_hierarchy(cloud.rgb, n, &g, labels.data(), hs, &ho, merges.data(), &nm)) == PNPR_OK) {
                uint32_t target = segmentsWanted > 0 ? static_cast<uint32_t>(segmentsWanted) : 0;
                if (target && invalid != PNPR_LABEL_NONE) target = target > 1 ? target - 1 : 1;
                st = pnpr_segment_hierarchy_cut(labels.data(), n, hs, merges.data(), nm, target, hThreshold,
                                                labels.data(), &S);
            }
        }
        if (st == PNPR_ERR_CANCELLED) return fail("cancelled; the layer is unchanged");
        if (st != PNPR_OK)
            return fail(QString("the region hierarchy of layer '%1' failed: %2").arg(layer).arg(pnpr_status_string(st)));
    }
    const double seconds = timer.elapsed() / 1000.0;
    /* after a cut the invalid points hold the last label */
    const uint32_t invalidLabel = invalid == PNPR_LABEL_NONE ? PNPR_LABEL_NONE : S - 1;
    const uint32_t validSegments = invalid == PNPR_LABEL_NONE ? S : S - 1;

    std::vector<float> mean;
    if (colorBy && lc.hasColor) {
        mean.assign(3 * static_cast<size_t>(S ? S : 1), 0.0f);
        if ((st = pnpr_segment_mean_colors(cloud.rgb, labels.data(), n, S, mean.data(), nullptr)) != PNPR_OK)
            return fail(QString("segment colours failed: %1").arg(pnpr_status_string(st)));
    }

    /* ---- write back (nothing above touched the layer) ---- */
    const QString dropped = dropStale(m, layer);
    if (!dropped.isEmpty()) Log("%s", qUtf8Printable(dropped));
    auto hSeg = attributeOfType<float>(m, kAttrSegment);
    for (CMeshO::VertexIterator vi = m.vert.begin(); vi != m.vert.end(); ++vi) hSeg[vi] = -1.0f;
    if (toQuality) mm->updateDataMask(MeshModel::MM_VERTQUALITY);
    if (colorBy) mm->updateDataMask(MeshModel::MM_VERTCOLOR);
    for (size_t i = 0; i < n; i++) {
        CMeshO::VertexPointer v = lc.verts[i];
        const uint32_t l = labels[i];
        const bool valid = l != invalidLabel && l < S;
        const float value = valid ? static_cast<float>(l) : -1.0f;
        hSeg[v] = value;
        if (toQuality) v->Q() = value;
        if (colorBy && valid) {
            if (lc.hasColor) {
                const float *c = &mean[3 * static_cast<size_t>(l)];
                v->C() = vcg::Color4b(static_cast<unsigned char>(std::lround(std::min(255.0f, std::max(0.0f, c[0])))),
                                      static_cast<unsigned char>(std::lround(std::min(255.0f, std::max(0.0f, c[1])))),
                                      static_cast<unsigned char>(std::lround(std::min(255.0f, std::max(0.0f, c[2])))),
                                      255);
            } else {
                v->C() = labelColor(l);
            }
        }
    }

    if (jseg)
        Log("pointnpr: layer '%s': JSEG: %zu points (%zu valid), %u colour classes, mean J %.3f, %u seed regions, "
            "%u grown, %u regions after merging", qUtf8Printable(layer), n, info.valid_points, info.classes,
            static_cast<double>(info.mean_j), info.seed_regions, info.grown_regions,
            invalid == PNPR_LABEL_NONE ? regions : regions - 1);
    else
        Log("pointnpr: layer '%s': %s: %zu points (%zu valid)", qUtf8Printable(layer), methodName, n, info.valid_points);
    if (cut)
        Log("pointnpr: region hierarchy cut (%s%s%s): %u segments", segmentsWanted > 0 ? "segment count" : "",
            segmentsWanted > 0 && hThreshold > 0 ? " and " : "", hThreshold > 0 ? "threshold" : "", validSegments);
    Log("pointnpr: %u segments; %.3f s; stored per-vertex attribute %s (float label 0..%u%s)%s%s", validSegments, seconds,
        kAttrSegment, validSegments ? validSegments - 1 : 0, invalid == PNPR_LABEL_NONE ? "" : ", -1 for NaN/Inf vertices",
        colorBy ? (lc.hasColor ? ", vertex colours = segment mean colour" : ", vertex colours = one colour per segment") : "",
        toQuality ? ", vertex quality = label" : "");
    pnpr_meshlab::writeStamp(m);
    if (cb) cb(100, "NPR segments: done");
    return true;
}

/* ---- NPR: Set layer style ------------------------------------------------------------------ */

bool FilterPointnprPlugin::layerStyle(MeshDocument &md, const RichParameterList &par)
{
    MeshModel *mm = md.mm();
    if (!mm) return fail("there is no current layer");
    const int choice = par.getEnum("style");
    if (choice < 0 || choice > (int)PNPR_STYLE_COUNT_) return fail(QString("unknown style choice %1").arg(choice));
    pnpr_meshlab::setLayerStyle(mm->cm, choice - 1);
    if (choice == 0)
        Log("pointnpr: layer '%s' takes the NPR render decoration's Style", qUtf8Printable(mm->label()));
    else
        Log("pointnpr: layer '%s' is drawn in the %s style by the NPR render decoration", qUtf8Printable(mm->label()),
            pnpr_style_name((pnpr_style)(choice - 1)));
    return true;
}

bool FilterPointnprPlugin::openSample(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb)
{
    const QString file = par.getOpenFileName("file");
    const int points = par.getInt("points");
    if (file.isEmpty()) return fail("no file given: choose a binary PLY");
    if (points <= 0) return fail(QString("the points must be > 0 (got %1)").arg(points));

    /* ---- read (nothing in the document changes before it succeeds) ---- */
    ProgressBridge pb = makeBridge(cb, 0, 90, false, "NPR open sample");
    pnpr_read_options ro;
    std::memset(&ro, 0, sizeof ro);
    ro.progress.fn = progressToMeshLab;
    ro.progress.user = &pb;
    CloudGuard g;
    pnpr_error err;
    std::memset(&err, 0, sizeof err);
    uint64_t total = 0;
    int ordered = 0;
    QElapsedTimer timer;
    timer.start();
    const QByteArray path = QFile::encodeName(file);
    pnpr_status st = pnpr_lod_read_sample(path.constData(), static_cast<uint64_t>(points), &ro, &g.cloud, &total,
                                          &ordered, &err);
    if (st != PNPR_OK) return fail(QString::fromUtf8(err.message) + "; no layer was added");
    const pnpr_cloud &c = g.cloud;
    if (c.count == 0) return fail(QString("%1 has no points; no layer was added").arg(file));
    if (c.count > static_cast<size_t>(std::numeric_limits<int>::max()))
        return fail("too many points for one MeshLab layer; ask for fewer");

    /* ---- the new layer: positions from the cloud's origin, which the layer's transformation
     * holds (MeshLab's floats at 4.2e6 step by 0.5: world coordinates would lose what a scan's
     * spacing needs; the decoration applies the transformation in double), normals, colours,
     * the features when the file has them ---- */
    MeshModel *out = md.addNewMesh("", QFileInfo(file).fileName() + " sample", true);
    if (!out) return fail("MeshLab could not add a layer");
    CMeshO &o = out->cm;
    Scalarm at[3]; /* the origin as the float matrix holds it exactly */
    for (int k = 0; k < 3; k++) at[k] = static_cast<Scalarm>(c.origin[k]);
    o.Tr.SetTranslate(at[0], at[1], at[2]);
    out->updateDataMask(MeshModel::MM_VERTNORMAL);
    if (c.rgb) out->updateDataMask(MeshModel::MM_VERTCOLOR);
    CMeshO::VertexIterator vi = vcg::tri::Allocator<CMeshO>::AddVertices(o, c.count);
    std::vector<CMeshO::VertexPointer> verts(c.count);
    for (size_t i = 0; i < c.count; i++, ++vi) {
        double w[3];
        pnpr_cloud_world(&c, i, w);
        vi->P() = Point3m(static_cast<Scalarm>(w[0] - at[0]), static_cast<Scalarm>(w[1] - at[1]),
                          static_cast<Scalarm>(w[2] - at[2]));
        vi->N() = c.normal ? Point3m(c.normal[3 * i], c.normal[3 * i + 1], c.normal[3 * i + 2]) : Point3m(0, 0, 0);
        if (c.rgb) vi->C() = vcg::Color4b(c.rgb[3 * i], c.rgb[3 * i + 1], c.rgb[3 * i + 2], 255);
        verts[i] = &*vi;
    }
    size_t counts[4] = {0, 0, 0, 0};
    const bool features = storeFeatures(*out, verts, c, false, false, counts);
    vcg::tri::UpdateBounding<CMeshO>::Box(o);
    const double origin[3] = {at[0], at[1], at[2]};
    pnpr_meshlab::setSampleSource(o, path.toStdString(), origin); /* the decoration streams it by the view */
    if (!features) pnpr_meshlab::writeStamp(o); /* storeFeatures stamped the layer already (it vouches for the file too) */
    Log("pointnpr: new layer '%s': %zu of the %llu points of %s (%.1f%%), %s; %.2f s",
        qUtf8Printable(out->label()), c.count, static_cast<unsigned long long>(total), qUtf8Printable(file),
        total ? 100.0 * static_cast<double>(c.count) / static_cast<double>(total) : 100.0,
        ordered ? "ordered for drawing: only the runs of the sample were read" : "a pass over every point first",
        timer.elapsed() / 1000.0);
    Log("pointnpr: its positions are offsets from %.3f %.3f %.3f, the layer's transformation (MeshLab's float "
        "coordinates keep their precision there)", static_cast<double>(at[0]), static_cast<double>(at[1]),
        static_cast<double>(at[2]));
    if (features)
        Log("pointnpr: the file's features kept: vertex quality = feature degree, attributes feature_class, "
            "feature_confidence, feature_dir (%zu feature points)", counts[1] + counts[2]);
    if (cb) cb(100, "NPR open sample: done");
    return true;
}
