// OBJ/OFF input through OpenMesh: a thin adapter from OpenMesh's readers to pnpr_cloud.
// pnpr_read_file sends OBJ and binary OFF here; ascii OFF is read by io/off.c (comments anywhere,
// colours as tools write them, which OpenMesh 9 refuses; docs/io.md says which reader reads what).
//
// Hostile input. OpenMesh 9 trusts the files it reads (header counts drive its loops and its
// reserve(), a number that does not parse silently drops an OBJ vertex or derails an OFF
// stream, a face corner without a vertex makes it write out of bounds). So every file first goes
// through a validating pre-pass, io/mesh_check.c (its header lists the rules), which walks the
// file once, streaming, the way OpenMesh tokenises it, and fails with "FILE: line N: ..."
// (err->line = N; binary OFF: "FILE: byte N: ...", err->offset) at the first thing OpenMesh would
// misread, loop on or over-allocate:
//  - counts are checked against what the file can hold before anything is allocated
//    (PNPR_ERR_TRUNCATED: "OFF\n2147483648 0 0" in 20 bytes fails at once), negative counts and
//    counts above 2^32-1 are PNPR_ERR_FORMAT, more than 2^31-1 vertices PNPR_ERR_UNSUPPORTED;
//  - numbers must parse whole and fit a float: an OBJ or OFF vertex with "nan", "1e400" or
//    "1,5" FAILS the read with its line and vertex number (PNPR_ERR_FORMAT). Chosen over keeping
//    such a vertex as a non-finite point because OpenMesh drops it and every later face index
//    would then name the wrong vertex; failing keeps indices meaning what the file says;
//  - face corners must name existing vertices (index 0, an index past the last vertex, a
//    relative index before the first, an OFF index >= the vertex count): PNPR_ERR_FORMAT, as in
//    the PLY reader, never a silent drop;
//  - binary bytes (NUL, control characters) in a text file, or an OBJ file without a single OBJ
//    statement, are PNPR_ERR_FORMAT: random bytes named .obj are not an empty cloud.
// What passes is read by OpenMesh with bounded loops and memory (at most a few bytes of storage
// per byte of file).
//
// OpenMesh parses the file; a small importer (derived from OpenMesh's ImporterT) records what
// the reader hands over, in file order: vertex positions, vertex colours and normals when the
// file has them, and faces exactly as the file lists them. Faces are recorded, not added to
// OpenMesh's mesh: its mesh would drop degenerate faces and duplicate vertices around
// non-manifold ones, and its checks cost time quadratic in a face's corners and a vertex's
// faces; a point cloud keeps the file's vertices one to one. Faces with fewer than 3 corners
// are dropped (OFF faces of 0-2 corners; OBJ faces after OpenMesh removes repeated corners).
// Float colours are clamped to [0, 1] before OpenMesh's rounding (its cast is undefined outside).
//
// Warnings. What OpenMesh prints during a read (omerr, omlog, and its direct std::cerr writes,
// e.g. "Error setting vertex color" or a missing material file) is captured and re-emitted on
// stderr as at most 5 lines "FILE: OpenMesh: ...", then "FILE: (N more warnings)".
//
// Exact coordinates: OpenMesh (9.x) parses ascii coordinates as float, which loses the detail of
// georeferenced data (5e6 + millimetres). The pre-pass reads the same vertex words as doubles
// (strtod, "C" form), and the adapter uses them (src_xyz, src_coord_type FLOAT64) after checking,
// vertex by vertex, that strtof of the same text gives exactly the float that OpenMesh produced,
// i.e. that both saw the same vertices in the same order. If they disagree in an OBJ the floats
// are used as they are (origin 0, FLOAT32); in an OFF that is an error (PNPR_ERR_FORMAT). Binary
// OFF (float32 on disk) gives the floats as they are.
//
// Inputs whose extension does not name the format (sniffed by io.c) are read through a
// temporary symbolic link with the right extension, because OpenMesh chooses its reader by
// extension and its OFF stream reader does not parse the keyword line. The file must be a
// regular file (OpenMesh reads it twice).
//
// Thread safety: OpenMesh's readers are process-wide singletons that keep per-file state, and the
// warning capture redirects std::cerr and std::clog during a read, so do not read OBJ/OFF files
// from several threads at once.
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
#include <OpenMesh/Core/System/omstream.hh>

