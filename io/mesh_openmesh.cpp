// OBJ/OFF input through OpenMesh: a thin adapter from OpenMesh's readers to pnpr_cloud.
//
// OpenMesh parses the file; a small importer (derived from OpenMesh's ImporterT) records what
// the reader hands over, in file order: vertex positions, vertex colours and normals when the
// file has them, and faces exactly as the file lists them (OpenMesh's own mesh would drop
// degenerate faces and duplicate vertices around non-manifold ones; a point cloud keeps the
// file's vertices one to one).
//
// Exact coordinates: OpenMesh (9.x) parses ascii coordinates as float, which loses the detail of
// georeferenced data (5e6 + millimetres). For ascii OBJ/OFF the adapter therefore re-reads the
// vertex lines itself with strtod, and uses those doubles (src_xyz, src_coord_type FLOAT64)
// after checking, vertex by vertex, that strtof of the same text gives exactly the float that
// OpenMesh produced — i.e. that both saw the same vertices in the same order. If anything
// disagrees in an OBJ (an exotic layout), or the file is binary OFF (float32 on disk), the
// floats are used as they are: origin 0, src_coord_type FLOAT32.
//
// OFF checks: OpenMesh silently returns too few or wrong vertices for some OFF files (a vertex
// list shorter than the header says, counts on the keyword line, comment lines in the body).
// The text pass catches these: PNPR_ERR_TRUNCATED when the file has fewer vertex lines than the
// header announces, PNPR_ERR_FORMAT when OpenMesh's vertex count or values differ from the text.
//
// Faces are kept when they have at least 3 corners that all name vertices of the file.
// Inputs whose extension does not name the format (sniffed by io.c) are read through a
// temporary symbolic link with the right extension, because OpenMesh chooses its reader by
// extension and its OFF stream reader does not parse the keyword line.
//
// Thread safety: OpenMesh's readers are process-wide singletons that keep per-file state, so
// do not read OBJ/OFF files from several threads at once.
//
// No C++ exception escapes: everything is wrapped in try/catch.
#include <pointnpr/io.h>

#ifndef PNPR_HAVE_OPENMESH

extern "C" pnpr_status pnpr_read_mesh_file(const char *path, const pnpr_read_options *opts,
                                           pnpr_cloud *cloud, pnpr_error *err)
{
    (void)opts;
    pnpr_cloud_free(cloud);
    return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                          "%s: OBJ/OFF input needs OpenMesh, which was not available at build time",
                          path ? path : "(null)");
}

#else

// OpenMesh's property containers default-construct its vector types, which leave their
// components uninitialised by design; GCC 12 then reports -Wmaybe-uninitialized inside the
// instantiated std::vector code. This adapter never reads those mesh properties (it records the
// reader's values itself).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

// MeshIO.hh must come before the mesh kernel headers.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace {

struct MeshTraits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
    typedef OpenMesh::Vec3uc Color;
};
typedef OpenMesh::PolyMesh_ArrayKernelT<MeshTraits> Mesh;

// Records the reader's vertices, colours, normals and faces in file order, and forwards
// everything to OpenMesh's own importer (readers may look at the mesh it builds).
class RecordingImporter : public OpenMesh::IO::ImporterT<Mesh> {
public:
    typedef OpenMesh::IO::ImporterT<Mesh> Base;

    explicit RecordingImporter(Mesh &mesh) : Base(mesh) {}

    std::vector<double> xyz;        // 3 per file vertex, as the reader gave them
    std::vector<float> xyz_float;   // same, when the reader gave floats (for the exactness check)
    bool reader_gave_doubles = false;
    std::vector<uint8_t> rgb;       // 3 per file vertex
    std::vector<float> normal;      // 3 per file vertex
    bool any_color = false, any_normal = false;
    std::vector<uint32_t> face_offset{0};
    std::vector<uint32_t> face_index;
    std::vector<long> vertex_of_handle; // mesh vertex idx -> file vertex index, -1 = not one

    OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3f &p) override
    {
        OpenMesh::VertexHandle vh = Base::add_vertex(p);
        record(vh, OpenMesh::Vec3d(p[0], p[1], p[2]));
        for (int a = 0; a < 3; a++) xyz_float.push_back(p[a]);
        return vh;
    }

    OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3d &p) override
    {
        OpenMesh::VertexHandle vh = Base::add_vertex(p);
        record(vh, p);
        for (int a = 0; a < 3; a++) xyz_float.push_back((float)p[a]);
        reader_gave_doubles = true;
        return vh;
    }

    OpenMesh::FaceHandle add_face(const VHandles &idx) override
    {
        std::vector<uint32_t> corners;
        bool ok = idx.size() >= 3;
        for (size_t k = 0; ok && k < idx.size(); k++) {
            long v = file_vertex(idx[k]);
            if (v < 0) ok = false;
            else corners.push_back((uint32_t)v);
        }
        if (ok && face_index.size() + corners.size() <= UINT32_MAX) {
            face_index.insert(face_index.end(), corners.begin(), corners.end());
            face_offset.push_back((uint32_t)face_index.size());
        }
        return Base::add_face(idx);
    }

    void set_color(OpenMesh::VertexHandle vh, const OpenMesh::Vec3uc &c) override
    {
        Base::set_color(vh, c);
        store_color(vh, c);
    }
    void set_color(OpenMesh::VertexHandle vh, const OpenMesh::Vec4uc &c) override
    {
        Base::set_color(vh, c);
        store_color(vh, OpenMesh::color_cast<OpenMesh::Vec3uc>(c));
    }
    void set_color(OpenMesh::VertexHandle vh, const OpenMesh::Vec3f &c) override
    {
        Base::set_color(vh, c);
        store_color(vh, OpenMesh::color_cast<OpenMesh::Vec3uc>(c));
    }
    void set_color(OpenMesh::VertexHandle vh, const OpenMesh::Vec4f &c) override
    {
        Base::set_color(vh, c);
        store_color(vh, OpenMesh::color_cast<OpenMesh::Vec3uc>(c));
    }
    void set_normal(OpenMesh::VertexHandle vh, const OpenMesh::Vec3f &n) override
    {
        Base::set_normal(vh, n);
        store_normal(vh, OpenMesh::Vec3d(n[0], n[1], n[2]));
    }
    void set_normal(OpenMesh::VertexHandle vh, const OpenMesh::Vec3d &n) override
    {
        Base::set_normal(vh, n);
        store_normal(vh, n);
    }
    // face colours/normals are not kept: the base class handles them (ignored unless requested)
    using Base::add_vertex;
    using Base::add_face;
    using Base::set_color;
    using Base::set_normal;

    size_t count() const { return xyz.size() / 3; }

private:
    void record(OpenMesh::VertexHandle vh, const OpenMesh::Vec3d &p)
    {
        long file_index = (long)count();
        for (int a = 0; a < 3; a++) xyz.push_back(p[a]);
        for (int a = 0; a < 3; a++) rgb.push_back(0);
        for (int a = 0; a < 3; a++) normal.push_back(0.0f);
        if (vh.idx() >= 0) {
            size_t h = (size_t)vh.idx();
            if (vertex_of_handle.size() <= h) vertex_of_handle.resize(h + 1, -1);
            vertex_of_handle[h] = file_index;
        }
    }
    long file_vertex(OpenMesh::VertexHandle vh) const
    {
        if (vh.idx() < 0 || (size_t)vh.idx() >= vertex_of_handle.size()) return -1;
        return vertex_of_handle[(size_t)vh.idx()];
    }
    void store_color(OpenMesh::VertexHandle vh, const OpenMesh::Vec3uc &c)
    {
        long v = file_vertex(vh);
        if (v < 0) return;
        for (int a = 0; a < 3; a++) rgb[3 * (size_t)v + a] = c[a];
        any_color = true;
    }
    void store_normal(OpenMesh::VertexHandle vh, const OpenMesh::Vec3d &n)
    {
        long v = file_vertex(vh);
        if (v < 0) return;
        double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int a = 0; a < 3; a++)
            normal[3 * (size_t)v + a] = len > 0 && std::isfinite(len) ? (float)(n[a] / len) : 0.0f;
        any_normal = true;
    }
};

// A symbolic link "<tmpdir>/pointnpr-XXXXXX/input<ext>" to a file, removed on destruction.
struct ExtLink {
    std::string dir, link_path;

