// Per-vertex attribute lookup shared by the filter and the decorate plugin (header-only: both
// plugins are separate modules).
#ifndef PNPR_MESHLAB_VCG_ATTRIBUTES_H
#define PNPR_MESHLAB_VCG_ATTRIBUTES_H

#include <common/ml_mesh_type.h>

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

} // namespace pnpr_meshlab

#endif
