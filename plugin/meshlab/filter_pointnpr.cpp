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

#include <pointnpr/features.h>

#include <cmath>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <typeinfo>
#include <vector>

#include <QElapsedTimer>

namespace {

const char *const kAttrClass = "feature_class";
const char *const kAttrConfidence = "feature_confidence";
const char *const kAttrDir = "feature_dir";

/* Class palette of "Colour points by class" (also documented in docs/meshlab.md). */
const unsigned char kPalette[4][3] = {
    {200, 200, 200}, /* 0 none: light grey */
    {40, 100, 230},  /* 1 non-directional feature: blue */
    {220, 30, 30},   /* 2 directional feature: red */
    {20, 20, 20},    /* 3 dithering point: near black */
};

/* Owns a pnpr_cloud for the duration of a call (freed on every path, exceptions included). */
struct CloudGuard {
    pnpr_cloud cloud;
    CloudGuard() { std::memset(&cloud, 0, sizeof cloud); }
    ~CloudGuard() { pnpr_cloud_free(&cloud); }
    CloudGuard(const CloudGuard &) = delete;
    CloudGuard &operator=(const CloudGuard &) = delete;
};

/* pnpr_progress -> vcg::CallBackPos: the library reports a fraction per named stage; MeshLab
 * wants one percentage. Stages are mapped to equal slices in pipeline order; stages the run skips
 * just make the bar jump. A host callback returning false cancels the run. */
struct ProgressBridge {
    vcg::CallBackPos *cb;
    int last_percent;
    std::string text;
};

int progressToMeshLab(void *user, const char *stage, double fraction)
{
    ProgressBridge *pb = static_cast<ProgressBridge *>(user);
    if (!pb || !pb->cb) return 0;
    int index = PNPR_STAGE_COUNT_ - 1;
    for (int s = 0; s < PNPR_STAGE_COUNT_; s++) {
        if (stage && std::strcmp(stage, pnpr_stage_name(static_cast<pnpr_stage>(s))) == 0) {
            index = s;
            break;
        }
    }
    if (!(fraction >= 0.0)) fraction = 0.0;
    if (fraction > 1.0) fraction = 1.0;
    int percent = static_cast<int>(100.0 * (index + fraction) / PNPR_STAGE_COUNT_);
    if (percent > 100) percent = 100;
    if (percent == pb->last_percent) return 0;
    pb->last_percent = percent;
    pb->text = std::string("NPR features: ") + (stage ? stage : "");
    return pb->cb(percent, pb->text.c_str()) ? 0 : 1;
}

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

/* The existing attribute of type T, or an invalid handle (nothing is created). */
template <class T>
bool findAttribute(CMeshO &m, const char *name, typename CMeshO::template PerVertexAttributeHandle<T> &h)
{
    CMeshO::PointerToAttribute key;
    key._name = name;
    auto it = m.vert_attr.find(key);
    if (it == m.vert_attr.end() || it->_type != std::type_index(typeid(T))) return false;
    h = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<T>(m, name);
    return vcg::tri::Allocator<CMeshO>::IsValidHandle<T>(m, h);
}

bool finite3(const Point3m &p)
{
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

} // namespace

FilterPointnprPlugin::FilterPointnprPlugin()
{
    typeList << FP_FEATURES << FP_SELECT_FEATURES;
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
    default: return QString();
    }
}

MeshFilterInterface::FilterClass FilterPointnprPlugin::getClass(QAction *a)
{
    if (ID(a) == FP_SELECT_FEATURES)
        return FilterClass(MeshFilterInterface::PointSet | MeshFilterInterface::Selection);
    return MeshFilterInterface::PointSet;
}

MeshFilterInterface::FILTER_ARITY FilterPointnprPlugin::filterArity(QAction *) const
{
    return SINGLE_MESH;
}

int FilterPointnprPlugin::getPreConditions(QAction *) const
{
    return MeshModel::MM_NONE; /* vertex count and attributes are checked with clear messages */
}

int FilterPointnprPlugin::postCondition(QAction *a) const
{
    if (ID(a) == FP_SELECT_FEATURES) return MeshModel::MM_VERTFLAGSELECT;
    return MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTNORMAL | MeshModel::MM_VERTCOLOR;
}