    bool make(const char *path, const char *ext)
    {
        const char *tmp = std::getenv("TMPDIR");
        std::string templ = std::string(tmp && *tmp ? tmp : "/tmp") + "/pointnpr-XXXXXX";
        std::vector<char> buf(templ.begin(), templ.end());
        buf.push_back('\0');
        if (!mkdtemp(buf.data())) return false;
        dir = buf.data();
        char *abs = realpath(path, nullptr);
        if (!abs) return false;
        std::string target(abs);
        std::free(abs);
        link_path = dir + "/input" + ext;
        if (symlink(target.c_str(), link_path.c_str()) != 0) {
            link_path.clear();
            return false;
        }
        return true;
    }
    ~ExtLink()
    {
        if (!link_path.empty()) unlink(link_path.c_str());
        if (!dir.empty()) rmdir(dir.c_str());
    }
};

bool ext_matches(const char *path, const char *ext)
{
    return pnpr_format_from_path(path) ==
           (std::strcmp(ext, ".obj") == 0 ? PNPR_FORMAT_OBJ : PNPR_FORMAT_OFF);
}

// Splits off the first three numbers after position `p` of `line` (strtod and strtof of the
// same text). Returns false when there are fewer than three.
bool parse3(const char *p, double d[3], float f[3])
{
    for (int a = 0; a < 3; a++) {
        char *end = nullptr;
        d[a] = std::strtod(p, &end);
        if (end == p) return false;
        f[a] = std::strtof(p, nullptr);
        p = end;
    }
    return true;
}

const char *skip_space(const char *p)
{
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\f' || *p == '\v') p++;
    return p;
}

// Exact vertex coordinates of an ascii OBJ ("v x y z ..." lines, in order).
bool exact_obj(std::istream &in, std::vector<double> &out, std::vector<float> &out_f)
{
    std::string line;
    while (std::getline(in, line)) {
        const char *p = skip_space(line.c_str());
        if (p[0] != 'v' || (p[1] != ' ' && p[1] != '\t')) continue;
        double d[3];
        float f[3];
        if (!parse3(p + 1, d, f)) return false;
        out.insert(out.end(), d, d + 3);
        out_f.insert(out_f.end(), f, f + 3);
    }
    return true;
}

// Next line that is neither empty nor a '#' comment.
bool next_content_line(std::istream &in, std::string &line, const char **r_p)
{
    while (std::getline(in, line)) {
        const char *p = skip_space(line.c_str());
        if (*p && *p != '#' && *p != '\n') { *r_p = p; return true; }
    }
    return false;
}

// What the text pass over an OFF file found.
enum OffText {
    OFF_TEXT_NONE,  // binary or non-3D variant (4OFF, nOFF), or no readable header: not checked
    OFF_TEXT_OK,    // header count and that many vertex lines with 3 numbers each
    OFF_TEXT_SHORT, // the header announces more vertex lines than the file has
    OFF_TEXT_BAD    // a vertex line with fewer than 3 numbers (OpenMesh's values are kept)
};

// Exact vertex coordinates of an ascii OFF: keyword, "nv nf ne" (on the keyword line or the
// next content line), then nv vertex lines; '#' comments and blank lines are skipped.
OffText exact_off(std::istream &in, std::vector<double> &out, std::vector<float> &out_f,
                  unsigned long long *r_nv)
{
    std::string line;
    const char *p = nullptr;
    *r_nv = 0;
    if (!next_content_line(in, line, &p)) return OFF_TEXT_NONE;
    const char *kw = p;
    while (*p && *p != ' ' && *p != '\t' && *p != '\r') p++;
    std::string keyword(kw, (size_t)(p - kw));
    if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0) return OFF_TEXT_NONE;
    if (keyword.find('4') != std::string::npos || keyword.find('n') != std::string::npos) return OFF_TEXT_NONE;
    if (line.find("BINARY") != std::string::npos) return OFF_TEXT_NONE;
    p = skip_space(p);
    if (!*p || *p == '#') {
        if (!next_content_line(in, line, &p)) return OFF_TEXT_NONE;
    }
    char *end = nullptr;
    unsigned long long nv = std::strtoull(p, &end, 10);
    if (end == p || *p == '-') return OFF_TEXT_NONE;
    *r_nv = nv;
    for (unsigned long long i = 0; i < nv; i++) {
        if (!next_content_line(in, line, &p)) return OFF_TEXT_SHORT;
        double d[3];
        float f[3];
        if (!parse3(p, d, f)) return OFF_TEXT_BAD;
        out.insert(out.end(), d, d + 3);
        out_f.insert(out_f.end(), f, f + 3);
    }
    return OFF_TEXT_OK;
}

