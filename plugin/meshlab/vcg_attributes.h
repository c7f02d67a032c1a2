// Per-vertex attribute lookup shared by the filter and the decorate plugin (header-only: both
// plugins are separate modules).
#ifndef PNPR_MESHLAB_VCG_ATTRIBUTES_H
#define PNPR_MESHLAB_VCG_ATTRIBUTES_H

#include <common/ml_mesh_type.h>
#include <pointnpr/props.h>

#include <cstdint>
#include <string>

#include <typeindex>
#include <typeinfo>

namespace pnpr_meshlab {

/* The existing per-vertex attribute `name` of type T in h, or false (nothing is created). */
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

/* The per-mesh attribute `name` of exactly type T into r_value; false when there is none (or one
 * of another type: vcglib's lookup checks only the size). */
template <class T> bool meshValue(CMeshO &m, const char *name, T &r_value)
{
    CMeshO::PointerToAttribute key;
    key._name = name;
    auto it = m.mesh_attr.find(key);
    if (it == m.mesh_attr.end() || it->_type != std::type_index(typeid(T))) return false;
    auto h = vcg::tri::Allocator<CMeshO>::template FindPerMeshAttribute<T>(m, name);
    if (!vcg::tri::Allocator<CMeshO>::template IsValidHandle<T>(m, h)) return false;
    r_value = h();
    return true;
}

/* Sets the per-mesh attribute `name` of type T (made when missing); one of that name but another
 * type is not ours and is kept (nothing written). */
template <class T> void setMeshValue(CMeshO &m, const char *name, const T &value)
{
    CMeshO::PointerToAttribute key;
    key._name = name;
    auto it = m.mesh_attr.find(key);
    if (it != m.mesh_attr.end() && it->_type != std::type_index(typeid(T))) return;
    auto h = vcg::tri::Allocator<CMeshO>::template GetPerMeshAttribute<T>(m, name);
    h() = value;
}

/* The per-mesh stamp the filter writes next to its per-vertex attributes (feature classes,
 * directions, segments): a hash of the vertices' positions and of those attributes' values. MeshLab
 * keeps attribute handles through File > Reload and through filters that move or rebuild
 * vertices; the values then belong to an older version of the layer (reset to zero by a reload,
 * or left on moved points). Readers compare the stamp with the layer as it is. */
const char *const kStampName = "pnpr_stamp";

inline uint64_t layerStamp(CMeshO &m)
{
    uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void *p, size_t n) {
        const unsigned char *c = static_cast<const unsigned char *>(p);
        for (size_t i = 0; i < n; i++) { h ^= c[i]; h *= 1099511628211ull; }
    };
    size_t n = m.vert.size();
    mix(&n, sizeof n);
    typename CMeshO::template PerVertexAttributeHandle<float> hc, hs;
    typename CMeshO::template PerVertexAttributeHandle<vcg::Point3f> hd;
    bool c = findAttribute<float>(m, PNPR_PROP_FEATURE_CLASS, hc), s = findAttribute<float>(m, PNPR_PROP_SEGMENT, hs);
    bool d = findAttribute<vcg::Point3f>(m, PNPR_PROP_FEATURE_DIR, hd);
    for (size_t i = 0; i < n; i++) {
        const CVertexO &v = m.vert[i];
        bool del = v.IsD();
        mix(&del, sizeof del);
        if (del) continue;
        float p[3] = {(float)v.cP()[0], (float)v.cP()[1], (float)v.cP()[2]};
        mix(p, sizeof p);
        if (c) mix(&hc[i], sizeof(float));
        if (s) mix(&hs[i], sizeof(float));
        if (d) { float q[3] = {hd[i][0], hd[i][1], hd[i][2]}; mix(q, sizeof q); }
    }
    return h;
}

inline void writeStamp(CMeshO &m) { setMeshValue<long long>(m, kStampName, (long long)layerStamp(m)); }

enum class StampState { None, Valid, Stale };