void FilterPointnprPlugin::initParameterSet(QAction *a, MeshModel &, RichParameterList &par)
{
    switch (ID(a)) {
    case FP_FEATURES:
        par.addParam(RichInt("k", 16, "Neighbours (k)",
                             "Number of nearest neighbours of each point (the point itself included), 1..1024. "
                             "16 suits typical scans; raise it for noisy scans. Clamped to the number of points."));
        par.addParam(RichFloat("threshold", 0.0f, "Feature threshold",
                               "Feature-degree threshold in [0,1] above which a point is a feature point. "
                               "0 = automatic (Otsu split of the degree histogram, never below 0.15)."));
        par.addParam(RichFloat("weightGeometry", 0.5f, "Geometry weight",
                               "Weight of the geometric term (variation of the plane-fit error: creases, corners). "
                               "The two weights are normalised to sum 1."));
        par.addParam(RichFloat("weightColor", 0.5f, "Colour weight",
                               "Weight of the colour term (colour gradient across the neighbourhood). Ignored "
                               "(geometry only) when the layer has no per-vertex colour."));
        par.addParam(RichFloat("directionConfidence", 0.6f, "Directional confidence",
                               "Minimum line-fit confidence in (0,1] for a feature point to be directional "
                               "(class 2); below it the point is non-directional (class 1)."));
        par.addParam(RichFloat("ditherScale", 1.0f, "Dither scale",
                               "Multiplies the tone (darkness from the colour, else from the normal lit from +z) "
                               "before dithering: more or fewer dithering points (class 3). Must be > 0."));
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

bool FilterPointnprPlugin::computeFeatures(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb)
{
    MeshModel *mm = md.mm();
    if (!mm) return fail("there is no current layer");
    CMeshO &m = mm->cm;
    const QString layer = mm->label();

    /* ---- parameters, checked before anything changes ---- */
    pnpr_features_options fo;
    std::memset(&fo, 0, sizeof fo);
    const int k = par.getInt("k");
    const float threshold = par.getFloat("threshold");
    const float wg = par.getFloat("weightGeometry"), wc = par.getFloat("weightColor");
    const float conf = par.getFloat("directionConfidence");
    const float dither = par.getFloat("ditherScale");
    if (k < 1 || k > 1024) return fail(QString("k must be in 1..1024 (got %1)").arg(k));
    if (!(threshold >= 0.0f && threshold <= 1.0f))
        return fail(QString("the feature threshold must be in [0,1], 0 = automatic (got %1)").arg(threshold));
    if (!(wg >= 0.0f && wc >= 0.0f && wg + wc > 0.0f && std::isfinite(wg + wc)))
        return fail(QString("the weights must be non-negative and not both 0 (got %1, %2)").arg(wg).arg(wc));
    if (!(conf > 0.0f && conf <= 1.0f))
        return fail(QString("the directional confidence must be in (0,1] (got %1)").arg(conf));
    if (!(dither > 0.0f && dither <= 1e6f))
        return fail(QString("the dither scale must be a positive number (got %1)").arg(dither));
    fo.k = static_cast<uint32_t>(k);
    fo.threshold = threshold;
    fo.weight_geometry = wg;
    fo.weight_color = wc;
    fo.direction_confidence = conf;
    fo.dither_scale = dither;
    const bool recompute = par.getBool("recomputeNormals");
    const bool colorByClass = par.getBool("colorByClass");

    /* ---- live vertices, finite bounding box in double ---- */
    std::vector<CMeshO::VertexPointer> verts;
    verts.reserve(m.vert.size());
    for (CMeshO::VertexIterator vi = m.vert.begin(); vi != m.vert.end(); ++vi)
        if (!vi->IsD()) verts.push_back(&*vi);
    const size_t n = verts.size();
    if (n == 0) return fail(QString("layer '%1' has no vertices: nothing to analyse").arg(layer));
    if (m.fn > 0)
        Log("pointnpr: layer '%s' is a mesh with %d faces: the features use its %zu vertices only; faces are "
            "left unchanged", qUtf8Printable(layer), m.fn, n);

    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    size_t finite = 0;
    for (CMeshO::VertexPointer v : verts) {
        const Point3m &p = v->cP();
        if (!finite3(p)) continue;
        for (int c = 0; c < 3; c++) {
            const double x = p[c];
            if (finite == 0 || x < lo[c]) lo[c] = x;
            if (finite == 0 || x > hi[c]) hi[c] = x;
        }
        finite++;
    }
    if (finite == 0)
        return fail(QString("layer '%1': none of its %2 vertices has finite coordinates").arg(layer).arg(n));
    if (finite < n)
        Log("pointnpr: %zu of %zu vertices have NaN/Inf coordinates: they are left out (class 0, quality 0)",
            n - finite, n);

    /* ---- the cloud: origin = bbox centre (double), float offsets ---- */
    CloudGuard g;
    pnpr_cloud &cloud = g.cloud;
    pnpr_status st = pnpr_cloud_alloc(&cloud, n);
    if (st != PNPR_OK) return fail(QString("cannot allocate the cloud: %1").arg(pnpr_status_string(st)));
    for (int c = 0; c < 3; c++) cloud.origin[c] = 0.5 * (lo[c] + hi[c]);
    cloud.src_coord_type = PNPR_TYPE_FLOAT32;
    for (size_t i = 0; i < n; i++) {
        const Point3m &p = verts[i]->cP();
        for (int c = 0; c < 3; c++)
            cloud.xyz[3 * i + c] = static_cast<float>(static_cast<double>(p[c]) - cloud.origin[c]);
    }
    const bool hasColor = mm->hasDataMask(MeshModel::MM_VERTCOLOR);
    if (hasColor) {
        if ((st = pnpr_cloud_alloc_rgb(&cloud)) != PNPR_OK)
            return fail(QString("cannot allocate colours: %1").arg(pnpr_status_string(st)));
        for (size_t i = 0; i < n; i++) {
            const vcg::Color4b &col = verts[i]->cC();
            for (int c = 0; c < 3; c++) cloud.rgb[3 * i + c] = col[c];
        }
    }

    /* Normals: kept (normalised) when the layer has them and they are meaningful: at least 99% of
     * the finite vertices carry a finite non-zero normal (MeshLab's normals of meshes are
     * area/angle-weighted sums, not unit length); else computed and written back. */
    bool keepNormals = false;
    if (!recompute && mm->hasDataMask(MeshModel::MM_VERTNORMAL)) {
        size_t good = 0;
        for (CMeshO::VertexPointer v : verts) {
            if (!finite3(v->cP())) continue;
            const Point3m &nn = v->cN();
            const double len = std::sqrt(double(nn[0]) * nn[0] + double(nn[1]) * nn[1] + double(nn[2]) * nn[2]);
            good += (std::isfinite(len) && len > 1e-12);
        }
        keepNormals = good > 0 && good >= finite - finite / 100;
    }
    if (keepNormals) {
        if ((st = pnpr_cloud_alloc_normals(&cloud)) != PNPR_OK)
            return fail(QString("cannot allocate normals: %1").arg(pnpr_status_string(st)));
        for (size_t i = 0; i < n; i++) {
            const Point3m &nn = verts[i]->cN();
            const double len = std::sqrt(double(nn[0]) * nn[0] + double(nn[1]) * nn[1] + double(nn[2]) * nn[2]);
            if (!(std::isfinite(len) && len > 0)) continue; /* stays (0,0,0) */
            for (int c = 0; c < 3; c++) cloud.normal[3 * i + c] = static_cast<float>(nn[c] / len);
        }
    }
    fo.recompute_normals = 0; /* without cloud.normal the library computes them anyway */

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

    ProgressBridge pb = {cb, -1, std::string()};
    fo.progress.fn = progressToMeshLab;
    fo.progress.user = &pb;

    /* ---- run ---- */
    pnpr_features_stats stats;
    std::memset(&stats, 0, sizeof stats);
    QElapsedTimer timer;
    timer.start();
    st = pnpr_compute_features(&cloud, &fo, &stats);
    const double seconds = timer.elapsed() / 1000.0;
    if (st == PNPR_ERR_CANCELLED) return fail("cancelled; the layer is unchanged");
    if (st != PNPR_OK)
        return fail(QString("feature analysis of layer '%1' failed: %2").arg(layer).arg(pnpr_status_string(st)));

    const pnpr_property *pDeg = pnpr_cloud_find_property(&cloud, "feature_degree");
    const pnpr_property *pCls = pnpr_cloud_find_property(&cloud, "feature_class");
    const pnpr_property *pConf = pnpr_cloud_find_property(&cloud, "feature_confidence");
    const pnpr_property *pDx = pnpr_cloud_find_property(&cloud, "feature_dir_x");
    const pnpr_property *pDy = pnpr_cloud_find_property(&cloud, "feature_dir_y");
    const pnpr_property *pDz = pnpr_cloud_find_property(&cloud, "feature_dir_z");
    if (!pDeg || !pCls || !pConf || !pDx || !pDy || !pDz || !cloud.normal)
        return fail("internal error: the library returned no feature properties");

    /* ---- write back (nothing above touched the layer) ---- */
    mm->updateDataMask(MeshModel::MM_VERTQUALITY);
    auto hClass = attributeOfType<float>(m, kAttrClass);
    auto hConf = attributeOfType<float>(m, kAttrConfidence);
    auto hDir = attributeOfType<vcg::Point3f>(m, kAttrDir);
    if (colorByClass) mm->updateDataMask(MeshModel::MM_VERTCOLOR);
    /* every vertex, deleted ones included, gets defined attribute values */
    for (CMeshO::VertexIterator vi = m.vert.begin(); vi != m.vert.end(); ++vi) {
        hClass[vi] = 0.0f;
        hConf[vi] = 0.0f;
        hDir[vi] = vcg::Point3f(0, 0, 0);
    }
    size_t counts[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < n; i++) {
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
        if (!keepNormals)
            v->N() = Point3m(cloud.normal[3 * i], cloud.normal[3 * i + 1], cloud.normal[3 * i + 2]);
        if (colorByClass)
            v->C() = vcg::Color4b(kPalette[cls][0], kPalette[cls][1], kPalette[cls][2], 255);
    }

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