bool same_float(float a, float b)
{
    return std::memcmp(&a, &b, sizeof a) == 0 || (a != a && b != b);
}

// Moves the recorded data into the cloud. Returns a status; message set by the caller.
pnpr_status fill_cloud(RecordingImporter &imp, const std::vector<double> *exact, pnpr_cloud *cloud)
{
    const size_t n = imp.count();
    pnpr_status st = pnpr_cloud_alloc(cloud, n);
    if (st != PNPR_OK) return st;
    if (exact || imp.reader_gave_doubles) {
        const double *w = exact ? exact->data() : imp.xyz.data();
        if ((st = pnpr_cloud_alloc_src_xyz(cloud)) != PNPR_OK) return st;
        if (n) std::memcpy(cloud->src_xyz, w, 3 * n * sizeof(double));
        cloud->src_coord_type = PNPR_TYPE_FLOAT64;
        if ((st = pnpr_cloud_set_world(cloud, cloud->src_xyz)) != PNPR_OK) return st;
    } else {
        // float source: origin 0, the reader's floats bit for bit
        for (size_t i = 0; i < 3 * n; i++) cloud->xyz[i] = imp.xyz_float[i];
        cloud->src_coord_type = PNPR_TYPE_FLOAT32;
    }
    if (imp.any_color) {
        if ((st = pnpr_cloud_alloc_rgb(cloud)) != PNPR_OK) return st;
        if (n) std::memcpy(cloud->rgb, imp.rgb.data(), 3 * n);
    }
    if (imp.any_normal) {
        if ((st = pnpr_cloud_alloc_normals(cloud)) != PNPR_OK) return st;
        if (n) std::memcpy(cloud->normal, imp.normal.data(), 3 * n * sizeof(float));
    }
    const size_t nf = imp.face_offset.size() - 1;
    if (nf) {
        cloud->faces.offset = (uint32_t *)std::malloc((nf + 1) * sizeof(uint32_t));
        cloud->faces.index = (uint32_t *)std::malloc((imp.face_index.size() ? imp.face_index.size() : 1) *
                                                     sizeof(uint32_t));
        if (!cloud->faces.offset || !cloud->faces.index) return PNPR_ERR_OUT_OF_MEMORY;
        std::memcpy(cloud->faces.offset, imp.face_offset.data(), (nf + 1) * sizeof(uint32_t));
        std::memcpy(cloud->faces.index, imp.face_index.data(), imp.face_index.size() * sizeof(uint32_t));
        cloud->faces.count = nf;
    }
    return PNPR_OK;
}