/* None: no stamp (attributes from elsewhere, e.g. a PLY file: taken as they are). */
inline StampState checkStamp(CMeshO &m)
{
    long long stamp = 0;
    if (!meshValue<long long>(m, kStampName, stamp)) return StampState::None;
    return (uint64_t)stamp == layerStamp(m) ? StampState::Valid : StampState::Stale;
}

/* A layer's own NPR style (per-mesh attribute, the pnpr_style value; set by the filter "NPR: Set
 * layer style", read by the decorator): layers without one take the decorator's Style. */
const char *const kLayerStyleName = "pnpr_style";

inline bool layerStyle(CMeshO &m, int &r_style)
{
    return meshValue<int>(m, kLayerStyleName, r_style) && r_style >= 0;
}

/* style < 0: the layer takes the decorator's Style again. */
inline void setLayerStyle(CMeshO &m, int style) { setMeshValue<int>(m, kLayerStyleName, style < 0 ? -1 : style); }

/* The file a layer is a sample of (per-mesh attributes; set by "NPR: Open a sample of a large
 * PLY", read by the decorator, which streams the file by the view when it is ordered for drawing:
 * decorate_stream.h): its path (local 8-bit) and the origin the layer's positions are offsets
 * from. The layer's stamp vouches for them: an edited layer (stale stamp) is drawn as it is. */
const char *const kSampleFileName = "pnpr_sample_file";
const char *const kSampleOriginName = "pnpr_sample_origin";

inline void setSampleSource(CMeshO &m, const std::string &path, const double origin[3])
{
    setMeshValue<std::string>(m, kSampleFileName, path);
    setMeshValue<vcg::Point3d>(m, kSampleOriginName, vcg::Point3d(origin[0], origin[1], origin[2]));
}

inline bool sampleSource(CMeshO &m, std::string &r_path, double r_origin[3])
{
    vcg::Point3d o;
    if (!meshValue<std::string>(m, kSampleFileName, r_path) || r_path.empty() ||
        !meshValue<vcg::Point3d>(m, kSampleOriginName, o) || checkStamp(m) != StampState::Valid)
        return false;
    for (int a = 0; a < 3; a++) r_origin[a] = o[a];
    return true;
}

/* Before a filter writes some of the attributes and a new stamp: the others, when they belong to an
 * older version of the layer, go (a new stamp would otherwise vouch for them). True when they went. */
inline bool dropStaleAttributes(CMeshO &m)
{
    if (checkStamp(m) != StampState::Stale) return false;
    for (const char *name : {PNPR_PROP_FEATURE_CLASS, PNPR_PROP_FEATURE_CONFIDENCE, PNPR_PROP_FEATURE_DIR, PNPR_PROP_SEGMENT})
        vcg::tri::Allocator<CMeshO>::DeletePerVertexAttribute(m, name);
    /* typed: vcglib's by-name deletion casts per-mesh attributes to the per-element base class */
    auto h = vcg::tri::Allocator<CMeshO>::FindPerMeshAttribute<long long>(m, kStampName);
    vcg::tri::Allocator<CMeshO>::DeletePerMeshAttribute<long long>(m, h);
    /* an edited sample is no longer the file's: a later stamp must not vouch for streaming it */
    std::string path;
    if (meshValue<std::string>(m, kSampleFileName, path)) {
        auto hf = vcg::tri::Allocator<CMeshO>::FindPerMeshAttribute<std::string>(m, kSampleFileName);
        vcg::tri::Allocator<CMeshO>::DeletePerMeshAttribute<std::string>(m, hf);
    }
    vcg::Point3d o;
    if (meshValue<vcg::Point3d>(m, kSampleOriginName, o)) {
        auto ho = vcg::tri::Allocator<CMeshO>::FindPerMeshAttribute<vcg::Point3d>(m, kSampleOriginName);
        vcg::tri::Allocator<CMeshO>::DeletePerMeshAttribute<vcg::Point3d>(m, ho);
    }
    return true;
}

} // namespace pnpr_meshlab

#endif