#include "mesh_check.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <new>
#include <streambuf>
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

// OpenMesh's colour cast (v * 255 + 0.5, truncated) for v in [0, 1]; clamped outside, where the
// cast would be undefined; NaN gives 0.
uint8_t unit_byte(float v)
{
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 255;
    return (uint8_t)(v * 255.0f + 0.5f);
}

// Records the reader's vertices, colours, normals and faces in file order. Vertices are also
// added to OpenMesh's mesh (the readers ask for its vertex count); faces, colours and normals
// are only recorded.
class RecordingImporter : public OpenMesh::IO::ImporterT<Mesh> {
public:
    typedef OpenMesh::IO::ImporterT<Mesh> Base;

    // expected: the vertex count the pre-pass validated (bounds what reserve() may allocate)
    RecordingImporter(Mesh &mesh, size_t expected) : Base(mesh), expected_(expected) {}

    std::vector<double> xyz;        // 3 per file vertex, as the reader gave them
    std::vector<float> xyz_float;   // same, when the reader gave floats (for the exactness check)
    bool reader_gave_doubles = false;
    std::vector<uint8_t> rgb;       // 3 per file vertex
    std::vector<float> normal;      // 3 per file vertex
    bool any_color = false, any_normal = false;
    std::vector<uint32_t> face_offset{0};
    std::vector<uint32_t> face_index;
    std::vector<long> vertex_of_handle; // mesh vertex idx -> file vertex index, -1 = not one

    void reserve(unsigned int nV, unsigned int, unsigned int) override
    {
        size_t n = std::min((size_t)nV, expected_);
        Base::reserve((unsigned int)n, 0, 0);
        xyz.reserve(3 * n);
        xyz_float.reserve(3 * n);
        rgb.reserve(3 * n);
        normal.reserve(3 * n);
        vertex_of_handle.reserve(n);
    }

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

    // Kept when it has at least 3 corners that all name vertices of the file. The handle
    // returned is invalid: nothing was added to OpenMesh's mesh, so readers attach nothing to it.
    OpenMesh::FaceHandle add_face(const VHandles &idx) override
    {
        if (idx.size() < 3 || face_index.size() + idx.size() > UINT32_MAX) return OpenMesh::FaceHandle();
        const size_t start = face_index.size();
        for (size_t k = 0; k < idx.size(); k++) {
            long v = file_vertex(idx[k]);
            if (v < 0) {
                face_index.resize(start);
                return OpenMesh::FaceHandle();
            }
            face_index.push_back((uint32_t)v);
        }
        face_offset.push_back((uint32_t)face_index.size());
        return OpenMesh::FaceHandle();
    }
    size_t n_faces() const override { return face_offset.size() - 1; }
    void add_face_texcoords(OpenMesh::FaceHandle, OpenMesh::VertexHandle, const std::vector<OpenMesh::Vec2f> &) override {}
    void add_face_texcoords(OpenMesh::FaceHandle, OpenMesh::VertexHandle, const std::vector<OpenMesh::Vec3f> &) override {}

    void set_color(OpenMesh::VertexHandle vh, const OpenMesh::Vec3uc &c) override { store_color(vh, c[0], c[1], c[2]); }
    void set_color(OpenMesh::VertexHandle vh, const OpenMesh::Vec4uc &c) override { store_color(vh, c[0], c[1], c[2]); }
    void set_color(OpenMesh::VertexHandle vh, const OpenMesh::Vec3f &c) override
    {
        store_color(vh, unit_byte(c[0]), unit_byte(c[1]), unit_byte(c[2]));
    }
    void set_color(OpenMesh::VertexHandle vh, const OpenMesh::Vec4f &c) override
    {
        store_color(vh, unit_byte(c[0]), unit_byte(c[1]), unit_byte(c[2]));
    }
    void set_normal(OpenMesh::VertexHandle vh, const OpenMesh::Vec3f &n) override
    {
        store_normal(vh, OpenMesh::Vec3d(n[0], n[1], n[2]));
    }
    void set_normal(OpenMesh::VertexHandle vh, const OpenMesh::Vec3d &n) override { store_normal(vh, n); }
    // face colours/normals are not kept: the base class handles them (ignored unless requested)
    using Base::add_vertex;
    using Base::add_face;
    using Base::set_color;
    using Base::set_normal;