pnpr_status read_mesh(const char *path, pnpr_file_format fmt, const pnpr_read_options *opts,
                      pnpr_cloud *cloud, pnpr_error *err)
{
    const pnpr_progress *progress = opts ? &opts->progress : nullptr;
    const char *ext = fmt == PNPR_FORMAT_OBJ ? ".obj" : ".off";
    if (pnpr_progress_report(progress, "read mesh", 0.0))
        return pnpr_error_set(err, PNPR_ERR_CANCELLED, "%s: cancelled", path);

    Mesh mesh;
    mesh.request_vertex_colors();
    mesh.request_vertex_normals();
    RecordingImporter imp(mesh);
    OpenMesh::IO::Options opt;
    opt += OpenMesh::IO::Options::VertexColor;
    opt += OpenMesh::IO::Options::VertexNormal;
    bool ok;
    if (ext_matches(path, ext)) {
        ok = OpenMesh::IO::IOManager().read(path, imp, opt);
    } else {
        // OpenMesh picks its reader by the extension, and its OFF reader only looks at the
        // keyword (COFF, NOFF, BINARY...) when given a file name: its stream entry point reuses
        // whatever the previous OFF file said. So give it a link with the right extension.
        ExtLink link;
        if (!link.make(path, ext))
            return pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot create a temporary link with a %s extension: %s",
                                  path, ext, std::strerror(errno));
        ok = OpenMesh::IO::IOManager().read(link.link_path, imp, opt);
    }
    if (!ok)
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: OpenMesh could not read the file", path);
    if (imp.count() > UINT32_MAX)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: %zu vertices, more than 2^32-1", path, imp.count());
    if (!opt.check(OpenMesh::IO::Options::VertexColor)) imp.any_color = false;
    if (!opt.check(OpenMesh::IO::Options::VertexNormal)) imp.any_normal = false;
    if (pnpr_progress_report(progress, "read mesh", 0.5))
        return pnpr_error_set(err, PNPR_ERR_CANCELLED, "%s: cancelled", path);

    // Exact coordinates from the text, when they provably match what OpenMesh read. For OFF the
    // header's vertex count is also checked: OpenMesh accepts some broken or unusual files
    // (a truncated vertex list, counts on the keyword line) and returns fewer or wrong vertices.
    std::vector<double> exact;
    std::vector<float> exact_f;
    bool use_exact = false;
    std::ifstream text(path, std::ios::in | std::ios::binary);
    if (text) {
        bool parsed;
        if (fmt == PNPR_FORMAT_OBJ) {
            parsed = exact_obj(text, exact, exact_f);
        } else {
            unsigned long long nv = 0;
            OffText t = exact_off(text, exact, exact_f, &nv);
            if (t == OFF_TEXT_SHORT)
                return pnpr_error_set(err, PNPR_ERR_TRUNCATED,
                                      "%s: the OFF header announces %llu vertices, the file has %zu vertex lines",
                                      path, nv, exact.size() / 3);
            if ((t == OFF_TEXT_OK || t == OFF_TEXT_BAD) && nv != (unsigned long long)imp.count())
                return pnpr_error_set(err, PNPR_ERR_FORMAT,
                                      "%s: OpenMesh read %zu vertices but the OFF header announces %llu",
                                      path, imp.count(), nv);
            parsed = t == OFF_TEXT_OK;
        }
        use_exact = parsed && exact.size() == imp.xyz.size();
        for (size_t i = 0; use_exact && i < exact_f.size(); i++) {
            if (same_float(exact_f[i], imp.xyz_float[i])) continue;
            use_exact = false;
            // OFF: same count but other values means OpenMesh misread the body (e.g. comment lines)
            if (fmt == PNPR_FORMAT_OFF)
                return pnpr_error_set(err, PNPR_ERR_FORMAT,
                                      "%s: OpenMesh read vertex %zu differently from the file's text "
                                      "(unusual OFF layout, e.g. comment lines between the data lines)",
                                      path, i / 3);
        }
        if (imp.reader_gave_doubles) use_exact = false; // a reader that parses doubles is exact already
    }
    pnpr_status st = fill_cloud(imp, use_exact ? &exact : nullptr, cloud);
    if (st != PNPR_OK)
        return pnpr_error_set(err, st, "%s: cannot store %zu vertices", path, imp.count());
    if (pnpr_progress_report(progress, "read mesh", 1.0))
        return pnpr_error_set(err, PNPR_ERR_CANCELLED, "%s: cancelled", path);
    return PNPR_OK;
}

} // namespace

extern "C" pnpr_status pnpr_read_mesh_file(const char *path, const pnpr_read_options *opts,
                                           pnpr_cloud *cloud, pnpr_error *err)
{
    if (err) { err->message[0] = '\0'; err->offset = -1; err->line = 0; }
    if (!cloud) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "pnpr_read_mesh_file: cloud is NULL");
    pnpr_cloud_free(cloud);
    if (!path) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "pnpr_read_mesh_file: path is NULL");
    pnpr_file_format fmt = opts && opts->format != PNPR_FORMAT_AUTO ? opts->format : pnpr_format_from_path(path);
    if (fmt != PNPR_FORMAT_OBJ && fmt != PNPR_FORMAT_OFF)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: not an OBJ or OFF file", path);
    struct stat sb;
    if (stat(path, &sb) != 0)
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, std::strerror(errno));
    if (S_ISDIR(sb.st_mode))
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, std::strerror(EISDIR));
    pnpr_status st;
    try {
        st = read_mesh(path, fmt, opts, cloud, err);
    } catch (const std::bad_alloc &) {
        st = pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory while reading", path);
    } catch (...) {
        st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: OpenMesh could not read the file", path);
    }
    if (st != PNPR_OK) pnpr_cloud_free(cloud);
    return st;
}

#endif