    size_t count() const { return xyz.size() / 3; }

private:
    size_t expected_;

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
    void store_color(OpenMesh::VertexHandle vh, uint8_t r, uint8_t g, uint8_t b)
    {
        long v = file_vertex(vh);
        if (v < 0) return;
        rgb[3 * (size_t)v] = r;
        rgb[3 * (size_t)v + 1] = g;
        rgb[3 * (size_t)v + 2] = b;
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

// Collects the lines written to it: the first kKeep (cut at kWidth bytes) and a count.
class WarningCapture : public std::streambuf {
public:
    static const size_t kKeep = 5, kWidth = 200;

    // Ends a last line without a newline; prints what was kept on stderr, prefixed with path.
    void emit(const char *path)
    {
        end_line();
        for (const std::string &l : kept_) std::fprintf(stderr, "%s: OpenMesh: %s\n", path, l.c_str());
        if (lines_ > kept_.size()) std::fprintf(stderr, "%s: (%zu more warnings)\n", path, lines_ - kept_.size());
    }

protected:
    int_type overflow(int_type c) override
    {
        if (!traits_type::eq_int_type(c, traits_type::eof())) put(traits_type::to_char_type(c));
        return traits_type::not_eof(c);
    }
    std::streamsize xsputn(const char *s, std::streamsize n) override
    {
        for (std::streamsize i = 0; i < n; i++) put(s[i]);
        return n;
    }

private:
    std::vector<std::string> kept_;
    std::string cur_;
    size_t lines_ = 0;

    void put(char c)
    {
        if (c == '\n') end_line();
        else if (cur_.size() < kWidth) cur_.push_back((unsigned char)c < 0x20 || c == 0x7f ? '?' : c);
    }
    void end_line()
    {
        size_t b = cur_.find_first_not_of(" \t?");
        if (b != std::string::npos) {
            lines_++;
            if (kept_.size() < kKeep) kept_.push_back(cur_.substr(b));
        }
        cur_.clear();
    }
};

// Sends std::cerr and std::clog (where OpenMesh's omerr and omlog go, and where its readers
// write directly) to a capture while it lives.
class StreamRedirect {
public:
    explicit StreamRedirect(WarningCapture &capture)
        : err_(std::cerr.rdbuf(&capture)), log_(std::clog.rdbuf(&capture)) {}
    ~StreamRedirect()
    {
        ::omerr().flush(); // a line OpenMesh left without its newline
        ::omlog().flush();
        std::cerr.rdbuf(err_);
        std::clog.rdbuf(log_);
    }
    StreamRedirect(const StreamRedirect &) = delete;
    StreamRedirect &operator=(const StreamRedirect &) = delete;

private:
    std::streambuf *err_, *log_;
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

// The pre-pass's exact coordinates and the floats strtof gives for the same text.
struct ExactText {
    std::vector<double> xyz;
    std::vector<float> xyz_float;
};

int exact_vertex(void *user, const double xyz[3], const float xyz_f[3])
{
    try {
        ExactText *t = static_cast<ExactText *>(user);
        t->xyz.insert(t->xyz.end(), xyz, xyz + 3);
        t->xyz_float.insert(t->xyz_float.end(), xyz_f, xyz_f + 3);
        return 0;
    } catch (...) {
        return 1;
    }
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

// OpenMesh reads om_path into imp; its warnings go to stderr, bounded and named by path.
bool run_openmesh(const char *path, const std::string &om_path, RecordingImporter &imp)
{
    OpenMesh::IO::Options opt;
    opt += OpenMesh::IO::Options::VertexColor;
    opt += OpenMesh::IO::Options::VertexNormal;
    WarningCapture capture;
    bool ok;
    {
        StreamRedirect redirect(capture);
        ok = OpenMesh::IO::IOManager().read(om_path, imp, opt);
    }
    capture.emit(path);
    if (!opt.check(OpenMesh::IO::Options::VertexColor)) imp.any_color = false;
    if (!opt.check(OpenMesh::IO::Options::VertexNormal)) imp.any_normal = false;
    return ok;
}

// Whether the pre-pass's exact coordinates describe the vertices OpenMesh read (same count,
// strtof of each text = OpenMesh's float). An OFF that disagrees is an error (*st set).
bool exact_matches(const char *path, pnpr_file_format fmt, const ExactText &text, const RecordingImporter &imp,
                   pnpr_status *st, pnpr_error *err)
{
    *st = PNPR_OK;
    if (imp.reader_gave_doubles || text.xyz.size() != imp.xyz.size()) return false;
    for (size_t i = 0; i < text.xyz_float.size(); i++) {
        if (same_float(text.xyz_float[i], imp.xyz_float[i])) continue;
        if (fmt == PNPR_FORMAT_OFF)
            *st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: OpenMesh read vertex %zu differently from the file's text",
                                 path, i / 3);
        return false;
    }
    return true;
}

pnpr_status read_mesh(const char *path, pnpr_file_format fmt, const pnpr_read_options *opts,
                      pnpr_cloud *cloud, pnpr_error *err)
{
    const pnpr_progress *progress = opts ? &opts->progress : nullptr;
    const char *ext = fmt == PNPR_FORMAT_OBJ ? ".obj" : ".off";
    if (pnpr_progress_report(progress, "read mesh", 0.0))
        return pnpr_error_set(err, PNPR_ERR_CANCELLED, "%s: cancelled", path);
    // OpenMesh picks its reader by the extension, and its OFF reader only looks at the keyword
    // (COFF, NOFF, BINARY...) when given a file name: its stream entry point reuses whatever the
    // previous OFF file said. So a file without the extension is read through a link that has it.
    ExtLink link;
    std::string om_path = path;
    if (!ext_matches(path, ext)) {
        if (!link.make(path, ext))
            return pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot create a temporary link with a %s extension: %s",
                                  path, ext, std::strerror(errno));
        om_path = link.link_path;
    }
    ExactText text;
    pnpr_mesh_check mc;
    std::memset(&mc, 0, sizeof mc);
    mc.format = fmt;
    mc.openmesh_path = om_path.c_str();
    mc.vertex = exact_vertex;
    mc.user = &text;
    pnpr_status st = pnpr_mesh_check_file(path, &mc, err);
    if (st != PNPR_OK) return st;

    Mesh mesh;
    RecordingImporter imp(mesh, (size_t)mc.vertices);
    if (!run_openmesh(path, om_path, imp))
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: OpenMesh could not read the file", path);
    if (imp.count() != mc.vertices)
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: OpenMesh read %zu vertices, the file has %llu", path,
                              imp.count(), (unsigned long long)mc.vertices);
    if (pnpr_progress_report(progress, "read mesh", 0.5))
        return pnpr_error_set(err, PNPR_ERR_CANCELLED, "%s: cancelled", path);

    bool use_exact = !mc.binary && exact_matches(path, fmt, text, imp, &st, err);
    if (st != PNPR_OK) return st;
    st = fill_cloud(imp, use_exact ? &text.xyz : nullptr, cloud);
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
    if (opts && opts->keep)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                              "%s: a point filter (a tile) reads binary PLY only (convert it: pointnpr convert IN OUT.ply)",
                              path);
    struct stat sb;
    if (stat(path, &sb) != 0)
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, std::strerror(errno));
    if (S_ISDIR(sb.st_mode))
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, std::strerror(EISDIR));
    if (!S_ISREG(sb.st_mode))
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: not a regular file", path);
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
